"""The identification findings in words, in Spanish and English.

One table of sentences with a Spanish and an English version each, as the derivation
reports keep theirs (:mod:`kinematica.symbolic.phrases`, a layer above this one): a
key, a pair ``(es, en)``, placeholders filled by name.
"""

from __future__ import annotations

from typing import Final

from kinematica.calibration.identify import Finding

__all__ = ["LANGS", "PHRASES", "correlation_text", "finding_text", "parameter_label", "phrase"]

LANGS: Final = ("es", "en")

PHRASES: Final[dict[str, tuple[str, str]]] = {
    "title": ("Calibración cinemática de {name}", "Kinematic calibration of {name}"),
    "intro": (
        "{m} medidas de {kind} ({loss}); ruido supuesto {sp} mm y {sr} grados. "
        "Modelo de error: una pequeña transformación rígida en cada eslabón, en la base "
        "y en la herramienta (valores DH y giro beta de Hayati).",
        "{m} {kind} measurements ({loss}); assumed noise {sp} mm and {sr} degrees. "
        "Error model: a small rigid transform in every link, the base and the tool "
        "(DH values and Hayati's beta twist).",
    ),
    "loss.linear": ("mínimos cuadrados", "least squares"),
    "loss.soft_l1": (
        "pérdida robusta soft-L1 de scipy",
        "scipy's robust soft-L1 loss",
    ),
    "loss.huber": ("pérdida robusta de Huber", "Huber's robust loss"),
    "loss.cauchy": ("pérdida robusta de Cauchy", "Cauchy's robust loss"),
    "loss.arctan": ("pérdida robusta arcotangente", "the robust arctangent loss"),
    "kind.pose": ("pose", "pose"),
    "kind.position": ("posición", "position"),
    "h.residuals": ("Residuos", "Residuals"),
    "residuals.table": (
        "| | RMS posición (mm) | máx. posición (mm) | RMS orientación (grados) "
        "| máx. orientación (grados) |",
        "| | RMS position (mm) | max position (mm) | RMS orientation (degrees) "
        "| max orientation (degrees) |",
    ),
    "before": ("antes", "before"),
    "after": ("después", "after"),
    "inliers": ("después, sin los {k} atípicos", "after, without the {k} outliers"),
    "outliers": (
        "Medidas atípicas (residuo mayor que {limit} desviaciones típicas robustas): {which}.",
        "Outliers (a residual beyond {limit} robust standard deviations): {which}.",
    ),
    "h.identify": ("Identificabilidad", "Identifiability"),
    "rank": (
        "Rango de la jacobiana de identificación: {rank} de {p} parámetros; con medidas "
        "suficientemente variadas de este tipo se determinan {generic} (Everett, Driels y "
        "Mooring: 4R + 2P + {extra}). Número de condición {cond}.",
        "Rank of the identification Jacobian: {rank} of {p} parameters; measurements of "
        "this kind varied enough determine {generic} (Everett, Driels and Mooring: "
        "4R + 2P + {extra}). Condition number {cond}.",
    ),
    "indices": (
        "Índices de observabilidad (Sun y Hollerbach): {values}.",
        "Observability indices (Sun and Hollerbach): {values}.",
    ),
    "left_out": (
        "Parámetros que las medidas no determinan (se dejan en su valor nominal):",
        "Parameters the measurements cannot determine (left at their nominal values):",
    ),
    "none_left": (
        "Las medidas determinan todos los parámetros pedidos.",
        "The measurements determine every parameter asked for.",
    ),
    "alike.one": (
        "{a} mueve la herramienta igual que {b}: los datos no pueden distinguirlos",
        "{a} and {b} move the tool alike: the data cannot tell them apart",
    ),
    "alike.many": (
        "{a} mueve la herramienta como una combinación de {list}",
        "{a} moves the tool as a combination of {list} does",
    ),
    "still.pose": ("{a} no mueve la herramienta", "{a} does not move the tool"),
    "still.position": ("{a} no mueve el punto medido", "{a} does not move the measured point"),
    "data": (
        " con estas medidas (otras poses más variadas lo determinarían)",
        " with these measurements (more varied poses would determine it)",
    ),
    "and": ("y", "and"),
    "h.correlated": ("Parámetros correlados", "Correlated parameters"),
    "correlated": (
        "{a} y {b}: correlación {r}; los datos determinan su {what} mucho mejor que cada uno",
        "{a} and {b}: correlation {r}; the data determines their {what} far better than each",
    ),
    "sum": ("suma", "sum"),
    "difference": ("diferencia", "difference"),
    "none_correlated": (
        "Ningún par supera |correlación| = {limit}.",
        "No pair exceeds |correlation| = {limit}.",
    ),
    "h.parameters": ("Parámetros", "Parameters"),
    "parameters.table": (
        "| parámetro | nominal | calibrado | corrección | error típico |",
        "| parameter | nominal | calibrated | correction | standard error |",
    ),
    "not_fitted": ("no ajustado", "not fitted"),
    "units": (
        "Longitudes en mm, ángulos en {angle}.",
        "Lengths in mm, angles in {angle}.",
    ),
    "h.dh": ("Tabla DH del brazo calibrado", "DH table of the calibrated arm"),
    "dh.error": (
        "La tabla DH ({convention}) leída de los ejes calibrados reproduce su cinemática "
        "directa con un error máximo de {error} m; el URDF la reproduce exactamente.",
        "The {convention} DH table read off the calibrated axes reproduces its forward "
        "kinematics within {error} m; the URDF reproduces it exactly.",
    ),
    "h.pictures": ("Figuras", "Pictures"),
    "histogram": ("Histograma de los residuos", "Residual histograms"),
    "along": ("Residuos a lo largo de las medidas", "Residuals along the measurements"),
    "axis.position": ("error de posición (mm)", "position error (mm)"),
    "axis.orientation": ("error de orientación (grados)", "orientation error (degrees)"),
    "axis.count": ("medidas", "measurements"),
    "axis.index": ("medida", "measurement"),
}


