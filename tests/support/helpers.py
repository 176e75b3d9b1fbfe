"""Shared test helpers: one transform comparison, a reference DH product, random robots.

The reference product here is written from the slides (seed 000 rule 14, seed 001)
with four explicit elementary matrices per link and ``np.linalg.multi_dot``; it
shares no code with ``kinematica.dh``. Random robots are plain :class:`RobotSpec`
values, from which the tests build both a :class:`kinematica.robot.Robot` and the
reference frames.
"""

from __future__ import annotations

import dataclasses
import html
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pytest
from hypothesis import settings
from hypothesis import strategies as st
from numpy.typing import ArrayLike, NDArray

from kinematica.dh import Prismatic, Revolute
from kinematica.ik import IKResult
from kinematica.robot import Robot

FloatArray = NDArray[np.float64]

#: Hypothesis settings for the property tests: modest, no deadline (first calls
#: warm caches), no example database (a test writes nothing into the repo).
PROPERTY = settings(max_examples=50, deadline=None, database=None, derandomize=True)

#: Angles a DH table most often holds, drawn often so the exact-value branches run.
SPECIAL_ANGLES = (0.0, math.pi / 2, -math.pi / 2, math.pi, -math.pi)


# --------------------------------------------------------------- comparison
def _rotation_angle(R: FloatArray) -> FloatArray:
    """Angle (rad) of the rotation closest to each ``(..., 3, 3)`` matrix ``R``."""
    cos = np.clip((np.trace(R, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    sin = np.linalg.norm(R - np.swapaxes(R, -1, -2), axis=(-2, -1)) / (2.0 * math.sqrt(2.0))
    return np.arctan2(sin, cos)


def assert_transform_close(
    T1: ArrayLike,
    T2: ArrayLike,
    atol: float = 1e-12,
    rtol: float = 0.0,
    err_msg: str = "",
) -> None:
    """Assert that two batches of homogeneous transforms agree entry by entry.

    Passes when ``|T1 - T2| <= atol + rtol * |T2|`` for every entry of the
    ``(..., 4, 4)`` arrays (same shape required). On failure the message gives
    the worst batch index, the largest entry difference, the position error
    (m) and the rotation error (rad, angle of ``R1ᵀ R2``) there, and both
    transforms.
    """
    A = np.asarray(T1, dtype=float)
    B = np.asarray(T2, dtype=float)
    if A.shape != B.shape or A.shape[-2:] != (4, 4):
        raise AssertionError(f"shape mismatch: {A.shape} vs {B.shape} (want equal (..., 4, 4))")
    bad = ~(np.abs(A - B) <= atol + rtol * np.abs(B))
    if not bad.any():
        return
    diff = np.where(np.isnan(A - B), np.inf, np.abs(A - B))
    per = diff.reshape(*A.shape[:-2], 16).max(axis=-1)
    idx = np.unravel_index(int(np.argmax(per)), per.shape) if per.ndim else ()
    a, b = A[idx], B[idx]
    pos = float(np.linalg.norm(a[:3, 3] - b[:3, 3]))
    rot = float(_rotation_angle(a[:3, :3].T @ b[:3, :3]))
    n_bad = int(bad.reshape(*A.shape[:-2], 16).any(axis=-1).sum())
    where = f" at batch index {tuple(int(i) for i in idx)}" if idx else ""
    with np.printoptions(precision=17, suppress=False, linewidth=120):
        raise AssertionError(
            f"{err_msg + ': ' if err_msg else ''}transforms differ{where} "
            f"({n_bad} of {max(per.size, 1)} transforms out of tolerance atol={atol:g}, "
            f"rtol={rtol:g}): max |dT| = {float(per[idx]):.3e}, "
            f"position error = {pos:.3e} m, rotation error = {rot:.3e} rad\n"
            f"T1 =\n{a}\nT2 =\n{b}"
        )


def assert_same_result(a: IKResult, b: IKResult) -> None:
    """Assert two IK answers identical: every field (NaN equals NaN), its type, the message.

    For two paths that must give the same answer (``robot.ik``'s one-target paths and
    the general one), not for two methods that may differ by round-off.
    """
    for f in dataclasses.fields(IKResult):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, np.ndarray):
            np.testing.assert_array_equal(x, y, err_msg=f.name)
            assert x.shape == y.shape, f.name
        else:
            np.testing.assert_equal(x, y, err_msg=f.name)
            assert type(x) is type(y) or f.name == "status", f.name
    assert a.message == b.message
    if a.parameter is not None:
        assert b.parameter is not None
        assert type(a.parameter[1]) is type(b.parameter[1]), "parameter"


# ------------------------------------------------------ reference DH product
def rot_z(theta: float) -> FloatArray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=float)


def rot_x(alpha: float) -> FloatArray:
    c, s = math.cos(alpha), math.sin(alpha)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]], dtype=float)


