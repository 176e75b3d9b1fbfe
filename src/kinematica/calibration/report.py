"""The calibration report: a Markdown page and its two pictures, in Spanish or English.

``calibration.md`` holds the residuals before and after, the identifiability findings in
words, the correlated pairs, the parameter table and the DH table's error; beside it
``calibration-histogram.png`` (the residuals' histograms before and after) and
``calibration-residuals.png`` (each measurement's residual, before and after, along the
measurement set). The pictures are drawn with matplotlib's object API on an Agg canvas
(no pyplot state).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from kinematica.calibration.identify import CORRELATION_LIMIT
from kinematica.calibration.words import (
    LANGS,
    correlation_text,
    finding_text,
    parameter_label,
    phrase,
)
from kinematica.errors import ArgumentError, KinematicaError
from kinematica.io.atomic import write_text_atomic

if TYPE_CHECKING:
    from kinematica.calibration.fit import CalibrationResult

__all__ = ["report_text", "write_report"]

#: Bins of the residual histograms.
BINS = 20


def _angle(v: float, degrees: bool) -> float:
    return math.degrees(v) if degrees else v


def report_text(
    result: CalibrationResult, lang: str = "es", *, degrees: bool = True, stem: str = "calibration"
) -> str:
    """The report's Markdown text (pictures referred to as ``{stem}-histogram.png``...).

    Args:
        result: The calibration.
        lang: ``"es"`` or ``"en"``.
        degrees: Angles of the parameter table in degrees (else radians).
        stem: The file name the pictures start with.
    """
    if lang not in LANGS:
        raise ArgumentError(f"lang must be one of {', '.join(LANGS)}, got {lang!r}", arg="lang")
    unit = "grados" if degrees and lang == "es" else ("degrees" if degrees else "rad")
    kind = phrase(f"kind.{result.kind}", lang)
    out = [f"# {phrase('title', lang, name=result.nominal.name)}", ""]
    out += [
        phrase(
            "intro",
            lang,
            m=result.before.shape[0],
            kind=kind,
            loss=result.loss,
            sp=f"{result.noise[0] * 1e3:g}",
            sr=f"{math.degrees(result.noise[1]):.3g}",
        ),
        "",
    ]
    out += [f"## {phrase('h.residuals', lang)}", "", phrase("residuals.table", lang)]
    out.append("|---|---|---|---|---|")
    for after in (False, True):
        rms, big = result.rms(after), result.max(after)
        label = phrase("after" if after else "before", lang)
        out.append(
            f"| {label} | {rms[0] * 1e3:.4f} | {big[0] * 1e3:.4f} | "
            f"{math.degrees(rms[1]):.5f} | {math.degrees(big[1]):.5f} |"
        )
    out += ["", f"## {phrase('h.identify', lang)}", ""]
    out.append(
        phrase(
            "rank",
            lang,
            rank=result.rank,
            p=len(result.parameters),
            generic=result.generic_count,
            extra=6 if result.kind == "pose" else 3,
            cond=f"{result.condition:.4g}",
        )
    )
    values = ", ".join(f"{k} = {v:.4g}" for k, v in result.observability.items())
    out += ["", phrase("indices", lang, values=values), ""]
    if result.undetermined:
        out += [phrase("left_out", lang), ""]
        out += [f"- {finding_text(f, lang, result.kind)}" for f in result.undetermined]
    else:
        out.append(phrase("none_left", lang))
    out += ["", f"## {phrase('h.correlated', lang)}", ""]
    if result.correlated:
        out += [f"- {correlation_text(a, b, r, lang)}" for a, b, r in result.correlated]
    else:
        out.append(phrase("none_correlated", lang, limit=CORRELATION_LIMIT))
    out += ["", f"## {phrase('h.parameters', lang)}", "", phrase("units", lang, angle=unit), ""]
    out += [phrase("parameters.table", lang), "|---|---|---|---|---|"]
    for p in result.parameters:
        scale = (lambda v: _angle(v, degrees)) if p.angle else (lambda v: v * 1e3)
        se = f"{scale(p.std_error):.3g}" if p.fitted else phrase("not_fitted", lang)
        out.append(
            f"| {parameter_label(p.name)} | {scale(p.nominal):.6g} | {scale(p.calibrated):.6g} | "
            f"{scale(p.correction):+.4g} | {se} |"
        )
    out += ["", f"## {phrase('h.dh', lang)}", ""]
    out.append(
        phrase(
            "dh.error",
            lang,
            convention=result.dh.robot.convention,
            error=f"{result.dh.fk_error:.2g}",
        )
    )
    out += ["", f"## {phrase('h.pictures', lang)}", ""]
    out.append(f"![{phrase('histogram', lang)}]({stem}-histogram.png)")
    out += ["", f"![{phrase('along', lang)}]({stem}-residuals.png)", ""]
    return "\n".join(out)


def _pictures(result: CalibrationResult, lang: str, stem: Path, dpi: int) -> list[Path]:
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:  # pragma: no cover - the test environment has matplotlib
        raise KinematicaError(
            "the report's pictures need matplotlib: pip install 'kinematica[calibration]'"
        ) from None
    pose = result.kind == "pose"
    columns = [(0, 1e3, "axis.position")] + (
        [(1, 180.0 / np.pi, "axis.orientation")] if pose else []
    )
    paths = []
    fig = Figure(figsize=(4.2 * len(columns), 3.4))
    FigureCanvasAgg(fig)
    for k, (col, scale, label) in enumerate(columns):
        ax = fig.add_subplot(1, len(columns), k + 1)
        before, after = result.before[:, col] * scale, result.after[:, col] * scale
        ax.hist(before, bins=BINS, alpha=0.6, label=phrase("before", lang), color="tab:red")
        ax.hist(after, bins=BINS, alpha=0.8, label=phrase("after", lang), color="tab:blue")
        ax.set_xlabel(phrase(label, lang))
        ax.set_ylabel(phrase("axis.count", lang))
        ax.legend()
    fig.suptitle(phrase("histogram", lang))
    fig.tight_layout()
    paths.append(stem.with_name(stem.name + "-histogram.png"))
    fig.savefig(paths[-1], dpi=dpi)
    fig = Figure(figsize=(8.0, 2.6 * len(columns)))
    FigureCanvasAgg(fig)
    index = np.arange(result.before.shape[0])
    for k, (col, scale, label) in enumerate(columns):
        ax = fig.add_subplot(len(columns), 1, k + 1)
        ax.semilogy(index, result.before[:, col] * scale, "o-", ms=3, color="tab:red",
                    label=phrase("before", lang))  # fmt: skip
        ax.semilogy(index, result.after[:, col] * scale, "o-", ms=3, color="tab:blue",
                    label=phrase("after", lang))  # fmt: skip
        ax.set_ylabel(phrase(label, lang))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(loc="upper right")
    ax.set_xlabel(phrase("axis.index", lang))
    fig.suptitle(phrase("along", lang))
    fig.tight_layout()
    paths.append(stem.with_name(stem.name + "-residuals.png"))
    fig.savefig(paths[-1], dpi=dpi)
    return paths


def write_report(
    result: CalibrationResult,
    path: str | Path,
    lang: str = "es",
    *,
    degrees: bool = True,
    dpi: int = 100,
) -> list[Path]:
    """Write the report ``path`` (Markdown) and its two pictures beside it.

    Args:
        result: The calibration.
        path: The Markdown file, e.g. ``calibration.md``; the pictures are
            ``calibration-histogram.png`` and ``calibration-residuals.png``.
        lang: ``"es"`` or ``"en"``.
        degrees: Angles of the parameter table in degrees (else radians).
        dpi: Of the pictures.

    Returns:
        The paths written: the report, then the pictures.
    """
    p = Path(path)
    stem = p.with_suffix("")
    text = report_text(result, lang, degrees=degrees, stem=stem.name)
    pictures = _pictures(result, lang, stem, dpi)
    write_text_atomic(p, text)
    return [p, *pictures]
