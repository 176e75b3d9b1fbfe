"""The IK server's one question: a JSON body in, every solution (or a clear refusal) out.

A request is a JSON object with exactly one key:

- ``"T"``: the target pose, base -> tool, as 4 rows of 4 numbers (m);
- ``"position"``: the tool's position only, 3 numbers (m), orientation free.

Anything else (another key, another shape, text or ``true`` where a number
belongs, a number JSON cannot hold finitely, nesting past a target's depth)
is refused with a :class:`~kinematica.errors.KinematicaError` whose message
says what was expected: the server answers it as a 4xx with that message.
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

from kinematica.errors import KinematicaError
from kinematica.robot import Robot

__all__ = ["TARGET_KEYS", "parse_request", "solve_request"]

#: What each key of a request holds, and the shape it must have.
TARGET_KEYS = {"T": (4, 4), "position": (3,)}
_SAYS = {
    "T": "a 4x4 pose (4 rows of 4 finite numbers, m)",
    "position": "3 finite coordinates x, y, z (m)",
}


def _constant(name: str) -> float:
    raise KinematicaError(f"the request holds {name}: every number must be finite")


def _load(body: bytes) -> Any:
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise KinematicaError(f"the request is not UTF-8 text: {exc}") from exc
    try:
        # Integers are read as floats: a 5,000-digit literal is then inf (refused below)
        # rather than past Python's int-from-text limit, or too large for a float.
        return json.loads(text, parse_int=float, parse_constant=_constant)
    except json.JSONDecodeError as exc:
        raise KinematicaError(f"the request is not JSON: {exc}") from exc
    except RecursionError as exc:
        raise KinematicaError("the request is not a target: JSON nested too deep") from exc


def _numbers(value: Any, shape: tuple[int, ...], key: str) -> list[Any]:
    """``value`` checked to be nested lists of finite numbers of this ``shape``."""
    wrong = KinematicaError(f'"{key}" must be {_SAYS[key]}, got {_describe(value)}')
    if not isinstance(value, list) or len(value) != shape[0]:
        raise wrong
    if len(shape) > 1:
        return [_numbers(v, shape[1:], key) for v in value]
    for v in value:
        if not isinstance(v, float) or not math.isfinite(v):
            raise wrong
    return value


def _describe(value: Any) -> str:
    if isinstance(value, list):
        kinds = {type(v).__name__ for v in value}
        inner = "numbers" if kinds <= {"float"} else ", ".join(sorted(kinds))
        return f"a list of {len(value)} ({inner})"
    if isinstance(value, float):
        return "a number" if math.isfinite(value) else "a number beyond a float's range"
    return {str: "text", bool: "true/false", dict: "an object", type(None): "null"}.get(
        type(value), type(value).__name__
    )


def parse_request(body: bytes) -> tuple[str, np.ndarray]:
    """The target a request body asks for.

    Args:
        body: The request's body, UTF-8 JSON.

    Returns:
        ``(key, target)``: ``"T"`` and a ``(4, 4)`` array, or ``"position"``
        and a ``(3,)`` array (m).

    Raises:
        KinematicaError: Anything but one finite target of the right shape.
    """
    request = _load(body)
    if not isinstance(request, dict):
        raise KinematicaError(
            f'the request must be a JSON object {{"T": ...}} or {{"position": ...}}, '
            f"got {_describe(request)}"
        )
    keys = sorted(request)
    if len(keys) != 1 or keys[0] not in TARGET_KEYS:
        raise KinematicaError(
            'the request needs exactly one of "T" (4x4 pose) or "position" (x, y, z), '
            f"got keys {keys}"
        )
    key = keys[0]
    return key, np.array(_numbers(request[key], TARGET_KEYS[key], key), dtype=float)


def _finite(a: Any) -> Any:
    """Nested lists with NaN/inf as ``None`` (valid JSON)."""
    return [_finite(v) for v in a] if isinstance(a, list) else (a if np.isfinite(a) else None)


def solve_request(robot: Robot, body: bytes) -> dict[str, Any]:
    """Answer one IK request (see the module's docstring for what it holds).

    Returns:
        ``{"status", "method", "message", "solutions" (rad, m), "branches"}``.

    Raises:
        KinematicaError: A malformed request, or a target ``robot.ik`` refuses
            (the message says what is wrong).
    """
    _, target = parse_request(body)
    res = robot.ik(target)
    solutions = np.asarray(getattr(res, "solutions", np.empty((0, robot.dof))))
    return {
        "status": str(res.status),
        "method": res.method,
        "message": getattr(res, "message", ""),
        "solutions": _finite(solutions.tolist()),
        "branches": [str(b) for b in getattr(res, "branches", ())],
    }