def tras_z(d: float) -> FloatArray:
    T = np.eye(4)
    T[2, 3] = d
    return T


def tras_x(a: float) -> FloatArray:
    T = np.eye(4)
    T[0, 3] = a
    return T


def ref_link(theta: float, d: float, a: float, alpha: float, convention: str) -> FloatArray:
    """One link matrix as the slides write it.

    standard (Paul): ``Rot(z, θ) · Tras(z, d) · Tras(x, a) · Rot(x, α)``;
    modified (Craig): ``Rot(x, α) · Tras(x, a) · Rot(z, θ) · Tras(z, d)``
    with ``a``, ``α`` being ``a_(i-1)``, ``α_(i-1)``.
    """
    if convention == "standard":
        return np.linalg.multi_dot([rot_z(theta), tras_z(d), tras_x(a), rot_x(alpha)])
    return np.linalg.multi_dot([rot_x(alpha), tras_x(a), rot_z(theta), tras_z(d)])


# -------------------------------------------------------------- robot specs
@dataclass(frozen=True)
class JointSpec:
    """One DH row as plain data: ``const`` is theta (P) or d (R), the fixed part."""

    kind: str  # "R" or "P"
    const: float
    a: float
    alpha: float
    offset: float
    qlim: tuple[float, float] | None = None

    def build(self) -> Revolute | Prismatic:
        if self.kind == "R":
            return Revolute(
                d=self.const, a=self.a, alpha=self.alpha, offset=self.offset, qlim=self.qlim
            )
        return Prismatic(
            theta=self.const, a=self.a, alpha=self.alpha, offset=self.offset, qlim=self.qlim
        )

    def params(self, q: float) -> tuple[float, float, float, float]:
        """``(theta, d, a, alpha)`` of this row at joint value ``q``."""
        if self.kind == "R":
            return (q + self.offset, self.const, self.a, self.alpha)
        return (self.const, q + self.offset, self.a, self.alpha)


@dataclass(frozen=True)
class RobotSpec:
    """A robot as plain data, with a reference FK written from the slides."""

    joints: tuple[JointSpec, ...]
    convention: str = "standard"
    base: FloatArray | None = None
    tool: FloatArray | None = None

    @property
    def dof(self) -> int:
        return len(self.joints)

    def build(self) -> Robot:
        return Robot.from_dh(
            [j.build() for j in self.joints],
            convention=self.convention,
            base=self.base,
            tool=self.tool,
        )

    def ref_links(self, q: Sequence[float]) -> list[FloatArray]:
        """The ``n`` link matrices ``i-1Ai`` at one configuration ``q``."""
        return [
            ref_link(*j.params(float(qi)), self.convention)
            for j, qi in zip(self.joints, q, strict=True)
        ]

    def ref_frames(self, q: Sequence[float]) -> FloatArray:
        """``(n+1, 4, 4)``: ``base``, ``base·0A1``, ..., ``base·0A1···An·tool``."""
        base = np.eye(4) if self.base is None else np.asarray(self.base, dtype=float)
        tool = np.eye(4) if self.tool is None else np.asarray(self.tool, dtype=float)
        frames = [base]
        for A in self.ref_links(q):
            frames.append(frames[-1] @ A)
        frames[-1] = frames[-1] @ tool
        return np.array(frames)

    def ref_fk(self, q: Sequence[float]) -> FloatArray:
        """``(4, 4)``: ``base · 0A1 · ... · (n-1)An · tool`` as one ``multi_dot``."""
        base = np.eye(4) if self.base is None else np.asarray(self.base, dtype=float)
        tool = np.eye(4) if self.tool is None else np.asarray(self.tool, dtype=float)
        return np.linalg.multi_dot([base, *self.ref_links(q), tool])


