"""A report as a list of blocks (headings, sentences, equations, tables), one per language.

The content is decided here once; :mod:`kinematica.symbolic.render` prints the
same blocks as Markdown, LaTeX or HTML.
"""

from __future__ import annotations

import string
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp

from kinematica.ik.structure import features
from kinematica.robot import classify
from kinematica.symbolic.geometric import GeometricDerivation, derive_geometric
from kinematica.symbolic.inverse import InverseDerivation, derive_inverse, target_symbols
from kinematica.symbolic.jacobian import jacobian
from kinematica.symbolic.kinematics import Factor, factors, frames, link_matrices
from kinematica.symbolic.model import SymbolicRobot
from kinematica.symbolic.notation import short, short_names
from kinematica.symbolic.phrases import phrase, structure_summary
from kinematica.symbolic.printing import latex, mathml

__all__ = ["Block", "Equations", "Heading", "Notation", "Para", "Table", "build"]

#: A matrix whose entries print longer than this (LaTeX characters) is shown entry by entry.
MAX_ENTRY_CHARS = 48
#: Largest arm whose report shows the geometric Jacobian: a redundant arm's columns
#: take seconds more to put in textbook form (the Panda's about 7 s) for entries too
#: long to read; kinematica.symbolic.jacobian still gives them.
MAX_JACOBIAN_DOF = 6


@dataclass(frozen=True)
class Notation:
    """A fixed piece of notation in the three forms the renderers need."""

    latex: str
    mathml: str
    text: str


@dataclass(frozen=True)
class Heading:
    """A section heading (level 1 to 3)."""

    level: int
    parts: tuple[Any, ...]


@dataclass(frozen=True)
class Para:
    """A sentence: text and inline mathematics (sympy or :class:`Notation`)."""

    parts: tuple[Any, ...]


@dataclass(frozen=True)
class Equations:
    """Displayed equations ``lhs = rhs``; a tuple rhs lists alternative solutions."""

    rows: tuple[tuple[Any, Any], ...]


@dataclass(frozen=True)
class Table:
    """A table of text and mathematics."""

    header: tuple[Any, ...]
    rows: tuple[tuple[Any, ...], ...]


Block = Heading | Para | Equations | Table

BASE = Notation("T_{\\mathrm{base}}", "<msub><mi>T</mi><mi>base</mi></msub>", "Tbase")
TOOL = Notation("T_{\\mathrm{tool}}", "<msub><mi>T</mi><mi>tool</mi></msub>", "Ttool")


def _scripted(base: str, sub: str, pre: str = "") -> Notation:
    """``{}^{pre}base_{sub}`` (e.g. 0A1) in the three forms."""
    if pre:
        ml = (
            f"<mmultiscripts><mi>{base}</mi>{_mi(sub)}<none/><mprescripts/><none/>"
            f"{_mi(pre)}</mmultiscripts>"
        )
        return Notation(f"{{}}^{{{pre}}}{base}_{{{sub}}}", ml, f"{pre}{base}{sub}")
    return Notation(f"{base}_{{{sub}}}", f"<msub><mi>{base}</mi>{_mi(sub)}</msub>", base + sub)


def _transpose_product(a: str, b: str) -> Notation:
    """``(R_a)^T R_b`` in the three forms."""
    return Notation(
        f"\\left(R_{{{a}}}\\right)^{{T}} R_{{{b}}}",
        f"<msup><mrow><mo>(</mo><msub><mi>R</mi><mn>{a}</mn></msub><mo>)</mo></mrow>"
        f"<mi>T</mi></msup><msub><mi>R</mi><mn>{b}</mn></msub>",
        f"(R{a})^T R{b}",
    )


