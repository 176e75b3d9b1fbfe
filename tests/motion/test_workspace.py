"""Workspace sampling: volume and area against closed forms, slices, memory, random_q."""

from __future__ import annotations

import itertools
import math
import time
import tracemalloc
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import ArgumentError
from kinematica.motion import (
    workspace,
)
from kinematica.motion.volume import FLAT_COMPONENT, cube_fraction
from kinematica.motion.workspace import CHUNK, MAX_CELLS, voxel_range

# anthropomorphic-3r: shoulder at height L1 = 0.5, links L2 = 0.4, L3 = 0.3, no limits:
# a spherical shell of radii |L2 - L3| and L2 + L3 about the shoulder.
SHELL = 4.0 / 3.0 * np.pi * (0.7**3 - 0.1**3)
# planar-3r: l = 0.4, 0.3, 0.2 -> a disc of radius 0.9 (inner radius max(0, 0.4 - 0.5) = 0).
DISC = np.pi * 0.9**2


def test_3r_shell_volume_within_1_percent() -> None:
    ws = km.workspace(km.load("anthropomorphic-3r"), samples=400_000, seed=0, manipulability=False)
    assert abs(ws.volume / SHELL - 1.0) < 0.01
    r = np.linalg.norm(ws.points - [0.0, 0.0, 0.5], axis=1)
    assert r.min() >= 0.1 - 1e-12 and r.max() <= 0.7 + 1e-12
    # the slice through the shoulder is an annulus
    sl = ws.slice("xz", at=0.0)
    assert abs(sl.area / (np.pi * (0.7**2 - 0.1**2)) - 1.0) < 0.03


def cartesian_box() -> km.Robot:
    """A PPP arm whose tool sweeps the box (0, 0.5) x (0, 0.4) x (0, 0.3): 0.06 m³."""
    return km.Robot.from_dh(
        [
            km.Prismatic(alpha=-np.pi / 2, qlim=(0.0, 0.5)),
            km.Prismatic(theta=-np.pi / 2, alpha=-np.pi / 2, qlim=(0.0, 0.4)),
            km.Prismatic(qlim=(0.0, 0.3)),
        ],
        convention="standard",
    )


@pytest.mark.parametrize("samples", [100_000, 300_000, 1_000_000])
def test_box_on_the_voxel_planes_within_1_percent(samples: int) -> None:
    """Issue 23 item 5: the lower faces lie on voxel planes (the grid starts there); a half
    weight for every boundary voxel made this 7.5, 5.6 and 3.6 % small."""
    ppp = cartesian_box()
    assert np.allclose(ppp.fk([0.5, 0.4, 0.3])[:3, 3], [0.3, 0.4, 0.5])  # the box's corner
    ws = km.workspace(ppp, samples=samples, seed=6, manipulability=False)
    assert abs(ws.volume / 0.06 - 1.0) < 0.01


def test_turned_box_within_1_percent() -> None:
    turn = km.make_transform(km.matrix_from_rotvec([0.3, -0.5, 0.7]), [0.1, 0.2, 0.3])
    ws = km.workspace(
        cartesian_box().with_base(turn), samples=100_000, seed=6, manipulability=False
    )
    assert abs(ws.volume / 0.06 - 1.0) < 0.01


def fraction_exact(a: list[float], t: float) -> float:
    """The cube's fraction below a·x = t by inclusion-exclusion in exact rationals."""
    from fractions import Fraction

    fa = [Fraction(x) for x in a if x != 0]
    ft, d = Fraction(t), len(fa)
    total = Fraction(0)
    for corner in itertools.product((0, 1), repeat=d):
        s = ft - sum(x * c for x, c in zip(fa, corner, strict=True))
        if s > 0:
            total += (-1) ** sum(corner) * s**d
    return float(total / (math.factorial(d) * math.prod(fa)))


def test_cube_fraction_by_hand_and_by_integration() -> None:
    a = np.array([[1.0, 0.0, 0.0], [0.6, 0.8, 0.0], [0.48, 0.6, 0.64], [0.48, 0.6, 0.64]])
    t = np.array([0.3, 0.3, 0.5, 0.86])
    got = cube_fraction(a, t)
    assert got[0] == pytest.approx(0.3, abs=1e-15)  # a slab
    assert got[1] == pytest.approx(0.3**2 / (2 * 0.6 * 0.8), abs=1e-15)  # a corner triangle
    # a tilted plane: midpoint integration of the height under it over the unit square
    x = (np.arange(2000) + 0.5) / 2000
    X, Y = np.meshgrid(x, x)
    for k in (2, 3):
        height = np.clip((t[k] - 0.48 * X - 0.6 * Y) / 0.64, 0.0, 1.0)
        assert got[k] == pytest.approx(height.mean(), abs=1e-6)
    # the halves: F(t) + F(L − t) = 1
    L = a.sum(axis=1)
    assert np.allclose(cube_fraction(a, t) + cube_fraction(a, L - t), 1.0, atol=1e-14)


