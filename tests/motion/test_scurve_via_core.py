"""The exact pieces and samples of a move through waypoints, made in the core in one call.

``jerk_via_move`` (``cpp/include/kinematica/jerk_pieces.hpp``) cuts each segment's
joints' profiles at their switches and samples the pieces. Checked here against what
does not share that code: each joint's phases from ``jerk_segments`` integrated in
Python (the state at any time from first principles), the pieces' exact peaks from
:meth:`PiecewisePolynomial.peak` (roots of the derivative, by eigenvalues), the sample
times from :func:`kinematica.motion.piecewise._times_between`, and ruckig's duration of
each segment.
"""

from __future__ import annotations

import kinematica._core as _core
import numpy as np
import pytest
from support.scurve_reference import random_limits

from kinematica.core.jerk import jerk_segments, jerk_via_move
from kinematica.errors import ArgumentError, KinematicaError
from kinematica.motion import via_trajectory
from kinematica.motion.piecewise import _times_between
from kinematica.motion.samples import LIMIT_RTOL, MAX_SAMPLES
from kinematica.motion.scurve_via import GOLDEN_STEPS, JOINT_SWEEPS, POSITION_ATOL, SWEEPS

#: The core's merge of switches closer than this fraction of a segment's duration.
PIECE_RTOL: float = _core.JERK_PIECE_RTOL
#: The state from the pieces against the phases integrated in Python (rad, rad/s, ...):
#: measured up to 5e-14 (the acceleration, over moves of 14-23 s).
STATE_ATOL = 1e-12
#: The core's peaks of |v|, |a|, |j| against PiecewisePolynomial.peak's (eigenvalues),
#: relative: measured up to 4.4e-13 (the acceleration at a piece's end).
PEAK_RTOL = 1e-11
SEARCH = (SWEEPS, GOLDEN_STEPS, JOINT_SWEEPS)


