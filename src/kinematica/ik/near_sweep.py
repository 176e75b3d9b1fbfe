"""The sweep along a near-continuum: a joint held across its turn, each arm left in closed form.

For many targets at once.

The guesses of :mod:`kinematica.ik.near_rank_five`. A joint ``s`` of the 6R arm is held at
:data:`SWEEP_SAMPLES` values ``t`` across its turn; the 5R arm left, with a virtual joint
at its tool (:func:`kinematica.ik.coaxial.with_virtual_joint`), is a regular 6R arm
solved in closed form for every solution: configurations of the real arm with ``q_s =
t`` that miss the target only by the virtual joint's angle θ. Along each branch θ
varies smoothly with ``t``; the real arm's solutions are its zeros.

**A held joint at an end of the chain: one arm, moved targets.** Where ``s`` is the
first joint, ``FK(t, q') = G(t) FK(0, q')`` with ``G(t) = FK(t e1) FK(0)⁻¹`` (the turn
about the first axis, whatever the arm after it); where it is the last, ``FK(q', t) =
FK(q', 0) H(t)`` with ``H(t) = FK(0)⁻¹ FK(t e6)``. The arm held at 0, with its virtual
joint, is therefore built once per chain (:func:`end_sweeps`, kept in the chain's
``memo``) and each sample is a target moved by ``G(t)⁻¹`` (or ``H(t)⁻¹``): every
sample of every target is one batch of the core (``ik_batch``). A joint in the middle
changes the geometry of the arm left with its value: it is swept only where neither end
joint moves along the near-continuum (four parallel or concurrent axes 2-5), on the arm
cut open at it (:mod:`kinematica.ik.near_cut`: one build per target, its samples moved
targets too).

What this costs and finds against sweeping each value on its own arm:
:mod:`kinematica.ik.near_rank_five`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.ik.rank_five import RANK_SAMPLES, RANK_SEED, free_motion, rank_five
from kinematica.ik.structure import features

if TYPE_CHECKING:
    from kinematica.ik.near_cut import CutSweep
    from kinematica.ik.tolerance import Tolerance

__all__ = [
    "MOVES_TOL",
    "NEWTON_DONE",
    "NEWTON_STEPS",
    "SWEEP_SAMPLES",
    "Brackets",
    "EndSweep",
    "end_samples",
    "end_sweeps",
    "held_values",
    "moving_joints",
    "newton",
    "seeds_between",
]

FloatArray = NDArray[np.float64]

#: Values of a swept joint, evenly across its turn.
SWEEP_SAMPLES = 24
#: A joint is swept when its share of the near-null direction (unit) is at least this at
#: every configuration the rank was measured at: below, holding it barely breaks the
#: near-continuum (the arm left is near rank 5 itself, and passed over). The shares of
#: joints that move are 0.05 and more on the arms of the tests; those that do not (joints
#: 1 and 6 beside four parallel axes 2-5), the arm's distance from rank 5 (1e-6 and less).
MOVES_TOL = 1e-3
#: Newton steps from each guess (quadratic convergence: a guess within reach settles in
#: 4-6).
NEWTON_STEPS = 12
#: Newton stops when every component of the pose error is below this (m, rad): a tenth
#: of the default tolerance, round-off's reach.
NEWTON_DONE = 1e-11


@dataclass(frozen=True, slots=True, eq=False)
class EndSweep:
    """An end joint held at 0, the arm left with a virtual joint, and its closed form.

    Attributes:
        joint: The held joint (0 or 5).
        arm: The 6R arm: the 5R arm with ``joint`` at 0 and a virtual joint at its tool.
        params: Its closed form's ``Params`` (``ik_batch``).
        start: ``(4, 4)`` FK of the real arm at q = 0 (base frame, m).
    """

    joint: int
    arm: Chain
    params: Any
    start: FloatArray

    def moved(self, chain: Chain, poses: FloatArray, t: FloatArray) -> FloatArray:
        """``(k, 4, 4)`` each of ``poses (k, 4, 4)`` moved for its held value ``t (k,)``."""
        q = np.zeros((len(t), 6))
        q[:, self.joint] = t
        F = np.asarray(chain.fk(q)[0])  # FK at t on the held joint, 0 elsewhere
        if self.joint == 0:  # G(t)⁻¹ T, G(t) = F(t) F(0)⁻¹
            return np.asarray(self.start @ np.linalg.inv(F) @ poses)
        return np.asarray(poses @ np.linalg.inv(F) @ self.start)  # T H(t)⁻¹, H = F(0)⁻¹ F(t)

    def solve(
        self, chain: Chain, poses: FloatArray, t: FloatArray, tol: Tolerance, workers: int = 1
    ) -> tuple[FloatArray, FloatArray, list[int]]:
        """Every solution of the virtual arm for each of ``poses (k, 4, 4)`` at ``t (k,)``.

        ``workers``: the core's threads for the batch.

        Returns:
            ``((k, m, 6) configurations of the real arm, (k, m) θ, counts)``: row r's
            first ``counts[r]`` slots (the held joint at ``t[r]``). One batch of the core.
        """
        from kinematica.ik.solvers import POSE_WEIGHTS, check_options

        moved = np.ascontiguousarray(self.moved(chain, poses, t))
        opts = check_options(tol, False, False, POSE_WEIGHTS)
        raw = self.params.ik_batch(self.arm.core, moved, opts, None, None, workers)
        q = np.asarray(raw.q)
        held = np.broadcast_to(np.asarray(t, dtype=np.float64)[:, None], q.shape[:2])
        real = np.insert(q[..., :5], self.joint, held, axis=2)
        return real, q[..., 5], np.asarray(raw.count).tolist()


def moving_joints(chain: Chain, rank: int) -> tuple[int, ...]:
    """The joints that move along the near-continuum, the end joints first, then by share.

    Those whose share of the near-null direction is at least :data:`MOVES_TOL` at every
    configuration the rank was measured at (made once per chain).
    """
    key = ("near-sweep", "moving")
    if key not in chain.memo:
        Q = np.random.default_rng(RANK_SEED).uniform(-math.pi, math.pi, (RANK_SAMPLES, 6))
        share = np.min([free_motion(chain, q, rank) for q in Q], axis=0)
        order = sorted(range(6), key=lambda j: (j not in (0, 5), -float(share[j])))
        chain.memo[key] = tuple(j for j in order if share[j] >= MOVES_TOL)
    got: tuple[int, ...] = chain.memo[key]  # type: ignore[assignment]
    return got


def end_sweeps(chain: Chain, rank: int) -> tuple[EndSweep, ...]:
    """The end joints that move (:func:`moving_joints`), each held at 0 with its virtual arm.

    With that arm's closed form (made once per chain); an end joint whose arm left has
    no closed form, or is itself near rank 5, on either virtual line, is left out.
    """
    key = ("near-sweep", "ends")
    if key in chain.memo:
        got: tuple[EndSweep, ...] = chain.memo[key]  # type: ignore[assignment]
        return got
    out = []
    for joint in (j for j in moving_joints(chain, rank) if j in (0, 5)):
        arm = _virtual_arm(chain, joint, 0.0)
        if arm is not None:
            from kinematica.ik.solvers import closed_form

            closed = closed_form(arm[0], "pose")
            assert closed is not None  # (checked by _virtual_arm)
            out.append(EndSweep(joint, arm[0], closed.params, np.asarray(chain.fk(np.zeros(6))[0])))
    chain.memo[key] = tuple(out)
    return tuple(out)


def _virtual_arm(chain: Chain, joint: int, value: float) -> tuple[Chain, int] | None:
    """The arm with ``joint`` at ``value`` and a virtual joint at its tool, and the line's index.

    The first of :data:`~kinematica.ik.coaxial.VIRTUAL_LINES` whose arm has a closed
    form and is not near rank 5; None where none is.
    """
    from kinematica.ik.coaxial import VIRTUAL_LINES, frame_on, with_virtual_joint
    from kinematica.ik.solvers import closed_form

    locked = chain.locked(joint, value)
    limits = np.array(locked.own_limits, dtype=np.float64)
    size = features(chain).size
    for k, (direction, point) in enumerate(VIRTUAL_LINES):
        arm = with_virtual_joint(
            locked, frame_on(np.array(direction), size * np.array(point)), limits
        )
        if closed_form(arm, "pose") is not None and rank_five(arm) is None:
            return arm, k
    return None


def held_values() -> FloatArray:
    """``(S,)`` the held values, :data:`SWEEP_SAMPLES` evenly across the turn (rad)."""
    step = 2.0 * math.pi / SWEEP_SAMPLES
    return np.asarray(-math.pi + step * np.arange(SWEEP_SAMPLES), dtype=np.float64)


def end_samples(
    chain: Chain,
    sweep: EndSweep | CutSweep,
    poses: FloatArray,
    tol: Tolerance,
    workers: int = 1,
) -> list[list[tuple[FloatArray, FloatArray]]]:
    """Per target of ``poses (k, 4, 4)``, per held value: ``((m, 6) configurations, (m,) θ)``.

    One batch of the core for every sample of every target (``workers`` threads).
    """
    t = held_values()
    S = len(t)
    real, theta, count = sweep.solve(
        chain, np.repeat(poses, S, axis=0), np.tile(t, len(poses)), tol, workers
    )
    return [
        [(real[r, : count[r]], theta[r, : count[r]]) for r in range(i * S, (i + 1) * S)]
        for i in range(len(poses))
    ]


def _wrapped(x: FloatArray) -> FloatArray:
    return np.asarray(np.remainder(x + math.pi, 2.0 * math.pi) - math.pi)


def _nearest(Qa: FloatArray, Qb: FloatArray) -> tuple[NDArray[np.intp], FloatArray]:
    """For each row of ``Qa (na, 6)``: the nearest row of ``Qb (nb, 6)``, and the step to it.

    The step ``(na, 6)`` has its joints wrapped to (-π, π].
    """
    d = _wrapped(Qb[None] - Qa[:, None])
    b = np.argmin(np.abs(d).max(axis=2), axis=1)
    return b, d[np.arange(len(Qa)), b]


@dataclass(frozen=True, slots=True)
class Brackets:
    """Intervals of a sweep's branches where θ changes sign, one per row.

    Attributes:
        qa: ``(b, 6)`` the configuration at one end (the held joint at its value).
        qb: ``(b, 6)`` at the other, unwrapped from ``qa`` (``qa`` plus the wrapped step).
        tha: ``(b,)`` θ at ``qa`` (rad, wrapped).
        thb: ``(b,)`` θ at ``qb``, of the other sign or 0.
    """

    qa: FloatArray
    qb: FloatArray
    tha: FloatArray
    thb: FloatArray

    def at_zero(self) -> FloatArray:
        """``(b, 6)`` each interval's configuration interpolated linearly at θ = 0."""
        den = self.tha - self.thb
        w = np.divide(self.tha, den, out=np.full_like(den, 0.5), where=den != 0.0)
        return self.qa + w[:, None] * (self.qb - self.qa)


