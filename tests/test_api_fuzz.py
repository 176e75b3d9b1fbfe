"""Hostile values through every public motion and robot function.

Each call either answers or raises a KinematicaError (and warns, if at all,
with a KinematicaWarning): never a LinAlgError, OverflowError, TypeError,
MemoryError or a ValueError of numpy's. Arguments with a stated range are
refused before any work starts, by a message naming the argument and the range.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import ArgumentError, KinematicaError, KinematicaWarning
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
from kinematica.motion.trajectory import MAX_DURATION, MAX_SAMPLES
from kinematica.motion.workspace import MAX_CELLS, voxel_range
from kinematica.motion.workspace import MAX_SAMPLES as MAX_WORKSPACE_SAMPLES
from kinematica.robot.sampling import MAX_CONFIGURATIONS
from kinematica.viz._mpl import (
    MAX_DPI,
    MAX_PIXELS,
    MAX_SIDE,
    MIN_DPI,
    MIN_SIDE,
    VizError,
    check_picture,
)
from kinematica.viz.animate import MAX_FPS, MAX_RESAMPLED, MIN_FPS, animation_samples

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


# --- the ranges, named, and refused before any work ---------------------------------------


def test_a_duration_and_dt_that_give_too_many_samples_are_refused() -> None:
    qa, qb = [0.0, 0.0], [1.0, 1.0]
    dt = 2.0**-10  # exact in binary: duration / dt is exact too
    at_limit = (MAX_SAMPLES - 1) * dt
    inside = joint_trajectory(qa, qb, at_limit, "trapezoid", dt=dt)  # the cheapest profile
    assert inside.t.size == MAX_SAMPLES  # just inside
    with pytest.raises(
        ArgumentError, match=r"^duration/dt gives 1e\+06 samples .* 1,000,000"
    ) as info:
        joint_trajectory(qa, qb, at_limit + dt, dt=dt)  # just outside
    assert info.value.arg == "duration/dt"
    with pytest.raises(ArgumentError, match=r"^duration/dt gives inf samples \(2 s every 1e-320"):
        joint_trajectory(qa, qb, 2.0, dt=1e-320)
    with pytest.raises(
        ArgumentError,
        match=r"^duration must be a number of seconds greater than 0 and at most 1e\+09 s, "
        r"got 1e\+308",
    ):
        joint_trajectory(qa, qb, 1e308)
    with pytest.raises(
        ArgumentError, match=r"^dt must be a number of seconds greater than 0 s?, got -1"
    ):
        joint_trajectory(qa, qb, 1.0, dt=-1)


def test_limits_that_need_too_long_a_duration_are_refused() -> None:
    qa, qb = [0.0, 0.0], [1.0, 1.0]
    with pytest.raises(
        ArgumentError, match=r"^vmax gives a duration of .* s; at most 1e\+09 s"
    ) as info:
        joint_trajectory(qa, qb, vmax=1e-320)
    assert info.value.arg == "vmax"
    with pytest.raises(ArgumentError, match=r"^vmax/amax give a duration"):
        joint_trajectory(qa, qb, None, "trapezoid", vmax=1e-320, amax=1e-320)
    # A slow joint whose duration is fine but whose samples are too many at this dt.
    with pytest.raises(ArgumentError, match=r"^amax gives .* samples"):
        joint_trajectory(qa, qb, amax=1e-9, dt=1e-3)


def test_the_voxel_range_follows_the_arm_and_the_grid() -> None:
    arm = _arm()  # planar 3R, links 0.4 + 0.3 + 0.2 m: a bound on its reach is 0.9 m
    smallest, largest = voxel_range(arm)
    assert largest == pytest.approx(2 * 0.9)
    assert smallest == pytest.approx(largest / MAX_CELLS)
    ws = workspace(arm, samples=50, seed=0, voxel=largest)  # just inside
    assert ws.area is not None and ws.area > 0
    start = time.perf_counter()
    with pytest.raises(
        ArgumentError, match=r"^voxel must be a length from .* to 1\.8 m for .*, got 1\.81"
    ):
        workspace(arm, samples=10**7, seed=0, voxel=largest * 1.01)  # refused before sampling
    with pytest.raises(ArgumentError, match=r"^voxel must be a length from 4\.29\d*e-07 to 1\.8"):
        workspace(arm, samples=10**7, seed=0, voxel=smallest * 0.99)
    assert time.perf_counter() - start < 0.5  # 10**7 samples would take seconds
    workspace(arm, samples=50, seed=0, voxel=smallest * 1.01)  # coarsened to fit, as before


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


def test_manipulability_of_a_batch_with_nan_rows_is_nan_there() -> None:
    arm = _arm()
    with pytest.warns(KinematicaWarning, match="1 row"):
        w = manipulability(arm, [[0.0, 0.5, 0.5], [0.0, math.nan, 0.0]], axes="trans")
    assert np.isnan(w[1])
    assert w[0] == pytest.approx(float(manipulability(arm, [0.0, 0.5, 0.5], axes="trans")))


def test_the_longest_duration() -> None:
    qa, qb = [0.0], [1.0]
    assert joint_trajectory(qa, qb, MAX_DURATION, dt=MAX_DURATION / 10).t[-1] == MAX_DURATION
    with pytest.raises(
        ArgumentError, match=r"^duration must be .* at most 1e\+09 s, got 1010000000\.0"
    ):
        joint_trajectory(qa, qb, MAX_DURATION * 1.01, dt=MAX_DURATION / 10)


# --- pictures and animations: their ranges, both sides of each bound ------------------------


def test_picture_sizes_and_dpi() -> None:
    assert check_picture((MIN_SIDE, MAX_SIDE), MIN_DPI) == ((MIN_SIDE, MAX_SIDE), MIN_DPI)
    tallest = MAX_PIXELS // MAX_SIDE
    assert check_picture((MAX_SIDE, tallest), MAX_DPI)[0] == (MAX_SIDE, tallest)
    for size, match in [
        ((MIN_SIDE - 1, 100), r"^size must be a whole number from 16 to 20,000, got 15"),
        ((100, MAX_SIDE + 1), r"^size must be a whole number from 16 to 20,000, got 20001"),
        ((MAX_SIDE, tallest + 1), r"^size gives 4e\+07 pixels; at most 40,000,000"),
        ((100.0, 100), r"^size must be a whole number"),
        ((100,), r"^size must be \(width, height\) in pixels"),
    ]:
        with pytest.raises(ArgumentError, match=match):
            check_picture(size, 100.0)
    for dpi in (MIN_DPI * 0.99, MAX_DPI * 1.01, math.nan, "100"):
        with pytest.raises(ArgumentError, match=r"^dpi must be a number of dots per inch from 10"):
            check_picture(None, dpi)


def test_animation_frame_rates() -> None:
    q = np.zeros((2, 1))
    slow = np.array([0.0, 1.0 / MIN_FPS])  # two samples, 100 s apart
    assert animation_samples(slow, q, MIN_FPS, None, timed=True)[2] == MIN_FPS
    assert animation_samples(slow, q, None, None, timed=True)[2] == pytest.approx(MIN_FPS)
    with pytest.raises(VizError, match=r"would play at 0\.0099 frames a second .* slower than"):
        animation_samples(slow * 1.01, q, None, None, timed=True)
    for fps in (MIN_FPS * 0.99, MAX_FPS * 1.01):
        with pytest.raises(ArgumentError, match=r"^fps must be a number of frames a second from"):
            animation_samples(slow, q, fps, None, timed=True)
    assert animation_samples(slow, q, MAX_FPS, 300, timed=True)[2] == pytest.approx(
        MAX_FPS * 299 / (100 * MAX_FPS)
    )
    # fps times the duration: the frames resampled, counted before any is made.
    longest = np.array([0.0, (MAX_RESAMPLED - 1) / 100.0])
    assert len(animation_samples(longest, q, 100.0, None, timed=True)[0]) == MAX_RESAMPLED
    with pytest.raises(ArgumentError, match=r"^fps gives 1e\+06 frames over .* at most 1,000,000"):
        animation_samples(longest + np.array([0.0, 0.01]), q, 100.0, None, timed=True)


def test_the_most_configurations_and_samples() -> None:
    one = km.Robot.from_dh([km.Revolute(a=1.0, qlim=(-1.0, 1.0))])
    assert random_q(one, (MAX_CONFIGURATIONS // 2, 0)).shape == (MAX_CONFIGURATIONS // 2, 0, 1)
    with pytest.raises(ArgumentError, match=r"^n gives 1e\+07 configurations; at most 10,000,000"):
        random_q(one, (MAX_CONFIGURATIONS // 2 + 1, 2))  # a batch shape counts all of it
    with pytest.raises(
        ArgumentError, match=r"^samples must be a whole number from 1 to 20,000,000"
    ):
        workspace(one, samples=MAX_WORKSPACE_SAMPLES + 1)
