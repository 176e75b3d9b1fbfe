"""The audit of issue 32 on the makers' 6R arms: every solution, exact, against ssik 8.2.0.

Run with ``nice -n 19 .venv/bin/python benchmarks/audit_makers.py`` (``--poses``,
``--perturbed``, ``--numeric``, ``--arms`` a substring of the arms' names, ``--seed``,
``--show``). ssik is the reference where it imports (e.g.
``PYTHONPATH=/tmp/ssikvenv/lib/python3.11/site-packages``, a venv holding
``ssik==8.2.0``); without it the checks against it are left out. No assertions.

**The arms as the makers give them** (``tests/data/makers``, the 53 six-joint arms),
``--poses`` poses each (default 1,000) of configurations ``q_gen`` uniform within the
limits, each answered by ``robot.ik(T, respect_limits=False)``. Counted per arm:

* ``numeric``: poses not answered by a closed form (``method`` not ``analytic:...``);
* ``inexact``: poses with a solution whose FK misses T by more than :data:`TOL`;
* ``lost_ssik``: ssik solutions (its default ``solve(T)`` and ``respect_limits=False``)
  reaching T to :data:`SSIK_TOL` by our FK that are not among ours (mod 2π, to :data:`SAME`
  plus what their FK's miss allows at their conditioning, :func:`determined`);
* ``lost_gen``: poses where ``q_gen`` is not among ours though the arm is regular there
  (σmin/σmax of the Jacobian at least :data:`SINGULAR_REL`);
* ``false``: ``unreachable``, ``not_found``, ``out_of_limits`` for a pose made by FK;
* our and ssik's mean solution counts.

**Perturbed arms**: ``--perturbed`` per arm (default 3; the issue's full audit is 200)
of the arm's DH table (``robot.to_dh()``, base and tool kept) with every d, a and α
moved by ±ε (random signs), log10 ε uniform in [-12, -3] (one ε per arm), ``--poses``
// 10 poses each (at least 10). Counted as above without ssik (its modules are the
exact arms'), and on ``--numeric`` poses per perturbed arm (default 2) a 200-start
numeric search (``method="numeric"``, 200 random q0): ``short`` where it finds more
distinct solutions than we return, ``lost_num`` its solutions not among ours at a
regular pose. The figures are split by ε (below and above 1e-9).

Each failure prints what reproduces it: the arm (and for a perturbed arm its ε, the
seed index and its DH rows), ``q_gen`` and the answer's status and method.
"""

from __future__ import annotations

import argparse
import collections
import dataclasses
import math
import sys
import time
import warnings
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
from numpy.typing import NDArray

sys.path.insert(0, str(Path(__file__).resolve().parent))

from ik_makers import MAKERS, six_r_arms, ssik_module

import kinematica as km

FloatArray = NDArray[np.float64]

#: Our solutions reach their pose to this (m, rad).
TOL = 1e-10
#: An ssik solution is a reference when it reaches its pose to this by our FK (m, rad).
SSIK_TOL = 1e-9
#: Two solutions are one when every joint agrees to this modulo 2π (rad).
SAME = 1e-6
#: A reference solution is matched to :data:`SAME` plus this times its FK's miss over
#: σmin of its Jacobian (:func:`determined`).
DETERMINED = 10.0
#: Below this σmin/σmax of the Jacobian at q_gen, the pose is singular.
SINGULAR_REL = 1e-6
#: Starts of the numeric search a perturbed arm's count is compared with.
STARTS = 200
#: ε of the perturbed arms: log10 uniform in this range.
EPS_RANGE = (-12.0, -3.0)
#: The perturbed arms' figures are split at this ε.
EPS_SPLIT = 1e-9
COUNTS = ("poses", "numeric", "inexact", "lost_ssik", "lost_gen", "false", "singular_poses")
NEAR_COUNTS = ("poses", "numeric", "inexact", "lost_gen", "false", "checked", "short", "lost_num")


@dataclasses.dataclass
class Failure:
    """One failing pose: enough to reproduce it."""

    what: str
    arm: str
    q: list[float]
    status: str
    method: str
    detail: str = ""


def configurations(robot: km.Robot, n: int, rng: np.random.Generator) -> FloatArray:
    """``(n, 6)`` configurations uniform within the limits (continuous: ±π)."""
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    return rng.uniform(np.maximum(lo, -math.pi), np.minimum(hi, math.pi), (n, robot.dof))


