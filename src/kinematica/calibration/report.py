"""The calibration report: a Markdown page and its two pictures, in Spanish or English.

``calibration.md`` holds the residuals before and after (and after without the
outliers, when a measurement stands out), the identifiability findings in
words, the correlated pairs, the parameter table and the DH table's error; beside it
``calibration-histogram.png`` (the residuals' histograms before and after, the
outliers left out of the latter) and
``calibration-residuals.png`` (each measurement's residual, before and after, along the
measurement set). The pictures are drawn with matplotlib's object API on an Agg canvas
(no pyplot state).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from kinematica.calibration.fit import OUTLIER_LIMIT
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
            loss=phrase(f"loss.{result.loss}", lang),
            sp=f"{result.noise[0] * 1e3:g}",
            sr=f"{math.degrees(result.noise[1]):.3g}",
        ),
        "",
    ]
    out += [f"## {phrase('h.residuals', lang)}", "", phrase("residuals.table", lang)]
    out.append("|---|---|---|---|---|")
    inliers = np.delete(result.after, result.outliers, axis=0)
    rows = [
        (phrase("before", lang), result.rms(False), result.max(False)),
        (phrase("after", lang), result.rms(True), result.max(True)),
    ]
    if len(result.outliers) and len(inliers):
        rows.append(
            (
                phrase("inliers", lang, k=len(result.outliers)),
                result.rms(True, inliers=True),
                (float(inliers[:, 0].max()), float(inliers[:, 1].max())),
            )
        )
    for label, rms, big in rows:
        out.append(
            f"| {label} | {rms[0] * 1e3:.4f} | {big[0] * 1e3:.4f} | "
            f"{math.degrees(rms[1]):.5f} | {math.degrees(big[1]):.5f} |"
        )
    if len(result.outliers):
        shown = ", ".join(str(int(i)) for i in result.outliers)
        out += ["", phrase("outliers", lang, limit=f"{OUTLIER_LIMIT:g}", which=shown)]
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
    columns = [(0, 1e3, "axis.position")]
    if pose:
        columns.append((1, 180.0 / np.pi, "axis.orientation"))
    paths = []
    fig = Figure(figsize=(4.2 * len(columns), 5.6))
    FigureCanvasAgg(fig)
    after = np.delete(result.after, result.outliers, axis=0)
    title = phrase("inliers", lang, k=len(result.outliers)) if len(result.outliers) else None
    panels = (
        (result.before, phrase("before", lang), "tab:red"),
        (after, title or phrase("after", lang), "tab:blue"),
    )
    for row, (errors, name, color) in enumerate(panels):
        for k, (col, scale, label) in enumerate(columns):
            ax = fig.add_subplot(2, len(columns), row * len(columns) + k + 1)
            ax.hist(errors[:, col] * scale, bins=BINS, color=color)
            ax.set_title(name)
            ax.set_xlabel(phrase(label, lang))
            ax.set_ylabel(phrase("axis.count", lang))
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
        ax.legend(loc="best")
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
