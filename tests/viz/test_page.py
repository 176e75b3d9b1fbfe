"""The interactive page, in a real headless Chromium, and its IK server.

The page computes FK in JavaScript from the DH table it embeds; what it shows
in ``#T`` is compared with the reference DH product of ``tests/support/helpers.py``
(and ``robot.fk``) for random robots of both conventions, prismatic joints,
offsets, base and tool. The browser tests skip only where no Chromium is
installed (``apt-get install chromium``); the driver is playwright, used with
that browser (never ``playwright install``).
"""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import urllib.error
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from support import DATA
from support.helpers import JointSpec, RobotSpec, transform_from

import kinematica as km
from kinematica import viz
from kinematica.spatial import GIMBAL_LOCK_TOL
from kinematica.viz.server import MAX_REQUEST_BYTES, TOKEN_HEADER

#: What the page shows: 7 decimals, so at most 5e-8 from the exact value.
PAGE_ATOL = 1e-6


def _chromium() -> str | None:
    for candidate in (
        os.environ.get("KINEMATICA_CHROMIUM"),
        "/usr/bin/chromium",
        shutil.which("chromium"),
        shutil.which("chromium-browser"),
        shutil.which("google-chrome"),
    ):
        if candidate and Path(candidate).exists():
            return candidate
    return None


CHROMIUM = _chromium()
needs_browser = pytest.mark.skipif(
    CHROMIUM is None,
    reason="no Chromium installed (apt-get install chromium): the page's browser tests skip",
)


def expect(locator: Any) -> Any:
    from playwright.sync_api import expect as playwright_expect

    return playwright_expect(locator)


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    from playwright.sync_api import sync_playwright  # the test extra installs it

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
    pg.errors = errors
    yield pg
    assert errors == [], errors
    pg.close()


def shown_T(pg: Any) -> np.ndarray:
    rows = pg.inner_text("#T").strip().splitlines()
    assert len(rows) == 4
    return np.array([[float(v) for v in row.split()] for row in rows])


def hash_of(robot: km.Robot, q: np.ndarray) -> str:
    shown = np.where(robot.is_prismatic, q, np.degrees(q))
    return "#q=" + ",".join(repr(float(v)) for v in shown)


def random_spec(rng: np.random.Generator) -> RobotSpec:
    """A random robot as plain data: mixed joints, special and random angles, offsets."""
    special = [0.0, math.pi / 2, -math.pi / 2, math.pi]
    joints = []
    for _ in range(int(rng.integers(1, 8))):
        kind = "P" if rng.random() < 0.3 else "R"

        def angle() -> float:
            return float(rng.choice(special)) if rng.random() < 0.4 else float(rng.uniform(-3, 3))

        def length() -> float:
            return 0.0 if rng.random() < 0.3 else float(rng.uniform(-0.6, 0.6))

        lim = None
        if rng.random() < 0.4:
            lo = float(rng.uniform(-2, 0))
            lim = (lo, lo + float(rng.uniform(0.2, 2)))
        joints.append(
            JointSpec(
                kind=kind,
                const=angle() if kind == "P" else length(),
                a=length(),
                alpha=angle(),
                offset=angle() if kind == "R" else length(),
                qlim=lim,
            )
        )

    def frame() -> np.ndarray | None:
        if rng.random() < 0.3:
            return None
        return transform_from(rng.normal(size=4), rng.uniform(-0.5, 0.5, 3))

    return RobotSpec(
        joints=tuple(joints),
        convention=str(rng.choice(["standard", "modified"])),
        base=frame(),
        tool=frame(),
    )


# ----------------------------------------------------------- without a browser
def test_page_embeds_the_table_and_escapes_names() -> None:
    robot = km.Robot.from_dh(
        [km.Revolute(a=0.3), km.Prismatic(qlim=(0, 0.2))],
        name="</script><b>x",
        convention="standard",
    )
    text = viz.page_html(robot)
    assert "</script><b>" not in text
    start = text.index('id="robot-data">') + len('id="robot-data">')
    data = json.loads(text[start : text.index("</script>", start)])
    assert data["name"] == "</script><b>x"
    assert data["joints"][1] == {
        "type": "P",
        "theta": 0.0,
        "d": 0.0,
        "a": 0.0,
        "alpha": 0.0,
        "qlim": [0.0, 0.2],
        "name": None,
    }
    assert data["plane"] is None and not data["serve"]  # the slide moves along the z axis
    assert "http://" not in text and "https://" not in text  # nothing fetched at view time


