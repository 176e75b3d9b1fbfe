"""The report's numeric decoupling (seed 002, step by step), in Spanish and English."""

from __future__ import annotations

import re

import numpy as np
import pytest

import kinematica as km
from kinematica.symbolic import report
from kinematica.symbolic.document import EXAMPLE_Q_DEG

pytest.importorskip("sympy")


@pytest.mark.parametrize(
    ("lang", "heading"),
    [("es", "desacoplo cinemático paso a paso"), ("en", "the kinematic decoupling step by step")],
)
def test_the_seed_arm_report_works_the_decoupling_with_numbers(lang: str, heading: str) -> None:
    arm = km.load("arm6-dh")
    text = report(arm, lang=lang)
    assert heading in text
    part = text[text.index(heading) :]
    T = arm.fk(np.radians(EXAMPLE_Q_DEG))
    p_m = T[:3, 3] - 0.1 * T[:3, 2]  # seed 002: p - d6·R·z, d6 = 0.1
    line = next(x for x in part.splitlines() if x.startswith("p_{m} &="))
    shown = [float(v) for v in re.findall(r"-?\d+\.\d+", line)]
    assert np.allclose(shown, p_m, atol=5e-5)
    # issue 35's arm solution of this p_m, and the configuration T came from
    assert r"\left( -150.0, \  -10.0, \  -30.0\right)" in part
    assert r"\left( 30.0, \  40.0, \  -30.0\right)" in part
    assert r"\left( 10.0, \  60.0, \  -20.0\right)" in part
    assert part.count("{}^{3}R_{6}") == 4


def test_an_arm_without_a_spherical_wrist_has_no_numeric_decoupling() -> None:
    assert "the kinematic decoupling step by step" not in report(km.load("ur5"), lang="en")
