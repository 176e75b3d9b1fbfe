"""3R elbow arms, anthropomorphic or with a shoulder offset: their closed form, built once per arm.

Axis 1 perpendicular to axes 2 and 3, which are parallel; the solver is
``cpp/include/kinematica/solvers/elbow.hpp`` (:class:`kinematica._core.elbow.ElbowParams`),
built in ``elbow_build.hpp`` from the joint axes at q = 0 and ``M = fk(0)``: any base,
tool, offsets and DH convention. This module names the family and its branches.

Branch labels (``σ = (p − p1)·(h1 × k1)`` with ``k1`` the current axis-2
direction, ψ the angle of link 3 relative to link 2 about ``k1``):

* ``"shoulder right"``: σ >= 0, the target lies on the ``h1 × k1`` side of
  axis 1. For an arm whose axes 1 and 2 meet this is Lee and Ziegler's right
  arm (a positive joint-2 rotation raises the wrist along h1); for the lecture notes'
  arm, ``q1 = atan2(py, px)``. ``"shoulder left"``: σ <= 0.
* ``"elbow up"``: in the arm's plane, the elbow (axis 3) lies on the side of
  the line from the shoulder (axis 2) to the target toward which ``h1``
  points (ψ has the sign of ``-(p - s)·(h1 × k1)``, ψ <= 0 when that is 0);
  ``"elbow down"``.

A pose target has one solution (in the slot of its branch); a position
target up to four.
"""

from __future__ import annotations

from kinematica import _core
from kinematica.core import Chain
from kinematica.ik.analytic.small_samples import sampler
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["LABELS", "SPECS", "build"]

#: Branch labels of the four candidate slots.
LABELS = (
    "shoulder right, elbow up",
    "shoulder right, elbow down",
    "shoulder left, elbow up",
    "shoulder left, elbow down",
)


def build(chain: Chain, features: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of a 3R elbow arm, or None when a link is degenerate.

    The core builds it (``km::elbow::build``, ``cpp/include/kinematica/solvers/
    elbow_build.hpp``), for pose or (``build_position``) position targets.

    Args:
        chain: The arm.
        features: Its joint axes at q = 0 (anthropomorphic-3R or elbow-3R).
        target: ``"pose"`` or ``"position"`` targets.
    """
    kind = next((s.kind for s in SPECS if s.handles(features)), None)
    core = _core.elbow.build if target == "pose" else _core.elbow.build_position
    params = None if kind is None else core(chain.core)
    if kind is None or params is None:
        return None
    return ClosedForm(name=kind, labels=LABELS, params=params, position_only=target == "position")


def _elbow(f: Features) -> bool:
    return f.joint_types == "RRR" and f.is_parallel(1, 2) and f.is_perpendicular(0, 1)


SPECS: tuple[SolverSpec, ...] = (
    SolverSpec(
        "anthropomorphic-3R",
        "3R anthropomorphic (shoulder axes meet)",
        "brazo antropomórfico 3R (los ejes del hombro se cortan)",
        lambda f: _elbow(f) and f.meet(0, 1),
        build,
        sampler("anthropomorphic-3R"),
        ("pose", "position"),
        derivation="elbow-3R",
        geometric="arm-plane",
        singular=frozenset({"shoulder", "elbow"}),
    ),
    SolverSpec(
        "elbow-3R",
        "3R elbow arm with shoulder offset",
        "brazo 3R de codo con desplazamiento en el hombro",
        lambda f: _elbow(f) and not f.meet(0, 1),
        build,
        sampler("elbow-3R"),
        ("pose", "position"),
        derivation="elbow-3R",
        geometric="arm-plane",
        singular=frozenset({"shoulder", "elbow"}),
    ),
)
