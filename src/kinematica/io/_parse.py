"""Checking loaded robot-file data and turning it into a :class:`RobotSpec`.

Every problem raises :class:`RobotFileError` naming the file, the joint number
(1-based), the key, what was expected and what was found.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from pathlib import PurePath
from typing import Any

import numpy as np

from kinematica.io import plausible
from kinematica.io._values import (
    CHAIN_KEYS,
    DH_KEYS,
    FRAME_KEYS,
    JOINT_KEYS,
    JOINT_TYPES,
    MATRIX_TOL,
    MAX_JOINTS,
    MAX_PARAMETERS,
    TOP_KEYS,
    Quantity,
    ValueReader,
    angle_to_si,
    describe,
    length_to_si,
)
from kinematica.io.expr import Affine
from kinematica.io.spec import (
    CONVENTION_ALIASES,
    ChainSpec,
    Convention,
    FrameSpec,
    JointKind,
    JointSpec,
    RobotSpec,
    convention_names,
    missing_convention,
)

__all__ = ["MAX_JOINTS", "MAX_PARAMETERS", "angle_to_si", "length_to_si", "parse_robot_dict"]


class _Reader(ValueReader):
    """:class:`ValueReader` with the file's sections: joints, frames, the chain."""

    def joint(self, raw: object, i: int) -> JointSpec:
        where: dict[str, Any] = {"joint": i}
        data = self.mapping(raw, "a mapping with theta, d, a, alpha", **where)
        self.check_keys(data, JOINT_KEYS, **where)
        missing = [k for k in DH_KEYS if k not in data]
        if missing:
            raise self.error(
                f"missing {', '.join(missing)}: every joint needs theta, d, a and alpha", **where
            )
        quantity: dict[str, Quantity] = {"theta": "angle", "d": "length", "a": "length"}
        quantity["alpha"] = "angle"
        forms: dict[str, Affine] = {}
        texts: dict[str, str] = {}
        for key in DH_KEYS:
            forms[key], texts[key] = self.value(
                data[key], quantity[key], key, constant=False, **where
            )

        var = f"q{i}"
        for key in DH_KEYS:
            for other in forms[key].coeffs:
                if other != var:
                    raise self.error(
                        f"found {other}, but joint {i}'s variable is {var} "
                        "(joint i uses q<i> and no other)",
                        key=key,
                        **where,
                    )
        present = [k for k in DH_KEYS if forms[k].coeffs]
        if not present:
            raise self.error(
                f"the joint variable {var} appears nowhere: write it in theta "
                "(revolute joint) or in d (prismatic joint)",
                **where,
            )
        if len(present) > 1:
            raise self.error(
                f"{var} appears in {' and '.join(present)}; it must appear exactly once, "
                "in theta (revolute) or in d (prismatic)",
                key=present[1],
                **where,
            )
        key = present[0]
        if key not in ("theta", "d"):
            raise self.error(
                f"{var} appears in {key}; the joint variable goes in theta (revolute) "
                "or in d (prismatic), never in a or alpha",
                key=key,
                **where,
            )
        coeff = forms[key].coeffs[var]
        if coeff != 1.0:
            raise self.error(
                f"{var} must appear with coefficient exactly 1, found {coeff:g} "
                f"in {texts[key]!r} (write {var} + offset)",
                key=key,
                **where,
            )
        kind: JointKind = "R" if key == "theta" else "P"
        self.joint_type(data.get("type"), kind, key, **where)

        qlim = None
        if "limits" in data:
            qty: Quantity = "angle" if kind == "R" else "length"
            lo, hi = self.numbers(data["limits"], (qty, qty), "limits", **where)
            if not lo < hi:
                shown = ", ".join(str(v) for v in data["limits"])
                raise self.error(
                    f"expected [lower, upper] with lower < upper, found [{shown}] "
                    f"(lower {'=' if lo == hi else '>'} upper; swap them?)",
                    key="limits",
                    **where,
                )
            qlim = (lo, hi)
        self.check_joint(forms, kind, qlim, data.get("limits"), i)
        angle, length = self.to_si("angle"), self.to_si("length")
        return JointSpec(
            kind=kind,
            theta=angle(forms["theta"].const),
            d=length(forms["d"].const),
            a=length(forms["a"].const),
            alpha=angle(forms["alpha"].const),
            qlim=qlim,
            name=self.text(data.get("name"), "name", **where),
            expr=texts,
        )

    def check_joint(
        self,
        forms: Mapping[str, Affine],
        kind: JointKind,
        qlim: tuple[float, float] | None,
        raw_limits: object,
        i: int,
    ) -> None:
        """Warn about values implausible for the file's units (degrees as radians...)."""
        for key in ("theta", "alpha"):
            self.check_angle(forms[key].const, key, i)
        to_m = self.to_si("length")
        for key in () if self.described else ("d", "a"):
            message = plausible.check_length(to_m(forms[key].const), self.length_unit)
            self.warn(message, joint=i, key=key)
        if qlim is None or kind != "R" or not isinstance(raw_limits, list | tuple):
            return
        for lim in qlim:
            if self.angle_unit == "deg":
                message = plausible.check_degrees(math.degrees(lim))
            else:
                message = plausible.check_limit(lim)
            if message is not None:
                self.warn(message, joint=i, key="limits")
                return

    def joint_type(self, raw: object, kind: JointKind, key: str, **where: Any) -> None:
        if raw is None:
            return
        stated = JOINT_TYPES.get(raw.strip().lower()) if isinstance(raw, str) else None
        if stated is None:
            raise self.error(
                f"expected R, P, revolute or prismatic, found {describe(raw)}", key="type", **where
            )
        if stated != kind:
            words = {"R": "revolute", "P": "prismatic"}
            raise self.error(
                f"type says {words[stated]}, but the joint variable is in {key}, "
                f"which makes the joint {words[kind]}",
                key="type",
                **where,
            )

    def frame(self, raw: object, which: str) -> FrameSpec | None:
        if raw is None:
            return None
        data = self.mapping(raw, "a mapping with xyz and rpy, or with matrix", key=which)
        self.check_keys(data, FRAME_KEYS, f"{which}.")
        if "matrix" in data:
            if "xyz" in data or "rpy" in data:
                raise self.error(
                    "give either matrix, or xyz and rpy, not both", key=f"{which}.matrix"
                )
            return FrameSpec(*self.matrix(data["matrix"], f"{which}.matrix"))
        x, y, z = self.numbers(data.get("xyz", (0, 0, 0)), ("length",) * 3, f"{which}.xyz")
        if "rpy" not in data:
            return FrameSpec(xyz=(x, y, z))
        roll, pitch, yaw = self.numbers(data["rpy"], ("angle",) * 3, f"{which}.rpy")
        for angle in (roll, pitch, yaw):
            written = math.degrees(angle) if self.angle_unit == "deg" else angle
            self.check_angle(written, f"{which}.rpy")
        return FrameSpec(xyz=(x, y, z), rpy=(roll, pitch, yaw))

    def chain(self, raw: object, n: int) -> ChainSpec | None:
        """The optional ``chain`` block: start, n - 1 between, end, n frames."""
        if raw is None:
            return None
        data = self.mapping(raw, "a mapping with start, between, end and frames", key="chain")
        self.check_keys(data, CHAIN_KEYS, "chain.")
        missing = [k for k in CHAIN_KEYS if k not in data]
        if missing:
            raise self.error(f"missing {', '.join(missing)}", key="chain")
        lists = {}
        for key, count in (("between", n - 1), ("frames", n)):
            items = data[key]
            if not isinstance(items, list | tuple) or len(items) != count:
                raise self.error(
                    f"expected a list of {count} frames (the robot has {n} joints), "
                    f"found {describe(items)}",
                    key=f"chain.{key}",
                )
            lists[key] = tuple(
                self.frame(item, f"chain.{key}[{i}]") or FrameSpec() for i, item in enumerate(items)
            )
        return ChainSpec(
            start=self.frame(data["start"], "chain.start") or FrameSpec(),
            between=lists["between"],
            end=self.frame(data["end"], "chain.end") or FrameSpec(),
            frames=lists["frames"],
        )

    def matrix(
        self, raw: object, key: str
    ) -> tuple[tuple[float, float, float], None, tuple[tuple[float, ...], ...]]:
        if not isinstance(raw, list | tuple) or len(raw) != 4:
            raise self.error(f"expected 4 rows of 4 numbers, found {describe(raw)}", key=key)
        # The translation column is a length; the bottom row is plain numbers.
        qty: tuple[Quantity, ...] = ("number", "number", "number", "length")
        plain: tuple[Quantity, ...] = ("number",) * 4
        rows = tuple(self.numbers(row, qty if i < 3 else plain, key) for i, row in enumerate(raw))
        M = np.array(rows)
        R = M[:3, :3]
        bottom = float(np.abs(M[3] - (0.0, 0.0, 0.0, 1.0)).max())
        if bottom > MATRIX_TOL:
            raise self.error(f"the last row must be [0, 0, 0, 1], found {list(rows[3])}", key=key)
        ortho = float(np.abs(R.T @ R - np.eye(3)).max())
        if ortho > MATRIX_TOL or np.linalg.det(R) < 0:
            raise self.error(
                f"the rotation part is not a rotation (max |R^T R - I| = {ortho:.1e}, "
                f"det = {np.linalg.det(R):.3g}; tolerance {MATRIX_TOL:g}): "
                "give more digits, or use rpy",
                key=key,
            )
        xyz = (rows[0][3], rows[1][3], rows[2][3])
        return xyz, None, rows