def transform_from(quat: Sequence[float], xyz: Sequence[float]) -> FloatArray:
    """``(4, 4)`` transform from a (not necessarily unit, nonzero) quaternion w, x, y, z."""
    w, x, y, z = np.asarray(quat, dtype=float) / np.linalg.norm(quat)
    R = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = xyz
    return T


# -------------------------------------------------------------- strategies
def _floats(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False, allow_subnormal=False)


lengths = st.one_of(st.just(0.0), _floats(-1.0, 1.0))
angles = st.one_of(st.sampled_from(SPECIAL_ANGLES), _floats(-math.pi, math.pi))


@st.composite
def transforms(draw: st.DrawFn) -> FloatArray | None:
    """A random rigid transform, or ``None`` (identity) a quarter of the time."""
    if draw(st.integers(0, 3)) == 0:
        return None
    quat = draw(st.lists(_floats(-1.0, 1.0), min_size=4, max_size=4))
    if np.linalg.norm(quat) < 0.1:
        quat = [1.0, 0.0, 0.0, 0.0]
    xyz = draw(st.lists(_floats(-1.0, 1.0), min_size=3, max_size=3))
    return transform_from(quat, xyz)


@st.composite
def joint_specs(draw: st.DrawFn) -> JointSpec:
    kind = draw(st.sampled_from("RP"))
    qlim = None
    if draw(st.booleans()):
        lo = draw(_floats(-3.0, 2.0))
        qlim = (lo, lo + draw(_floats(0.01, 3.0)))
    return JointSpec(
        kind=kind,
        const=draw(angles if kind == "P" else lengths),
        a=draw(lengths),
        alpha=draw(angles),
        offset=draw(angles if kind == "R" else lengths),
        qlim=qlim,
    )


@st.composite
def robot_specs(
    draw: st.DrawFn, min_dof: int = 1, max_dof: int = 8, convention: str | None = None
) -> RobotSpec:
    """Random robots: 1-8 joints, mixed R/P, either convention, offsets, limits, base, tool."""
    n = draw(st.integers(min_dof, max_dof))
    return RobotSpec(
        joints=tuple(draw(joint_specs()) for _ in range(n)),
        convention=convention or draw(st.sampled_from(["standard", "modified"])),
        base=draw(transforms()),
        tool=draw(transforms()),
    )


def random_q(spec: RobotSpec, rng: np.random.Generator, batch: tuple[int, ...] = ()) -> FloatArray:
    """Joint values ``(*batch, n)``: radians in (-π, π) for R, metres in (-1, 1) for P."""
    scale = np.array([math.pi if j.kind == "R" else 1.0 for j in spec.joints])
    return rng.uniform(-1.0, 1.0, size=(*batch, spec.dof)) * scale


#: Seeds for numpy generators drawn inside hypothesis tests.
seeds = st.integers(0, 2**32 - 1)


# ------------------------------------------------------------------ command line
def run_cli(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    """Run the command line in-process: ``(exit code, stdout, stderr)``.

    argparse's SystemExit (usage errors, ``--help``) becomes an exit code.
    """
    from kinematica.cli.main import main

    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else 2
    out, err = capsys.readouterr()
    return code, out, err


# --------------------------------------------------------------- notebook tables
def table_cells(fragment: str) -> list[list[str]]:
    """The rows of an HTML table, each a list of its unescaped cell texts."""
    rows = re.findall(r"<tr>(.*?)</tr>", fragment, flags=re.S)
    return [[html.unescape(c) for c in re.findall(r"<t[dh]>(.*?)</t[dh]>", r)] for r in rows]


def random_7r(seed: int, tool_off_axis: bool = False) -> Robot:
    """A generic 7R arm: standard DH, lengths and twists drawn at random; no joint limits.

    Args:
        seed: The draw's seed.
        tool_off_axis: Move the tool point off the last joint's axis (5-10 cm).
    """
    rng = np.random.default_rng(seed)
    rows = [
        Revolute(
            d=float(rng.uniform(-0.4, 0.4)),
            a=float(rng.uniform(-0.4, 0.4)),
            alpha=float(rng.uniform(-math.pi, math.pi)),
        )
        for _ in range(7)
    ]
    tool = np.eye(4)
    if tool_off_axis:
        tool[:3, 3] = [0.05, -0.03, 0.1]
    return Robot.from_dh(rows, name=f"random 7R ({seed})", convention="standard", tool=tool)
