"""Kinematic calibration: a whole fit, its analytic Jacobian, and pybotics when it installs.

Run with ``.venv/bin/python benchmarks/calibration.py`` (``--poses``). On one core (BLAS
limited to one thread before numpy loads), each figure measured in the same run:

* ``calibrate`` of a 6R arm (PUMA 560, UR5) from ``--poses`` measured poses, every
  parameter of the error model asked for (48, of which 30 identifiable), the nominal
  arm off by up to 1 mm / 0.1 degree, noise 10 µm / 0.001 degree: its CPU time (best
  of 9; the whole call: identification, fit, covariance, the calibrated robot, its URDF
  and DH table) against the issue's target of 50 ms, and its median wall time;
* one analytic identification Jacobian against one by central differences of the same
  residuals (2 x 48 evaluations), and the same fit with scipy's finite differences
  (``jac="2-point"``) instead of the analytic Jacobian;
* pybotics (PyPI, pure Python; fits modified DH to measured points by its own
  ``optimize_accuracy`` and scipy's ``least_squares`` with finite differences) on the UR10
  of its own predefined models, against ``calibrate(kind="position")`` on the same
  arm, points and noise: time, and the RMS error of each calibrated arm at 200 other
  configurations.

No assertions; the figures go in docs/calibration.md.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one core, as the target says
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from _common import best_of, fmt_time, header, median_of, table
from support.calibration import NOISE, perturbed

import kinematica as km
from kinematica import calibration
from kinematica.calibration.model import ErrorModel
from kinematica.calibration.residuals import Measurements, jacobian, residuals

TARGET = 0.050  # s: the target for 100 poses, full parameter set, one core


def _fd_jacobian(model: ErrorModel, data: Measurements) -> np.ndarray:
    d0 = np.zeros(model.size)
    h = 1e-7
    cols = []
    for k in range(model.size):
        e = np.zeros(model.size)
        e[k] = h
        cols.append((residuals(model, d0 + e, data) - residuals(model, d0 - e, data)) / (2 * h))
    return np.stack(cols, axis=1)


def _fd_fit(robot: km.Robot, q: np.ndarray, measured: np.ndarray) -> float:
    """The same fit (same identified parameters) with scipy's finite differences."""
    from scipy.optimize import least_squares

    res = calibration.calibrate(robot, q, measured, noise=NOISE)
    model = ErrorModel.of(robot.chain)
    free = res.identification.chosen
    data = Measurements(q, measured, "pose", NOISE)

    def fun(x: np.ndarray) -> np.ndarray:
        d = np.zeros(model.size)
        d[free] = x
        return residuals(model, d, data)

    t0 = time.process_time()
    least_squares(fun, np.zeros(len(free)), method="lm", x_scale="jac", ftol=1e-12,
                  xtol=1e-12, gtol=1e-12)  # fmt: skip
    return time.process_time() - t0


def ours(poses: int) -> None:
    rows = []
    for name in ("puma560", "ur5"):
        robot = km.load(name)
        true = perturbed(robot, 1)
        q = robot.random_q(poses, seed=2)
        measured = calibration.simulate(true, q, NOISE, seed=3)
        run = lambda r=robot, q=q, m=measured: calibration.calibrate(r, q, m, noise=NOISE)  # noqa: E731
        wall = median_of(run, 9)
        fit = best_of(run, 9, clock=time.process_time)  # CPU time: one thread, one core
        model = ErrorModel.of(robot.chain)
        data = Measurements(q, measured, "pose", NOISE)
        analytic = median_of(lambda m=model, d=data: jacobian(m, np.zeros(m.size), d), 15)
        fd = median_of(lambda m=model, d=data: _fd_jacobian(m, d), 5)
        fd_fit = min(_fd_fit(robot, q, measured) for _ in range(3))
        res = calibration.calibrate(robot, q, measured, noise=NOISE)
        rows.append([
            name, str(poses), str(res.rank), fmt_time(fit), fmt_time(wall),
            "met" if fit <= TARGET else f"NOT met ({fit / TARGET:.1f}x)",
            fmt_time(analytic), f"{fd / analytic:.0f}x", f"{fd_fit / fit:.1f}x",
        ])  # fmt: skip
    print(table(rows, ["arm", "poses", "fitted", "calibrate (CPU)", "(wall, median)",
                       "<= 50 ms", "Jacobian", "FD Jacobian", "FD fit"]))  # fmt: skip
    print("  FD Jacobian, FD fit: how many times longer (CPU) with central / scipy's finite")
    print("  differences (the fit: the same identified parameters, scipy's lm)")