def test_page_bad_arguments(tmp_path: Path) -> None:
    robot = km.load("puma560")
    with pytest.raises(viz.VizError, match="'angle' must be one of"):
        viz.page_html(robot, units={"angle": "grad"})
    with pytest.raises(km.EulerSequenceError):
        viz.page_html(robot, euler="ZZY")
    with pytest.raises(km.DimensionError, match="6 joint values"):
        viz.page_html(robot, q=[0, 1])
    with pytest.raises(viz.VizError, match="does not exist"):
        viz.write_page(robot, tmp_path / "no" / "a.html")


def test_units_of_files_and_builtins(tmp_path: Path) -> None:
    assert viz.robot_units("puma560") == {"angle": "deg", "length": "m"}
    path = tmp_path / "arm.toml"
    path.write_text(MM_ROBOT)
    assert viz.robot_units(path) == {"angle": "rad", "length": "mm"}


MM_ROBOT = """
name = "mm arm"
convention = "standard"
units = { angle = "rad", length = "mm" }
joints = [
  { theta = "q1", d = 300, a = 0, alpha = "pi/2" },
  { theta = 0, d = "q2", a = 0, alpha = 0, limits = [100, 500] },
]
"""


def _post(server: viz.PageServer, body: bytes) -> tuple[int, dict[str, Any]]:
    req = urllib.request.Request(server.url + "api/ik", data=body, method="POST")
    req.add_header("Content-Type", "application/json")
    req.add_header(TOKEN_HEADER, server.token)
    try:
        with urllib.request.urlopen(req, timeout=10) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as exc:
        return exc.code, json.loads(exc.read())


def test_server_answers_ik_and_rejects_bad_requests() -> None:
    puma = km.load("puma560")
    T = puma.fk([0.2, -0.5, 0.3, 0.4, 0.8, -0.1])
    with viz.serve(puma) as server:
        assert server.url.startswith("http://127.0.0.1:")
        with urllib.request.urlopen(server.url, timeout=10) as r:
            assert b'"serve": true' in r.read()
        status, res = _post(server, json.dumps({"T": T.tolist()}).encode())
        assert status == 200 and res["status"] == "ok"
        expected = puma.ik(T)
        np.testing.assert_allclose(res["solutions"], expected.solutions)
        assert res["branches"] == list(expected.branches)
        for q in res["solutions"]:
            np.testing.assert_allclose(puma.fk(q), T, atol=1e-9)
        far = km.transl(5.0, 0.0, 0.0)
        status, res = _post(server, json.dumps({"T": far.tolist()}).encode())
        assert (status, res["status"], res["solutions"]) == (200, "unreachable", [])
        status, res = _post(server, json.dumps({"position": [5.0, 0.0, 0.0]}).encode())
        assert (status, res["status"], res["solutions"]) == (200, "unreachable", [])
        assert _post(server, b"{nope")[1]["error"].startswith("the request is not JSON")
        assert _post(server, b'{"T": [1, 2]}') == (
            400,
            {
                "error": '"T" must be a 4x4 pose (4 rows of 4 finite numbers, m), '
                "got a list of 2 (numbers)"
            },
        )
        assert _post(server, b'{"x": 1}')[0] == 400
        big = b'{"T": "' + b"x" * MAX_REQUEST_BYTES + b'"}'
        assert _post(server, big) == (413, {"error": f"the body is over {MAX_REQUEST_BYTES} bytes"})


#: Text a robot file may hold that would be markup if a page took it as HTML: each one,
#: run, sets ``window.pwned`` (and the title), which the browser tests check did not happen.
PAYLOADS = (
    "<img src=x onerror=\"window.pwned=1;document.title='pwned'\">",
    "</script><script>window.pwned=2;document.title='pwned'</script>",
    "<!--<script>window.pwned=3</script>",
    "<svg><script>window.pwned=4</script></svg>\u2028\u2029&amp;",
)
EVIL_NAME = "</script><script>window.pwned=5;document.title='pwned'</script><b>x"


def evil_yaml(path: Path, names: tuple[str, ...] = PAYLOADS) -> Path:
    """A planar robot file named :data:`EVIL_NAME`, one joint for each of ``names``."""
    joints = "\n".join(
        f"  - {{theta: q{i + 1}, d: 0, a: 0.2, alpha: 0, name: {json.dumps(name)}}}"
        for i, name in enumerate(names)
    )
    text = f"name: {json.dumps(EVIL_NAME)}\nconvention: standard\njoints:\n{joints}\n"
    path.write_text(text, encoding="utf-8")
    return path


