"""What a start imports: packages load their names on first use (kinematica._lazy).

The command line's start-up is mostly imports. A fresh process reports which
modules it holds after each step, and the modules a step does not need must be
absent: ``import kinematica`` imports neither numpy nor the core; a built-in
robot's FK imports no IK, URDF, robot-file writer or DH extraction; its first IK
imports the solver modules of the families tried before its own, not the
others' nor the redundancy layer, and a first one-pose IK (a 6R, a redundant
arm at its parameter) none of the general path's modules nor numpy.random;
``kinematica fk`` imports no IK. One process for the library's steps, one for
the command line's (each about half a second).
"""

from __future__ import annotations

import importlib
import json
import subprocess
import sys
import textwrap

import pytest

#: Packages built with kinematica._lazy.exports.
LAZY_PACKAGES = (
    "kinematica",
    "kinematica.dh",
    "kinematica.io",
    "kinematica.ik",
    "kinematica.motion",
    "kinematica.robot",
)

#: Modules no built-in robot's FK needs (the IK layer is checked as a whole).
NOT_FOR_FK = (
    "kinematica.dh.extract",
    "kinematica.io.robotfile",
    "kinematica.io.urdf",
    "kinematica.io.urdf_write",
    "kinematica.io.xacro",
    "kinematica.robot.dh_rules",
    "kinematica.robot.structure",
    "kinematica.robot.urdf",
    "difflib",
    "tempfile",
    "webbrowser",
    "xml.etree.ElementTree",
)

#: Modules the PUMA 560's first IK must not import: solver families not tried before its
#: own, and the redundancy layer (a 6R arm holds no joint).
NOT_FOR_PUMA_IK = (
    *(
        f"kinematica.ik.analytic.{m}"
        for m in ("arm_position", "elbow_arms", "general_6r", "planar_arms", "spherical_shoulder")
    ),
    "kinematica.ik.analytic.srs",
    "kinematica.ik.parameter",
    "kinematica.ik.redundancy",
)

#: Modules the first one-pose IK with every default (PUMA 560, its position target, iiwa 14
#: at its arm angle, the Panda with q7 held, a general 6R arm) must not import either: the
#: general path's (parsing, options, the numeric search), and numpy.random (10-20 ms).
NOT_FOR_ONE_POSE = (
    "kinematica.ik.at_values",
    "kinematica.ik.numeric",
    "kinematica.ik.options",
    "kinematica.ik.solve",
    "kinematica.ik.targets",
    "numpy.random",
)

_REPORT = """
import json, sys
seen = {}
def report(step):
    seen[step] = sorted(sys.modules)
"""


def _steps(body: str) -> dict[str, set[str]]:
    """Run ``body`` (which calls ``report(step)``) in a fresh process: modules per step."""
    code = textwrap.dedent(_REPORT) + textwrap.dedent(body) + "\nprint(json.dumps(seen))"
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return {step: set(mods) for step, mods in json.loads(done.stdout.splitlines()[-1]).items()}


def _ours(modules: set[str], prefix: str) -> set[str]:
    return {m for m in modules if m == prefix or m.startswith(prefix + ".")}


@pytest.mark.parametrize("package", LAZY_PACKAGES)
def test_every_public_name_resolves(package: str) -> None:
    module = importlib.import_module(package)
    missing = [name for name in module.__all__ if not hasattr(module, name)]
    assert missing == []
    assert set(module.__all__) <= set(dir(module))
    with pytest.raises(AttributeError, match="no attribute 'no_such_name'"):
        _ = module.no_such_name


def test_a_package_name_is_its_module_s_object() -> None:
    import kinematica as km
    from kinematica.io import builtin
    from kinematica.robot import load

    assert km.builtin_names is builtin.builtin_names
    assert km.load is load and callable(load)  # the function, not the module robot.load
    assert km.ik is importlib.import_module("kinematica.ik")


def test_a_submodule_not_named_in_the_exports_loads_as_an_attribute() -> None:
    # in a fresh process, where nothing imported kinematica.dh.lines before
    code = "import kinematica as km; print(km.dh.lines.AXIS_ANGLE_TOL, km.ik.analytic.srs.__name__)"
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.split() == ["1e-09", "kinematica.ik.analytic.srs"]


