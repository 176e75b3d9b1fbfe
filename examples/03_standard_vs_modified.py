"""Standard (Paul) and modified (Craig) DH tables of one arm give the same T.

Seed 001: the intermediate frames differ, the end result is the same.
"""

from __future__ import annotations

import numpy as np

import kinematica as km


def main() -> None:
    puma = km.load("puma560")
    craig = puma.to_convention("modified")
    print(f"{puma.name}: standard table (theta offset, d, a, alpha) at q = 0")
    print(np.array2string(puma.dh_table(), precision=4, suppress_small=True))
    print("modified table (theta offset, d, a(i-1), alpha(i-1)) at q = 0")
    print(np.array2string(craig.dh_table(), precision=4, suppress_small=True))
    print(
        "tool added by the conversion:\n",
        np.array2string(craig.tool, precision=4, suppress_small=True),
    )

    q = np.random.default_rng(1).uniform(-np.pi, np.pi, (1000, 6))
    diff = np.abs(puma.fk(q) - craig.fk(q)).max()
    print(f"max |T_standard - T_modified| over 1000 configurations: {diff:.1e}")
    assert diff < 1e-12

    # Intermediate frames differ: frame 3 of each convention sits elsewhere.
    f_std = puma.fk(q[0], all_frames=True)
    f_mod = craig.fk(q[0], all_frames=True)
    print(
        "origin of frame 3, standard:",
        f_std[3, :3, 3].round(4),
        " modified:",
        f_mod[3, :3, 3].round(4),
    )


if __name__ == "__main__":
    main()