def _default_name(source: str | None) -> str:
    if source is None or source.startswith("builtin:"):
        return "robot"
    return PurePath(source).stem or "robot"


def parse_robot_dict(
    data: object, *, source: str | None = None, parameters: Mapping[str, float] | None = None
) -> RobotSpec:
    """Check already-loaded robot-file data and build its :class:`RobotSpec`.

    Args:
        data: The file's content as loaded by a YAML/JSON/TOML reader: a
            mapping with the keys described in :mod:`kinematica.io.robotfile`.
        source: Where the data came from (a path, or ``"builtin:NAME"``);
            named in error messages and kept in ``RobotSpec.source``.
        parameters: Values (file units) replacing those of the named
            parameters before anything else is evaluated, so expressions that
            use them (``l2: 1 - l1``, DH cells, limits, base, tool) follow. Only
            parameters that use no other parameter can be set, and a bounded
            parameter only within its ``[min, max]``.

    Returns:
        The robot description in radians and metres.

    Raises:
        RobotFileError: naming the file, joint, key, what was expected and
            what was found.
    """
    r = _Reader(source, overrides=dict(parameters or {}))
    top = r.mapping(data, f"a mapping with the keys {', '.join(TOP_KEYS)}")
    r.check_keys(top, TOP_KEYS)

    name = r.text(top.get("name"), "name")
    if name is not None and not name.strip():
        raise r.error("expected a non-empty name", key="name")

    word = top.get("convention")
    if "convention" not in top:
        convention: Convention | None = missing_convention(r.path or "the robot data", stacklevel=2)
    else:
        convention = CONVENTION_ALIASES.get(word.strip().lower()) if isinstance(word, str) else None
    if convention is None:
        raise r.error(
            f"expected {convention_names()}, found {describe(word)}",
            key="convention",
        )

    r.units(top.get("units"))
    r.read_parameters(top.get("parameters"))
    r.described = top.get("chain") is not None

    if "joints" not in top:
        raise r.error("missing key 'joints': the DH table, one entry per joint")
    rows = top["joints"]
    if not isinstance(rows, list | tuple):
        raise r.error(f"expected a list of joints, found {describe(rows)}", key="joints")
    if not rows:
        raise r.error("expected at least one joint, found an empty list", key="joints")
    if len(rows) > MAX_JOINTS:
        raise r.error(f"{len(rows)} joints; at most {MAX_JOINTS} are accepted", key="joints")
    joints = tuple(r.joint(row, i) for i, row in enumerate(rows, start=1))

    return RobotSpec(
        name=name if name is not None else _default_name(source),
        convention=convention,
        joints=joints,
        base=r.frame(top.get("base"), "base"),
        tool=r.frame(top.get("tool"), "tool"),
        parameters=dict(r.parameters),
        parameter_texts=dict(r.parameter_texts),
        source=source,
        description=r.text(top.get("description"), "description"),
        units={"angle": r.angle_unit, "length": r.length_unit},
        reference=r.text(top.get("source"), "source"),
        parameter_bounds=dict(r.bounds),
        document=_document(r, top),
        chain=r.chain(top.get("chain"), len(joints)),
    )


def _document(r: _Reader, top: Mapping[str, Any]) -> dict[str, Any]:
    """A private copy of the checked file data, kept so the spec can be rebuilt."""
    try:
        return copy.deepcopy(dict(top))
    except RecursionError as exc:
        raise r.error("the file is nested too deeply") from exc
