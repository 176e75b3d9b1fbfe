"""Plain-text formatting (``cli/format.py``): significant digits, round trips, safe text."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from support.cli import run, strict_json

import kinematica as km
from kinematica.cli.format import DEFAULT_PRECISION, num, plain


def printed_matrix(out: str, title: str = "T:") -> np.ndarray:
    """The 4x4 matrix printed under ``title``."""
    lines = out.split(f"\n{title}\n", 1)[1].splitlines()[:4]
    return np.array([[float(v) for v in ln.split()] for ln in lines])


def test_num_significant_digits() -> None:
    assert num(0.5) == "0.5"
    assert num(np.cos(np.pi / 4)) == "0.7071067812"
    assert num(np.cos(np.pi / 4), 3) == "0.707"
    assert num(-123456.789, 4) == "-123500"
    assert num(1e-17) == "0" and num(-3e-13) == "0"
    assert num(1.5e-9) == "1.5e-09"
    assert num(2.5e20) == "2.5e+20"
    assert num(float("nan")) == "nan" and num(float("-inf")) == "-inf"
    assert float(num(1 / 3, 17)) == 1 / 3


def test_fk_text_prints_ten_significant_digits(capsys: pytest.CaptureFixture[str]) -> None:
    q = [10, 20, 30, 40, 50, 60]
    code, out, _ = run(capsys, "fk", "puma560", "--q", *map(str, q))
    assert code == 0
    T = km.load("puma560").fk(np.radians(q))
    printed = printed_matrix(out)
    np.testing.assert_allclose(printed, T, rtol=6e-10, atol=1e-12)
    values = out.split("\nT:\n")[1].split()[:12]
    digits = [len(v.lstrip("-").replace(".", "").lstrip("0")) for v in values]
    assert max(digits) == DEFAULT_PRECISION


@pytest.mark.parametrize(
    ("name", "q"),
    [
        ("puma560", [10, 20, 30, 40, 50, 60]),
        ("irb120", [10, 20, 30, 40, 50, 60]),  # millimetres
        ("ur5", [10, -60, 30, 40, 50, 60]),
        ("kr6", [10, -20, 30, 40, 50, 60]),
        ("arm6-dh", [30, 50, 20, 10, 60, -20]),
    ],
)
def test_fk_text_pasted_into_ik_matrix_gives_q_back(
    capsys: pytest.CaptureFixture[str], name: str, q: list[float]
) -> None:
    code, out, _ = run(capsys, "fk", name, "--q", *map(str, q))
    assert code == 0
    numbers = out.split("\nT:\n", 1)[1].split("\n\n")[0].split()
    code, out, err = run(capsys, "ik", name, "--matrix", *numbers, "--json")
    assert code == 0, err
    data = strict_json(out)
    found = np.array(data["solutions"] + data["out_of_limits"])
    assert np.abs(found - q).max(axis=1).min() < 1e-6  # degrees


def test_control_characters_in_names_are_neutralised(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    evil = "arm\x1b[2J\x1b[31m red\nsecond line\u202e"
    path = tmp_path / "evil.json"
    path.write_text(
        json.dumps(
            {
                "name": evil,
                "description": "text\r\nwith\x07bell",
                "convention": "standard",
                "joints": [{"theta": "q1", "d": 0, "a": 1, "alpha": 0, "name": "j\x1b1"}],
            }
        )
    )
    for argv in (("show", str(path)), ("fk", str(path), "--q", "0"), ("robots",)):
        code, out, err = run(capsys, *argv)
        assert code == 0, err
        assert "\x1b" not in out and "\x07" not in out and "\u202e" not in out and "\r" not in out
    code, out, _ = run(capsys, "show", str(path))
    assert out.splitlines()[0].startswith("arm\\x1b[2J\\x1b[31m red\\nsecond line\\u202e: ")
    code, out, _ = run(capsys, "show", str(path), "--json")
    assert strict_json(out)["robot"] == evil  # JSON keeps the exact text, escaped
    code, _, err = run(capsys, "fk", "no\x1b[31msuch", "--q", "0")
    assert code == 2 and "\x1b" not in err


def test_plain_keeps_ordinary_unicode() -> None:
    assert plain("Brazo robótico 6R — π/2, 90°") == "Brazo robótico 6R — π/2, 90°"
    assert plain("tab\there") == "tab\\there"
