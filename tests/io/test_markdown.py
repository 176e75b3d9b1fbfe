"""Text from robot files in Markdown reports: shown literally by a CommonMark renderer."""

from __future__ import annotations

import html
import re

import pytest

from kinematica.io.markdown import markdown_code, markdown_text

markdown_it = pytest.importorskip("markdown_it")

HOSTILE = [
    "<img src=x onerror=alert(1)>",
    "<script>alert(2)</script>",
    "*b* **s** _i_ __u__ ~~d~~",
    "[l](javascript:x) ![i](x.png)",
    "`c` ``c2`` $x$ \\( y \\)",
    "a | b | c",
    "# not a heading",
    "&amp; &lt; &#65;",
    "{t} !x",
    "line one\n# line two\n<b>x</b>",
    "Planar 3R (seed 001), l1 + l2 = 1 - a.b",
]


def _render_inline(text: str) -> str:
    page = markdown_it.MarkdownIt("commonmark").render(f"before {text} after")
    found = re.fullmatch(r"<p>before (.*) after</p>\n", page, flags=re.S)
    assert found is not None, page
    return found.group(1)


@pytest.mark.parametrize("text", HOSTILE)
def test_text_is_shown_as_written(text: str) -> None:
    shown = _render_inline(markdown_text(text))
    assert "<" not in shown.replace("&lt;", "")  # no element at all
    assert html.unescape(shown) == text.replace("\n", " ")


@pytest.mark.parametrize("text", [*HOSTILE, "`start", "end`", "a ``` b"])
def test_code_spans_hold_any_text(text: str) -> None:
    shown = _render_inline(markdown_code(text))
    found = re.fullmatch(r"<code>(.*)</code>", shown, flags=re.S)
    assert found is not None, shown
    assert html.unescape(found.group(1)) == text.replace("\n", " ")


def test_plain_names_are_unchanged() -> None:
    assert markdown_text("Planar 3R (seed 001), l1 + l2 = 1") == "Planar 3R (seed 001), l1 + l2 = 1"
    assert markdown_code("best.yaml") == "`best.yaml`"
