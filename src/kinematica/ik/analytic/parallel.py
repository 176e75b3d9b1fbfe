"""Builder of the closed-form IK of 6R arms with axes 2, 3, 4 parallel (UR type).

Once per arm, from its joint axes at q = 0 (:class:`Features`) and its tool
pose ``M = fk(0)``, this packs the parameters of the kernel
:mod:`kinematica.kernels.solvers.parallel` (where the method is described):
the vectors and constants of equations (1) and (2) in ``(q1, q5)``, the planar
triangle axis 2 -> 3 -> 4, a proven reach bound, and the arm's mode: axes 5
and 6 meeting (every UR and its clones), parallel, or apart (a5 != 0: the
quartic). Up to 8 solutions, exact, for any link values, offsets, twists,
base, tool and DH convention.

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

from kinematica.dh import DHChain
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import MEET_TOL, Features, line_distance, lines_parallel
from kinematica.kernels import fk
from kinematica.kernels.solvers import parallel as kernel
from kinematica.kernels.solvers import parallel_layout as layout

__all__ = ["GENERAL_LABELS", "LABELS", "SPEC", "build", "pack"]

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


def _feet(
    h1: FloatArray, p1: FloatArray, h2: FloatArray, p2: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """The feet on line 1 and line 2 of their common normal (non-parallel lines)."""
    d = p2 - p1
    b = float(h1 @ h2)
    den = 1.0 - b * b
    s = (d @ h1 - b * (d @ h2)) / den
    t = (b * (d @ h1) - d @ h2) / den
    return p1 + s * h1, p2 + t * h2


def _project(x: FloatArray, h: FloatArray, p: FloatArray) -> FloatArray:
    """The point of the line ``p + t h`` closest to ``x``."""
    return np.asarray(p + ((x - p) @ h) * h, dtype=float)


def _angle(u: FloatArray, v: FloatArray) -> float:
    """Angle between unit vectors (accurate near 0 and π)."""
    return math.atan2(float(np.linalg.norm(np.cross(u, v))), float(u @ v))


def _middle(lo: float, hi: float) -> float:
    return 0.5 * (lo + hi) if math.isfinite(lo) and math.isfinite(hi) else 0.0


def pack(chain: DHChain, features: Features) -> tuple[FloatArray, int] | None:
    """The kernel's parameters for an arm, and its mode; ``None`` if declined.

    Args:
        chain: A 6R chain whose axes 2, 3, 4 are parallel.
        features: Its joint axes at q = 0.

    Returns:
        ``(params (P_SIZE,), mode)`` with ``mode`` one of ``MODE_MEET``,
        ``MODE_PARALLEL``, ``MODE_GENERAL``; ``None`` for the arms the module
        docstring lists.
    """
    h = np.array(features.directions, dtype=float)
    p = np.array(features.points, dtype=float)
    k = _unit(h[1])
    h1, h5, h6 = h[0], h[4], h[5]
    if lines_parallel(h1, k) or lines_parallel(h5, k):
        return None
    e1 = _unit(np.cross(k, [1.0, 0.0, 0.0] if abs(k[0]) < 0.9 else [0.0, 1.0, 0.0]))
    e2 = np.cross(k, e1)

    def plane(x: FloatArray) -> FloatArray:
        return np.array([x @ e1, x @ e2])

    zA, zB = (complex(*plane(x)) for x in (p[2] - p[1], p[3] - p[2]))
    if min(abs(zA), abs(zB)) <= layout.CONTINUUM_TOL * (abs(zA) + abs(zB)):
        return None
    if lines_parallel(h5, h6):
        if line_distance(h5, p[4], h6, p[5]) < MEET_TOL:
            return None
        mode, p5 = layout.MODE_PARALLEL, p[4]
        p6 = _project(p5, h6, p[5])
    else:
        p5, p6 = _feet(h5, p[4], h6, p[5])
        mode = layout.MODE_GENERAL
        if np.linalg.norm(p6 - p5) < MEET_TOL:
            mode = layout.MODE_MEET
            p5 = p6 = 0.5 * (p5 + p6)
    h6par = (h5 @ h6) * h5
    h6perp = h6 - h6par
    h5x6 = np.cross(h5, h6)
    z = p6 - p5
    eq1 = np.array([k @ h6perp, k @ h5x6, (k @ h5) * (h5 @ h6)])
    eq2 = np.array(
        [k @ (z - (h5 @ z) * h5), k @ np.cross(h5, z), (k @ h5) * (h5 @ z) + k @ (p5 - p[0])]
    )
    minv = np.zeros(4)
    if mode == layout.MODE_MEET:
        eq2[:2] = 0.0
    elif mode == layout.MODE_PARALLEL:
        eq1 = np.array([0.0, 0.0, (k @ h5) * math.copysign(1.0, h5 @ h6)])
    else:
        minv = np.linalg.inv(np.array([eq1[:2], eq2[:2]])).ravel()
    alpha, beta = _angle(k, h5), _angle(h6, h5)
    # reach: |G(a6) - p1s| <= the length of the chain of feet p1s, a2, ..., a6
    p1s, a = _feet(h1, p[0], k, p[1])
    bound = float(np.linalg.norm(a - p1s))
    for i in (2, 3, 4, 5):
        nxt = _project(a, h[i], p[i])
        bound += float(np.linalg.norm(nxt - a))
        a = nxt
    M, _, _ = fk(chain, np.zeros(6))
    kpar = (h1 @ k) * h1
    vectors = [
        k, h1, p[0], kpar, k - kpar, np.cross(h1, k), h5, p5, h6, p6, h6par, h6perp, h5x6,
        p[1], p[3], e1, e2, *M[:3, :3], M[:3, 3], p1s, a,
    ]  # fmt: skip
    scalars = [
        mode, *eq1, *eq2, *minv,
        2.0 * math.sin(0.5 * (alpha - beta)) ** 2, 2.0 * math.cos(0.5 * (alpha + beta)) ** 2,
        *np.abs([zA, zB]), *np.angle([zA, zB]), *plane(np.cross(h1, k)),
        math.copysign(1.0, h[2] @ k), math.copysign(1.0, h[3] @ k),
        bound, abs(h1 @ k) + float(np.linalg.norm(k - kpar)), bound,
        _middle(*chain.qlim[0]), _middle(*chain.qlim[1]),
    ]  # fmt: skip
    params = np.concatenate([np.ravel(vectors), scalars]).astype(float)
    assert params.shape == (layout.P_SIZE,)
    return params, mode


def build(chain: DHChain, features: Features, target: TargetKind) -> ClosedForm | None:
    """The closed-form solver of a UR-type arm for pose targets, or ``None``."""
    if target != "pose":
        return None
    packed = pack(chain, features)
    if packed is None:
        return None
    params, mode = packed
    return ClosedForm(
        name="three-parallel-6R",
        labels=LABELS if mode == layout.MODE_MEET else GENERAL_LABELS,
        params=params,
        solve_one=kernel.solve,
        solve_batch=kernel.solve_batch,
    )


SPEC = SolverSpec(
    kind="three-parallel-6R",
    summary="6R, three parallel axes (2-3-4), UR type",
    handles=lambda f: f.joint_types == "RRRRRR" and {(1, 2), (2, 3)} <= set(f.parallel),
    build=build,
)