def _phase_state(p0: float, v0: float, t: np.ndarray, j: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """``(4, m)`` position, velocity, acceleration, jerk at local times ``tau`` of phases
    ``t, j`` from ``(p0, v0, 0)``: each phase's start state integrated, then the cubic."""
    starts = np.concatenate([[0.0], np.cumsum(t)])
    out = np.empty((4, tau.size))
    p, v, a = p0, v0, 0.0
    state = []
    for h, jk in zip(t, j, strict=True):
        state.append((p, v, a, jk))
        p, v, a = p + h * (v + h * (a / 2 + h * jk / 6)), v + h * (a + h * jk / 2), a + h * jk
    used = np.flatnonzero(t > 0)
    for s, x in enumerate(tau):
        # the last phase of nonzero duration begun at x (the right-hand one at a switch)
        k = used[np.searchsorted(starts[used], x, side="right") - 1] if x > 0 else used[0]
        p, v, a, jk = state[k]
        h = x - starts[k]
        out[:, s] = (
            p + h * (v + h * (a / 2 + h * jk / 6)),
            v + h * (a + h * jk / 2),
            a + h * jk,
            jk,
        )
    return out


def _random_move(seed: int) -> tuple[np.ndarray, tuple[np.ndarray, ...]]:
    rng = np.random.default_rng(seed)
    n, k = int(rng.choice([6, 7])), int(rng.integers(5, 9))
    lim = random_limits(rng, n)
    return np.cumsum(rng.uniform(-0.5, 1.0, (k, n)), axis=0), lim


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_samples_are_the_phases_integrated_at_their_times(seed: int) -> None:
    w, lim = _random_move(seed)
    k, n = w.shape
    z = np.zeros(n)
    dt = 0.01
    move = jerk_via_move(w, z, z, lim, None, 0.0, SEARCH, dt, MAX_SAMPLES)
    assert move.samples is not None and move.knots is not None
    t, q, qd, qdd, qddd = move.samples
    v = move.choice.velocity
    assert np.array_equal(move.knots, np.concatenate([[0.0], np.cumsum(move.choice.time)]))
    assert np.array_equal(t, _times_between(move.knots, dt))
    seg = jerk_segments(w[:-1], v[:-1], w[1:], v[1:], lim)
    assert np.array_equal(seg.duration, move.choice.time)
    got = np.stack([q, qd, qdd, qddd])  # (4, m, n)
    worst = shifted = 0.0  # the second: each joint's start 2 STATE_ATOL off
    for i in range(k - 1):
        a, b = move.knots[i], move.knots[i + 1]
        inside = (t >= a) & (t < b)
        for j in range(n):
            want = _phase_state(w[i, j], v[i, j], seg.t[i, j], seg.j[i, j], t[inside] - a)
            worst = max(worst, np.abs(got[:, inside, j] - want).max())
            want[0] += 2.0 * STATE_ATOL
            shifted = max(shifted, np.abs(got[:, inside, j] - want).max())
    # the boundary: not exact (a tolerance 1000x smaller fails), and an error of twice it
    # is seen (one 1000x larger would miss it)
    assert STATE_ATOL / 1000 < worst <= STATE_ATOL < shifted
    # every waypoint a sample, hit to the bit; the last sample the end state exactly
    at = np.searchsorted(t, move.knots)
    assert np.array_equal(t[at], move.knots) and np.array_equal(q[at], w)
    assert np.array_equal(qd[-1], z) and np.array_equal(qdd[-1], z)


def test_peaks_are_those_of_the_pieces() -> None:
    w, lim = _random_move(5)
    traj = via_trajectory(w, "scurve", vmax=lim[0], amax=lim[1], jmax=lim[2])
    z = np.zeros(w.shape[1])
    move = jerk_via_move(w, z, z, lim, None, 0.0, SEARCH, 0.01, MAX_SAMPLES)
    assert move.peak is not None
    eig = np.stack([traj.pieces.peak(order) for order in (1, 2, 3)])
    worst = float(np.abs(move.peak / eig - 1.0).max())
    # the boundary: not exact (a tolerance 1000x smaller fails), and a peak twice it off
    # is seen (one 1000x larger would miss it)
    assert PEAK_RTOL / 1000 < worst <= PEAK_RTOL
    assert np.abs(move.peak * (1.0 + 2.0 * PEAK_RTOL) / eig - 1.0).max() > PEAK_RTOL
    assert np.all(move.peak <= np.stack(lim) * (1 + LIMIT_RTOL))


def test_piece_rtol_boundary() -> None:
    # one segment, joint 2 a hair shorter than joint 1: its switches lie a hair from
    # joint 1's; gaps of half PIECE_RTOL are merged (joint 1's pieces alone), of twice it kept
    lim = (np.ones(2), np.ones(2), np.ones(2))
    z = np.zeros(2)

    def cut(delta: float) -> tuple[int, float, float, int]:
        w = np.array([[0.0, 0.0], [1.0, 1.0 - delta]])
        move = jerk_via_move(w, z, z, lim, None, 0.0, SEARCH, 0.5, MAX_SAMPLES)
        assert move.breaks is not None
        seg = jerk_segments(w[:1], z[None], w[1:], z[None], lim)
        T = float(seg.duration[0])
        s1, s2 = (np.cumsum(seg.t[0, j])[:-1] for j in range(2))
        s1, s2 = s1[seg.t[0, 0, 1:] > 0], s2[seg.t[0, 1, 1:] > 0]
        gaps = np.abs(s2[:, None] - s1[None, :]).min(axis=1)
        return move.breaks.size - 1, gaps.min() / T, gaps.max() / T, np.unique(s1).size + 1

    _, lo, hi, _ = cut(1e-9)
    unit = 1e-9 / hi  # delta per relative gap (the gaps grow linearly with delta)
    pieces, lo, hi, alone = cut(0.5 * PIECE_RTOL * unit)
    assert hi <= PIECE_RTOL and pieces == alone
    pieces, lo, hi, alone = cut(2.0 * PIECE_RTOL * unit * (hi / lo))
    assert lo > PIECE_RTOL and pieces > alone


def test_too_many_samples_and_unkept_limits_make_nothing() -> None:
    w = np.array([[0.0], [1.0], [2.0]])
    one = (np.ones(1), np.ones(1), np.ones(1))
    z = np.zeros(1)
    move = jerk_via_move(w, z, z, one, None, 0.0, SEARCH, 1e-9, MAX_SAMPLES)
    assert move.samples is None and move.breaks is None
    assert move.choice.time.sum() > 0.0
    with pytest.raises(ArgumentError, match="samples"):
        via_trajectory(w, "scurve", vmax=1, amax=1, jmax=1, dt=1e-9)
    up = np.array([[0.99], [0.5], [0.0]])
    move = jerk_via_move(
        up,
        np.array([0.9]),
        z,
        one,
        np.array([[-1.0, 1.0]]),
        POSITION_ATOL,
        SEARCH,
        0.01,
        MAX_SAMPLES,
    )
    assert move.samples is None and not np.isfinite(move.choice.stop[0])


def test_bad_core_input_is_a_value_error() -> None:
    w = np.array([[0.0], [1.0]])
    one, z = (np.ones(1), np.ones(1), np.ones(1)), np.zeros(1)
    with pytest.raises(ValueError, match="dt"):
        jerk_via_move(w, z, z, one, None, 0.0, SEARCH, 0.0, MAX_SAMPLES)
    with pytest.raises(ValueError, match="equal"):
        jerk_via_move(w[[0, 0]], z, z, one, None, 0.0, SEARCH, 0.1, MAX_SAMPLES)


def test_a_peak_beyond_a_limit_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    # the core's profiles hold the limits by construction; a peak it reports past a limit
    # by more than LIMIT_RTOL (a broken promise) is an error, one within it round-off
    import kinematica.motion.scurve_via as sv

    w = np.array([[0.0, 0.0], [1.0, 0.5], [2.0, 1.5]])
    made = sv.jerk_via_move

    def reported(factor: float) -> None:
        def fake(*args: object) -> object:
            move = made(*args)  # type: ignore[arg-type]
            move.peak[:] = 0.0
            move.peak[2, 1] = factor * 10.0  # joint 2's jerk
            return move

        monkeypatch.setattr(sv, "jerk_via_move", fake)
        via_trajectory(w, "scurve", vmax=1.0, amax=2.0, jmax=10.0)

    reported(1.0 + 0.5 * LIMIT_RTOL)
    with pytest.raises(KinematicaError, match=r"joint 2 would reach .* > jmax 10"):
        reported(1.0 + 2.0 * LIMIT_RTOL)
