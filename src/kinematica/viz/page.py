"""The interactive page: one self-contained HTML file that draws the arm in 3-D.

The page embeds the robot's DH table (both conventions, prismatic joints,
offsets, base, tool) and computes forward kinematics itself in plain
JavaScript (``web/kinematics.js``), so it works from a file with no network
and no Python. It has one slider per joint in the robot file's units, frames
on/off, the live T (element ``id="T"``, four rows of numbers) and the pose;
``page.html#q=10,20,30,0,45,0`` (degrees, metres for prismatic joints) starts
at that configuration. :func:`kinematica.viz.serve` adds a draggable target
whose IK runs in Python. With ``reach=``, the page also shows a reachability
map (:mod:`kinematica.viz.page_reach`), with a switch and a slice control.
"""

from __future__ import annotations

import base64
import hashlib
import html
import json
import math
import os
import re
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from kinematica import __version__
from kinematica.errors import DimensionError
from kinematica.io.atomic import unchanged, write_text_atomic
from kinematica.reach import ReachabilityMap
from kinematica.robot import Robot, classify, load
from kinematica.spatial import euler_from_matrix
from kinematica.viz._mpl import VizError
from kinematica.viz.geometry import ARROW, drawing_plane, robot_scale
from kinematica.viz.page_reach import page_map, reach_data

__all__ = ["EULER_SEQUENCES", "page_data", "page_html", "robot_units", "write_page"]

#: The Euler sequences the page offers: intrinsic (upper case) then extrinsic.
EULER_SEQUENCES = tuple(
    s
    for case in (str.upper, str.lower)
    for s in map(
        case,
        ("ZYZ", "ZXZ", "XYX", "XZX", "YXY", "YZY", "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"),
    )
)
#: Random configurations sampled to frame the view around everything the arm reaches.
VIEW_SAMPLES = 256
_UNITS = {"angle": ("deg", "rad"), "length": ("m", "mm")}


def robot_units(robot: Robot | str | os.PathLike[str]) -> dict[str, str]:
    """The units a robot's file is written in, for its sliders.

    Args:
        robot: A :class:`~kinematica.Robot`, or what :func:`kinematica.load`
            takes (a built-in name, a robot file or a URDF).

    Returns:
        ``{"angle": "deg" | "rad", "length": "m" | "mm"}``: the robot file's
        units; degrees and metres for a URDF or a robot made in Python.
    """
    spec = (robot if isinstance(robot, Robot) else load(robot)).source_spec
    units = {} if spec is None else spec.units
    return {"angle": units.get("angle", "deg"), "length": units.get("length", "m")}


def _check_units(units: dict[str, str] | None) -> dict[str, str]:
    out = {"angle": "deg", "length": "m"}
    for key, value in (units or {}).items():
        if key not in _UNITS or value not in _UNITS[key]:
            raise VizError(
                f"page units: {key!r} must be one of "
                f"{', '.join(f'{k}: {v}' for k, v in _UNITS.items())}; got {value!r}"
            )
        out[key] = value
    return out


def _nice_step(length: float) -> float:
    """1, 2 or 5 times a power of ten, about ``length``."""
    power = 10.0 ** math.floor(math.log10(length))
    return float(min((1.0, 2.0, 5.0, 10.0), key=lambda m: abs(m * power - length)) * power)


def page_data(
    robot: Robot,
    *,
    units: dict[str, str] | None = None,
    q: ArrayLike | None = None,
    euler: str = "ZYZ",
    serve: bool = False,
    token: str | None = None,
    reach: ReachabilityMap | str | os.PathLike[str] | None = None,
) -> dict[str, Any]:
    """What the page embeds: the DH table (rad, m), limits, base, tool and view.

    Args:
        robot: The robot.
        units: Slider units ``{"angle": "deg"|"rad", "length": "m"|"mm"}``.
        q: ``(n,)`` start configuration (rad, m); zeros moved into the limits if ``None``.
        euler: The Euler sequence shown first.
        serve: The page talks to :func:`kinematica.viz.serve` (the IK target).
        token: The server's secret for this run, sent back with every IK request.
        reach: A reachability map to show (its voxels coloured by the index,
            :mod:`kinematica.viz.page_reach`), or the path of one saved as ``.npz``;
            None: none.
    """
    euler_from_matrix(np.eye(3), euler)  # raises EulerSequenceError on a bad name
    qlim = robot.qlim
    if q is None:
        q0 = np.clip(np.zeros(robot.dof), qlim[:, 0], qlim[:, 1])
    else:
        q0 = robot.check_q(q)
        if q0.ndim != 1:
            raise DimensionError(
                f"the page starts at one configuration ({robot.dof},), got {q0.shape}"
            )
    table = robot.dh_table()
    joints = []
    for link, row, lim, limited in zip(robot.links, table, qlim, robot.has_limits, strict=True):
        joints.append(
            {
                "type": link.type,
                "theta": float(row[0]),
                "d": float(row[1]),
                "a": float(row[2]),
                "alpha": float(row[3]),
                "qlim": [float(lim[0]), float(lim[1])] if limited else None,
                "name": link.name,
            }
        )
    scale = robot_scale(robot)
    rng = np.random.default_rng(0)
    lo = np.where(np.isfinite(qlim[:, 0]), qlim[:, 0], -scale)
    hi = np.where(np.isfinite(qlim[:, 1]), qlim[:, 1], scale)
    samples = np.concatenate([q0[None], rng.uniform(lo, hi, size=(VIEW_SAMPLES, robot.dof))])
    pts = robot.fk(samples, all_frames=True)[..., :3, 3].reshape(-1, 3)
    pts = np.concatenate([pts, np.zeros((1, 3))])
    centre = (pts.min(axis=0) + pts.max(axis=0)) / 2.0
    radius = float(np.linalg.norm(pts - centre, axis=1).max()) + ARROW * scale
    plane = drawing_plane(robot)
    return {
        "name": robot.name,
        "convention": robot.convention,
        "joints": joints,
        "base": robot.base.tolist(),
        "tool": robot.tool.tolist(),
        "has_base": not np.array_equal(robot.base, np.eye(4)),
        "has_tool": not np.array_equal(robot.tool, np.eye(4)),
        "units": _check_units(units),
        "q0": q0.tolist(),
        "euler": euler,
        "serve": serve,
        "token": token,
        "scale": scale,
        "center": centre.tolist(),
        "radius": radius,
        "grid": _nice_step(radius / 4.0),
        "plane": list(plane) if plane is not None else None,
        "reach": None if reach is None else reach_data(page_map(robot, reach)),
    }


