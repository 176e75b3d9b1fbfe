"""``kinematica trajectory --optimal``: the library's timing, its figure, its exit codes."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from support.helpers import run_cli as run

import kinematica as km

FROM = ["0", "-30", "20", "0", "30", "0"]
TO = ["90", "-20", "30", "30", "45", "120"]


def test_optimal_json_is_the_library_timing(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["--from", *FROM, "--to", *TO, "--optimal", "--vmax", "90", "--amax", "300"]
    code, out, _ = run(capsys, "trajectory", "puma560", *args, "--json")
    assert code == 0
    got = json.loads(out)
    W = np.radians([[float(v) for v in FROM], [float(v) for v in TO]])
    ref = km.time_optimal(W, np.radians(90), np.radians(300))
    assert got["status"] == "ok" and got["duration"] == pytest.approx(ref.duration, rel=1e-12)
    assert np.allclose(np.radians(got["q"]), ref.trajectory.q, atol=1e-9)
    assert np.abs(got["qd"]).max() <= 90 * (1 + 1e-9)


def test_optimal_figure_and_csv(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    png, csv = tmp_path / "topp.png", tmp_path / "topp.csv"
    args = ["--from", *FROM, "--to", *TO, "--optimal", "--vmax", "90", "--amax", "300"]
    code, out, _ = run(capsys, "trajectory", "puma560", *args, "--plot", str(png), "-o", str(csv))
    assert code == 0 and "time-optimal" in out and png.stat().st_size > 10_000
    t, q = km.motion.read_csv(csv)
    assert t[0] == 0.0 and np.allclose(np.degrees(q[-1]), [float(v) for v in TO])


def test_a_path_the_limits_hold_still_exits_1(capsys: pytest.CaptureFixture[str]) -> None:
    vmax = ["90", "90", "0", "90", "90", "90"]
    args = ["--from", *FROM, "--to", *TO, "--optimal", "--vmax", *vmax, "--amax", "300"]
    code, out, _ = run(capsys, "trajectory", "puma560", *args)
    assert code == 1 and "velocity of joint 3" in out and "infeasible" in out


def test_optimal_cartesian_with_a_tool_speed(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["--from", "10", "-40", "20", "0", "50", "0", "--to", "20", "-30", "10", "10", "40", "5"]
    more = ["--cartesian", "--optimal", "--vmax", "90", "--tcp-speed", "0.2", "--json"]
    code, out, _ = run(capsys, "trajectory", "puma560", *args, *more)
    got = json.loads(out)
    assert code == 0 and got["status"] == "ok" and got["cartesian"]
    puma = km.load("puma560")
    q, qd = np.radians(got["q"]), np.radians(got["qd"])
    speed = np.linalg.norm(np.einsum("mij,mj->mi", puma.jacobian(q)[:, :3], qd), axis=1)
    assert speed.max() <= 0.2 * (1 + 1e-9)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ([], "--optimal needs limits"),
        (["--vmax", "90", "--duration", "2"], "drop --duration"),
        (["--vmax", "90", "--tcp-speed", "-1"], "--tcp-speed must be"),
    ],
)
def test_optimal_bad_options(
    capsys: pytest.CaptureFixture[str], extra: list[str], message: str
) -> None:
    code, _, err = run(
        capsys, "trajectory", "puma560", "--from", *FROM, "--to", *TO, "--optimal", *extra
    )
    assert code == 2 and message in err


def test_tcp_speed_without_optimal_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(
        capsys, "trajectory", "puma560", "--from", *FROM, "--to", *TO, "--tcp-speed", "0.5"
    )
    assert code == 2 and "--optimal" in err
