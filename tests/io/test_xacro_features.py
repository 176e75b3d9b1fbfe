"""kinematica's xacro expander against the ``xacro`` package, feature by feature.

Each file of ``tests/data/xacro/features`` exercises one part of xacro (properties,
macros, includes, conditions, arguments, elements, YAML, expressions); both expanders
must make the same URDF tree of it, element for element (``support.xacro.canonical``).
Each file of ``features/bad`` is malformed: both must refuse it. The xacro package runs
once, in a child process, on all of them (``support/real_xacro.py``).
"""

from __future__ import annotations

import json
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from support import ROOT
from support.xacro import XACRO_DIR, canonical

import kinematica as km
import kinematica.io.xacro as xacro_module
from kinematica.io.xacro import xacro_to_urdf

FEATURES = XACRO_DIR / "features"
PACKAGES = {"feature_pkg_a": FEATURES / "pkg_a"}
GOOD = sorted(FEATURES.glob("*.xacro"))
BAD = sorted((FEATURES / "bad").glob("*.xacro"))

needs_xacro = pytest.mark.skipif(
    xacro_module._xacro_dir() is None, reason="the xacro package is not installed"
)


@pytest.fixture(scope="module")
def real() -> dict[str, str]:
    """What the xacro package makes of every feature file (text, or "error: ...")."""
    done = subprocess.run(
        [
            sys.executable,
            "-I",  # not the script's folder on the path: its xacro.py is not the package
            str(ROOT / "tests" / "support" / "real_xacro.py"),
            json.dumps({k: str(v) for k, v in PACKAGES.items()}),
            *map(str, GOOD + BAD),
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    answers: dict[str, str] = json.loads(done.stdout)
    return answers


def ours(path: Path) -> ET.Element:
    return ET.fromstring(xacro_to_urdf(path, max_bytes=2**20, packages=PACKAGES))


def test_every_feature_has_a_file() -> None:
    names = {p.stem for p in GOOD}
    assert names >= {
        "properties",
        "macros",
        "includes",
        "conditions",
        "elements",
        "yaml",
        "expressions",
    }
    assert len(BAD) >= 9


@needs_xacro
@pytest.mark.parametrize("path", GOOD, ids=lambda p: p.stem)
def test_the_same_tree_as_the_xacro_package(real: dict[str, str], path: Path) -> None:
    expected = real[str(path)]
    assert not expected.startswith("error:"), expected
    assert canonical(ours(path)) == canonical(ET.fromstring(expected))


@needs_xacro
@pytest.mark.parametrize("path", BAD, ids=lambda p: p.stem)
def test_both_refuse_a_malformed_file(real: dict[str, str], path: Path) -> None:
    assert real[str(path)].startswith("error:")
    with pytest.raises(km.RobotFileError) as info:
        ours(path)
    message = str(info.value)
    assert "\n" not in message and str(path) in message
    assert "line " in message


def test_what_the_features_compute() -> None:
    # independent of the xacro package: a few values worked out by hand
    info = ours(FEATURES / "properties.xacro").find("info")
    assert info is not None
    assert info.get("b") == "3.0"  # c = a + 1 = 1.5, used before it was defined, b = 2c
    assert info.get("word") == "hello world" and info.get("under") == "1_000"
    assert info.get("parent") == "30" and info.get("global") == "42"
    assert info.get("dollars") == "${not evaluated}"
    macros = ours(FEATURES / "macros.xacro")
    limits = [j.find("limit").get("upper") for j in macros.iter("joint")]  # type: ignore[union-attr]
    assert limits == ["0.5", "1.0", "1.5", "2.0"]  # len * i * scale, scale 2 by default
    assert [link.get("name") for link in macros.iter("link")][-4:] == [
        "extra_a",
        "extra_b",
        "called_a",
        "called_b",
    ]
    yaml_info = ours(FEATURES / "yaml.xacro").find("info")
    assert yaml_info is not None
    assert float(yaml_info.get("shoulder", "")) == pytest.approx(1.5707963267948966, abs=0)
    assert yaml_info.get("reach") == "0.25" and yaml_info.get("axis") == "0 1 0"


def test_what_only_kinematica_offers(tmp_path: Path) -> None:
    # $(dirname) (xacro 2.1 cannot), abs() and sum() (xacro has them under python. only)
    path = tmp_path / "extra.xacro"
    path.write_text(
        '<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<info dir="$(dirname)" abs="${abs(-2)}" sum="${sum([1, 2, 0.5])}"/>'
        '<link name="l"/></robot>'
    )
    info = ET.fromstring(xacro_to_urdf(path, max_bytes=2**20)).find("info")
    assert info is not None
    assert info.get("dir") == str(tmp_path.resolve())
    assert info.get("abs") == "2" and info.get("sum") == "3.5"


@pytest.mark.parametrize("trust", [False, pytest.param(True, marks=needs_xacro, id="trusted")])
def test_arguments_given_by_the_caller(trust: bool) -> None:
    given = {"gripper": "false", "side": "right", "count": "5"}
    text = xacro_to_urdf(
        FEATURES / "conditions.xacro", max_bytes=2**20, packages=PACKAGES, args=given, trust=trust
    )
    root = ET.fromstring(text)
    links = [link.get("name") for link in root.iter("link")]
    assert "no_gripper" in links and "gripper_right" not in links and "left_side" not in links
    info = root.find("info")
    assert info is not None
    assert (info.get("count"), info.get("twice"), info.get("cond")) == ("5", "10", "no")
    assert info.get("xarg") == "right"
