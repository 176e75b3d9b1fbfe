"""A held arm with a nearly coaxial pair: isolated solutions along its neighbour's circles.

Holding the elbow of a nearly SRS 7R arm at the value that makes axes 3 and 5
parallel (the Realman RM75 at q4 = 0: 0.77 µm apart; rtb-data's iiwa 14 URDF: 0.44 mm)
leaves a 6R arm with two consecutive axes nearly on one line. The arm with them on one
line exactly reaches each pose of a 5-dimensional set along circles (only their sum
counts: :mod:`kinematica.ik.coaxial`); the real arm reaches the pose at a few isolated
points beside those circles, each determined only to about the tolerance over σ6 of its
Jacobian (σ6/σ1 about the pair's distance over the arm's size). The numeric search gives
one point, and the test for a continuum would call it one.

**The method.** The coaxial neighbour (:func:`coaxial_neighbour`: the second axis of the
pair moved across itself onto the first's line, every other frame kept) is solved by
:mod:`kinematica.ik.coaxial`'s closed form with a virtual joint at the tool: each of its
solutions names a circle (the pair's sum and the other joints; the split b = q_(a+1)
free). On the real arm, a point q(b) of a circle misses the pose by about the pair's
distance. After :data:`STRONG_STEPS` Gauss-Newton steps across the circle (in the
Jacobian's five strong directions only) the error e left is along its weakest left
singular vector u6, and a real solution lies where ``h(b) = u6 · e`` vanishes. h is
sampled at :data:`CIRCLE_SAMPLES` values of b on each circle near the pose; each sign
change is narrowed by bisection (:data:`CIRCLE_STEPS`), a sample where h comes nearest
0 without a sign change is followed by parabolic steps (:data:`TOUCH_STEPS`: two
solutions close together), and the configuration is taken by the core's repair
(``_core.repair_candidates``) to the real arm's solution, kept when its forward
kinematics meets the tolerance.

A one-dimensional search: a double root of h (two solutions merging) can be missed, so
the answer is never marked complete, and ``near_singular`` says the rows are determined
only to about the tolerance over σ6.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.dh.lines import AXIS_EXACT_TOL, line_distance
from kinematica.ik.coaxial_pair import CoaxialPair

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

__all__ = [
    "CIRCLE_SAMPLES",
    "CIRCLE_STEPS",
    "METHOD",
    "NEAR_COAXIAL_TOL",
    "PARALLEL_TOL",
    "STRONG_STEPS",
    "TOUCH_FRACTION",
    "TOUCH_STEPS",
    "coaxial_neighbour",
    "near_coaxial_answer",
    "near_coaxial_pair",
    "near_coaxial_sweep",
]

FloatArray = NDArray[np.float64]

#: What the answers' ``method`` says.
METHOD = "sweep:coaxial-neighbour"
#: A pair of consecutive axes is nearly coaxial when they are parallel (PARALLEL_TOL)
#: and at most this apart, relative to ``1 + size`` (m per m); beyond it the sweep over a
#: joint of the arm answers (:mod:`kinematica.ik.held_sweep`). rtb-data's iiwa 14 URDF at
#: q4 = 0: 1.9e-4; the RM75: 4.8e-7.
NEAR_COAXIAL_TOL = 1e-2
#: The sine of the angle of two axes counted parallel here.
PARALLEL_TOL = 1e-9
#: Values of the split b sampled over each circle's turn (every 5°).
CIRCLE_SAMPLES = 72
#: Bisection steps on a sign change of h (5° / 2²⁴, 5e-9 rad: the repair does the rest).
CIRCLE_STEPS = 24
#: A circle's sample where |h| is least among its neighbours and below this share of
#: its largest on the circle is searched for a touch (two solutions close together).
TOUCH_FRACTION = 0.1
#: Steps of successive parabolic interpolation towards such a touch.
TOUCH_STEPS = 12
#: Gauss-Newton steps in the strong directions before h is read (quadratic: the error
#: across the circle, about the pair's distance, falls to round-off in three).
STRONG_STEPS = 3
#: A circle is searched when one of its samples misses the pose by at most this many
#: times the pair's distance (m, and rad times the arm's size): the circles of the
#: neighbour's other solutions (a virtual joint far from 0) miss by the arm's size.
CIRCLE_REACH = 100.0


def near_coaxial_pair(chain: Chain) -> tuple[CoaxialPair, float] | None:
    """The first pair of consecutive axes of a 6R arm nearly on one line, and their distance (m).

    Parallel within :data:`PARALLEL_TOL`, their distance above the exact tolerance
    (:data:`~kinematica.dh.lines.AXIS_EXACT_TOL`, where :mod:`kinematica.ik.coaxial`
    answers) and at most :data:`NEAR_COAXIAL_TOL` of the arm's size.
    """
    from kinematica.ik.structure import features

    if chain.dof != 6 or bool(chain.prismatic.any()):
        return None
    f = features(chain)
    h, p = f.directions, f.points
    for i in range(5):
        if float(np.linalg.norm(np.cross(h[i], h[i + 1]))) > PARALLEL_TOL:
            continue
        d = line_distance(h[i], p[i], h[i + 1], p[i + 1])
        if AXIS_EXACT_TOL * (1.0 + f.size) < d <= NEAR_COAXIAL_TOL * (1.0 + f.size):
            return CoaxialPair(i, 1.0 if float(np.dot(h[i], h[i + 1])) > 0.0 else -1.0), d
    return None


def coaxial_neighbour(chain: Chain, pair: CoaxialPair) -> Chain:
    """The 6R arm with the pair's second axis moved across itself onto the first's line.

    Its frame before that joint's motion (at q = 0) is moved by the perpendicular from
    its origin to the first axis and turned onto the first axis' direction; every other
    frame, and the tool's pose at q = 0, stay. Made once per chain.
    """
    found = chain.memo.get("coaxial neighbour")
    if isinstance(found, Chain):
        return found
    F = chain.fixed_parts
    P = np.empty((6, 4, 4))
    P[0] = chain.start
    for i in range(5):
        P[i + 1] = P[i] @ F[i]
    a, b = pair.first, pair.second
    moved = P.copy()
    z = pair.sign * P[a, :3, 2]
    R = P[b, :3, :3]
    axis = np.cross(R[:, 2], z)
    s, c = float(np.linalg.norm(axis)), float(R[:, 2] @ z)
    if s > 0.0:  # turn the frame onto the first axis' direction (by under PARALLEL_TOL)
        k = axis / s
        K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
        moved[b, :3, :3] = (np.eye(3) + s * K + (1.0 - c) * K @ K) @ R
    r = P[b, :3, 3] - P[a, :3, 3]
    moved[b, :3, 3] = P[a, :3, 3] + float(r @ P[a, :3, 2]) * P[a, :3, 2]
    inverse = np.linalg.inv(moved)
    found = Chain.from_transforms(
        moved[0],
        np.ascontiguousarray(inverse[:-1] @ moved[1:]),
        inverse[-1] @ P[-1] @ F[-1] @ chain.tool,
        np.broadcast_to(np.eye(4), (6, 4, 4)).copy(),
        np.zeros(6, dtype=bool),
        chain.own_limits,
        np.eye(4),
    )
    chain.memo["coaxial neighbour"] = found
    return found


def _wrap(x: FloatArray | float) -> FloatArray:
    return np.remainder(np.asarray(x) + math.pi, 2.0 * math.pi) - math.pi


def _on_circles(pair: CoaxialPair, base: FloatArray, b: FloatArray) -> FloatArray:
    """``(c, m, 6)`` the points of circles ``base (c, 6)`` (q_a the sum) at splits ``b (c, m)``."""
    Q = np.repeat(base[:, None, :], b.shape[1], axis=1)
    Q[..., pair.second] = b
    Q[..., pair.first] = base[:, None, pair.first] - pair.sign * b
    return Q


def _weak_error(
    chain: Chain, Q: FloatArray, T: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``(m,)`` h = u6 · e at the rows of ``Q (m, 6)`` moved across; ``(m, 6)`` u6; the rows.

    Each row first takes :data:`STRONG_STEPS` Gauss-Newton steps restricted to the
    Jacobian's five strong directions (its weakest left out): the pose error left is
    then along u6 alone to second order in the pair's distance, and h's sign changes
    where the real arm's solution lies (at the circle's point itself h would be
    perturbed by the strong error's curvature, of the same order).
    """
    Q = np.array(Q, dtype=float)
    for step in range(STRONG_STEPS + 1):
        e = _pose_error(chain, Q, T)
        U, S, Vt = np.linalg.svd(chain.jacobian(np.ascontiguousarray(Q), workers=1)[0])
        if step == STRONG_STEPS:
            return np.einsum("mi,mi->m", U[:, :, -1], e), U[:, :, -1], Q
        c = np.einsum("mij,mi->mj", U[:, :, :5], e) / S[:, :5]
        Q += np.einsum("mj,mjk->mk", c, Vt[:, :5])
    raise AssertionError  # the loop returns