def phrase(key: str, lang: str, **values: object) -> str:
    """The sentence ``key`` in ``lang`` (``"es"`` or ``"en"``), placeholders filled."""
    text = PHRASES[key][LANGS.index(lang)]
    return text.format(**values) if values else text


def parameter_label(name: str) -> str:
    """A parameter's name as printed: ``theta2`` stays, ``base_rz`` reads ``base rz``."""
    return name.replace("_", " ")


def _listed(names: tuple[str, ...], lang: str) -> str:
    labels = [parameter_label(n) for n in names]
    if len(labels) == 1:
        return labels[0]
    return f"{', '.join(labels[:-1])} {phrase('and', lang)} {labels[-1]}"


def finding_text(finding: Finding, lang: str, kind: str = "pose") -> str:
    """Why a parameter is left out, in one sentence.

    Args:
        finding: The parameter and the chosen ones it moves the tool like.
        lang: ``"es"`` or ``"en"``.
        kind: ``"pose"`` or ``"position"`` (what "does not move" refers to).
    """
    a = parameter_label(finding.name)
    if not finding.partners:
        text = phrase(f"still.{kind}", lang, a=a)
    elif len(finding.partners) == 1:
        text = phrase("alike.one", lang, a=a, b=parameter_label(finding.partners[0]))
    else:
        text = phrase("alike.many", lang, a=a, list=_listed(finding.partners, lang))
    if not finding.structural:
        text += phrase("data", lang)
    return text + "."


def correlation_text(a: str, b: str, r: float, lang: str) -> str:
    """A correlated pair in one sentence: which combination the data determines.

    Errors of estimates correlated positively move together, so their difference
    is well determined; of estimates correlated negatively, their sum.
    """
    what = phrase("difference" if r > 0 else "sum", lang)
    return (
        phrase(
            "correlated", lang, a=parameter_label(a), b=parameter_label(b), r=f"{r:+.3f}", what=what
        )
        + "."
    )
