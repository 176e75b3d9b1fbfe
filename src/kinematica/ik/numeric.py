"""Numeric IK on any serial chain: the set-up of the core's Levenberg-Marquardt search.

The search itself is the core's (``cpp/include/kinematica/lm.hpp``: one target; a
batch runs it in the core's threads). This module prepares what it needs, once
per arm and settings: each joint's wrap window and clamps, the reach bound, and
the restart configurations drawn from the seed (the same for every target of a
batch, so a target gets the same answer alone or in a batch).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.errors import ArgumentError
from kinematica.ik.result import arrays_of

__all__ = [
    "DEFAULT_MAX_ITERATIONS",
    "DEFAULT_RESTARTS",
    "DEFAULT_SEED",
    "FULL_TURN",
    "LABEL",
    "METHOD",
    "PRISMATIC_SPAN",
    "NumericSetup",
    "check_seed",
    "numeric_setup",
    "numeric_solver",
    "reach_bound",
]

if TYPE_CHECKING:
    from kinematica.ik.tolerance import Tolerance

FloatArray = NDArray[np.float64]

#: Steps per attempt. A converging attempt rarely needs more than 30; most
#: failing ones are stopped earlier by the stall test.
DEFAULT_MAX_ITERATIONS = 60
#: Restarts (from random configurations) for a target whose attempts failed.
#: Most targets need none; the hardest reachable ones seen (near the limits of
#: a 7-DOF arm, one pose in a few hundred) have 2-5 % of random starts
#: succeeding, and one in a few thousand used more than 100. An unreachable
#: target inside the reach bound costs them all.
DEFAULT_RESTARTS = 200
#: Seed of the restarts when none is given: results are reproducible.
DEFAULT_SEED = 0
#: Half-width (m) of the range restarts sample for a prismatic joint with no
#: limits; with one finite limit, the range is 2·PRISMATIC_SPAN from it.
PRISMATIC_SPAN = 1.0
#: A revolute range at least this wide (rad) is a full turn: wrapped, never clamped.
FULL_TURN = 2.0 * math.pi - 1e-12
#: The one label of the numeric solver's single candidate slot.
LABEL = "numeric"
#: The method name its results carry.
METHOD = "numeric:lm"


def _is_generator(seed: object) -> bool:
    """True for a ``numpy.random.Generator`` (without importing numpy.random: ~10 ms)."""
    random = sys.modules.get("numpy.random")
    return random is not None and isinstance(seed, random.Generator)


@dataclass(frozen=True, eq=False)
class NumericSetup:
    """The core's search for one arm and settings, and what it is made from.

    The restart configurations are drawn when a target first needs them: most
    targets are found from the first guess. A target, alone or in a batch, is
    searched from its first guess alone first, and from the restarts only when that
    did not settle it: the same answer either way, and no attempt made twice.

    Attributes:
        bounds: ``(n, 3)`` per joint: start of its 2π wrap window, lower and
            upper clamp (±inf where none).
        reach: Bound on the distance of the tool origin from the base origin (m).
        middle: ``(n,)`` the default first guess, the middle of the sampled box.
        quick: The search from the first guess alone (no restarts).
    """

    bounds: FloatArray
    reach: float
    middle: FloatArray
    quick: _core.NumericSolver
    _sampler: Callable[[], FloatArray] = field(repr=False)
    _make: Callable[[FloatArray], _core.NumericSolver] = field(repr=False)

    @cached_property
    def samples(self) -> FloatArray:
        """``(R, n)`` restart configurations, uniform within the limits (from the seed)."""
        samples = self._sampler()
        samples.flags.writeable = False
        return samples

    @cached_property
    def solver(self) -> _core.NumericSolver:
        """The search after :attr:`quick`: the restarts in order (the first guess not again)."""
        solver = self._make(self.samples)
        solver.skip_first = True
        return solver

    def ik(
        self,
        core: _core.Chain,
        T: FloatArray,
        options: _core.CheckOptions,
        q0: Any,
        labels: tuple[str, ...],
    ) -> Any:
        """One target: the first guess alone, the restarts only when it fails."""
        out = self.quick.ik(core, T, options, q0, labels)
        return out if _settled(out) else self.solver.ik(core, T, options, q0, labels)

    def prepare(
        self,
        core: _core.Chain,
        options: _core.CheckOptions,
        roundoff: float,
        labels: tuple[str, ...],
        *result: Any,
    ) -> Callable[..., Any]:
        """The search made ready for one target, as a closed form's ``prepare`` makes it.

        The first guess alone; a target it does not settle goes to the restarts (their
        answer is the caller's to complete). ``result``: ``(class, fields, statuses,
        final codes)``, as the core's ``prepare`` takes them.
        """
        cls, fields, statuses, final = result
        quick = self.quick.prepare(
            core, options, roundoff, labels, cls, fields, statuses, final & ~_UNSETTLED
        )

        def call(T: Any, q0: Any = None) -> Any:
            out: Any = quick(T, q0)
            if out is None or out.__class__ is cls or _settled(out):
                return out
            return self.solver.ik(core, T, options, q0, labels)

        return call

    def ik_batch(
        self,
        core: _core.Chain,
        T: FloatArray,
        options: _core.CheckOptions,
        q0: Any,
        invalid: Any,
        workers: int,
    ) -> Any:
        """A batch, each target as :meth:`ik` solves it (the core's ``ik_batch``).

        The first guesses alone, then the restarts on the targets they did not settle.
        Not one search of the first guess and the restarts on every target: where the
        first attempt stops short of the tolerance but within the check's polish, the
        check completes it, while that search goes on to a restart that may converge
        elsewhere (single calls and a batch would then give different solutions).
        """
        out = self.quick.ik_batch(core, T, options, q0, invalid, workers)
        rows = np.flatnonzero((out.status == _NOT_FOUND) & ~np.isfinite(out.gap))
        if rows.size:
            guess = None if q0 is None else np.ascontiguousarray(np.asarray(q0)[rows])
            poses = np.ascontiguousarray(T[rows])
            redo = self.solver.ik_batch(core, poses, options, guess, None, workers)
            merged = arrays_of(out)
            for key, value in merged.items():
                value[rows] = getattr(redo, key)
            out = _core.BatchAnswer(**merged)
        return out


#: The core's code of a target the search did not find (it may need the restarts).
_NOT_FOUND = _core.STATUS["not_found"]
_UNSETTLED = 1 << _NOT_FOUND


def _settled(out: _core.Answer) -> bool:
    """True when a search without restarts has answered (the restarts are not tried)."""
    return out.status != _NOT_FOUND or out.gap is not None  # found, or a proven gap


_SETUPS_PER_CHAIN = 8


def check_seed(seed: object) -> int | np.random.Generator | None:
    """The ``seed`` argument, validated: None, a whole number >= 0, or a Generator.

    Called before anything is solved, whether or not restarts will be needed,
    so a bad seed is an error on every call.

    Raises:
        ArgumentError: Anything else (say what was given).
    """
    if seed is None or _is_generator(seed):
        return cast("np.random.Generator | None", seed)
    if isinstance(seed, int | np.integer) and not isinstance(seed, bool) and seed >= 0:
        return int(seed)
    raise ArgumentError(
        f"seed must be a whole number >= 0 or a numpy Generator, got {seed!r}", arg="seed"
    )


def numeric_setup(
    chain: Chain,
    *,
    respect_limits: bool,
    tol_position: float,
    tol_rotation: float,
    seed: int | np.random.Generator | None,
    weights: tuple[float, ...],
    restarts: int = DEFAULT_RESTARTS,
    max_iterations: int = DEFAULT_MAX_ITERATIONS,
) -> NumericSetup:
    """The set-up, from the cache when this chain has seen these settings.

    A Generator ``seed`` is drawn from (so it is never cached). ``weights``
    (6 floats) weigh the error components x, y, z, rx, ry, rz (0: not counted).
    """
    w = weights
    key = (respect_limits, tol_position, tol_rotation, seed, restarts, max_iterations, w)
    cacheable = not _is_generator(seed)
    per_chain: dict[tuple[object, ...], NumericSetup]
    per_chain = chain.memo.setdefault("numeric set-ups", {})  # type: ignore[assignment]
    if cacheable and key in per_chain:
        return per_chain[key]
    setup = _compile(
        chain, respect_limits, tol_position, tol_rotation, seed, restarts, max_iterations, w
    )
    if cacheable:
        if len(per_chain) >= _SETUPS_PER_CHAIN:
            per_chain.pop(next(iter(per_chain)))
        per_chain[key] = setup
    return setup


def numeric_solver(
    chain: Chain,
    tolerance: Tolerance,
    respect_limits: bool,
    seed: int | np.random.Generator | None,
    weights: tuple[float, ...],
) -> tuple[NumericSetup, tuple[str, ...], str]:
    """``(set-up, branch labels, method name)`` of the search, as ``robot.ik`` runs it."""
    setup = numeric_setup(
        chain,
        respect_limits=respect_limits,
        tol_position=tolerance.position,
        tol_rotation=tolerance.rotation,
        seed=seed,
        weights=weights,
    )
    return setup, (LABEL,), METHOD


def reach_bound(chain: Chain, lo: FloatArray, hi: FloatArray) -> float:
    """A bound (m) on the distance of the tool origin from the start frame's origin.

    The tool origin is never farther than the sum of the chain's translations: each
    joint part's ``|tx| + |ty| + |tz|`` (a DH row's ``|a| + |d|``; a slide's ``tz``
    over its bounds ``lo``, ``hi``) and the tool offset. Leaving position
    components out only shortens a distance, so the bound holds under any mask.
    """
    reach = float(np.linalg.norm(chain.tool[:3, 3]))
    for t, slide, b_lo, b_hi in zip(chain.translations, chain.prismatic, lo, hi, strict=True):
        reach += abs(t[0]) + abs(t[1])
        reach += max(abs(t[2] + b_lo), abs(t[2] + b_hi)) if slide else abs(t[2])
    return reach


def _compile(
    chain: Chain,
    respect_limits: bool,
    tol_position: float,
    tol_rotation: float,
    seed: int | np.random.Generator | None,
    restarts: int,
    max_iterations: int,
    weights: tuple[float, ...],
) -> NumericSetup:
    prismatic = chain.prismatic
    revolute = ~prismatic
    lo, hi = chain.qlim[:, 0], chain.qlim[:, 1]
    free = (revolute & (hi - lo >= FULL_TURN)) | (not respect_limits)
    bounds = np.empty((chain.dof, 3))
    bounds[:, 0] = np.where(prismatic | (not respect_limits), -math.pi, lo)  # wrap window start
    bounds[:, 1] = np.where(free, -np.inf, lo)  # clamps
    bounds[:, 2] = np.where(free, np.inf, hi)
    # Restarts sample each joint's limits (revolute: one turn at most; all of
    # it when the limits are ignored); a prismatic joint without limits
    # ±PRISMATIC_SPAN, with one limit 2·PRISMATIC_SPAN from it.
    s_lo = np.where(revolute & (not respect_limits), -math.pi, lo)
    s_hi = np.where(revolute & (not respect_limits), math.pi, hi)
    s_hi = np.where(revolute, np.minimum(s_hi, s_lo + 2.0 * math.pi), s_hi)
    span = PRISMATIC_SPAN
    sample_lo = np.where(
        np.isfinite(s_lo), s_lo, np.where(np.isfinite(s_hi), s_hi - 2 * span, -span)
    )
    sample_hi = np.where(
        np.isfinite(s_hi), s_hi, np.where(np.isfinite(s_lo), s_lo + 2 * span, span)
    )
    reach = reach_bound(chain, bounds[:, 1], bounds[:, 2])
    middle = 0.5 * (sample_lo + sample_hi)
    base = chain.start[:3, 3].copy()
    n = chain.dof

    def make(samples: FloatArray) -> _core.NumericSolver:
        return _core.NumericSolver(
            bounds, _core.Tolerance(tol_position, tol_rotation), max_iterations, reach, base,
            list(weights),
            np.ascontiguousarray(samples), np.ascontiguousarray(middle),
        )  # fmt: skip

    def sampler() -> FloatArray:
        if isinstance(seed, int) or seed is None:
            rng = np.random.default_rng(DEFAULT_SEED if seed is None else seed)
        else:
            rng = seed
        return np.asarray(rng.uniform(sample_lo, sample_hi, size=(restarts, n)), dtype=float)

    if _is_generator(seed):  # drawn now: the caller's generator is consumed in call order
        drawn = sampler()

        def sampler() -> FloatArray:
            return drawn

    for a in (bounds, middle):
        a.flags.writeable = False
    return NumericSetup(bounds, reach, middle, make(np.empty((0, n))), sampler, make)
