"""The core from C++ alone: the PUMA example of examples/cpp, and every solver family.

``kinematica convert ROBOT --to cpp`` writes a header filling the core's solver for one
arm; a C++ program built on the core's headers then gives what ``robot.ik`` gives.
Skipped where no C++ compiler is installed.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest
from support import ROOT

import kinematica as km
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.structure import features
from kinematica.robot.export_cpp import cpp_header

CXX = shutil.which("c++") or shutil.which("g++") or shutil.which("clang++")
pytestmark = [
    pytest.mark.skipif(CXX is None, reason="no C++ compiler"),
    pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning"),
]
# Eigen's headers (PyPI's cmeel-eigen, a test and build requirement): the general 6R's
# header includes them; -isystem, as CMake gives them to the extension.
EIGEN = [
    str(Path(entry) / "cmeel.prefix" / "include" / "eigen3")
    for entry in sys.path
    if entry and (Path(entry) / "cmeel.prefix" / "include" / "eigen3").is_dir()
][:1]
WARNINGS = ["-Wall", "-Wextra", "-Werror"]
# -O0: the program of every family is the suite's longest test, and the compiler's front
# end takes most of it on the general 6R's Eigen decompositions (92 s in all on the 2-core
# VM in December 2026, a program of one other family 2 s; -O1 adds the optimiser's time
# on top); the answers are the same bits: -ffp-contract=off, as the extension is built
# (CMakeLists.txt), so that no optimisation level fuses a multiply-add.
FLAGS = [
    "-std=c++17",
    "-O0",
    "-ffp-contract=off",
    *WARNINGS,
    "-I",
    str(ROOT / "cpp" / "include"),
    *(flag for path in EIGEN for flag in ("-isystem", path)),
]


def _build(source: Path, include: Path, out: Path) -> None:
    assert CXX is not None
    done = subprocess.run(
        [CXX, *FLAGS, "-I", str(include), str(source), "-o", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-3000:]


@pytest.fixture(scope="module")
def docs_example(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    """The commands of docs/contributing.md's "From C++" run in a fresh folder, as written
    (the compiler line with warnings as errors added): the PUMA program and its output."""
    import re
    import shlex

    folder = tmp_path_factory.mktemp("docs_example")
    text = (ROOT / "docs" / "contributing.md").read_text()
    block = re.search(r"## From C\+\+.*?```sh\n(.*?)```", text, flags=re.S)
    assert block is not None
    exe = None
    for line in block.group(1).strip().splitlines():
        args = shlex.split(line)
        if args[0].endswith("kinematica"):
            args = [sys.executable, "-m", "kinematica", *args[1:]]
        elif args[0] == "c++":
            args = [
                CXX or "c++",
                *(str(ROOT / a) if a.startswith(("cpp/", "examples/")) else a for a in args[1:]),
                *WARNINGS,
            ]
            exe = folder / args[args.index("-o") + 1]
        done = subprocess.run(args, cwd=folder, capture_output=True, text=True, check=False)
        assert done.returncode == 0, done.stderr[-2000:]
    assert exe is not None and exe.exists()
    return exe, done.stdout


def test_the_docs_commands_build_and_run_the_example(docs_example: tuple[Path, str]) -> None:
    assert "status 0" in docs_example[1]


def test_the_puma_example_gives_what_robot_ik_gives(docs_example: tuple[Path, str]) -> None:
    exe = docs_example[0]
    robot = km.load("puma560")
    for q in ([0.1, -0.5, 0.3, 0.7, 0.4, -0.2], [1.2, 0.4, -0.9, -2.0, 1.1, 2.5]):
        out = subprocess.run([str(exe), *map(repr, q)], capture_output=True, text=True, check=False)
        lines = out.stdout.splitlines()
        T = np.array([[float(v) for v in line.split()] for line in lines[1:4]])
        np.testing.assert_allclose(T, robot.fk(np.array(q))[:3], atol=1e-9)
        res = robot.ik(robot.fk(np.array(q)))
        assert lines[4].startswith(
            f"status 0, {res.count} solutions ({res.out_of_limits.shape[0]} "
        )
        rows = lines[5:]
        assert [r[:44].strip() for r in rows] == list(res.branches)
        got = np.array([[float(v) for v in r[44:].split()[:6]] for r in rows])
        np.testing.assert_allclose(got, res.solutions, atol=1e-8)


# A program solving one pose per argument line with every family's header (one build).
_MAIN = """
#include <cstdio>
#include <vector>
#include "kinematica/ik.hpp"
{includes}

