"""The waypoint search of jerk-limited moves against a brute-force search and the limits.

The search (``cpp/include/kinematica/jerk_via.hpp``) times its candidates on a lower
bound of the segments' durations and searches only the joints that bind a segment; these
tests catch a search that gets cheaper by getting worse: on small cases its duration is
compared with the best of a dense grid of waypoint velocities (every combination, each
segment planned by the core's own segment, ``jerk_segments``), its reported durations
with the segments planned again at the velocities it chose, and its moves with every
limit and ``qlim`` on a 1 ms resampling and at their exact extremes. The common-speed part
of the search (no joint's own speed) is replayed in plain Python, every candidate timed in
full by ``jerk_segments``: the core's bounds skip work, never change the outcome.
"""

from __future__ import annotations

import numpy as np
from support.scurve_reference import random_limits

from kinematica.core.jerk import jerk_segments, jerk_via
from kinematica.motion import JerkTrajectory, via_trajectory
from kinematica.motion.scurve_via import GOLDEN_STEPS, JOINT_SWEEPS, POSITION_ATOL, SWEEPS
from kinematica.motion.trajectory import LIMIT_RTOL

#: How far (relative) the search's duration may be above the best of the brute-force grid
#: on the small cases: a heuristic over one speed fraction per waypoint and then per joint,
#: each golden section ending within 0.618^6 (about 6 %) of it; measured up to 4.2 % with
#: the default search, 1.5 % with two joint sweeps.
SEARCH_RTOL = 0.05


def _grid_best(w: np.ndarray, lim: tuple[np.ndarray, ...], m: int) -> float:
    """The shortest move over every combination of m velocities per inner waypoint and joint."""
    k, n = w.shape
    vmax = lim[0]
    axes = [np.linspace(-vmax[j], vmax[j], m) for _ in range(k - 2) for j in range(n)]
    mesh = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, (k - 2) * n)
    c = mesh.shape[0]
    vel = np.zeros((c, k, n))
    vel[:, 1:-1] = mesh.reshape(c, k - 2, n)
    p0 = np.broadcast_to(w[:-1], (c, k - 1, n)).reshape(-1, n)
    p1 = np.broadcast_to(w[1:], (c, k - 1, n)).reshape(-1, n)
    seg = jerk_segments(p0, vel[:, :-1].reshape(-1, n), p1, vel[:, 1:].reshape(-1, n), lim)
    return float(seg.duration.reshape(c, k - 1).sum(axis=1).min())


def _cases() -> list[tuple[int, int, int]]:
    """(joints, waypoints, grid points per velocity): about 10^4 combinations each."""
    return [(1, 3, 4001), (2, 3, 101), (1, 4, 101), (3, 3, 21)]


def _search_gaps(seed: int) -> tuple[list[float], list[float]]:
    """The search's and a stop at each waypoint's excess over the grid's best, per case."""
    rng = np.random.default_rng(seed)
    search, stop = [], []
    for n, k, m in _cases() * 3:
        lim = random_limits(rng, n)
        w = np.cumsum(rng.uniform(-0.5, 1.0, (k, n)), axis=0)
        z = np.zeros(n)
        choice = jerk_via(w, z, z, lim, None, 0.0, (SWEEPS, GOLDEN_STEPS, JOINT_SWEEPS))
        # the reported durations are those of the segments at the chosen velocities
        v = choice.velocity
        again = jerk_segments(w[:-1], v[:-1], w[1:], v[1:], lim).duration
        assert np.array_equal(again, choice.time)  # the same planner, the same inputs
        best = _grid_best(w, lim, m)
        search.append(float(choice.time.sum()) / best - 1.0)
        stop.append(float(choice.stop.sum()) / best - 1.0)
    return search, stop


def test_the_search_is_within_search_rtol_of_a_brute_force_grid() -> None:
    search, stop = _search_gaps(36)
    assert max(search) <= SEARCH_RTOL
    # the boundary: the search is not exact (a tolerance 1000x smaller fails), and stopping
    # at every waypoint is beyond the tolerance (one 1000x larger would let it pass)
    assert max(search) > SEARCH_RTOL / 1000
    assert max(stop) > 5 * SEARCH_RTOL


GOLD = (5**0.5 - 1) / 2


