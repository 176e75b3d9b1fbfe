"""6R arms of rank 5 at every configuration: their structure, read from the joint axes.

Some 6R arms cannot move their tool in six independent directions anywhere: their
Jacobian has rank 5 at every configuration (intrinsically degenerate arms). They reach
a five-dimensional set of poses, each along a one-dimensional continuum of
configurations (a self-motion), and no elimination of the general 6R applies to them.
Besides the coaxial pair (:mod:`kinematica.ik.coaxial_pair`, answered on its own),
the axes that make one:

- **four concurrent axes**: four consecutive axes through one point turn the links
  after them about that point with three degrees of freedom, not four;
- **four parallel axes**: four consecutive parallel axes move the links after them
  in a plane with three degrees of freedom, not four;
- **a spherical shoulder and a spherical wrist** (axes 1-3 meet at S, 4-6 at W): the
  distance SW is fixed, and the middle link turns freely about the line SW;
- **three parallel axes and three concurrent ones** (axes 1-3 parallel, 4-6 meeting at
  W, or the reverse): W moves in a plane normal to the parallel axes (two degrees of
  freedom), the wrist turns the tool about it (three).

The test that decides is the Jacobian's rank at :data:`RANK_SAMPLES` random
configurations (lengths in units of the arm's size, :func:`rank_size`): σ6 / σ1 at most
:data:`RANK_EXACT_TOL` at every one of them. The structure read from the axes only
names the free motion for the answer's note; an arm of rank 5 whose axes match none of
the above is still answered (its structure unnamed), and so is one of rank 4 or less
(five parallel axes): its continua have more dimensions, and its answers name every
joint that moves along them.

An arm whose ratio stays below :data:`RANK_NEAR_TOL` everywhere, but not below the
exact tolerance, is *near* one of these: its solutions are isolated but ill-conditioned
at every pose, and the elimination may lose some (:func:`rank_five` says so: ``exact``
False).
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.dh.lines import common_point
from kinematica.ik.coaxial_pair import coaxial_pair
from kinematica.ik.structure import Features, features

__all__ = [
    "FREE_TOL",
    "HELD_PROBES",
    "RANK_EXACT_TOL",
    "RANK_FIVE_HELD",
    "RANK_NEAR_TOL",
    "RANK_SAMPLES",
    "RANK_SEED",
    "RankFive",
    "free_motion",
    "held_rank_five",
    "rank_five",
    "rank_size",
    "relative_sigma",
    "scaled_jacobian",
]

FloatArray = NDArray[np.float64]

#: Random configurations the rank is measured at.
RANK_SAMPLES = 8
#: Their seed (the same verdict for the same arm, every call).
RANK_SEED = 5
#: The arm has rank 5 everywhere when σ6 / σ1 of its Jacobian (lengths in units of the
#: arm's size) is at most this at every sample. Round-off leaves a few 1e-16 on an exact
#: arm (up to 4e-15 on 300 random ones); an arm moved off its structure by ε has a ratio
#: of about ε (relative), so arms moved by 1e-12 and more are not taken as exact.
RANK_EXACT_TOL = 1e-13
#: Near such an arm: the ratio at most this at every sample (and above the exact one).
#: Arms whose ratio stays below it had their solutions missed by the general 6R's
#: elimination and the search alike (81 of 210 poses); above it, none of 390.
RANK_NEAR_TOL = 1e-5
#: A joint moves along the self-motion when its share of the Jacobian's null direction
#: (unit) is above this.
FREE_TOL = 1e-6
#: The values a held joint is measured at (:func:`held_rank_five`), rad or m: generic
#: (a straight elbow, 0, lines axes up).
HELD_PROBES = (1.0, -2.0)
#: The memo key marking an arm left by a held joint as of rank 5 at every configuration
#: whatever the value held (:func:`held_rank_five`; set by
#: :func:`kinematica.ik.moved.locked_chain`): no elimination of the general 6R applies to
#: it (its builder declines every exact rank-5 arm: each pose it reaches, a continuum),
#: and the builder is not tried.
RANK_FIVE_HELD = "rank 5 at every value held"


@dataclass(frozen=True, slots=True)
class RankFive:
    """A 6R arm of rank 5 at every configuration, or near one.

    Attributes:
        structure: The axes that make it so, in words (``"axes 1-4 meet at one point"``),
            or words saying none was named.
        kind: ``"four-concurrent"``, ``"four-parallel"``, ``"shoulder-wrist"``,
            ``"parallel-concurrent"`` or ``"rank-5"``.
        exact: True when σ6 / σ1 is at most :data:`RANK_EXACT_TOL` at every sample (a
            continuum at every pose); False for an arm only near one.
        ratio: The largest σ6 / σ1 over the samples.
        rank: The rank at a generic configuration (5; 4 or less where more singular values
            than σ6 are below the tolerance at every sample, e.g. five parallel axes).
        groups: The axes of the structure named, as ``(first, stop)`` index ranges
            (0-based; ``((0, 3), (3, 6))`` for a spherical shoulder and wrist); ``()``
            when none was named.
    """

    structure: str
    kind: str
    exact: bool
    ratio: float
    rank: int = 5
    groups: tuple[tuple[int, int], ...] = ()


def rank_size(chain: Chain) -> float:
    """The arm's size (m) the rank is measured in: :func:`~kinematica.ik.structure.arm_size`.

    Measured along the axes where the frames wander far from them (a DH table of nearly
    parallel axes puts frames at the foot of their common normal: the Kinova Gen3 Lite's
    ``to_dh()``, 38 km off, 76 km of frames for an arm of 0.85 m): in units of the
    frames' size the arm's Jacobian is of rank 3 to 6e-7, in units of its own not.
    """
    return features(chain).size


def scaled_jacobian(chain: Chain, q: FloatArray) -> FloatArray:
    """``(..., 6, 6)`` the Jacobian at ``q (..., 6)``, its lengths in units of :func:`rank_size`."""
    size = max(rank_size(chain), 1e-300)
    J = np.array(chain.jacobian(np.ascontiguousarray(q, dtype=np.float64))[0])
    J[..., :3, :] /= size
    return J


def relative_sigma(chain: Chain, q: FloatArray) -> FloatArray:
    """``(...)`` σ6 / σ1 of the Jacobian at ``q (..., 6)`` (:func:`scaled_jacobian`)."""
    s = np.linalg.svd(scaled_jacobian(chain, q), compute_uv=False)
    return np.asarray(s[..., -1] / s[..., 0])


def free_motion(chain: Chain, q: FloatArray, rank: int = 5) -> FloatArray:
    """``(6,)`` each joint's share of the Jacobian's null space at ``q (6,)``.

    The null space of dimension ``6 - rank`` (the last right singular vectors of
    :func:`scaled_jacobian`): the norm of each joint's row of its orthonormal basis.
    """
    basis = np.linalg.svd(scaled_jacobian(chain, q))[2][rank:]
    return np.asarray(np.linalg.norm(basis, axis=0))


_FOUND: weakref.WeakKeyDictionary[Chain, RankFive | None] = weakref.WeakKeyDictionary()


def rank_five(chain: Chain) -> RankFive | None:
    """The rank-5 structure of a 6R arm (exact, or near), or None (a coaxial pair: None).

    Measured once per chain (:data:`RANK_SAMPLES` configurations).
    """
    if chain in _FOUND:
        return _FOUND[chain]
    found = None
    if chain.dof == 6 and not bool(chain.prismatic.any()) and coaxial_pair(chain) is None:
        Q = np.random.default_rng(RANK_SEED).uniform(-math.pi, math.pi, (RANK_SAMPLES, 6))
        s = np.linalg.svd(scaled_jacobian(chain, Q), compute_uv=False)
        worst = np.max(s / s[:, :1], axis=0)  # each σ_i / σ1's largest over the samples
        ratio = float(worst[-1])
        if ratio <= RANK_NEAR_TOL:
            kind, words, groups = _structure(features(chain))
            exact = ratio <= RANK_EXACT_TOL
            rank = int(np.count_nonzero(worst > (RANK_EXACT_TOL if exact else RANK_NEAR_TOL)))
            found = RankFive(words, kind, exact, ratio, rank, groups)
    _FOUND[chain] = found
    return found


def held_rank_five(chain: Chain, joint: int) -> RankFive | None:
    """The exact rank-5 structure of the 6R arm ``chain`` leaves with ``joint`` held at any value.

    Holding a joint moves the axes after it rigidly (a turn about its axis, or a slide
    along it) and keeps those before it: a relation among axes all on one side of it
    (three or four through one point, four parallel) holds at every value. The arm
    left at 0 is measured (:func:`rank_five`); when it is exactly of rank 5 and each
    group of axes its named structure holds among lies on one side of the held joint,
    that structure, hence rank 5 at every configuration, holds at every value held
    (an SRS arm with its elbow held: a spherical shoulder and wrist). Read once per
    chain and joint, at the values :data:`HELD_PROBES` (both must agree; a value where
    more axes line up by accident, e.g. an elbow stretched straight, only says None).

    Args:
        chain: A 7R arm (other arms: None).
        joint: The held joint (0-based).

    Returns:
        The arm left's structure at the first probe, or None (not of rank 5 there, near one only,
        no structure named, or a group straddling the held joint).
    """
    per: dict[int, RankFive | None]
    per = chain.memo.setdefault("held rank five", {})  # type: ignore[assignment]
    if joint not in per:
        found = None
        if chain.dof == 7 and not bool(chain.prismatic.any()):
            fives = [rank_five(chain.locked(joint, v)) for v in HELD_PROBES]
            if all(f is not None and f.exact and f.groups for f in fives):
                sides = [b <= joint or a >= joint for f in fives for a, b in f.groups]  # type: ignore[union-attr]
                found = fives[0] if all(sides) else None
        per[joint] = found
    return per[joint]


def _structure(f: Features) -> tuple[str, str, tuple[tuple[int, int], ...]]:
    """``(kind, words, groups)``: which axes make the arm's rank 5 (the first structure matched).

    ``groups``: the index ranges ``(first, stop)`` of the axes each relation holds among.
    """
    h, p, size = f.directions, f.points, f.size
    for i in range(3):
        if (
            not f.all_parallel(range(i, i + 4))
            and common_point(h[i : i + 4], p[i : i + 4], size) is not None
        ):
            return "four-concurrent", f"axes {i + 1}-{i + 4} meet at one point", ((i, i + 4),)
    for i in range(3):
        if f.all_parallel(range(i, i + 4)):
            return "four-parallel", f"axes {i + 1}-{i + 4} are parallel", ((i, i + 4),)
    if f.shoulder_center is not None and f.wrist_center is not None:
        return (
            "shoulder-wrist",
            (
                "a spherical shoulder (axes 1-3 meet) and a spherical wrist (axes 4-6 meet) at a "
                "fixed distance: the middle link turns freely about the line through both centres"
            ),
            _HALVES,
        )
    if f.all_parallel(range(3)) and f.wrist_center is not None:
        return (
            "parallel-concurrent",
            ("axes 1-3 are parallel and axes 4-6 meet: the wrist centre moves in a plane"),
            _HALVES,
        )
    if f.shoulder_center is not None and f.all_parallel(range(3, 6)):
        return (
            "parallel-concurrent",
            (
                "axes 1-3 meet and axes 4-6 are parallel: seen from the tool, the shoulder "
                "centre moves in a plane"
            ),
            _HALVES,
        )
    return "rank-5", "no structure named (the Jacobian's rank measured)", ()


#: The two triples of axes a spherical shoulder and wrist (or a parallel triple) hold among.
_HALVES = ((0, 3), (3, 6))
