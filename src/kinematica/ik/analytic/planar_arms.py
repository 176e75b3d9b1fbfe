"""Planar 2R, 3R, PR and PRR arms and the SCARA: their closed form, built once per arm.

The solver is ``cpp/include/kinematica/solvers/planar.hpp``
(:class:`kinematica._core.planar.PlanarParams`), built in ``planar_build.hpp`` from the
joint axes at q = 0 and the tool pose ``M = fk(0)``, so any base, tool, offsets and DH
convention are handled alike.

Branch labels (angles about ``k``, the first revolute axis's direction, seen
from the side it points to: positive turns are counter-clockwise):

* planar 2R and 3R: ``"elbow up"``, ``"elbow down"``. Elbow up: the elbow lies
  to the left of the line from the shoulder (axis 1) to the wrist (the tool
  origin of a 2R arm, axis 3 of a 3R arm), i.e. link 2 is turned clockwise
  from link 1 (relative angle ψ in [-π, 0]); drawn with the target to the
  right of the shoulder, the elbow is above the line.
* SCARA: ``"right-handed"`` (ψ in [0, π]: the elbow to the right of the
  shoulder-wrist line, as a right arm seen from above) and ``"left-handed"``.
* planar PR and PRR: ``"link forward"`` (the revolute link points along the
  slide direction, the lecture notes' ``q2A = asin(y/l2)``) and ``"link backward"``
  (``q2B = π - asin(y/l2)``).

For position targets of the 3R, PRR and SCARA arms the last revolute joint is
free and the labels describe the representatives.
"""

from __future__ import annotations

from kinematica import _core
from kinematica.core import Chain
from kinematica.ik.analytic.small_samples import sampler
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["LABELS", "SPECS", "build"]

#: Branch labels of the candidate slots, per kind.
LABELS: dict[str, tuple[str, str]] = {
    "planar-2R": ("elbow up", "elbow down"),
    "planar-3R": ("elbow up", "elbow down"),
    "scara": ("right-handed", "left-handed"),
    "planar-PR": ("link forward", "link backward"),
    "planar-PRR": ("link forward", "link backward"),
}


def build(chain: Chain, features: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of a planar arm or a SCARA, or None for degenerate links.

    The core builds it (``km::planar::build``, ``cpp/include/kinematica/solvers/
    planar_build.hpp``), for pose or (``build_position``) position targets.

    Args:
        chain: The arm.
        features: Its joint axes at q = 0 (one of the planar kinds or SCARA).
        target: ``"pose"`` or ``"position"`` targets.
    """
    kind = next((s.kind for s in SPECS if s.handles(features)), None)
    core = _core.planar.build if target == "pose" else _core.planar.build_position
    params = None if kind is None else core(chain.core)
    if kind is None or params is None:
        return None
    return ClosedForm(
        name=kind, labels=LABELS[kind], params=params, position_only=target == "position"
    )


_BOTH: tuple[TargetKind, ...] = ("pose", "position")

SPECS: tuple[SolverSpec, ...] = (
    SolverSpec(
        "planar-2R",
        "2R planar",
        "brazo plano 2R",
        lambda f: f.joint_types == "RR" and f.is_parallel(0, 1),
        build,
        sampler("planar-2R"),
        _BOTH,
        derivation="planar-2R",
        geometric="planar",
        singular=frozenset({"elbow"}),
    ),
    SolverSpec(
        "planar-PR",
        "PR planar (prismatic then revolute)",
        "brazo plano PR (prismática y rotacional)",
        lambda f: f.joint_types == "PR" and f.is_perpendicular(0, 1),
        build,
        sampler("planar-PR"),
        _BOTH,
        derivation="planar-PR",
        geometric="planar",
    ),
    SolverSpec(
        "planar-3R",
        "3R planar",
        "brazo plano 3R",
        lambda f: f.joint_types == "RRR" and f.all_parallel(range(3)),
        build,
        sampler("planar-3R"),
        _BOTH,
        derivation="planar-3R",
        geometric="planar",
        singular=frozenset({"elbow"}),
    ),
    SolverSpec(
        "planar-PRR",
        "PRR planar (prismatic then two parallel revolute)",
        "brazo plano PRR (prismática y dos rotacionales paralelas)",
        lambda f: f.joint_types == "PRR" and f.is_parallel(1, 2) and f.is_perpendicular(0, 1),
        build,
        sampler("planar-PRR"),
        _BOTH,
        derivation="planar-PRR",
        geometric="planar",
    ),
    SolverSpec(
        "scara",
        "SCARA (RRPR, all axes parallel)",
        "SCARA (RRPR, todos los ejes paralelos)",
        lambda f: f.joint_types == "RRPR" and f.all_parallel(range(4)),
        build,
        sampler("scara"),
        _BOTH,
        derivation="scara",
        geometric=None,
        singular=frozenset({"elbow"}),
    ),
)
