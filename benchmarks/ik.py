"""Inverse kinematics: closed-form speed and exactness against EAIK, then numeric IK.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/ik.py``; ``--poses``,
``--singles``, ``--seed`` change the sample). For eight 6R arms with a closed
form (PUMA 560, UR5, ABB IRB 120, KUKA KR 6, an arbitrary spherical-wrist
arm whose first three axes are skew, the same arm reversed (a spherical
shoulder: the two families on one geometry), the Panda with q7 = 0.3 (a
spherical shoulder), and the UR5 with a5 = 5 cm: axes 5 and 6
apart, the quartic) it draws random reachable poses (forward
kinematics of configurations uniform within the joint limits, seeded) and
prints:

* time per pose: one pose at a time (median over ``--singles`` poses, each
  call timed on its own; with every default, and with ``respect_limits=False``,
  ``tol=``, ``options=`` and ``q0=``, which cost what the defaults cost: issue 33; each
  pose's shortest of ``SINGLE_PASSES`` passes; ours
  and EAIK's passes in turn, so that both meet the same state of the machine)
  and batched on one thread (one call on all ``--poses`` poses, best of
  ``BATCH_REPEATS``; for ``robot.ik`` and EAIK also the "steady" figure, the shortest
  of ``STEADY_REPEATS`` batches of ``STEADY_POSES``), for the public
  ``robot.ik`` (solve, check by FK, deduplicate, limits) and for the solver
  alone (``params.candidates``: the core's raw candidates of one pose, before
  the check; the core has no batched entry for them);
* where the time of one ``robot.ik`` call goes: the core's check of the
  target, solve and check (``plan.prepared``), building the result
  (``result_of``), and the rest (the keyword test, dispatch) by difference;
* solutions per pose: mean and histogram of counts, within the limits
  (what ``robot.ik`` returns as ``solutions``) and in all (plus
  ``out_of_limits``); the share of poses whose every returned solution our
  own FK puts within 1e-10 m and 1e-10 rad of the target (angle of
  ``R_targetᵀ R``), the worst residual, and the share of poses among whose
  solutions is the configuration that made the pose (modulo 2π).

When ``import eaik`` works (EAIK, C++ subproblem decomposition), the same poses
go to its ``DhRobot.IK`` (one pose) and ``IK_batched`` (one worker thread), and
its answers are judged the same way by our FK: exact ones, least-squares ones
(its ``is_LS`` flag), duplicates modulo 2π, and any exact EAIK solution that
``robot.ik`` does not return (each such pose is printed: that is a bug of ours).

Last, ``benchmarks/ik_numeric.py``'s report (numeric IK on two 7-DOF arms,
success judged by our FK at 1e-10) is run once from here, so that ``make
bench`` prints it too. No assertions.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import (
    best_of,
    fmt_time,
    header,
    shortest_per_item,
    shortest_per_item_together,
    table,
    verdict,
)

import kinematica as km
from kinematica.dh import Revolute, link_matrix
from kinematica.errors import KinematicaWarning
from kinematica.ik import ClosedForm, IKBatchResult, IKOptions, closed_form
from kinematica.ik.analytic.spherical_shoulder import reversed_arm
from kinematica.ik.request import IKRequest
from kinematica.ik.result import result_of
from kinematica.ik.solvers import plan_of
from kinematica.robot import Robot
from kinematica.spatial import inv_transform, rotation_angle, wrap_angle

#: A solution is exact when our FK puts the tool this close to the target (m and rad).
TOL = 1e-10
#: Two solutions closer than this in every joint (rad, modulo 2π) are the same,
#: as ``robot.ik`` deduplicates.
SAME_TOL = 1e-7
#: An EAIK solution is among ours when one of ours is this close in every joint.
MATCH_TOL = 1e-6
#: Most solutions a 6R arm has at a non-singular pose: the histogram's last column.
MAX_COUNT = 8
#: Batched calls timed per arm (ours and EAIK's alike); the shortest counts.
#: A batch takes 10-30 ms: five runs keep a neighbour's burst on this shared
#: machine out of the figure at little cost.
BATCH_REPEATS = 5
#: The steady batched figure: the shortest of this many batches of
#: ``STEADY_POSES`` poses. Bursts of a neighbour last longer than one batch
#: of 500 (1.5 ms) but not than 150 of them: their shortest is what the code
#: costs, and it varies little from run to run.
STEADY_REPEATS, STEADY_POSES = 150, 500
#: Passes over the poses timed one at a time (see :func:`median_per_pose`).
SINGLE_PASSES = 3
#: Issue 19's targets: robot.ik (checked) over EAIK (unchecked), one pose and batched.
TARGET_SINGLE_VS_EAIK, TARGET_BATCHED_VS_EAIK = 1.0, 0.5
#: Poses described, per arm and kind, where EAIK's exact solutions and ours differ.
SHOW_POSES = 3

GENERAL_ROWS = [  # theta offset, d, a, alpha: 'general-spherical-wrist' of ik_reference.json
    (0.0, 0.3, 0.12, 1.1),
    (0.0, 0.1, 0.45, -0.7),
    (0.0, -0.15, -0.08, 2.0),
    (0.0, 0.35, 0.0, math.pi / 2),
    (0.0, 0.0, 0.0, -math.pi / 2),
    (0.0, 0.1, 0.0, 0.0),
]


def shoulder_arms(general: Robot) -> list[Robot]:
    """Two spherical-shoulder arms: ``general`` reversed, and the Panda with q7 = 0.3.

    The reversed arm (the modified DH table of ``fk(q)⁻¹``, see
    :func:`kinematica.ik.analytic.spherical_shoulder.reversed_arm`) has the
    spherical-wrist arm's geometry exactly: the two families' figures compare
    like with like. The Panda's joint 7 at 0.3 rad goes into the tool (its row:
    a6 = 0.088, α6 = 90°, d7 = 0); joints 1-6 keep their limits.
    """
    rows, base, tool = reversed_arm(list(general.links), general.base, general.tool)
    reversed_general = Robot.from_dh(
        rows, convention="modified", base=base, tool=tool, name="general spherical wrist, reversed"
    )
    panda = km.load("panda")
    last, q7 = panda.links[6], 0.3
    joint7 = link_matrix(q7 + last.offset, last.d, last.a, last.alpha, "modified")
    panda6 = Robot.from_dh(
        panda.links[:6],
        convention="modified",
        base=panda.base,
        tool=joint7 @ panda.tool,
        name="Panda, q7 = 0.3 (spherical shoulder)",
    )
    return [reversed_general, panda6]


def arms() -> list[Robot]:
    general = Robot.from_dh(
        [Revolute(offset=th, d=d, a=a, alpha=al) for th, d, a, al in GENERAL_ROWS],
        name="general spherical wrist",
        convention="standard",
    )
    ur5 = km.load("ur5")
    rows = list(ur5.links)
    rows[4] = Revolute(d=rows[4].d, a=0.05, alpha=rows[4].alpha, offset=rows[4].offset)
    ur5_a5 = Robot.from_dh(
        rows, name="UR5, a5 = 5 cm", base=ur5.base, tool=ur5.tool, convention="standard"
    )
    ur5_a5 = ur5_a5.with_limits(ur5.qlim)
    return [
        *(km.load(name) for name in ("puma560", "ur5", "irb120", "kr6")),
        general,
        *shoulder_arms(general),
        ur5_a5,
    ]


#: The settings timed beside the defaults' one pose (issue 33: each costs what they cost).
OPTIONS = IKOptions(tol=(1e-10, 1e-10), respect_limits=True)


def option_calls(robot: Robot) -> list[tuple[str, Callable[[np.ndarray], object]]]:
    """``robot.ik`` of one pose with a setting given: its label and the call."""
    with np.errstate(invalid="ignore"):  # no limits: -inf + inf
        q0 = np.nan_to_num(robot.chain.qlim.mean(axis=1))  # the middle of the limits
    return [
        ("q0=", lambda t: robot.ik(t, q0=q0)),
        ("respect_limits=False", lambda t: robot.ik(t, respect_limits=False)),
        ("tol=1e-9", lambda t: robot.ik(t, tol=1e-9)),
        ("options=IKOptions(...)", lambda t: robot.ik(t, options=OPTIONS)),
    ]


def raw(closed: ClosedForm, robot: Robot, T: np.ndarray) -> np.ndarray:
    """The closed form's candidates ``(N, m, n)`` for poses ``T (N, 4, 4)``, before the check."""
    core = robot.chain.core
    return np.array([closed.params.candidates(core, t)[0] for t in T])


