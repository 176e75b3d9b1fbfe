"""6R arms with two consecutive joints on one axis: a continuum at every pose they reach.

Two consecutive revolute joints a, a + 1 whose axes are one line (a DH row with
``a = 0`` and ``α = 0`` or π between them, URDF axes on one line) turn the rest of
the arm about that line together: only ``q_a + σ q_(a+1)`` counts (σ = +1 when the
axes point the same way, -1 when opposite). Such a 6R arm has five effective degrees
of freedom. It reaches a five-dimensional set of poses; each pose of that set is
reached along a circle of (q_a, q_(a+1)) for each solution of the arm with the pair
merged, and a generic pose is out of reach. No elimination of the general 6R applies
(every one degenerates), and the numeric search would answer one point of a
continuum as if it were the answer.

**The method.** Joint a + 1 is held at 0 (:meth:`~kinematica.core.Chain.locked`: the
arm's own transforms, so joint a now stands for the pair's sum), which leaves a 5R
arm, over-determined by a pose. A virtual revolute joint is added at the tool, about
a fixed line in general position relative to the tool frame
(:data:`VIRTUAL_AXIS`, :data:`VIRTUAL_POINT`): the 6R arm so made reaches the
target with the virtual angle θ at 0 exactly at the 5R arm's solutions, and the
closed form of that 6R (the general 6R, or whichever family its axes make) gives
every one of its solutions, hence every solution of the 5R arm. The virtual joint's
twist lies outside the 5R arm's five Jacobian columns at a generic configuration, so
the 6R is regular there and its solutions with θ = 0 are isolated and accurate to
round-off; the fixed line is skew to every axis of a generic arm, so the builder
meets no new degeneracy (should it, a second line is tried, :data:`VIRTUAL_LINES`).

This was preferred to a one-dimensional search over the pair's sum (a sub-problem
per step, tangencies to detect): it is one closed-form solve, the general 6R's
completeness carries over, and the answer's accuracy is the closed form's.

**Which solutions are kept.** A solution of the virtual arm with θ = 0 is one of the
real arm with joint a + 1 at 0: each is put on the real arm with θ dropped and kept
when its forward kinematics there meets the target within the check's tolerance
(the call's ``tol``). That is the one test that decides, measured on the arm the
user has, so no second tolerance on θ is introduced (θ off 0 by ε moves the tool by
at most ε times the line's distance from it, which the residual measures).

**The answer.** Where representatives exist: ``singular``, the pair named free
(``free_joints``); each representative has joint a + 1 at the value nearest 0 that
keeps both joints within their limits (0 without limits) and joint a at the sum
less it. Where none: ``unreachable`` when the virtual arm's answer is complete (a
closed form, every solution given, none with θ at 0; its gap when it proves one,
since the 5R arm reaches no more than the 6R), else ``not_found``.

The pair must be one line to within the line geometry's exact tolerance
(:data:`~kinematica.dh.lines.AXIS_EXACT_TOL`): an arm whose pair is only nearly
coaxial has isolated solutions, not a continuum, and is not answered here.
"""

from __future__ import annotations

import dataclasses
import math
import weakref
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.ik.coaxial_pair import CoaxialPair, coaxial_pair
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.stack import pose_residuals, solve_each
from kinematica.ik.status import IKStatus
from kinematica.ik.structure import features

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions
    from kinematica.ik.targets import Targets

__all__ = [
    "METHOD",
    "VIRTUAL_AXIS",
    "VIRTUAL_LINES",
    "VIRTUAL_POINT",
    "CoaxialPair",
    "aimed_line",
    "coaxial_answer",
    "coaxial_pair",
    "frame_on",
    "solve_coaxial",
    "turn_axis",
    "virtual_answer",
    "virtual_arm",
    "with_virtual_joint",
]

FloatArray = NDArray[np.float64]
Solve = Callable[[Chain, FloatArray, "IKOptions"], "IKResult | IKBatchResult"]

