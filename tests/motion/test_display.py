"""Trajectories and Cartesian paths show as HTML tables in a notebook."""

from __future__ import annotations

import html

import numpy as np
from support.helpers import table_cells as _cells

import kinematica as km


def test_a_trajectory_shows_evenly_spaced_samples_from_start_to_end() -> None:
    from kinematica.motion.display import SAMPLES_SHOWN

    traj = km.joint_trajectory([0.0, 0.0], [1.0, -0.5], 2.0, "quintic", dt=0.01)
    rows = _cells(traj._repr_html_())
    assert rows[0] == ["sample", "t (s)", "q1", "q2"]
    assert len(rows) == 1 + SAMPLES_SHOWN
    assert rows[1][1:] == ["0", "0", "0"] and rows[-1][1:] == ["2", "1", "−0.5"]
    assert rows[-1][0] == str(len(traj.t) - 1)
    short = km.joint_trajectory([0.0], [1.0], 0.05, "cubic", dt=0.01)
    assert len(_cells(short._repr_html_())) == 1 + len(short.t)  # every sample when few


def test_a_cartesian_path_lists_its_events() -> None:
    from kinematica.motion import cartesian_path

    puma = km.load("puma560")
    q_mid = np.radians([20, -30, 40, 10, 0, 0])  # wrist singular
    T = puma.fk(q_mid)
    T0, T1 = T.copy(), T.copy()
    T0[:3, 3] -= [0, 0.1, 0.05]
    T1[:3, 3] += [0, 0.1, 0.05]
    path = cartesian_path(puma, T0, T1, steps=41, q0=q_mid)
    text = path._repr_html_()
    assert path.events and all(html.escape(e.message) in text for e in path.events)
    k = len(path.events)
    assert (f"{k} events" if k > 1 else "1 event (") in text