def parts(closed: ClosedForm, robot: Robot, poses: np.ndarray) -> list[float]:
    """Seconds of one ``robot.ik`` call and of its parts (median over ``poses``)."""
    core = robot.chain.core
    plan = plan_of(robot.chain, "pose", IKRequest.parse())  # what robot.ik(T) runs
    labels, method, opts = closed.labels, closed.method, plan.options
    out = [closed.params.ik(core, t, opts, None, labels) for t in poses]
    by_id = {id(t): o for t, o in zip(poses, out, strict=True)}
    times = [
        shortest_per_item(f, poses, SINGLE_PASSES)
        for f in (
            robot.ik,
            plan.prepared,
            lambda t: closed.params.candidates(core, t),
            lambda t: closed.params.ik(core, t, opts, None, labels),
            lambda t: result_of(by_id[id(t)], method, True, ()),
        )
    ]
    return [*times, times[0] - times[1]]


# ---------------------------------------------------------------------- judging
def residuals(robot: Robot, q: np.ndarray, T: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position (m), rotation (rad) errors ``(N, m)`` of ``q (N, m, n)`` vs ``T (N, 4, 4)``.

    NaN rows of ``q`` (no solution in that slot) get ``inf``.
    """
    N, m, n = q.shape
    real = np.all(np.isfinite(q), axis=-1)
    with warnings.catch_warnings():  # solutions outside the limits are judged too
        warnings.simplefilter("ignore", KinematicaWarning)
        F = robot.fk(np.where(real[..., None], q, 0.0).reshape(-1, n)).reshape(N, m, 4, 4)
    pos = np.linalg.norm(F[..., :3, 3] - T[:, None, :3, 3], axis=-1)
    rot = rotation_angle(F[..., :3, :3], np.broadcast_to(T[:, None, :3, :3], F[..., :3, :3].shape))
    return np.where(real, pos, np.inf), np.where(real, rot, np.inf)


def same_joints(a: np.ndarray, b: np.ndarray, tol: float) -> np.ndarray:
    """``(N, ma, mb)`` True where ``a (N, ma, n)`` and ``b (N, mb, n)`` agree modulo 2π."""
    d = wrap_angle(a[:, :, None, :] - b[:, None, :, :])
    return np.all(np.abs(d) < tol, axis=-1)


def repeats_earlier(q: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """``(N, m)`` True where a kept slot of ``q (N, m, n)`` repeats an earlier kept slot."""
    m = q.shape[1]
    earlier = np.tril(np.ones((m, m), dtype=bool), k=-1)
    return keep & np.any(same_joints(q, q, SAME_TOL) & earlier & keep[:, None, :], axis=-1)


def histogram(counts: np.ndarray) -> list[str]:
    """Poses with 0, 1, ..., MAX_COUNT solutions (the last column: that many or more)."""
    h = np.bincount(np.minimum(counts, MAX_COUNT), minlength=MAX_COUNT + 1)
    return [f"{v:,}" if v else "." for v in h]


def pad(rows: list[np.ndarray], n: int) -> np.ndarray:
    """Stack ``(k_i, n)`` arrays into ``(N, max k, n)``, NaN-padded."""
    m = max([len(r) for r in rows] + [1])
    out = np.full((len(rows), m, n), np.nan)
    for i, r in enumerate(rows):
        out[i, : len(r)] = r
    return out


@dataclass
class Judged:
    """What our FK says of the solutions a solver returned for N poses."""

    label: str
    count: np.ndarray  # (N,) solutions counted
    all_exact: float  # share of poses whose every returned solution is exact
    worst: tuple[float, float]  # largest position (m) and rotation (rad) residual
    found: float | None  # share of poses whose generating q is among the solutions

    def row(self) -> list[str]:
        worst = (
            "-" if not np.isfinite(self.worst[0]) else f"{self.worst[0]:.0e} / {self.worst[1]:.0e}"
        )
        return [
            self.label,
            f"{self.count.mean():.2f}",
            *histogram(self.count),
            f"{100 * self.all_exact:.2f} %",
            worst,
            "-" if self.found is None else f"{100 * self.found:.2f} %",
        ]


def judge(
    label: str, robot: Robot, q: np.ndarray, T: np.ndarray, q_gen: np.ndarray | None
) -> Judged:
    """Judge solutions ``q (N, m, n)`` (NaN-padded) of ``T (N, 4, 4)`` by our FK."""
    real = np.all(np.isfinite(q), axis=-1)
    pos, rot = residuals(robot, q, T)
    exact = real & (pos <= TOL) & (rot <= TOL)
    worst = (float(pos[real].max()), float(rot[real].max())) if real.any() else (math.inf, math.inf)
    found = None
    if q_gen is not None:
        found = float(np.any(same_joints(q, q_gen[:, None, :], MATCH_TOL)[:, :, 0], axis=1).mean())
    return Judged(
        label, real.sum(axis=1), float(np.all(exact | ~real, axis=1).mean()), worst, found
    )


def every_solution(res: IKBatchResult) -> np.ndarray:
    """``(N, k, n)``: the solutions within the limits, then those outside them."""
    return np.concatenate([res.solutions, res.out_of_limits], axis=1)


# ------------------------------------------------------------------------- EAIK
@dataclass
class Eaik:
    """EAIK's model of a robot, and how to turn poses and answers into ours."""

    version: str
    model: Any
    offsets: np.ndarray  # (n,) DH theta offsets, not part of EAIK's DH
    base_inv: np.ndarray
    tool_inv: np.ndarray

    def poses(self, T: np.ndarray) -> np.ndarray:
        """Our targets ``(N, 4, 4)`` in EAIK's frames (no base, no tool)."""
        return self.base_inv @ T @ self.tool_inv

    def joints(self, theta: np.ndarray) -> np.ndarray:
        """EAIK's joint angles (DH theta) as our joint values, wrapped."""
        return wrap_angle(theta - self.offsets)


def eaik_version() -> str | None:
    """``"EAIK x.y.z"`` if EAIK imports, else None."""
    try:
        import eaik.IK_DH  # noqa: F401
    except ImportError:
        return None
    from importlib.metadata import version

    return f"EAIK {version('eaik')}"


def eaik_model(robot: Robot, name: str) -> Eaik | str:
    """EAIK's ``DhRobot`` of the arm, or why there is none."""
    from eaik.IK_DH import DhRobot

    if robot.convention != "standard" or robot.is_prismatic.any():
        return f"EAIK: {robot.name} is not a standard-DH all-revolute arm, skipped"
    L = robot.links
    model = DhRobot(
        np.array([j.alpha for j in L]), np.array([j.a for j in L]), np.array([j.d for j in L])
    )
    if not model.hasKnownDecomposition():
        return f"EAIK: no decomposition known for {robot.name}, skipped"
    e = Eaik(
        name,
        model,
        np.array([j.offset for j in L]),
        inv_transform(robot.base),
        inv_transform(robot.tool),
    )
    q = np.random.default_rng(1).uniform(*robot.qlim.T, size=(5, robot.dof))
    gap = max(
        np.abs(robot.base @ model.fwdKin(qi + e.offsets) @ robot.tool - robot.fk(qi)).max()
        for qi in q
    )
    if gap > 1e-12:
        return f"EAIK: its FK of {robot.name} differs from ours by {gap:.1e}, skipped"
    return e


# ---------------------------------------------------------------------- timing
@dataclass
class Report:
    """Everything measured on one arm."""

    arm: str
    times: list[tuple[str, float, float]]  # (call, single s, batched s per pose)
    judged: list[Judged]
    eaik: list[str] | None = None  # a row of the EAIK table
    notes: list[str] = field(default_factory=list)
    steady: float = math.nan  # robot.ik batched, s per pose: shortest of many small batches
    eaik_steady: float = math.nan  # the same for EAIK's IK_batched
    parts: list[float] = field(default_factory=list)  # see parts()


def bench_arm(robot: Robot, n_poses: int, n_singles: int, seed: int, eaik: str | None) -> Report:
    """Time and judge kinematica, and EAIK (``eaik``: its name) unless None, on one arm."""
    solver = closed_form(robot.chain, "pose")
    if solver is None:
        raise SystemExit(f"{robot.name}: no closed-form solver, nothing to benchmark")
    lo, hi = robot.qlim.T
    q_gen = np.random.default_rng(seed).uniform(lo, hi, (n_poses, robot.dof))
    T = robot.fk(q_gen)
    few = list(T[:n_singles])
    core = robot.chain.core
    e = None if eaik is None else eaik_model(robot, eaik)
    # one pose at a time, with every default and with each kind of setting (issue 33: the
    # same cost), ours and EAIK's passes in turn
    calls = [(robot.ik, few), *((call, few) for _, call in option_calls(robot))]
    if isinstance(e, Eaik):
        *mine, e_single = shortest_per_item_together(
            [*calls, (e.model.IK, list(e.poses(T[:n_singles])))], SINGLE_PASSES
        )
    else:
        mine, e_single = shortest_per_item_together(calls, SINGLE_PASSES), math.nan
    single, with_options = mine[0], mine[1:]

    rep = Report(
        robot.name,
        [
            (
                "kinematica robot.ik",
                single,
                best_of(lambda: robot.ik(T, workers=1), BATCH_REPEATS) / n_poses,
            ),
            *(
                (f"kinematica robot.ik(T, {label})", t, math.nan)
                for (label, _), t in zip(option_calls(robot), with_options, strict=True)
            ),
            (
                f"kinematica solver alone (params.candidates, {solver.name})",
                shortest_per_item(lambda t: solver.params.candidates(core, t), few, SINGLE_PASSES),
                math.nan,
            ),
        ],
        [],
    )
    rep.parts = parts(solver, robot, few[: max(1, n_singles // 4)])
    part = T[:STEADY_POSES]
    rep.steady = best_of(lambda: robot.ik(part, workers=1), STEADY_REPEATS) / len(part)
    res = robot.ik(T, workers=1)
    if not isinstance(res, IKBatchResult):
        raise TypeError(f"robot.ik of a batch gave {type(res).__name__}")
    ours = every_solution(res)
    rep.judged += [
        judge("robot.ik: solutions (within limits)", robot, res.solutions, T, q_gen),
        judge("robot.ik: + out_of_limits", robot, ours, T, q_gen),
        judge("solver alone: real candidates (raw)", robot, raw(solver, robot, T), T, q_gen),
    ]
    statuses = dict(zip(*np.unique(res.status, return_counts=True), strict=True))
    if set(statuses) != {"ok"}:
        rep.notes.append(
            "robot.ik statuses: " + ", ".join(f"{k} {v:,}" for k, v in statuses.items())
        )

    if isinstance(e, str):
        rep.notes.append(e)
    elif e is not None:
        bench_eaik(rep, robot, e, T, q_gen, ours, e_single)
    return rep


def bench_eaik(
    rep: Report,
    robot: Robot,
    e: Eaik,
    T: np.ndarray,
    q_gen: np.ndarray,
    ours: np.ndarray,
    single: float,
) -> None:
    """Time EAIK on the poses ``T`` and judge its answers against ``ours`` (every solution).

    ``single``: its one-pose time, taken beside ours (:func:`bench_arm`).
    """
    n_poses = len(T)
    Te = e.poses(T)  # converted outside the timed calls
    pose_list = list(Te)
    rep.times.append(
        (
            f"{e.version} IK / IK_batched (1 thread)",
            single,
            best_of(lambda: e.model.IK_batched(pose_list, 1), BATCH_REPEATS) / n_poses,
        )
    )
    part = pose_list[:STEADY_POSES]
    steady = best_of(lambda: e.model.IK_batched(part, 1), STEADY_REPEATS)
    rep.eaik_steady = steady / len(part)
    sols = e.model.IK_batched(pose_list, 1)
    qe = pad([e.joints(np.asarray(s.Q).reshape(-1, robot.dof)) for s in sols], robot.dof)
    ls = pad([np.asarray(s.is_LS, dtype=float).reshape(-1, 1) for s in sols], 1)[..., 0] == 1
    real = np.all(np.isfinite(qe), axis=-1)
    pos, rot = residuals(robot, qe, T)
    exact = real & (pos <= TOL) & (rot <= TOL)
    # The exact answers alone (at most a few per pose, where EAIK may give 30 answers).
    qx = pad([qe[i][exact[i]] for i in range(n_poses)], robot.dof)
    dup = repeats_earlier(qx, np.all(np.isfinite(qx), axis=-1))
    distinct = np.where(dup[..., None], np.nan, qx)
    rep.judged += [
        judge(f"{e.version}: every answer", robot, qe, T, q_gen),
        judge(f"{e.version}: exact, distinct", robot, distinct, T, q_gen),
    ]

    # Set against set, modulo 2π: EAIK's exact solutions we lack (our bug), and
    # ours without an exact EAIK twin (EAIK's miss, or an answer of it just above 1e-10).
    ours_real = np.all(np.isfinite(ours), axis=-1)
    distinct_real = np.all(np.isfinite(distinct), axis=-1)
    missed = distinct_real & ~np.any(same_joints(distinct, ours, MATCH_TOL), axis=-1)
    extra = ours_real & ~np.any(same_joints(ours, qx, MATCH_TOL), axis=-1)

    def count(mask: np.ndarray) -> str:
        return f"{int(mask.sum()):,} / {int(mask.any(axis=1).sum()):,}"

    rep.eaik = [
        robot.name,
        f"{real.sum(axis=1).mean():.2f}",
        f"{int(real.sum()):,}",
        f"{int(exact.sum()):,}",
        f"{int(dup.sum()):,}",
        f"{int((real & ls).sum()):,}",
        f"{int((exact & ls).sum()):,}",
        f"{int((real & ~ls & ~exact).sum()):,}",
        count(missed),
        count(extra),
    ]
    for i in np.flatnonzero(missed.any(axis=1))[:SHOW_POSES]:
        rep.notes.append(
            f"BUG: pose {i} has exact EAIK solutions robot.ik does not return: "
            f"{distinct[i][missed[i]].tolist()}\n    q that made it {q_gen[i].tolist()}\n"
            f"    T = {T[i].tolist()}\n    robot.ik: {ours[i][ours_real[i]].tolist()}"
        )
    for i in np.flatnonzero(extra.any(axis=1))[:SHOW_POSES]:
        for q in ours[i][extra[i]]:
            near = np.abs(wrap_angle(qe[i] - q)).max(axis=-1)
            k = int(np.nanargmin(near))
            rep.notes.append(
                f"pose {i}: robot.ik's {np.round(q, 6).tolist()} has no exact EAIK twin; EAIK's "
                f"nearest answer is {near[k]:.0e} rad away, its residual {pos[i, k]:.1e} m / "
                f"{rot[i, k]:.1e} rad (is_LS {bool(ls[i, k])})"
            )


# ------------------------------------------------------------------------ main
def grouped(reports: list[Report], rows_of: Callable[[Report], list[list[str]]]) -> list[list[str]]:
    """One heading row per arm, then its rows indented."""
    out = []
    for rep in reports:
        rows = rows_of(rep)
        out.append([rep.arm] + [""] * (len(rows[0]) - 1))
        out += [["  " + r[0], *r[1:]] for r in rows]
    return out


def time_rows(rep: Report) -> list[list[str]]:
    ref = next((t for t in rep.times if t[0].startswith("EAIK")), None)

    def vs(t: float, r: float | None) -> str:
        return "-" if r is None or math.isnan(t) else f"{t / r:.2f}x"

    return [
        [
            call,
            fmt_time(single),
            "-" if math.isnan(batched) else fmt_time(batched),
            vs(single, ref and ref[1]),
            vs(batched, ref and ref[2]),
        ]
        for call, single, batched in rep.times
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=10_000, help="poses per arm (10,000)")
    parser.add_argument("--singles", type=int, default=1_000, help="poses timed one by one (1,000)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the poses (0)")
    args = parser.parse_args()

    print(header("kinematica inverse-kinematics benchmark"))
    wall0, cpu0 = time.perf_counter(), time.process_time()
    print(
        f"Closed form: {args.poses:,} random reachable poses per arm (FK of q uniform within the "
        f"limits, seed {args.seed}).\nsingle = median over {args.singles:,} poses, each call "
        f"timed on its own (each pose's shortest of {SINGLE_PASSES} passes); batched = one call "
        f"on all {args.poses:,} (best of {BATCH_REPEATS}), per pose."
    )
    eaik = eaik_version()
    if eaik is None:
        print("EAIK is not importable (pip install eaik): its rows are skipped.")
    reports = [bench_arm(robot, args.poses, args.singles, args.seed, eaik) for robot in arms()]

    head = ["", "single", "batched/pose"]
    if eaik is None:
        print("\n  time per pose")
        rows = [r[:3] for r in grouped(reports, time_rows)]
    else:
        print("\n  time per pose ('vs EAIK' = time / EAIK's time: above 1, EAIK is faster)")
        head += ["single vs EAIK", "batched vs EAIK"]
        rows = grouped(reports, time_rows)
    print(table(rows, head))

    print(
        f"\n  solutions per pose: mean and histogram of counts (poses with 0, 1, ... {MAX_COUNT}+);"
        f" 'all exact' = poses whose every solution our FK\n  puts within {TOL:g} m and "
        f"{TOL:g} rad of the target; worst residual (m / rad); 'q found' = poses among whose "
        "solutions\n  is the q that made the pose (modulo 2π)"
    )
    counts = [*(str(k) for k in range(MAX_COUNT)), f"{MAX_COUNT}+"]
    head = ["", "mean", *counts, "all exact", "worst", "q found"]
    print(table(grouped(reports, lambda r: [j.row() for j in r.judged]), head))

    eaik_rows = [r.eaik for r in reports if r.eaik is not None]
    if eaik_rows:
        print(
            "\n  EAIK's answers judged by our FK at 1e-10: duplicates = exact answers repeating "
            "another modulo 2π; is_LS = flagged\n  least-squares (approximate); 'EAIK exact, not "
            "in robot.ik' and 'robot.ik, no exact EAIK twin' count solutions / poses"
        )
        head = [
            "",
            "per pose",
            "answers",
            "exact",
            "duplicates",
            "is_LS",
            "is_LS exact",
            "unflagged inexact",
            "EAIK exact, not in robot.ik",
            "robot.ik, no exact EAIK twin",
        ]
        print(table(eaik_rows, head))

    notes = [f"  {r.arm}: {n}" for r in reports for n in r.notes]
    if notes:
        print("\n" + "\n".join(dict.fromkeys(notes)))

    print(
        "\n  where one robot.ik call's time goes (median over a quarter of the single poses): "
        "the plan's one core call\n  (plan.prepared: reading the target, solve, check and the "
        "result; of it the solver alone, params.candidates),\n  the same as two calls (the "
        "core's Answer, params.ik, then result_of), the rest (settings, dispatch) by "
        "difference"
    )
    head = ["", "robot.ik", "core call", "of it: solver", "params.ik", "result_of", "rest"]
    print(table([[r.arm, *(fmt_time(t) for t in r.parts)] for r in reports], head))

    print(
        f"\n  issue 19 targets: robot.ik (checked) one pose <= {TARGET_SINGLE_VS_EAIK:g}x EAIK's "
        f"(unchecked) one pose, batched <= {TARGET_BATCHED_VS_EAIK:g}x EAIK's\n  per pose "
        f"(steady = shortest of {STEADY_REPEATS} batches of {STEADY_POSES} poses; the batched "
        "ratio takes the shorter figure of each)"
    )
    rows = []
    for r in reports:
        e = next((t for t in r.times if t[0].startswith("EAIK")), None)
        _, single, batched = r.times[0]
        if e is None:
            rows.append([r.arm, fmt_time(single), "-", "", fmt_time(batched), "-", "", "(no EAIK)"])
            continue
        one, many = single / e[1], min(batched, r.steady) / min(e[2], r.eaik_steady)
        rows.append(
            [
                r.arm,
                fmt_time(single),
                f"{one:.2f}x",
                verdict(one <= TARGET_SINGLE_VS_EAIK, f"{one / TARGET_SINGLE_VS_EAIK:.2f}x"),
                f"{fmt_time(batched)} ({fmt_time(r.steady)})",
                f"{fmt_time(e[2])} ({fmt_time(r.eaik_steady)})",
                f"{many:.2f}x",
                verdict(many <= TARGET_BATCHED_VS_EAIK, f"{many / TARGET_BATCHED_VS_EAIK:.2f}x"),
            ]
        )
    head = ["", "single", "vs EAIK", "", "batched (steady)", "EAIK's", "vs EAIK", ""]
    print(table(rows, head))

    print(
        "\n  issue 33 target: one pose with any setting (q0=, respect_limits=False, tol=, "
        "options=) <= EAIK's one pose, same run"
    )
    rows = []
    for r in reports:
        e = next((t for t in r.times if t[0].startswith("EAIK")), None)
        given = [t for t in r.times if t[0].startswith("kinematica robot.ik(T, ")]
        worst = max(given, key=lambda t: t[1])
        if e is None:
            rows.append([r.arm, fmt_time(r.times[0][1]), fmt_time(worst[1]), "-", "-", "(no EAIK)"])
            continue
        ratio = worst[1] / e[1]
        rows.append(
            [
                r.arm,
                fmt_time(r.times[0][1]),
                f"{fmt_time(worst[1])} ({worst[0].removeprefix('kinematica robot.ik(T, ')[:-1]})",
                fmt_time(e[1]),
                f"{ratio:.2f}x",
                verdict(ratio <= TARGET_SINGLE_VS_EAIK, f"{ratio:.2f}x"),
            ]
        )
    head = ["", "defaults", "slowest setting", "EAIK", "vs EAIK", ""]
    print(table(rows, head))

    print("\nNumeric IK: benchmarks/ik_numeric.py, run from here.\n")
    try:
        import ik_numeric
    except ImportError as exc:  # the report needs what its own script imports
        print(f"benchmarks/ik_numeric.py does not import ({exc}): skipped")
    else:
        argv = sys.argv
        sys.argv = [ik_numeric.__file__]  # its own defaults, not our options
        try:
            ik_numeric.main()
        finally:
            sys.argv = argv

    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    print(
        f"\ncores used: CPU time / wall time over the whole run = {cpu:.1f} s / {wall:.1f} s"
        f" = {cpu / wall:.2f}"
    )


if __name__ == "__main__":
    main()