def seeds_between(
    samples: Sequence[tuple[FloatArray, FloatArray]],
) -> tuple[FloatArray, Brackets]:
    """The guesses of one sweep: the minima of |θ| along its branches, and its sign changes.

    Samples are paired with their neighbours (cyclically): each configuration with the
    nearest of the next sample and of the one before (the joints' change, wrapped).

    Returns:
        ``((k, 6) minima, brackets)``: every configuration whose |θ| is at most its
        neighbours' (a zero θ touches without crossing, two zeros near a fold of the
        branch), and the intervals where θ changes sign from a configuration to its next
        (:class:`Brackets`).
    """
    n = len(samples)
    seeds: list[FloatArray] = []
    parts: list[tuple[FloatArray, ...]] = []
    for k in range(n):
        Qa, ta = samples[k]
        if not len(Qa):
            continue
        th_a = _wrapped(ta)
        least = np.ones(len(Qa), dtype=bool)
        for j in (k - 1, (k + 1) % n):
            Qb, tb = samples[j]
            if not len(Qb):
                continue
            b, d = _nearest(Qa, Qb)
            th_b = _wrapped(tb[b])
            least &= np.abs(th_a) <= np.abs(th_b)
            if j == k - 1:
                continue
            ok = (th_a * th_b <= 0.0) & (np.abs(th_a - th_b) <= math.pi) & (th_a != th_b)
            parts.append((Qa[ok], Qa[ok] + d[ok], th_a[ok], th_b[ok]))
        seeds.append(Qa[least])
    minima = np.concatenate(seeds) if seeds else np.zeros((0, 6))
    if not parts:
        return minima, Brackets(np.zeros((0, 6)), np.zeros((0, 6)), np.zeros(0), np.zeros(0))
    return minima, Brackets(*(np.concatenate(c) for c in zip(*parts, strict=True)))


