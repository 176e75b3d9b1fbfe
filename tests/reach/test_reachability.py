"""Reachability maps against geometry worked by hand (issue 37's "done means").

Each arm below has a reachable set of tool orientations known in closed form at
every point: the map's count of orientations reached must equal, voxel by voxel,
the count of the set's orientations that the hand-derived condition accepts,
wherever no orientation lies within MARGIN of the condition's boundary (there
round-off decides either way). The continuous value (the share of *all*
orientations) is checked against the set's discrepancy.
"""

from __future__ import annotations

import numpy as np
import pytest
from support.reach_arms import L1, L2, L3, R_IN, R_OUT, elbow_wrist, planar

import kinematica as km

#: Pairs (voxel, orientation) whose hand-derived condition is within this (m) of
#: its boundary are left out: there IK and the formula may differ by round-off.
MARGIN = 1e-7


def _shell_ok(r: np.ndarray, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """(inside the shell lo <= r <= hi, clear of its boundary by MARGIN)."""
    ok = (r >= lo) & (r <= hi)
    clear = (np.abs(r - lo) > MARGIN) & (np.abs(r - hi) > MARGIN)
    return ok, clear


def test_planar_3r_counts_every_orientation_the_wrist_circle_allows() -> None:
    robot = planar(3)
    n = 36
    m = km.reachability(robot, resolution=0.1, orientations=n)
    assert m.shape[2] == 1 and m.plane == 2
    c = m.centres()[:, :, 0, :2]  # (nx, ny, 2), the plane z = 0
    phi = 2 * np.pi * (np.arange(n) + 0.5) / n  # planar_set's turns about z
    w = c[..., None, :] - L3 * np.stack([np.cos(phi), np.sin(phi)], axis=-1)
    ok, clear = _shell_ok(np.linalg.norm(w, axis=-1), abs(L1 - L2), L1 + L2)
    decided = clear.all(axis=-1)
    assert decided.mean() > 0.9
    expected = ok.sum(axis=-1)
    np.testing.assert_array_equal(m.reached[..., 0][decided], expected[decided])
    # The share of all turns reaching, in closed form: |c - l3 e(φ)|² = ρ² + l3² − 2ρ l3
    # cos(φ − θ) lies in [(l1 − l2)², (l1 + l2)²] on two arcs symmetric about θ, each
    # holding its length × n / 2π turns of the grid to within one.
    rho = np.linalg.norm(c, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        lo = (rho**2 + L3**2 - (L1 + L2) ** 2) / (2 * rho * L3)
        hi = (rho**2 + L3**2 - (L1 - L2) ** 2) / (2 * rho * L3)
    exact = (np.arccos(np.clip(lo, -1, 1)) - np.arccos(np.clip(hi, -1, 1))) / np.pi
    err = np.abs(m.index[..., 0] - exact)[decided & (rho > 0)]
    assert err.max() <= 2.0 / n
    assert m.reached.max() == n  # the disc of radius l1 + l2 - l3 about the base is dexterous


def test_planar_2r_positions_fill_the_annulus() -> None:
    m = km.reachability(planar(2), resolution=0.05, orientations=None)
    assert m.count == 1 and m.orientations.shape == (0, 3, 3)
    rho = np.linalg.norm(m.centres()[:, :, 0, :2], axis=-1)
    ok, clear = _shell_ok(rho, L1 - L2, L1 + L2)
    np.testing.assert_array_equal(m.reachable[..., 0][clear], ok[clear])
    assert m.reachable_volume == pytest.approx(ok.sum() * 0.05**2)


def test_spherical_wrist_without_offset_is_dexterous_across_its_wrist_workspace() -> None:
    m = km.reachability(elbow_wrist(), resolution=0.1, orientations=24, manipulability=False)
    r = np.linalg.norm(m.centres(), axis=-1)
    ok, clear = _shell_ok(r, R_IN, R_OUT)
    np.testing.assert_array_equal(m.index[clear], np.where(ok[clear], 1.0, 0.0))
    assert np.all(np.isnan(m.manipulability))
    assert ok[clear].sum() > 500


def test_tool_offset_moves_the_wrist_centre_and_the_sphere_rule_holds() -> None:
    d = 0.12
    n = 32
    m = km.reachability(elbow_wrist(d), resolution=0.1, orientations=n)
    c = m.centres()  # (nx, ny, nz, 3)
    z = m.orientations[:, :, 2]  # (N, 3) the tool z axes
    wc = c[..., None, :] - d * z  # the wrist centre of each orientation
    ok, clear = _shell_ok(np.linalg.norm(wc, axis=-1), R_IN, R_OUT)
    decided = clear.all(axis=-1)
    np.testing.assert_array_equal(m.reached[decided], ok.sum(axis=-1)[decided])
    # Dexterous iff the sphere of radius d about the voxel centre lies in the shell.
    r = np.linalg.norm(c, axis=-1)
    sphere_in = (r - d >= R_IN) & (r + d <= R_OUT)
    assert np.all(m.dexterous[sphere_in])
    # ... and where the sphere pokes out by more than the set's covering angle, some
    # orientation sees it: the share of the sphere outside is then well above 1/N.
    with np.errstate(divide="ignore", invalid="ignore"):
        lo = (r**2 + d**2 - R_OUT**2) / (2 * r * d)
        hi = (r**2 + d**2 - R_IN**2) / (2 * r * d)
    exact = (np.clip(hi, -1, 1) - np.clip(lo, -1, 1)) / 2  # cos γ uniform on [-1, 1]
    sel = decided & (r > 0)
    err = np.abs(m.index - exact)[sel]
    assert err.max() <= 3.0 / n  # the Fibonacci lattice's zone discrepancy at n = 32: 2.7/n
    assert np.all(~m.dexterous[sel & (exact < 1 - 4 / n)])
    # the best manipulability is that of some solution: positive where reached
    assert np.all(m.manipulability[m.reachable] > 0)
    assert np.all(np.isnan(m.manipulability[~m.reachable]))