def test_the_library_imports_what_each_step_needs_only() -> None:
    seen = _steps(
        """
        import kinematica as km
        report("import")
        robot = km.load("puma560")
        T = robot.fk([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
        report("fk")
        assert robot.ik(T).method == "analytic:spherical-wrist"
        report("ik")
        assert robot.ik(T[:3, 3].copy()).method == "analytic:arm-position"
        iiwa = km.load("iiwa14")
        assert iiwa.ik(iiwa.fk([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3])).method == "analytic:srs"
        panda = km.load("panda")
        T7 = panda.fk([0.3, 0.2, 0.3, -1.2, 0.3, 1.5, 0.3])
        assert panda.ik(T7).method == "analytic:spherical-shoulder"
        report("redundant")
        rows = [(0.2, 0.25, 0.8), (-0.2, -0.35, -1.2), (-0.1, -0.35, 2.1), (0.4, 0.1, -0.7)]
        rows += [(-0.05, 0.4, 1.4), (0.3, -0.1, -2.6)]
        arm = km.Robot.from_dh([km.Revolute(d=d, a=a, alpha=al) for d, a, al in rows])
        assert arm.ik(arm.fk([0.3] * 6)).method == "analytic:general-6R"
        report("general")
        """
    )
    imported = seen["import"] - {"kinematica", "kinematica._lazy", "kinematica.errors"}
    assert _ours(imported, "kinematica") == set()
    assert "numpy" not in imported
    assert _ours(seen["fk"], "kinematica.ik") == set()
    assert set(NOT_FOR_FK) & seen["fk"] == set()
    assert "kinematica.ik.analytic.spherical_wrist" in seen["ik"]
    assert set(NOT_FOR_PUMA_IK) & seen["ik"] == set()
    assert set(NOT_FOR_ONE_POSE) & seen["general"] == set()


def test_the_command_line_imports_no_ik_for_fk() -> None:
    seen = _steps(
        """
        import contextlib, io
        from kinematica.cli.main import main
        with contextlib.redirect_stdout(io.StringIO()):
            assert main(["fk", "puma560", "--q", "0", "45", "-30", "0", "0", "0"]) == 0
            report("fk")
            assert main(["ik", "puma560", "--pose", "0.4", "0.1", "0.3", "0", "90", "0"]) == 0
            report("ik")
        """
    )
    assert _ours(seen["fk"], "kinematica.ik") == set()
    assert set(NOT_FOR_FK) & seen["fk"] == set()
    assert set(NOT_FOR_PUMA_IK) & seen["ik"] == set()
    others = ("analysis", "control", "convert", "derive", "design", "motion", "self_motion", "viz")
    assert {f"kinematica.cli.{m}" for m in others} & seen["ik"] == set()  # fk's module alone


def test_timing_a_path_imports_no_cartesian_paths_robots_or_ik() -> None:
    """``km.time_optimal``'s first call imports the timing's own modules only.

    It once imported the whole motion package (the Cartesian paths, the singularities,
    the IK layer: 147 modules, 140-200 ms; 51 and 45-80 ms now, benchmarks/_startup.py).
    """
    seen = _steps(
        """
        import numpy as np
        import kinematica as km
        report("import")
        km.time_optimal(np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]), vmax=1.0, amax=1.0)
        report("timed")
        """
    )
    new = seen["timed"] - seen["import"]
    assert "kinematica.motion.optimal" in new
    for heavy in ("kinematica.motion.cartesian", "kinematica.robot", "kinematica.ik", "scipy"):
        assert _ours(new, heavy) == set(), heavy


def test_the_motion_package_s_workspace_is_the_function_whoever_imported_its_module() -> None:
    code = (
        "import kinematica as km; import kinematica.motion.workspace as m; "
        "from kinematica.motion import workspace; "
        "print(callable(workspace), km.workspace is workspace, m is workspace)"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.split() == ["True", "True", "True"]