def test_text_from_the_file_is_never_markup_in_the_page(tmp_path: Path) -> None:
    robot = km.load(evil_yaml(tmp_path / "evil.yaml"))
    assert [link.name for link in robot.links] == list(PAYLOADS)
    text = viz.page_html(robot, serve=True, token="t0k")
    start = text.index('id="robot-data">') + len('id="robot-data">')
    blob = text[start : text.index("</script>", start)]
    assert not {"<", ">", "&", "\u2028", "\u2029"} & set(blob)  # escaped, all of them
    data = json.loads(blob)
    assert (data["name"], data["token"]) == (EVIL_NAME, "t0k")
    assert [j["name"] for j in data["joints"]] == list(PAYLOADS)
    assert text.count("<script") == 2  # the data and the page's own script, nothing more


def test_units_of_urdf_and_robots_made_in_python() -> None:
    urdf = DATA / "urdf" / "abb_irb140.urdf"
    assert viz.robot_units(urdf) == {"angle": "deg", "length": "m"}
    assert viz.robot_units(km.load(urdf)) == {"angle": "deg", "length": "m"}
    assert viz.robot_units(km.Robot.from_dh([km.Revolute(a=1.0)], convention="standard")) == {
        "angle": "deg",
        "length": "m",
    }


# --------------------------------------------------------------- in Chromium
@needs_browser
def test_random_robots_random_q(page: Any, tmp_path: Path) -> None:
    rng = np.random.default_rng(20240611)
    for k in range(12):
        spec = random_spec(rng)
        robot = spec.build()
        url = viz.write_page(robot, tmp_path / f"r{k}.html").as_uri()
        for j in range(3):
            q = rng.uniform(-3, 3, spec.dof)  # inside and outside any limits
            if j == 0:
                page.goto(url + hash_of(robot, q))  # a fresh load
            else:
                page.evaluate(f"window.location.hash = {json.dumps(hash_of(robot, q))}")
                page.locator("#q1-value").wait_for(state="attached")
            np.testing.assert_allclose(shown_T(page), spec.ref_fk(q), atol=PAGE_ATOL, rtol=0)
            np.testing.assert_allclose(shown_T(page), robot.fk(q), atol=PAGE_ATOL, rtol=0)


@needs_browser
def test_seed_configuration_and_slider(page: Any, tmp_path: Path) -> None:
    robot = km.load("arm6-dh")
    url = viz.write_page(robot, tmp_path / "arm.html").as_uri()
    page.goto(url + "#q=10,20,30,0,45,0")
    q = np.radians([10, 20, 30, 0, 45, 0])
    np.testing.assert_allclose(shown_T(page), robot.fk(q), atol=PAGE_ATOL, rtol=0)
    before = shown_T(page)
    page.locator("#q2").fill("-37.5")
    q[1] = np.radians(-37.5)
    np.testing.assert_allclose(shown_T(page), robot.fk(q), atol=PAGE_ATOL, rtol=0)
    assert np.abs(shown_T(page) - before).max() > 0.01
    assert "#q=10,-37.5,30,0,45,0" in page.url  # the link reproduces the view
    page.locator("#q6-value").fill("90")
    page.locator("#q6-value").dispatch_event("change")
    q[5] = np.radians(90)
    np.testing.assert_allclose(shown_T(page), robot.fk(q), atol=PAGE_ATOL, rtol=0)
    shot = tmp_path / "arm6.png"
    page.screenshot(path=str(shot))
    from PIL import Image

    with Image.open(shot) as im:
        assert im.size == (1100, 720)
        canvas = np.asarray(im.convert("L"), dtype=float)[100:700, 20:780]
    assert canvas.std() > 5  # the arm is drawn


