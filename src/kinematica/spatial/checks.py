"""Validation of rotations and homogeneous transforms at the public boundary.

Every public function of :mod:`kinematica.spatial` turns its array arguments
into float arrays through :func:`as_batch_array`, which checks the trailing
shape and finiteness and names the offending batch element. The stricter
:func:`check_rotation` and :func:`check_transform` also check that a matrix
really is a rotation (orthonormal, det +1) or a rigid transform.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError

__all__ = [
    "ORTHONORMAL_TOL",
    "as_batch_array",
    "as_float_array",
    "check_rotation",
    "check_transform",
    "nearest_rotation",
    "orthonormality_error",
    "orthonormalize",
]

FloatArray = NDArray[np.float64]

# Largest accepted max|RᵀR − I| (and deviation of the last row of a transform
# from [0, 0, 0, 1]). Matrices computed by forward kinematics are orthonormal to
# ~1e-15; 1e-6 still accepts matrices written out with about seven significant
# digits, while catching scaled, sheared, transposed-by-mistake or mistyped ones.
ORTHONORMAL_TOL = 1e-6

#: max|RᵀR − I| of a rotation computed in double precision (a product of a few
#: rotations is orthonormal to ~1e-15): up to this a matrix is a rotation as it
#: stands; beyond it, it was written with few digits and
#: :func:`orthonormalize` replaces it by the nearest rotation.
ROUNDOFF_TOL = 1e-14


def _where(name: str, index: tuple[int, ...]) -> str:
    """``"T"`` for an unbatched array, ``"T[2, 0]"`` for a batch element."""
    return f"{name}[{', '.join(str(i) for i in index)}]" if index else name


def _first(mask: NDArray[np.bool_]) -> tuple[int, ...]:
    """Batch index of the first ``True`` in ``mask`` (which has at least one)."""
    return tuple(int(i) for i in np.argwhere(mask)[0]) if mask.ndim else ()


def first_bad(name: str, mask: NDArray[np.bool_]) -> str:
    """Name of the first batch element flagged in ``mask``, e.g. ``"q[3]"``."""
    return _where(name, _first(mask))


def as_float_array(x: ArrayLike, name: str, tail: tuple[int, ...] = ()) -> FloatArray:
    """Convert ``x`` to a float array of shape ``(..., *tail)``; NaN and inf pass through.

    For the elementary operations (rotations about an axis, products of
    transforms), where a NaN in is a NaN out, as in numpy.

    Raises:
        DimensionError: ``x`` is not numeric, or has the wrong trailing shape.
    """
    try:
        raw = np.asarray(x)
    except (TypeError, ValueError) as exc:  # ragged nested lists, say
        raise DimensionError(f"{name} must be an array of numbers: {exc}") from None
    if raw.dtype.kind not in "biuf":  # None, text, objects, complex numbers
        shown = repr(x) if len(repr(x)) <= 60 else repr(x)[:57] + "..."
        raise DimensionError(f"{name} must be an array of numbers, got {shown}")
    a = raw.astype(np.float64, copy=False)
    if a.ndim < len(tail) or a.shape[a.ndim - len(tail) :] != tail:
        expected = ", ".join(["..."] + [str(n) for n in tail])
        raise DimensionError(f"{name} must have shape ({expected}), got {a.shape}")
    return a


def as_batch_array(x: ArrayLike, name: str, tail: tuple[int, ...]) -> FloatArray:
    """Convert ``x`` to a float array of shape ``(..., *tail)`` with finite entries.

    Args:
        x: The array-like to check.
        name: Its name in messages, e.g. ``"T"`` or ``"angles"``.
        tail: The required trailing shape, e.g. ``(4, 4)``; ``()`` for scalars.

    Returns:
        ``x`` as a float64 array (not copied when it already is one).

    Raises:
        DimensionError: ``x`` is not numeric, has the wrong trailing shape, or
            holds NaN or inf (the message names the first bad batch element).
    """
    a = as_float_array(x, name, tail)
    finite = np.isfinite(a)
    if not finite.all():
        bad = np.asarray(~finite.reshape(*a.shape[: a.ndim - len(tail)], -1).all(axis=-1))
        raise DimensionError(f"{first_bad(name, bad)} contains NaN or inf")
    return a


def shown_above(value: float, limit: float) -> str:
    """``value`` (> ``limit``) printed with the fewest digits that show it exceeds ``limit``.

    ``1.04e-4`` against ``1e-4`` prints ``1.04e-04``, never ``1.0e-04``, which
    would read as equal to the limit it is said to exceed.
    """
    shown_limit = float(f"{limit:.0e}")
    for digits in range(1, 17):
        text = f"{value:.{digits}e}"
        if float(text) > shown_limit:
            return text
    return repr(value)


def _check_orthonormal(R: FloatArray, name: str, tol: float) -> None:
    """Raise unless every ``(..., 3, 3)`` block of ``R`` is a rotation within ``tol``."""
    gram = np.swapaxes(R, -1, -2) @ R
    err = np.abs(gram - np.eye(3)).max(axis=(-1, -2))
    bad = err > tol
    if bad.any():
        i = _first(bad)
        raise DimensionError(
            f"{_where(name, i)} rotation is not orthonormal: "
            f"max |RᵀR − I| = {shown_above(float(err[i]), tol)} (tolerance {tol:.0e})"
        )
    det = np.linalg.det(R)
    bad = det < 0.0
    if bad.any():
        i = _first(bad)
        raise DimensionError(
            f"{_where(name, i)} rotation has det = {det[i]:+.3f}, expected +1 "
            "(it is a reflection, not a rotation)"
        )


def check_rotation(R: ArrayLike, name: str = "R", tol: float = ORTHONORMAL_TOL) -> FloatArray:
    """Validate a batch of rotation matrices.

    Args:
        R: Rotations, shape ``(..., 3, 3)``.
        name: Name used in error messages.
        tol: Largest accepted ``max|RᵀR − I|``.

    Returns:
        ``R`` as a float64 array of shape ``(..., 3, 3)``.

    Raises:
        DimensionError: Wrong shape, NaN/inf, not orthonormal within ``tol``, or
            det −1; the message names the first offending batch element.
    """
    Ra = as_batch_array(R, name, (3, 3))
    _check_orthonormal(Ra, name, tol)
    return Ra


def check_transform(T: ArrayLike, name: str = "T", tol: float = ORTHONORMAL_TOL) -> FloatArray:
    """Validate a batch of homogeneous (rigid-body) transforms.

    Args:
        T: Transforms, shape ``(..., 4, 4)``; translations in metres.
        name: Name used in error messages.
        tol: Largest accepted ``max|RᵀR − I|`` of the rotation block, and largest
            accepted deviation of the last row from ``[0, 0, 0, 1]``.

    Returns:
        ``T`` as a float64 array of shape ``(..., 4, 4)``.

    Raises:
        DimensionError: Wrong shape, NaN/inf, a last row other than
            ``[0, 0, 0, 1]``, or a rotation block that is not a rotation; the
            message names the first offending batch element.
    """
    Ta = as_batch_array(T, name, (4, 4))
    row_err = np.abs(Ta[..., 3, :] - [0.0, 0.0, 0.0, 1.0]).max(axis=-1)
    bad = row_err > tol
    if bad.any():
        i = _first(bad)
        raise DimensionError(
            f"{_where(name, i)} last row must be [0, 0, 0, 1], got {Ta[(*i, 3)].tolist()}"
        )
    _check_orthonormal(Ta[..., :3, :3], name, tol)
    return Ta


def nearest_rotation(R: ArrayLike) -> FloatArray:
    """The rotation nearest to each ``(..., 3, 3)`` matrix (Frobenius norm).

    ``U Vᵀ`` from the SVD ``R = U Σ Vᵀ``, with the sign of the last singular
    direction flipped where needed so that the determinant is +1: the
    orthogonal Procrustes solution. A rotation comes back unchanged to
    round-off; one written with a few digits comes back exactly orthonormal.

    Args:
        R: ``(..., 3, 3)`` matrices (nearly rotations).

    Returns:
        ``(..., 3, 3)`` rotations.
    """
    Ra = np.asarray(R, dtype=np.float64)
    U, _, Vt = np.linalg.svd(Ra)
    d = np.sign(np.linalg.det(U @ Vt))
    d = np.where(d == 0.0, 1.0, d)
    U = U.copy()
    U[..., :, 2] *= d[..., None]
    out: FloatArray = U @ Vt
    return out


def orthonormality_error(R: ArrayLike) -> FloatArray:
    """``max|RᵀR − I|`` of each ``(..., 3, 3)`` matrix: ``(...)``."""
    Ra = np.asarray(R, dtype=np.float64)
    gram = np.swapaxes(Ra, -1, -2) @ Ra
    err: FloatArray = np.abs(gram - np.eye(3)).max(axis=(-1, -2))
    return err


def orthonormalize(R: ArrayLike) -> tuple[FloatArray, NDArray[np.bool_]]:
    """Rotations as given where orthonormal to round-off, else the nearest rotation.

    Args:
        R: ``(..., 3, 3)`` matrices, rotations to within a few digits.

    Returns:
        ``(rotations, projected)``: ``(..., 3, 3)`` and ``(...)`` bool, True
        where the matrix was farther than ``ROUNDOFF_TOL`` from orthonormal
        and was replaced by :func:`nearest_rotation`.
    """
    Ra = np.array(R, dtype=np.float64)
    projected = orthonormality_error(Ra) > ROUNDOFF_TOL
    if projected.any():
        Ra[projected] = nearest_rotation(Ra[projected])
    return Ra, projected
