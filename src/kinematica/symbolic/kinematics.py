"""Forward kinematics in sympy: elementary transforms, link matrices, T, lambdify.

Standard (Paul) convention, seed 000 rule 14 and seed 003::

    i-1Ai = Rot(z, θi) · Tras(z, di) · Tras(x, ai) · Rot(x, αi)

Modified (Craig) convention, seed 001::

    i-1Ai = Rot(x, α(i-1)) · Tras(x, a(i-1)) · Rot(z, θi) · Tras(z, di)

and ``T = base · 0A1 · 1A2 · ... · (n-1)An · tool``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Literal

import numpy as np
import sympy as sp
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError
from kinematica.symbolic.model import (
    RobotLike,
    SymbolicError,
    SymbolicRobot,
    SymbolicRow,
    numeric_model,
    rot,
    symbolic_robot,
    trans,
)
from kinematica.symbolic.notation import tidy

__all__ = [
    "Factor",
    "factors",
    "fk",
    "frames",
    "lambdify",
    "link_factors",
    "link_matrices",
    "orientation",
    "position",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Factor:
    """One elementary transform of a DH row.

    Attributes:
        kind: ``"Rot"`` (rotation) or ``"Tras"`` (translation), the seeds' names.
        axis: ``"x"`` or ``"z"``.
        value: The angle (rad) or distance (m).
        matrix: The ``(4, 4)`` homogeneous matrix.
    """

    kind: Literal["Rot", "Tras"]
    axis: Literal["x", "z"]
    value: sp.Expr
    matrix: sp.Matrix


def _row_factors(row: SymbolicRow, convention: str) -> list[Factor]:
    rz = Factor("Rot", "z", row.theta, rot("z", row.theta))
    tz = Factor("Tras", "z", row.d, trans("z", row.d))
    tx = Factor("Tras", "x", row.a, trans("x", row.a))
    rx = Factor("Rot", "x", row.alpha, rot("x", row.alpha))
    return [rz, tz, tx, rx] if convention == "standard" else [rx, tx, rz, tz]


def factors(robot: RobotLike, i: int) -> list[Factor]:
    """The four elementary transforms of row ``i`` (1-based), with their names.

    See :func:`link_factors`; this variant also says which transform each is.
    """
    model = symbolic_robot(robot)
    if isinstance(i, bool) or not isinstance(i, int | np.integer) or not 1 <= i <= model.dof:
        raise SymbolicError(
            f"row {i!r} does not exist: {model.name} has rows 1 to {model.dof} "
            "(numbered as in the DH table, joint i moves row i)"
        )
    return _row_factors(model.rows[int(i) - 1], model.convention)


def link_factors(robot: RobotLike, i: int) -> list[sp.Matrix]:
    """The four elementary transforms of DH row ``i``, in the convention's order.

    Standard: ``Rot(z, θi), Tras(z, di), Tras(x, ai), Rot(x, αi)``; modified:
    ``Rot(x, α(i-1)), Tras(x, a(i-1)), Rot(z, θi), Tras(z, di)``. Their product
    is ``i-1Ai``.

    Args:
        robot: A ``Robot``, built-in name, robot-file path or ``SymbolicRobot``.
        i: The row, 1 to n as in the DH table (joint i moves row i).

    Returns:
        Four ``(4, 4)`` sympy matrices (m, rad).

    Raises:
        SymbolicError: ``i`` is not a row of the table.
    """
    return [f.matrix for f in factors(robot, i)]


def link_matrices(robot: RobotLike) -> list[sp.Matrix]:
    """The link matrices ``0A1, 1A2, ..., (n-1)An`` (no base, no tool).

    Args:
        robot: A ``Robot``, built-in name, robot-file path or ``SymbolicRobot``.

    Returns:
        n ``(4, 4)`` sympy matrices in the joint symbols ``q1 ... qn`` (m, rad),
        each the product of its row's :func:`link_factors`.
    """
    model = symbolic_robot(robot)
    out = []
    for row in model.rows:
        A = sp.eye(4)
        for f in _row_factors(row, model.convention):
            A = A * f.matrix
        out.append(tidy(A))
    return out


def frames(robot: RobotLike) -> list[sp.Matrix]:
    """Every frame in the world (base) frame: ``0T0 (base), 0T1, ..., 0Tn (with tool)``.

    The layout of ``robot.fk(q, all_frames=True)``: entry k is
    ``base · 0A1 ··· (k-1)Ak`` and the last one includes the tool.

    Args:
        robot: A ``Robot``, built-in name, robot-file path or ``SymbolicRobot``.

    Returns:
        n+1 ``(4, 4)`` sympy matrices in textbook form (m, rad).
    """
    model = symbolic_robot(robot)
    base, tool = sp.Matrix(model.base), sp.Matrix(model.tool)
    out = [base]
    P = sp.eye(4)
    for k, A in enumerate(link_matrices(model), start=1):
        P = tidy(P * A)
        # A constant base or tool only combines entries linearly: nothing to fold.
        T = base * P * tool if k == model.dof else base * P
        out.append(P if T == P else tidy(T, fold=False))
    return out


def _product_frames(model: SymbolicRobot) -> list[sp.Matrix]:
    """``frames`` without simplification: the plain products."""
    T = sp.Matrix(model.base)
    out = [T]
    for k, A in enumerate(link_matrices(model), start=1):
        T = T * A
        out.append(T * sp.Matrix(model.tool) if k == model.dof else T)
    return out


def fk(robot: RobotLike) -> sp.Matrix:
    """``T = base · 0A1 · ... · (n-1)An · tool``: ``(4, 4)`` sympy matrix in q1 ... qn."""
    return frames(robot)[-1]


def position(robot: RobotLike) -> sp.Matrix:
    """The three position equations ``(px, py, pz)`` of the tool, in textbook form.

    Args:
        robot: A ``Robot``, built-in name, robot-file path or ``SymbolicRobot``.

    Returns:
        ``(3, 1)`` sympy column: x, y, z of the tool in the world frame (m),
        e.g. ``c1*(L2*c2 + L3*c23)`` once printed with :func:`short`.
    """
    return sp.Matrix(fk(robot)[:3, 3])


def orientation(robot: RobotLike) -> sp.Matrix:
    """The orientation of the tool: the ``(3, 3)`` rotation part of T (columns n, o, a)."""
    return sp.Matrix(fk(robot)[:3, :3])


def substitute(
    model: SymbolicRobot, expr: sp.MatrixBase, values: Mapping[str, float] | None = None
) -> sp.MatrixBase:
    """``expr`` with the parameter symbols replaced by their values (m, rad).

    Args:
        model: The symbolic robot (its ``values`` are the defaults).
        expr: A sympy matrix.
        values: Values in place of the defaults, by parameter name.

    Raises:
        SymbolicError: a name that is not a parameter of the robot.
    """
    mapping: dict[sp.Symbol, float] = dict(model.values)
    for name, value in (values or {}).items():
        matches = [s for s in mapping if s.name == name]
        if not matches:
            known = ", ".join(sorted(s.name for s in mapping)) or "none"
            raise SymbolicError(f"unknown parameter {name!r}; this robot's parameters: {known}")
        mapping[matches[0]] = float(value)
    return expr.xreplace({s: sp.Float(v) for s, v in mapping.items()})


def lambdify(
    robot: RobotLike,
    *,
    all_frames: bool = False,
    values: Mapping[str, float] | None = None,
    simplify: bool = True,
) -> Callable[[ArrayLike], FloatArray]:
    """A numeric function of q computed from the symbolic T.

    Args:
        robot: A ``Robot``, built-in name, robot-file path or ``SymbolicRobot``.
        all_frames: Return every frame ``0T0 ... 0Tn`` as :func:`frames` does.
        values: Parameter values (m, rad) in place of the file's, by name.
        simplify: Compile the textbook form of :func:`frames` (``True``) or the
            plain product of the link matrices (``False``: much faster to build
            for long chains of general numeric rows; the same function).

    Returns:
        ``f(q)``: ``q`` of shape ``(..., n)`` (rad, m) gives ``(..., 4, 4)``
        (or ``(..., n+1, 4, 4)``), equal to ``robot.fk(q)``.
    """
    model = numeric_model(robot)
    mats = _product_frames(model) if simplify is False else frames(model)
    if not all_frames:
        mats = mats[-1:]
    entries = [substitute(model, sp.Matrix(M), values) for M in mats]
    flat = [e for M in entries for e in M]
    leftover = set().union(*(e.free_symbols for e in flat)) - set(model.q)
    if leftover:
        names = ", ".join(sorted(s.name for s in leftover))
        raise SymbolicError(f"no value for the parameter(s) {names}")
    fn = sp.lambdify(model.q, flat, modules="numpy", cse=True)
    n, k = model.dof, len(mats)

    def evaluate(q: ArrayLike) -> FloatArray:
        try:
            qa = np.asarray(q, dtype=float)
        except (TypeError, ValueError) as exc:
            raise DimensionError(f"q must be numbers, got {q!r}") from exc
        if qa.ndim == 0 or qa.shape[-1] != n:
            raise DimensionError(
                f"q must hold {n} joint values for {model.name}, got shape {qa.shape}"
            )
        cols = fn(*np.moveaxis(qa, -1, 0))
        out = np.empty((*qa.shape[:-1], k * 16))
        for j, col in enumerate(cols):
            out[..., j] = col
        shape = (*qa.shape[:-1], 4, 4) if not all_frames else (*qa.shape[:-1], k, 4, 4)
        return out.reshape(shape)

    return evaluate
