"""Checks of scalar arguments at the public boundary, one helper per kind of check.

Each helper raises :class:`~kinematica.errors.ArgumentError` with ``arg`` set
and a message that begins with the argument's name and states the accepted
range (``"duration must be a number of seconds greater than 0 and at most
1e+09 s, got 1e+308"``),
so the command line can say the same of its option. They run before any work
starts: a call that would sample ``1e308`` seconds, draw ``1e10`` pixels or
read ``/dev/zero`` is refused at once rather than after memory runs out.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from kinematica.errors import ArgumentError

__all__ = ["check_choice", "check_count", "check_flag", "check_number", "check_size"]


def _shown(value: object) -> str:
    """``value`` as typed: numpy numbers as plain numbers, long texts cut."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool | np.bool_):
        text = str(int(value))
    elif isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_):
        text = repr(float(value))
    else:
        text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _range(lo: float | None, hi: float | None, positive: bool, unit: str) -> str:
    """``"from 1e-06 to 1e+06 s"``, ``"greater than 0 and at most 1000"``..."""
    u = f" {unit}" if unit else ""
    if positive and (lo is None or lo <= 0.0):
        return "greater than 0" + (f" and at most {hi:g}{u}" if hi is not None else u)
    if lo is not None and hi is not None:
        return f"from {lo:g} to {hi:g}{u}"
    if lo is not None:
        return f"of at least {lo:g}{u}"
    return f"of at most {hi:g}{u}" if hi is not None else f"(finite){u}"


def check_number(
    value: object,
    name: str,
    *,
    lo: float | None = None,
    hi: float | None = None,
    positive: bool = False,
    unit: str = "",
    what: str = "a number",
) -> float:
    """``value`` as a finite float within ``[lo, hi]`` (and > 0 with ``positive``).

    Args:
        value: What the caller gave: a Python or numpy real number (not a bool,
            not text).
        name: The argument's name, first word of the message (``"dt"``).
        lo: Smallest accepted value, or ``None``.
        hi: Largest accepted value, or ``None``.
        positive: Refuse 0 and below too (``lo`` may then be ``None``).
        unit: The unit, shown after the range (``"s"``, ``"m"``).
        what: What the value is, for the message (``"a number of seconds"``).

    Raises:
        ArgumentError: Not a real number, NaN, infinite, or out of range.
    """
    ok = isinstance(value, numbers.Real) and not isinstance(value, bool)
    v = float(value) if ok else math.nan  # type: ignore[arg-type]
    if (
        not math.isfinite(v)
        or (positive and v <= 0.0)
        or (lo is not None and v < lo)
        or (hi is not None and v > hi)
    ):
        accepted = _range(lo, hi, positive, unit)
        raise ArgumentError(f"{name} must be {what} {accepted}, got {_shown(value)}", arg=name)
    return v


def check_count(value: object, name: str, *, lo: int = 0, hi: int | None = None) -> int:
    """``value`` as a whole number within ``[lo, hi]`` (a float such as ``2.0`` is refused).

    Raises:
        ArgumentError: Not an integer (bools and floats are not), or out of range.
    """
    ok = isinstance(value, numbers.Integral) and not isinstance(value, bool)
    if not ok or value < lo or (hi is not None and value > hi):  # type: ignore[operator]
        accepted = f"from {lo:,} to {hi:,}" if hi is not None else f"of at least {lo:,}"
        raise ArgumentError(
            f"{name} must be a whole number {accepted}, got {_shown(value)}", arg=name
        )
    return int(value)  # type: ignore[call-overload]


def check_size(count: float, limit: float, name: str, what: str, *, arg: str | None = None) -> None:
    """Refuse arguments that imply more than ``limit`` of something (samples, cells...).

    Args:
        count: How many the arguments imply (a float: it may be huge or inf).
        limit: The most that is made.
        name: The argument(s) responsible, first words of the message (``"duration/dt"``).
        arg: The argument the error is about (``"dt"``); ``name`` by default.
        what: What is counted (``"samples"``).

    Raises:
        ArgumentError: ``count > limit`` (or NaN).
    """
    if not count <= limit:
        raise ArgumentError(
            f"{name} gives {count:.3g} {what}; at most {limit:,.0f} are made",
            arg=arg or name,
        )


def check_choice(value: object, name: str, choices: tuple[str, ...]) -> str:
    """``value`` if it is one of the words ``choices``.

    Raises:
        ArgumentError: Anything else (an array, a number, another word):
            ``"frame must be 'base' or 'tool', got 'world'"``.
    """
    if isinstance(value, str) and value in choices:
        return value
    words = [repr(c) for c in choices]
    listed = words[0] if len(words) == 1 else f"{', '.join(words[:-1])} or {words[-1]}"
    raise ArgumentError(f"{name} must be {listed}, got {_shown(value)}", arg=name)


def check_flag(value: object, name: str) -> bool:
    """``value`` if it is ``True`` or ``False`` (numpy's booleans too).

    Raises:
        ArgumentError: Anything else; an array, whose truth is ambiguous, or a
            number or text, which is a mistake for a switch.
    """
    if isinstance(value, bool | np.bool_):
        return bool(value)
    raise ArgumentError(f"{name} must be True or False, got {_shown(value)}", arg=name)
