"""Design templates: a robot file whose parameters carry bounds.

::

    name: planar 2R, total length 1
    convention: standard
    parameters:
      l1: {value: 0.3, min: 0.1, max: 0.9}   # a design variable
      l2: 1 - l1                             # follows it: a fixed total length
    joints:
      - {theta: q1, d: 0, a: l1, alpha: 0}
      - {theta: q2, d: 0, a: l2, alpha: 0}

The bounded parameters are the design variables, in file order and in the
file's units; every other parameter, DH cell, limit, base and tool that uses
them is evaluated again for each candidate by the robot-file parser
(:func:`kinematica.io.with_parameters`). ``km.load`` reads a template as the
robot at its ``value`` s.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError, RobotFileError
from kinematica.io import RobotSpec, read_robot_file, with_parameters
from kinematica.robot import Robot, robot_from_spec

if TYPE_CHECKING:
    from kinematica.design.compiled import CompiledTemplate

__all__ = ["DesignTemplate", "load_template"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class DesignTemplate:
    """A robot description with design variables (bounded parameters).

    Attributes:
        spec: The description at the parameters' ``value`` s.
        names: The design variables, in file order.
        lower: ``(p,)`` lower bounds, file units.
        upper: ``(p,)`` upper bounds, file units.
    """

    spec: RobotSpec
    names: tuple[str, ...] = field(init=False)
    lower: FloatArray = field(init=False, repr=False)
    upper: FloatArray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        spec = self.spec
        where = spec.source or spec.name
        if spec.document is None:
            raise RobotFileError(
                f"{where}: a design template must be read from a robot file "
                "(its parameters are evaluated again for every candidate)"
            )
        if not spec.parameter_bounds:
            raise RobotFileError(
                f"{where}: a design template needs at least one parameter with bounds, "
                "e.g. parameters: {l1: {value: 0.3, min: 0.1, max: 0.9}}"
            )
        names = tuple(spec.parameter_bounds)
        bounds = np.array([spec.parameter_bounds[n] for n in names], dtype=float)
        lower, upper = bounds[:, 0].copy(), bounds[:, 1].copy()
        lower.flags.writeable = upper.flags.writeable = False
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "lower", lower)
        object.__setattr__(self, "upper", upper)

    @property
    def name(self) -> str:
        """The robot's name."""
        return self.spec.name

    @property
    def units(self) -> Mapping[str, str]:
        """The units of the parameters: ``{"angle": ..., "length": ...}``."""
        return self.spec.units

    @property
    def nominal(self) -> dict[str, float]:
        """The design variables' ``value`` s in the file."""
        return {n: float(self.spec.parameters[n]) for n in self.names}

    def vector(self, params: Mapping[str, float]) -> FloatArray:
        """``(p,)`` the design variables of ``params`` (missing ones nominal)."""
        unknown = sorted(set(params) - set(self.names))
        if unknown:
            raise KinematicaError(
                f"{unknown[0]!r} is not a design variable of {self.name}; "
                f"they are: {', '.join(self.names)}"
            )
        values = {**self.nominal, **params}
        return np.array([float(values[n]) for n in self.names])

    def params(self, x: ArrayLike) -> dict[str, float]:
        """``name -> value`` of a ``(p,)`` vector of design variables."""
        xa = np.asarray(x, dtype=float)
        if xa.shape != (len(self.names),):
            raise KinematicaError(
                f"expected {len(self.names)} values ({', '.join(self.names)}), got shape {xa.shape}"
            )
        return {n: float(v) for n, v in zip(self.names, xa, strict=True)}

    def spec_at(self, params: Mapping[str, float] | ArrayLike) -> RobotSpec:
        """The description with other values of the design variables.

        Args:
            params: ``name -> value`` (file units; missing ones keep their
                value), or a ``(p,)`` vector in the order of :attr:`names`.

        Raises:
            RobotFileError: A value outside its bounds, or an unknown name.
        """
        values = dict(params) if isinstance(params, Mapping) else self.params(params)
        return with_parameters(self.spec, values)

    def robot_at(self, params: Mapping[str, float] | ArrayLike) -> Robot:
        """The robot with other values of the design variables (see :meth:`spec_at`)."""
        return robot_from_spec(self.spec_at(params))

    @cached_property
    def compiled(self) -> CompiledTemplate:
        """The template compiled once (:mod:`kinematica.design.compiled`).

        A candidate's robot from its DH values, without reading the file again.
        """
        from kinematica.design.compiled import compile_template

        return compile_template(self)

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        state.pop("compiled", None)  # compiled again where it is used (a Dask worker)
        return state

    @property
    def fingerprint(self) -> str:
        """A hash of the file content and the bounds (checkpoints check it)."""
        text = json.dumps(
            {"document": self.spec.document, "names": self.names},
            sort_keys=True,
            default=repr,
        )
        return hashlib.sha256(text.encode()).hexdigest()


def load_template(template: DesignTemplate | RobotSpec | str | os.PathLike[str]) -> DesignTemplate:
    """A :class:`DesignTemplate` from a robot file path, a spec read from one, or itself.

    Raises:
        RobotFileError: The file is malformed or has no bounded parameter.
    """
    if isinstance(template, DesignTemplate):
        return template
    if isinstance(template, RobotSpec):
        return DesignTemplate(template)
    return DesignTemplate(read_robot_file(template))
