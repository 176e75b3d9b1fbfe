"""The trajectory command through via points, and its sync option: output against the library."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.cli.main import main

FROM = ["0", "-30", "20", "0", "40", "0"]
VIA = ["30", "-20", "30", "10", "30", "20"]
TO = ["60", "-10", "40", "30", "20", "45"]


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


def waypoints() -> np.ndarray:
    return np.radians(np.array([FROM, VIA, TO], dtype=float))


def test_via_json_equals_the_library(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["trajectory", "puma560", "--from", *FROM, "--via", *VIA, "--to", *TO]
    code, out, _ = run(capsys, *argv, "--profile", "cubic", "--times", "0", "1", "2.5", "--json")
    assert code == 0
    d = json.loads(out)
    ref = km.via_trajectory(waypoints(), "cubic", [0, 1, 2.5])
    assert d["duration"] == 2.5 and np.allclose(d["t"], ref.t)
    assert np.allclose(np.radians(d["q"]), ref.q, atol=1e-12)
    assert np.allclose(np.radians(d["qd"]), ref.qd, atol=1e-12)
    assert np.allclose(d["waypoints"], np.degrees(waypoints()))
    # the via point is a sample, hit exactly
    i = int(np.flatnonzero(np.isclose(d["t"], 1.0))[0])
    assert np.allclose(d["q"][i], np.array(VIA, dtype=float), atol=1e-12)


def test_mstraj_with_limits_and_a_waypoint_file(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    argv = ["trajectory", "puma560", "--from", *FROM, "--via", *VIA, "--to", *TO]
    out_csv = tmp_path / "w.csv"
    code, out, _ = run(
        capsys, *argv, "--profile", "mstraj", "--vmax", "45", "--tacc", "0.3", "-o", str(out_csv)
    )
    assert code == 0 and "through 3 waypoints" in out
    t, q = km.motion.read_csv(out_csv)
    ref = km.via_trajectory(waypoints(), "mstraj", vmax=np.radians(45), tacc=0.3)
    assert np.allclose(t, ref.t) and np.allclose(q, ref.q, atol=1e-12)
    # one blend time per segment, as the Toolbox's tacc
    code, _, _ = run(
        capsys, *argv, "--profile", "mstraj", "--vmax", "45", "--tacc", "0.3", "0.5", "-o",
        str(out_csv),
    )  # fmt: skip
    ref = km.via_trajectory(waypoints(), "mstraj", vmax=np.radians(45), tacc=[0.3, 0.5])
    t, q = km.motion.read_csv(out_csv)
    assert code == 0 and np.allclose(t, ref.t) and np.allclose(q, ref.q, atol=1e-12)
    one = km.via_trajectory(waypoints(), "mstraj", vmax=np.radians(45), tacc=0.3)
    assert ref.t.size != one.t.size  # the second blend is longer
    # a waypoint file in the -o format (t,q1..qn, SI): its t column gives the times
    wfile = tmp_path / "waypoints.csv"
    km.motion.write_csv(wfile, [0.0, 1.0, 2.5], waypoints())
    code, out, _ = run(capsys, "trajectory", "puma560", "--waypoints", str(wfile), "--json")
    assert code == 0
    d = json.loads(out)
    ref = km.via_trajectory(waypoints(), "quintic", [0, 1, 2.5])
    assert np.allclose(np.radians(d["q"]), ref.q, atol=1e-12)


def test_sync_option(capsys: pytest.CaptureFixture[str]) -> None:
    base = ["trajectory", "puma560", "--from", *FROM, "--to", *TO, "--profile", "trapezoid"]
    lim = ["--vmax", "20", "40", "40", "40", "40", "40", "--amax", "100", "100", "10", "100"]
    lim += ["100", "100", "--json"]
    durations = {}
    for sync in ("each", "shared"):
        code, out, _ = run(capsys, *base, *lim, "--sync", sync)
        assert code == 0
        durations[sync] = json.loads(out)["duration"]
    a, b = np.radians(np.array(FROM, dtype=float)), np.radians(np.array(TO, dtype=float))
    v = np.radians([20, 40, 40, 40, 40, 40])
    acc = np.radians([100, 100, 10, 100, 100, 100])
    T = km.motion.minimum_time(b - a, v, acc).max()
    assert durations["each"] == pytest.approx(T, rel=1e-12)
    assert durations["shared"] > durations["each"] + 0.1


def test_cartesian_through_vias_with_a_blend(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(
        capsys,
        "trajectory",
        "puma560",
        "--from",
        *["10", "-20", "10", "20", "40", "10"],
        "--via",
        *["20", "-20", "10", "20", "40", "10"],
        "--to",
        *["20", "-10", "10", "20", "40", "10"],
        "--cartesian",
        "--blend",
        "0.02",
        "--json",
    )
    assert code == 0
    d = json.loads(out)
    assert d["events"] == [] and d["cartesian"] is True
    puma = km.load("puma560")
    q = np.radians(np.array(d["q"]))
    start = puma.fk(np.radians([10, -20, 10, 20, 40, 10]))
    end = puma.fk(np.radians([20, -10, 10, 20, 40, 10]))
    assert np.allclose(puma.fk(q[0]), start, atol=1e-9) and np.allclose(puma.fk(q[-1]), end)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--profile", "trapezoid"], "through --via points use mstraj"),
        (["--profile", "mstraj"], "--tacc must be the blend time"),
        (["--times", "0", "1"], "--times must be 3 finite values"),
        (["--times", "0", "1", "3", "--duration", "2"], "--times sets the duration"),
        (["--blend", "0.1"], "--blend rounds the corners of a --cartesian path"),
        (["--profile", "cubic", "--times", "0", "2", "1"], "--times must start at 0"),
    ],
)
def test_bad_via_options(
    capsys: pytest.CaptureFixture[str], extra: list[str], message: str
) -> None:
    argv = ["trajectory", "puma560", "--from", *FROM, "--via", *VIA, "--to", *TO, *extra]
    code, _, err = run(capsys, *argv)
    assert code == 2 and message in err and "Traceback" not in err


def test_missing_ends(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "trajectory", "puma560", "--from", *FROM)
    assert code == 2 and "give --from and --to" in err