#: Characters a JSON text inside ``<script>`` must not carry as themselves: ``<`` (``</script>``,
#: ``<!--`` and ``<script`` change how the HTML parser reads the element), ``>`` and ``&``
#: for good measure, and the line separators JavaScript source once forbade in strings.
_SCRIPT_ESCAPES = {c: f"\\u{ord(c):04x}" for c in "<>&\u2028\u2029"}


def _script_json(data: Any) -> str:
    r"""``data`` as JSON that is safe as the content of a ``<script>`` element.

    Every character that could end the element or start a comment inside it is
    written as a ``\u`` escape: the same JSON value, with no markup in the text.
    """
    text = json.dumps(data, allow_nan=False)
    return re.sub("[<>&\u2028\u2029]", lambda m: _SCRIPT_ESCAPES[m.group(0)], text)


def _asset(name: str) -> str:
    return resources.files("kinematica.viz").joinpath("web", name).read_text(encoding="utf-8")


def _policy(script: str, css: str) -> str:
    """The page's Content-Security-Policy: its own script and style run, nothing else.

    Were any text ever to become markup, no script of its own would run (no
    inline handler, no other ``<script>``), and nothing would be fetched but the
    served page's own IK endpoint.
    """

    def digest(text: str) -> str:
        return base64.b64encode(hashlib.sha256(text.encode("utf-8")).digest()).decode("ascii")

    return (
        f"default-src 'none'; script-src 'sha256-{digest(script)}'; "
        f"style-src 'sha256-{digest(css)}'; img-src data:; connect-src 'self'; "
        "base-uri 'none'; form-action 'none'"
    )


def page_html(
    robot: Robot,
    *,
    units: dict[str, str] | None = None,
    q: ArrayLike | None = None,
    euler: str = "ZYZ",
    serve: bool = False,
    token: str | None = None,
    reach: ReachabilityMap | str | os.PathLike[str] | None = None,
) -> str:
    """The page as one HTML text (arguments as :func:`page_data`)."""
    data = page_data(robot, units=units, q=q, euler=euler, serve=serve, token=token, reach=reach)
    blob = _script_json(data)
    options = "".join(
        f'<option value="{s}"{" selected" if s == euler else ""}>{s}</option>'
        for s in EULER_SEQUENCES
    )
    script = "\n".join(_asset(name) for name in ("kinematics.js", "reach.js", "view.js"))
    css = _asset("page.css")
    replacements = {
        "__CSP__": _policy(script, css),
        "__CSS__": css,
        "__TITLE__": html.escape(robot.name),
        "__SUMMARY__": html.escape(f"{classify(robot).summary}, {robot.convention} DH"),
        "__VERSION__": html.escape(__version__),
        "__EULER_OPTIONS__": options,
        "__JS__": script,
        "__DATA__": blob,
    }
    # One pass, so no inserted text (a robot's name...) is itself substituted.
    return re.sub(
        r"__(CSP|CSS|TITLE|SUMMARY|VERSION|EULER_OPTIONS|JS|DATA)__",
        lambda m: replacements[m.group(0)],
        _asset("page.html"),
    )


def write_page(
    robot: Robot,
    path: str | os.PathLike[str],
    *,
    units: dict[str, str] | None = None,
    q: ArrayLike | None = None,
    euler: str = "ZYZ",
    reach: ReachabilityMap | str | os.PathLike[str] | None = None,
) -> Path:
    """Write the self-contained page to ``path`` (arguments as :func:`page_data`)."""
    out = Path(path)
    if not out.parent.is_dir():
        raise VizError(f"{out}: the folder {out.parent} does not exist")
    text = page_html(robot, units=units, q=q, euler=euler, reach=reach)
    try:
        write_text_atomic(out, text)
    except OSError as exc:
        raise VizError(
            f"{out}: cannot write the page ({exc.strerror or exc}); {unchanged(out)}"
        ) from exc
    return out
