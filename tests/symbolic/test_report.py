"""Reports: the three formats in both languages, LaTeX compiles, HTML opens offline."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest
from support import ROOT

import kinematica as km

sp = pytest.importorskip("sympy")

from kinematica import symbolic  # noqa: E402
from kinematica.symbolic.geometric import derive_geometric  # noqa: E402

LATEX = shutil.which("pdflatex") or shutil.which("latex")
CHROMIUM = next(
    (shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)),
    None,
)


@pytest.mark.parametrize("fmt", ["markdown", "latex", "html"])
@pytest.mark.parametrize("lang", ["es", "en"])
def test_report_sections(fmt: str, lang: str) -> None:
    text = symbolic.report("planar-3r", format=fmt, lang=lang)
    words = {
        "es": [
            "Tabla de Denavit-Hartenberg",
            "Matriz de transformación homogénea",
            "Ecuaciones de posición",
            "Método geométrico",
            "Cinemática inversa",
        ],
        "en": [
            "Denavit-Hartenberg table",
            "homogeneous transformation matrix",
            "Position equations",
            "Geometric method",
            "Inverse kinematics",
        ],
    }[lang]
    for w in words:
        assert w in text
    trans = {"es": "Tras", "en": "Trans"}[lang]  # each row's four elementary transforms
    assert trans in text and "Rot" in text
    if lang == "en":
        assert "Tras" not in text


def test_markdown_shows_short_notation_and_seed_formula() -> None:
    text = symbolic.report("anthropomorphic-3r", lang="en")
    assert "c_{1} \\left(L_{2} c_{2} + L_{3} c_{23}\\right)" in text  # px of seed 002
    assert "\\operatorname{atan2}\\left(p_{y}, p_{x}\\right)" in text


def test_report_modified_convention_lists_craig_order() -> None:
    text = symbolic.report(km.load("panda"), lang="en")  # numbers: no derivation, but every row
    assert "Modified convention" in text
    assert text.index("\\mathrm{Rot}(x, \\alpha_{i-1})") < text.index(
        "\\mathrm{Rot}(z, \\theta_{i})"
    )


def test_bad_format_and_language() -> None:
    with pytest.raises(symbolic.SymbolicError, match="unknown report format 'pdf'"):
        symbolic.report("planar-pr", format="pdf")
    with pytest.raises(symbolic.SymbolicError, match="unknown report language 'fr'"):
        symbolic.report("planar-pr", lang="fr")


@pytest.mark.parametrize(
    "name", ["planar-pr", "planar-prr", "planar-3r", "rrr-geometric", "anthropomorphic-3r"]
)
def test_geometric_method_agrees_with_dh(name: str) -> None:
    g = derive_geometric(symbolic.symbolic_robot(name))
    assert g is not None and g.agrees
    assert "agrees with the position from Denavit-Hartenberg" in symbolic.report(name, lang="en")


def test_geometric_method_seed_000_example_2_form() -> None:
    # Seed 000: y = r cos q1, z = r sin q1, r = l2 cos q2 + l3 cos(q2 + q3).
    g = derive_geometric(symbolic.symbolic_robot("rrr-geometric"))
    assert g is not None
    r, h = sp.symbols("r h")
    q1 = sp.Symbol("q1")
    assert list(g.position) == [h, r * sp.cos(q1), r * sp.sin(q1)]


@pytest.mark.skipif(
    LATEX is None, reason="no latex/pdflatex installed (apt-get install texlive-latex-base)"
)
@pytest.mark.parametrize(
    ("name", "lang"), [("arm6-dh", "es"), ("planar-prr", "en"), ("scara", "es")]
)
def test_latex_compiles(name: str, lang: str, tmp_path: Path) -> None:
    tex = tmp_path / "report.tex"
    tex.write_text(symbolic.report(name, format="latex", lang=lang), encoding="utf-8")
    proc = subprocess.run(
        [str(LATEX), "-interaction=nonstopmode", "-halt-on-error", tex.name],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        errors="replace",
        timeout=120,
        check=False,
    )
    assert proc.returncode == 0, proc.stdout[-3000:]
    assert "\\usepackage{amsmath}" in tex.read_text()


def test_html_is_self_contained() -> None:
    page = symbolic.report("arm6-dh", format="html", lang="es")
    assert page.startswith("<!DOCTYPE html>") and "<math" in page and "<mtable>" in page
    assert not re.search(r"(src|href)=|https?:|<script|@import", page)


@pytest.mark.skipif(CHROMIUM is None, reason="no chromium installed (apt-get install chromium)")
def test_html_opens_in_chromium_without_console_errors(tmp_path: Path) -> None:
    page = tmp_path / "arm6.html"
    page.write_text(symbolic.report("arm6-dh", format="html", lang="en"), encoding="utf-8")
    shot = tmp_path / "arm6.png"
    proc = subprocess.run(
        [
            str(CHROMIUM),
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--enable-logging=stderr",
            "--v=0",
            f"--screenshot={shot}",
            "--window-size=1000,1400",
            page.as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert shot.stat().st_size > 10_000  # a picture with content
    console = [line for line in proc.stderr.splitlines() if ":CONSOLE" in line]
    assert console == []


def test_committed_arm6_report_is_current() -> None:
    # docs/symbolic.md: docs/arm6-dh.md is `kinematica derive arm6-dh -o docs/arm6-dh.md`.
    committed = ROOT / "docs" / "arm6-dh.md"
    assert committed.read_text(encoding="utf-8") == symbolic.report("arm6-dh")


def test_geometric_segments_are_a_table_not_sines() -> None:
    # s_1, s_2 would read as sin q1, sin q2 beside the short notation of the same report
    text = symbolic.report("planar-prr", lang="en")
    geometric = text[text.index("## Geometric method") :]
    assert "| segment | angle turned | segment vector at zero |" in geometric
    assert not re.search(r"s_\{\d\} &= \\left\(", geometric)
    assert "| tramo | ángulo girado |" in symbolic.report("planar-prr", lang="es")


def test_short_notation_legend_names_what_the_equations_use() -> None:
    # planar-pr: q1 is prismatic, so there is no c1; the legend defines c2
    text = symbolic.report("planar-pr", lang="en")
    legend = text[text.index("## Position equations") :].split("\n\n")[1]
    assert "c_{2} = \\cos{\\left(q_{2} \\right)}" in legend and "c_{1}" not in legend
    six = symbolic.report("arm6-dh", lang="en")
    legend = six[six.index("## Position equations") :].split("\n\n")[1]
    assert "c_{1} = \\cos{\\left(q_{1} \\right)}" in legend
    assert "c_{23} = \\cos{\\left(q_{2} + q_{3} \\right)}" in legend


def test_six_dof_report_shows_T() -> None:
    # T is too long to print whole: it is shown by its entries, given just below
    text = symbolic.report("arm6-dh", lang="en")
    t_section = text[text.index("## The homogeneous transformation matrix T") :]
    t_section = t_section[: t_section.index("## Position equations")]
    assert "T &= \\left[\\begin{matrix}r_{11} & r_{12} & r_{13} & p_{x}" in t_section


def test_html_parentheses_and_minus_signs() -> None:
    page = symbolic.report("arm6-dh", format="html", lang="en")
    # Rot(z, q1) beside its matrix: parentheses that do not stretch to the matrix
    assert '<mi>Rot</mi><mo stretchy="false">(</mo><mi>z</mi>' in page
    assert "<mi>Trans</mi>" in page and "<mi>Tras</mi>" not in page
    # minus signs, not hyphens: neither <mo>-</mo> nor a negative <mn>
    assert "<mo>-</mo>" not in page and "<mn>-" not in page
    assert "<mo>\u2212</mo>" in page


EVIL_NAME = "<img src=x onerror=alert(1)> *b* _i_ [l](http://x) `c` $x$ | ~s~ # \\ &amp; {t} !"


@pytest.mark.parametrize("lang", ["es", "en"])
def test_markdown_shows_a_robot_name_literally(lang: str) -> None:
    """CommonMark (markdown-it, as GitHub and Jupyter render) makes no markup of a name."""
    markdown_it = pytest.importorskip("markdown_it")
    import html

    robot = km.load("planar-3r")
    evil = km.Robot.from_dh(
        robot.links, name=EVIL_NAME + "\n# heading\n<script>x</script>", convention="standard"
    )
    text = symbolic.report(evil, format="markdown", lang=lang)
    page = markdown_it.MarkdownIt("commonmark").render(text)  # raw HTML passes through
    for tag in ("<img", "<script", "<a ", "<em>", "<strong>", "<code>", "<h2>heading"):
        assert tag not in page
    title = re.search(r"<h1>(.*)</h1>", page)
    assert title is not None
    word = "Kinematics of" if lang == "en" else "Cinemática de"
    shown = EVIL_NAME + " # heading <script>x</script>"
    assert html.unescape(title.group(1)) == f"{word} {shown}"
    # the report of a plain name is unchanged: no escape where none is needed
    assert symbolic.report(robot, format="markdown", lang=lang).startswith(
        f"# {word} {robot.name}\n"
    )
