"""Filling a reachability map: every voxel centre, every orientation, the batched IK.

The voxels inside the reach ball are taken in C order and cut into *blocks*
of whole voxels, about :data:`CHUNK_QUERIES` poses each: memory stays bounded
by one block's targets and IK answer (about 12 MB: under the size above which
the C allocator maps every array afresh, so that a block does not fault in its
memory again; 11 % faster than blocks four times as big) plus the per-voxel
results (24 bytes a voxel), however many poses the map asks. Each block is one call of
:func:`solve_block`, a pure function of its arguments: in this process
(``scheduler=None``) or on Dask workers, the results are the same bit for bit,
and a voxel's values do not depend on the blocks.

On Dask the voxels are dealt to the tasks as cards are (task ``t`` of ``T``
takes voxels ``t, t + T, t + 2T, ...``): each task holds voxels from the whole
ball, near its centre and its rim alike, so the tasks cost the same to within
a few per cent (cut into runs of neighbouring voxels, a run at the rim, where
most targets are out of reach, costs a third of one through the middle). The
robot and the orientations are sent to each worker once; a task sends back
three numbers a voxel (16 bytes).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.result import IKBatchResult
from kinematica.robot.velocity import selected_rows

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["CHUNK_QUERIES", "Block", "shares", "solve_block", "solve_blocks"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int32]

#: Poses solved in one IK call (bounds the memory of a map, see the module docs).
CHUNK_QUERIES = 1 << 14
#: Tasks given to each Dask worker at least (load balance against task overhead).
TASKS_PER_WORKER = 4
#: Most blocks in one Dask task (bounds its share of the voxels: their centres, its answer).
MAX_BLOCKS = 64


@dataclass(frozen=True)
class Block:
    """The results of a run of voxels.

    Attributes:
        reached: ``(v,)`` orientations reached within the limits, per voxel.
        solutions: ``(v,)`` IK solutions within the limits, summed over them.
        manipulability: ``(v,)`` best manipulability over those solutions
            (NaN where none, or not asked).
        complete: Every pose was solved in closed form (all its solutions).
        held: The parameter the IK held for a redundant arm (``"arm angle"``,
            ``"q1"``...), or None.
    """

    reached: IntArray
    solutions: IntArray
    manipulability: FloatArray
    complete: bool = True
    held: str | None = None


def solve_block(
    robot: Robot,
    centres: FloatArray,
    rotations: FloatArray | None,
    manipulability: bool,
    threads: int | None,
) -> Block:
    """Solve every pose of ``centres`` × ``rotations`` and reduce per voxel.

    Args:
        robot: The robot.
        centres: ``(v, 3)`` voxel centres (m, base frame).
        rotations: ``(N, 3, 3)`` tool orientations, or None for positions alone
            (any orientation; ``N = 1``).
        manipulability: Also the best manipulability per voxel.
        threads: Threads of the core's batch (None: the library default).

    Returns:
        The :class:`Block` of those voxels.
    """
    v = centres.shape[0]
    if rotations is None:
        targets = centres
        n_orient = 1
    else:
        n_orient = rotations.shape[0]
        targets = np.zeros((v, n_orient, 4, 4))
        targets[:, :, :3, :3] = rotations
        targets[:, :, :3, 3] = centres[:, None, :]
        targets[:, :, 3, 3] = 1.0
        targets = targets.reshape(v * n_orient, 4, 4)
    res = robot.ik(targets, workers=threads)
    assert isinstance(res, IKBatchResult)
    count = res.count.reshape(v, n_orient)
    reached = np.count_nonzero(count > 0, axis=1).astype(np.int32)
    solutions = count.sum(axis=1, dtype=np.int64).astype(np.int32)
    best = np.full(v, np.nan)
    if manipulability and bool(reached.any()):
        # Yoshikawa's w of the task rows (kinematica.motion.manipulability's), every
        # solution in one core call over the NaN-padded (v·N·k, n) array: the padding
        # comes out NaN and the maximum over a voxel's solutions skips it
        sol = res.solutions
        rows = selected_rows(robot, "task")
        w = robot.chain.volumes(sol.reshape(-1, sol.shape[-1]), rows, workers=threads)
        per_voxel = np.fmax.reduce(w.reshape(v, -1), axis=1)
        best = np.where(reached > 0, per_voxel, np.nan)
    complete = bool(res.complete) and not res.methods
    held = None if res.parameter is None else str(res.parameter[0])
    return Block(reached, solutions, best, complete, held)


def shares(count: int, per_block: int, dealt: bool, workers: int) -> list[slice]:
    """Where each call's voxels are among ``count``: runs of ``per_block``, or dealt.

    Args:
        count: Voxels to solve.
        per_block: Voxels in one block (one IK call).
        dealt: For Dask tasks: at least :data:`TASKS_PER_WORKER` a worker, each
            of at most :data:`MAX_BLOCKS` blocks, task ``t`` of ``T`` taking
            voxels ``t, t + T, ...`` (module docs); else consecutive blocks.
        workers: Worker processes.

    Returns:
        One slice of the voxels per call, together taking each voxel once.
    """
    if not dealt:
        return [slice(i, i + per_block) for i in range(0, count, per_block)]
    tasks = max(workers * TASKS_PER_WORKER, math.ceil(count / (MAX_BLOCKS * per_block)))
    tasks = max(1, min(tasks, count))
    return [slice(t, None, tasks) for t in range(tasks)]


def solve_blocks(
    robot: Robot,
    voxel_centres: Callable[[NDArray[np.intp]], FloatArray],
    voxels: NDArray[np.intp],
    rotations: FloatArray | None,
    *,
    manipulability: bool,
    threads: int | None,
    client: Any,
    workers: int,
    progress: Callable[[int], None] | None,
) -> tuple[IntArray, IntArray, FloatArray, Block]:
    """Every voxel of ``voxels``: here, or on the Dask ``client``'s workers.

    Args:
        robot: The robot.
        voxel_centres: Flat voxel indices -> ``(m, 3)`` centres.
        voxels: ``(V,)`` flat indices of the voxels to solve, ascending.
        rotations: ``(N, 3, 3)`` orientations, or None (positions).
        manipulability: Also the best manipulability.
        threads: Core threads per call (None: the library default; 1 on workers).
        client: A ``distributed.Client`` or None (this process).
        workers: Worker processes (sets how many blocks a cluster gets).
        progress: Called with the number of poses done after each block.

    Returns:
        ``(V,)`` reached orientations, solution counts, best manipulability, and
        an empty :class:`Block` holding ``complete`` and ``held`` over them all.
    """
    n_orient = 1 if rotations is None else rotations.shape[0]
    places = shares(voxels.size, max(1, CHUNK_QUERIES // n_orient), client is not None, workers)
    parts = [voxels[p] for p in places]
    reached = np.zeros(voxels.size, dtype=np.int32)
    solutions = np.zeros(voxels.size, dtype=np.int32)
    best = np.full(voxels.size, np.nan)
    how: dict[str, Any] = {"complete": True, "held": None}

    def store(i: int, block: Block) -> None:
        s = places[i]
        reached[s], solutions[s], best[s] = block.reached, block.solutions, block.manipulability
        how["complete"] = bool(how["complete"]) and block.complete
        how["held"] = how["held"] or block.held
        if progress is not None:
            progress(int(parts[i].size) * n_orient)

    if client is None:
        for i, part in enumerate(parts):
            store(i, solve_block(robot, voxel_centres(part), rotations, manipulability, threads))
        return reached, solutions, best, _summary(how)

    from dask.distributed import as_completed

    remote_robot, remote_rot = client.scatter([robot, rotations], broadcast=True)
    futures = [
        client.submit(
            _remote_block, remote_robot, voxel_centres(part), remote_rot, manipulability, pure=False
        )
        for part in parts
    ]
    index = {f.key: i for i, f in enumerate(futures)}
    for future in as_completed(futures):
        store(index[future.key], future.result())
    return reached, solutions, best, _summary(how)


def _summary(how: dict[str, Any]) -> Block:
    empty = np.zeros(0, dtype=np.int32)
    return Block(empty, empty, np.zeros(0), bool(how["complete"]), how["held"])


def _remote_block(
    robot: Robot, centres: FloatArray, rotations: FloatArray | None, manipulability: bool
) -> Block:
    """A block on a Dask worker: blocks of at most CHUNK_QUERIES poses, one core thread."""
    n_orient = 1 if rotations is None else rotations.shape[0]
    step = max(1, CHUNK_QUERIES // n_orient)
    pieces = [
        solve_block(robot, centres[i : i + step], rotations, manipulability, 1)
        for i in range(0, centres.shape[0], step)
    ]
    return Block(
        np.concatenate([p.reached for p in pieces]),
        np.concatenate([p.solutions for p in pieces]),
        np.concatenate([p.manipulability for p in pieces]),
        all(p.complete for p in pieces),
        next((p.held for p in pieces if p.held is not None), None),
    )