def misses(robot: km.Robot, q: FloatArray, T: FloatArray) -> FloatArray:
    """``(k,)``: the larger of the position (m) and rotation (rad) error of each q at T."""
    with warnings.catch_warnings():  # solutions outside the limits are meant here
        warnings.simplefilter("ignore", km.KinematicaWarning)
        F = robot.fk(q)
    pos = np.linalg.norm(F[..., :3, 3] - T[:3, 3], axis=-1)
    return np.maximum(pos, km.rotation_angle(F[..., :3, :3], T[:3, :3]))


def among(q: FloatArray, solutions: FloatArray, slack: float = 0.0) -> bool:
    """Whether ``q`` is one of ``solutions`` modulo 2π (:data:`SAME` + ``slack``, rad)."""
    if len(solutions) == 0:
        return False
    d = (solutions - q + math.pi) % (2.0 * math.pi) - math.pi
    return bool(np.abs(d).max(axis=1).min() <= SAME + slack)


def determined(robot: km.Robot, q: FloatArray, T: FloatArray) -> FloatArray:
    """``(k,)`` how far (rad) each solution ``q (k, 6)`` of T may be from the exact one.

    :data:`DETERMINED` times its FK's miss of T over σmin of its Jacobian (m or rad per
    rad): an ill-conditioned solution that misses by 1e-11 may lie 1e-5 rad off.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", km.KinematicaWarning)
        sv = np.linalg.svd(robot.jacobian(q), compute_uv=False)[:, -1]
    return np.asarray(DETERMINED * misses(robot, q, T) / np.maximum(sv, 1e-300))


def distinct(qs: FloatArray) -> FloatArray:
    """The rows of ``qs`` one per class modulo 2π (:data:`SAME`)."""
    out: list[FloatArray] = []
    for q in qs:
        if not among(q, np.array(out).reshape(-1, qs.shape[1])):
            out.append(q)
    return np.array(out).reshape(-1, qs.shape[1])


def regular(robot: km.Robot, q: FloatArray) -> NDArray[np.bool_]:
    """``(n,)``: σmin/σmax of the Jacobian at each q at least :data:`SINGULAR_REL`."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", km.KinematicaWarning)
        sv = np.linalg.svd(robot.jacobian(q), compute_uv=False)
    return np.asarray(sv[:, -1] >= SINGULAR_REL * sv[:, 0])


def check_poses(
    robot: km.Robot,
    q_gen: FloatArray,
    name: str,
    counts: collections.Counter[str],
    failures: list[Failure],
    ssik: ModuleType | None = None,
) -> list[Any]:
    """Solve the FK poses of ``q_gen``, count what :data:`COUNTS` names; the answers."""
    Ts = robot.fk(q_gen)
    res = robot.ik(Ts, respect_limits=False)
    ok = regular(robot, q_gen)
    answers = []
    for i, T in enumerate(Ts):
        one = res[i]
        answers.append(one)
        counts["poses"] += 1
        counts["ours"] += one.count
        counts["singular_poses"] += not ok[i]

        def fail(what: str, detail: str = "", one: Any = one, i: int = i) -> None:
            counts[what] += 1
            failures.append(Failure(what, name, q_gen[i].tolist(), str(one.status),
                                    one.method, detail))  # fmt: skip

        if not one.method.startswith("analytic:"):
            fail("numeric")
        if str(one.status) in ("unreachable", "not_found", "out_of_limits"):
            fail("false", one.message)
        if one.count:
            worst = float(misses(robot, one.solutions, T).max())
            if worst > TOL:
                fail("inexact", f"miss {worst:.1e}")
        if ok[i] and not among(q_gen[i], one.solutions):
            fail("lost_gen", f"{one.count} solutions")
        if ssik is not None:
            both = ssik.solve(T) + ssik.solve(T, respect_limits=False)
            theirs = np.array([s.q for s in both], dtype=float).reshape(-1, 6)
            if len(theirs):
                theirs = distinct(theirs[misses(robot, theirs, T) < SSIK_TOL])
            counts["ssik"] += len(theirs)
            slack = determined(robot, theirs, T) if len(theirs) else []
            lost = [q for q, e in zip(theirs, slack, strict=True) if not among(q, one.solutions, e)]
            if lost:
                fail("lost_ssik", f"{len(lost)} of {len(theirs)}: {np.round(lost, 6).tolist()}")
    return answers


