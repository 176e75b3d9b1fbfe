"""Closed-form inverse kinematics derived step by step, as seed 002 does it.

For the arms whose class has a textbook solution (planar 2R/3R/PR/PRR,
SCARA, anthropomorphic and elbow 3R, 6R with a spherical wrist) the
derivation is built from the robot's own symbolic kinematics, whatever its
DH convention, offsets, base or tool:

* q1 from the projection on the plane normal to axis 1 (two solutions);
* the elbow from the distance to the shoulder axis, ``A cos q + B sin q = v``
  (two solutions: elbow up / elbow down);
* the shoulder from two equations linear in its cosine and sine (one
  solution);
* for a spherical wrist, the wrist centre ``p_m = p + R w`` first, then
  ``R36 = R03ᵀ R`` and the three wrist angles;
* a joint that only turns the tool about a parallel axis from the orientation.

Each derivation is checked before it is shown (:func:`derive_inverse` runs
it on random poses of the numeric robot); a derivation that does not
reproduce them is not returned.
"""

from __future__ import annotations

import itertools
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Final

import numpy as np
import sympy as sp
from numpy.typing import NDArray
from sympy.polys.polyerrors import BasePolynomialError

from kinematica.errors import KinematicaWarning
from kinematica.robot import classify
from kinematica.symbolic.kinematics import factors
from kinematica.symbolic.model import SymbolicRobot
from kinematica.symbolic.notation import tidy
from kinematica.symbolic.trig import Linear, linear_cs, solve_pair, solve_single

__all__ = ["Assign", "InverseDerivation", "Step", "derive_inverse", "target_symbols"]

#: A derived solution reproduces a pose when robot.fk of it is this close (m, entries of T).
CHECK_TOL: Final = 1e-9
#: Random configurations a derivation is checked on.
CHECK_POSES: Final = 6

PX, PY, PZ = sp.symbols("p_x p_y p_z")


def target_symbols() -> tuple[sp.Matrix, sp.Matrix]:
    """The target ``p = (p_x, p_y, p_z)`` and ``R = [r11 ... r33]`` (world frame)."""
    R = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"r{i + 1}{j + 1}"))
    return sp.Matrix([PX, PY, PZ]), R


@dataclass(frozen=True)
class Step:
    """One step of the derivation: a sentence (by key) and the equations it leads to.

    Attributes:
        key: The sentence in the report's phrase book (``"ik.q1"``...).
        args: Values for the sentence's placeholders (sympy or text).
        equations: ``(lhs, rhs)`` pairs shown one per line.
    """

    key: str
    args: Mapping[str, Any] = field(default_factory=dict)
    equations: tuple[tuple[Any, Any], ...] = ()


@dataclass(frozen=True)
class Assign:
    """An unknown and its formula(s), evaluated in order: one per branch."""

    symbol: sp.Symbol
    branches: tuple[sp.Expr, ...]


@dataclass(frozen=True)
class InverseDerivation:
    """A checked closed-form derivation.

    Attributes:
        kind: The structure class (``km.classify(robot).kind``).
        steps: What the report shows, in order.
        plan: The formulas, in evaluation order (2 branches where two solutions).
        solutions: How many solutions the formulas give in general.
    """

    kind: str
    steps: tuple[Step, ...]
    plan: tuple[Assign, ...]

    @property
    def solutions(self) -> int:
        """Number of branch combinations (solutions in general)."""
        return int(np.prod([len(a.branches) for a in self.plan]))


class _OutOfPatternError(Exception):
    """The robot's geometry is outside the textbook pattern of its class."""


@dataclass
class _Ctx:
    model: SymbolicRobot
    chain: list[sp.Matrix]
    rotz: dict[int, int]
    steps: list[Step] = field(default_factory=list)
    plan: list[Assign] = field(default_factory=list)

    def step(self, key: str, *eqs: tuple[Any, Any], **args: Any) -> None:
        self.steps.append(Step(key, args, tuple(eqs)))

    def assign(self, symbol: sp.Symbol, *branches: sp.Expr) -> None:
        self.plan.append(Assign(symbol, tuple(branches)))

    def q(self, k: int) -> sp.Symbol:
        return self.model.rows[k - 1].q

    def offset(self, k: int) -> sp.Expr:
        row = self.model.rows[k - 1]
        return sp.expand(row.theta - row.q)


def _context(model: SymbolicRobot) -> _Ctx:
    chain: list[sp.Matrix] = [sp.Matrix(model.base)]
    rotz = {}
    for k in range(1, model.dof + 1):
        for f in factors(model, k):
            if f.kind == "Rot" and f.axis == "z":
                rotz[k] = len(chain)
            chain.append(f.matrix)
    chain.append(sp.Matrix(model.tool))
    return _Ctx(model, chain, rotz)