@needs_browser
def test_pose_matches_euler_from_matrix(page: Any, tmp_path: Path) -> None:
    robot = km.load("puma560")
    q = np.radians([20, -30, 40, 50, 60, 70])
    page.goto(viz.write_page(robot, tmp_path / "p.html").as_uri() + hash_of(robot, q))
    T = robot.fk(q)
    for seq in ("ZYZ", "XYZ", "zyx", "xzx"):
        page.select_option("#euler", seq)
        lines = page.inner_text("#pose").splitlines()
        xyz = [float(v) for v in lines[0].split(":")[1].split(",")]
        angles = [float(v) for v in lines[1].split(":")[1].split(",")]
        np.testing.assert_allclose(xyz, T[:3, 3], atol=1e-6)
        np.testing.assert_allclose(
            angles, km.euler_from_matrix(T[:3, :3], seq, degrees=True), atol=1e-4
        )
    # gimbal lock: the third angle is 0, as in kinematica (and scipy)
    page.evaluate("window.kinematica.setQ([0, 0, 0, 0, 0, 0])")
    page.select_option("#euler", "ZYZ")
    angles = [float(v) for v in page.inner_text("#pose").splitlines()[1].split(":")[1].split(",")]
    np.testing.assert_allclose(
        angles, km.euler_from_matrix(robot.fk(np.zeros(6))[:3, :3], "ZYZ", degrees=True), atol=1e-4
    )


@needs_browser
@pytest.mark.parametrize("middle", [GIMBAL_LOCK_TOL / 100, GIMBAL_LOCK_TOL * 100])
@pytest.mark.parametrize("seq", ["ZYZ", "xyx", "XYZ", "zyx"])
def test_euler_near_gimbal_lock_as_kinematica(
    page: Any, tmp_path: Path, middle: float, seq: str
) -> None:
    # the second angle just inside / outside the lock band, on both sides of GIMBAL_LOCK_TOL
    lock = 0.0 if seq[0].lower() == seq[2].lower() else math.pi / 2
    angles = np.array([0.7, lock - middle, -0.4])
    R = km.matrix_from_euler(angles, seq)
    T = np.eye(4)
    T[:3, :3] = R
    page.goto(viz.write_page(km.load("planar-3r"), tmp_path / "e.html").as_uri())
    got = page.evaluate(f"window.kinematica.euler({json.dumps(T.ravel().tolist())}, '{seq}')")
    np.testing.assert_allclose(got, km.euler_from_matrix(R, seq), atol=1e-9)
    locked = middle < GIMBAL_LOCK_TOL
    assert (got[2] == 0.0) == locked


@needs_browser
def test_file_units_and_limits(page: Any, tmp_path: Path) -> None:
    path = tmp_path / "mm.toml"
    path.write_text(MM_ROBOT)
    robot = km.load(path)
    page_file = viz.write_page(robot, tmp_path / "mm.html", units=viz.robot_units(path))
    page.goto(page_file.as_uri() + "#q=30,0.25")  # degrees and metres in the link
    np.testing.assert_allclose(shown_T(page), robot.fk([math.radians(30), 0.25]), atol=PAGE_ATOL)
    assert page.inner_text("label[for=q1]") == "q1 (rad)"
    assert page.inner_text("label[for=q2]") == "q2 (mm)"
    assert page.get_attribute("#q2", "min") == "100" and page.get_attribute("#q2", "max") == "500"
    page.locator("#q2").fill("400")  # mm on the slider
    np.testing.assert_allclose(shown_T(page), robot.fk([math.radians(30), 0.4]), atol=PAGE_ATOL)
    page.goto(page_file.as_uri() + "#q=0,0.9")
    assert "outside its limits" in page.inner_text("#limits")
    np.testing.assert_allclose(shown_T(page), robot.fk([0, 0.9]), atol=PAGE_ATOL)


@needs_browser
def test_bad_hash_is_reported_on_the_page(page: Any, tmp_path: Path) -> None:
    robot = km.load("planar-3r")
    page.goto(viz.write_page(robot, tmp_path / "p.html").as_uri() + "#q=1,2")
    assert "#q= needs 3 numbers" in page.inner_text("#message")
    np.testing.assert_allclose(shown_T(page), robot.fk(np.zeros(3)), atol=PAGE_ATOL)
    page.uncheck("#frames")
    page.check("#frames")


