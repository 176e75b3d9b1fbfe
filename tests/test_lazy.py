"""Packages' public names (kinematica._lazy): each resolves, and no optional extra loads early.

What each start-up step costs is measured, against its budget, by
``benchmarks/_startup.py``; here, in a fresh process: ``import kinematica``, and
every public name of its packages resolved, import none of the optional extras
(scipy, matplotlib, sympy, Dask, ruckig): each is imported by the function that
needs it, when it runs.
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


#: The optional extras' top-level modules (pyproject.toml's extras).
OPTIONAL = ("scipy", "matplotlib", "sympy", "dask", "distributed", "ruckig")


def test_no_optional_extra_is_imported_before_it_is_needed() -> None:
    code = textwrap.dedent(
        f"""
        import importlib, json, sys
        import kinematica
        seen = {{"import": sorted(sys.modules)}}
        for package in {LAZY_PACKAGES!r}:
            module = importlib.import_module(package)
            for name in module.__all__:
                getattr(module, name)
        seen["names"] = sorted(sys.modules)
        print(json.dumps(seen))
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    seen = json.loads(done.stdout.splitlines()[-1])
    assert "kinematica.robot.robot" in seen["import"]  # what load and fk need: imported
    for step, modules in seen.items():
        loaded = {m.split(".")[0] for m in modules} & set(OPTIONAL)
        assert loaded == set(), f"{step}: {sorted(loaded)}"


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
