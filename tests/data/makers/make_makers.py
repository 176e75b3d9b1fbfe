"""Regenerate the makers' arms (``*.urdf``) and ``ssik_reference.json`` from ssik 8.2.0.

ssik (https://pypi.org/project/ssik/, BSD-3-Clause) ships one generated module
per maker's arm, ``ssik.prebuilt.<maker>.<arm>_ik``, with the arm's geometry as
numbers: per joint ``T_left`` (4x4), a unit axis, ``T_right`` (4x4), its type
and limits (``None``: continuous), the base and tip link names and
``T_HOME`` (the forward kinematics at q = 0). Its forward kinematics is
``T_left[0] Rot(axis[0], q[0]) T_right[0] ... T_left[n-1] Rot(axis[n-1], q[n-1])
T_right[n-1]``; this script checks that convention against ssik's ``fk`` and
``T_HOME`` before it writes anything. Only those numbers are taken, and ssik's
IK solutions as numbers; none of ssik's code.

What it writes, in this folder:

- ``<maker>_<arm>.urdf`` for each of the 72 arms: joint ``i``'s origin is
  ``T_right[i-1] T_left[i]`` (in ssik 8.2.0 every ``T_right`` but the last is
  the identity, so the origin is ``T_left[i]`` itself), written as ``xyz`` and
  an ``rpy`` that reproduces the rotation to round-off; its axis is ssik's;
  the last ``T_right``, when it is not the identity, is a fixed joint to the
  tip link. Link names are ssik's (``_poe_link_k`` are ssik's names for the
  frames between joints).
- ``ssik_reference.json``: per arm its ssik module, solver (``SOLVER_NAME``)
  and dof; for each 6-joint arm, 20 configurations ``q_gen`` drawn uniformly
  within the joint limits (continuous joints: within [-pi, pi]) from
  ``numpy.random.default_rng([SEED, crc32(arm)])``, their poses ``T`` as
  kinematica's forward kinematics of the URDF computes them, and ssik's
  solutions of each pose from its default ``solve(T)`` (``ssik``). That default
  returns every copy of a solution shifted by 2 pi that stays within the limits
  (256 for a UR5 pose); the file keeps one representative per class modulo 2 pi
  (the first ssik returned, its numbers as returned) and the count ssik returned
  (``ssik_count``). Apart (``ssik_beyond_limits``), the further classes its
  ``solve(T, respect_limits=False)`` finds. Per arm also: where ssik's manifest
  says the description came from (``upstream``), ``T_HOME``, and the largest
  difference between our FK and ssik's ``fk`` over q = 0 and 50 random
  configurations (``fk_max_diff``; the script stops if it exceeds 1e-12).

Run it from the repository root with kinematica's venv and the ssik venv's
packages (ssik, and cython's pure-Python shadow module it imports; numpy, scipy
and sympy are the same versions in both venvs)::

    python3 -m venv /tmp/ssikvenv
    /tmp/ssikvenv/bin/pip install ssik==8.2.0 numpy
    PYTHONPATH=/tmp/ssikvenv/lib/python3.11/site-packages \\
        .venv/bin/python tests/data/makers/make_makers.py

The test suite (tests/robot/test_makers_ik.py) reads the files; it never
needs ssik.
"""

from __future__ import annotations

import importlib
import json
import math
import pkgutil
import sys
import tomllib
import warnings
import zlib
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

import kinematica as km

HERE = Path(__file__).resolve().parent
REFERENCE = HERE / "ssik_reference.json"
#: The ssik release the data come from.
SSIK_VERSION = "8.2.0"
#: Seed of the configurations (each arm's generator also takes its name's crc32).
SEED = 20260601
#: Poses per 6-joint arm.
POSES = 20
#: Random configurations of the FK comparison with ssik.
FK_SAMPLES = 50
#: Largest entry difference allowed between our FK and ssik's.
FK_TOL = 1e-12
#: Two solutions closer than this (rad, each joint, modulo 2 pi) are one.
SAME_TOL = 1e-9


