"""A joint in the middle held across its turn: the arm cut open at it, one build per target.

Holding joint s of a 6R arm at t changes the geometry of the arm left with t when s is
not an end joint: each value would build the general 6R anew (about 13 ms each, 24
values a sweep). Cut the closed loop at joint s instead. With ``T(q) = start Π_i [Rz(q_i)
F_i] tool`` (:attr:`~kinematica.core.Chain.fixed_parts`), ``A = start Π_(i<s)
[Rz(q_i) F_i]`` and ``B = Π_(i>s) [Rz(q_i) F_i] tool``, a configuration reaches T when
``A Rz(q_s) F_s B = T``, that is when

    ``F_s B T⁻¹ A = Rz(-q_s)``:

the five joints s+1, ..., 6, 1, ..., s-1, in that order, make an arm (its links the F's,
and ``F_6 tool T⁻¹ start`` between joint 6 and joint 1) whose tool must reach the turn
``Rz(-t)``. That arm depends on the target but not on t: built once per target (with a
virtual joint at its tool, as for an end joint, :mod:`kinematica.ik.near_sweep`), its
samples are moved targets ``Rz(-t)``, one batch.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain

if TYPE_CHECKING:
    from kinematica.ik.tolerance import Tolerance

__all__ = ["CutSweep", "cut_arm", "cut_sweep"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True, eq=False)
class CutSweep:
    """A middle joint held across its turn, for one target: the cut arm and its closed form.

    Attributes:
        joint: The held joint (1-4, 0-based).
        arm: The 6R arm: the cut arm (:func:`cut_arm`) with a virtual joint at its tool.
        params: Its closed form's ``Params`` (``ik_batch``).
    """

    joint: int
    arm: Chain
    params: Any

    def solve(
        self, chain: Chain, poses: FloatArray, t: FloatArray, tol: Tolerance, workers: int = 1
    ) -> tuple[FloatArray, FloatArray, list[int]]:
        """Every solution with the joint at each of ``t (k,)`` (``poses``: its target, unused).

        Returns:
            ``((k, m, 6) configurations of the real arm, (k, m) θ, counts)``, as
            :meth:`kinematica.ik.near_sweep.EndSweep.solve`.
        """
        from kinematica.ik.solvers import POSE_WEIGHTS, check_options

        t = np.asarray(t, dtype=np.float64)
        c, s = np.cos(-t), np.sin(-t)
        turn = np.zeros((len(t), 4, 4))
        turn[:, 0, 0], turn[:, 0, 1], turn[:, 1, 0], turn[:, 1, 1] = c, -s, s, c
        turn[:, 2, 2] = turn[:, 3, 3] = 1.0
        opts = check_options(tol, False, False, POSE_WEIGHTS)
        raw = self.params.ik_batch(self.arm.core, turn, opts, None, None, workers)
        q = np.asarray(raw.q)
        j = self.joint
        real = np.empty((*q.shape[:2], 6))
        real[..., j + 1 :] = q[..., : 5 - j]
        real[..., :j] = q[..., 5 - j : 5]
        real[..., j] = t[:, None]
        return real, q[..., 5], np.asarray(raw.count).tolist()


def cut_arm(chain: Chain, joint: int, T: FloatArray) -> Chain:
    """The 5R arm of joints ``joint + 1, ..., 5, 0, ..., joint - 1`` (0-based) cut at ``joint``.

    Its FK at those joints' values is ``Rz(-q_joint)`` exactly where the 6R arm's reaches
    ``T (4, 4)`` (the module says why). ``joint`` is 1-4.
    """
    F = np.asarray(chain.fixed_parts)
    s = joint
    loop = F[5] @ chain.tool @ np.linalg.inv(T) @ chain.start
    between = [*F[s + 1 : 5], loop, *F[: s - 1]]
    return Chain.from_transforms(
        F[s],
        np.ascontiguousarray(between),
        F[s - 1],
        np.broadcast_to(np.eye(4), (5, 4, 4)).copy(),
        np.zeros(5, dtype=bool),
        np.tile([-np.inf, np.inf], (5, 1)),
        np.eye(4),
    )


def cut_sweep(chain: Chain, joint: int, T: FloatArray) -> CutSweep | None:
    """The cut arm at ``joint`` for ``T`` with a virtual joint, where it has a regular closed form.

    None where, on either virtual line, its arm has no closed form or is near rank 5.
    """
    from kinematica.ik.coaxial import VIRTUAL_LINES, frame_on, with_virtual_joint
    from kinematica.ik.rank_five import rank_five
    from kinematica.ik.solvers import closed_form
    from kinematica.ik.structure import features

    cut = cut_arm(chain, joint, T)
    size = features(chain).size
    for direction, point in VIRTUAL_LINES:
        W = frame_on(np.array(direction), size * np.array(point))
        arm = with_virtual_joint(cut, W, np.tile([-np.inf, np.inf], (5, 1)))
        closed = closed_form(arm, "pose")
        if closed is not None and rank_five(arm) is None:
            return CutSweep(joint, arm, closed.params)
    return None