class _Writer:
    def __init__(self, model: SymbolicRobot, lang: str) -> None:
        self.model = model
        self.lang = lang
        self.blocks: list[Block] = []

    def fill(self, key: str, **args: Any) -> tuple[Any, ...]:
        parts: list[Any] = []
        for literal, field, _, _ in string.Formatter().parse(phrase(key, self.lang)):
            if literal:
                parts.append(literal)
            if field is not None:
                parts.append(args[field])
        return tuple(parts)

    def heading(self, level: int, key: str, **args: Any) -> None:
        self.blocks.append(Heading(level, self.fill(key, **args)))

    def para(self, key: str, **args: Any) -> None:
        self.blocks.append(Para(self.fill(key, **args)))

    def eqs(self, *rows: tuple[Any, Any]) -> None:
        self.blocks.append(Equations(tuple(rows)))

    def matrix(self, lhs: Any, M: sp.Matrix, names: sp.Matrix | None = None) -> None:
        """``lhs = M``, or entry by entry when the entries are long."""
        M = short(M)
        if max(len(sp.latex(e)) for e in M) <= MAX_ENTRY_CHARS or names is None:
            self.eqs((lhs, M))
            return
        self.eqs(*((n, e) for n, e in zip(names, M, strict=True) if n is not None))


def _short_legend(T: sp.Matrix) -> Notation | None:
    """``c1 = cos(q1), s23 = sin(q2 + q3)``: one of each kind ``T`` uses, or None if none.

    Taken from the equations themselves, so a prismatic q1 never gets a ``c1``.
    """
    names = short_names(T)

    def key(sym: sp.Symbol) -> tuple[int, bool, str]:
        return (len(sp.Add.make_args(names[sym].args[0])), str(sym)[0] != "c", str(sym))

    ordered = sorted(names, key=key)
    single = [sym for sym in ordered if len(sp.Add.make_args(names[sym].args[0])) == 1]
    summed = [sym for sym in ordered if len(sp.Add.make_args(names[sym].args[0])) > 1]
    examples = [sp.Eq(sym, names[sym]) for sym in (single[:1] + summed[:1])]
    if not examples:
        return None
    latex = ",\\; ".join(sp.latex(e) for e in examples)
    mathml = "<mo>,</mo>".join(sp.mathml(e, printer="presentation") for e in examples)
    return Notation(latex, mathml, ", ".join(str(e) for e in examples))


def _dh_table(model: SymbolicRobot, lang: str) -> Table:
    if model.convention == "standard":
        keys = ("theta", "d", "a", "alpha")
        header = (
            "i",
            sp.Symbol("theta_i"),
            sp.Symbol("d_i"),
            sp.Symbol("a_i"),
            sp.Symbol("alpha_i"),
        )
    else:
        keys = ("a", "alpha", "theta", "d")
        header = (
            "i",
            Notation(
                "a_{i-1}",
                "<msub><mi>a</mi><mrow><mi>i</mi><mo>-</mo><mn>1</mn></mrow></msub>",
                "a(i-1)",
            ),
            Notation(
                "\\alpha_{i-1}",
                "<msub><mi>&alpha;</mi><mrow><mi>i</mi><mo>-</mo><mn>1</mn></mrow></msub>",
                "alpha(i-1)",
            ),
            sp.Symbol("theta_i"),
            sp.Symbol("d_i"),
        )
    rows = tuple(
        (str(i), *(getattr(row, k) for k in keys), phrase(f"kind.{row.kind}", lang))
        for i, row in enumerate(model.rows, 1)
    )
    return Table((*header, phrase("joint", lang)), rows)