def _pose_error(chain: Chain, Q: FloatArray, T: FloatArray) -> FloatArray:
    """``(m, 6)`` the target's position less the tool's, and the rotation vector to it."""
    from kinematica.spatial import rotvec_from_matrix

    F = chain.fk(np.ascontiguousarray(Q), workers=1)[0]
    R = T[:3, :3] @ np.swapaxes(F[:, :3, :3], 1, 2)
    return np.concatenate([T[:3, 3] - F[:, :3, 3], rotvec_from_matrix(R)], axis=1)


def near_coaxial_sweep(
    chain: Chain, pair: CoaxialPair, distance: float, T: FloatArray, options: IKOptions
) -> FloatArray | None:
    """``(k, 6)`` the real arm's solutions beside its coaxial neighbour's circles, or None.

    Args:
        chain: The 6R arm (a 7R arm's held arm).
        pair: Its nearly coaxial pair (:func:`near_coaxial_pair`).
        distance: The pair's distance (m).
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``).
    """
    from kinematica.ik.coaxial import virtual_answer
    from kinematica.ik.held_sweep import SAME_TOL, repaired
    from kinematica.ik.solve import solve_ik
    from kinematica.ik.stack import pose_residuals
    from kinematica.ik.structure import features
    from kinematica.ik.tolerance import parse_tolerance

    neighbour = coaxial_neighbour(chain, pair)
    opts = dataclasses.replace(options, respect_limits=False)
    res = virtual_answer(neighbour, pair, T, opts, solve_ik)
    if res is None:
        return None
    virtual = np.concatenate([res.solutions, res.out_of_limits])
    if not len(virtual):
        return None
    keep = [j for j in range(6) if j != pair.second]
    base = np.zeros((len(virtual), 6))
    base[:, keep] = virtual[:, :5]
    b = np.broadcast_to(
        np.linspace(-math.pi, math.pi, CIRCLE_SAMPLES, endpoint=False), (len(base), CIRCLE_SAMPLES)
    ).copy()
    Q = _on_circles(pair, base, b)
    size = features(chain).size
    err = pose_residuals(chain, Q.reshape(-1, 6), T).reshape(len(base), CIRCLE_SAMPLES, 2)
    miss = (err[..., 0] + size * err[..., 1]).min(axis=1)
    near = miss <= CIRCLE_REACH * distance + parse_tolerance(options.tol).position
    base, b, Q = base[near], b[near], Q[near]
    if not len(base):
        return None
    h, u, _ = _weak_error(chain, Q.reshape(-1, 6), T)
    h, u = h.reshape(b.shape), u.reshape(*b.shape, 6)
    # u6's sign is free: made to agree along each circle with the sample before
    flip = np.einsum("cmi,cmi->cm", u[:, 1:], u[:, :-1]) < 0.0
    sign = np.ones(b.shape)
    sign[:, 1:] = np.where(np.cumsum(flip, axis=1) % 2 == 1, -1.0, 1.0)
    h, u = h * sign, u * sign[..., None]
    h_next = np.roll(h, -1, axis=1)
    around = np.einsum("ci,ci->c", u[:, -1], u[:, 0]) < 0.0  # the last sample and the first
    h_next[:, -1] = np.where(around, -h_next[:, -1], h_next[:, -1])
    c, m = np.nonzero(h * h_next <= 0.0)
    touch = _vertices(chain, pair, base, b, h, u, T)
    if not c.size and not len(touch):
        return None
    step = 2.0 * math.pi / CIRCLE_SAMPLES
    lo, hi = b[c, m].copy(), b[c, m] + step
    f_lo = h[c, m].copy()
    u_lo = u[c, m].copy()
    seeds = _on_circles(pair, base[c], lo[:, None])[:, 0]
    for _ in range(CIRCLE_STEPS):
        mid = 0.5 * (lo + hi)
        Qm = _on_circles(pair, base[c], mid[:, None])[:, 0]
        fm, um, moved = _weak_error(chain, Qm, T)
        turn = np.where(np.einsum("mi,mi->m", um, u_lo) < 0.0, -1.0, 1.0)
        fm, um = fm * turn, um * turn[:, None]
        left = fm * f_lo > 0.0
        lo, f_lo = np.where(left, mid, lo), np.where(left, fm, f_lo)
        u_lo = np.where(left[:, None], um, u_lo)
        seeds = moved
        hi = np.where(left, hi, mid)
    out, ok = repaired(chain, T, np.concatenate([seeds, touch]), parse_tolerance(options.tol))
    found: list[FloatArray] = []
    for row in _wrap(out[ok]):
        if all(np.abs(_wrap(row - o)).max() > SAME_TOL for o in found):
            found.append(row)
    return np.array(found) if found else None