#: What the answers' ``method`` says.
METHOD = "analytic:coaxial-pair"
#: The virtual joint's axis, in the tool frame: a direction with no special relation to
#: the frame's axes (unit; the components of (2, -3, 5) / √38).
VIRTUAL_AXIS: tuple[float, float, float] = (
    2 / math.sqrt(38),
    -3 / math.sqrt(38),
    5 / math.sqrt(38),
)
#: A point of that axis, in the tool frame, in units of the arm's size (m per m).
VIRTUAL_POINT: tuple[float, float, float] = (0.31, 0.17, -0.23)
#: The lines tried (the second only where the first leaves a 6R without a closed form):
#: (direction, point) in the tool frame; the second is the first turned and moved.
VIRTUAL_LINES: tuple[tuple[tuple[float, float, float], tuple[float, float, float]], ...] = (
    (VIRTUAL_AXIS, VIRTUAL_POINT),
    ((-5 / math.sqrt(42), 1 / math.sqrt(42), 4 / math.sqrt(42)), (-0.19, 0.41, 0.13)),
)


#: Random configurations of the 5R arm tried for a line aimed at a target.
AIM_SAMPLES = 32
#: Bisection steps on the segment between two of them (2⁻⁶⁰ of the segment: round-off).
AIM_STEPS = 60
#: The aimed line's turn must be a turn (|sin φ|, 1 + cos φ above this) of pitch at most
#: this relative to its translation.
AIM_TOL = 1e-9
#: The seed of those configurations (the same line for the same target, every call).
AIM_SEED = 32


_VIRTUAL: weakref.WeakKeyDictionary[Chain, tuple[Chain, ...]] = weakref.WeakKeyDictionary()


def virtual_arm(chain: Chain, pair: CoaxialPair, line: int = 0) -> Chain:
    """The 6R arm: joint a + 1 held at 0, and a virtual joint about ``VIRTUAL_LINES[line]``.

    Its FK at ``(q without q_(a+1), θ)`` is the real arm's at q_(a+1) = 0, times the
    turn by θ about the virtual line at the tool (made once per chain and line).
    """
    made = _VIRTUAL.get(chain, ())
    if line < len(made):
        return made[line]
    size = features(chain).size
    arms = list(made)
    for direction, point in VIRTUAL_LINES[len(made) : line + 1]:
        W = frame_on(np.array(direction), size * np.array(point))
        arms.append(_with_virtual(chain, pair, W))
    _VIRTUAL[chain] = tuple(arms)
    return arms[line]


def _with_virtual(chain: Chain, pair: CoaxialPair, W: FloatArray) -> Chain:
    """The virtual arm about the z axis of the frame ``W (4, 4)`` (tool frame).

    Joint a stands for the pair's sum: its limits are the sum of the pair's
    (``[lo_a + lo_b, hi_a + hi_b]``, or for opposite axes ``[lo_a - hi_b, hi_a - lo_b]``);
    the virtual joint has none.
    """
    locked = _held(chain, pair)
    limits = np.array(locked.own_limits, dtype=np.float64)
    limits[pair.first] = _sum_limits(chain.own_limits, pair)
    return with_virtual_joint(locked, W, limits)


def with_virtual_joint(locked: Chain, W: FloatArray, limits: FloatArray) -> Chain:
    """A 5R arm with a revolute joint added at its tool, about the z axis of ``W (4, 4)``.

    Args:
        locked: The 5R arm (revolute joints).
        W: ``(4, 4)`` the frame (in the tool frame) whose z axis the virtual joint turns
            about.
        limits: ``(5, 2)`` the 5R arm's joints' limits (rad); the virtual joint has none.

    Returns:
        The 6R arm whose FK at ``(q, θ)`` is the 5R arm's at q times the turn by θ about
        that line, at the tool.
    """
    F = locked.fixed_parts
    between = np.concatenate([F[:4], (F[4] @ locked.tool @ W)[None]])
    return Chain.from_transforms(
        locked.start,
        between,
        np.asarray(np.linalg.inv(W), dtype=np.float64),
        np.broadcast_to(np.eye(4), (6, 4, 4)).copy(),
        np.zeros(6, dtype=bool),
        np.vstack([limits, [-math.inf, math.inf]]),
        np.eye(4),
    )


_HELD: weakref.WeakKeyDictionary[Chain, Chain] = weakref.WeakKeyDictionary()


def _held(chain: Chain, pair: CoaxialPair) -> Chain:
    """The 5R arm: joint a + 1 held at 0 (made once per chain)."""
    found = _HELD.get(chain)
    if found is None:
        found = _HELD[chain] = chain.locked(pair.second, 0.0)
    return found


