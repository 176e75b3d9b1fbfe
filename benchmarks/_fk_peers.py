"""The arms of the FK/Jacobian benchmark and the same arms in the peers' models.

Two arms: PUMA 560 (6R, standard DH) and Franka Panda (7R, modified DH, flange
tool). Baselines: a plain numpy loop and a naive vectorised numpy DH product;
peers: Pinocchio (a model of revolute-Z joints with constant placements) and
the Robotics Toolbox (``DHRobot`` and its compiled ``ETS``), each only when
installed. Every peer function returns arrays comparable with kinematica's:
``T (4, 4)`` and the geometric Jacobian ``(6, n)`` (linear rows first) in
the base frame.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from kinematica.dh import Revolute
from kinematica.robot import Robot

DEG = math.pi / 180
Fn = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Arm:
    """One benchmark arm: DH rows (theta offset, d, a, alpha) and a tool."""

    name: str
    convention: str
    rows: list[tuple[float, float, float, float]]
    tool: np.ndarray

    def robot(self) -> Robot:
        return Robot.from_dh(
            [Revolute(offset=th, d=d, a=a, alpha=al) for th, d, a, al in self.rows],
            convention=self.convention,
            name=self.name,
            tool=self.tool,
        )


def tz(z: float) -> np.ndarray:
    T = np.eye(4)
    T[2, 3] = z
    return T


PUMA = Arm(
    "PUMA 560 (6R, standard DH)",
    "standard",
    [
        (0, 0, 0, 90 * DEG),
        (0, 0, 0.4318, 0),
        (0, 0.15005, 0.0203, -90 * DEG),
        (0, 0.4318, 0, 90 * DEG),
        (0, 0, 0, -90 * DEG),
        (0, 0, 0, 0),
    ],
    np.eye(4),
)
PANDA = Arm(
    "Franka Panda (7R, modified DH, flange Tz(0.107))",
    "modified",
    [  # theta offset, d, a(i-1), alpha(i-1)
        (0, 0.333, 0, 0),
        (0, 0, 0, -90 * DEG),
        (0, 0.316, 0, 90 * DEG),
        (0, 0, 0.0825, 90 * DEG),
        (0, 0.384, -0.0825, -90 * DEG),
        (0, 0, 0, 90 * DEG),
        (0, 0, 0.088, 90 * DEG),
    ],
    tz(0.107),
)


# ---------------------------------------------------------------- numpy baselines
def _link(th: float, d: float, a: float, al: float, modified: bool) -> np.ndarray:
    ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
    if modified:
        return np.array(
            [
                [ct, -st, 0, a],
                [st * ca, ct * ca, -sa, -sa * d],
                [st * sa, ct * sa, ca, ca * d],
                [0, 0, 0, 1],
            ]
        )
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, d],
            [0, 0, 0, 1],
        ]
    )


def numpy_loop(arm: Arm, Q: np.ndarray) -> np.ndarray:
    """Per configuration: build every 4x4 link matrix and multiply them with ``@``."""
    modified = arm.convention == "modified"
    out = np.empty((len(Q), 4, 4))
    for k, q in enumerate(Q):
        T = np.eye(4)
        for qi, (th, d, a, al) in zip(q, arm.rows, strict=True):
            T = T @ _link(qi + th, d, a, al, modified)
        out[k] = T @ arm.tool
    return out


def numpy_vectorised(arm: Arm, Q: np.ndarray) -> np.ndarray:
    """Per link: a ``(N, 4, 4)`` stack of link matrices, then one batched ``@``."""
    N = len(Q)
    T = np.broadcast_to(np.eye(4), (N, 4, 4))
    for i, (th, d, a, al) in enumerate(arm.rows):
        theta = Q[:, i] + th
        ct, st = np.cos(theta), np.sin(theta)
        ca, sa = math.cos(al), math.sin(al)
        A = np.zeros((N, 4, 4))
        if arm.convention == "modified":
            A[:, 0, 0], A[:, 0, 1], A[:, 0, 3] = ct, -st, a
            A[:, 1, 0], A[:, 1, 1], A[:, 1, 2], A[:, 1, 3] = st * ca, ct * ca, -sa, -sa * d
            A[:, 2, 0], A[:, 2, 1], A[:, 2, 2], A[:, 2, 3] = st * sa, ct * sa, ca, ca * d
        else:
            A[:, 0, 0], A[:, 0, 1], A[:, 0, 2], A[:, 0, 3] = ct, -st * ca, st * sa, a * ct
            A[:, 1, 0], A[:, 1, 1], A[:, 1, 2], A[:, 1, 3] = st, ct * ca, -ct * sa, a * st
            A[:, 2, 1], A[:, 2, 2], A[:, 2, 3] = sa, ca, d
        A[:, 3, 3] = 1.0
        T = T @ A
    return T @ arm.tool


# ---------------------------------------------------------------- optional peers
@dataclass(frozen=True)
class Peer:
    """A peer's FK and Jacobian of one arm: single calls, and Python loops over a batch."""

    name: str
    fk: Fn
    jacobian: Fn
    fk_calls: str  # what ``fk`` calls, for the tables
    jacobian_calls: str

    def fk_loop(self, Q: np.ndarray) -> np.ndarray:
        return np.array([self.fk(q) for q in Q])

    def jacobian_loop(self, Q: np.ndarray) -> np.ndarray:
        return np.array([self.jacobian(q) for q in Q])