def _vertices(
    chain: Chain,
    pair: CoaxialPair,
    base: FloatArray,
    b: FloatArray,
    h: FloatArray,
    u: FloatArray,
    T: FloatArray,
) -> FloatArray:
    """``(k, 6)`` the points where h comes nearest 0 without a sign change between samples.

    A sample of a circle where ``|h|`` is smaller than at both neighbours, on the same
    side and below :data:`TOUCH_FRACTION` of the circle's largest, may lie beside two
    solutions close together (h touching 0, or crossing it twice, between samples):
    its vertex is sought by successive parabolic interpolation (:data:`TOUCH_STEPS`),
    and the configuration there (moved across the circle) is a seed for the repair,
    which decides.
    """
    mid = np.abs(h[:, 1:-1])
    mask = (
        (mid <= np.abs(h[:, :-2]))
        & (mid <= np.abs(h[:, 2:]))
        & (h[:, 1:-1] * h[:, :-2] > 0.0)
        & (h[:, 1:-1] * h[:, 2:] > 0.0)
        & (mid <= TOUCH_FRACTION * np.abs(h).max(axis=1, keepdims=True))
    )
    c, m = np.nonzero(mask)
    if not c.size:
        return np.zeros((0, 6))
    m = m + 1
    t = np.stack([b[c, m - 1], b[c, m], b[c, m + 1]], axis=1)
    f = np.stack([h[c, m - 1], h[c, m], h[c, m + 1]], axis=1)
    ref = u[c, m]
    best = _on_circles(pair, base[c], b[c, m][:, None])[:, 0]
    for _ in range(TOUCH_STEPS):
        t0, t1, t2 = t[:, 0], t[:, 1], t[:, 2]
        f0, f1, f2 = f[:, 0], f[:, 1], f[:, 2]
        num = (t1 - t0) ** 2 * (f1 - f2) - (t1 - t2) ** 2 * (f1 - f0)
        den = (t1 - t0) * (f1 - f2) - (t1 - t2) * (f1 - f0)
        with np.errstate(divide="ignore", invalid="ignore"):
            v = t1 - 0.5 * num / den
        wide = np.where(t1 - t0 > t2 - t1, t0, t2)
        v = np.where(np.isfinite(v) & (v > t0) & (v < t2) & (v != t1), v, 0.5 * (t1 + wide))
        fv, uv, moved = _weak_error(chain, _on_circles(pair, base[c], v[:, None])[:, 0], T)
        fv = np.where(np.einsum("mi,mi->m", uv, ref) < 0.0, -fv, fv)
        for j in range(c.size):  # the three points about the smallest |h| of the four
            pts = sorted([(t[j, 0], f[j, 0]), (t[j, 1], f[j, 1]), (t[j, 2], f[j, 2]),
                          (v[j], fv[j])])  # fmt: skip
            k = min(max(int(np.argmin([abs(p[1]) for p in pts])), 1), 2)
            if abs(fv[j]) <= abs(f[j, 1]):
                best[j] = moved[j]
            t[j], f[j] = (np.array(col) for col in zip(*pts[k - 1 : k + 2], strict=True))
    return best


