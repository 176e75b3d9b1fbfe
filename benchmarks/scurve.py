"""Jerk-limited moves: speed against ruckig's own ``calculate``, and a 10,000-case audit.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/scurve.py [--cases N]``).

* Speed, 7 joints, random states: ruckig's ``calculate`` alone (its Python
  objects made once), our segment planner (the same call, with the lists set
  and ruckig's input check), ruckig's calculate with its own ``at_time``
  every 10 ms, the whole ``joint_trajectory(profile="scurve")`` (limits
  checked, ruckig's plan, then the exact pieces, the settled ends and the
  samples every 10 ms, jerk included, by one call of the core); the core's own
  segment at zero accelerations (``jerk.hpp``) beside ruckig on the same
  states; and through waypoints: the core's search of the waypoint velocities
  alone per segment (the default search, none of each joint's own speed, two
  sweeps of it, and golden sections of 7 and 6 points instead of 8: the cheaper
  settings' speed beside what they give up), and the whole
  ``via_trajectory(W, "scurve")`` per segment (search, exact pieces and samples
  every 10 ms, all in the core) against the search alone; both again with
  position limits 0-2 cm outside the waypoints. Last, the cheaper settings
  against the default on 300 random paths: each path's duration change; and the
  default against its durations before issue 36's speed-up (commit a2640cd, stored in
  ``data/scurve_via_main.txt``).
* Audit on ``--cases`` random cases (10,000 by default), 1 to 7 joints:
  rest-to-rest durations against the hand-derived closed form
  (``tests/support/scurve_reference.py``; the slowest joint's time), and from
  random start and target states: the end state, the limits on a 1 ms
  resampling, the time-optimal structure of some joint (every phase at a
  limit), and the synchronisation one joint at a time (each joint planned
  alone to last at least ``T`` takes exactly ``T``; to last ``T - 1e-6`` s,
  some joint cannot). Counts of failures, and the largest errors. Then the
  core's segments at zero accelerations (``jerk.hpp``) against ruckig on
  ``--cases`` random cases: durations, end states and limits.

No assertions: figures only.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
sys.path.insert(0, str(Path(__file__).parents[1] / "tests"))

import ruckig
from _common import fmt_time, header, per_call, table
from support.scurve_reference import (
    random_limits,
    random_state,
    rest_to_rest_time,
    retimed_durations,
)

from kinematica.core.jerk import jerk_segments, jerk_via
from kinematica.motion import joint_trajectory, via_trajectory
from kinematica.motion.scurve import JerkTrajectory, Segment
from kinematica.motion.scurve_via import GOLDEN_STEPS, JOINT_SWEEPS, POSITION_ATOL, SWEEPS
from kinematica.motion.trajectory import LIMIT_RTOL


def _saturated(traj: JerkTrajectory, joint: int, tol: float = 1e-7) -> bool:
    """Every phase of ``joint`` at a limit: |j| = J, or j = 0 at |a| = A or at |v| = V, a = 0."""
    p = traj.pieces
    J, A, V = traj.jmax[joint], traj.amax[joint], traj.vmax[joint]
    for i in range(p.coef.shape[0]):
        if p.breaks[i + 1] - p.breaks[i] <= 1e-9 * max(traj.duration, 1.0):
            continue
        j, a, v = 6.0 * p.coef[i, 3, joint], 2.0 * p.coef[i, 2, joint], p.coef[i, 1, joint]
        if abs(abs(j) - J) <= tol * J:
            continue
        at_a = abs(abs(a) - A) <= tol * A
        at_v = abs(a) <= tol * A and abs(abs(v) - V) <= tol * V
        if abs(j) <= tol * J and (at_a or at_v):
            continue
        return False
    return True


def audit(cases: int) -> list[tuple[str, str, str]]:
    rng = np.random.default_rng(36)
    worst_rest = 0.0
    bad_rest = 0
    worst_end = 0.0
    worst_limit = 0.0
    not_extremal = 0
    not_synced = 0
    shorter_feasible = 0
    for c in range(cases):
        n = 1 if c % 4 == 0 else int(rng.integers(2, 8))
        V, A, J = random_limits(rng, n)
        q0, q1 = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
        rest = joint_trajectory(q0, q1, profile="scurve", dt=0.1, vmax=V, amax=A, jmax=J)
        want = max(rest_to_rest_time(d, *lim) for d, *lim in zip(q1 - q0, V, A, J, strict=True))
        err = abs(rest.duration - want)
        worst_rest = max(worst_rest, err)
        bad_rest += err > 1e-6
        v0, a0 = random_state(rng, V, A, J)
        v1, a1 = random_state(rng, V, A, J, target=True)
        traj = joint_trajectory(
            q0, q1, profile="scurve", dt=0.1, vmax=V, amax=A, jmax=J,
            qd0=v0, qdd0=a0, qd1=v1, qdd1=a1,
        )  # fmt: skip
        T, p = traj.duration, traj.pieces
        for order, goal in enumerate((q1, v1, a1)):
            worst_end = max(worst_end, float(np.abs(p(T, order, left=True)[0] - goal).max()))
        t = np.union1d(np.arange(0.0, T, 1e-3), [T])
        for order, lim in ((1, V), (2, A), (3, J)):
            worst_limit = max(worst_limit, float((np.abs(p(t, order)) / lim).max()) - 1.0)
        not_extremal += not any(_saturated(traj, j) for j in range(n))
        states = (q0, v0, a0, q1, v1, a1)
        at_T = retimed_durations(*states, (V, A, J), T)
        not_synced += bool(np.abs(at_T - T).max() > 1e-9)
        shorter = retimed_durations(*states, (V, A, J), T - 1e-6)
        shorter_feasible += not np.any(shorter > T - 1e-6 + 1e-9)
    return [
        (
            f"rest to rest, {cases} cases: duration vs closed form",
            f"largest error {worst_rest:.2e} s",
            f"{bad_rest} beyond 1e-6 s",
        ),
        (
            f"any state to any state, {cases} cases: end state",
            f"largest error {worst_end:.2e}",
            f"{'within' if worst_end <= 1e-10 else 'BEYOND'} 1e-10",
        ),
        (
            "  limits on a 1 ms resampling",
            f"largest excess {worst_limit:+.2e} (relative)",
            f"{'within' if worst_limit <= LIMIT_RTOL else 'BEYOND'} {LIMIT_RTOL:g}",
        ),
        ("  some joint with every phase at a limit", f"{cases - not_extremal} of {cases}", ""),
        ("  every joint alone can take T", f"{cases - not_synced} of {cases}", ""),
        ("  some joint alone cannot take T - 1e-6 s", f"{cases - shorter_feasible} of {cases}", ""),
    ]


def _walk(p: float, v: float, t: np.ndarray, j: np.ndarray) -> tuple[float, ...]:
    """End p, v, a of a joint's phases from (p, v, 0); the largest |v|, |a| on the way."""
    a, vmax, amax = 0.0, abs(v), 0.0
    for h, jk in zip(t, j, strict=True):
        if jk != 0.0 and 0.0 < -a / jk < h:
            tau = -a / jk
            vmax = max(vmax, abs(v + a * tau + jk * tau * tau / 2.0))
        p, v, a = p + h * (v + h * (a / 2.0 + h * jk / 6.0)), v + h * (a + h * jk / 2.0), a + h * jk
        vmax, amax = max(vmax, abs(v)), max(amax, abs(a))
    return p, v, a, vmax, amax


