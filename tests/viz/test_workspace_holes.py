"""Workspace slices fill the holes the sampling left, and no genuine cavity."""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.motion.volume import sampling_holes

pytest.importorskip("matplotlib")
from kinematica.motion.plot import slice_figure


def _full_with_hole(hole: tuple[slice, slice]) -> np.ndarray:
    occ = np.zeros((14, 14), dtype=bool)
    occ[2:12, 2:12] = True
    occ[hole] = False
    return occ


@pytest.mark.parametrize(
    ("hole", "filled"),
    [
        ((slice(6, 7), slice(6, 7)), 1),  # one cell: filled
        ((slice(6, 8), slice(6, 8)), 4),  # two cells wide: below the grid's resolution, filled
        ((slice(5, 8), slice(5, 8)), 0),  # three cells wide: a cavity, kept
        ((slice(4, 9), slice(5, 8)), 0),
    ],
)
def test_holes_filled_and_cavities_kept(hole: tuple[slice, slice], filled: int) -> None:
    occ = _full_with_hole(hole)
    holes = sampling_holes(occ)
    assert not (holes & occ).any()
    assert int(holes.sum()) == filled
    assert not holes[:2].any() and not holes[12:].any()  # nothing outside the square


def test_staircase_notches_are_not_filled() -> None:
    # a disc of cells: the closing fills notches of its staircase, which are outside it
    i, j = np.meshgrid(np.arange(30), np.arange(30), indexing="ij")
    occ = (i - 14.5) ** 2 + (j - 14.5) ** 2 <= 11.0**2
    assert not sampling_holes(occ).any()
    flat = sampling_holes(occ[:, :, None])  # a planar grid: a flat third axis
    assert flat.shape == (30, 30, 1) and not flat.any()


def test_two_link_arm_slice_keeps_its_inner_hole() -> None:
    # a planar 2R arm reaches the annulus |l1 - l2| <= r <= l1 + l2, nothing else
    l1, l2 = 1.0, 0.6
    arm = km.Robot.from_dh([km.Revolute(a=l1), km.Revolute(a=l2)], convention="standard")
    ws = km.workspace(arm, samples=12_000, seed=3, manipulability=True)
    sl = ws.slice()
    assert sl.plane == "xy"
    fig = slice_figure(sl, "2R")
    reach_image, manip_image = fig.axes[0].images[:2]
    shown = np.isfinite(np.ma.filled(reach_image.get_array(), np.nan)).T
    manip = np.ma.filled(manip_image.get_array(), np.nan).T
    nu, nv = sl.occupancy.shape
    u0, v0 = sl.origin
    iu, iv = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    corners = [
        np.hypot(u0 + (iu + du) * sl.pixel, v0 + (iv + dv) * sl.pixel)
        for du in (0, 1)
        for dv in (0, 1)
    ]
    far = np.max(corners, axis=0)  # the pixel's farthest point from the base
    # every point of a pixel is within half its diagonal of its centre
    centre = np.hypot(u0 + (iu + 0.5) * sl.pixel, v0 + (iv + 0.5) * sl.pixel)
    margin = sl.pixel / np.sqrt(2.0)
    in_hole = far < abs(l1 - l2)
    outside = centre - margin > l1 + l2
    inside = (centre - margin > abs(l1 - l2)) & (centre + margin < l1 + l2)
    assert in_hole.sum() > 20 and inside.sum() > 500  # the test has cells of each kind
    assert not shown[in_hole].any()  # the genuine hole stays empty
    assert not shown[outside].any()
    assert (~sl.occupancy[inside]).any()  # the sampling left holes inside ...
    assert shown[inside].all()  # ... and the picture fills every one
    holes = sampling_holes(sl.occupancy)
    assert np.isfinite(manip[holes]).all()
    dots = next(c for c in fig.axes[0].collections if c.get_gid() == "sampling-holes")
    assert len(dots.get_offsets()) == int(holes.sum())
    legend = fig.axes[0].get_legend()
    assert legend is not None and "no sample" in legend.get_texts()[0].get_text()
