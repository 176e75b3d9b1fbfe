"""An audit of ``method="auto"`` on random 6R DH tables with the special values makers use.

Each DH row draws its twist among 0, ±π/2, π and a random angle, its length a and
offset d as 0 or random (each half the time), its joint offset at random: tables
with many meeting, parallel and perpendicular axes, among them arms of rank 5 at every
configuration (:mod:`kinematica.ik.rank_five`). Arms with a coaxial pair are passed
over (:mod:`kinematica.ik.coaxial` answers them). Each arm's targets are the forward
kinematics of random configurations; each answer is counted:

* ``numeric``: ``method="auto"`` answered by the numeric search (``numeric:lm``);
* ``numeric_ok``: ... with status ``ok``;
* ``bad_fk``: a solution whose FK misses the target by more than :data:`TOL`;
* ``missing``: ``ok`` without the generating configuration among the solutions, at a
  configuration where the arm is not singular (σ6 / σ1 above :data:`SINGULAR_REL`);
* ``missing_near``: the same at any configuration, the generating one matched to
  :data:`FOUND_TOL` plus :data:`TOL` over σ6 / σ1 there (how well a solution of an
  ill-conditioned arm is determined), for the arms near rank 5;
* ``singular``: answered ``singular`` (a continuum);
* ``false``: ``unreachable``, ``not_found`` or ``out_of_limits`` (limits are not
  respected, the target was made by FK);
* ``us``: the time ``robot.ik(T)`` took, µs, summed (one core, one pose at a time).

:func:`perturbed` moves every DH value of an arm by a random amount between 1e-12 and
1e-3 (log-uniform), the near-degenerate arms of the issue.
"""

from __future__ import annotations

import collections
import math
import time
from collections.abc import Iterator

import numpy as np
from numpy.typing import NDArray

import kinematica as km
from kinematica.dh.joints import Revolute
from kinematica.ik.coaxial_pair import coaxial_pair
from kinematica.ik.rank_five import rank_five, relative_sigma

FloatArray = NDArray[np.float64]
PI = math.pi

#: Solutions reach their target to this (m, rad).
TOL = 1e-10
#: The generating configuration is among the solutions to this (rad, modulo 2π).
FOUND_TOL = 1e-6
#: Below this σ6 / σ1 at the generating configuration, it need not be returned.
SINGULAR_REL = 1e-6
#: The counts, in the order they are printed.
COUNTS = (
    "targets",
    "numeric",
    "numeric_ok",
    "bad_fk",
    "missing",
    "missing_near",
    "singular",
    "false",
)


def random_table(rng: np.random.Generator) -> list[Revolute]:
    """Six DH rows: twists among 0, ±π/2, π, random; a and d 0 or random (m, rad)."""
    rows = []
    for _ in range(6):
        alpha = float(rng.choice([0.0, PI / 2, -PI / 2, PI, rng.uniform(-PI, PI)]))
        a = 0.0 if rng.random() < 0.5 else float(rng.uniform(-0.5, 0.5))
        d = 0.0 if rng.random() < 0.5 else float(rng.uniform(-0.5, 0.5))
        rows.append(Revolute(d=d, a=a, alpha=alpha, offset=float(rng.uniform(-PI, PI))))
    return rows


def arms(count: int, seed: int) -> Iterator[tuple[list[Revolute], km.Robot]]:
    """``count`` random arms without a coaxial pair (standard convention)."""
    rng = np.random.default_rng(seed)
    made = 0
    while made < count:
        rows = random_table(rng)
        robot = km.Robot.from_dh(rows, convention="standard")
        if coaxial_pair(robot.chain) is not None:
            continue
        made += 1
        yield rows, robot


def perturbed(rows: list[Revolute], rng: np.random.Generator) -> list[Revolute]:
    """The rows with every d, a, α moved by ±10^u, u uniform in [-12, -3] (one u per arm)."""
    eps = 10.0 ** rng.uniform(-12, -3)

    def moved(x: float) -> float:
        return x + eps * float(rng.choice([-1.0, 1.0]))

    return [
        Revolute(d=moved(r.d), a=moved(r.a), alpha=moved(r.alpha), offset=r.offset) for r in rows
    ]


def _wrapped(d: FloatArray) -> FloatArray:
    return np.abs(np.remainder(d + PI, 2 * PI) - PI)


def audit(
    robot: km.Robot, targets: int, rng: np.random.Generator, show: bool = False
) -> collections.Counter[str]:
    """The counts of one arm's ``targets`` FK poses answered by ``robot.ik(T)``.

    With ``show``, each false status and missed configuration is printed.
    """
    c: collections.Counter[str] = collections.Counter()
    for _ in range(targets):
        q = rng.uniform(-PI, PI, 6)
        T = robot.fk(q)
        t0 = time.perf_counter()
        res = robot.ik(T)
        c["us"] += round(1e6 * (time.perf_counter() - t0))
        c["targets"] += 1
        status = str(res.status)
        if res.method.startswith("numeric"):
            c["numeric"] += 1
            c["numeric_ok"] += status == "ok"
        c["singular"] += status == "singular"
        c["false"] += status in ("unreachable", "not_found", "out_of_limits")
        if len(res.solutions):
            F = robot.fk(res.solutions)
            pos = np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1)
            rot = np.array([km.rotation_angle(f[:3, :3], T[:3, :3]) for f in F])
            bad = int(((pos > TOL) | (rot > TOL)).sum())
            c["bad_fk"] += bad
            if show and bad:
                print(f"  bad FK {res.method} {status} {pos.max():.1e} m {rot.max():.1e} rad")
        sigma = float(relative_sigma(robot.chain, q))
        missed = False
        if status == "ok":
            gap = _wrapped(res.solutions - q).max(axis=1).min() if len(res.solutions) else PI
            missed = gap > FOUND_TOL + TOL / sigma
            c["missing"] += sigma > SINGULAR_REL and gap > FOUND_TOL
            c["missing_near"] += sigma <= SINGULAR_REL and missed
        if show and (missed or status in ("unreachable", "not_found", "out_of_limits")):
            print(f"  {status} {res.method} q={q.tolist()} σ6/σ1 there {sigma:.1e}")
    return c


def run(
    count: int, targets: int, seed: int, perturbations: int = 2, show: bool = False
) -> dict[str, collections.Counter[str]]:
    """The counts per class of arm: ``rank-5`` (exact), ``near`` (perturbed rank-5), ``other``.

    ``near`` arms are the rank-5 arms' tables perturbed (:func:`perturbed`),
    ``perturbations`` per rank-5 arm met; their counts are split at σ6 / σ1 = 1e-5
    (``near<1e-5``, ``near>1e-5``). With ``show``, the failures are printed.
    """
    rng = np.random.default_rng(seed + 1)
    out: dict[str, collections.Counter[str]] = collections.defaultdict(collections.Counter)
    for rows, robot in arms(count, seed):
        five = rank_five(robot.chain)
        exact = five is not None and five.exact
        out["rank-5" if exact else "other"].update(audit(robot, targets, rng, show))
        for _ in range(perturbations if exact else 0):
            table = perturbed(rows, rng)
            moved = km.Robot.from_dh(table, convention="standard")
            key = "near<1e-5" if rank_five(moved.chain) is not None else "near>1e-5"
            if show:
                print(f"{key}: {[(r.d, r.a, r.alpha, r.offset) for r in table]}")
            out[key].update(audit(moved, targets, rng, show))
    return dict(out)