def audit_core(cases: int) -> list[tuple[str, str, str]]:
    """The core's zero-acceleration segments (jerk.hpp) against ruckig, 1 to 7 joints."""
    rng = np.random.default_rng(3636)
    worst_t = worst_end = worst_lim = 0.0
    bad = 0
    for c in range(cases):
        n = 1 if c % 4 == 0 else int(rng.integers(2, 8))
        V, A, J = random_limits(rng, n)
        kind = rng.integers(0, 4, (2, n))
        v0, v1 = (
            np.select([k == 0, k == 1, k == 2], [np.zeros(n), V, -V], rng.uniform(-1, 1, n) * V)
            for k in kind
        )
        p0 = rng.uniform(-2, 2, n)
        p1 = p0 + rng.uniform(-1, 1, n) * (2.0, 0.05, 1e-4, 10.0)[c % 4]
        seg = jerk_segments(p0[None], v0[None], p1[None], v1[None], (V, A, J))
        T = float(seg.duration[0])
        otg, inp, out = ruckig.Ruckig(n), ruckig.InputParameter(n), ruckig.Trajectory(n)
        inp.current_position, inp.current_velocity = p0.tolist(), v0.tolist()
        inp.target_position, inp.target_velocity = p1.tolist(), v1.tolist()
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = V.tolist(), A.tolist(), J.tolist()
        otg.calculate(inp, out)
        err = abs(T - out.duration)
        worst_t = max(worst_t, err)
        bad += err > 1e-6
        for i in range(n):
            k = int(seg.phases[0, i])
            p, v, a, vm, am = _walk(p0[i], v0[i], seg.t[0, i, :k], seg.j[0, i, :k])
            worst_end = max(worst_end, abs(p - p1[i]), abs(v - v1[i]), abs(a))
            jm = float(np.abs(seg.j[0, i, :k]).max(initial=0.0))
            worst_lim = max(worst_lim, vm / V[i] - 1.0, am / A[i] - 1.0, jm / J[i] - 1.0)
    return [
        (
            f"the core's segments (zero accelerations), {cases} cases: duration vs ruckig",
            f"largest difference {worst_t:.2e} s",
            f"{bad} beyond 1e-6 s",
        ),
        (
            "  end state (integrated phases)",
            f"largest error {worst_end:.2e}",
            f"{'within' if worst_end <= 1e-10 else 'BEYOND'} 1e-10",
        ),
        (
            "  limits at the phases' extremes",
            f"largest excess {worst_lim:+.2e} (relative)",
            f"{'within' if worst_lim <= LIMIT_RTOL else 'BEYOND'} {LIMIT_RTOL:g}",
        ),
    ]