@pytest.mark.parametrize("t", [0.7, 1.1])
def test_cube_fraction_flat_component_boundary(t: float) -> None:
    """Above FLAT_COMPONENT a component is kept (dropping 5e-4 would cost 1e-4); below it is
    dropped (keeping 2e-9 would cost 2e-8 to cancellation, dropping it 1e-9)."""
    for c, tol in ((500 * FLAT_COMPONENT, 1e-12), (FLAT_COMPONENT / 500, 5e-9)):
        got = cube_fraction(np.array([[0.6, 0.8, c]]), np.array([t]))[0]
        assert abs(got - fraction_exact([0.6, 0.8, c], t)) < tol


def test_planar_3r_area_within_2_percent() -> None:
    ws = km.workspace(km.load("planar-3r"), samples=100_000, seed=1)
    assert ws.planar and ws.volume == 0.0
    assert ws.area is not None and abs(ws.area / DISC - 1.0) < 0.02
    assert abs(ws.slice("xy").area / DISC - 1.0) < 0.02


def test_planar_2r_annulus_with_a_given_voxel() -> None:
    arm = km.Robot.from_dh([km.Revolute(a=0.5), km.Revolute(a=0.3)], convention="standard")
    ws = km.workspace(arm, samples=200_000, seed=2, voxel=0.005, manipulability=False)
    assert ws.voxel == 0.005
    assert ws.area is not None and abs(ws.area / (np.pi * (0.8**2 - 0.2**2)) - 1.0) < 0.02


def test_manipulability_map_holds_the_largest_sample_per_voxel() -> None:
    arm = km.load("anthropomorphic-3r")
    ws = km.workspace(arm, samples=20_000, seed=3, voxel=0.1)
    assert ws.manipulability is not None
    assert np.allclose(ws.manipulability, km.manipulability(arm, _q(arm, 20_000, 3), axes="task"))
    occupied = ws.occupancy
    assert np.isfinite(ws.manipulability_map[occupied]).all()
    assert np.isnan(ws.manipulability_map[~occupied]).all()
    idx = np.floor((ws.points - ws.origin) / ws.voxel).astype(int)
    k = int(np.argmax(ws.manipulability))
    assert ws.manipulability_map[tuple(idx[k])] == ws.manipulability[k]


def _q(robot: km.Robot, n: int, seed: int) -> np.ndarray:
    """The same draws as km.workspace (one generator, chunk by chunk)."""
    rng = np.random.default_rng(seed)
    return np.concatenate([robot.random_q(min(CHUNK, n - s), seed=rng) for s in range(0, n, CHUNK)])


def test_points_are_forward_kinematics_of_samples_within_limits() -> None:
    puma = km.load("puma560")
    ws = km.workspace(puma, samples=1000, seed=4, manipulability=False)
    q = _q(puma, 1000, 4)
    assert np.all((q >= puma.qlim[:, 0]) & (q <= puma.qlim[:, 1]))
    assert np.allclose(ws.points, puma.fk(q)[:, :3, 3])
    assert np.allclose(ws.bounds, [ws.points.min(axis=0), ws.points.max(axis=0)])


def test_memory_grows_by_32_bytes_per_sample() -> None:
    """Structural bound: points (24 B) + manipulability (8 B) per sample, plus one chunk
    and one grid of at most MAX_CELLS cells. Measured at two sizes, the slope and the
    fixed part extrapolate 10 million samples to under 500 MB."""
    puma = km.load("puma560")

    def peak(n: int) -> int:
        tracemalloc.start()
        km.workspace(puma, samples=n, seed=0, voxel=0.05)
        size = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        return size

    small, large = peak(CHUNK), peak(3 * CHUNK)
    slope = (large - small) / (2 * CHUNK)
    fixed = small - slope * CHUNK
    assert slope < 40
    assert slope * 10_000_000 + fixed + MAX_CELLS * 10 < 500e6


def test_random_q_within_limits_and_shapes() -> None:
    puma = km.load("puma560")
    q = puma.random_q(5000, seed=0)
    assert q.shape == (5000, 6)
    assert np.all((q >= puma.qlim[:, 0]) & (q <= puma.qlim[:, 1]))
    assert np.array_equal(q, puma.random_q(5000, seed=0))
    # each joint covers its range (uniform: min/max near the limits)
    span = (q.max(axis=0) - q.min(axis=0)) / (puma.qlim[:, 1] - puma.qlim[:, 0])
    assert np.all(span > 0.99)
    for shape in [(1,), (3, 2)]:
        assert puma.random_q(shape, seed=1).shape == (*shape, 6)


