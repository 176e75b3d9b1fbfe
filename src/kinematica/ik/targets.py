"""What ``robot.ik`` is asked: targets of any batch shape, masks, q0 and tolerances.

Validated once here at the public boundary. In a batch, a malformed target
does not stop the others: it is reported (flat index -> what is wrong) and
replaced by a harmless placeholder, its result marked ``invalid``. A rotation
written with a few digits (orthonormal to ``PROJECTION_TOL``) is replaced by
the nearest rotation, with a note saying so.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.errors import DimensionError
from kinematica.ik.tolerance import POSITION_TOL, ROTATION_TOL, Tolerance, parse_tolerance
from kinematica.spatial import ROUNDOFF_TOL, nearest_rotation
from kinematica.spatial.checks import shown_above

__all__ = [
    "POSITION_TOL",
    "PROJECTION_TOL",
    "QUIET_PROJECTION",
    "ROTATION_TOL",
    "Targets",
    "Tolerance",
    "parse_mask",
    "parse_q0",
    "parse_targets",
    "parse_tolerance",
]

FloatArray = NDArray[np.float64]
#: No remarks: an empty, read-only mapping shared by every clean batch.
_NONE: Mapping[int, Any] = MappingProxyType({})

#: A target rotation orthonormal to within this (max |RᵀR − I|, and the last
#: row within this of [0, 0, 0, 1]) is accepted. A rotation copied with 4
#: decimals has entries off by up to 5e-5, so (RᵀR − I)ᵢⱼ = Σₖ (Rₖᵢ Eₖⱼ + Eₖᵢ Rₖⱼ)
#: + O(E²) reaches 2·√3·5e-5 ≈ 1.73e-4 (each column of R a unit vector): every
#: 4-decimal copy is accepted, a 3-decimal one (up to ~1.7e-3) is not. It is
#: replaced by the nearest rotation (with a note) when farther than round-off from
#: orthonormal; beyond this, it is an error.
PROJECTION_TOL = 2e-4
#: A projection onto SO(3) is said (a note) only when the rotation was farther than
#: this from orthonormal: the projection moves it by about half that angle, and below
#: ROTATION_TOL a solution meets the tolerance on the rotation as written too (a copy
#: with 10 digits, orthonormal to ~1e-10, is projected silently).
QUIET_PROJECTION = ROTATION_TOL


class Targets:
    """Targets, flattened for the core.

    A plain class: ``robot.ik`` of one pose builds one on every call (a frozen
    dataclass took a microsecond of it), and a named tuple's class took 0.15 ms
    to make at the first ``robot.ik``.

    Attributes:
        poses: ``(N, 4, 4)`` C-contiguous; a position target is a pose with an
            identity rotation (ignored through the weights); malformed rows
            are identities.
        shape: The batch shape ``(...)``; ``()`` for one target.
        position: True for position targets ``(..., 3)``.
        invalid: Flat index -> what is wrong with that target.
        notes: Flat index -> remarks (a rotation projected onto SO(3)).
    """

    __slots__ = ("invalid", "notes", "poses", "position", "shape")

    def __init__(
        self,
        poses: FloatArray,
        shape: tuple[int, ...],
        position: bool,
        invalid: Mapping[int, str] = _NONE,
        notes: Mapping[int, tuple[str, ...]] = _NONE,
    ) -> None:
        self.poses = poses
        self.shape = shape
        self.position = position
        self.invalid = invalid
        self.notes = notes

    @property
    def single(self) -> bool:
        """True for one target (shape ``()``)."""
        return self.shape == ()

    def replace(self, **changes: Any) -> Targets:
        """The same targets with the given attributes changed (``poses=``, ``shape=``...)."""
        fields = {name: getattr(self, name) for name in self.__slots__}
        return Targets(**(fields | changes))


def _where(shape: tuple[int, ...], flat: int) -> str:
    if not shape:
        return "target"
    if len(shape) == 1:
        return f"target row {flat}"
    return f"target {tuple(int(v) for v in np.unravel_index(flat, shape))}"


def parse_targets(target: ArrayLike) -> Targets:
    """Read poses ``(..., 4, 4)`` or positions ``(..., 3)``.

    Raises:
        DimensionError: Non-numbers, an ambiguous or wrong shape, or a single
            target that is malformed (a batch marks such rows instead).
    """
    if type(target) is np.ndarray and target.shape == (4, 4) and target.dtype == np.float64:
        raw: np.ndarray = target  # the common case: one pose, no conversion
    else:
        try:
            raw = np.asarray(target)  # a subclass (numpy.matrix) as a plain array
        except (TypeError, ValueError) as exc:
            raise DimensionError(
                f"target must be numbers, got {type(target).__name__}", arg="target"
            ) from exc
        if raw.dtype.kind not in "iuf":
            raise DimensionError(
                f"target must be real numbers (a 4x4 pose or a position), got dtype {raw.dtype}",
                arg="target",
            )
    if raw.shape == (3, 3):
        raise DimensionError(
            "a (3, 3) target is ambiguous: a rotation alone is not a target (give a "
            "4x4 pose), and three positions must be given as shape (3, 1, 3)",
            arg="target",
        )
    if raw.ndim >= 2 and raw.shape[-2:] == (4, 4):
        return _poses(raw)
    if raw.ndim >= 1 and raw.shape[-1] == 3:
        return _positions(raw.astype(np.float64))
    raise DimensionError(
        "target must be a pose (4, 4), a position (3,), or batches (..., 4, 4) / (..., 3); "
        f"got shape {raw.shape}",
        arg="target",
    )


_IDENTITY = np.eye(4)


def _positions(arr: FloatArray) -> Targets:
    shape = arr.shape[:-1]
    if not shape:  # one position: plain floats, one copy of the identity
        x, y, z = arr.tolist()
        if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(z)):
            raise DimensionError("target position holds NaN or inf", arg="target")
        pose = _IDENTITY.copy()
        pose[0, 3], pose[1, 3], pose[2, 3] = x, y, z
        return Targets(pose[None], shape, True)
    flat = arr.reshape(-1, 3)
    poses = np.zeros((flat.shape[0], 4, 4))
    poses[:, 0, 0] = poses[:, 1, 1] = poses[:, 2, 2] = poses[:, 3, 3] = 1.0
    bad = np.flatnonzero(~np.all(np.isfinite(flat), axis=-1))
    if bad.size and not shape:
        raise DimensionError("target position holds NaN or inf", arg="target")
    invalid = {int(i): f"{_where(shape, int(i))}: position holds NaN or inf" for i in bad}
    poses[:, :3, 3] = np.where(np.isfinite(flat), flat, 0.0)
    return Targets(poses, shape, True, invalid)


def _poses(raw: np.ndarray) -> Targets:
    shape = raw.shape[:-2]
    if not shape and raw.dtype == np.float64:  # one pose: one core call, no copy if rigid
        poses = raw[None] if raw.flags.c_contiguous else raw[None].copy()
        finite1, last1, ortho1, det1 = _core.pose_defects(poses[0])
        if finite1 and ortho1 <= ROUNDOFF_TOL and last1 == 0.0 and det1 > 0.0:
            return Targets(poses, shape, False)  # read, never written
        poses = raw[None].copy()  # projected or explained below
    else:
        poses = np.array(raw.reshape(-1, 4, 4), dtype=np.float64, order="C")  # a copy
    finite, last, ortho, det = _core.pose_defects_batch(poses)
    clean = finite & (ortho <= ROUNDOFF_TOL) & (last == 0.0) & (det > 0.0)
    if clean.all():
        return Targets(poses, shape, False)
    invalid: dict[int, str] = {}
    notes: dict[int, tuple[str, ...]] = {}
    for i in np.flatnonzero(~clean).tolist():
        where = _where(shape, i)
        if not finite[i]:
            invalid[i] = f"{where} holds NaN or inf"
        elif last[i] > PROJECTION_TOL:
            invalid[i] = f"{where} last row must be [0, 0, 0, 1], got {poses[i, 3].tolist()}"
        elif ortho[i] > PROJECTION_TOL:
            invalid[i] = (
                f"{where} rotation is not orthonormal: max |RᵀR − I| = "
                f"{shown_above(float(ortho[i]), PROJECTION_TOL)}, more than the "
                f"{PROJECTION_TOL:.0e} a copy with 4 decimals stays within"
            )
        elif det[i] <= 0.0:
            invalid[i] = f"{where} rotation has det = {det[i]:+.3f}, expected +1 (a reflection)"
        else:
            poses[i, 3] = [0.0, 0.0, 0.0, 1.0]
            if ortho[i] > ROUNDOFF_TOL:
                poses[i, :3, :3] = nearest_rotation(poses[i, :3, :3])
            if ortho[i] > QUIET_PROJECTION:
                notes[i] = (
                    f"target rotation projected onto SO(3) (it was orthonormal to "
                    f"{ortho[i]:.1e} only)",
                )
    if invalid and not shape:
        raise DimensionError(invalid[0], arg="target")
    for i in invalid:
        poses[i] = np.eye(4)
    return Targets(poses, shape, False, invalid, notes)


def parse_q0(q0: ArrayLike | None, n: int, shape: tuple[int, ...]) -> FloatArray | None:
    """``(N, n)`` first guesses, one per target of batch shape ``shape`` (flat, C order).

    Args:
        q0: ``(n,)`` for every target, or ``(..., n)`` broadcast to the batch; or None.
        n: The arm's joints.
        shape: The targets' batch shape.

    Raises:
        DimensionError: Not numbers, not n values a row, NaN or inf, or a shape that
            does not broadcast to the batch (``arg="q0"``).
    """
    if q0 is None:
        return None
    try:
        q = np.asarray(q0, dtype=float)
    except (TypeError, ValueError) as exc:
        raise DimensionError(f"q0 must be numbers, got {q0!r}"[:200], arg="q0") from exc
    if q.ndim == 0 or q.shape[-1] != n:
        raise DimensionError(f"q0 must hold {n} joint values, got shape {q.shape}", arg="q0")
    if not np.all(np.isfinite(q)):
        raise DimensionError("q0 holds NaN or inf", arg="q0")
    try:
        full = np.broadcast_to(q, (*shape, n))
    except ValueError:
        raise DimensionError(
            f"q0 of shape {q.shape} does not match targets of batch shape {shape}", arg="q0"
        ) from None
    return np.ascontiguousarray(full.reshape(-1, n))


def parse_mask(mask: ArrayLike | None) -> FloatArray | None:
    """``(6,)`` non-negative weights of x, y, z, rx, ry, rz, or None for the whole pose."""
    if mask is None:
        return None
    try:
        m = np.asarray(mask, dtype=float)
    except (TypeError, ValueError) as exc:
        raise DimensionError(f"mask must be 6 numbers, got {mask!r}", arg="mask") from exc
    if m.shape != (6,) or not np.all(np.isfinite(m)) or np.any(m < 0):
        raise DimensionError(
            "mask must be 6 non-negative weights for x, y, z, rx, ry, rz; "
            f"got {np.asarray(mask).tolist()}",
            arg="mask",
        )
    if not np.any(m > 0):
        raise DimensionError("mask selects no error component: every weight is 0", arg="mask")
    return None if np.all(m == 1.0) else m
