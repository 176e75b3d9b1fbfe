"""Which parameters the measurements can determine, which they cannot, and why.

The identification Jacobian ``J`` (scaled residuals by parameters, m and rad) has its
columns normalised to unit length (a parameter's unit then does not matter) and is read
by its singular values: the rank is the number above :data:`RANK_RTOL` times the
largest. A basis of parameters is chosen in a fixed order of preference (the base's six,
the tool's six, then each joint's θ, d, a, α, then the β and y twists, see
:data:`PREFERENCE`): a parameter joins when the part of its column that the parameters
chosen before it cannot explain (Gram-Schmidt in that order) is above the same
tolerance. Each parameter left out is written as a combination of the chosen ones (least
squares over the columns): those it moves the tool like are its reason. The
observability indices of the chosen columns are Sun and Hollerbach's (Observability
index selection for robot calibration, ICRA 2008): O1 (Borm and Menq's geometric mean
of the singular values over √m), O2 (the inverse condition number), O3 (the smallest
singular value), O4 (σ_min²/σ_max, the noise amplification index) and O5 (1/Σ 1/σ_i).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "CORRELATION_LIMIT",
    "RANK_RTOL",
    "REASON_SHARE",
    "Finding",
    "Identification",
    "correlated_pairs",
    "identify",
    "preference",
]

FloatArray = NDArray[np.float64]

#: A singular value of the column-normalised identification Jacobian below this times the
#: largest is a direction the measurements cannot see. The structural redundancies of the
#: error model sit at round-off (1e-15 relative); a parameter the poses do determine, at
#: 1e-4 or above on the built-in arms with 30 poses.
RANK_RTOL = 1e-8
#: A parameter left out is said to move the tool like those chosen parameters whose
#: coefficient in its combination is at least this share of the largest one.
REASON_SHARE = 0.1
#: Two identified parameters whose estimates correlate beyond this (absolute value) are
#: reported as a correlated pair: the data tells their sum or difference far better.
CORRELATION_LIMIT = 0.9
#: The order of preference of the blocks' components when a basis is chosen: base, tool,
#: then each link's DH values, then Hayati's β and the y offset (indices into a block).
PREFERENCE = ((5, 2, 0, 3), (4,), (1,))


def preference(dof: int) -> list[int]:
    """Parameter indices in the order a basis is chosen (see :data:`PREFERENCE`)."""
    order = list(range(6)) + list(range(6 * dof + 6, 6 * dof + 12))
    for group in PREFERENCE:
        order += [6 * (i + 1) + c for i in range(dof) for c in group]
    return order


@dataclass(frozen=True)
class Finding:
    """A parameter the measurements cannot determine, and why.

    Attributes:
        name: The parameter.
        partners: The chosen parameters it moves the tool like (empty when it
            does not move the tool at all).
        structural: True when no set of measurements of this kind could tell it
            apart (the model's own redundancy); False when these measurements
            cannot, but more varied ones could.
    """

    name: str
    partners: tuple[str, ...]
    structural: bool


@dataclass(frozen=True)
class Identification:
    """What a Jacobian says about its parameters.

    Attributes:
        rank: Singular values above ``RANK_RTOL`` times the largest.
        chosen: ``(r,)`` indices of the parameters chosen as a basis.
        left_out: The parameters left out, each with its reason.
        singular_values: ``(r,)`` of the chosen columns (normalised), largest first.
    """

    rank: int
    chosen: NDArray[np.intp]
    left_out: tuple[Finding, ...]
    singular_values: FloatArray

    @property
    def condition(self) -> float:
        """The chosen columns' condition number σ_max / σ_min."""
        return float(self.singular_values[0] / self.singular_values[-1])

    def observability(self, measurements: int) -> dict[str, float]:
        """Sun and Hollerbach's indices O1..O5 of the chosen columns (module docstring)."""
        s = self.singular_values
        return {
            "O1": float(np.exp(np.mean(np.log(s))) / np.sqrt(measurements)),
            "O2": float(s[-1] / s[0]),
            "O3": float(s[-1]),
            "O4": float(s[-1] ** 2 / s[0]),
            "O5": float(1.0 / np.sum(1.0 / s)),
        }


def identify(
    J: FloatArray,
    names: tuple[str, ...],
    order: list[int],
    candidates: NDArray[np.intp] | None = None,
    generic: NDArray[np.intp] | None = None,
) -> Identification:
    """Rank, basis and reasons of an identification Jacobian.

    Args:
        J: ``(rows, p)`` the Jacobian of the scaled residuals.
        names: ``(p,)`` the parameters' names.
        order: The parameters in order of preference (:func:`preference`).
        candidates: The parameters that may be chosen (default all); the others are
            held at their nominal values and not reported.
        generic: The parameters a rich set of measurements of the same kind would
            choose, to tell a structural redundancy from a lack of data (default:
            every one left out is called structural).

    Returns:
        The :class:`Identification`.
    """
    allowed = set(range(J.shape[1]) if candidates is None else (int(c) for c in candidates))
    norms = np.linalg.norm(J, axis=0)
    biggest = float(norms.max()) if norms.size else 0.0
    moving = norms > RANK_RTOL * biggest
    A = J / np.where(moving, norms, 1.0)
    A[:, ~moving] = 0.0
    cols = [j for j in order if j in allowed]
    R = np.asarray(np.linalg.qr(A[:, cols], mode="r") if cols else np.zeros((0, 0)), dtype=float)
    position = {j: k for k, j in enumerate(cols)}
    s_all = np.linalg.svd(R, compute_uv=False) if cols else np.zeros(0)
    top = float(s_all[0]) if s_all.size else 0.0
    rank = int(np.sum(s_all > RANK_RTOL * top))
    # Gram-Schmidt in the order of preference over the columns of R (the geometry of A's
    # columns): a column joins when the part the chosen ones cannot explain is above the
    # tolerance; a column left out adds no direction (a plain QR's R_kk would: a left-out
    # column gets an arbitrary direction there, which hides the next columns' parts)
    chosen: list[int] = []
    Q = np.zeros((R.shape[0], 0))
    for k, j in enumerate(cols):
        if not moving[j]:
            continue
        v = R[:, k] - Q @ (Q.T @ R[:, k])
        v = v - Q @ (Q.T @ v)  # twice is enough (Kahan-Parlett)
        size = float(np.linalg.norm(v))
        if size > RANK_RTOL * top:
            chosen.append(j)
            Q = np.column_stack([Q, v / size])
    basis = R[:, [position[k] for k in chosen]]
    s: FloatArray = np.linalg.svd(basis, compute_uv=False) if chosen else np.zeros(0)
    generic_set = None if generic is None else {int(g) for g in generic}
    out = [j for j in cols if j not in set(chosen)]
    # least squares over the columns of A = Q R is least squares over those of R
    combos = np.zeros((len(chosen), len(out)))
    if chosen and out:
        combos = np.linalg.lstsq(basis, R[:, [position[j] for j in out]], rcond=None)[0]
    left_out = []
    for k, j in enumerate(out):
        partners: tuple[str, ...] = ()
        c = combos[:, k]
        if moving[j] and chosen and np.abs(c).max() > 0.0:
            keep = np.abs(c) >= REASON_SHARE * np.abs(c).max()
            partners = tuple(names[chosen[i]] for i in np.flatnonzero(keep))
        structural = generic_set is None or j not in generic_set
        left_out.append(Finding(names[j], partners, structural))
    return Identification(rank, np.array(chosen, dtype=np.intp), tuple(left_out), s)


def correlated_pairs(
    covariance: FloatArray, names: tuple[str, ...]
) -> tuple[tuple[str, str, float], ...]:
    """The pairs whose correlation exceeds :data:`CORRELATION_LIMIT` in absolute value.

    Args:
        covariance: ``(r, r)`` the estimates' covariance.
        names: ``(r,)`` their names.

    Returns:
        ``(name_a, name_b, correlation)`` triples, strongest first.
    """
    sd = np.sqrt(np.diag(covariance))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = covariance / np.outer(sd, sd)
    pairs = [
        (names[a], names[b], float(corr[a, b]))
        for a in range(len(names))
        for b in range(a + 1, len(names))
        if abs(corr[a, b]) > CORRELATION_LIMIT
    ]
    return tuple(sorted(pairs, key=lambda t: -abs(t[2])))