def _forward(w: _Writer, model: SymbolicRobot) -> sp.Matrix:
    n = model.dof
    w.heading(2, "h.dh")
    A = _scripted("A", "i", "i-1")
    w.para(f"dh.{model.convention}", A=A)
    w.blocks.append(Para((_factor_formula(model.convention, w.lang),)))
    w.blocks.append(_dh_table(model, w.lang))
    if model.values:
        w.para("params")
        w.eqs(*((s, sp.Float(v, 6)) for s, v in sorted(model.values.items(), key=str)))
    if model.base != sp.eye(4):
        w.para("base")
        w.eqs((BASE, model.base))
    if model.tool != sp.eye(4):
        w.para("tool", n=sp.Integer(n))
        w.eqs((TOOL, model.tool))

    w.heading(2, "h.links")
    mats = link_matrices(model)
    for i, Ai in enumerate(mats, 1):
        w.heading(3, "h.row", i=str(i))
        w.para("row.factors", i=str(i))
        w.eqs(*((_factor_name(f, w.lang), f.matrix) for f in factors(model, i)))
        w.para("row.product", A=_scripted("A", str(i), str(i - 1)))
        w.eqs((_scripted("A", str(i), str(i - 1)), short(Ai)))

    w.heading(2, "h.T")
    T = frames(model)[-1]
    w.para("T.text", n=sp.Integer(n))
    w.blocks.append(Para((_chain_formula(n, model.base != sp.eye(4), model.tool != sp.eye(4)),)))
    p, R = target_symbols()
    if max(len(sp.latex(e)) for e in short(T)) <= MAX_ENTRY_CHARS:
        w.eqs((sp.Symbol("T"), short(T)))
    else:  # too long to print whole: T by the names of its entries, each given below
        named = sp.Matrix(4, 4, lambda i, j: R[i, j] if i < 3 and j < 3 else 0)
        named[:3, 3] = p
        named[3, 3] = 1
        w.eqs((sp.Symbol("T"), named))
        w.para("T.entries")

    w.heading(2, "h.position")
    legend = _short_legend(T)
    if legend is None:
        w.para("position.plain")
    else:
        w.para("position.text", short=legend)
    w.eqs(*((p[i], short(T[i, 3])) for i in range(3)))
    w.heading(2, "h.orientation")
    w.para("orientation.text")
    w.eqs(*((R[i, j], short(T[i, j])) for i in range(3) for j in range(3)))
    return T


def _jacobian(w: _Writer, model: SymbolicRobot) -> None:
    w.heading(2, "h.jacobian")
    w.para(f"jacobian.{model.convention}")
    J = jacobian(model)
    for i in range(model.dof):
        names = sp.Matrix([sp.Symbol(f"J_{k}{i + 1}") for k in range(1, 7)])
        w.matrix(sp.Symbol(f"J_{i + 1}"), J[:, i], names)


#: A parenthesis of inline notation: MathML stretches an ``<mo>(</mo>`` to the
#: tallest item of its row (the matrix beside ``Rot(z, q1) =``) unless told not to.
_OPEN, _CLOSE = '<mo stretchy="false">(</mo>', '<mo stretchy="false">)</mo>'


def _factor_name(f: Factor, lang: str) -> Notation:
    """``Rot(z, q2 + pi/2)``, ``Tras(x, l2)`` (``Trans`` in English) in the three forms."""
    kind = phrase(f"op.{f.kind}", lang)
    return Notation(
        f"\\mathrm{{{kind}}}({f.axis}, {latex(f.value)})",
        f"<mrow><mi>{kind}</mi>{_OPEN}<mi>{f.axis}</mi><mo>,</mo>{mathml(f.value)}{_CLOSE}</mrow>",
        f"{kind}({f.axis}, {f.value})",
    )


def _mi(x: str) -> str:
    return f"<mn>{x}</mn>" if x.isdigit() else f"<mi>{x}</mi>"


def _factor_formula(convention: str, lang: str) -> Notation:
    """``i-1Ai = Rot(z, θi)·Tras(z, di)·Tras(x, ai)·Rot(x, αi)`` (or Craig's order)."""
    trans = phrase("op.Tras", lang)
    sub = "i" if convention == "standard" else "i-1"
    sub_ml = "<mi>i</mi>" if sub == "i" else "<mrow><mi>i</mi><mo>-</mo><mn>1</mn></mrow>"
    items = [
        ("Rot", "z", "\\theta", "&theta;", "i", "<mi>i</mi>"),
        (trans, "z", "d", "d", "i", "<mi>i</mi>"),
        (trans, "x", "a", "a", sub, sub_ml),
        ("Rot", "x", "\\alpha", "&alpha;", sub, sub_ml),
    ]
    if convention != "standard":
        items = [items[3], items[2], items[0], items[1]]
    lhs = _scripted("A", "i", "i-1")
    latex = (
        lhs.latex
        + " = "
        + " \\cdot ".join(
            f"\\mathrm{{{k}}}({ax}, {sym}_{{{sb}}})" for k, ax, sym, _, sb, _ in items
        )
    )
    mathml = (
        lhs.mathml
        + "<mo>=</mo>"
        + "<mo>&middot;</mo>".join(
            f"<mi>{k}</mi>{_OPEN}<mi>{ax}</mi><mo>,</mo><msub><mi>{ml}</mi>{sbml}</msub>{_CLOSE}"
            for k, ax, _, ml, _, sbml in items
        )
    )
    text = "i-1Ai = " + " · ".join(
        f"{k}({ax}, {sym.strip(chr(92))}{sb})" for k, ax, sym, _, sb, _ in items
    )
    return Notation(latex, mathml, text)