def arm_modules() -> list[tuple[str, ModuleType]]:
    """Every prebuilt ssik arm as ``(maker_arm, module)``, sorted by name."""
    import ssik
    import ssik.prebuilt

    if ssik.__version__ != SSIK_VERSION:
        sys.exit(f"ssik {SSIK_VERSION} expected, found {ssik.__version__}")
    out = []
    for maker in pkgutil.iter_modules(ssik.prebuilt.__path__):
        if not maker.ispkg:
            continue
        package = importlib.import_module(f"ssik.prebuilt.{maker.name}")
        for mod in pkgutil.iter_modules(package.__path__):
            if mod.name.endswith("_ik"):
                module = importlib.import_module(f"ssik.prebuilt.{maker.name}.{mod.name}")
                out.append((f"{maker.name}_{mod.name[:-3]}", module))
    return sorted(out, key=lambda item: item[0])


def upstream(m: ModuleType) -> str:
    """Where ssik's MANIFEST.toml says the arm's description came from (its fixture_source)."""
    import ssik.prebuilt

    manifest = tomllib.loads((Path(ssik.prebuilt.__file__).parent / "MANIFEST.toml").read_text())
    _, _, vendor, stem = m.__name__.split(".")
    arms = {k: e for k, e in manifest["arms"].items() if e.get("vendor") == vendor}
    # the manifest's key is the module's name, or it with the maker's name before it
    found = [arms[stem]] if stem in arms else [e for k, e in arms.items() if k.endswith(f"_{stem}")]
    assert len(found) == 1, m.__name__
    return str(found[0]["fixture_source"])


def num(x: float) -> str:
    """A float as the shortest text that reads back to it (``1`` for 1.0, 0 for both zeros)."""
    x = float(x)
    text = "0" if x == 0.0 else repr(x)
    return text[:-2] if text.endswith(".0") else text


def rot_axis(axis: np.ndarray, q: float) -> np.ndarray:
    """The 4x4 rotation by ``q`` about the unit ``axis`` (Rodrigues)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    out = np.eye(4)
    out[:3, :3] = np.eye(3) + math.sin(q) * k + (1.0 - math.cos(q)) * (k @ k)
    return out


def rpy_matrix(r: float, p: float, y: float) -> np.ndarray:
    """URDF's rotation of ``rpy``: ``Rz(y) Ry(p) Rx(r)``."""
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
    return rz @ ry @ rx


def rpy_of(R: np.ndarray) -> tuple[float, float, float]:
    """Roll, pitch, yaw with ``Rz(yaw) Ry(pitch) Rx(roll) = R``, to round-off everywhere.

    The yaw comes from the first column; ``M = Rz(yaw)^T R = Ry(pitch) Rx(roll)``
    then gives the pitch from its first column and the roll from its second row,
    neither divided by cos(pitch): exact near pitch = ±pi/2 too (where the yaw is
    free and comes out 0 or whatever the round-off of the column says; M absorbs it).
    """
    yaw = math.atan2(R[1, 0], R[0, 0])
    cy, sy = math.cos(yaw), math.sin(yaw)
    M = np.array([[cy, sy, 0.0], [-sy, cy, 0.0], [0.0, 0.0, 1.0]]) @ R
    pitch = math.atan2(-M[2, 0], M[0, 0])
    roll = math.atan2(-M[1, 2], M[1, 1])
    return roll, pitch, yaw


def origin_xml(T: np.ndarray) -> tuple[str, float]:
    """``<origin .../>`` of a 4x4 transform and its rotation's reconstruction error."""
    rpy = rpy_of(T[:3, :3])
    err = float(np.abs(rpy_matrix(*rpy) - T[:3, :3]).max())
    xyz = " ".join(num(v) for v in T[:3, 3])
    return f'<origin xyz="{xyz}" rpy="{" ".join(num(v) for v in rpy)}"/>', err


def ssik_fk(m: ModuleType, q: np.ndarray) -> np.ndarray:
    """ssik's chain composed in numpy: ``T_left Rot(axis, q) T_right`` per joint."""
    T = np.eye(4)
    for i in range(m.DOF):
        assert m._JOINT_TYPES[i] == "revolute"  # ssik 8.2.0's arms have no prismatic joint
        turn = rot_axis(np.asarray(m._JOINT_AXES[i]), q[i])
        T = T @ m._JOINT_T_LEFTS[i] @ turn @ m._JOINT_T_RIGHTS[i]
    return T


