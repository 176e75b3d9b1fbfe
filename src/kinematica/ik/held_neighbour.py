"""A joint held on a nearly SRS 7R arm: its solutions along the SRS neighbour's arm angle.

Holding a joint of a 7R arm that is SRS but for offsets (rtb-data's iiwa 14 URDF: a
shoulder 0.44 mm off; the Realman RM75: micrometres) leaves a 6R arm that is nearly a
continuum: the exact SRS arm reaches the pose along the whole circle of its arm angle,
the offsets break that circle into a few isolated solutions, and no elimination of the
general 6R is accurate there (:mod:`kinematica.ik.held_sweep` says why).

**The method.** The arm's SRS neighbour (:func:`srs_neighbour`: each of axes 1-3 moved
across itself onto the point nearest all three, each of axes 5-7 onto the point nearest
those, directions and the tool at q = 0 kept) is solved in closed form at
:data:`PSI_SAMPLES` arm angles ψ across the turn, every branch, in one call of the core
(its SRS solver at a value per target). With the elbow held, the target it is given is
moved along its shoulder-wrist line so that its elbow is at the value held (near the
stretched elbow the neighbour would otherwise miss the pose by the offsets). Each of
those configurations, a few offsets from the real arm's self-motion, is carried onto it
by the core's repair (``_core.repair_candidates``: the check's Gauss-Newton steps damped
by the residual, on all 7 joints). Along each branch (a slot of the neighbour's solver)
the held joint's value on the real arm varies with ψ by the offsets' size; where a
branch jumps between samples (a shoulder or wrist nearly singular there), midpoints are
added (:data:`REFINE_ROUNDS`); each sign change of q_k - value between adjacent samples
is narrowed on ψ (Illinois, all brackets in one call a step), a branch nearest the value
between samples is followed by parabolic steps (:data:`TOUCH_STEPS`), and the
configuration found, the held joint put at its value, is repaired on the held arm and
kept when its forward kinematics meets the tolerance.

Compared with the sweep over a joint of the real arm (:mod:`kinematica.ik.held_sweep`:
an arm built and solved per value), this costs one closed form of a fixed arm, about
3-7 ms a pose against 0.2-0.7 s (``benchmarks/ik_held.py``). It is still a
one-dimensional search, so the answer is never marked complete.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.ik.held_sweep import (
    HUG_G,
    ROOT_STEPS,
    ROUNDOFF_G,
    SAME_TOL,
    SWEEP_JUMP,
    TOUCH_G,
    repaired,
)

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions
    from kinematica.ik.registry import ClosedForm
    from kinematica.ik.tolerance import Tolerance

__all__ = [
    "MAX_SAMPLES",
    "METHOD",
    "NEIGHBOUR_TOL",
    "PSI_SAMPLES",
    "REFINE_ROUNDS",
    "TOUCH_STEPS",
    "neighbour_sweep",
    "srs_neighbour",
]

FloatArray = NDArray[np.float64]

#: What the answers' ``method`` says.
METHOD = "sweep:srs-neighbour"
#: The SRS neighbour stands in for an arm whose axes it moves by at most this, relative
#: to ``1 + size`` (m per m): the repair carries a neighbour's configuration a few such
#: offsets to the real arm in a few steps. rtb-data's iiwa 14 URDF needs 1.3e-4, the
#: RM75 2.9e-7, the Kinova Gen3 2.9e-3.
NEIGHBOUR_TOL = 1e-2
#: Arm angles of the neighbour's sweep over its turn (every 5°).
PSI_SAMPLES = 72
#: Rounds of midpoints added where a branch jumps between samples (5° / 2¹⁰ at most).
REFINE_ROUNDS = 10
#: Samples of the sweep at most, the added midpoints included.
MAX_SAMPLES = 512
#: Steps of successive parabolic interpolation towards a branch's nearest approach to
#: the value between samples (:func:`_touches`).
TOUCH_STEPS = 12


def _meeting_point(h: FloatArray, p: FloatArray) -> FloatArray:
    """``(3,)`` the point nearest the lines through ``p[i]`` along ``h[i]`` (least squares)."""
    A = np.zeros((3, 3))
    b = np.zeros(3)
    for hi, pi in zip(h, p, strict=True):
        P = np.eye(3) - np.outer(hi, hi)
        A += P
        b += P @ pi
    return np.asarray(np.linalg.lstsq(A, b, rcond=None)[0])


def srs_neighbour(chain: Chain) -> tuple[Chain, ClosedForm] | None:
    """The SRS arm next to a nearly SRS 7R chain, and its closed form at an arm angle; or None.

    Axes 1-3 are each moved across themselves (their directions kept) onto the point
    nearest all three, axes 5-7 onto the point nearest those; axis 4 and the tool's pose
    at q = 0 stay. None for an arm not 7R revolute, one already SRS (its own closed form
    answers), one whose axes would move by more than :data:`NEIGHBOUR_TOL` of its size,
    or a neighbour the SRS solver does not take. Made once per chain.
    """
    memo = chain.memo
    if "srs neighbour" not in memo:
        memo["srs neighbour"] = _build(chain)
    found: tuple[Chain, ClosedForm] | None = memo["srs neighbour"]  # type: ignore[assignment]
    return found


def _build(chain: Chain) -> tuple[Chain, ClosedForm] | None:
    from kinematica.ik.solvers import closed_form
    from kinematica.ik.structure import features

    if chain.dof != 7 or bool(chain.prismatic.any()):
        return None
    f = features(chain)
    # the frames before each motion at q = 0 (their z axes are the joints' axes)
    F = chain.fixed_parts
    P = np.empty((7, 4, 4))
    P[0] = chain.start
    for i in range(6):
        P[i + 1] = P[i] @ F[i]
    h, p = P[:, :3, 2], P[:, :3, 3]
    moved = P.copy()
    for group in ((0, 1, 2), (4, 5, 6)):
        centre = _meeting_point(h[list(group)], p[list(group)])
        for i in group:
            r = centre - p[i]
            moved[i, :3, 3] = p[i] + r - float(r @ h[i]) * h[i]
    shift = float(np.abs(moved[:, :3, 3] - p).max())
    if shift <= f.length_tol or shift > NEIGHBOUR_TOL * (1.0 + f.size):
        return None
    inverse = np.linalg.inv(moved)
    between = inverse[:-1] @ moved[1:]
    tool = inverse[-1] @ P[-1] @ F[-1] @ chain.tool
    neighbour = Chain.from_transforms(
        moved[0],
        np.ascontiguousarray(between),
        tool,
        np.broadcast_to(np.eye(4), (7, 4, 4)).copy(),
        np.zeros(7, dtype=bool),
        chain.own_limits,
        np.eye(4),
    )
    closed = closed_form(neighbour, "pose", "arm_angle")
    return None if closed is None else (neighbour, closed)


def _wrap(x: FloatArray | float) -> FloatArray:
    return np.remainder(np.asarray(x) + math.pi, 2.0 * math.pi) - math.pi


class _Sweep:
    """The neighbour's configurations at arm angles, carried onto the real arm's self-motion."""

    def __init__(
        self, chain: Chain, joint: int, value: float, T: FloatArray, tol: Tolerance
    ) -> None:
        from kinematica.ik.solvers import POSE_WEIGHTS, check_options

        found = srs_neighbour(chain)
        assert found is not None
        self.neighbour, closed = found
        self.params = closed.params
        self.slots = len(closed.labels)
        self.T = T
        self.tol = tol
        self.check = check_options(tol, False, True, POSE_WEIGHTS)
        self.chain = chain
        # q4 held: T moved along the neighbour's shoulder-wrist line to the distance q4
        # gives there (the real arm's differs by about the offsets; the repair carries each
        # configuration to the real arm's self-motion at T)
        self.aim = T if joint != 3 else self.params.aimed(T, value)

    def at(self, psi: FloatArray) -> FloatArray:
        """``(len(psi), slots, 7)`` the real arm's self-motion beside each branch (NaN: none)."""
        m = len(psi)
        aims = np.ascontiguousarray(np.broadcast_to(self.aim, (m, 4, 4)))
        raw = self.params.ik_batch_at(self.neighbour.core, aims, psi, self.check, None, None, 1)
        Q = np.full((m, self.slots, 7), np.nan)
        slot = raw.slot
        rows, cols = np.nonzero(slot >= 0)
        Q[rows, slot[rows, cols]] = raw.q[rows, cols]
        flat = Q.reshape(-1, 7)
        live = np.flatnonzero(np.isfinite(flat).all(axis=1))
        if live.size:
            out, ok = repaired(self.chain, self.T, flat[live], self.tol)
            flat[live] = np.nan
            flat[live[ok]] = out[ok]
        return Q


