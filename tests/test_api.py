"""The public API: every exported name exists; layers import only downwards."""

from __future__ import annotations

import ast
from pathlib import Path

import kinematica as km

SRC = Path(km.__file__).parent

#: DESIGN.md's layers, bottom (0) to top; a module may import its own layer or lower.
LAYER = {
    "errors": 0,
    "io": 0,
    "spatial": 1,
    "dh": 2,
    "kernels": 3,
    "ik": 4,
    "robot": 5,
    "motion": 6,
    "design": 6,
    "viz": 7,
    "symbolic": 7,
    "cli": 8,
}


def test_every_name_in_all_exists() -> None:
    missing = [name for name in km.__all__ if not hasattr(km, name)]
    assert missing == []
    assert len(set(km.__all__)) == len(km.__all__)


def test_design_names_are_public() -> None:
    for name in (
        "load",
        "Robot",
        "Revolute",
        "Prismatic",
        "to_pose",
        "from_pose",
        "KinematicaError",
    ):
        assert name in km.__all__


def _imports(path: Path) -> list[tuple[str, bool]]:
    """Imported kinematica subpackages of a module, and whether at top level."""
    tree = ast.parse(path.read_text())
    found = []
    top = set(map(id, tree.body))
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.ImportFrom)
            and node.module
            and node.module.startswith("kinematica.")
        ):
            found.append((node.module.split(".")[1], id(node) in top))
    return found


def test_layers_import_only_downwards() -> None:
    bad = []
    for path in SRC.rglob("*.py"):
        rel = path.relative_to(SRC)
        if len(rel.parts) < 2:
            continue
        own = LAYER[rel.parts[0]]
        for mod, at_top in _imports(path):
            # Robot.ik's deferred import of the ik layer is the one documented exception.
            if LAYER.get(mod, 0) > own and at_top:
                bad.append(f"{rel} imports kinematica.{mod}")
    assert bad == []
