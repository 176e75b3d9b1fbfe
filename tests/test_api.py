"""The public API: every exported name exists.

That layers import only downwards, with no cycle, is checked by import-linter
(``lint-imports`` in ``make test``; contracts in pyproject.toml).
"""

from __future__ import annotations

import kinematica as km


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