def speed() -> list[tuple[str, str, str]]:
    n = 7
    rng = np.random.default_rng(7)
    V, A, J = np.full(n, 2.0), np.full(n, 5.0), np.full(n, 30.0)
    states = []
    for _ in range(64):
        q0, q1 = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
        v0, a0 = random_state(rng, V, A, J)
        states.append((q0, v0, a0, q1))
    otg, inp, out = ruckig.Ruckig(n), ruckig.InputParameter(n), ruckig.Trajectory(n)
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = V.tolist(), A.tolist(), J.tolist()
    inputs = []
    for q0, v0, a0, q1 in states:  # ruckig's inputs made beforehand: calculate alone is timed
        x = ruckig.InputParameter(n)
        x.max_velocity, x.max_acceleration, x.max_jerk = V.tolist(), A.tolist(), J.tolist()
        x.current_position, x.current_velocity = q0.tolist(), v0.tolist()
        x.current_acceleration, x.target_position = a0.tolist(), q1.tolist()
        inputs.append(x)
    it = iter(range(10**9))

    def rk() -> None:
        otg.calculate(inputs[next(it) % 64], out)

    def rk_sampled() -> None:  # the same output from ruckig itself: samples every 10 ms
        otg.calculate(inputs[next(it) % 64], out)
        for t in np.arange(0.0, out.duration, 0.01):
            out.at_time(t)

    seg = Segment(V, A, J)
    z = np.zeros(n)

    def ours_plan() -> None:
        q0, v0, a0, q1 = states[next(it) % 64]
        seg.plan(q0, v0, a0, q1, z, z)

    def ours_full() -> None:
        q0, v0, a0, q1 = states[next(it) % 64]
        joint_trajectory(q0, q1, profile="scurve", vmax=V, amax=A, jmax=J, qd0=v0, qdd0=a0)

    t_rk = per_call(rk, calls=20_000)
    t_plan = per_call(ours_plan, calls=20_000)
    t_full = per_call(ours_full, calls=2_000)
    t_rks = per_call(rk_sampled, calls=2_000)
    rows = [
        ("7 joints, state to state: ruckig calculate", fmt_time(t_rk), "1.00x"),
        ("  our segment planner (ruckig + input check)", fmt_time(t_plan), f"{t_plan / t_rk:.2f}x"),
        ("  ruckig calculate + at_time every 10 ms", fmt_time(t_rks), f"{t_rks / t_rk:.2f}x"),
        (
            "  joint_trajectory(profile='scurve'), 10 ms samples",
            fmt_time(t_full),
            f"{t_full / t_rk:.2f}x ({t_full / t_rks:.2f}x ruckig sampled; the issue: <= 2x)",
        ),
    ]
    # the core's own segment, zero accelerations, beside ruckig on the same states
    zero = []
    for q0, v0, _, q1 in states:
        v1 = np.clip(rng.uniform(-1, 1, n) * V, -V, V)
        x = ruckig.InputParameter(n)
        x.max_velocity, x.max_acceleration, x.max_jerk = V.tolist(), A.tolist(), J.tolist()
        x.current_position, x.current_velocity = q0.tolist(), v0.tolist()
        x.target_position, x.target_velocity = q1.tolist(), v1.tolist()
        zero.append((x, q0[None], v0[None], q1[None], v1[None]))

    def rk_zero() -> None:
        otg.calculate(zero[next(it) % 64][0], out)

    def core_zero() -> None:
        _, q0, v0, q1, v1 = zero[next(it) % 64]
        jerk_segments(q0, v0, q1, v1, (V, A, J))

    batch = [np.concatenate([z[i] for z in zero]) for i in range(1, 5)]
    t_rkz = per_call(rk_zero, calls=20_000)
    t_core = per_call(core_zero, calls=20_000)
    t_batch = per_call(lambda: jerk_segments(*batch, (V, A, J)), calls=300) / 64
    rows += [
        ("7 joints, zero accelerations: ruckig calculate", fmt_time(t_rkz), f"{t_rkz / t_rk:.2f}x"),
        (
            "  the core's segment (jerk.hpp), one a call",
            fmt_time(t_core),
            f"{t_core / t_rkz:.2f}x ruckig",
        ),
        ("  the core's segment, 64 a call", fmt_time(t_batch), f"{t_batch / t_rkz:.2f}x ruckig"),
    ]
    searches = {
        f"default {SWEEPS, GOLDEN_STEPS, JOINT_SWEEPS}": (SWEEPS, GOLDEN_STEPS, JOINT_SWEEPS),
        f"no joint sweeps {SWEEPS, GOLDEN_STEPS, 0}": (SWEEPS, GOLDEN_STEPS, 0),
        f"two joint sweeps {SWEEPS, GOLDEN_STEPS, 2}": (SWEEPS, GOLDEN_STEPS, 2),
        f"golden 7 {SWEEPS, 7, JOINT_SWEEPS}": (SWEEPS, 7, JOINT_SWEEPS),
        f"golden 6 {SWEEPS, 6, JOINT_SWEEPS}": (SWEEPS, 6, JOINT_SWEEPS),
    }
    lim = {"vmax": V, "amax": A, "jmax": J, "dt": 0.01}
    for k in (5, 10, 20):
        W = np.cumsum(rng.uniform(-0.6, 0.9, (k, n)), axis=0)
        z = np.zeros(n)
        for name, search in searches.items():
            choice = jerk_via(W, z, z, (V, A, J), None, POSITION_ATOL, search)
            t_search = per_call(
                lambda W=W, z=z, s=search: jerk_via(W, z, z, (V, A, J), None, 0.0, s), 30
            )
            t_search /= k - 1
            evals = choice.evaluations / (k - 1)
            saving = 1.0 - choice.time.sum() / choice.stop.sum()
            rows.append(
                (
                    f"7 joints through {k} waypoints: the search, {name}, per segment",
                    fmt_time(t_search),
                    f"{t_search / t_rkz:.1f}x ruckig's segment; {evals:.0f} segments planned each; "
                    f"{saving:.1%} shorter than stopping",
                )
            )
            if search == (SWEEPS, GOLDEN_STEPS, JOINT_SWEEPS):
                t_default = t_search
        # position limits 0-2 cm outside the waypoints' range: some segments must slow
        edge = rng.uniform(0.0, 0.02, (2, n))
        qlim = np.stack([W.min(axis=0) - edge[0], W.max(axis=0) + edge[1]], axis=1)
        default = (SWEEPS, GOLDEN_STEPS, JOINT_SWEEPS)
        t_q = per_call(
            lambda W=W, z=z, q=qlim, s=default: jerk_via(W, z, z, (V, A, J), q, POSITION_ATOL, s),
            30,
        )
        t_q /= k - 1
        for label, kw, t_alone in (("", {}, t_default), (" with qlim", {"qlim": qlim}, t_q)):
            if kw:
                rows.append(
                    (
                        "  the search with qlim (default), per segment",
                        fmt_time(t_q),
                        f"{t_q / t_rkz:.1f}x ruckig's segment",
                    )
                )
            per_seg = per_call(lambda W=W, kw=kw: via_trajectory(W, "scurve", **lim, **kw), 10)
            per_seg /= k - 1
            traj = via_trajectory(W, "scurve", **lim, **kw)
            assert isinstance(traj, JerkTrajectory) and traj.margin is not None
            rows.append(
                (
                    f"  via_trajectory(W, 'scurve'){label}, per segment",
                    fmt_time(per_seg),
                    f"{per_seg / t_alone:.2f}x the search, {per_seg / t_rkz:.1f}x ruckig's segment "
                    f"(exact pieces, {traj.t.size} samples at 10 ms); "
                    f"{traj.margin:.3f} s shorter than stopping",
                )
            )
    return rows