def test_prismatic_joint_without_limits_is_an_error() -> None:
    arm = km.Robot.from_dh([km.Revolute(a=0.3), km.Prismatic()], convention="standard")
    with pytest.raises(km.KinematicaError, match=r"joint 2 .* prismatic without limits"):
        arm.random_q(3)
    with pytest.raises(km.KinematicaError, match="joint 2"):
        km.workspace(arm, samples=10)


def test_bad_arguments() -> None:
    arm = km.load("planar-3r")
    with pytest.raises(km.KinematicaError, match="samples"):
        km.workspace(arm, samples=0)
    with pytest.raises(km.KinematicaError, match="voxel"):
        km.workspace(arm, samples=10, voxel=-1.0)
    ws = km.workspace(arm, samples=1000, seed=0)
    with pytest.raises(km.KinematicaError, match="plane"):
        ws.slice("xw")
    with pytest.raises(km.KinematicaError, match="outside the workspace"):
        ws.slice("xz", at=5.0)


# The seed 000 PR arm as a student types it, with no base transform: q1 slides along
# z0 (stroke L = 0.5 m), joint 2 turns about y, so the tool sweeps the base's xz plane.
# The tool is on a circle of radius r = 0.4 about a centre sliding along L: it covers
# the stadium (pi r² + 2 r L) but for the lens where the discs about both ends overlap
# (points nearer than r to every centre): 2 r² acos(L / 2r) - (L / 2) sqrt(4 r² - L²).
PR_XZ = km.Robot.from_dh(
    [
        km.Prismatic(offset=0.5, alpha=np.pi / 2, qlim=(0.0, 0.5)),
        km.Revolute(offset=np.pi / 2, a=0.4),
    ],
    convention="standard",
)
PR_AREA = (
    np.pi * 0.4**2
    + 2 * 0.4 * 0.5
    - (2 * 0.4**2 * np.arccos(0.5 / 0.8) - 0.25 * np.sqrt(4 * 0.4**2 - 0.5**2))
)


def test_planar_workspace_out_of_xy_is_measured_in_its_own_plane() -> None:
    ws = km.workspace(PR_XZ, samples=100_000, seed=4, manipulability=False)
    assert ws.planar and ws.plane == "xz"
    assert ws.area is not None and abs(ws.area / PR_AREA - 1.0) < 0.02
    sl = ws.slice()  # the arm's own plane, not a sliver of xy
    assert sl.plane == "xz" and abs(sl.area / PR_AREA - 1.0) < 0.02
    assert km.workspace(km.load("planar-3r"), samples=2_000, seed=0).plane == "xy"
    assert km.workspace(km.load("anthropomorphic-3r"), samples=2_000, seed=0).plane is None


#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


WORKSPACE_PLANAR_TOL = 1e-9  # motion/workspace.py PLANAR_TOL


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_workspace_planar_tol_is_a_thickness(factor: float, inside: bool) -> None:
    """motion/workspace.PLANAR_TOL: a workspace thinner than it (m) along an axis
    is planar (an area, no volume).

    A planar 2R arm on a z slide of travel t: the sampled points span at most
    t in z (and nearly all of it, with 2000 samples drawn uniformly).
    """
    t = factor * WORKSPACE_PLANAR_TOL
    arm = km.Robot.from_dh(
        [km.Revolute(a=0.4), km.Revolute(a=0.3), km.Prismatic(qlim=(0.0, t))],
        name="2R on a slide",
        convention="standard",
    )
    ws = km.workspace(arm, samples=2000, seed=3, manipulability=False)
    thickness = float(np.ptp(ws.points[:, 2]))
    assert 0.9 * t <= thickness <= t * (1 + 1e-9) + 1e-15
    assert ws.planar is inside
    assert (ws.area is not None) is inside and (ws.volume == 0.0) is inside


def _arm() -> km.Robot:
    return km.load("planar-3r")


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


def test_a_slice_map_of_no_picture_type_is_an_argument_error(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    from kinematica.motion.plot import plot_workspace_slice

    sl = workspace(km.load("planar-3r"), samples=200, seed=0).slice("xy")
    with pytest.raises(ArgumentError, match=r"ws\.txt: cannot draw a map .* '\.txt'"):
        plot_workspace_slice(sl, tmp_path / "ws.txt")
    assert list(tmp_path.iterdir()) == []
    assert plot_workspace_slice(sl, tmp_path / "ws.svg").read_text().lstrip().startswith("<?xml")