def near_coaxial_answer(
    locked: Chain, joint: int, value: float, T: FloatArray, options: IKOptions
) -> tuple[FloatArray, str, str] | None:
    """The held arm's solutions beside its coaxial neighbour's circles, or None.

    Args:
        locked: The 7R arm with ``joint`` held at ``value``.
        joint: The held joint (0-based, in the 7R arm).
        value: Its value (rad).
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``).

    Returns:
        ``(solutions (k, 7), method, note)``, ``k >= 1``; None where the held arm has
        no nearly coaxial pair or none was found.
    """
    near = near_coaxial_pair(locked)
    if near is None:
        return None
    pair, distance = near
    rows = near_coaxial_sweep(locked, pair, distance, T, options)
    if rows is None:
        return None
    J = locked.jacobian(np.ascontiguousarray(rows), workers=1)[0]
    s = np.linalg.svd(J, compute_uv=False)
    ratio = float(np.min(s[:, -1] / s[:, 0]))
    a, b = (j + (j >= joint) + 1 for j in (pair.first, pair.second))
    sign = "+" if pair.sign > 0 else "-"
    note = (
        f"with q{joint + 1} held at {value:.6g} the arm left is nearly a continuum: axes "
        f"{a} and {b} are parallel {distance:.2e} m apart, nearly one line, and it reaches "
        f"the pose at isolated points beside circles on which only q{a} {sign} q{b} counts "
        f"(σ6/σ1 of its Jacobian {ratio:.1e} at these solutions: each is exact, "
        "but the circle's points meet the tolerance too over a span of about the tolerance "
        "over σ6); found beside the circles of the arm with the two axes on one line, "
        "solved in closed form; two solutions merging may be missed"
    )
    return np.insert(rows, joint, value, axis=1), METHOD, note
