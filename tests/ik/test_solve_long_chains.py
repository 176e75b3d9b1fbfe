"""robot.ik of batches on long chains: 32 to 100 joints (robot files allow 100).

The core names a target's free joints in a 32-bit mask (``FREE_JOINTS``); a batch
read every joint's bit, and a shift of that mask by 32 or more is undefined
behaviour (a batch on a 33-joint arm aborted the sanitizer build). Bits past the
mask read as not free; only closed forms name free joints, on arms of at most 32
joints. ``make sanitize`` runs this file.
"""

from __future__ import annotations

import numpy as np
import pytest
from support.helpers import assert_transform_close

import kinematica as km
from kinematica import _core_testing

#: Residual (m, rad) the numeric search is held to here: its default tolerance.
TOL = 1e-9


def long_arm(n: int, rng: np.random.Generator) -> km.Robot:
    rows = [
        km.Revolute(
            a=float(rng.uniform(0.02, 0.06)),
            d=float(rng.uniform(0.0, 0.03)),
            alpha=float(rng.uniform(-1.5, 1.5)),
        )
        for _ in range(n)
    ]
    return km.Robot.from_dh(rows, name=f"{n}R", convention="standard")


def test_the_mask_has_the_bits_arm_position_names() -> None:
    assert _core_testing.decoupled.MAX_POSITION_DOF == 32


@pytest.mark.parametrize("n", [33, 40, 100])
def test_pose_batches_on_long_arms(n: int) -> None:
    rng = np.random.default_rng(n)
    robot = long_arm(n, rng)
    q = rng.uniform(-0.5, 0.5, (6, n))
    T = robot.fk(q)
    res = robot.ik(T, seed=1)
    assert res.method == "numeric:lm"
    assert list(res.status) == ["ok"] * 6
    assert res.free.shape == (6, n) and not res.free.any()
    assert_transform_close(robot.fk(res.solutions[:, 0]), T, atol=TOL)


def test_position_batches_at_the_mask_width_and_past_it() -> None:
    rng = np.random.default_rng(7)
    # 32 joints: the PUMA's arm, then 28 more; the closed form of joints 1-3 places the
    # tool origin and names joints 4..32 free (bits 3..31)
    rows = list(km.load("puma560").links[:4])
    rows += [km.Revolute(a=0.01, alpha=float(rng.uniform(-1.5, 1.5))) for _ in range(28)]
    arm32 = km.Robot.from_dh(rows, name="32R", convention="standard")
    q = rng.uniform(-0.5, 0.5, (4, 32))
    p = arm32.fk(q)[:, :3, 3]
    res = arm32.ik(p)
    assert res.method == "analytic:arm-position"
    assert (res.status == "singular").all()
    expected = np.zeros(32, dtype=bool)
    expected[3:] = True
    np.testing.assert_array_equal(res.free, np.broadcast_to(expected, (4, 32)))
    sols = res.solutions[np.isfinite(res.solutions[..., 0])]
    np.testing.assert_allclose(arm32.fk(sols)[:, :3, 3], np.repeat(p, res.count, axis=0), atol=TOL)
    # 40 joints: past the closed form's reach, searched, no joint named free
    arm40 = long_arm(40, rng)
    q40 = rng.uniform(-0.5, 0.5, (4, 40))
    p40 = arm40.fk(q40)[:, :3, 3]
    res40 = arm40.ik(p40, seed=1)
    assert list(res40.status) == ["ok"] * 4 and not res40.free.any()
    np.testing.assert_allclose(arm40.fk(res40.solutions[:, 0])[:, :3, 3], p40, atol=TOL)