def aimed_line(
    chain: Chain, pair: CoaxialPair, T: FloatArray, rng: np.random.Generator
) -> FloatArray | None:
    """``(4, 4)`` a frame (tool frame) whose z axis makes a virtual arm that reaches T, or None.

    The virtual arm reaches T at (q, θ) when ``E = FK5(q)⁻¹ T`` is a turn by θ about the
    line: a screw of pitch 0. The pitch's numerator ``s(q) = w · t`` (w the vector of
    E's rotation, ``|w| = sin φ``; t its translation) is continuous in q; two of
    :data:`AIM_SAMPLES` random configurations where it has opposite signs are joined by
    a segment, bisected to a root (:data:`AIM_STEPS` steps), and kept when E there is a
    turn about a line to :data:`AIM_TOL` (a sign change through φ = π is not one).
    None where no sample pair gives one.
    """
    locked = _held(chain, pair)
    Q = rng.uniform(-math.pi, math.pi, (AIM_SAMPLES, 5))
    Tinv_free = T  # T is used as FK5(q)⁻¹ T below

    def screw(q: FloatArray) -> tuple[FloatArray, FloatArray]:
        F = locked.fk(q)[0]
        Finv = np.linalg.inv(F)
        E = Finv @ Tinv_free
        R = E[..., :3, :3]
        w = 0.5 * np.stack(
            [R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]],
            axis=-1,
        )
        return E, np.einsum("...i,...i->...", w, E[..., :3, 3])

    _, s = screw(Q)
    order = np.argsort(s)
    for lo_i, hi_i in zip(order[: AIM_SAMPLES // 2], order[::-1][: AIM_SAMPLES // 2], strict=True):
        if not s[lo_i] < 0.0 < s[hi_i]:
            break
        a, b = Q[lo_i], Q[hi_i]
        for _ in range(AIM_STEPS):
            mid = 0.5 * (a + b)
            if screw(mid[None])[1][0] < 0.0:
                a = mid
            else:
                b = mid
        E = screw(0.5 * (a + b)[None])[0][0]
        W = turn_axis(E)
        if W is not None:
            return W
    return None


def turn_axis(E: FloatArray) -> FloatArray | None:
    """A frame whose z axis is the line ``E (4, 4)`` turns about, or None (not a turn)."""
    R, t = E[:3, :3], E[:3, 3]
    w = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    cos = 0.5 * (np.trace(R) - 1.0)
    sin = float(np.linalg.norm(w))
    if sin < AIM_TOL or cos < -1.0 + AIM_TOL:  # near no turn, or a half turn: axis ill-posed
        return None
    z = w / sin
    if abs(float(z @ t)) > AIM_TOL * (1.0 + float(np.linalg.norm(t))):
        return None
    # the axis' point: (I - R) c = t in the plane normal to z (least squares)
    c = np.linalg.lstsq(np.eye(3) - R, t - (z @ t) * z, rcond=None)[0]
    return frame_on(z, c - (z @ c) * z)


def frame_on(z: FloatArray, origin: FloatArray) -> FloatArray:
    """``(4, 4)`` a frame whose z axis is the unit ``z`` and whose origin is ``origin``."""
    x = np.cross(z, (1.0, 0.0, 0.0) if abs(z[0]) < 0.9 else (0.0, 1.0, 0.0))
    x /= np.linalg.norm(x)
    W = np.eye(4)
    W[:3, 0], W[:3, 1], W[:3, 2], W[:3, 3] = x, np.cross(z, x), z, origin
    return W


def _sum_limits(own: FloatArray, pair: CoaxialPair) -> tuple[float, float]:
    """The range of ``q_a + σ q_(a+1)`` over the pair's own limits (rad)."""
    (lo_a, hi_a), (lo_b, hi_b) = own[pair.first], own[pair.second]
    if pair.sign > 0:
        return lo_a + lo_b, hi_a + hi_b
    return lo_a - hi_b, hi_a - lo_b


def _split(s: float, chain: Chain, pair: CoaxialPair, respect_limits: bool) -> tuple[float, float]:
    """``(q_a, q_(a+1))`` with ``q_a + σ q_(a+1) = s``: q_(a+1) nearest 0 within both limits.

    Without limits (or where none such exists) q_(a+1) is 0 (its limits' nearest point).
    """
    (lo_a, hi_a), (lo_b, hi_b) = chain.qlim[pair.first], chain.qlim[pair.second]
    if not respect_limits:
        return math.remainder(s, 2.0 * math.pi), 0.0
    # q_b within its limits and q_a = s - σ q_b within a's: q_b in [lo, hi]
    if pair.sign > 0:
        lo, hi = max(lo_b, s - hi_a), min(hi_b, s - lo_a)
    else:
        lo, hi = max(lo_b, lo_a - s), min(hi_b, hi_a - s)
    b = min(max(0.0, lo), hi) if lo <= hi else min(max(0.0, lo_b), hi_b)
    a = s - pair.sign * b
    if not (math.isfinite(lo_a) or math.isfinite(hi_a)):
        a = math.remainder(a, 2.0 * math.pi)
    return a, b


def _real(chain: Chain, pair: CoaxialPair, q: FloatArray, respect_limits: bool) -> FloatArray:
    """``(k, 6)`` real configurations of the virtual arm's solutions ``q (k, 6)``."""
    out = np.empty((len(q), 6))
    keep = [j for j in range(6) if j != pair.second]
    for r, row in enumerate(q):
        out[r, keep] = row[:5]
        out[r, pair.first], out[r, pair.second] = _split(
            float(row[pair.first]), chain, pair, respect_limits
        )
    return out


def coaxial_answer(
    chain: Chain, pair: CoaxialPair, T: FloatArray, options: IKOptions, solve: Solve
) -> IKResult:
    """Every representative of the continua reaching the pose ``T (4, 4)``, or why none.

    Args:
        chain: The 6R arm.
        pair: Its coaxial pair (:func:`coaxial_pair`).
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``, ``respect_limits``; ``q0`` orders them).
        solve: ``solve_ik`` (the virtual arm's closed form answers through it).
    """
    from kinematica.ik.tolerance import parse_tolerance

    tol = parse_tolerance(options.tol)
    respect = bool(options.respect_limits)
    a, b = pair.first + 1, pair.second + 1
    res = virtual_answer(chain, pair, T, options, solve)
    if res is None:
        note = (
            f"joints {a} and {b} turn about one line, and no arm with a virtual joint at the "
            "tool has a closed form: nothing was proven"
        )
        return _answer(chain, T, _Verdict(IKStatus.NOT_FOUND, note, complete=False))
    found = np.concatenate([res.solutions, res.out_of_limits])
    Q = _real(chain, pair, found, respect)
    err = pose_residuals(chain, Q, T)
    meets = (err[:, 0] <= tol.position) & (err[:, 1] <= tol.rotation)
    # within the virtual arm's limits (the pair's summed) iff a split within both exists
    inside = np.arange(len(found)) < len(res.solutions)
    Q, err, inside = Q[meets], err[meets], inside[meets]
    if options.q0 is not None and len(Q):
        order = np.argsort(np.linalg.norm(Q - np.asarray(options.q0, dtype=float), axis=1))
        Q, err, inside = Q[order], err[order], inside[order]
    sign = "+" if pair.sign > 0 else "-"
    why = (
        f"joints {a} and {b} turn about one line (only q{a} {sign} q{b} counts): the arm "
        "has 5 degrees of freedom"
    )
    complete = _decides(res)
    if len(Q):
        status = IKStatus.SINGULAR if inside.any() else IKStatus.OUT_OF_LIMITS
        note = (
            f"{why}, and reaches this pose along a continuum: the solutions given are its "
            f"representatives with q{b} nearest 0 within the limits, every solution of the "
            f"arm with q{b} held (solved in closed form with a virtual joint at the tool)"
        )
        free = (pair.first, pair.second)
        verdict = _Verdict(status, note, complete, None, free, res.near_singular)
        return _answer(chain, T, verdict, found=(Q[inside], Q[~inside], err[inside]))
    closest = None
    if len(found):
        every = pose_residuals(chain, _real(chain, pair, found, respect), T)
        closest = every[int(np.argmin(every[:, 0] + every[:, 1]))]
    if not complete and respect:  # the limited reach may still prove it
        from kinematica.ik.reach import beyond_limited_reach

        code = np.array([_core.STATUS["not_found"]])
        beyond, gaps = beyond_limited_reach(chain, T[None], code, np.array([np.nan]), tol.position)
        if beyond[0]:
            note = f"{why}, and the target lies beyond its reach within the joint limits"
            verdict = _Verdict(IKStatus.UNREACHABLE, note, complete=True, gap=float(gaps[0]))
            return _answer(chain, T, verdict, closest)
    if not complete:
        note = (
            f"{why}; the arm with a virtual joint at the tool found no solution in "
            "closed form: nothing was proven"
        )
        return _answer(chain, T, _Verdict(IKStatus.NOT_FOUND, note, complete=False), closest)
    gap = res.gap if str(res.status) == IKStatus.UNREACHABLE else None
    note = (
        f"{why}: it reaches only a 5-dimensional set of poses, and not this one (every "
        "solution of the arm with a virtual joint at the tool has that joint away from 0)"
    )
    return _answer(chain, T, _Verdict(IKStatus.UNREACHABLE, note, complete=True, gap=gap), closest)


def virtual_answer(
    chain: Chain, pair: CoaxialPair, T: FloatArray, options: IKOptions, solve: Solve
) -> IKResult | None:
    """The answer of the first virtual arm that gives a complete one (else the first's).

    None when no virtual arm has a closed form. A virtual arm's answer is incomplete
    where its closed form found nothing and the search answered (a target outside that
    arm's workspace, or at its boundary): another line makes another arm, which may
    prove more.
    """
    from kinematica.ik.solvers import closed_form

    opts = dataclasses.replace(options, q0=None, fixed=None, arm_angle=None, mask=None)
    first = None
    for line in range(len(VIRTUAL_LINES)):
        arm = virtual_arm(chain, pair, line)
        if closed_form(arm, "pose") is None or coaxial_pair(arm) is not None:
            continue
        res = solve(arm, T, opts)
        assert isinstance(res, IKResult)
        if _decides(res):
            return res
        first = res if first is None else first
    W = aimed_line(chain, pair, T, np.random.default_rng(AIM_SEED))
    if W is not None:  # a line through which this target is reached: made for it alone
        arm = _with_virtual(chain, pair, W)
        if closed_form(arm, "pose") is not None and coaxial_pair(arm) is None:
            res = solve(arm, T, opts)
            assert isinstance(res, IKResult)
            if _decides(res) or first is None:
                return res
    return first


def _decides(res: IKResult) -> bool:
    """A virtual arm's answer gives every solution it has, each once.

    A closed form's (not the search's), of isolated solutions (not a continuum's
    representatives), away from a singular set (where solutions merge within round-off).
    """
    return (
        res.complete
        and str(res.status) in (IKStatus.OK, IKStatus.OUT_OF_LIMITS, IKStatus.UNREACHABLE)
        and not res.near_singular
    )


@dataclasses.dataclass(frozen=True, slots=True)
class _Verdict:
    """What :func:`coaxial_answer` concludes of one target, beyond its solutions."""

    status: IKStatus
    note: str
    complete: bool
    gap: float | None = None
    free: tuple[int, ...] = ()
    near: bool = False


def _answer(
    chain: Chain,
    T: FloatArray,
    verdict: _Verdict,
    closest: FloatArray | None = None,
    found: tuple[FloatArray, FloatArray, FloatArray] | None = None,
) -> IKResult:
    """The :class:`IKResult` of one target.

    ``found``: its solutions within the limits, those beyond them, the residuals of
    the first; none when not given.
    """
    none = np.zeros((0, 6))
    inside, outside, residuals = found or (none, none, pose_residuals(chain, none, T))
    nearest = (math.nan, math.nan) if closest is None else (float(closest[0]), float(closest[1]))
    return IKResult(
        solutions=inside,
        status=verdict.status,
        method=METHOD,
        residuals=residuals,
        branches=tuple(f"representative #{k + 1}" for k in range(len(inside))),
        out_of_limits=outside,
        out_of_limits_branches=tuple(
            f"representative #{len(inside) + k + 1}" for k in range(len(outside))
        ),
        free_joints=verdict.free,
        gap=verdict.gap,
        nearest_error=nearest,
        notes=(verdict.note,),
        complete=verdict.complete,
        near_singular=verdict.near,
    )


def solve_coaxial(
    chain: Chain, pair: CoaxialPair, targets: Targets, options: IKOptions, solve: Solve
) -> IKResult | IKBatchResult:
    """:func:`coaxial_answer` of each pose target (one, or a batch of any shape)."""
    return solve_each(lambda T, opts: coaxial_answer(chain, pair, T, opts, solve), targets, options)