@needs_browser
def test_served_page_drags_the_target_and_steps_through_solutions(
    page: Any, tmp_path: Path
) -> None:
    robot = km.load("puma560").with_limits([None] * 6)  # all 8 solutions
    q0 = np.array([0.2, -0.5, 0.3, 0.4, 0.8, -0.1])
    with viz.serve(robot, q=q0) as server:
        page.goto(server.url)
        np.testing.assert_allclose(shown_T(page), robot.fk(q0), atol=PAGE_ATOL)
        x, y = page.evaluate("window.kinematica.targetScreen()")
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(x + 15, y - 10, steps=4)
        page.mouse.up()
        # locators, not wait_for_function: the page's CSP forbids the eval that one needs
        expect(page.locator("#solution")).to_have_text(re.compile("^solution 1 of"))
        target = np.array(page.evaluate("window.kinematica.target()")).reshape(4, 4)
        assert np.linalg.norm(target[:3, 3] - robot.fk(q0)[:3, 3]) > 1e-3  # it moved
        np.testing.assert_allclose(target[:3, :3], robot.fk(q0)[:3, :3], atol=1e-12)
        count = len(robot.ik(target).solutions)
        assert count == 8
        assert page.inner_text("#solution").startswith(f"solution 1 of {count}")
        seen = set()
        for _ in range(count):
            np.testing.assert_allclose(shown_T(page), target, atol=PAGE_ATOL)
            seen.add(tuple(np.round(page.evaluate("window.kinematica.q()"), 9)))
            page.click("#next")
        assert len(seen) == count
        page.screenshot(path=str(tmp_path / "served.png"))
        page.evaluate("window.kinematica.setTarget([[1,0,0,5],[0,1,0,0],[0,0,1,0],[0,0,0,1]])")
        expect(page.locator("#ik-status")).to_have_text(re.compile("^unreachable"))
        assert page.inner_text("#solution") == "no solution"


@needs_browser
@pytest.mark.parametrize("names", [PAYLOADS, PAYLOADS[:1]], ids=["all", "img"])
def test_names_from_the_file_are_shown_as_text(
    page: Any, tmp_path: Path, names: tuple[str, ...]
) -> None:
    robot = km.load(evil_yaml(tmp_path / "evil.yaml", names))
    page.goto(viz.write_page(robot, tmp_path / "evil.html").as_uri())
    _shown_literally(page, robot)


@needs_browser
def test_names_from_the_file_are_shown_as_text_when_served(page: Any, tmp_path: Path) -> None:
    robot = km.load(evil_yaml(tmp_path / "evil.yaml"))
    with viz.serve(robot) as server:
        page.goto(server.url)
        _shown_literally(page, robot)
        T = robot.fk(np.full(robot.dof, 0.3))
        page.evaluate(f"window.kinematica.setTarget({json.dumps(T.tolist())})")
        expect(page.locator("#ik-status")).to_have_text(re.compile("^ok"))


def _shown_literally(page: Any, robot: km.Robot) -> None:
    page.wait_for_timeout(300)  # time for an image's onerror to have run, were there one
    assert page.evaluate("window.pwned") is None
    assert page.title() == f"{EVIL_NAME} — kinematica"
    assert page.inner_text("h1") == EVIL_NAME
    for i, link in enumerate(robot.links):
        label = page.locator(f"label[for=q{i + 1}]")
        assert label.text_content() == f"q{i + 1} {link.name} (deg)"
    assert page.locator("#joints img, #joints script, #joints svg").count() == 0
    np.testing.assert_allclose(shown_T(page), robot.fk(np.zeros(robot.dof)), atol=PAGE_ATOL)


@needs_browser
def test_frame_labels_do_not_print_over_each_other(page: Any, tmp_path: Path) -> None:
    # the notes' arm: "S4, S5" at the wrist centre, "S6" l4 = 0.1 m further (issue 22):
    # every label the canvas writes keeps clear of the others
    page.add_init_script(
        """
        window.labels = [];
        const write = CanvasRenderingContext2D.prototype.fillText;
        CanvasRenderingContext2D.prototype.fillText = function (text, x, y) {
          window.labels.push([text, x, y, this.measureText(text).width]);
          return write.apply(this, arguments);
        };
        """
    )
    robot = km.load("arm6-dh")
    q = np.radians([30, 40, -30, 10, 60, -20])
    page.goto(viz.write_page(robot, tmp_path / "a.html").as_uri() + hash_of(robot, q))
    page.evaluate("window.labels = []")
    page.uncheck("#labels")
    page.check("#labels")  # one drawing with the labels
    labels = page.evaluate("window.labels")
    names = [label[0] for label in labels]
    assert "S4, S5" in names and "S6" in names
    line = page.evaluate("14 * (window.devicePixelRatio || 1)")
    for i, (a, xa, ya, wa) in enumerate(labels):
        for b, xb, yb, wb in labels[i + 1 :]:
            apart = xa + wa <= xb or xb + wb <= xa or abs(ya - yb) >= line
            assert apart, f"{a!r} at ({xa:.0f}, {ya:.0f}) and {b!r} at ({xb:.0f}, {yb:.0f})"