def _prod(mats: Sequence[sp.Matrix]) -> sp.Matrix:
    out = sp.eye(4)
    for M in mats:
        out = out * M
    return out


def _origin() -> sp.Matrix:
    return sp.Matrix([0, 0, 0, 1])


def _lin(expr: sp.Expr, q: sp.Symbol) -> Linear:
    eq = linear_cs(expr, q)
    if eq is None:
        raise _OutOfPatternError(f"{expr} is not linear in cos({q}), sin({q})")
    return eq


# ------------------------------------------------------------------ pieces
def _frame1(ctx: _Ctx, p: sp.Matrix) -> sp.Matrix:
    """The target in the frame whose z is axis 1 (modified DH: after Rot(x)·Tras(x))."""
    J = _prod(ctx.chain[: ctx.rotz[1]])
    if sp.simplify(J - sp.eye(J.rows)) == sp.zeros(J.rows, J.cols):
        return p
    Ji = tidy(J.inv())
    new = tidy(Ji[:3, :3] * p + Ji[:3, 3])
    prime = sp.Matrix(sp.symbols("x' y' z'"))
    ctx.step("ik.frame1", *zip(prime, new, strict=True))
    for s, e in zip(prime, new, strict=True):
        ctx.assign(s, e)
    return prime


def _after_rotz(ctx: _Ctx, k: int, end: int, local: sp.Matrix, frozen: Sequence[int]) -> sp.Matrix:
    """The point ``prod(chain[rotz_k+1 : end]) · local``; joints in ``frozen`` set to 0.

    ``frozen`` joints turn about axes through the point: it does not move with them.
    """
    P = (_prod(ctx.chain[ctx.rotz[k] + 1 : end]) * local)[:3, 0]
    return tidy(P.xreplace({ctx.q(j): 0 for j in frozen}))


def _wrist_point(ctx: _Ctx, k: int, p: sp.Matrix, R: sp.Matrix, name: str) -> sp.Matrix:
    """The point on axis ``k`` fixed in the tool: ``p_w = p + R w`` (seed 002's p_m)."""
    K = _prod(ctx.chain[ctx.rotz[k] + 1 :])
    later = {ctx.q(j): 0 for j in range(k + 1, ctx.model.dof + 1)}
    w = tidy((-K[:3, :3].T * K[:3, 3]).xreplace(later))  # the point lies on those axes
    pw = sp.Matrix(sp.symbols(f"{name}_x {name}_y {name}_z"))
    rhs = tidy(p + R * w)
    ctx.step("ik.wrist_point", *zip(pw, rhs, strict=True), w=w.T, k=k)
    for s, e in zip(pw, rhs, strict=True):
        ctx.assign(s, e)
    return pw


def _shoulder_q1(
    ctx: _Ctx, p1: sp.Matrix, W: sp.Matrix
) -> tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]:
    """q1 of an arm whose axis 2 is normal to axis 1 (seed 002: two solutions).

    ``W`` is the point in the frame turned by q1 (q1-free). Returns the
    in-plane coordinates ``(U, V)`` of the point seen from axis 2, functions of
    q2, q3, and their target values ``(u, v)``.
    """
    i1, i2 = ctx.rotz[1], ctx.rotz[2]
    C = _prod(ctx.chain[i1 + 1 : i2])
    u2, o2 = tidy(C[:3, 2]), tidy(C[:3, 3])
    if u2.free_symbols & set(ctx.model.q) or u2[2] != 0:
        raise _OutOfPatternError("axis 2 is not normal to axis 1")
    beta = sp.atan2(u2[1], u2[0])
    perp = sp.Matrix([-sp.sin(beta), sp.cos(beta), 0])
    e = tidy(sp.expand((u2.T * W)[0]))
    if e.free_symbols & set(ctx.model.q):
        raise _OutOfPatternError("the offset along axis 2 depends on the joints")
    r_expr = tidy(sp.expand((perp.T * W)[0]))
    x, y, z = p1
    r = sp.Symbol("r")
    radial = sp.sqrt(tidy(sp.expand(x**2 + y**2 - e**2)))
    shift = sp.simplify(beta + sp.pi / 2 + ctx.offset(1))
    q1 = sp.atan2(y, x) + sp.atan2(e, r) - shift
    q1_shown: Any = (sp.atan2(y, x) - shift, sp.atan2(y, x) + sp.pi - shift) if e == 0 else q1
    ctx.step("ik.q1.plane", (r, r_expr), (W[2], z), q=ctx.q(1), e=e)
    ctx.step("ik.q1.solve", (r, (radial, -radial)), (ctx.q(1), q1_shown), q=ctx.q(1), e=e)
    ctx.step("ik.q1.singular", q=ctx.q(1), cond=sp.Eq(radial, 0))
    ctx.assign(r, radial, -radial)
    ctx.assign(ctx.q(1), q1)
    r_a = tidy((perp.T * o2)[0])
    return r_expr - r_a, W[2] - o2[2], r - r_a, z - o2[2]


