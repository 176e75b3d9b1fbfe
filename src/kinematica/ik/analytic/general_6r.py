"""Any 6R arm: the builder of the general 6R solver (Raghavan-Roth, Manocha-Canny).

The core's solver (``cpp/include/kinematica/solvers/general_6r.hpp``) solves the arm
written as a loop ``I = Rz(q'1) L1 ... Rz(q'6) L6`` (one link holding the target), by
eliminating q'3, then the 8 products of (q'1, q'2), leaving a 12 x 12 matrix quadratic
in tan(q'6/2) whose determinant's roots are a 16 x 16 eigenproblem (its 8 roots at ±i
deflated from the 24 x 24 companion matrix). This module writes
the loop from the joint axes at q = 0 (product of exponentials: any base, tool,
convention or URDF chain), computes the constants of the elimination once per arm
(the left side's 14 x 8 matrix Q, its left null space and pseudo-inverse), and
chooses the labelling of the joints (the loop turned cyclically or reversed) for
which the elimination is well posed: of the eight, those on which random poses are
solved (the generating configuration found among the candidates), the one whose
eigenvalues are the most accurate there.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.convert import convert_table
from kinematica.dh.joints import Joint, Revolute
from kinematica.dh.lines import cross3
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = [
    "ACCURATE",
    "LABELLINGS",
    "LABELS",
    "PHI",
    "PROBES",
    "PROBE_CONFIGS",
    "PROBE_TOL",
    "RANK_TOL",
    "SEARCH_NOTE",
    "SPEC",
    "accuracy",
    "build",
    "free_joints",
    "loop_of",
    "mark_continua",
]

FloatArray = NDArray[np.float64]
PI = math.pi
_G = _core.general6r

#: Shifts (rad) of q'4, q'5, q'6 in the half-angle substitution: a configuration with
#: q'k = shift + π (tan = ∞) is then no special value of a DH table (0, ±π/2, π).
PHI = (0.3771, 0.6133, 0.8909)
#: A labelling is rank-deficient when σ8 / σ1 of its 14 x 8 matrix Q is below this (the
#: core's: the same test decides, per target, for a labelling with T on the left side).
RANK_TOL: float = _G.RANK_TOL
#: A labelling passes a probe pose when the configuration that made it is among the raw
#: candidates to this (rad; the check's polish takes them the rest of the way).
PROBE_TOL = 1e-6
#: The configurations whose poses each labelling is probed on: uniform in (-π, π],
#: ``np.random.default_rng(6).uniform(-π, π, (8, 6))`` written out (the choice is
#: reproducible, and the first IK of a process does not import numpy.random: 10-20 ms).
PROBE_CONFIGS = (
    (0.2397936924265509, -0.9847581679958686, -0.8226747951461473,
     -0.788560078461733, 3.062707200397904, 0.8341322614811477),
    (1.0953095588356296, -1.0683711188056741, 1.1304560051279005,
     -2.3689344345096206, -2.8165683032376525, 2.200317124970402),
    (-3.085698658954023, 3.0081853122768454, 2.0546206072295448,
     1.7920333090860519, -2.8394751945374326, -1.8382133040260147),
    (2.1982705927845485, -0.42414760756750125, 0.8009046481796953,
     -2.3732696820540706, -1.9708070338793215, -0.017166210520705327),
    (1.630276583194279, 0.250430200722215, -2.4700453142945857,
     2.300814988218379, -2.2640898449367772, -0.37914149140104936),
    (0.5456913354825392, -1.1363171893390018, -0.5148808609029172,
     2.43136960316206, -0.28817388591814597, 0.24659688064192586),
    (2.9561705279185215, -1.4075394657208866, 2.480539907955195,
     -0.8679873580267703, -1.180981117766106, 2.395710664347914),
    (-2.730064447817266, 2.303762074792796, 2.059424684268012,
     2.4800664901287144, -2.7661266688773907, -1.6411328506132996),
)  # fmt: skip
#: Poses each labelling is probed on.
PROBES = len(PROBE_CONFIGS)
#: The labellings (start, reversed) in the order they are tried: the eight whose
#: elimination's constants are the arm's (made once), then the four with the target's
#: link at L1 or L2 (made for each target: a 14 x 8 SVD more a solve), which are the
#: well-posed ones where the eight degenerate (FANUC CRX, Kinova JACO 2).
LABELLINGS: tuple[tuple[int, bool], ...] = tuple(
    (start, reverse) for starts in (range(4), range(4, 6)) for reverse in (False, True)
    for start in starts
)  # fmt: skip
#: A labelling whose candidates hold the probe poses' configurations to this (rad; the
#: geometric mean of their distances, before Newton's step) is taken without scoring the
#: others: round-off for a well-posed elimination (generic arms: 1e-15..1e-13), where
#: the ranking could only trade one round-off for another; it saves seven labellings'
#: constants and probes (about 10 of a generic arm's 12 ms of building).
ACCURATE = 1e-12

#: Said of a target the elimination found nothing for (the core's not_found, its near
#: flag raised: no candidate within the check's polish, no reach gap), answered by the
#: numeric search.
SEARCH_NOTE = (
    "the general 6R elimination gave no candidate closing the loop for this target "
    "(the target at the workspace boundary, or its eigenproblem degenerate there): "
    "not proven unreachable; the numeric search answered"
)


def _class_label(cls: int, k: int) -> str:
    signs = [(cls >> 2) & 1, (cls >> 1) & 1, cls & 1]
    parts = [f"q{j} {'>' if s else '<'} 0" for j, s in zip((2, 3, 5), signs, strict=True)]
    return f"{', '.join(parts)} #{k + 1}"


#: Branch names of the candidate slots: the signs of q2, q3, q5 (wrapped to (-π, π]),
#: the members of a class numbered by increasing q1; then members beyond PER_CLASS.
LABELS: tuple[str, ...] = tuple(
    _class_label(c, k) for c in range(_G.CLASSES) for k in range(_G.PER_CLASS)
) + tuple(f"further solution #{k + 1}" for k in range(_G.FURTHER))


# ------------------------------------------------------------------ the loop
def _frame(z: FloatArray, origin: FloatArray) -> FloatArray:
    """A (4, 4) frame with z axis ``z`` at ``origin`` (x any unit normal)."""
    seed = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = cross3(z, seed)
    x /= np.linalg.norm(x)
    G = np.eye(4)
    G[:3, 0], G[:3, 1], G[:3, 2], G[:3, 3] = x, cross3(z, x), z, origin
    return G


def _foot(h: FloatArray, p: FloatArray, i: int, j: int) -> FloatArray:
    """The point of axis i nearest axis j (axis i's point when they are parallel)."""
    w = cross3(h[i], h[j])
    n2 = float(w @ w)
    if n2 < 1e-18:
        return p[i]
    t = float(cross3(p[j] - p[i], h[j]) @ w) / n2
    return p[i] + t * h[i]


def loop_of(chain: Chain, f: Features) -> tuple[list[FloatArray], FloatArray, float]:
    """``(K, G1, size)``: the arm as ``T(q) = G1 Rz(q1) K1 Rz(q2) K2 ... Rz(q6) K6``.

    G_i is a frame with z along axis i at q = 0 (base frame), K_i = G_i⁻¹ G_{i+1} and
    K6 = G6⁻¹ M (M the tool at q = 0): the product of exponentials
    ``Π G_i Rz(q_i) G_i⁻¹ · M`` regrouped. Origins at the feet of the common normals keep
    the numbers of the order of the arm's size.
    """
    h, p = f.directions, f.points
    G = [_frame(h[i], _foot(h, p, i, i + 1 if i < 5 else 4)) for i in range(6)]
    M = chain.fk(np.zeros(6))[0]
    K = [np.linalg.inv(G[i]) @ G[i + 1] for i in range(5)] + [np.linalg.inv(G[5]) @ M]
    return K, G[0], max(f.size, 1e-9)


def _scaled(A: FloatArray, scale: float) -> FloatArray:
    B = A.copy()
    B[:3, 3] *= scale
    return B


def elimination(L1: FloatArray, L2: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``(c0 (14,), Q (14, 8))``: the left side ``Rz(q'1) L1 Rz(q'2) L2 · z`` as c0 + Q S2.

    S2: the products of (1, cos q'1, sin q'1) ⊗ (1, cos q'2, sin q'2) but 1, in that
    order (c2, s2, c1, c1 c2, c1 s2, s1, s1 c2, s1 s2). The quantities are trigonometric
    polynomials of degree 1 in each angle (Raghavan-Roth): the core finds them exactly
    from their values on a 3 x 3 grid (``general_6r.hpp``, ``left_side``).
    """
    c0, Q = _G.left_side(L1, L2)
    return np.asarray(c0), np.asarray(Q)


def _labelling(
    K: list[FloatArray], G1: FloatArray, start: int, reverse: bool
) -> tuple[list[int], float, list[FloatArray | None], tuple[int, FloatArray, FloatArray]]:
    """``(order, sign, links (None: the target's), (power, pre, post))`` of one labelling.

    Forward: ``I = Rz(q1) K1 ... Rz(q6) [K6 T⁻¹ G1]``; reversed (q' = -q, joints 6..1):
    ``I = Rz(-q6) K5⁻¹ ... K1⁻¹ Rz(-q1) [G1⁻¹ T K6⁻¹]``; turned to start at joint
    ``start`` (0..5) of that order. Starts 4 and 5 put the target's link at L2 or L1:
    the elimination's constants are then the target's.
    """

    def inv(A: FloatArray) -> FloatArray:
        return np.asarray(np.linalg.inv(A), dtype=np.float64)

    if reverse:
        order, sign = [5, 4, 3, 2, 1, 0], -1.0
        links: list[FloatArray | None] = [inv(K[i]) for i in (4, 3, 2, 1, 0)] + [None]
        target = (1, inv(G1), inv(K[5]))
    else:
        order, sign = [0, 1, 2, 3, 4, 5], 1.0
        links = [K[i] for i in range(5)] + [None]
        target = (-1, K[5], G1)
    return order[start:] + order[:start], sign, links[start:] + links[:start], target


def _params(
    K: list[FloatArray], G1: FloatArray, size: float, start: int, reverse: bool
) -> tuple[Any, float] | None:
    """The core's Params of one labelling and its Q's σ8 / σ1, or None when rank-deficient.

    A labelling with the target's link at L1 or L2 has no constant Q (the core eliminates
    for each target, and refuses a target whose Q is rank-deficient): its ratio is NaN.
    """
    scale = 1.0 / size
    order, sign, links, (power, pre, post) = _labelling(K, G1, start, reverse)
    params = _G.General6RParams()
    params.link = np.stack([np.eye(4) if L is None else _scaled(L, scale) for L in links]).reshape(
        6, 16
    )
    params.t_link = next(k for k, L in enumerate(links) if L is None)
    params.t_power = power
    params.t_pre = _scaled(pre, scale)
    params.t_post = _scaled(post, scale)
    params.order = np.array(order, dtype=np.int64)
    params.sign = sign
    params.scale = scale
    ratio = math.nan if params.per_target else float(params.eliminate())
    if not (params.per_target or ratio > RANK_TOL):
        return None
    params.phi = np.array(PHI)
    params.centre = G1[:3, 3].copy()
    params.reach = float(sum(np.linalg.norm(k[:3, 3]) for k in K)) * (1.0 + 1e-12) + 1e-12
    return params, ratio


def _probe(params: Any, chain: Chain, refine: bool) -> FloatArray:
    """``(PROBES,)``: per probe pose, how far its configuration is from the candidates.

    The distance (rad) of the configuration that made the pose to the nearest candidate
    (inf: none), with Newton's step or (``refine`` False) as the eigenproblem gives them.
    """
    q = np.array(PROBE_CONFIGS)
    params.refine_misses = refine
    out = np.full(PROBES, math.inf)
    for i, T in enumerate(chain.fk(q)[0]):
        Q = params.candidates(chain.core, T)[0]
        d = np.abs(np.remainder(Q - q[i] + PI, 2.0 * PI) - PI).max(axis=1)
        if np.isfinite(d).any():
            out[i] = float(np.nanmin(d))
    params.refine_misses = True
    return out


def accuracy(params: Any, chain: Chain) -> tuple[float, float]:
    """How well a labelling's eigenproblem finds the probe poses' configurations.

    Returns:
        ``(score, worst)``: the mean of log10 of their distances (rad) to the nearest
        candidate before Newton's step, clipped to [1e-16, 1] (1: none found; lower is
        better), and the largest of those distances.
    """
    d = _probe(params, chain, refine=False)
    return float(np.mean(np.log10(np.clip(d, 1e-16, 1.0)))), float(d.max())


def build(chain: Chain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The general 6R solver of a 6R arm, or None (position targets; no labelling works).

    Tries the twelve labellings (forward, then reversed; each turned to start at joints
    1-4 of its order; then those starting at joints 5 and 6, whose elimination is made
    for each target) and keeps, of those whose elimination is well posed and whose
    candidates hold the generating configuration of every probe pose, the one whose
    eigenproblem is the most accurate on the probes. On an arm near one whose
    elimination degenerates (a calibrated UR5) the labellings' root errors differ by
    orders of magnitude, and the first that passes is often not the best (measured on
    30 calibrated UR5s, 200 poses each: 122 generating configurations missed with the
    first that passes, 9 with the most accurate, 8 of them at singular poses). The
    first labelling accurate to round-off (ACCURATE) that passes is kept at once; one
    whose every probe is within PROBE_TOL before Newton's step passes without the
    refined probes.
    """
    if target != "pose" or f.joint_types != "RRRRRR":
        return None
    K, G1, size = loop_of(chain, f)

    def passes(params: Any) -> bool:
        return bool(_probe(params, chain, refine=True).max() <= PROBE_TOL)

    ranked: list[tuple[float, int, Any]] = []
    for start, reverse in LABELLINGS:
        built = _params(K, G1, size, start, reverse)
        if built is None:
            continue
        score, worst = accuracy(built[0], chain)
        # every probe's configuration among the raw candidates to PROBE_TOL already:
        # Newton's step only takes a candidate nearer the solution it is near, so
        # the refined probes would pass too (tested on random arms)
        if score <= math.log10(ACCURATE) and (worst <= PROBE_TOL or passes(built[0])):
            return _closed_form(built[0])
        ranked.append((score, len(ranked), built[0]))
    for _, _, params in sorted(ranked, key=lambda r: r[:2]):
        if passes(params):
            return _closed_form(params)
    return None


def _closed_form(params: Any) -> ClosedForm:
    return ClosedForm(
        name="general-6R",
        labels=LABELS,
        params=params,
        exact=True,
        search_note=SEARCH_NOTE,
        mark_searched=functools.partial(mark_continua, params),
    )


# ------------------------------------------------------ continua of a search's answers
def free_joints(params: Any, T: FloatArray, q: FloatArray) -> tuple[int, ...]:
    """The joints free along the continuum of solutions through ``q``, or ``()``.

    The core's self-motion test (``general_6r.hpp``: the loop's Jacobian rank-deficient
    at q, a step along its null direction, the loop closed again with one joint held),
    the one the elimination's own candidates go through.

    Args:
        params: The arm's ``General6RParams``.
        T: ``(4, 4)`` the target (base frame, m).
        q: ``(6,)`` a solution of T (rad), e.g. the numeric search's.

    Returns:
        0-based indices of the free joints (ascending); ``()`` when q is regular, at a
        fold, or not a solution to within the loop's closure tolerance.
    """
    try:
        verdict, _, _, _, mask = _G.self_motion(params, T, q)
    except ValueError:  # q does not close the loop: no test
        return ()
    if _G.DEGENERACY[verdict] != "continuum":
        return ()
    return tuple(j for j in range(6) if (mask >> j) & 1)


def mark_continua(params: Any, poses: FloatArray, q: FloatArray, status: Any, free: Any) -> None:
    """Say ``singular`` where the numeric search's answer lies on a continuum (in place).

    The search answers the targets the elimination found nothing for (its candidates
    lost where the method degenerates, a continuum among them): a solution on a
    continuum is one point of infinitely many, so its status becomes singular and the
    joints free along it are named, as the closed form says of its own.

    Args:
        params: The arm's ``General6RParams``.
        poses: ``(k, 4, 4)`` the targets searched.
        q: ``(k, 6)`` the search's solution of each (NaN: none).
        status: ``(k,)`` int status codes, changed in place.
        free: ``(k, 6)`` bool free joints, changed in place.
    """
    solved, singular = _core.STATUS["ok"], _core.STATUS["singular"]
    for i in range(len(poses)):
        if int(status[i]) != solved or not np.isfinite(q[i]).all():
            continue
        joints = free_joints(params, poses[i], q[i])
        if joints:
            status[i] = singular
            free[i, list(joints)] = True


# ------------------------------------------------------------- sample arms
def _random_rows(rng: np.random.Generator) -> list[Revolute]:
    u = rng.uniform
    return [
        Revolute(d=u(-0.4, 0.4), a=u(-0.4, 0.4), alpha=u(-PI, PI), offset=u(-PI, PI))
        for _ in range(6)
    ]


#: The UR5's DH table (standard; m, rad), perturbed for the "calibrated UR" edge.
_UR5 = (
    (0.089159, 0.0, PI / 2),
    (0.0, -0.425, 0.0),
    (0.0, -0.39225, 0.0),
    (0.10915, 0.0, PI / 2),
    (0.09465, 0.0, -PI / 2),
    (0.0823, 0.0, 0.0),
)


#: The edges of the general family a degenerate sample arm is drawn from.
_EDGES = (
    "equal links",
    "offset 1e-10",
    "parallel 1e-9",
    "calibrated UR",
    "one common normal",
    "two pairs meet",
    "parallel pairs",
)


def _edge(rng: np.random.Generator) -> tuple[list[Revolute], str, bool]:
    """A 6R arm on an edge of the general family: ``(rows, what it is, standard)``.

    ``standard``: the rows are a real arm's table in the standard convention (a
    calibrated UR's), to be converted for Craig's; the others are random tables that
    serve either convention as they are.
    """
    u = rng.uniform
    edge = str(rng.choice(_EDGES))
    if edge in ("one common normal", "two pairs meet", "parallel pairs"):
        return _special(rng, edge), edge, False
    if edge == "calibrated UR":
        rows = [
            Revolute(d=d, a=a, alpha=al + 1e-3 * float(rng.choice([-1.0, 1.0])), offset=u(-PI, PI))
            for d, a, al in _UR5
        ]
        return rows, "UR5 with every twist 1e-3 off", True
    rows = _random_rows(rng)
    i = int(rng.integers(6))
    r = rows[i]
    if edge == "equal links":
        a, d = u(0.2, 0.4), u(0.1, 0.3)
        rows = [Revolute(d=d, a=a, alpha=x.alpha, offset=x.offset) for x in rows]
    elif edge == "offset 1e-10":
        rows[i] = Revolute(d=1e-10, a=1e-10, alpha=r.alpha, offset=r.offset)
        edge = f"joint {i + 1}: d = a = 1e-10"
    else:
        rows[i] = Revolute(
            d=r.d, a=r.a, alpha=1e-9 * float(rng.choice([-1.0, 1.0])), offset=r.offset
        )
        edge = f"axes {i + 1} and {i + 2} parallel but for 1e-9" if i < 5 else "alpha6 = 1e-9"
    return rows, edge, False


def _special(rng: np.random.Generator, edge: str) -> list[Revolute]:
    """A random table with the special axes of makers' cobots (FANUC CRX, Kinova JACO 2).

    "one common normal": every a but one 0 (consecutive axes meet), the twists right
    angles or random (the one beside the nonzero a may be 0 or π: a parallel pair, the
    CRX's 2 ∥ 3); "two pairs meet": two a's 0; "parallel pairs": one or two twists 0 or π
    (a pair of parallel axes anywhere).
    """
    rows = _random_rows(rng)
    u = rng.uniform
    a = [r.a for r in rows]
    alpha = [r.alpha for r in rows]
    if edge == "one common normal":
        k = int(rng.integers(6))
        a = [u(0.2, 0.6) if i == k else 0.0 for i in range(6)]
        for i in range(6):
            if rng.random() < 0.6:  # coaxial consecutive joints (a = 0, α = 0 or π) excluded
                alpha[i] = float(rng.choice([PI / 2, -PI / 2] + ([0.0, PI] if i == k else [])))
    elif edge == "two pairs meet":
        for i in rng.choice(6, 2, replace=False):
            a[int(i)] = 0.0
    else:
        for i in rng.choice(6, int(rng.integers(1, 3)), replace=False):
            alpha[int(i)] = float(rng.choice([0.0, PI]))
            a[int(i)] = u(0.1, 0.4)
    return [Revolute(d=r.d, a=a[i], alpha=alpha[i], offset=r.offset) for i, r in enumerate(rows)]


def sample_arm(rng: np.random.Generator, degenerate: bool) -> ArmSample:
    """A random 6R arm of general geometry (an edge case with ``degenerate``)."""
    rows, note, standard = _edge(rng) if degenerate else (_random_rows(rng), "", False)
    modified = str(rng.choice(["standard", "modified"])) == "modified"
    base, tool = random_transform(rng, 0.5), random_transform(rng, 0.2)
    links: tuple[Joint, ...] = tuple(rows)
    if modified and standard:  # the same arm, its table in Craig's convention
        links, b, t = convert_table(links, "standard", "modified", np.eye(4), np.eye(4))
        base, tool = base @ b, t @ tool
    return ArmSample(
        links=links,
        convention="modified" if modified else "standard",
        base=base,
        tool=tool,
        note=note,
    )


SPEC = SolverSpec(
    kind="general-6R",
    summary="6R, general geometry",
    summary_es="6R de geometría general",
    handles=lambda f: f.joint_types == "RRRRRR",
    build=build,
    sample_arm=sample_arm,
)