def limits(m: ModuleType) -> np.ndarray:
    """``(n, 2)`` joint limits; a continuous joint (``None``) gets [-pi, pi]."""
    return np.array([(-math.pi, math.pi) if lim is None else lim for lim in m._JOINT_LIMITS], float)


def urdf_text(name: str, m: ModuleType) -> tuple[str, float]:
    """The URDF of an ssik arm and the largest rpy reconstruction error in it."""
    n = m.DOF
    eye = np.eye(4)
    last_right = np.asarray(m._JOINT_T_RIGHTS[-1])
    tool = not np.array_equal(last_right, eye)
    links = list(m._LINK_NAMES[:n]) + ([f"_poe_link_{n}", m.EE_LINK] if tool else [m.EE_LINK])
    assert links[0] == m.BASE_LINK and len(set(links)) == len(links), name
    module = m.__name__.split(".", 2)[2]
    lines = [
        '<?xml version="1.0"?>',
        f"<!-- {name}: the geometry of ssik {SSIK_VERSION}'s ssik.prebuilt.{module}"
        " (BSD-3-Clause), written by make_makers.py; see PROVENANCE.md. -->",
        f'<robot name="{name}">',
        *(f'  <link name="{link}"/>' for link in links),
    ]
    worst = 0.0
    before = eye
    for i in range(n):
        origin, err = origin_xml(before @ np.asarray(m._JOINT_T_LEFTS[i]))
        worst = max(worst, err)
        axis = " ".join(num(v) for v in m._JOINT_AXES[i])
        lim = m._JOINT_LIMITS[i]
        kind = "continuous" if lim is None else "revolute"
        lines += [
            f'  <joint name="{m._JOINT_NAMES[i]}" type="{kind}">',
            f'    <parent link="{links[i]}"/>',
            f'    <child link="{links[i + 1]}"/>',
            f"    {origin}",
            f'    <axis xyz="{axis}"/>',
        ]
        if lim is not None:
            lines.append(
                f'    <limit lower="{num(lim[0])}" upper="{num(lim[1])}" effort="0" velocity="0"/>'
            )
        lines.append("  </joint>")
        before = np.asarray(m._JOINT_T_RIGHTS[i])
    if tool:
        origin, err = origin_xml(last_right)
        worst = max(worst, err)
        joint = f"{m.EE_LINK}_fixed"
        assert joint not in m._JOINT_NAMES, name
        lines += [
            f'  <joint name="{joint}" type="fixed">',
            f'    <parent link="{links[n]}"/>',
            f'    <child link="{m.EE_LINK}"/>',
            f"    {origin}",
            "  </joint>",
        ]
    lines.append("</robot>")
    return "\n".join(lines) + "\n", worst


def wrap(a: np.ndarray) -> np.ndarray:
    """Angles into [-pi, pi)."""
    return (np.asarray(a) + math.pi) % (2.0 * math.pi) - math.pi


def distinct(qs: list[np.ndarray]) -> list[np.ndarray]:
    """One representative (the first) per class of solutions modulo 2 pi."""
    reps: list[np.ndarray] = []
    for q in qs:
        if not any(np.abs(wrap(q - r)).max() < SAME_TOL for r in reps):
            reps.append(q)
    return reps


