"""The SRS solver's header (``solvers/srs.hpp``): its Params as the builder fills them for
the iiwa 14 (against the lengths of its DH table), its raw candidate slots, and ``at``.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

import kinematica as km
from kinematica import _core_testing
from kinematica.ik import closed_form
from kinematica.ik.analytic.srs import LABELS

#: iiwa 14: shoulder height, upper arm, forearm, flange (m), from its DH table.
D1, UPPER, FORE, FLANGE = 0.36, 0.42, 0.4, 0.126


@pytest.fixture(scope="module")
def iiwa() -> km.Robot:
    return km.load("iiwa14")


def test_the_iiwa_as_the_builder_reads_it(iiwa: km.Robot) -> None:
    closed = closed_form(iiwa.chain, "pose", "arm_angle")
    assert closed is not None and closed.labels == LABELS and closed.slots == 8
    p = SimpleNamespace(**_core_testing.decoupled.srs_values(iiwa.chain.core))  # the built values
    np.testing.assert_allclose(p.s, [0.0, 0.0, D1], atol=1e-15)  # axes 1-3 meet at S
    np.testing.assert_allclose(p.se, [0.0, 0.0, UPPER], atol=1e-15)  # E on axis 4, above S
    np.testing.assert_allclose(p.ew, [0.0, 0.0, FORE], atol=1e-15)  # W above E
    np.testing.assert_allclose(p.w_tool, [0.0, 0.0, -FLANGE], atol=1e-15)
    np.testing.assert_allclose(p.ref, [0.0, 0.0, 1.0], atol=1e-15)
    assert abs(float(np.dot(p.ref, p.ref_alt))) <= 1e-15
    assert p.stretched == pytest.approx(0.0, abs=1e-15)  # q = 0 is the stretched arm
    assert p.d_max == pytest.approx(UPPER + FORE, abs=1e-15)
    assert p.d_min == pytest.approx(UPPER - FORE, abs=1e-15)
    assert closed_form(iiwa.chain, "pose") is None  # without the parameter: no closed form


def test_raw_slots_and_a_copy_at_another_angle(iiwa: km.Robot) -> None:
    p = closed_form(iiwa.chain, "pose", "arm_angle").params  # type: ignore[union-attr]
    q = np.array([0.3, 0.7, -0.4, 1.2, 0.5, -0.8, 0.2])
    T = iiwa.fk(q)
    at = p.at(float(iiwa.arm_angle(q)))
    assert p.psi == 0.0 and at.psi == pytest.approx(float(iiwa.arm_angle(q)))
    Q, singular, near, gap, free = at.candidates(iiwa.chain.core, T)
    assert Q.shape == (8, 7) and not singular and not near and math.isnan(gap) and free == 0
    # slot 4 e + 2 s + w: elbow + has q4 > 0, shoulder no-flip q2 > 0, wrist no-flip q6 > 0
    for k in range(8):
        e, s, w = k // 4, (k // 2) % 2, k % 2
        assert (Q[k, 3] > 0) == (e == 0) and (Q[k, 1] > 0) == (s == 0)
        assert (Q[k, 5] > 0) == (w == 0)
    d = np.abs(np.angle(np.exp(1j * (Q - q)))).max(axis=1)
    assert d.min() <= 1e-12  # the generating q is a raw candidate already
    far = T.copy()
    far[:3, 3] *= 10.0
    Q, singular, near, gap, free = at.candidates(iiwa.chain.core, far)
    assert np.isnan(Q).all() and gap > 1.0


def test_a_target_aimed_at_a_q4_puts_the_wrist_centre_where_that_q4_does(iiwa: km.Robot) -> None:
    # the iiwa's wrist centre is FLANGE below its flange, its shoulder centre D1 above the base
    p = closed_form(iiwa.chain, "pose", "arm_angle").params  # type: ignore[union-attr]
    q = np.array([0.3, 0.7, -0.4, 1.2, 0.5, -0.8, 0.2])
    T = iiwa.fk(q)
    S = np.array([0.0, 0.0, D1])

    def wrist(P: np.ndarray) -> np.ndarray:
        return P[:3, :3] @ np.array([0.0, 0.0, -FLANGE]) + P[:3, 3]

    np.testing.assert_allclose(p.aimed(T, q[3]), T, atol=1e-15)  # its own q4: as it is
    for q4 in (0.3, -1.9, 2.0):
        other = q.copy()
        other[3] = q4
        want = np.linalg.norm(wrist(iiwa.fk(other)) - S)  # our FK at that q4
        A = p.aimed(T, q4)
        assert np.linalg.norm(wrist(A) - S) == pytest.approx(want, rel=1e-12)
        np.testing.assert_array_equal(A[:3, :3], T[:3, :3])  # moved, not turned
        along = np.cross(wrist(A) - S, wrist(T) - S)  # along the shoulder-wrist line
        assert np.linalg.norm(along) <= 1e-12