def _chain_formula(n: int, base: bool, tool: bool) -> Notation:
    """``T = Tbase · 0A1 · ... · (n-1)An · Ttool``."""
    parts = [_scripted("A", str(i), str(i - 1)) for i in range(1, n + 1)]
    if base:
        parts.insert(0, BASE)
    if tool:
        parts.append(TOOL)
    return Notation(
        "T = " + " \\cdot ".join(p.latex for p in parts),
        "<mi>T</mi><mo>=</mo>" + "<mo>&middot;</mo>".join(p.mathml for p in parts),
        "T = " + " · ".join(p.text for p in parts),
    )


def _geometric(w: _Writer, g: GeometricDerivation, model: SymbolicRobot) -> None:
    w.heading(2, "h.geometric")
    if g.kind == "planar":
        zero = {q: 0 for q in model.q}
        axis = next(
            f
            for i in range(1, model.dof + 1)
            for f in [_axis(model, i)]
            if model.rows[i - 1].kind == "R"
        )
        w.para("geo.planar", k=axis.xreplace(zero).T)
        # a table, not named vectors: s1, s2 would read as sin q1, sin q2
        header = tuple(phrase(f"geo.col.{c}", w.lang) for c in ("segment", "angle", "vector"))
        rows = tuple((str(i), a, v.T) for i, (a, v) in enumerate(g.segments, 1))
        w.blocks.append(Table(header, rows))
    else:
        w.para("geo.arm_plane", q=model.q[0])
        w.eqs(*((s, short(e)) for s, e in g.extra))
    w.para("geo.result")
    p, _ = target_symbols()
    w.eqs(*((p[i], short(g.position[i])) for i in range(3)))
    w.para("geo.agrees" if g.agrees else "geo.differs")


def _axis(model: SymbolicRobot, i: int) -> sp.Matrix:
    """Direction of joint i's axis in the world frame (from the DH factors)."""
    T = sp.Matrix(model.base)
    for k in range(1, i + 1):
        for f in factors(model, k):
            if k == i and f.kind == "Rot" and f.axis == "z":
                return sp.simplify(T[:3, 2])
            T = T * f.matrix
    raise AssertionError("unreachable")


def _display(value: Any) -> Any:
    if isinstance(value, tuple):
        return tuple(_display(v) for v in value)
    if isinstance(value, sp.Basic | sp.MatrixBase):
        return short(value)
    return value


def _inverse(w: _Writer, d: InverseDerivation | None, model: SymbolicRobot, method: str) -> None:
    w.heading(2, "h.ik")
    structure = classify(model.robot)
    if d is None:
        # a recipe with no symbolic steps (yet) is said in words
        recipe = structure.spec.derivation if structure.spec is not None else None
        key = "ik.reversed" if recipe == "reversed-spherical-wrist" else "ik.none"
        if structure.kind == "general-6R":
            key = "ik.general6r"
        w.para(key, summary=structure_summary(structure, w.lang), method=method)
        return
    p, R = target_symbols()
    has_pose = any(s.key in ("ik.last", "ik.wrist.R36") for s in d.steps)
    if has_pose:
        w.para("ik.target", p=p.T, R=R)
    else:
        w.para("ik.target_position", p=p.T, n=sp.Integer(model.dof))
    q = model.q
    for step in d.steps:
        args = {k: _display(v) for k, v in step.args.items()}
        if step.key == "ik.wrist.R36":
            args = {
                "q123": sp.Tuple(*q[:3]),
                "R03": _scripted("R", "3", "0"),
                "R36": Notation(
                    "{}^{3}R_{6} = " + _transpose_product("03", "06").latex,
                    "<mmultiscripts><mi>R</mi><mn>6</mn><none/><mprescripts/><none/><mn>3</mn>"
                    "</mmultiscripts><mo>=</mo>" + _transpose_product("03", "06").mathml,
                    "3R6 = (R03)^T R06",
                ),
            }
            r03t_r = Notation(
                "\\left({}^{0}R_{3}\\right)^{T} R",
                "<msup><mrow><mo>(</mo><mmultiscripts><mi>R</mi><mn>3</mn><none/><mprescripts/>"
                "<none/><mn>0</mn></mmultiscripts><mo>)</mo></mrow><mi>T</mi></msup><mi>R</mi>",
                "(0R3)^T R",
            )
            rows: list[tuple[Any, Any]] = [(sp.Symbol("M"), r03t_r)]
            rows.append((step.equations[1][0], short(step.equations[1][1])))
            w.para(step.key, **args)
            w.eqs(*rows)
            continue
        w.para(step.key, **args)
        if step.equations:
            w.eqs(*((_display(lhs), _display(rhs)) for lhs, rhs in step.equations))
    w.para("ik.count", n=sp.Integer(d.solutions))