def tradeoff(paths: int = 300) -> list[tuple[str, str, str]]:
    """Cheaper search settings against the default on random 7-joint paths (5, 10, 20
    waypoints; the benchmark's limits on half, random limits on the other half): each
    path's duration change. The issue's bar for a faster default: none longer by > 0.5 %."""
    n = 7
    rng = np.random.default_rng(36)
    z = np.zeros(n)
    cases = []
    for c in range(paths):
        k = (5, 10, 20)[c % 3]
        if c % 2:
            lim = (rng.uniform(1, 3, n), rng.uniform(3, 8, n), rng.uniform(15, 60, n))
        else:
            lim = (np.full(n, 2.0), np.full(n, 5.0), np.full(n, 30.0))
        cases.append((np.cumsum(rng.uniform(-0.6, 0.9, (k, n)), axis=0), lim))

    def durations(search: tuple[int, int, int]) -> np.ndarray:
        return np.array([jerk_via(W, z, z, lim, None, 0.0, search).time.sum() for W, lim in cases])

    base = durations((SWEEPS, GOLDEN_STEPS, JOINT_SWEEPS))
    # the default search before issue 36's speed-up (commit a2640cd), its durations stored
    main = np.loadtxt(Path(__file__).parent / "data" / "scurve_via_main.txt")
    r = base / main - 1.0
    rows = [
        (
            f"default search against a2640cd's (stored), {paths} paths",
            f"change min {r.min():+.1e}, median {np.median(r):+.1e}, max {r.max():+.1e}",
            f"{int((r > 0.005).sum())} longer by > 0.5 %, {int((r != 0.0).sum())} changed",
        )
    ]
    for search in ((SWEEPS, 7, JOINT_SWEEPS), (SWEEPS, 6, JOINT_SWEEPS), (SWEEPS, GOLDEN_STEPS, 0)):
        r = durations(search) / base - 1.0
        rows.append(
            (
                f"search {search} against the default, {paths} paths",
                f"change min {r.min():+.2%}, median {np.median(r):+.3%}, "
                f"95th percentile {np.quantile(r, 0.95):+.2%}, max {r.max():+.2%}",
                f"{int((r > 0.005).sum())} longer by > 0.5 %, {int((r < -1e-12).sum())} shorter",
            )
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=10_000, help="audit cases (default 10,000)")
    cases = parser.parse_args().cases
    print(
        header("kinematica jerk-limited moves (profile scurve, ruckig " + ruckig.__version__ + ")")
    )
    print(table(speed(), ("what", "time per call", "against ruckig calculate")))
    print()
    print(table(audit(cases) + audit_core(cases) + tradeoff(), ("audit", "result", "")))


if __name__ == "__main__":
    main()