template <class P>
void solve(const km::Chain& chain, const P& params, const double* rows) {{
    const km::ClosedForm<P> solver{{params}};
    const int m = solver.slots(), n = chain.dof();
    km::IKWork<km::ClosedForm<P>> work(solver, n);
    km::CheckOptions options;
    options.complete = true;
    std::vector<double> Q(m * n), res(2 * m);
    std::vector<int> slot(m);
    const km::CheckOut out{{Q.data(), slot.data(), res.data()}};
    const km::CheckReport r =
        km::solve_ik(solver, chain.view(), km::Pose::from_rows(rows), options, nullptr, work, out);
    std::printf("%d %d %d", static_cast<int>(r.status), r.count, r.out_count);
    for (int k = 0; k < (r.count + r.out_count) * n; ++k) std::printf(" %.17g", Q[k]);
    std::printf("\\n");
}}

int main() {{
    double T[16];
    int which;
    while (std::scanf("%d", &which) == 1) {{
        for (double& v : T) std::scanf("%lf", &v);
        switch (which) {{
{cases}
        }}
    }}
}}
"""


def _exportable(robot: km.Robot) -> bool:
    try:
        cpp_header(robot)
    except km.KinematicaError:
        return False
    return True


def test_every_family_solves_in_cpp_as_in_python(tmp_path: Path) -> None:
    robots = []
    extra: dict[int, dict[str, float]] = {}
    families = [(s, deg) for s in SOLVERS if "pose" in s.targets for deg in (False, True)]
    for k, (spec, degenerate) in enumerate(families):
        rng = np.random.default_rng(zlib.crc32(f"{spec.kind}/{degenerate}".encode()))
        # What the header is compared on: an arm its family's solver is built for (that
        # every sampled arm gets one is tests/ik/test_registry.py's and test_audit.py's to
        # hold), and not one near its family only (its candidates are repaired in Python).
        while True:
            arm = spec.sample_arm(rng, degenerate)
            robot = km.Robot.from_dh(
                arm.links, convention=arm.convention, base=arm.base, tool=arm.tool
            )
            if not features(robot.chain).near_degenerate and _exportable(robot):
                break
        (tmp_path / f"arm{k}.hpp").write_text(cpp_header(robot, namespace=f"arm{k}"))
        robots.append((k, robot, rng))
        if spec.parameter is not None:  # the header's solver is at the parameter 0
            extra[k] = {spec.parameter: 0.0}
    rng = np.random.default_rng(5)
    for k, name in enumerate(("ur5_robot.urdf", "kuka_kr16_2.urdf"), start=len(families)):
        robot = km.load(
            ROOT / "tests" / "data" / "urdf" / name, tip="tool0"
        )  # the file's transforms
        (tmp_path / f"arm{k}.hpp").write_text(cpp_header(robot, namespace=f"arm{k}"))
        robots.append((k, robot, rng))
    includes = "\n".join(f'#include "arm{k}.hpp"' for k, _, _ in robots)
    cases = "\n".join(
        f"            case {k}: solve(arm{k}::chain(), arm{k}::solver(), T); break;"
        for k, _, _ in robots
    )
    (tmp_path / "main.cpp").write_text(_MAIN.format(includes=includes, cases=cases))
    exe = tmp_path / "families"
    _build(tmp_path / "main.cpp", tmp_path, exe)
    lines, expected = [], []
    for k, robot, rng in robots:
        lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
        lo, hi = np.where(np.isfinite(lo), lo, -1.0), np.where(np.isfinite(hi), hi, 1.0)
        for q in rng.uniform(lo, hi, (5, robot.dof)):
            T = robot.fk(q)
            lines.append(f"{k} " + " ".join(repr(float(v)) for v in T.ravel()))
            expected.append(robot.ik(T, **extra.get(k, {})))
    out = subprocess.run(
        [str(exe)], input="\n".join(lines) + "\n", capture_output=True, text=True, check=True
    )
    for line, res in zip(out.stdout.splitlines(), expected, strict=True):
        status, count, outside, *values = line.split()
        assert int(count) == res.count and int(outside) == res.out_of_limits.shape[0]
        rows = np.array(values, dtype=float).reshape(-1, res.solutions.shape[1] if res.count else 1)
        both = np.concatenate([res.solutions, res.out_of_limits]).reshape(rows.shape)
        np.testing.assert_array_equal(rows, both)  # the same code: the same bits
        assert km.ik.status.STATUS_NAMES[int(status)] == res.status