def _planar_pair(ctx: _Ctx, a: int, b: int, U: sp.Expr, V: sp.Expr, u: sp.Expr, v: sp.Expr) -> None:
    """Shoulder ``a`` and elbow ``b`` of a planar 2R: ``(U, V)(qa, qb) = (u, v)``.

    ``(U, V)`` are measured from a point on axis a, so ``U² + V²`` depends on qb only.
    """
    qa, qb = ctx.q(a), ctx.q(b)
    D = sp.expand((U**2 + V**2).xreplace({qa: 0}))
    eq = _lin(D, qb)
    value = tidy(u) ** 2 + tidy(v) ** 2
    branches = solve_single(eq, value)
    lhs = sp.Add(eq.A * sp.cos(qb), eq.B * sp.sin(qb), eq.K)
    ctx.step("ik.elbow", (lhs, value), (qb, tuple(branches)), q=qb)
    ctx.step("ik.elbow.singular", q=qb)
    ctx.assign(qb, *branches)
    pair = solve_pair(_lin(U, qa), _lin(V, qa), u, v)
    if pair is None:
        raise _OutOfPatternError("the shoulder equations do not fix the shoulder angle")
    cos_q, sin_q = pair
    ctx.step(
        "ik.shoulder",
        (U, u),
        (V, v),
        (sp.cos(qa), cos_q),
        (sp.sin(qa), sin_q),
        (qa, sp.atan2(sp.sin(qa), sp.cos(qa))),
        q=qa,
    )
    ctx.assign(qa, sp.atan2(sin_q, cos_q))


def _last_angle(ctx: _Ctx, k: int, R: sp.Matrix) -> None:
    """The last revolute joint k from the orientation: ``Rot(z, θk) = Cᵀ R Kᵀ``."""
    C = _prod(ctx.chain[: ctx.rotz[k]])
    K = _prod(ctx.chain[ctx.rotz[k] + 1 :])
    M = tidy(C[:3, :3].T * R * K[:3, :3].T)
    qk = sp.atan2(M[1, 0], M[0, 0]) - ctx.offset(k)
    ctx.step("ik.last", (ctx.q(k), qk), q=ctx.q(k))
    ctx.assign(ctx.q(k), qk)


def _prismatic(ctx: _Ctx, k: int, P: sp.Matrix, p: sp.Matrix) -> None:
    """A prismatic joint k along a fixed direction u: ``qk = u·(p - P|qk=0) / |u|²``."""
    qk = ctx.q(k)
    u = tidy(P.diff(qk))
    if u.free_symbols & set(ctx.model.q) or u == sp.zeros(3, 1):
        raise _OutOfPatternError("the prismatic axis turns")
    norm2 = tidy(sp.expand((u.T * u)[0]))
    rhs = tidy(sp.expand((u.T * (p - P.xreplace({qk: 0})))[0] / norm2))
    ctx.step("ik.prismatic", (qk, rhs), q=qk, u=u.T)
    ctx.assign(qk, rhs)


def _in_plane(ctx: _Ctx, P: sp.Matrix, p: sp.Matrix, a: int, b: int) -> None:
    """Planar 2R on joints a, b with all axes along z of the axis-1 frame."""
    J = _prod(ctx.chain[: ctx.rotz[1]])
    P1 = tidy(J.inv()[:3, :3] * P + J.inv()[:3, 3])
    p1 = _frame1(ctx, p)
    if P1[2].free_symbols & {ctx.q(a), ctx.q(b)}:
        raise _OutOfPatternError("the arm leaves its plane")
    ctx.step("ik.plane", (P1[2], p1[2]))
    _planar_pair(ctx, a, b, P1[0], P1[1], p1[0], p1[1])


