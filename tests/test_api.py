"""The public API: every exported name exists, and hostile values raise our errors only.

Each public motion and robot function, given hostile values, either answers or
raises a KinematicaError (and warns, if at all, with a KinematicaWarning): never a
LinAlgError, OverflowError, TypeError, MemoryError or a ValueError of numpy's.
Arguments with a stated range are refused by a message naming the argument.

That layers import only downwards, with no cycle, is checked by import-linter
(``lint-imports`` in ``make test``; contracts in pyproject.toml).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import KinematicaError, KinematicaWarning
from kinematica.motion import (
    analytic_jacobian,
    cartesian_path,
    condition_number,
    jacobian_rank,
    joint_trajectory,
    manipulability,
    random_q,
    singularities,
    time_scaling,
    workspace,
)


def test_every_name_in_all_exists() -> None:
    missing = [name for name in km.__all__ if not hasattr(km, name)]
    assert missing == []
    assert len(set(km.__all__)) == len(km.__all__)


def test_design_names_are_public() -> None:
    for name in (
        "load",
        "Robot",
        "Revolute",
        "Prismatic",
        "to_pose",
        "from_pose",
        "KinematicaError",
    ):
        assert name in km.__all__


#: Values no argument should crash on: non-numbers, non-finite and extreme
#: numbers, floats where counts are expected, wrong shapes.
HOSTILE: list[Any] = [
    math.nan,
    math.inf,
    -math.inf,
    1e308,
    -1e308,
    1e-320,
    -1,
    0,
    2.0,
    10**30,
    2**63,
    True,
    1j,
    "a",
    "",
    None,
    [],
    [[1.0, 2.0]],
    np.zeros((2, 3)),
    object(),
]


Call = Callable[[Any], object]


def _arm() -> km.Robot:
    return km.load("planar-3r")


def _q(v: Any, n: int = 3) -> Any:
    """A configuration made of ``v``: v itself when it is not a number."""
    if isinstance(v, float | int) and not isinstance(v, bool):
        return [0.1, v, 0.2][:n] if n == 3 else [v] * n
    return v


def _calls() -> dict[str, Call]:
    arm = _arm()
    puma = km.load("puma560")
    T = arm.fk([0.1, 0.2, 0.3])
    qa, qb = [0.0, 0.0, 0.0], [0.5, -0.5, 1.0]
    return {
        "fk q": lambda v: arm.fk(_q(v)),
        "fk batch q": lambda v: arm.fk([qa, _q(v)]),
        "fk all_frames": lambda v: arm.fk(qa, all_frames=v),
        "fk workers": lambda v: arm.fk([qa, qb], workers=v),
        "jacobian q": lambda v: arm.jacobian(_q(v)),
        "jacobian batch q": lambda v: arm.jacobian([qa, _q(v)]),
        "jacobian frame": lambda v: arm.jacobian(qa, frame=v),
        "jacobian euler": lambda v: arm.jacobian(qa, euler=v),
        "link_matrices q": lambda v: arm.link_matrices(_q(v)),
        "joint_axes q": lambda v: arm.joint_axes(_q(v)),
        "dh_table q": lambda v: arm.dh_table(_q(v)),
        "ik target": lambda v: arm.ik(v),
        "ik position": lambda v: arm.ik([0.5, v, 0.0]),
        "ik batch": lambda v: arm.ik(np.stack([T, np.full((4, 4), v)]) if _num(v) else v),
        "ik method": lambda v: arm.ik(T, method=v),
        "ik q0": lambda v: arm.ik(T, method="numeric", q0=_q(v)),
        "ik mask": lambda v: arm.ik(T, method="numeric", mask=[1, 1, v, 0, 0, 1]),
        "ik seed": lambda v: arm.ik(T, method="numeric", seed=v),
        "ik tol": lambda v: arm.ik(T, tol=v),
        "ik respect_limits": lambda v: arm.ik(T, respect_limits=v),
        "ik options": lambda v: arm.ik(T, options=v),
        "ik workers": lambda v: arm.ik(np.stack([T, T]), workers=v),
        "ik tol pair": lambda v: arm.ik(T, tol=(1e-9, v)),
        "with_limits": lambda v: arm.with_limits([(-1, 1), (-1, 1), v]),
        "with_tool": lambda v: arm.with_tool(np.full((4, 4), v) if _num(v) else v),
        "with_base": lambda v: arm.with_base(v),
        "to_convention": lambda v: arm.to_convention(v),
        "load": lambda v: km.load(v),
        "workspace manipulability": lambda v: workspace(arm, samples=50, manipulability=v),
        "cartesian_path position_only": lambda v: cartesian_path(arm, T, T, 2, position_only=v),
        "ik 6R target": lambda v: puma.ik(np.full((4, 4), v) if _num(v) else v),
        "singularities q": lambda v: singularities(arm, _q(v)),
        "singularities batch": lambda v: singularities(puma, [[0.0] * 6, _q(v, 6)]),
        "robot.singularities": lambda v: puma.singularities(_q(v, 6), detail=True),
        "jacobian_rank q": lambda v: jacobian_rank(arm, [qa, _q(v)]),
        "manipulability q": lambda v: manipulability(arm, [qa, _q(v)]),
        "manipulability axes": lambda v: manipulability(arm, qa, axes=v),
        "condition_number q": lambda v: condition_number(puma, [[0.0] * 6, _q(v, 6)]),
        "analytic_jacobian q": lambda v: analytic_jacobian(puma, _q(v, 6)),
        "analytic_jacobian euler": lambda v: analytic_jacobian(puma, [0.1] * 6, v),
        "random_q n": lambda v: random_q(arm, v),
        "random_q shape": lambda v: random_q(arm, (2, v)),
        "random_q seed": lambda v: random_q(arm, 2, seed=v),
        "robot.random_q n": lambda v: arm.random_q(v),
        "workspace samples": lambda v: workspace(arm, samples=v, seed=0),
        "workspace seed": lambda v: workspace(arm, samples=50, seed=v),
        "workspace voxel": lambda v: workspace(arm, samples=50, seed=0, voxel=v),
        "workspace progress": lambda v: workspace(arm, samples=50, seed=0, progress=v),
        "workspace slice at": lambda v: workspace(arm, samples=50, seed=0).slice("xy", at=v),
        "workspace slice plane": lambda v: workspace(arm, samples=50, seed=0).slice(v),
        "joint_trajectory q0": lambda v: joint_trajectory(_q(v), qb, 1.0),
        "joint_trajectory q1": lambda v: joint_trajectory(qa, _q(v), 1.0),
        "joint_trajectory duration": lambda v: joint_trajectory(qa, qb, v),
        "joint_trajectory profile": lambda v: joint_trajectory(qa, qb, 1.0, v),
        "joint_trajectory dt": lambda v: joint_trajectory(qa, qb, 1.0, dt=v),
        "joint_trajectory vmax": lambda v: joint_trajectory(qa, qb, vmax=v),
        "joint_trajectory amax": lambda v: joint_trajectory(qa, qb, amax=v),
        "trapezoid vmax": lambda v: joint_trajectory(qa, qb, None, "trapezoid", vmax=v, amax=1),
        "trapezoid amax": lambda v: joint_trajectory(qa, qb, None, "trapezoid", vmax=1, amax=v),
        "trapezoid duration": lambda v: joint_trajectory(qa, qb, v, "trapezoid", amax=1e3),
        "quintic qd0": lambda v: joint_trajectory(qa, qb, 1.0, qd0=v),
        "quintic qdd1": lambda v: joint_trajectory(qa, qb, 1.0, qdd1=_q(v)),
        "time_scaling duration": lambda v: time_scaling("quintic", [0.0, 0.5], v),
        "time_scaling t": lambda v: time_scaling("cubic", v, 1.0),
        "time_scaling vmax": lambda v: time_scaling("trapezoid", [0.0, 0.5], 1.0, v),
        "cartesian_path T1": lambda v: cartesian_path(arm, T, np.full((4, 4), v) if _num(v) else v),
        "cartesian_path steps": lambda v: cartesian_path(arm, T, T, steps=v),
        "cartesian_path q0": lambda v: cartesian_path(arm, T, T, steps=2, q0=_q(v)),
        "cartesian_path via": lambda v: cartesian_path(arm, T, T, steps=2, via=[v, 0.0, 0.0]),
        "cartesian_path s": lambda v: cartesian_path(arm, T, T, s=[0.0, v] if _num(v) else v),
    }


def _num(v: Any) -> bool:
    return isinstance(v, float | int) and not isinstance(v, bool)


CALLS = _calls()


@pytest.mark.parametrize("name", sorted(CALLS))
def test_hostile_values_raise_kinematica_errors_only(name: str) -> None:
    call = CALLS[name]
    for value in HOSTILE:
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            with np.errstate(all="ignore"):
                try:
                    call(value)
                except KinematicaError:
                    pass
                except Exception as exc:  # the defect this test is for
                    pytest.fail(f"{name}({value!r}) raised {type(exc).__name__}: {exc}")
        other = [w for w in seen if not issubclass(w.category, KinematicaWarning)]
        assert not other, f"{name}({value!r}) warned {other[0].category.__name__}: {other[0]}"


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: workspace(_arm(), samples=2.0), r"^samples must be a whole number from 1 to"),
        (lambda: workspace(_arm(), samples=50, seed=0.0), r"^seed must be a whole number >= 0"),
        (lambda: random_q(_arm(), 2.0), r"^n must be a whole number of at least 0, got 2\.0"),
        (lambda: _arm().random_q(10**8), r"^n gives 1e\+08 configurations; at most 10,000,000"),
        (lambda: random_q(_arm(), 2, seed="x"), r"^seed must be a whole number"),
        (lambda: workspace(_arm(), samples=50, seed=0).slice("xy", at=math.nan), r"^at must be"),
        (lambda: cartesian_path(_arm(), np.eye(4), np.eye(4), steps=10**9), r"^steps must be"),
        (lambda: singularities(_arm(), [[0, 0, 0], [0, math.nan, 0]]), r"q\[1\] contains NaN"),
        (lambda: jacobian_rank(_arm(), [math.inf, 0, 0]), r"q contains NaN or inf"),
    ],
)
def test_range_errors_name_the_argument(call: Callable[[], object], match: str) -> None:
    with pytest.raises(KinematicaError, match=match):
        call()
