"""Textbook form of kinematic expressions, and the short notation c1, s23, c234.

:func:`tidy` brings an entry of a DH product to the form the seeds write: the
products of sines and cosines of parallel joints are folded into sines and
cosines of sums (``c2 c3 - s2 s3`` is ``c23``), and the terms are collected by
the trigonometric functions of the joints, base first
(``px = c1 (a2 c2 + a3 c23)``). :func:`short` then writes ``cos(q2 + q3)`` as
``c23``.
"""

from __future__ import annotations

from typing import TypeVar

import sympy as sp
from sympy.simplify.fu import TR10i

from kinematica.symbolic.model import joint_index

__all__ = ["short", "short_names", "tidy"]

_E = TypeVar("_E", sp.Expr, sp.MatrixBase)


def _joint_trig(expr: sp.Expr) -> list[sp.Expr]:
    """``cos``/``sin`` factors of the expression, ordered by their lowest joint."""
    found = {f for f in expr.atoms(sp.sin, sp.cos) if _joints(f.args[0])}

    def key(f: sp.Expr) -> tuple[int, int, int, str]:
        joints = _joints(f.args[0])
        return (min(joints), len(joints), 0 if isinstance(f, sp.cos) else 1, str(f))

    return sorted(found, key=key)


def _joints(arg: sp.Expr) -> list[int]:
    return sorted(i for s in arg.free_symbols if (i := joint_index(s)) is not None)


def _collect(expr: sp.Expr) -> sp.Expr:
    """Collect by the first joint's cos/sin, recursively in each coefficient."""
    if not isinstance(expr, sp.Add):
        return sp.factor_terms(expr)
    trig = _joint_trig(expr)
    if not trig:
        return sp.factor_terms(expr)
    first = min(min(_joints(f.args[0])) for f in trig)
    pivots = [f for f in trig if _joints(f.args[0]) == [first]]
    if not pivots:
        return sp.factor_terms(expr)
    collected = sp.collect(expr, pivots, evaluate=False)
    terms = []
    for factor, coeff in collected.items():
        inner = _collect(sp.expand(coeff))
        terms.append(factor * inner)
    return sp.Add(*terms)


def _tidy_scalar(expr: sp.Expr, fold: bool = True) -> sp.Expr:
    e = sp.expand(sp.sympify(expr))
    if not fold or not e.has(sp.sin, sp.cos):
        return _collect(e)
    # TR10i folds c_i c_j - s_i s_j into cos(q_i + q_j) and the like; twice,
    # so that a sum of three (c234) is reached from c23 c4 - s23 s4.
    for _ in range(2):
        folded = sp.expand(TR10i(e))
        if folded == e:
            break
        e = folded
    return _collect(e)


def tidy(expr: _E, fold: bool = True) -> _E:
    """The textbook form of an expression or of every entry of a matrix.

    Args:
        expr: A sympy expression or matrix, polynomial in sines and cosines of
            the joint symbols.
        fold: Fold products of sines and cosines into sums of angles. A linear
            combination of entries already folded (a constant base or tool
            times a chain of link matrices) needs no folding: ``False`` saves
            the (costly) search.

    Returns:
        The same value, with sums of joint angles folded and terms collected
        by the base-most joint.
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(lambda e: _tidy_scalar(e, fold))
    return _tidy_scalar(expr, fold)


def _short_name(f: sp.Expr) -> sp.Symbol | None:
    """``c23`` for ``cos(q2 + q3)``, ``s1`` for ``sin(q1)``; ``None`` if not a plain sum."""
    arg = f.args[0]
    terms = sp.Add.make_args(arg)
    indices = []
    for term in terms:
        i = joint_index(term)
        if i is None:
            return None
        indices.append(i)
    indices.sort()
    sep = "," if any(i > 9 for i in indices) else ""
    letter = "c" if isinstance(f, sp.cos) else "s"
    return sp.Symbol(letter + sep.join(map(str, indices)))


def short_names(expr: sp.Expr | sp.MatrixBase) -> dict[sp.Symbol, sp.Expr]:
    """The short symbols :func:`short` would write in ``expr``: ``{c1: cos(q1), s23: ...}``.

    Args:
        expr: A sympy expression or matrix.

    Returns:
        Each short symbol and the sine or cosine it stands for.
    """
    e = sp.Matrix(expr) if isinstance(expr, sp.MatrixBase) else sp.sympify(expr)
    out = {}
    for f in e.atoms(sp.sin, sp.cos):
        name = _short_name(f)
        if name is not None:
            out[name] = f
    return out


def short(expr: _E) -> _E:
    """The short notation of the seeds: ``c1`` for cos q1, ``s23`` for sin(q2 + q3).

    Only sines and cosines of a joint symbol or of a plain sum of joint
    symbols are shortened; ``cos(q2 - q3)`` or ``cos(q1 + pi/7)`` stay as
    they are. Indices above 9 are separated by commas (``c9,10``).

    Args:
        expr: A sympy expression or matrix (e.g. from :func:`position`).

    Returns:
        The same expression with the symbols ``c1``, ``s23``, ``c234`` ... in
        place of those sines and cosines (print it with any sympy printer).
    """
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(short)
    e = sp.sympify(expr)
    mapping = {}
    for f in e.atoms(sp.sin, sp.cos):
        name = _short_name(f)
        if name is not None:
            mapping[f] = name
    return e.xreplace(mapping)