def neighbour_sweep(
    chain: Chain, held: Chain, joint: int, value: float, T: FloatArray, options: IKOptions
) -> tuple[FloatArray, str, str] | None:
    """The held arm's solutions found along the SRS neighbour's arm angle, or None.

    Args:
        chain: The 7R arm.
        held: It with ``joint`` held at ``value`` (``chain.locked(joint, value)``).
        joint: The held joint (0-based).
        value: Its value (rad).
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``).

    Returns:
        ``(solutions (k, 7), method, note)``: every solution found (the held joint at
        ``value``, forward kinematics within the tolerance), ``k >= 1``; None where the
        arm has no SRS neighbour or none was found.
    """
    from kinematica.ik.tolerance import parse_tolerance

    if srs_neighbour(chain) is None:
        return None
    tol = parse_tolerance(options.tol)
    sweep = _Sweep(chain, joint, value, T, tol)
    grid, Q = _refined(sweep, np.linspace(-math.pi, math.pi, PSI_SAMPLES, endpoint=False))
    seeds = _crossings(sweep, grid, Q, joint, value)
    if not len(seeds):
        return None
    seeds[:, joint] = value
    out, ok = repaired(held, T, np.delete(seeds, joint, axis=1), tol)
    found: list[FloatArray] = []
    for row in np.insert(out[ok], joint, value, axis=1):
        row = _wrap(row)
        row[joint] = value
        if all(np.abs(_wrap(row - o)).max() > SAME_TOL for o in found):
            found.append(row)
    if not found:
        return None
    rows = np.array(found)
    J = held.jacobian(np.ascontiguousarray(np.delete(rows, joint, axis=1)), workers=1)[0]
    s = np.linalg.svd(J, compute_uv=False)
    ratio = float(np.min(s[:, -1] / s[:, 0]))
    note = (
        f"with q{joint + 1} held at {value:.6g} the arm left is nearly a continuum "
        f"(σ6/σ1 of its Jacobian {ratio:.1e} at these solutions: each meets the tolerance "
        "but is determined in its joints only to about the tolerance over σ6): found along "
        f"the arm angle of the SRS arm next to it, at {PSI_SAMPLES} values across its turn "
        "solved in closed form and carried onto this arm, and the values where "
        f"q{joint + 1} crosses {value:.6g} narrowed; a branch touching that value between "
        "two samples may be missed"
    )
    return rows, METHOD, note


