"""Forward-kinematics speed: kinematica against plain numpy, Pinocchio and the Robotics Toolbox.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/fk.py``). Prints, for a
6R arm (PUMA 560, standard DH) and a 7R arm (Franka Panda, modified DH, flange
tool), the latency of one ``robot.fk(q)`` call and the throughput on batches of
1e3 and 1e6 configurations, each with its ratio to kinematica measured in the
same run. Baselines:

* plain numpy loop: per configuration, the 4x4 link matrices multiplied with ``@``;
* naive vectorised numpy: per link, a ``(N, 4, 4)`` stack of link matrices and a
  batched ``@``;
* Pinocchio (``import pinocchio``) and the Robotics Toolbox (``roboticstoolbox``:
  ``DHRobot.fkine`` and the compiled ``ETS.eval``), each only when installed;
* ``np.sin`` + ``np.cos`` of the same joint values: a floor for any numpy FK.

Loop baselines on 1e6 configurations are timed on a slice and scaled (said so in
the table). Each row also gives the largest entry difference from kinematica's
result, so a reader sees that the rows compute the same thing. No assertions.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import best_of, fmt_time, header, median_of, per_call, table

from kinematica.dh import Revolute
from kinematica.robot import Robot

DEG = math.pi / 180
#: Batch sizes timed; 1e6 runs take the best of 3, 1e3 runs the median of 15.
SMALL, LARGE = 1_000, 1_000_000
#: Configurations a Python-loop baseline really runs on the large batch (then scaled).
LOOP_SLICE = 10_000


@dataclass(frozen=True)
class Arm:
    """One benchmark arm: DH rows (theta offset, d, a, alpha) and a tool."""

    name: str
    convention: str
    rows: list[tuple[float, float, float, float]]
    tool: np.ndarray

    def robot(self) -> Robot:
        return Robot.from_dh(
            [Revolute(offset=th, d=d, a=a, alpha=al) for th, d, a, al in self.rows],
            convention=self.convention,
            name=self.name,
            tool=self.tool,
        )


def _tz(z: float) -> np.ndarray:
    T = np.eye(4)
    T[2, 3] = z
    return T


PUMA = Arm(
    "PUMA 560 (6R, standard DH)",
    "standard",
    [
        (0, 0, 0, 90 * DEG),
        (0, 0, 0.4318, 0),
        (0, 0.15005, 0.0203, -90 * DEG),
        (0, 0.4318, 0, 90 * DEG),
        (0, 0, 0, -90 * DEG),
        (0, 0, 0, 0),
    ],
    np.eye(4),
)
PANDA = Arm(
    "Franka Panda (7R, modified DH, flange Tz(0.107))",
    "modified",
    [  # theta offset, d, a(i-1), alpha(i-1)
        (0, 0.333, 0, 0),
        (0, 0, 0, -90 * DEG),
        (0, 0.316, 0, 90 * DEG),
        (0, 0, 0.0825, 90 * DEG),
        (0, 0.384, -0.0825, -90 * DEG),
        (0, 0, 0, 90 * DEG),
        (0, 0, 0.088, 90 * DEG),
    ],
    _tz(0.107),
)


# ---------------------------------------------------------------- numpy baselines
def _link(th: float, d: float, a: float, al: float, modified: bool) -> np.ndarray:
    ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
    if modified:
        return np.array(
            [
                [ct, -st, 0, a],
                [st * ca, ct * ca, -sa, -sa * d],
                [st * sa, ct * sa, ca, ca * d],
                [0, 0, 0, 1],
            ]
        )
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, d],
            [0, 0, 0, 1],
        ]
    )


def numpy_loop(arm: Arm, Q: np.ndarray) -> np.ndarray:
    """Per configuration: build every 4x4 link matrix and multiply them with ``@``."""
    modified = arm.convention == "modified"
    out = np.empty((len(Q), 4, 4))
    for k, q in enumerate(Q):
        T = np.eye(4)
        for qi, (th, d, a, al) in zip(q, arm.rows, strict=True):
            T = T @ _link(qi + th, d, a, al, modified)
        out[k] = T @ arm.tool
    return out


def numpy_vectorised(arm: Arm, Q: np.ndarray) -> np.ndarray:
    """Per link: a ``(N, 4, 4)`` stack of link matrices, then one batched ``@``."""
    N = len(Q)
    T = np.broadcast_to(np.eye(4), (N, 4, 4))
    for i, (th, d, a, al) in enumerate(arm.rows):
        theta = Q[:, i] + th
        ct, st = np.cos(theta), np.sin(theta)
        ca, sa = math.cos(al), math.sin(al)
        A = np.zeros((N, 4, 4))
        if arm.convention == "modified":
            A[:, 0, 0], A[:, 0, 1], A[:, 0, 3] = ct, -st, a
            A[:, 1, 0], A[:, 1, 1], A[:, 1, 2], A[:, 1, 3] = st * ca, ct * ca, -sa, -sa * d
            A[:, 2, 0], A[:, 2, 1], A[:, 2, 2], A[:, 2, 3] = st * sa, ct * sa, ca, ca * d
        else:
            A[:, 0, 0], A[:, 0, 1], A[:, 0, 2], A[:, 0, 3] = ct, -st * ca, st * sa, a * ct
            A[:, 1, 0], A[:, 1, 1], A[:, 1, 2], A[:, 1, 3] = st, ct * ca, -ct * sa, a * st
            A[:, 2, 1], A[:, 2, 2], A[:, 2, 3] = sa, ca, d
        A[:, 3, 3] = 1.0
        T = T @ A
    return T @ arm.tool


# ---------------------------------------------------------------- optional peers
PinFK = tuple[str, Callable[[np.ndarray], np.ndarray], Callable[[np.ndarray], np.ndarray]]


def pinocchio_fk(arm: Arm) -> PinFK | str:
    """A Pinocchio model of the arm (RZ joints, constant placements), or why not."""
    try:
        import pinocchio as pin
    except ImportError:
        return "Pinocchio: not installed (pip install pin), skipped"

    def rz(t: float) -> np.ndarray:
        return np.array([[math.cos(t), -math.sin(t), 0], [math.sin(t), math.cos(t), 0], [0, 0, 1]])

    def rx_tx(al: float, a: float) -> np.ndarray:
        c, s = math.cos(al), math.sin(al)
        return np.array([[1, 0, 0, a], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])

    def se3(M: np.ndarray) -> Any:
        return pin.SE3(M[:3, :3].copy(), M[:3, 3].copy())

    # Joint i's placement is whatever constant transform precedes its Rz(q):
    # standard:  T = Π Rz(θi + q) · [Tz(d) Tx(a) Rx(α)]i;
    # modified:  T = Π [Rx(α) Tx(a)]i Rz(θi + q) Tz(di).
    model = pin.Model()
    parent, pending = 0, np.eye(4)
    for k, (th, d, a, al) in enumerate(arm.rows):
        offset = np.eye(4)
        offset[:3, :3] = rz(th)
        if arm.convention == "modified":
            pending = pending @ rx_tx(al, a)
        placement = pending @ offset
        parent = model.addJoint(parent, pin.JointModelRZ(), se3(placement), f"j{k + 1}")
        pending = _tz(d) @ (rx_tx(al, a) if arm.convention == "standard" else np.eye(4))
    frame = model.addFrame(
        pin.Frame("tool", parent, 0, se3(pending @ arm.tool), pin.FrameType.OP_FRAME)
    )
    data = model.createData()

    def one(q: np.ndarray) -> np.ndarray:
        pin.forwardKinematics(model, data, q)
        return pin.updateFramePlacement(model, data, frame).homogeneous

    def many(Q: np.ndarray) -> np.ndarray:
        out = np.empty((len(Q), 4, 4))
        for k, q in enumerate(Q):
            pin.forwardKinematics(model, data, q)
            out[k] = pin.updateFramePlacement(model, data, frame).homogeneous
        return out

    return f"Pinocchio {pin.__version__}", one, many


def rtb_models(arm: Arm) -> tuple[str, Any, Any] | str:
    """(version, DHRobot, ETS) of the arm in the Robotics Toolbox, or why not."""
    try:
        import roboticstoolbox as rtb
        from spatialmath import SE3
    except ImportError:
        return "Robotics Toolbox: not installed (pip install roboticstoolbox-python), skipped"
    link = rtb.RevoluteMDH if arm.convention == "modified" else rtb.RevoluteDH
    robot = rtb.DHRobot(
        [link(d=d, a=a, alpha=al, offset=th) for th, d, a, al in arm.rows],
        tool=SE3(arm.tool, check=False),
    )
    return f"Robotics Toolbox {rtb.__version__}", robot, robot.ets()


# ---------------------------------------------------------------------- running
@dataclass
class Row:
    label: str
    seconds: float  # for the whole batch, or per call
    n: int  # configurations the seconds are for
    diff: float | None  # max |T - T_kinematica|
    note: str = ""


def rows_table(rows: list[Row], ref: float, per_config: bool) -> str:
    out = []
    for r in rows:
        t = r.seconds
        cells = [r.label + (f" [{r.note}]" if r.note else "")]
        if per_config:
            cells += [fmt_time(t), f"{r.n / t / 1e6:.3f}", fmt_time(t / r.n)]
        else:
            cells += [fmt_time(t)]
        cells += [f"{t / ref:.2f}x", "-" if r.diff is None else f"{r.diff:.1e}"]
        out.append(cells)
    head = (
        ["", "time", "Mconfig/s", "per config", "vs kinematica", "max|dT|"]
        if per_config
        else ["", "per call", "vs kinematica", "max|dT|"]
    )
    return table(out, head)


def diff(A: np.ndarray, B: np.ndarray) -> float:
    return float(np.abs(A - B).max())


def bench_arm(arm: Arm, rng: np.random.Generator) -> None:
    robot = arm.robot()
    n = robot.dof
    pin_fk = pinocchio_fk(arm)
    rtb = rtb_models(arm)
    skipped = [m for m in (pin_fk, rtb) if isinstance(m, str)]

    print(f"\n== {arm.name} ==")
    for why in skipped:
        print(f"  ({why})")

    # ------------------------------------------------------------ single call
    q = rng.uniform(-math.pi, math.pi, n)
    ql = q.tolist()
    ref_T = robot.fk(q)
    single: list[Row] = [
        Row("kinematica robot.fk(q), q (n,) ndarray", per_call(lambda: robot.fk(q)), 1, 0.0),
        Row(
            "kinematica robot.fk(q), q list",
            per_call(lambda: robot.fk(ql)),
            1,
            diff(robot.fk(ql), ref_T),
        ),
        Row(
            "plain numpy: n link matrices and @",
            per_call(lambda: numpy_loop(arm, q[None]), calls=5_000),
            1,
            diff(numpy_loop(arm, q[None])[0], ref_T),
        ),
        Row(
            "naive vectorised numpy, batch of 1",
            per_call(lambda: numpy_vectorised(arm, q[None]), calls=5_000),
            1,
            diff(numpy_vectorised(arm, q[None])[0], ref_T),
        ),
    ]
    if not isinstance(pin_fk, str):
        name, one, _ = pin_fk
        single.append(
            Row(
                f"{name} forwardKinematics + frame",
                per_call(lambda: one(q)),
                1,
                diff(one(q), ref_T),
            )
        )
    if not isinstance(rtb, str):
        name, dh, ets = rtb
        single.append(
            Row(f"{name} ETS.eval(q)", per_call(lambda: ets.eval(q)), 1, diff(ets.eval(q), ref_T))
        )
        single.append(
            Row(
                f"{name} DHRobot.fkine(q)",
                per_call(lambda: dh.fkine(q), calls=2_000),
                1,
                diff(dh.fkine(q).A, ref_T),
            )
        )
    print(f"\n  single call (median over ~20,000 calls; {n} joints)")
    print(rows_table(single, single[0].seconds, per_config=False))

    for N in (SMALL, LARGE):
        bench_batch(arm, robot, rng.uniform(-math.pi, math.pi, (N, n)), pin_fk, rtb)


def bench_batch(arm: Arm, robot: Robot, Q: np.ndarray, pin_fk: PinFK | str, rtb: Any) -> None:
    """Throughput on the batch ``Q (N, n)``: best of 3 for 1e6, median of 15 below."""
    N, n = Q.shape
    large = N >= LARGE

    def time_it(f: Callable[[], object]) -> float:
        return best_of(f, 3) if large else median_of(f, 15)

    ref = robot.fk(Q)
    part = Q[:LOOP_SLICE]
    scale = N / len(part)
    loop_note = f"timed on {len(part):,}, scaled" if scale > 1 else ""
    rows = [
        Row("kinematica robot.fk(Q)", time_it(lambda: robot.fk(Q)), N, 0.0),
        Row(
            "naive vectorised numpy (batched 4x4 @)",
            time_it(lambda: numpy_vectorised(arm, Q)),
            N,
            diff(numpy_vectorised(arm, Q), ref),
        ),
        Row(
            "plain numpy loop over configurations",
            best_of(lambda: numpy_loop(arm, part), 1) * scale,
            N,
            diff(numpy_loop(arm, part), ref[:LOOP_SLICE]),
            loop_note,
        ),
    ]
    if not isinstance(pin_fk, str):
        name, _, many = pin_fk
        rows.append(
            Row(
                f"{name} loop",
                best_of(lambda: many(part), 3 if scale > 1 else 1) * scale,
                N,
                diff(many(part), ref[:LOOP_SLICE]),
                loop_note,
            )
        )
    if not isinstance(rtb, str):
        name, dh, ets = rtb
        rows.append(
            Row(f"{name} ETS.eval(Q)", time_it(lambda: ets.eval(Q)), N, diff(ets.eval(Q), ref))
        )
        few = Q[:1_000]
        rows.append(
            Row(
                f"{name} DHRobot.fkine(Q)",
                best_of(lambda: dh.fkine(few), 1) * (N / len(few)),
                N,
                diff(np.array([T.A for T in dh.fkine(few)]), ref[:1_000]),
                "timed on 1,000, scaled" if N > 1_000 else "",
            )
        )
    rows.append(
        Row(
            f"floor: np.sin + np.cos of the {N * n:,} joint values",
            time_it(lambda: (np.sin(Q), np.cos(Q))),
            N,
            None,
        )
    )
    how = "best of 3" if large else "median of 15"
    print(f"\n  batch of {N:,} configurations ({how})")
    print(rows_table(rows, rows[0].seconds, per_config=True))


def main() -> None:
    print(header("kinematica forward-kinematics benchmark"))
    print("'vs kinematica' = time / kinematica's time (above 1: kinematica is faster).")
    wall0, cpu0 = time.perf_counter(), time.process_time()
    rng = np.random.default_rng(0)
    for arm in (PUMA, PANDA):
        bench_arm(arm, rng)
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    print(
        f"\ncores used: CPU time / wall time over the whole run = {cpu:.1f} s / {wall:.1f} s"
        f" = {cpu / wall:.2f}"
    )


if __name__ == "__main__":
    main()