def _tag(arm: dict[str, Any]) -> int:
    """A whole number of the arm's name, for its random generators' seeds."""
    return int.from_bytes(arm["arm"].encode()[:6], "little")


def exact_arm(
    arm: dict[str, Any], n: int, seed: int, failures: list[Failure]
) -> collections.Counter[str]:
    """The counts of one arm as the maker gives it on ``n`` poses."""
    robot = km.load(MAKERS / arm["urdf"])
    rng = np.random.default_rng([seed, _tag(arm)])
    counts: collections.Counter[str] = collections.Counter()
    t0 = time.perf_counter()
    check_poses(robot, configurations(robot, n, rng), arm["arm"], counts, failures,
                ssik_module(arm))  # fmt: skip
    counts["ms"] = round(1e3 * (time.perf_counter() - t0))
    return counts


def perturb(robot: km.Robot, rng: np.random.Generator) -> tuple[km.Robot, float]:
    """The robot's DH table with every d, a, α moved by ±ε, log10 ε in :data:`EPS_RANGE`."""
    eps = float(10.0 ** rng.uniform(*EPS_RANGE))

    def moved(x: float) -> float:
        return x + eps * float(rng.choice([-1.0, 1.0]))

    with warnings.catch_warnings():  # a near-parallel pair's common normal may be km away
        warnings.simplefilter("ignore", km.KinematicaWarning)
        table = robot.to_dh().robot
        rows = [
            dataclasses.replace(j, d=moved(j.d), a=moved(j.a), alpha=moved(j.alpha))
            for j in table.links
        ]
    out = km.Robot.from_dh(rows, convention=table.convention, base=table.base, tool=table.tool,
                           name=f"{robot.name} ±{eps:.1e}")  # fmt: skip
    return out, eps


def numeric_check(
    robot: km.Robot,
    q: FloatArray,
    answer: Any,
    rng: np.random.Generator,
    counts: collections.Counter[str],
) -> str:
    """Compare ``answer`` with a :data:`STARTS`-start numeric search at fk(q); "" or what failed."""
    T = robot.fk(q)
    q0 = rng.uniform(-math.pi, math.pi, (STARTS, 6))
    with warnings.catch_warnings():  # starts outside the limits are meant
        warnings.simplefilter("ignore", km.KinematicaWarning)
        res = robot.ik(np.broadcast_to(T, (STARTS, 4, 4)).copy(), method="numeric", q0=q0,
                       respect_limits=False)  # fmt: skip
    found = [res[i].solutions for i in range(STARTS) if res[i].count]
    sols = np.concatenate(found) if found else np.zeros((0, 6))
    if len(sols):
        sols = distinct(sols[misses(robot, sols, T) <= TOL])
    counts["checked"] += 1
    counts["numeric_sols"] += len(sols)
    counts["ours_at_checked"] += answer.count
    out = []
    if len(sols) > answer.count:
        counts["short"] += 1
        out.append(f"numeric {len(sols)} > ours {answer.count}")
    ok = regular(robot, sols) if len(sols) else np.zeros(0, bool)
    slack = determined(robot, sols, T) if len(sols) else np.zeros(0)
    lost = [
        s
        for s, r, e in zip(sols, ok, slack, strict=True)
        if r and not among(s, answer.solutions, e)
    ]
    if lost:
        counts["lost_num"] += 1
        out.append(f"{len(lost)} numeric solutions not ours: {np.round(lost, 6).tolist()}")
    return "; ".join(out)


def perturbed_arms(
    arm: dict[str, Any], m: int, n: int, numeric: int, seed: int, failures: list[Failure]
) -> dict[str, collections.Counter[str]]:
    """The counts of ``m`` perturbed copies of one arm, split by ε at :data:`EPS_SPLIT`."""
    base = km.load(MAKERS / arm["urdf"])
    out: dict[str, collections.Counter[str]] = collections.defaultdict(collections.Counter)
    for k in range(m):
        rng = np.random.default_rng([seed, 1 + k, _tag(arm)])
        robot, eps = perturb(base, rng)
        key = "ε<1e-9" if eps < EPS_SPLIT else "ε≥1e-9"
        c = out[key]
        tag = f"{arm['arm']} perturbed #{k} (seed {seed}) ε={eps:.3e}"
        q_gen = configurations(base, n, rng)
        before = len(failures)
        answers = check_poses(robot, q_gen, tag, c, failures)
        for i in range(min(numeric, n)):
            detail = numeric_check(robot, q_gen[i], answers[i], rng, c)
            if detail:
                one = answers[i]
                failures.append(Failure("numeric_more", tag, q_gen[i].tolist(), str(one.status),
                                        one.method, detail))  # fmt: skip
        if len(failures) > before:
            rows = [(j.d, j.a, j.alpha, j.offset) for j in robot.links]
            failures[before].detail += f"\n    {robot.convention} DH rows (d, a, α, θ0) = {rows}"
    return out