def newton(chain: Chain, seeds: FloatArray, T: FloatArray) -> FloatArray:
    """``(k, 6)`` each of ``seeds (k, 6)`` after at most :data:`NEWTON_STEPS` Newton steps.

    Full (undamped) steps on the pose error, position (m) and rotation vector (rad),
    against the geometric Jacobian (solved; by least squares where it is singular): along the
    near-continuum the step is Newton's on the virtual angle's zero, however small σ6.
    All rows at once; ``T`` is ``(4, 4)`` or one target per row ``(k, 4, 4)``.
    """
    from kinematica.spatial import rotvec_from_matrix

    q = np.array(seeds, dtype=np.float64).reshape(-1, 6)
    T = np.broadcast_to(T, (len(q), 4, 4))
    live = np.ones(len(q), dtype=bool)
    for _ in range(NEWTON_STEPS):
        idx = np.flatnonzero(live)
        if not len(idx):
            break
        Q = np.ascontiguousarray(q[idx])
        F = np.asarray(chain.fk(Q)[0])
        Ti = T[idx]
        R = Ti[:, :3, :3] @ np.swapaxes(F[:, :3, :3], 1, 2)
        e = np.concatenate([Ti[:, :3, 3] - F[:, :3, 3], rotvec_from_matrix(R)], axis=1)
        done = ~np.isfinite(e).all(axis=1) | (np.abs(e).max(axis=1) < NEWTON_DONE)
        live[idx[done]] = False
        go = ~done
        if not go.any():
            break
        J = np.asarray(chain.jacobian(Q[go])[0])
        try:  # J is invertible off an exact continuum (σ6 / σ1 above 1e-13)
            step = np.linalg.solve(J, e[go][..., None])[..., 0]
        except np.linalg.LinAlgError:  # exactly singular somewhere: least squares
            step = np.einsum("kij,kj->ki", np.linalg.pinv(J, rcond=1e-15), e[go])
        q[idx[go]] += step
    return q