def _refined(sweep: _Sweep, grid: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``(S,)`` arm angles (sorted, one turn) and ``(S, slots, 7)`` the configurations there.

    Between two adjacent samples where a branch is found at both but jumps (a joint by
    more than SWEEP_JUMP: the self-motion swings through a shoulder or wrist nearly
    singular there, where the real arm's branches reconnect), the midpoint is added, for
    :data:`REFINE_ROUNDS` rounds: a crossing inside the swing is bracketed.
    """
    Q = sweep.at(grid)
    for _ in range(REFINE_ROUNDS):
        after = np.roll(Q, -1, axis=0)
        both = np.isfinite(Q).all(axis=2) & np.isfinite(after).all(axis=2)
        jump = both & (np.abs(_wrap(after - Q)).max(axis=2) > SWEEP_JUMP)
        gaps = np.flatnonzero(jump.any(axis=1))
        if not gaps.size or len(grid) + gaps.size > MAX_SAMPLES:
            break
        ends = np.append(grid[1:], grid[0] + 2.0 * math.pi)
        mid = 0.5 * (grid[gaps] + ends[gaps])
        mid = np.where(mid >= math.pi, mid - 2.0 * math.pi, mid)
        grid = np.concatenate([grid, mid])
        Q = np.concatenate([Q, sweep.at(mid)])
        order = np.argsort(grid)
        grid, Q = grid[order], Q[order]
    return grid, Q


def _crossings(
    sweep: _Sweep, grid: FloatArray, Q: FloatArray, joint: int, value: float
) -> FloatArray:
    """``(k, 7)`` the real arm's configurations where a branch's held joint is ``value``.

    Each branch (a neighbour's slot) is followed along the samples; a sign change of
    ``q_k - value`` between adjacent samples (the branch continuous: no joint jumps by
    more than SWEEP_JUMP) is narrowed on ψ, all brackets at once.
    """
    g = _wrap(Q[..., joint] - value)  # (S, slots)
    a = Q
    b = np.roll(Q, -1, axis=0)
    linked = np.abs(_wrap(b - a)).max(axis=2) <= SWEEP_JUMP  # NaN compares False
    ga, gb = g, np.roll(g, -1, axis=0)
    crossing = linked & (ga * gb <= 0.0) & (np.abs(ga) <= 1.0) & (np.abs(gb) <= 1.0)
    i, slot = np.nonzero(crossing)
    ends = np.append(grid[1:], grid[0] + 2.0 * math.pi)
    ta, tb = grid[i], ends[i]
    xa, xb = a[i, slot], b[i, slot]
    fa, fb = ga[i, slot], gb[i, slot]
    more, seeds = _touches(sweep, grid, Q, g, linked, joint, value)
    if more is not None:
        ta, tb, xa, xb, fa, fb, slot = (
            np.concatenate([x, y])
            for x, y in zip((ta, tb, xa, xb, fa, fb, slot), more, strict=True)
        )
    if not ta.size:
        return seeds
    ta, tb, xa, xb, fa, fb = (np.array(x, dtype=float) for x in (ta, tb, xa, xb, fa, fb))
    best = np.where((np.abs(fa) <= np.abs(fb))[:, None], xa, xb)
    gbest = np.minimum(np.abs(fa), np.abs(fb))
    active = (gbest > ROUNDOFF_G) & (np.maximum(np.abs(fa), np.abs(fb)) > HUG_G)
    side = np.zeros(ta.size, dtype=int)
    for _ in range(ROOT_STEPS):
        live = np.flatnonzero(active & (fa != fb))
        if not live.size:
            break
        t = (ta[live] * fb[live] - tb[live] * fa[live]) / (fb[live] - fa[live])
        x = sweep.at(t)[np.arange(live.size), slot[live]]
        gx = _wrap(x[:, joint] - value)
        w = ((t - ta[live]) / (tb[live] - ta[live]))[:, None]
        near = (
            np.abs(_wrap(x - (xa[live] + w * _wrap(xb[live] - xa[live])))).max(axis=1) <= SWEEP_JUMP
        )
        lost = ~np.isfinite(gx) | ~near
        active[live[lost]] = False
        keep = ~lost
        idx, t, x, gx = live[keep], t[keep], x[keep], gx[keep]
        better = np.abs(gx) < gbest[idx]
        best[idx[better]], gbest[idx[better]] = x[better], np.abs(gx[better])
        left = gx * fa[idx] > 0.0  # the root lies between t and tb
        for j, k in enumerate(idx.tolist()):
            if left[j]:
                ta[k], xa[k], fa[k] = t[j], x[j], gx[j]
                if side[k] == -1:
                    fb[k] *= 0.5
                side[k] = -1
            else:
                tb[k], xb[k], fb[k] = t[j], x[j], gx[j]
                if side[k] == 1:
                    fa[k] *= 0.5
                side[k] = 1
        active[idx[np.abs(gx) <= ROUNDOFF_G]] = False
    return np.concatenate([np.asarray(best), seeds])


def _touches(
    sweep: _Sweep,
    grid: FloatArray,
    Q: FloatArray,
    g: FloatArray,
    linked: NDArray[np.bool_],
    joint: int,
    value: float,
) -> tuple[tuple[FloatArray, ...] | None, FloatArray]:
    """Brackets inside a branch's approach to the value between samples, and seeds.

    A sample of a branch nearer the value than both its neighbours, on the same side
    and within TOUCH_G, is where the branch may touch or cross the value twice between
    samples (two solutions close together). Its vertex is sought by successive
    parabolic interpolation on ψ (:data:`TOUCH_STEPS`); where a point crosses the value,
    the two brackets on either side are returned (as ``_crossings`` makes them: ψ
    ends, configurations, values of q_k - value, slots), else the point nearest the
    value is a seed for the repair, which decides.
    """
    S = len(grid)
    before, after = np.roll(g, 1, axis=0), np.roll(g, -1, axis=0)
    linked_before = np.roll(linked, 1, axis=0)
    mask = (
        linked
        & linked_before
        & (np.abs(g) <= TOUCH_G)
        & (g * before > 0.0)
        & (g * after > 0.0)
        & (np.abs(g) <= np.abs(before))
        & (np.abs(g) <= np.abs(after))
    )
    i, slot = np.nonzero(mask)
    if not i.size:
        return None, np.zeros((0, 7))
    turn = 2.0 * math.pi
    t = np.stack(
        [grid[(i - 1) % S] - turn * (i == 0), grid[i], grid[(i + 1) % S] + turn * (i == S - 1)], 1
    )
    x = np.stack([Q[(i - 1) % S, slot], Q[i, slot], Q[(i + 1) % S, slot]], 1)
    f = np.stack([before[i, slot], g[i, slot], after[i, slot]], 1)
    out: list[list[FloatArray]] = [[] for _ in range(7)]
    seeds: list[FloatArray] = []
    live = np.ones(i.size, dtype=bool)
    for _ in range(TOUCH_STEPS):
        k = np.flatnonzero(live)
        if not k.size:
            break
        t0, t1, t2 = t[k, 0], t[k, 1], t[k, 2]
        f0, f1, f2 = f[k, 0], f[k, 1], f[k, 2]
        num = (t1 - t0) ** 2 * (f1 - f2) - (t1 - t2) ** 2 * (f1 - f0)
        den = (t1 - t0) * (f1 - f2) - (t1 - t2) * (f1 - f0)
        with np.errstate(divide="ignore", invalid="ignore"):
            v = t1 - 0.5 * num / den
        v = np.where(
            np.isfinite(v) & (v > t0) & (v < t2) & (v != t1),
            v,
            0.5 * (t1 + np.where(t1 - t0 > t2 - t1, t0, t2)),
        )
        xv = sweep.at(v)[np.arange(k.size), slot[k]]
        fv = _wrap(xv[:, joint] - value)
        for j, c in enumerate(k.tolist()):
            if not np.isfinite(fv[j]):
                live[c] = False
                continue
            if fv[j] * f[c, 1] <= 0.0:  # crossed: a root either side of v
                lo, hi = (1, 2) if v[j] > t[c, 1] else (0, 1)
                at_v = (v[j], xv[j], fv[j])
                for left, right in (
                    ((t[c, lo], x[c, lo], f[c, lo]), at_v),
                    (at_v, (t[c, hi], x[c, hi], f[c, hi])),
                ):
                    row = (left[0], right[0], left[1], right[1], left[2], right[2], slot[c])
                    for column, item in zip(out, row, strict=True):
                        column.append(np.asarray(item))
                live[c] = False
                continue
            # keep the three points nearest the vertex: v and its two neighbours
            pts = sorted(
                [
                    (t[c, 0], x[c, 0], f[c, 0]),
                    (t[c, 1], x[c, 1], f[c, 1]),
                    (t[c, 2], x[c, 2], f[c, 2]),
                    (v[j], xv[j], fv[j]),
                ],
                key=lambda p: p[0],
            )
            m = int(np.argmin([abs(p[2]) for p in pts]))
            m = min(max(m, 1), 2)
            for r, p in enumerate(pts[m - 1 : m + 2]):
                t[c, r], x[c, r], f[c, r] = p
    for c in np.flatnonzero(live).tolist():
        seeds.append(x[c, int(np.argmin(np.abs(f[c])))])
    brackets = None
    if out[0]:
        brackets = tuple(np.array(col) for col in out)
    return brackets, np.array(seeds).reshape(-1, 7)