def pinocchio(arm: Arm) -> Peer | str:
    """The arm in Pinocchio (RZ joints, constant placements), or why not."""
    try:
        import pinocchio as pin
    except ImportError:
        return "Pinocchio: not installed (pip install pin), skipped"

    def rz(t: float) -> np.ndarray:
        R = np.eye(4)
        R[:2, :2] = [[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]]
        return R

    def rx_tx(al: float, a: float) -> np.ndarray:
        c, s = math.cos(al), math.sin(al)
        return np.array([[1, 0, 0, a], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])

    def se3(M: np.ndarray) -> Any:
        return pin.SE3(M[:3, :3].copy(), M[:3, 3].copy())

    # Joint i's placement is whatever constant transform precedes its Rz(q):
    # standard:  T = Π Rz(θi + q) · [Tz(d) Tx(a) Rx(α)]i;
    # modified:  T = Π [Rx(α) Tx(a)]i Rz(θi + q) Tz(di).
    model = pin.Model()
    parent, pending = 0, np.eye(4)
    for k, (th, d, a, al) in enumerate(arm.rows):
        if arm.convention == "modified":
            pending = pending @ rx_tx(al, a)
        placement = pending @ rz(th)
        parent = model.addJoint(parent, pin.JointModelRZ(), se3(placement), f"j{k + 1}")
        pending = tz(d) @ (rx_tx(al, a) if arm.convention == "standard" else np.eye(4))
    frame = model.addFrame(
        pin.Frame("tool", parent, 0, se3(pending @ arm.tool), pin.FrameType.OP_FRAME)
    )
    data = model.createData()
    world_aligned = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED

    def fk(q: np.ndarray) -> np.ndarray:
        pin.forwardKinematics(model, data, q)
        return pin.updateFramePlacement(model, data, frame).homogeneous

    def jacobian(q: np.ndarray) -> np.ndarray:
        pin.computeJointJacobians(model, data, q)
        return pin.getFrameJacobian(model, data, frame, world_aligned)

    return Peer(
        f"Pinocchio {pin.__version__}",
        fk,
        jacobian,
        "forwardKinematics + updateFramePlacement",
        "computeJointJacobians + getFrameJacobian(LOCAL_WORLD_ALIGNED)",
    )


def robotics_toolbox(arm: Arm) -> tuple[Peer, Any] | str:
    """The arm in the Robotics Toolbox: its compiled ``ETS``, and the ``DHRobot``."""
    try:
        import roboticstoolbox as rtb
        from spatialmath import SE3
    except ImportError:
        return "Robotics Toolbox: not installed (pip install roboticstoolbox-python), skipped"
    link = rtb.RevoluteMDH if arm.convention == "modified" else rtb.RevoluteDH
    dh = rtb.DHRobot(
        [link(d=d, a=a, alpha=al, offset=th) for th, d, a, al in arm.rows],
        tool=SE3(arm.tool, check=False),
    )
    ets = dh.ets()
    peer = Peer(
        f"Robotics Toolbox {rtb.__version__}", ets.eval, ets.jacob0, "ETS.eval", "ETS.jacob0"
    )
    return peer, dh
