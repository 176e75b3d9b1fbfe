"""The reachability map in the interactive page: what it embeds, and what Chromium draws.

The page decodes the voxels itself (JavaScript, ``web/reach.js``); the number it draws
in a slice is compared with the map's own arrays counted by numpy, its colours with
matplotlib's viridis, and its map with the one the file holds. A saved map of another
robot, or a file that is not a map, is refused with a message; nothing from the map is
markup. The browser tests skip where no Chromium is installed (as ``test_page.py``).
"""

from __future__ import annotations

import json
import os
import re
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from support.cli import run

import kinematica as km
from kinematica import viz
from kinematica.reach import ReachabilityMap, save_map
from kinematica.viz import VizError
from kinematica.viz.page_reach import COARSE_VOXELS, MAX_PAGE_VOXELS, reach_data


def _chromium() -> str | None:
    for candidate in (
        os.environ.get("KINEMATICA_CHROMIUM"),
        "/usr/bin/chromium",
        shutil.which("chromium"),
        shutil.which("chromium-browser"),
    ):
        if candidate and Path(candidate).exists():
            return candidate
    return None


CHROMIUM = _chromium()
needs_browser = pytest.mark.skipif(CHROMIUM is None, reason="no Chromium installed")


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = p.chromium.launch(
            executable_path=CHROMIUM,
            args=["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking"],
        )
        yield b
        b.close()


@pytest.fixture
def page(browser: Any) -> Iterator[Any]:
    pg = browser.new_page(viewport={"width": 1100, "height": 720})
    pg.set_default_timeout(10_000)
    errors: list[str] = []
    pg.on("console", lambda m: errors.append(m.text) if m.type in ("error", "warning") else None)
    pg.on("pageerror", lambda e: errors.append(str(e)))
    yield pg
    assert errors == [], errors
    pg.close()


def _map(n_reached: int, count: int = 4) -> ReachabilityMap:
    """A map of ``n_reached`` reachable voxels in a row (x), reaching 1..count orientations."""
    reached = (np.arange(n_reached, dtype=np.int32) % count + 1).reshape(n_reached, 1, 1)
    return ReachabilityMap(
        robot="PUMA 560",
        origin=np.zeros(3),
        resolution=0.1,
        orientations=np.broadcast_to(np.eye(3), (count, 3, 3)).copy(),
        reached=reached,
        solutions=reached.copy(),
        manipulability=np.full(reached.shape, np.nan),
        centre=np.zeros(3),
        radius=1.0,
    )


def _embedded(html: str) -> dict[str, Any]:
    found = re.search(r'<script type="application/json" id="robot-data">(.*?)</script>', html, re.S)
    assert found is not None
    data: dict[str, Any] = json.loads(found.group(1))
    return data


# ----------------------------------------------------------- without a browser
def test_page_embeds_the_maps_numbers() -> None:
    robot = km.load("puma560")
    m = viz.coarse_map(robot)
    data = _embedded(viz.page_html(robot, reach=m))["reach"]
    assert data["shape"] == list(m.shape) and data["count"] == m.count == 16
    assert data["resolution"] == m.resolution == pytest.approx(2 * m.radius / COARSE_VOXELS)
    flat = m.reached.reshape(-1)
    assert data["voxels"] == np.flatnonzero(flat).tolist()
    assert data["reached"] == flat[flat > 0].tolist()
    assert data["dexterous"] == int(np.count_nonzero(m.dexterous))
    assert _embedded(viz.page_html(robot))["reach"] is None


def test_page_voxel_limit_boundary() -> None:
    assert len(reach_data(_map(MAX_PAGE_VOXELS))["voxels"]) == MAX_PAGE_VOXELS
    with pytest.raises(VizError, match="coarser resolution"):
        reach_data(_map(MAX_PAGE_VOXELS + 1))


def test_saved_maps_are_checked(tmp_path: Path) -> None:
    puma, ur5 = km.load("puma560"), km.load("ur5")
    saved = save_map(_map(30), tmp_path / "puma.npz")
    assert viz.page_map(puma, saved).reached.sum() == _map(30).reached.sum()
    with pytest.raises(VizError, match="the map of 'PUMA 560', not of 'UR5'"):
        viz.page_map(ur5, saved)
    vti = save_map(_map(30), tmp_path / "puma.vti")
    with pytest.raises(VizError, match="not a reachability map"):
        viz.page_map(puma, vti)
    with pytest.raises(VizError, match="not a reachability map"):
        viz.page_map(puma, tmp_path / "missing.npz")
    with pytest.raises(VizError, match="ReachabilityMap or the path"):
        viz.page_map(puma, 3)  # type: ignore[arg-type]


def test_cli_view_with_a_map(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    saved = save_map(_map(30), tmp_path / "puma.npz")
    out = tmp_path / "puma.html"
    code, _, err = run(capsys, "view", "puma560", "--reach", str(saved), "-o", str(out))
    assert code == 0, err
    assert len(_embedded(out.read_text())["reach"]["voxels"]) == 30
    code, _, err = run(capsys, "view", "ur5", "--reach", str(saved), "-o", str(out))
    assert code == 2 and "not of 'UR5'" in err and "Traceback" not in err
    code, _, err = run(capsys, "view", "planar-3r", "--reach", "-o", str(out))
    assert code == 0, err
    data = _embedded(out.read_text())["reach"]
    assert data["positions"] and data["plane"] == 2 and data["voxels"]


# -------------------------------------------------------------- in a browser
@needs_browser
def test_the_page_draws_the_maps_voxels_and_slices(page: Any, tmp_path: Path) -> None:
    from matplotlib import colormaps

    robot = km.load("puma560")
    m = viz.coarse_map(robot)
    path = viz.write_page(robot, tmp_path / "puma.html", reach=m)
    page.goto(path.as_uri())
    page.wait_for_function("window.kinematica && window.kinematica.ready")
    assert page.is_visible("#reach")
    reachable = m.reached > 0
    assert page.evaluate("window.kinematica.mapDrawn()") == int(reachable.sum())
    for axis, layer in ((0, 5), (1, 12), (2, 17)):
        page.evaluate(f"window.kinematica.setSlice({axis}, {layer})")
        expected = int(np.take(reachable, layer, axis=axis).sum())
        assert page.evaluate("window.kinematica.mapDrawn()") == expected
        at = m.origin[axis] + (layer + 0.5) * m.resolution
        assert f"slice {'xyz'[axis]} = {float(np.round(at, 4))!r} m: {expected} voxels" in (
            page.inner_text("#reach-info")
        )
    page.uncheck("#reach-show")
    assert page.evaluate("window.kinematica.mapDrawn()") == 0
    # the colours: matplotlib's viridis at the ends and in the middle, to a unit of 255
    for t in (0.0, 0.5, 1.0):
        shown = page.evaluate(f"KM_REACH.colour({t})")
        rgb = np.array([int(v) for v in re.findall(r"\d+", shown)])
        ref = np.array(colormaps["viridis"](t)[:3]) * 255
        assert np.all(np.abs(rgb - ref) <= 1.0), (t, shown, ref)


@needs_browser
def test_a_page_without_a_map_hides_its_panel(page: Any, tmp_path: Path) -> None:
    path = viz.write_page(km.load("ur5"), tmp_path / "ur5.html")
    page.goto(path.as_uri())
    page.wait_for_function("window.kinematica && window.kinematica.ready")
    assert not page.is_visible("#reach")
    assert page.evaluate("window.kinematica.mapDrawn()") is None
