"""The two trigonometric equations every closed-form derivation of the seeds reduces to.

1. One equation ``A cos q + B sin q + K = v`` (seed 002's ``cos q3 = ...``, seed
   000's ``sin q2 = y / l2``): two solutions,
   ``q = atan2(B, A) ± acos((v - K) / sqrt(A² + B²))``.
2. Two equations linear in ``cos q`` and ``sin q`` (seed 002's ``q2``): one
   solution, ``q = atan2(sin q, cos q)`` from Cramer's rule.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final

import sympy as sp

from kinematica.symbolic.notation import tidy

__all__ = ["COEFF_TOL", "Linear", "linear_cs", "solve_pair", "solve_single"]

#: A numeric coefficient below this (relative to the largest one) is a rounding
#: residue of exact cancellation (c² + s² = 1 with floats) and is dropped.
COEFF_TOL: Final = 1e-12


@dataclass(frozen=True)
class Linear:
    """``A cos q + B sin q + K``, with A, B, K free of q."""

    A: sp.Expr
    B: sp.Expr
    K: sp.Expr


def _chop(coeffs: dict[tuple[int, ...], sp.Expr]) -> dict[tuple[int, ...], sp.Expr]:
    numeric = [abs(float(c)) for c in coeffs.values() if c.is_number]
    scale = max(numeric, default=0.0)
    out = {}
    for monom, c in coeffs.items():
        if c.is_number and abs(float(c)) <= COEFF_TOL * max(scale, 1.0):
            continue
        out[monom] = c
    return out


def linear_cs(expr: sp.Expr, q: sp.Symbol) -> Linear | None:
    """``expr`` as ``A cos q + B sin q + K``, or ``None`` if it is not of that form.

    Sines and cosines of sums are expanded; ``sin² q`` becomes ``1 - cos² q``.
    """
    e = sp.expand(sp.expand_trig(sp.sympify(expr)))
    C, S = sp.Dummy("C"), sp.Dummy("S")
    e = e.xreplace({sp.cos(q): C, sp.sin(q): S})
    if e.has(q):
        return None
    _, rem = sp.reduced(sp.expand(e), [S**2 + C**2 - 1], S, C)
    poly = sp.Poly(sp.expand(rem), S, C)
    coeffs = _chop(dict(poly.as_dict()))
    if any(sum(m) > 1 for m in coeffs):
        return None
    zero = sp.Integer(0)
    return Linear(
        A=tidy(coeffs.get((0, 1), zero)),
        B=tidy(coeffs.get((1, 0), zero)),
        K=tidy(coeffs.get((0, 0), zero)),
    )


def solve_single(eq: Linear, value: sp.Expr) -> list[sp.Expr]:
    """Both solutions of ``A cos q + B sin q + K = value``.

    Returns:
        Two expressions (the ``+`` and the ``-`` branch): ``acos`` when
        ``B = 0``, ``asin`` and ``pi - asin`` when ``A = 0``, else
        ``atan2(B, A) ± acos((value - K) / sqrt(A² + B²))``.

    Raises:
        ValueError: ``A`` and ``B`` are both zero (q does not appear).
    """
    A, B = eq.A, eq.B
    rhs = value - eq.K
    if A == 0 and B == 0:
        raise ValueError("the joint does not appear in the equation")
    if B == 0:
        x = rhs / A
        return [sp.acos(x), -sp.acos(x)]
    if A == 0:
        x = rhs / B
        return [sp.asin(x), sp.pi - sp.asin(x)]
    norm = sp.sqrt(tidy(sp.expand(A**2 + B**2)))
    x = rhs / norm
    return [sp.atan2(B, A) + sp.acos(x), sp.atan2(B, A) - sp.acos(x)]


def solve_pair(
    first: Linear, second: Linear, v1: sp.Expr, v2: sp.Expr
) -> tuple[sp.Expr, sp.Expr] | None:
    """``(cos q, sin q)`` from two equations linear in them (Cramer's rule).

    ``first`` = ``v1`` and ``second`` = ``v2``; ``None`` when the determinant is
    identically zero (the equations do not fix q).
    """
    a, b, c, d = first.A, first.B, second.A, second.B
    det = tidy(sp.expand(a * d - b * c))
    if det == 0:
        return None
    r1, r2 = v1 - first.K, v2 - second.K
    shown = sp.factor_terms(a * d - b * c)  # (a2 + a3 c3)² + a3² s3², as seed 002 writes it
    return _ratio(d * r1 - b * r2, det, shown), _ratio(a * r2 - c * r1, det, shown)


def _ratio(num: sp.Expr, det: sp.Expr, shown: sp.Expr) -> sp.Expr:
    """``num / det``, cancelled when they share a factor (the wrist's sin q5)."""
    top = tidy(sp.expand(num))
    common = sp.gcd(sp.expand(top), sp.expand(det))
    if common.free_symbols:
        return sp.factor_terms(sp.cancel(top / det))
    return top / shown