def print_table(title: str, rows: list[list[str]], head: list[str]) -> None:
    widths = [max(len(str(r[i])) for r in [head, *rows]) for i in range(len(head))]
    print(f"\n{title}")
    print("  ".join(h.rjust(w) for h, w in zip(head, widths, strict=True)))
    for r in rows:
        print("  ".join(str(x).rjust(w) for x, w in zip(r, widths, strict=True)))


def exact_table(arms: list[dict[str, Any]], n: int, seed: int, failures: list[Failure]) -> None:
    """Audit the arms as given, ``n`` poses each, and print their table."""
    have = ssik_module(arms[0]) is not None if arms else False
    print(f"ssik: {'8.2.0 imported' if have else 'not importable: its checks left out'}")
    rows, total = [], collections.Counter[str]()

    def row(name: str, c: collections.Counter[str]) -> list[str]:
        k = max(c["poses"], 1)
        return [name, *(str(c[x]) for x in COUNTS), f"{c['ours'] / k:.2f}",
                f"{c['ssik'] / k:.2f}" if have else "-", f"{c['ms'] / k:.2f}"]  # fmt: skip

    for arm in arms:
        c = exact_arm(arm, n, seed, failures)
        total.update(c)
        rows.append(row(arm["arm"], c))
        print(f"  {arm['arm']} done", file=sys.stderr, flush=True)
    rows.append(row("all", total))
    head = ["arm", *COUNTS, "ours/pose", "ssik/pose", "ms/pose (audit)"]
    print_table(f"The makers' arms as given, {n} poses each", rows, head)


def near_table(
    arms: list[dict[str, Any]], m: int, n: int, numeric: int, seed: int, failures: list[Failure]
) -> None:
    """Audit ``m`` perturbed copies of each arm, ``n`` poses each, and print their table."""
    rows, total = [], collections.defaultdict(collections.Counter)

    def row(name: str, key: str, c: collections.Counter[str]) -> list[str]:
        return [name, key, *(str(c[x]) for x in NEAR_COUNTS),
                f"{c['ours'] / max(c['poses'], 1):.2f}"]  # fmt: skip

    for arm in arms:
        split = perturbed_arms(arm, m, n, numeric, seed, failures)
        for key, c in sorted(split.items()):
            total[key].update(c)
            rows.append(row(arm["arm"], key, c))
        print(f"  {arm['arm']} perturbed done", file=sys.stderr, flush=True)
    rows += [row("all", key, c) for key, c in sorted(total.items())]
    title = f"{m} perturbed arms per arm, {n} poses each ({numeric} vs a {STARTS}-start search)"
    print_table(title, rows, ["arm", "ε", *NEAR_COUNTS, "ours/pose"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=1000, help="poses per exact arm")
    parser.add_argument("--perturbed", type=int, default=3, help="perturbed arms per arm")
    parser.add_argument("--numeric", type=int, default=2, help="poses per perturbed arm "
                        f"compared with a {STARTS}-start numeric search")  # fmt: skip
    parser.add_argument(
        "--perturbed-poses",
        type=int,
        default=None,
        help="poses per perturbed arm (default --poses // 10, at least 10)",
    )
    parser.add_argument("--arms", default="", help="only arms whose names hold this")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--show", type=int, default=30, help="failures to print")
    args = parser.parse_args()
    np.set_printoptions(precision=17)
    arms = six_r_arms(args.arms)
    failures: list[Failure] = []
    if args.poses:
        exact_table(arms, args.poses, args.seed, failures)
    if args.perturbed:
        per = args.perturbed_poses or max(args.poses // 10, 10)
        near_table(arms, args.perturbed, per, args.numeric, args.seed, failures)
    kinds = collections.Counter(f.what for f in failures)
    print(f"\nfailures: {dict(kinds) or 'none'}")
    for f in failures[: args.show]:
        print(f"\n{f.what}: {f.arm}: {f.status} {f.method}\n  q_gen = {f.q}\n  {f.detail}")


if __name__ == "__main__":
    main()