def _replayed_search(
    w: np.ndarray, lim: tuple[np.ndarray, ...], steps: int
) -> tuple[np.ndarray, np.ndarray]:
    """The search with one speed fraction per waypoint (``jerk_via.hpp``, steps 1 and 2,
    one sweep, no joint's own speed), each candidate's two segments timed in full:
    ``(velocity (k, n), time (k - 1,))``."""
    k, n = w.shape
    vmax = lim[0]
    vhat = np.zeros((k, n))
    for i in range(1, k - 1):
        before, after = w[i] - w[i - 1], w[i + 1] - w[i]
        same = (before != 0.0) & (after != 0.0) & ((before > 0.0) == (after > 0.0))
        u = np.where(same, w[i + 1] - w[i - 1], 0.0)
        if np.any(u != 0.0):
            scale = min(vmax[j] / abs(u[j]) for j in range(n) if u[j] != 0.0)
            vhat[i] = np.minimum(vmax, np.maximum(-vmax, u * scale))

    def times(vel: np.ndarray, first: int = 0, last: int = k - 1) -> np.ndarray:
        sl = slice(first, last)
        p0, p1 = w[:-1][sl], w[1:][sl]
        return jerk_segments(p0, vel[:-1][sl], p1, vel[1:][sl], lim).duration

    def total(d: np.ndarray) -> float:  # in order, as the core adds (sum() compensates)
        out = 0.0
        for t in d.tolist():
            out += t
        return out

    vel = np.zeros((k, n))
    time = times(vel)
    best = total(time)
    for x in (0.5, 1.0):
        trial = x * vhat
        d = times(trial)
        if total(d) < best:
            vel, time, best = trial, d, total(d)
    for i in range(1, k - 1):
        if not np.any(vhat[i] != 0.0):
            continue

        def f(x: float, i: int = i, vel: np.ndarray = vel) -> float:
            trial = vel.copy()
            trial[i] = x * vhat[i]
            d = times(trial, i - 1, i + 1)
            return float(d[0]) + float(d[1])

        lo, hi = 0.0, 1.0
        x1, x2 = hi - GOLD, lo + GOLD
        f1, f2 = f(x1), f(x2)
        xb, fb = (x1, f1) if f1 <= f2 else (x2, f2)
        for _ in range(2, steps):
            if f1 <= f2:
                hi, x2, f2 = x2, x1, f1
                x1 = hi - GOLD * (hi - lo)
                f1 = f(x1)
                xb, fb = (x1, f1) if f1 < fb else (xb, fb)
            else:
                lo, x1, f1 = x1, x2, f2
                x2 = lo + GOLD * (hi - lo)
                f2 = f(x2)
                xb, fb = (x2, f2) if f2 < fb else (xb, fb)
        if fb < float(time[i - 1]) + float(time[i]):
            vel = vel.copy()
            vel[i] = xb * vhat[i]
            time = time.copy()
            time[i - 1 : i + 1] = times(vel, i - 1, i + 1)
    return vel, time


def test_the_common_speed_search_is_its_plain_replay_to_the_bit() -> None:
    # the core drops a golden-section point once a lower bound of its two segments passes
    # the point it keeps, keeps the best point's timing and stops timing a grid's common
    # speed once past the best: each only skips work, so the outcome is the plain search's
    rng = np.random.default_rng(39)
    accepted = 0
    for c in range(12):
        n, k = 7, 3 + c % 4
        lim = random_limits(rng, n)
        w = np.cumsum(rng.uniform(-0.6, 0.9, (k, n)), axis=0)
        z = np.zeros(n)
        choice = jerk_via(w, z, z, lim, None, 0.0, (1, GOLDEN_STEPS, 0))
        vel, time = _replayed_search(w, lim, GOLDEN_STEPS)
        assert np.array_equal(choice.velocity, vel)
        assert np.array_equal(choice.time, time)
        accepted += int(np.any(vel[1:-1] != 0.0))
    assert accepted >= 6  # the searches move off a stop: the replay checks their choices


def test_random_moves_hold_every_limit_and_qlim_at_their_extremes() -> None:
    rng = np.random.default_rng(37)
    held_back = 0  # moves that leave qlim unless it is given
    for _ in range(6):
        n, k = int(rng.choice([6, 7])), int(rng.integers(5, 12))
        vmax, amax, jmax = random_limits(rng, n)
        w = np.cumsum(rng.uniform(-0.5, 1.0, (k, n)), axis=0)
        w -= 0.5 * (w.max(axis=0) + w.min(axis=0))  # centred: qlim symmetric about 0
        edge = np.abs(w).max(axis=0) + rng.uniform(0.0, 0.05, n)
        qlim = np.stack([-edge, edge], axis=1)
        lim = {"vmax": vmax, "amax": amax, "jmax": jmax, "dt": 0.02}
        free = via_trajectory(w, "scurve", **lim)
        held_back += bool(np.any(free.pieces.peak(0) > edge + POSITION_ATOL))
        traj = via_trajectory(w, "scurve", **lim, qlim=qlim)
        assert isinstance(traj, JerkTrajectory) and traj.waypoint_times is not None
        p = traj.pieces
        assert np.abs(p(traj.waypoint_times) - w).max() <= 1e-10
        # position within qlim at the exact extremes of every piece
        assert np.all(p.peak(0) <= edge + POSITION_ATOL)
        t = np.union1d(np.arange(0.0, traj.duration, 1e-3), [traj.duration])
        for order, lim in ((1, vmax), (2, amax), (3, jmax)):
            assert np.all(np.abs(p(t, order)) <= lim * (1.0 + LIMIT_RTOL))
            assert np.all(p.peak(order) <= lim * (1.0 + LIMIT_RTOL))
        assert traj.margin is not None and traj.margin >= 0.0
    assert held_back >= 2


def test_a_joint_added_to_a_segment_never_shortens_it() -> None:
    # the bound the per-joint search stops and skips on: a segment's duration without one
    # joint is no longer than with it (the search then ends where it reaches that bound)
    rng = np.random.default_rng(38)
    m, n = 2000, 7
    vmax, amax, jmax = random_limits(rng, n)
    p0 = rng.uniform(-1.0, 1.0, (m, n))
    p1 = p0 + rng.uniform(-1.0, 1.0, (m, n)) * rng.choice([0.01, 1.0], (m, n))
    v0, v1 = (rng.uniform(-1.0, 1.0, (m, n)) * vmax for _ in range(2))
    full = jerk_segments(p0, v0, p1, v1, (vmax, amax, jmax)).duration
    shorter = 0
    for j in range(n):
        keep = np.arange(n) != j
        part = jerk_segments(
            p0[:, keep], v0[:, keep], p1[:, keep], v1[:, keep], (vmax[keep], amax[keep], jmax[keep])
        ).duration
        assert np.all(part <= full)
        shorter += int(np.sum(part < full))
    assert shorter > m // 10  # the joint left out often binds: the check can fail
