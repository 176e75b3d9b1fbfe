"""Builder of the closed-form IK of 6R arms with axes 2, 3, 4 parallel (UR type).

Once per arm, from its joint axes at q = 0 (:class:`Features`) and its tool
pose ``M = fk(0)``, this fills the parameters of the C++ closed form
(``cpp/include/kinematica/solvers/parallel.hpp``, where the method is
described; :class:`kinematica._core.parallel.ParallelParams` here): the vectors
and constants of equations (1) and (2) in ``(q1, q5)``, the planar triangle
axis 2 -> 3 -> 4, a proven reach bound, and the arm's mode: axes 5 and 6
meeting (every UR and its clones), parallel, or apart (a5 != 0: the quartic).
Up to 8 solutions, exact, for any link values, offsets, twists, base, tool and
DH convention.

Arms it declines (``None``: the numeric solver takes them): axis 1 or axis 5
parallel to axes 2-4 (four parallel axes), axes 5 and 6 on one line, or a
link of the triangle of length zero (axes 2 and 3, or 3 and 4, on one line).

Branch labels: where axes 5 and 6 meet, ``"shoulder right|left, elbow up|down,
wrist no-flip|flip"``:

* shoulder right: the wrist point (where axes 5 and 6 meet) lies on the
  ``h1 × k1`` side of axis 1 (``k1`` the current direction of axis 2);
* elbow up: the elbow (axis 3) lies on the side of the line axis 2 -> axis 4
  toward which ``h1`` points;
* wrist no-flip: ``(k1 × h6)·h5 >= 0`` for the current axes (for the UR5's
  table, ``sin q5 >= 0``).

Otherwise ``"root j, elbow up|down"``: root j is the j-th ``(q1, q5)`` pair in
increasing order of q1 in (-π, π].
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica import _core
from kinematica.core import Chain
from kinematica.dh.convert import convert_table
from kinematica.dh.joints import Convention, Revolute
from kinematica.dh.lines import cross3, line_distance, lines_parallel, normal_feet
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["DEGENERATE", "GENERAL_LABELS", "LABELS", "SPEC", "build", "pack", "sample_arm"]

FloatArray = NDArray[np.float64]

#: Labels where axes 5 and 6 meet: shoulder, then wrist, then elbow (fastest).
LABELS = tuple(
    f"shoulder {s}, elbow {e}, wrist {w}"
    for s in ("right", "left")
    for w in ("no-flip", "flip")
    for e in ("up", "down")
)
#: Labels where axes 5 and 6 do not meet: the j-th (q1, q5) pair by q1.
GENERAL_LABELS = tuple(f"root {j}, elbow {e}" for j in range(1, 5) for e in ("up", "down"))


def _unit(v: FloatArray) -> FloatArray:
    return np.asarray(v / np.linalg.norm(v), dtype=float)


def _project(x: FloatArray, h: FloatArray, p: FloatArray) -> FloatArray:
    """The point of the line ``p + t h`` closest to ``x``."""
    return np.asarray(p + ((x - p) @ h) * h, dtype=float)


def _angle(u: FloatArray, v: FloatArray) -> float:
    """Angle between unit vectors (accurate near 0 and π)."""
    return math.atan2(float(np.linalg.norm(cross3(u, v))), float(u @ v))


def _middle(lo: float, hi: float) -> float:
    return 0.5 * (lo + hi) if math.isfinite(lo) and math.isfinite(hi) else 0.0


def pack(
    chain: Chain, features: Features
) -> tuple[_core.parallel.ParallelParams, _core.parallel.Mode] | None:
    """The closed form's parameters for an arm, and its mode; ``None`` if declined.

    Args:
        chain: A 6R chain whose axes 2, 3, 4 are parallel.
        features: Its joint axes at q = 0 (base frame).

    Returns:
        ``(params, mode)`` with ``mode`` one of ``Mode.meet``, ``Mode.parallel``,
        ``Mode.general``; ``None`` for the arms the module docstring lists.
    """
    h = np.array(features.directions, dtype=float)
    p = np.array(features.points, dtype=float)
    k = _unit(h[1])
    h1, h5, h6 = h[0], h[4], h[5]
    if lines_parallel(h1, k) or lines_parallel(h5, k):
        return None
    e1 = _unit(cross3(k, [1.0, 0.0, 0.0] if abs(k[0]) < 0.9 else [0.0, 1.0, 0.0]))
    e2 = cross3(k, e1)

    def plane(x: FloatArray) -> FloatArray:
        return np.array([x @ e1, x @ e2])

    zA, zB = (complex(*plane(x)) for x in (p[2] - p[1], p[3] - p[2]))
    if min(abs(zA), abs(zB)) <= _core.parallel.CONTINUUM_TOL * (abs(zA) + abs(zB)):
        return None
    meet = features.length_tol
    if lines_parallel(h5, h6):
        if line_distance(h5, p[4], h6, p[5]) <= meet:
            return None
        mode, p5 = _core.parallel.Mode.parallel, p[4]
        p6 = _project(p5, h6, p[5])
    else:
        p5, p6 = normal_feet(h5, p[4], h6, p[5])
        mode = _core.parallel.Mode.general
        if np.linalg.norm(p6 - p5) <= meet:
            mode = _core.parallel.Mode.meet
            p5 = p6 = 0.5 * (p5 + p6)
    h6par = (h5 @ h6) * h5
    z = p6 - p5
    eq1 = np.array([k @ (h6 - h6par), k @ cross3(h5, h6), (k @ h5) * (h5 @ h6)])
    eq2 = np.array(
        [k @ (z - (h5 @ z) * h5), k @ cross3(h5, z), (k @ h5) * (h5 @ z) + k @ (p5 - p[0])]
    )
    minv = np.zeros(4)
    if mode == _core.parallel.Mode.meet:
        eq2[:2] = 0.0
    elif mode == _core.parallel.Mode.parallel:
        eq1 = np.array([0.0, 0.0, (k @ h5) * math.copysign(1.0, h5 @ h6)])
    else:
        minv = np.linalg.inv(np.array([eq1[:2], eq2[:2]])).ravel()
    alpha, beta = _angle(k, h5), _angle(h6, h5)
    # reach: |G(a6) - p1s| <= the length of the chain of feet p1s, a2, ..., a6
    p1s, a = normal_feet(h1, p[0], k, p[1])
    bound = float(np.linalg.norm(a - p1s))
    for i in (2, 3, 4, 5):
        nxt = _project(a, h[i], p[i])
        bound += float(np.linalg.norm(nxt - a))
        a = nxt
    kpar = (h1 @ k) * h1
    P = _core.parallel.ParallelParams()
    P.k, P.h1, P.p1, P.kpar, P.kperp, P.hk = k, h1, p[0], kpar, k - kpar, cross3(h1, k)
    P.h5, P.p5, P.h6, P.p6 = h5, p5, h6, p6
    P.h6par, P.h6perp, P.h5xh6 = h6par, h6 - h6par, cross3(h5, h6)
    P.p2, P.p4, P.e1, P.e2 = p[1], p[3], e1, e2
    P.home = chain.fk(np.zeros(6))[0]
    P.p1s, P.a6 = p1s, a
    P.mode = mode
    P.D1, P.E1, P.F1 = (float(v) for v in eq1)
    P.D2, P.E2, P.F2 = (float(v) for v in eq2)
    P.minv = minv
    P.wlo = 2.0 * math.sin(0.5 * (alpha - beta)) ** 2
    P.whi = 2.0 * math.cos(0.5 * (alpha + beta)) ** 2
    P.len_a, P.len_b = (float(v) for v in np.abs([zA, zB]))
    P.arg_a, P.arg_b = (float(v) for v in np.angle([zA, zB]))
    P.zup = plane(cross3(h1, k))
    P.sign3 = math.copysign(1.0, h[2] @ k)
    P.sign4 = math.copysign(1.0, h[3] @ k)
    P.bound = bound
    P.lip = float(abs(h1 @ k) + float(np.linalg.norm(k - kpar)))
    P.scale = bound
    P.slack = features.slack  # 0 unless near-degenerate: the triangle straddles its fold
    lims = chain.qlim
    P.q1rep = _middle(*lims[0])
    P.q2rep = _middle(*lims[1])
    return P, mode


def build(chain: Chain, features: Features, target: TargetKind) -> ClosedForm | None:
    """The closed-form solver of a UR-type arm for pose targets, or ``None``.

    An arm whose axes have the structure only within the line geometry's tolerance
    (``features.near_degenerate``) gets the general 6R's candidates too, when its
    builder finds a labelling (``cpp/include/kinematica/solvers/near_6r.hpp``: near the
    family's singular sets the real arm's solutions lie beyond the repair's reach of
    the family's); their branch labels follow the family's.
    """
    if target != "pose":
        return None
    packed = pack(chain, features)
    if packed is None:
        return None
    params, mode = packed
    labels = LABELS if mode == _core.parallel.Mode.meet else GENERAL_LABELS
    if features.near_degenerate:
        from kinematica.ik.analytic import general_6r  # a near-degenerate arm's only

        exact = general_6r.build(chain, features, target)
        if exact is not None:
            near = _core.general6r.NearParallelParams()
            near.family = params
            near.general = exact.params
            near.watch = _core.general6r.WATCH_FACTOR * math.sqrt(features.slack / features.size)
            return ClosedForm(name="three-parallel-6R", labels=labels + exact.labels, params=near)
    return ClosedForm(name="three-parallel-6R", labels=labels, params=params)


# ------------------------------------------------------------------ sample arms
#: The edge geometries sample_arm draws from (its note says which).
DEGENERATE = (
    "equal links",
    "offsets of 1e-10",
    "twists of axes 2-4 within 1e-9 of 0 or pi",
    "wrist twists of 90 degrees",
    "axes 5 and 6 1e-10 m apart",
    "axes 5 and 6 1e-9 m apart",
    "axes 5 and 6 parallel within 1e-10",
    "no offset along axis 2",
    "axes 4, 5, 6 meeting",
)


def _sign(rng: np.random.Generator) -> float:
    return float(rng.choice([-1.0, 1.0]))


def _twist(rng: np.random.Generator, square: bool) -> float:
    """±90° (``square``: the wrist can align), else a twist well away from 0 and π (rad)."""
    if square:
        return _sign(rng) * math.pi / 2
    return _sign(rng) * float(rng.uniform(0.3, math.pi - 0.3))


def sample_arm(rng: np.random.Generator, degenerate: bool = False) -> ArmSample:
    """A random UR-type arm (axes 2, 3, 4 parallel) in a random DH convention.

    Axes 5 and 6 meet, lie apart or are parallel (drawn at random); a quarter of
    the generic arms have ±90° twists at joints 1, 4, 5 (the wrist can align).

    Args:
        rng: Random numbers.
        degenerate: Draw one of the edge geometries of :data:`DEGENERATE` (the
            sample's ``note``): equal links 2 and 3 (the elbow folds onto axis 2),
            offsets a1, d2, d3 of 1e-10 m, twists of axes 2-4 within 1e-9 rad of 0
            or π, ±90° twists, axes 5 and 6 1e-10 or 1e-9 m apart or parallel within
            1e-10 rad, nothing along axis 2 between axes 2 and 5 (the wrist point
            reaches axis 1), axes 4-6 meeting.

    Returns:
        The arm as DH rows (m, rad) with a random base and tool.
    """
    u = rng.uniform
    case = str(rng.choice(DEGENERATE)) if degenerate else ""
    mode = str(rng.choice(["meet", "apart", "parallel"]))
    square = case == "wrist twists of 90 degrees" or bool(rng.random() < 0.25)
    small = 1e-10 if case == "offsets of 1e-10" else 0.0
    a2 = u(0.2, 0.6) * _sign(rng)
    a3 = abs(a2) * _sign(rng) if case == "equal links" else u(0.2, 0.6) * _sign(rng)
    flat = [float(rng.choice([0.0, math.pi])) for _ in range(2)]
    if case == "twists of axes 2-4 within 1e-9 of 0 or pi":
        flat = [v + u(-5e-10, 5e-10) for v in flat]
    d4, a4, alpha4 = u(-0.2, 0.2), u(-0.1, 0.1), _twist(rng, square)
    d5, a5, alpha5 = u(-0.2, 0.2), 0.0, _twist(rng, square)
    if mode == "apart":
        a5 = u(0.03, 0.15) * _sign(rng)
    elif mode == "parallel":
        a5, alpha5 = u(0.03, 0.15), 0.0
    # (with a5 of 1e-9 or less, axes 5 and 6 need a twist: on one line they are declined)
    if case == "axes 5 and 6 1e-10 m apart":
        a5, alpha5 = 1e-10, _twist(rng, square)
    elif case == "axes 5 and 6 1e-9 m apart":
        a5, alpha5 = 1e-9, _twist(rng, square)
    elif case == "axes 5 and 6 parallel within 1e-10":
        a5, alpha5 = u(0.03, 0.15), 1e-10 * _sign(rng)
    elif case == "axes 4, 5, 6 meeting":
        d5, a5, alpha5 = 0.0, 0.0, _twist(rng, square)
    elif case == "no offset along axis 2":  # d5 runs along axis 5, across axis 4
        d4, a4, alpha4, a5, alpha5 = 0.0, 0.0, _twist(rng, True), 0.0, _twist(rng, square)
    rows = (
        Revolute(d=u(0.05, 0.4), a=small, alpha=_twist(rng, square), offset=u(-math.pi, math.pi)),
        Revolute(d=small, a=a2, alpha=flat[0]),
        Revolute(d=small, a=a3, alpha=flat[1]),
        Revolute(d=d4, a=a4, alpha=alpha4, offset=u(-math.pi, math.pi)),
        Revolute(d=d5, a=a5, alpha=alpha5, offset=u(-math.pi, math.pi)),
        Revolute(d=u(-0.2, 0.2), a=u(-0.1, 0.1), alpha=u(-math.pi, math.pi)),
    )
    base, tool = random_transform(rng, 0.5), random_transform(rng, 0.2)
    convention: Convention = "modified" if rng.random() < 0.5 else "standard"
    links, base, tool = convert_table(rows, "standard", convention, base, tool)
    return ArmSample(links, convention, base, tool, case)


def _handles(f: Features) -> bool:
    return f.joint_types == "RRRRRR" and {(1, 2), (2, 3)} <= set(f.parallel)


SPEC: SolverSpec = SolverSpec(
    kind="three-parallel-6R",
    summary="6R, three parallel axes (2-3-4), UR type",
    summary_es="6R con tres ejes paralelos (2-3-4), tipo UR",
    handles=_handles,
    build=build,
    sample_arm=sample_arm,
    singular=frozenset({"shoulder", "elbow", "wrist"}),
)
