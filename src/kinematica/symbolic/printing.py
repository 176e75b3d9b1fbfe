"""sympy's LaTeX and presentation-MathML printers, with ``atan2(y, x)`` as the seeds write it."""

from __future__ import annotations

import re
from typing import Any

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.mathml import MathMLPresentationPrinter

__all__ = ["latex", "mathml"]


class _Latex(LatexPrinter):
    """sympy's LaTeX with ``atan2(y, x)`` written as the seeds write it."""

    def _print_atan2(self, expr: sp.Expr) -> str:
        y, x = (self._print(a) for a in expr.args)
        return f"\\operatorname{{atan2}}\\left({y}, {x}\\right)"


class _MathML(MathMLPresentationPrinter):
    """sympy's presentation MathML with ``atan2(y, x)``."""

    def _print_atan2(self, expr: sp.Expr) -> Any:
        row = self.dom.createElement("mrow")
        name = self.dom.createElement("mi")
        name.appendChild(self.dom.createTextNode("atan2"))
        row.appendChild(name)
        args = self.dom.createElement("mrow")
        for k, token in enumerate(("(", ",", ")")):
            mo = self.dom.createElement("mo")
            mo.appendChild(self.dom.createTextNode(token))
            args.appendChild(mo)
            if k < 2:
                args.appendChild(self._print(expr.args[k]))
        row.appendChild(args)
        return row


def latex(item: Any) -> str:
    """LaTeX (math mode) of a sympy object or :class:`Notation`."""
    if hasattr(item, "latex") and not isinstance(item, sp.Basic):
        return str(item.latex)
    return str(_Latex({"mat_delim": "["}).doprint(sp.sympify(item)))


#: The minus operator. sympy and our notation write the ASCII hyphen-minus, which
#: Chromium's MathML shows as a short hyphen; the minus sign U+2212 is what MathML means.
_MINUS = "<mo>\u2212</mo>"


def mathml(item: Any) -> str:
    """Presentation MathML (the content of a ``<math>`` element), minus signs as U+2212."""
    if hasattr(item, "mathml") and not isinstance(item, sp.Basic):
        text = str(item.mathml)
    else:
        text = str(_MathML().doprint(sp.sympify(item)))
    return re.sub(r"<mn>-(?=[0-9.])", _MINUS + "<mn>", text.replace("<mo>-</mo>", _MINUS))