def _prismatic_revolute(ctx: _Ctx, P: sp.Matrix, p: sp.Matrix) -> None:
    """Planar PR (seed 000): the component normal to the slide gives q2, then q1."""
    q1, q2 = ctx.q(1), ctx.q(2)
    u = tidy(P.diff(q1))
    w = tidy(_prod(ctx.chain[: ctx.rotz[2]])[:3, 2])
    n = tidy(w.cross(u))
    if n == sp.zeros(3, 1) or (n.free_symbols | u.free_symbols) & set(ctx.model.q):
        raise _OutOfPatternError("not a planar PR pair")
    lhs = tidy(sp.expand((n.T * P)[0]))
    value = tidy(sp.expand((n.T * p)[0]))
    eq = _lin(lhs, q2)
    branches = solve_single(eq, value)
    ctx.step("ik.pr.normal", (lhs, value), (q2, tuple(branches)), n=n.T, q=q2)
    ctx.assign(q2, *branches)
    _prismatic(ctx, 1, P, p)


def _wrist_angles(ctx: _Ctx, R: sp.Matrix) -> None:
    """q4, q5, q6 of a spherical wrist from ``R36 = R03ᵀ R`` (seed 002)."""
    i4 = ctx.rotz[4]
    C = _prod(ctx.chain[:i4])
    Mw = tidy(_prod(ctx.chain[i4:])[:3, :3])
    m = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"m{i + 1}{j + 1}"))
    target = C[:3, :3].T * R
    ctx.step("ik.wrist.R36", (sp.Symbol("M"), sp.Symbol("R03^T R")), (m, Mw))
    for i, j in itertools.product(range(3), range(3)):
        ctx.assign(m[i, j], target[i, j])
    q4, q5, q6 = ctx.q(4), ctx.q(5), ctx.q(6)
    wrist = {q4, q5, q6}
    cells = [(i, j) for i in range(3) for j in range(3) if Mw[i, j].free_symbols & wrist == {q5}]
    if not cells:
        raise _OutOfPatternError("no entry of R36 depends on q5 alone")
    i, j = cells[0]
    eq5 = _lin(Mw[i, j], q5)
    branches = solve_single(eq5, m[i, j])
    ctx.step("ik.wrist.q5", (Mw[i, j], m[i, j]), (q5, tuple(branches)), q=q5)
    ctx.assign(q5, *branches)
    rows = [k for k in range(3) if k != i]
    cols = [k for k in range(3) if k != j]
    for q, cells2 in ((q4, [(k, j) for k in rows]), (q6, [(i, k) for k in cols])):
        e1, e2 = (Mw[c] for c in cells2)
        pair = solve_pair(_lin(e1, q), _lin(e2, q), m[cells2[0]], m[cells2[1]])
        if pair is None:
            raise _OutOfPatternError(f"{q} is not fixed by R36")
        cos_q, sin_q = pair
        ctx.step(
            "ik.wrist.angle",
            (e1, m[cells2[0]]),
            (e2, m[cells2[1]]),
            (q, sp.atan2(sin_q, cos_q)),
            q=q,
            q5=q5,
        )
        ctx.assign(q, sp.atan2(sin_q, cos_q))
    ctx.step("ik.wrist.singular", q5=q5, q4=q4, q6=q6)


# ------------------------------------------------------------- per class
def _build(ctx: _Ctx, recipe: str | None) -> bool:
    """Fill ``ctx`` with the derivation ``recipe`` (the class's spec names it).

    Returns True when the target has an orientation.
    """
    p, R = target_symbols()
    n = ctx.model.dof
    tool_point = (len(ctx.chain), _origin())
    if recipe == "elbow-3R":
        end, local = tool_point
        W = _after_rotz(ctx, 1, end, local, ())
        U, V, u, v = _shoulder_q1(ctx, _frame1(ctx, p), W)
        _planar_pair(ctx, 2, 3, U, V, u, v)
        return False
    if recipe == "spherical-wrist":
        pm = _wrist_point(ctx, 5, p, R, "p_m")
        W = _after_rotz(ctx, 1, ctx.rotz[5], _origin(), (4,))
        U, V, u, v = _shoulder_q1(ctx, _frame1(ctx, pm), W)
        _planar_pair(ctx, 2, 3, U, V, u, v)
        _wrist_angles(ctx, R)
        return True
    if recipe == "planar-2R":
        _in_plane(ctx, _prod(ctx.chain)[:3, 3], p, 1, 2)
        return False
    if recipe == "planar-3R":
        pw = _wrist_point(ctx, 3, p, R, "p_w")
        _in_plane(ctx, _prod(ctx.chain[: ctx.rotz[3]])[:3, 3], pw, 1, 2)
        _last_angle(ctx, 3, R)
        return True
    if recipe == "planar-PR":
        _prismatic_revolute(ctx, _prod(ctx.chain)[:3, 3], p)
        return False
    if recipe == "planar-PRR":
        pw = _wrist_point(ctx, 3, p, R, "p_w")
        _prismatic_revolute(ctx, _prod(ctx.chain[: ctx.rotz[3]])[:3, 3], pw)
        _last_angle(ctx, 3, R)
        return True
    if recipe == "scara" and n == 4:
        pw = _wrist_point(ctx, 4, p, R, "p_w")
        Pw = _prod(ctx.chain[: ctx.rotz[4]])[:3, 3]
        _in_plane(ctx, Pw.xreplace({ctx.q(3): 0}), pw, 1, 2)
        _prismatic(ctx, 3, Pw, pw)
        _last_angle(ctx, 4, R)
        return True
    raise _OutOfPatternError(f"no textbook derivation {recipe!r}")