#: The configuration (degrees) of the report's numeric decoupling: the demo's and the
#: README's picture's, within the limits of the built-in 6R arms.
EXAMPLE_Q_DEG = (30.0, 40.0, -30.0, 10.0, 60.0, -20.0)


def _number(v: float) -> sp.Float:
    """A value as the example prints it: 4 decimals."""
    return sp.Float(f"{float(v) + 0.0:.4f}")


def _numbers(M: Any) -> sp.Matrix:
    return sp.Matrix(np.vectorize(_number, otypes=[object])(np.atleast_1d(M)))


def _decoupling_example(w: _Writer, model: SymbolicRobot) -> None:
    """Seed 002's decoupling with numbers, step by step, for a 6R arm with a spherical wrist."""
    robot = model.robot
    if robot.dof != 6 or robot.joint_types != "RRRRRR" or robot.transforms is not None:
        return
    if features(robot.chain).wrist_center is None:
        return
    q = np.radians(EXAMPLE_Q_DEG)
    T = robot.with_limits([None] * 6).fk(q)
    steps = robot.decouple(T)
    deg = [sp.Tuple(*(sp.Integer(round(v)) for v in EXAMPLE_Q_DEG))]
    w.heading(2, "h.decoupling")
    w.para("dec.target", q=deg[0])
    w.eqs((sp.Symbol("T"), _numbers(T)))
    w.para("dec.pm", c=_numbers(steps.offset).T)
    w.eqs((sp.Symbol("p_m"), _numbers(steps.wrist_center).T))
    w.para("dec.arms", n=sp.Integer(len(steps.arms)))
    names = model.q
    for k, arm in enumerate(steps.arms, start=1):
        w.para("dec.arm", k=sp.Integer(k))
        rows: list[tuple[Any, Any]] = [
            (sp.Tuple(*names[:3]), sp.Tuple(*_numbers(np.degrees(arm.q)))),
            (_scripted("R", "3", "0"), _numbers(arm.R03)),
            (_scripted("R", "6", "3"), _numbers(arm.R36)),
        ]
        rows += [(sp.Tuple(*names[3:]), sp.Tuple(*_numbers(np.degrees(v)))) for v in arm.wrist]
        w.eqs(*rows)
    w.para("dec.check", n=sp.Integer(steps.solutions.shape[0]))


def build(model: SymbolicRobot, lang: str) -> list[Block]:
    """Every block of the report of ``model`` in ``lang`` (``"es"`` or ``"en"``)."""
    w = _Writer(model, lang)
    w.heading(1, "title", name=model.name)
    w.para("intro", q=sp.Tuple(*model.q))
    structure = classify(model.robot)
    w.para("structure", summary=structure_summary(structure, lang))
    _forward(w, model)
    if model.dof <= MAX_JACOBIAN_DOF:
        _jacobian(w, model)
    geo = derive_geometric(model)
    if geo is not None:
        _geometric(w, geo, model)
    method = "numeric:lm"
    d = derive_inverse(model)
    if d is None and structure.kind != "general":
        method = f"analytic ({structure.kind})"
    _inverse(w, d, model, method)
    _decoupling_example(w, model)
    return w.blocks