def reference(name: str, m: ModuleType, robot: km.Robot) -> dict[str, Any]:
    """The reference of one 6-joint arm: q_gen, T and ssik's solutions."""
    rng = np.random.default_rng([SEED, zlib.crc32(name.encode())])
    lim = limits(m)
    q_gen = rng.uniform(lim[:, 0], lim[:, 1], (POSES, m.DOF))
    T = robot.fk(q_gen)
    sols, beyond, counts, raw, missed, refined = [], [], [], [], 0, 0
    for qg, target in zip(q_gen, T, strict=True):
        found = m.solve(target)
        unlimited = m.solve(target, respect_limits=False)
        counts.append(len(found))
        refined += sum(s.refinement_used != "none" for s in [*found, *unlimited])
        reps = distinct([np.asarray(s.q, float) for s in found])
        every = distinct(reps + [np.asarray(s.q, float) for s in unlimited])
        raw.append(len(every))
        missed += not any(np.abs(wrap(r - qg)).max() < 1e-6 for r in reps)
        sols.append([[float(v) for v in r] for r in reps])
        beyond.append([[float(v) for v in r] for r in every[len(reps) :]])
    return {
        "ssik_mean_count": float(np.mean(counts)),
        "ssik_mean_distinct": float(np.mean([len(s) for s in sols])),
        "ssik_mean_unlimited": float(np.mean(raw)),
        "ssik_missed_q_gen": missed,
        "ssik_refined": refined,
        "q_gen": q_gen.tolist(),
        "T": T.tolist(),
        "ssik_count": counts,
        "ssik": sols,
        "ssik_beyond_limits": beyond,
    }


def main() -> None:
    """Write the URDFs and the reference, checking FK against ssik's on the way."""
    arms = []
    for name, m in arm_modules():
        text, rpy_err = urdf_text(name, m)
        path = HERE / f"{name}.urdf"
        path.write_text(text)
        robot = km.load(path)
        assert robot.dof == m.DOF and tuple(robot.joint_names) == tuple(m._JOINT_NAMES), name
        rng = np.random.default_rng([SEED, zlib.crc32(name.encode()), 1])
        lim = limits(m)
        qs = np.vstack([np.zeros(m.DOF), rng.uniform(lim[:, 0], lim[:, 1], (FK_SAMPLES, m.DOF))])
        with warnings.catch_warnings():  # q = 0 is outside some arms' limits
            warnings.simplefilter("ignore", km.KinematicaWarning)
            ours = robot.fk(qs)
        theirs = np.array([m.fk(q) for q in qs])
        composed = np.array([ssik_fk(m, q) for q in qs])
        fk_diff = float(np.abs(ours - theirs).max())
        convention = float(np.abs(composed - theirs).max())
        home = float(np.abs(ours[0] - m.T_HOME).max())
        print(
            f"{name:32s} dof {m.DOF}  {m.SOLVER_NAME:36s} rpy {rpy_err:.1e}  "
            f"FK vs ssik {fk_diff:.1e}  T_left Rot T_right vs ssik {convention:.1e}  "
            f"T_HOME {home:.1e}",
            flush=True,
        )
        assert max(fk_diff, convention, home) <= FK_TOL, name
        arm: dict[str, Any] = {
            "arm": name,
            "urdf": path.name,
            "module": m.__name__,
            "dof": m.DOF,
            "solver": m.SOLVER_NAME,
            "upstream": upstream(m),
            "T_home": np.asarray(m.T_HOME).tolist(),
            "fk_max_diff": fk_diff,
        }
        if m.DOF == 6:
            arm.update(reference(name, m, robot))
            print(
                f"{'':32s} ssik solutions per pose {arm['ssik_mean_count']:.1f} "
                f"({arm['ssik_mean_distinct']:.2f} distinct mod 2pi; "
                f"{arm['ssik_mean_unlimited']:.2f} without limits), "
                f"q_gen missed {arm['ssik_missed_q_gen']}, refined {arm['ssik_refined']}",
                flush=True,
            )
        arms.append(arm)
    meta = {
        "source": f"ssik {SSIK_VERSION} (PyPI, BSD-3-Clause): ssik.prebuilt.<maker>.<arm>_ik",
        "made_by": "tests/data/makers/make_makers.py",
        "seed": SEED,
        "poses": POSES,
        "same_tol": SAME_TOL,
        "fk_tol": FK_TOL,
    }
    body = ",\n".join(json.dumps(a, separators=(",", ":")) for a in arms)
    REFERENCE.write_text(f'{{"meta":{json.dumps(meta)},\n"arms":[\n{body}\n]}}\n')
    print(f"{len(arms)} arms; {REFERENCE.name}: {REFERENCE.stat().st_size / 1e6:.2f} MB")


if __name__ == "__main__":
    main()
