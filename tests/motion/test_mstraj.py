"""``via_trajectory(W, "mstraj")`` against the Robotics Toolbox's own ``mstraj`` output.

The reference (``tests/data/mstraj/rtb_mstraj.json``, PROVENANCE beside it) was
made once by roboticstoolbox-python 1.5.0. The Toolbox leaves the start out of
its samples; here it is sample 0, so its sample ``j`` is ours ``j + 1``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import kinematica as km
from kinematica.motion import JointTrajectory, via_polynomials, via_trajectory

DATA = Path(__file__).parent.parent / "data" / "mstraj" / "rtb_mstraj.json"
CASES: dict[str, Any] = json.loads(DATA.read_text())["cases"]
#: Agreement with the Toolbox's samples: both evaluate the same polynomials in
#: floating point, in other orders (qdd, the largest coefficients, differs by 2e-13).
MATCH = 1e-12


def ours(args: dict[str, Any]) -> tuple[JointTrajectory, np.ndarray]:
    """The Toolbox's call ``mstraj(**args)`` translated as the via module's docstring says."""
    via = np.asarray(args["viapoints"], dtype=float)
    W = via if "q0" not in args else np.vstack([args["q0"], via])
    kw: dict[str, Any] = {"tacc": args["tacc"]}
    if "qdmax" in args:
        kw["vmax"] = args["qdmax"]
    if "tsegment" in args:
        kw["times"] = np.concatenate([[0.0], np.cumsum(args["tsegment"])])
    if "qd0" in args:
        kw["qd0"] = args["qd0"]
    if "qdf" in args:
        kw["qd1"] = args["qdf"]
    return via_trajectory(W, "mstraj", dt=args["dt"], **kw), W


@pytest.mark.parametrize("name", [n for n in CASES if n != "short_segment"])
def test_the_toolbox_sample_for_sample(name: str) -> None:
    case = CASES[name]
    traj, W = ours(case["args"])
    dt = case["args"]["dt"]
    ref_q = np.array(case["q"])
    assert traj.q.shape == (ref_q.shape[0] + 1, W.shape[1])  # one more: the start
    assert np.array_equal(traj.q[0], W[0]) and np.array_equal(traj.t, np.arange(len(traj.t)) * dt)
    for x in ("q", "qd", "qdd"):
        assert np.abs(getattr(traj, x)[1:] - np.array(case[x])).max() < MATCH, x
    assert np.array_equal(traj.q[-1], W[-1])
    # the Toolbox stamps its first sample (one step after the start) t = 0
    assert traj.t[-1] == pytest.approx(case["t"][-1] + dt, abs=1e-12)


def test_the_toolbox_unit_test_by_hand() -> None:
    # The Toolbox's test_mstraj expects (to 4 decimals) these samples after the start
    # (4, 1): the first segment has no length (tseg = 2 tacc = 2 s); the second
    # moves (0, 3) at qdmax (2, 1): 1 s of blend + 3 s = 4 s, line velocity (0, 0.75).
    traj, _ = ours(CASES["toolbox_test_qdmax"]["args"])
    expected = [[4, 1], [4, 1], [4, 1.75], [4, 2.5], [4, 3.25], [13 / 3, 10 / 3], [14 / 3, 8 / 3],
                [4.25, 2.75], [3.5, 3.5], [2.75, 4.25], [2, 5]]  # fmt: skip
    assert np.allclose(traj.q, expected, atol=1e-14)
    assert traj.t[-1] == 10.0  # the Toolbox's last stamp is 9 s: its start is not a sample


def test_a_segment_too_short_for_its_line_blends_from_where_the_arm_is() -> None:
    case = CASES["short_segment"]
    traj, _ = ours(case["args"])
    ref = np.array(case["q"])
    # the Toolbox's next blend starts from a stale sample: its positions jump
    assert np.abs(np.diff(ref, axis=0)).max() > 0.35
    assert np.abs(np.diff(traj.q, axis=0)).max() < 0.1
    # ours equals the Toolbox's everywhere but on that blend (our samples 23-27)
    differ = np.flatnonzero(np.abs(traj.q[1:] - ref).max(axis=1) > MATCH) + 1
    assert differ.tolist() == [23, 24, 25, 26, 27]
    # and that blend is the quintic from the last blend's end: continuous q and qd
    pieces = via_polynomials(
        np.vstack([case["args"]["q0"], case["args"]["viapoints"]]),
        "mstraj",
        times=np.concatenate([[0.0], np.cumsum(case["args"]["tsegment"])]),
        tacc=0.3,
        dt=0.05,
    )
    for order in (0, 1):
        at = pieces.breaks[1:-1]
        assert np.abs(pieces(at, order, left=True) - pieces(at, order)).max() < 1e-12


def test_collinear_waypoints_by_hand() -> None:
    # dt and tacc exact in binary: tacc 0.5 s = 4 steps, its half 2 steps (0.25 s)
    a, b = np.array([0.2, -0.4, 1.0]), np.array([1.2, 0.6, -0.5])
    W = a + np.array([0.0, 0.3, 0.7, 1.0])[:, None] * (b - a)
    vmax, dt = np.array([0.5, 0.8, 0.6]), 0.125
    traj = via_trajectory(W, "mstraj", vmax=vmax, tacc=0.5, dt=dt)
    s = (traj.q - a) / (b - a)  # every joint at the same fraction of the line: no corner
    assert np.allclose(s, s[:, :1], atol=1e-12)
    # segment 1: joint 3 is slowest, |Δ| 0.45 at 0.6 rad/s: 0.75 s = 6 steps, plus the
    # first blend's half, 0.25 s: T = 1.0 s, line speed 0.45 / 1.0
    p = via_polynomials(W, "mstraj", vmax=vmax, tacc=0.5, dt=dt)
    assert p.breaks[1] == 0.25 and p.coef[1, 1, 2] == pytest.approx(-0.45, abs=1e-15)
    # the first blend runs from rest at w0 to the line through w0 at t = 0, which is
    # already 0.25·v ahead: Δ = T·v in T, the quintic's speed v·(15s⁴ - 32s³ + 18s²),
    # 1.512·v at s = 0.6: above the line's speed (as in the Toolbox)
    v = p.coef[1, 1]
    assert np.allclose(p(0.6 * 0.25, 1)[0], 1.512 * v, atol=1e-14)
    assert p.peak(1) == pytest.approx(1.512 * np.abs(v), rel=1e-12)  # the end blend's too


def test_per_segment_speed_limits() -> None:
    # kinematica's extension of qdmax: one row per segment; equal rows are the vector
    W = np.radians([[0, 0], [40, 10], [60, -30], [30, 0]])
    one = via_trajectory(W, "mstraj", dt=0.05, vmax=[1.0, 0.5], tacc=0.2)
    rows = via_trajectory(W, "mstraj", dt=0.05, vmax=np.tile([1.0, 0.5], (3, 1)), tacc=0.2)
    assert all(np.array_equal(a, b) for a, b in zip(one, rows, strict=True))
    vmax = np.array([[1.0, 1.0], [0.25, 0.25], [2.0, 2.0]])
    p = via_polynomials(W, "mstraj", vmax=vmax, tacc=0.2, dt=0.05)
    lines = [i for i in range(len(p.coef)) if not p.coef[i, 2:].any()]  # no acceleration
    speeds = np.abs(p.coef[lines, 1])  # each line's velocity, in segment order
    assert len(lines) == 3
    assert np.all(speeds <= vmax * (1 + 1e-12))
    # its slowest joint within one step's rounding of its limit: |Δq| / (tl + blend)
    dq = np.abs(np.diff(W, axis=0)).max(axis=1)
    tl = np.ceil(dq / vmax[:, 0] / 0.05) * 0.05
    blend = np.array([0.1, 0.2, 0.2])  # the first segment's is the half
    assert np.allclose(speeds.max(axis=1), dq / (tl + blend), atol=1e-14)


def test_bad_input() -> None:
    W = np.radians([[0, 0], [40, 10], [60, -30]])
    with pytest.raises(km.KinematicaError, match="tacc must be the blend time of mstraj"):
        via_trajectory(W, "mstraj", vmax=1.0)
    with pytest.raises(km.KinematicaError, match="tacc must be >= 0"):
        via_trajectory(W, "mstraj", vmax=1.0, tacc=-0.1)
    with pytest.raises(km.DimensionError, match="tacc must be a number or numbers of shape"):
        via_trajectory(W, "mstraj", vmax=1.0, tacc=[0.1, 0.2, 0.3])
    with pytest.raises(km.KinematicaError, match="times or vmax"):
        via_trajectory(W, "mstraj", [0, 1, 2], vmax=1.0, tacc=0.2)
    with pytest.raises(km.KinematicaError, match="times or vmax"):
        via_trajectory(W, "mstraj", tacc=0.2)
    with pytest.raises(km.KinematicaError, match="drop qdd0"):
        via_trajectory(W, "mstraj", vmax=1.0, tacc=0.2, qdd0=[0, 0])
    with pytest.raises(km.KinematicaError, match="nothing moves"):
        via_trajectory(np.zeros((3, 2)), "mstraj", vmax=1.0, tacc=0.0)
    with pytest.raises(km.ArgumentError, match="dt"):
        via_trajectory(W, "mstraj", vmax=1.0, tacc=0.2, dt=0.0)
    with pytest.raises(km.KinematicaError, match=r"joint .* > amax"):
        via_trajectory(W, "mstraj", vmax=1.0, tacc=0.2, amax=0.5)
    with pytest.raises(km.KinematicaError, match="dt is the step of method='mstraj'"):
        via_polynomials(W, "cubic", [0.0, 1.0, 2.0], dt=0.1)