# ------------------------------------------------------------------ check
def _evaluate(
    plan: Sequence[Assign], env: Mapping[sp.Symbol, float]
) -> list[dict[sp.Symbol, float]]:
    fns: list[list[tuple[Callable[..., Any], list[sp.Symbol]]]] = []
    for a in plan:
        row = []
        for e in a.branches:
            args = sorted(e.free_symbols, key=str)
            row.append((sp.lambdify(args, e, modules="numpy"), args))
        fns.append(row)
    results = []
    for choice in itertools.product(*(range(len(a.branches)) for a in plan)):
        vals = dict(env)
        with np.errstate(all="ignore"):
            for a, row, c in zip(plan, fns, choice, strict=True):
                fn, args = row[c]
                vals[a.symbol] = float(np.real_if_close(fn(*(vals[s] for s in args))))
        results.append(vals)
    return results


def _check(ctx: _Ctx, plan: Sequence[Assign], pose: bool, seed: int = 0) -> bool:
    robot = ctx.model.robot
    rng = np.random.default_rng(seed)
    lim = robot.qlim
    lo = np.where(robot.is_prismatic, np.maximum(lim[:, 0], -1.0), -np.pi)
    hi = np.where(robot.is_prismatic, np.minimum(lim[:, 1], 1.0), np.pi)
    with warnings.catch_warnings():
        # derived solutions may lie beyond the joint limits: that is not the question here
        warnings.simplefilter("ignore", KinematicaWarning)
        return _check_poses(ctx, plan, pose, rng, lo, hi)


def _check_poses(
    ctx: _Ctx,
    plan: Sequence[Assign],
    pose: bool,
    rng: np.random.Generator,
    lo: NDArray[np.float64],
    hi: NDArray[np.float64],
) -> bool:
    model, robot = ctx.model, ctx.model.robot
    p, R = target_symbols()
    for _ in range(CHECK_POSES):
        q = rng.uniform(lo, hi)
        T0 = T = robot.fk(q)
        env: dict[sp.Symbol, float] = {s: float(v) for s, v in model.values.items()}
        env.update({s: float(T0[i, 3]) for i, s in enumerate(p)})
        env.update({R[i, j]: float(T0[i, j]) for i in range(3) for j in range(3)})
        good = 0
        for vals in _evaluate(plan, env):
            qs = np.array([vals.get(s, np.nan) for s in model.q])
            if not np.all(np.isfinite(qs)):
                continue
            Ts = robot.fk(qs)
            err = np.abs(Ts - T).max() if pose else np.abs(Ts[:3, 3] - T[:3, 3]).max()
            if err > CHECK_TOL:
                return False
            good += 1
        if good == 0:
            return False
    return True


def derive_inverse(model: SymbolicRobot) -> InverseDerivation | None:
    """The checked step-by-step closed-form IK of a robot, or ``None``.

    Args:
        model: The symbolic robot.

    Returns:
        The derivation when the robot's class has a textbook solution and the
        formulas, evaluated on random poses of the numeric robot, reproduce
        every one of them (every finite branch a solution); else ``None``.
    """
    structure = classify(model.robot)
    kind = structure.kind
    ctx = _context(model)
    try:
        pose = _build(ctx, structure.spec.derivation if structure.spec else None)
    # Any of these means the geometry is outside the textbook pattern (sympy's
    # polynomial tools raise their own errors on a non-polynomial entry): no
    # derivation is shown, and robot.ik still solves the arm.
    except (_OutOfPatternError, ArithmeticError, ValueError, TypeError, BasePolynomialError):
        return None
    if not _check(ctx, ctx.plan, pose):
        return None
    return InverseDerivation(kind, tuple(ctx.steps), tuple(ctx.plan))
