"""Printing a report's blocks as Markdown, LaTeX (amsmath) or HTML (MathML, offline).

Markdown carries its mathematics as LaTeX between ``$`` signs (GitHub, pandoc
and Jupyter render it); the LaTeX file needs amsmath only; the HTML page is
self-contained: presentation MathML from sympy's printer, shown by browsers
with no script, font or network access.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from typing import Any, Final

import sympy as sp

from kinematica.io.markdown import markdown_text
from kinematica.symbolic.document import Block, Equations, Heading, Notation, Para
from kinematica.symbolic.phrases import phrase
from kinematica.symbolic.printing import latex, mathml

__all__ = ["FORMATS", "render"]

FORMATS: Final = ("markdown", "latex", "html")

#: Longest line of a displayed LaTeX sum (characters of source) before it is broken.
LATEX_LINE = 110


def _latex_lines(expr: Any) -> list[str]:
    """A long sum split over several lines (LaTeX has no automatic breaks in maths)."""
    whole = latex(expr)
    if isinstance(expr, Notation) or len(whole) <= LATEX_LINE or not isinstance(expr, sp.Add):
        return [whole]
    lines, current = [], ""
    for k, term in enumerate(sp.Add.make_args(expr)):
        neg = term.could_extract_minus_sign()
        body = latex(-term if neg else term)
        piece = ("- " if neg else ("+ " if k else "")) + body
        if current and len(current) + len(piece) > LATEX_LINE:
            lines.append(current)
            current = ""
        current += (" " if current else "") + piece
    lines.append(current)
    return lines


# ------------------------------------------------------------------ markdown
def _md_parts(parts: Sequence[Any]) -> str:
    return "".join(markdown_text(p) if isinstance(p, str) else f"${latex(p)}$" for p in parts)


def _md(blocks: Sequence[Block], lang: str) -> str:
    out: list[str] = []
    for b in blocks:
        if isinstance(b, Heading):
            out.append("#" * b.level + " " + _md_parts(b.parts))
        elif isinstance(b, Para):
            out.append(_md_parts(b.parts))
        elif isinstance(b, Equations):
            rows = _latex_rows(b, lang)
            out.append("$$\n\\begin{aligned}\n" + " \\\\\n".join(rows) + "\n\\end{aligned}\n$$")
        else:
            cell = lambda c: markdown_text(c) if isinstance(c, str) else f"${latex(c)}$"  # noqa: E731
            lines = ["| " + " | ".join(cell(c) for c in b.header) + " |"]
            lines.append("|" + "---|" * len(b.header))
            lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in b.rows]
            out.append("\n".join(lines))
    return "\n\n".join(out) + "\n"


def _latex_rows(b: Equations, lang: str) -> list[str]:
    """Rows of an ``align*``/``aligned``: long sums broken, alternatives one per line."""
    rows: list[str] = []
    word = phrase("or", lang)
    for lhs, rhs in b.rows:
        for k, alt in enumerate(rhs if isinstance(rhs, tuple) else (rhs,)):
            lead = f"\\text{{{word}}} \\quad " if k else ""
            lines = _latex_lines(alt)
            rows.append(f"{lead}{latex(lhs)} &= {lines[0]}")
            rows += [f"&\\quad {line}" for line in lines[1:]]
    return rows


# --------------------------------------------------------------------- latex
_TEX_ESCAPES: Final = {
    "\\": "\\textbackslash{}",
    "&": "\\&",
    "%": "\\%",
    "$": "\\$",
    "#": "\\#",
    "_": "\\_",
    "{": "\\{",
    "}": "\\}",
    "~": "\\textasciitilde{}",
    "^": "\\textasciicircum{}",
}


def _tex_text(text: str) -> str:
    return "".join(_TEX_ESCAPES.get(ch, ch) for ch in text)


def _tex_parts(parts: Sequence[Any]) -> str:
    return "".join(_tex_text(p) if isinstance(p, str) else f"${latex(p)}$" for p in parts)


def _tex(blocks: Sequence[Block], lang: str) -> str:
    title = _tex_parts(blocks[0].parts) if blocks and isinstance(blocks[0], Heading) else ""
    body: list[str] = []
    for b in blocks:
        if isinstance(b, Heading):
            if b.level == 1:
                continue
            cmd = "section*" if b.level == 2 else "subsection*"
            body.append(f"\\{cmd}{{{_tex_parts(b.parts)}}}")
        elif isinstance(b, Para):
            body.append(_tex_parts(b.parts) + "\n")
        elif isinstance(b, Equations):
            rows = _latex_rows(b, lang)
            body.append("\\begin{align*}\n" + " \\\\\n".join(rows) + "\n\\end{align*}")
        else:
            cols = "c" * len(b.header)
            cell = lambda c: _tex_text(c) if isinstance(c, str) else f"${latex(c)}$"  # noqa: E731
            lines = [" & ".join(cell(c) for c in b.header) + " \\\\ \\hline"]
            lines += [" & ".join(cell(c) for c in row) + " \\\\" for row in b.rows]
            body.append(
                "\\begin{center}\n\\begin{tabular}{"
                + cols
                + "}\n"
                + "\n".join(lines)
                + "\n\\end{tabular}\n\\end{center}"
            )
    return (
        "\\documentclass[a4paper,10pt]{article}\n"
        "\\usepackage[utf8]{inputenc}\n"
        "\\usepackage[T1]{fontenc}\n"
        "\\usepackage{amsmath}\n"
        "\\setlength{\\parindent}{0pt}\n"
        "\\setlength{\\parskip}{0.6em}\n"
        "\\allowdisplaybreaks\n"
        f"\\title{{{title}}}\n\\date{{}}\n"
        "\\begin{document}\n\\maketitle\n\n" + "\n\n".join(body) + "\n\n\\end{document}\n"
    )


# ---------------------------------------------------------------------- html
_CSS: Final = """
body { font-family: Georgia, 'DejaVu Serif', serif; max-width: 60em; margin: 2em auto;
       padding: 0 1em; line-height: 1.5; color: #222; }
h1, h2, h3 { font-family: 'DejaVu Sans', Arial, sans-serif; color: #1a3a5a; }
div.eq { overflow-x: auto; overflow-y: hidden; margin: 0.4em 0 0.8em 1.5em; padding: 0.2em 0; }
div.eq math { text-align: left; }
table.dh { border-collapse: collapse; margin: 0.5em 1.5em; }
table.dh td, table.dh th { border-bottom: 1px solid #bbb; padding: 0.2em 1em; text-align: center; }
"""


def _html_parts(parts: Sequence[Any]) -> str:
    return "".join(
        html.escape(p) if isinstance(p, str) else f"<math>{mathml(p)}</math>" for p in parts
    )


def _html(blocks: Sequence[Block], lang: str) -> str:
    first = blocks[0] if blocks else None
    title = "".join(map(str, first.parts)) if isinstance(first, Heading) else ""
    body: list[str] = []
    word = html.escape(phrase("or", lang))
    for b in blocks:
        if isinstance(b, Heading):
            body.append(f"<h{b.level}>{_html_parts(b.parts)}</h{b.level}>")
        elif isinstance(b, Para):
            body.append(f"<p>{_html_parts(b.parts)}</p>")
        elif isinstance(b, Equations):
            for lhs, rhs in b.rows:
                alts = rhs if isinstance(rhs, tuple) else (rhs,)
                gap = f'<mspace width="1.5em"/><mtext>{word}</mtext><mspace width="1.5em"/>'
                shown = gap.join(mathml(r) for r in alts)
                body.append(
                    f'<div class="eq"><math display="block"><mrow>{mathml(lhs)}<mo>=</mo>'
                    f"{shown}</mrow></math></div>"
                )
        else:
            cell = lambda c: html.escape(c) if isinstance(c, str) else f"<math>{mathml(c)}</math>"  # noqa: E731
            head = "".join(f"<th>{cell(c)}</th>" for c in b.header)
            rows = "".join(
                "<tr>" + "".join(f"<td>{cell(c)}</td>" for c in row) + "</tr>" for row in b.rows
            )
            body.append(
                f'<table class="dh"><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>'
            )
    return (
        f'<!DOCTYPE html>\n<html lang="{lang}">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{html.escape(title)}</title>\n<style>{_CSS}</style>\n</head>\n<body>\n"
        + "\n".join(body)
        + "\n</body>\n</html>\n"
    )


def render(blocks: Sequence[Block], format: str, lang: str) -> str:
    """The report in ``format`` (``"markdown"``, ``"latex"`` or ``"html"``)."""
    return {"markdown": _md, "latex": _tex, "html": _html}[format](blocks, lang)