def _pybotics_case(poses: int):  # type: ignore[no-untyped-def]
    from pybotics.predefined_models import ur10
    from pybotics.robot import Robot

    mdh = np.array(ur10(), dtype=float)  # alpha, a, theta, d per row (mm, rad)
    rows = [
        km.Revolute(d=d / 1000, a=a / 1000, alpha=alpha, offset=theta) for alpha, a, theta, d in mdh
    ]
    tool = km.transl(0.05, 0.03, 0.1)  # a target off the last axis
    nominal = km.Robot.from_dh(rows, convention="modified", name="UR10 (pybotics)", tool=tool)
    true = perturbed(nominal, 4)
    q = nominal.random_q(poses, seed=5)
    points = calibration.simulate(true, q, NOISE, kind="position", seed=6)
    peer = Robot.from_parameters(mdh.copy())
    peer.tool.position = np.array([50.0, 30.0, 100.0])
    return nominal, true, q, points, peer


def pybotics_peer(poses: int) -> None:
    try:
        from pybotics.optimization import OptimizationHandler, optimize_accuracy
    except ImportError:
        print("  pybotics is not installed (pip install pybotics): peer skipped")
        return
    from scipy.optimize import least_squares

    nominal, true, q, points, peer = _pybotics_case(poses)
    check = nominal.random_q(200, seed=7)
    truth = true.fk(check)[:, :3, 3]

    def run_ours() -> km.Robot:
        return calibration.calibrate(nominal, q, points, "position", noise=NOISE).robot

    def run_peer():  # type: ignore[no-untyped-def]
        handler = OptimizationHandler(
            robot=peer, kinematic_chain_mask=True, tool_mask=[True] * 3 + [False] * 3,
            world_mask=True,
        )  # fmt: skip
        x0 = handler.generate_optimization_vector()
        least_squares(optimize_accuracy, x0, args=(handler, q, points * 1000.0), method="lm")
        return handler.robot

    t_ours = best_of(run_ours, 5, clock=time.process_time)
    t0 = time.process_time()
    fitted = run_peer()
    t_peer = time.process_time() - t0
    ours_rms = np.sqrt(np.mean(np.sum((run_ours().fk(check)[:, :3, 3] - truth) ** 2, axis=1)))
    peer_xyz = np.array([fitted.fk(c)[:3, 3] for c in check]) / 1000.0
    peer_rms = np.sqrt(np.mean(np.sum((peer_xyz - truth) ** 2, axis=1)))
    print(table([
        ["kinematica calibrate", fmt_time(t_ours), f"{ours_rms * 1e6:.1f} µm", "1.0x"],
        ["pybotics optimize_accuracy", fmt_time(t_peer), f"{peer_rms * 1e6:.1f} µm",
         f"{t_peer / t_ours:.0f}x"],
    ], ["UR10, points", "CPU time", "RMS error, 200 new q", "time ratio"]))  # fmt: skip
    print(f"  noise {NOISE[0] * 1e6:.0f} µm per coordinate: an RMS near "
          f"{math.sqrt(3) * NOISE[0] * 1e6:.0f} µm is the noise itself")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=100)
    args = parser.parse_args()
    print(header("kinematica calibration (one core)"))
    ours(args.poses)
    print()
    pybotics_peer(args.poses)


if __name__ == "__main__":
    main()
