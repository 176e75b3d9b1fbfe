"""A redundant arm's parameter: a joint held at a value (``robot.ik(T, fixed={6: 0.3})``).

Locking joint k of an n-joint arm leaves an (n - 1)-joint arm whose FK is the
same (:meth:`kinematica.core.Chain.locked`: the joint's motion folded exactly into
the neighbouring fixed transforms). That arm is solved by whatever the registry
gives it, a closed form (every solution) or the numeric search, and each solution
comes back as an n-vector with ``q_k`` = the value. The answer is relative to the
lock: "unreachable" means unreachable with that joint at that value, and the
result's :attr:`~kinematica.ik.IKResult.parameter` and message say so.

A parameter is an object with a ``name``, a ``unit``, a ``span`` and a ``solve``
(:class:`Parameter`); a joint is one (:class:`JointParameter`), the arm angle of an
SRS arm another (:mod:`kinematica.ik.arm_angle`). ``fixed=`` read: :mod:`kinematica.ik.fixed`.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.core import Chain
from kinematica.errors import DimensionError, KinematicaError
from kinematica.ik.held_continuum import continuum_answer
from kinematica.ik.held_near import near_continuum_answer
from kinematica.ik.moved import (
    LOCKED_CACHE,
    end_arm,
    held_at,
    held_prepared,
    locked_chain,
    moved_targets,
    narrowed_tolerance,
    on_axis,
)
from kinematica.ik.request import IKRequest
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.solve import solve_ik
from kinematica.ik.stack import replace_rows, stack_results, widen_batch, widen_result
from kinematica.ik.targets import Targets, parse_targets
from kinematica.spatial import wrap_angle

__all__ = [
    "LOCKED_CACHE",
    "JointParameter",
    "Parameter",
    "joint_names",
    "locked_chain",
]

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

FloatArray = NDArray[np.float64]


class Parameter(Protocol):
    """What a redundancy parameter is: a name, a unit, a span, and the arm solved at values."""

    @property
    def name(self) -> str:
        """How results and messages name it (``"q7"``, a joint's name, ``"arm angle"``)."""
        ...

    @property
    def unit(self) -> str:
        """``"rad"`` or ``"m"``."""
        ...

    @property
    def keyword(self) -> str:
        """The ``robot.ik`` keyword that holds it at another value (``"fixed="``)."""
        ...

    def default_reason(self, chain: Chain) -> str:
        """Why :meth:`default` is the value ``auto`` holds without q0, for its note."""
        ...

    @property
    def round_values(self) -> int:
        """Values of one target that cost about what a round of ``auto``'s sweep costs.

        :func:`~kinematica.ik.nearest_value.nearest_with_solutions` tries at least this
        many over a round's targets: 1 where one value costs as much as a round.
        """
        ...

    def span(self, chain: Chain) -> tuple[float, float]:
        """The values it takes (a joint: its limits)."""
        ...

    def default(self, chain: Chain) -> float:
        """The value used when neither a value nor q0 is given."""
        ...

    def value_of(self, chain: Chain, q: FloatArray) -> FloatArray:
        """``(N,)`` its value at configurations ``q (N, n)`` (q0's, for ``auto``)."""
        ...

    def describe(self, value: float) -> str:
        """``"q7 = 0.3 rad"``: the parameter at a value, for notes."""
        ...

    def solve(
        self, chain: Chain, target: ArrayLike, values: ArrayLike, options: IKOptions
    ) -> IKResult | IKBatchResult:
        """Every solution of ``target`` with the parameter at ``values`` (one per target)."""
        ...


def joint_names(chain: Chain, names: Sequence[str] | None) -> tuple[str, ...]:
    """The joints' display names: ``names`` when given, else ``q1..qn``."""
    if names is not None:
        return tuple(names)
    return tuple(f"q{i + 1}" for i in range(chain.dof))


@dataclass(frozen=True, slots=True)
class JointParameter:
    """Joint ``index`` (0-based) as the parameter: the arm solved with it held at a value.

    Attributes:
        index: The joint, 0-based.
        name: Its display name (the joint's own name, else ``"q<index + 1>"``).
        prismatic: True for a sliding joint (values in m, else rad).
    """

    index: int
    name: str
    prismatic: bool = False
    #: One: a value may cost a locked arm's general 6R (tens of µs), about a round.
    round_values: ClassVar[int] = 1
    keyword: ClassVar[str] = "fixed="

    @property
    def unit(self) -> str:
        """``"m"`` for a prismatic joint, else ``"rad"``."""
        return "m" if self.prismatic else "rad"

    def describe(self, value: float) -> str:
        """``"q7 = 0.3 rad"``."""
        return f"{self.name} = {value:.6g} {self.unit}"

    def span(self, chain: Chain) -> tuple[float, float]:
        """The joint's limits solutions are held to (``(-π, π)`` for a free revolute joint)."""
        lo, hi = chain.qlim[self.index]
        return float(lo), float(hi)

    def default(self, chain: Chain) -> float:
        """The value used when none is given: the middle of its own limits, 0 when it has none."""
        lo, hi = chain.own_limits[self.index]
        return float(0.5 * (lo + hi)) if math.isfinite(lo) and math.isfinite(hi) else 0.0

    def default_reason(self, chain: Chain) -> str:
        """``"the middle of its limits"``, or ``"0: it has no limits"``."""
        middle = np.isfinite(chain.own_limits[self.index]).all()
        return "the middle of its limits" if middle else "0: it has no limits"

    def value_of(self, chain: Chain, q: FloatArray) -> FloatArray:
        """``(N,)`` the joint's entry of each configuration ``q (N, n)``."""
        return np.asarray(q[:, self.index], dtype=float)

    def check(self, chain: Chain, value: object, respect_limits: bool = True) -> float:
        """``value`` as a float the joint may hold.

        Raises:
            KinematicaError: (``arg="fixed"``) not a real number, NaN/inf, or, when
                limits are respected, outside them (no solution could be within them).
        """
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise KinematicaError(
                f"fixed: the value of {self.name} must be a number ({self.unit}), got {value!r}",
                arg="fixed",
            )
        v = float(value)
        if not math.isfinite(v):
            raise KinematicaError(f"fixed: {self.name} must be finite, got {v}", arg="fixed")
        own_lo, own_hi = chain.own_limits[self.index].tolist()
        if not self.prismatic and not (math.isfinite(own_lo) or math.isfinite(own_hi)):
            v = float(wrap_angle(v))  # a joint free to turn: its angles come out in (-π, π]
        lo, hi = chain.qlim[self.index].tolist()
        if respect_limits and not lo <= v <= hi:
            raise KinematicaError(
                f"fixed: {self.name} = {v:.6g} {self.unit} is outside its limits "
                f"[{lo:.6g}, {hi:.6g}] {self.unit}, so no solution would be within them "
                "(ignore the limits to see the solutions there)",
                arg="fixed",
            )
        return v

    def solve(
        self, chain: Chain, target: ArrayLike, values: ArrayLike, options: IKOptions
    ) -> IKResult | IKBatchResult:
        """Every solution with the joint held at ``values`` (one, or one per target).

        A pose target of the first or last joint: the value only moves the base or
        the tool, so the arm locked at 0 is built once and the targets are moved
        instead (``T' = G₀ M(v)⁻¹ G₀⁻¹ T`` for the first, ``T G⁻¹ M(v)⁻¹ G`` for the
        last, ``G₀`` the chain's start, ``G`` the last fixed part times the tool;
        the last joint's for one value only where the tool point is on its axis,
        :func:`~kinematica.ik.moved.on_axis`). Otherwise (a middle joint, a position
        target, a mask, or fewer than 6 joints left) one locked arm per value.

        Args:
            chain: The whole arm.
            target: As :func:`~kinematica.ik.solve_ik` takes it.
            values: One value for every target, or ``(N,)`` one per target of a
                batch (C order); already checked (:meth:`check`).
            options: The IK settings (``q0`` of the whole arm; ``fixed`` ignored).

        Returns:
            The whole arm's result: solutions ``(k, n)`` (``(..., k, n)``) with
            ``q[index]`` equal to the value, and ``parameter`` naming it.
        """
        k, n = self.index, chain.dof
        if type(target) is np.ndarray and target.shape in ((4, 4), (3,)):
            # one target: read where it is solved (its pose only where it is moved)
            targets = _ONE_POSITION if target.shape == (3,) else _ONE_POSE
            parsed = False
        else:
            targets, parsed = parse_targets(target), True
        N = targets.poses.shape[0]
        scalar = isinstance(values, float | int)
        v = np.full(N, float(values)) if isinstance(values, float | int) else None
        v = np.broadcast_to(np.asarray(values, dtype=float), (N,)).copy() if v is None else v
        q0 = options.q0
        if q0 is not None:
            q0 = np.asarray(q0, dtype=float)
            if q0.ndim == 0 or q0.shape[-1] != n:
                raise DimensionError(
                    f"q0 must hold {n} joint values, got shape {q0.shape}", arg="q0"
                )
            q0 = np.delete(q0, k, axis=-1)
        opts = IKRequest.of(options).but(q0=q0, fixed=None, arm_angle=None)
        # no target (an empty batch): the arm locked at the default value answers, empty
        first = float(v[0]) if N else self.default(chain)
        same = scalar or bool(np.all(v == first))
        # The first joint's value, and the last's with the tool point on its axis, move the
        # target to the same problem (one locked arm for every value); the last's otherwise
        # only for values that differ per target, against a narrower tolerance (narrowed_
        # tolerance). A mask's components, an over-determined target's digits: solved as given.
        moved = not targets.position and options.mask is None and n - 1 >= 6
        exact = moved and (k == 0 or (k == n - 1 and on_axis(chain)))
        if exact and k and same:  # the held arm without a closed form: its neighbours'
            exact = not self._continua(chain, 0.0, opts, targets)
        moved = exact or (moved and k == n - 1 and not same)
        if moved:
            arm = end_arm(chain, k)
            if not exact:
                narrow = narrowed_tolerance(options.tol, chain, k, v)
                moved = narrow is not None
                if narrow is not None:
                    opts = opts.but(tol=narrow)
        ready = None if parsed else self.lean(chain, opts)  # one pose: the core's one call
        if (got := held_at(chain, k, self.name, opts, ready, target, first)) is not None:
            return got
        try:
            if moved:  # one locked arm, moved targets
                targets = targets if parsed else parse_targets(target)
                poses = moved_targets(chain, k, targets.poses, v)
                out = solve_ik(arm, targets.replace(poses=poses), opts)
                if not exact and isinstance(out, IKBatchResult):
                    out = widen_batch(out, k, v, self.name)
                    return self._exact_gaps(chain, targets, v, out, options)
            elif same and not (N > 1 and self._continua(chain, first, opts, targets)):
                if N == 1 and self._continua(chain, first, opts, targets):
                    if not parsed:  # nearly a continuum: a neighbour's sweep, before the search
                        targets, parsed = parse_targets(target), True
                    if targets.single:
                        T = targets.poses[0]
                        near = near_continuum_answer(
                            chain, k, first, self.name, T, opts, locked_chain
                        )
                        if near is not None:
                            return near
                out = solve_ik(locked_chain(chain, k, first), target, opts)
                if isinstance(out, IKResult) and self._continua(chain, first, opts, targets):
                    if not parsed:
                        targets = parse_targets(target)
                    wide = widen_result(out, k, first, (self.name, first))
                    return self._held_answer(chain, first, targets.poses[0], wide, opts)
            else:  # a middle joint at several values: one arm per value, each target alone
                return self._one_by_one(chain, targets, v, opts)
        except KinematicaError as exc:
            if exc.arg != "method":
                raise
            raise KinematicaError(
                f"{exc.message} (the arm left with {self.name} held)",
                arg=exc.arg,
                suggest=exc.suggest,
            ) from None
        if isinstance(out, IKResult):
            return widen_result(out, k, float(v[0]), (self.name, float(v[0])))
        return widen_batch(out, k, v, self.name)

    def lean(self, chain: Chain, request: IKRequest) -> Any:
        """One pose at any value in one core call (:func:`~kinematica.ik.moved.held_prepared`).

        The first joint, or the last with the tool point on its axis, of an arm of 7
        joints or more, without ``q0``, a mask or a continuum (:meth:`_continua`); else None.
        """
        k, n, one = self.index, chain.dof, _ONE_POSE
        if not (request.bare and request.key is not None and request.mask is None and n > 6):
            return None
        if k and (k != n - 1 or not on_axis(chain) or self._continua(chain, 0, request, one)):
            return None
        try:
            return held_prepared(chain, k, request, self.name)
        except KinematicaError:  # no closed form: the general path says so
            return None

    def _continua(self, chain: Chain, value: float, opts: IKOptions, targets: Targets) -> bool:
        """True when ``auto``'s pose answers on the arm locked at ``value`` may be continua.

        The arm left has no closed form (every elimination degenerate) and is tested
        for a continuum at the search's answer (:mod:`kinematica.ik.held_continuum`).
        """
        if opts.method != "auto" or targets.position or opts.mask is not None or chain.dof != 7:
            return False
        locked = locked_chain(chain, self.index, value)
        found = locked.memo.get("continua")
        if found is None:
            from kinematica.ik.coaxial_pair import coaxial_pair
            from kinematica.ik.solvers import closed_form

            found = locked.memo["continua"] = (
                not bool(chain.prismatic.any())
                and closed_form(locked, "pose") is None
                and coaxial_pair(locked) is None  # a coaxial pair: kinematica.ik.coaxial answers
            )
        return bool(found)

    def _held_answer(
        self, chain: Chain, value: float, T: FloatArray, answer: IKResult, opts: IKOptions
    ) -> IKResult:
        """The search's ``answer`` on an arm without a closed form: a continuum, or the sweep's.

        A continuum (:mod:`kinematica.ik.held_continuum`) is said so; else the solutions
        found along the self-motion (:mod:`kinematica.ik.held_sweep`) answer, where it
        finds any: the search's single point stands only where the sweep found nothing.
        """
        from kinematica.ik.held_sweep import held_sweep, sweep_result

        k = self.index
        one = continuum_answer(chain, k, value, self.name, T, answer, opts, locked_chain, solve_ik)
        if one is not answer or T.shape != (4, 4):
            return one

        def hold(s: int, target: FloatArray, values: FloatArray | float, o: IKOptions) -> object:
            return JointParameter(s, f"q{s + 1}").solve(chain, target, values, o)

        q = np.concatenate([answer.solutions, answer.out_of_limits])
        first = q[0] if len(q) else None
        swept = held_sweep(chain, k, value, T, opts, hold, first)  # type: ignore[arg-type]
        if swept is None:
            return one
        found, method, note = swept
        res = sweep_result(chain, found, method, note, T, bool(opts.respect_limits),
                           (self.name, value))  # fmt: skip
        return continuum_answer(chain, k, value, self.name, T, res, opts, locked_chain, solve_ik)

    def _exact_gaps(
        self,
        chain: Chain,
        targets: Targets,
        v: FloatArray,
        out: IKBatchResult,
        options: IKOptions,
    ) -> IKBatchResult:
        """``out`` with the targets proven out of reach solved again on their own arms.

        A gap measured from a moved target is the distance of another point than
        the tool's: those few targets are solved as they are, for a gap that is
        the tool's.
        """
        rows = np.flatnonzero(np.isfinite(out.raw.gap))
        if not rows.size:
            return out
        sub = targets.replace(
            poses=np.ascontiguousarray(targets.poses[rows]),
            shape=(int(rows.size),),
            invalid={},
            notes={},
        )
        q0 = None
        if options.q0 is not None:  # the whole arm's: the locked arm's without joint k
            q0 = np.delete(_q0_rows(options.q0, targets.shape, rows), self.index, axis=-1)
        opts = dataclasses.replace(options, q0=q0, fixed=None)
        again = self._one_by_one(chain, sub, v[rows], opts)
        return replace_rows(out, rows, again, None)

    def _one_by_one(
        self, chain: Chain, targets: Targets, v: FloatArray, opts: IKOptions
    ) -> IKBatchResult:
        """Each target on the arm locked at its own value (``opts.q0``: the locked arm's)."""
        results: dict[int, IKResult] = {}
        for i in range(targets.poses.shape[0]):
            if i in targets.invalid:
                continue
            T = targets.poses[i, :3, 3] if targets.position else targets.poses[i]
            q0 = None if opts.q0 is None else _q0_rows(opts.q0, targets.shape, i)
            vi = float(v[i])
            if self._continua(chain, vi, opts, targets):
                near = near_continuum_answer(
                    chain, self.index, vi, self.name, T, opts, locked_chain
                )
                if near is not None:
                    results[i] = near
                    continue
            arm = locked_chain(chain, self.index, vi)
            one = solve_ik(arm, T, dataclasses.replace(opts, q0=q0))
            assert isinstance(one, IKResult)
            one = widen_result(one, self.index, vi, (self.name, vi))
            if self._continua(chain, vi, opts, targets):
                one = self._held_answer(chain, vi, T, one, opts)
            results[i] = one
        return stack_results(results, targets, chain.dof, self.name, v)


#: One target not read yet (:meth:`JointParameter.solve`): its kind alone, no pose.
_ONE_POSE = Targets(np.full((1, 4, 4), np.nan), (), False)
_ONE_POSITION = Targets(_ONE_POSE.poses, (), True)
_ONE_POSE.poses.flags.writeable = False


def _q0_rows(q0: ArrayLike, shape: tuple[int, ...], rows: int | NDArray[np.intp]) -> FloatArray:
    """Row(s) ``rows`` (flat, C order) of a q0 broadcast over a batch of shape ``shape``."""
    q = np.asarray(q0, dtype=float)
    return np.broadcast_to(q, (*shape, q.shape[-1])).reshape(-1, q.shape[-1])[rows]
