"""A parametrised closed form at given values: the values per target, and one call per value."""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import ArgumentError, DimensionError
from kinematica.ik import closed_form
from kinematica.ik.at_values import AtValues, parameter_values
from kinematica.ik.result import BATCH_FIELDS


def test_one_value_or_one_per_target() -> None:
    np.testing.assert_array_equal(parameter_values("arm_angle", 0.5, ()), [0.5])
    np.testing.assert_array_equal(parameter_values("arm_angle", np.float32(0.5), (2, 3)), [0.5] * 6)
    per = np.arange(6.0).reshape(2, 3)
    np.testing.assert_array_equal(parameter_values("arm_angle", per, (2, 3)), np.arange(6.0))
    np.testing.assert_array_equal(parameter_values("arm_angle", [[0.1]], (1, 1)), [0.1])


@pytest.mark.parametrize(
    ("value", "error", "match"),
    [
        (True, ArgumentError, "arm_angle must be a number"),
        ("up", ArgumentError, "arm_angle must be a number"),
        (math.inf, ArgumentError, "arm_angle must be finite"),
        ([0.1, math.nan], ArgumentError, "arm_angle must be finite"),
        ([0.1, 0.2, 0.3], DimensionError, r"one per target \(shape \(2,\)\), got shape \(3,\)"),
        ([[0.1, 0.2]], DimensionError, "one per target"),  # broadcastable is not enough
    ],
)
def test_bad_values(value: object, error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match) as err:
        parameter_values("arm_angle", value, (2,))  # type: ignore[arg-type]
    assert err.value.arg == "arm_angle"  # type: ignore[attr-defined]


def test_a_batch_of_values_solves_each_target_at_its_own() -> None:
    iiwa = km.load("iiwa14")
    q = np.random.default_rng(0).uniform(-1.5, 1.5, (5, 7))
    T = np.ascontiguousarray(iiwa.fk(q))
    closed = closed_form(iiwa.chain, "pose", "arm_angle")
    assert closed is not None
    opts = km._core.CheckOptions()
    values = np.array([0.2, -1.0, 0.2, 2.5, -1.0])
    got = AtValues(closed.params, values).ik_batch(iiwa.chain.core, T, opts, None, None, 1)
    for v in np.unique(values):
        rows = np.flatnonzero(values == v)
        want = closed.params.at(v).ik_batch(iiwa.chain.core, T[rows], opts, None, None, 1)
        for key in BATCH_FIELDS:
            np.testing.assert_array_equal(getattr(got, key)[rows], getattr(want, key), err_msg=key)
    assert closed.params.psi == 0.0  # the solver built once per arm is never changed
    with pytest.raises(ValueError, match="psi must be of size 5"):
        closed.params.ik_batch_at(iiwa.chain.core, T, values[:2], opts, None, None, 1)
