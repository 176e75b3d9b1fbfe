"""Branch labels rendered in the Robotics Toolbox's letters (l/r, u/d, n/f)."""

from __future__ import annotations

import itertools

import numpy as np

import kinematica as km
from kinematica.ik.letters import toolbox_letters

#: The PUMA 560's nominal pose in the Toolbox (``p560.qn``), which its ``ikine_a``
#: returns for the letters ``"ruf"`` (issue 23, item 6).
QN = np.array([0.0, np.pi / 4, -np.pi, 0.0, np.pi / 4, 0.0])  # q3 = π, within the limits


def test_words_to_letters() -> None:
    assert toolbox_letters("shoulder right, elbow up, wrist no-flip") == "ruf"
    assert toolbox_letters("shoulder left, elbow down, wrist flip") == "ldn"
    assert toolbox_letters("elbow up") == "u"
    # parts the Toolbox has no letter for render as nothing
    assert toolbox_letters("shoulder front, elbow down") == "d"
    assert toolbox_letters("root 3, elbow up") == "u"
    assert toolbox_letters("position 2") == ""


def test_puma_nominal_pose_is_ruf_and_wrist_no_flip() -> None:
    puma = km.load("puma560")
    res = puma.ik(puma.fk(QN), respect_limits=False)
    assert res.count == 8
    diff = km.wrap_angle(res.solutions - QN)
    i = int(np.argmin(np.abs(diff).max(axis=1)))
    assert np.abs(diff[i]).max() < 1e-9
    assert res.branches[i].endswith("wrist no-flip")
    assert res.letters[i] == "ruf"


def test_puma_letters_cover_the_eight_toolbox_configurations() -> None:
    puma = km.load("puma560")
    q = np.array([0.3, 0.5, -1.0, 0.4, 0.7, 0.2])
    res = puma.ik(puma.fk(q), respect_limits=False)
    assert res.count == 8
    expected = {"".join(c) for c in itertools.product("lr", "ud", "nf")}
    assert set(res.letters) == expected
    # flipping the wrist ((q4, q5, q6) -> (q4 + π, -q5, q6 + π)) swaps n and f only
    for sol, letters in zip(res.solutions, res.letters, strict=True):
        flipped = sol + np.array([0, 0, 0, np.pi, 0, np.pi])
        flipped[4] = -sol[4]
        other = [
            b
            for s, b in zip(res.solutions, res.letters, strict=True)
            if np.abs(km.wrap_angle(s - flipped)).max() < 1e-9
        ]
        assert other == [letters[:2] + {"n": "f", "f": "n"}[letters[2]]]


def test_batch_letters_equal_the_single_results() -> None:
    puma = km.load("puma560")
    T = puma.fk(puma.random_q(4, seed=1))
    many = puma.ik(T)
    for i in range(4):
        single = many[i]
        assert tuple(many.letters[i][: single.count]) == single.letters
        assert all(s == "" for s in many.letters[i][single.count :])
