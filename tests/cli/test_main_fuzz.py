"""A catalogue of hostile arguments and robot files, run through the command line.

Every case must end (no hang: an alarm in-process, a timeout for the console
script), exit with 0, 1 or 2, print no traceback and no internal error, put
only ``kinematica...`` lines on stderr (one error line at most, safe to print),
and print valid JSON (no NaN, no Infinity) whenever ``--json`` was asked and
the command answered. Most cases run ``main([...])`` in-process; a handful run
the installed console script.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from types import FrameType
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import kinematica as km
from kinematica.cli.main import main

SCRIPT = Path(sys.executable).with_name("kinematica")

#: Seconds a case may take in-process before it counts as a hang.
HANG = 60

Z6 = ["0"] * 6
#: The identity rotation 1e300 m away, and a reflection: 16 numbers for --matrix.
FAR = ["1", "0", "0", "1e300", "0", "1", "0", "0", "0", "0", "1", "0", "0", "0", "0", "1"]
MIRROR = ["-1", "0", "0", "0", "0", "1", "0", "0", "0", "0", "1", "0", "0", "0", "0", "1"]


# --- hostile files ---------------------------------------------------------------------

_ROW = '{"theta": "q1", "d": 0, "a": 1, "alpha": 0}'


def _write_files(folder: Path) -> dict[str, str]:
    """Create the hostile robot files; returns name -> path."""
    files: dict[str, str] = {}

    def put(name: str, content: bytes | str) -> None:
        path = folder / name
        path.write_bytes(content if isinstance(content, bytes) else content.encode())
        files[name] = str(path)

    put("binary.yaml", bytes(range(256)) * 4)
    put("binary.json", b"\x00\xff\xfe" * 100)
    put("binary.toml", b"\x89PNG\r\n\x1a\n" + bytes(200))
    put("empty.yaml", b"")
    put("empty.json", b"")
    put("empty.toml", b"")
    put("blank.json", "   \n\t\n")
    put("deep.json", "[" * 100_000 + "]" * 100_000)
    put("deep.yaml", "[" * 50_000 + "]" * 50_000)
    put("deep.toml", "a = " + "[" * 10_000 + "]" * 10_000)
    put("deep_map.yaml", "".join(" " * i + f"k{i}:\n" for i in range(300)))
    put(
        "bomb.yaml",
        "name: &a [x, x, x, x, x, x, x, x, x]\n"
        + "".join(
            f"{k}: &{k} [*{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}]\n"
            for p, k in zip("abcdefgh", "bcdefghi", strict=True)
        ),
    )
    put("bomb_joints.yaml", "convention: standard\njoints: &j [*j]\n")
    put("string.json", '"robot"')
    put("list.yaml", "- theta: q1\n")
    put("number.toml", "joints = 3\nconvention = 1\n")
    put("nan.yaml", "convention: standard\njoints:\n  - {theta: q1, d: .nan, a: .inf, alpha: 0}\n")
    put("inf.json", '{"convention": "standard", "joints": [{"theta": "q1", "d": 1e400, '
        '"a": 0, "alpha": 0}]}')  # fmt: skip
    put("bigint.yaml", "convention: standard\njoints:\n  - {theta: q1, d: " + "9" * 5000 + ", "
        "a: 0, alpha: 0}\n")  # fmt: skip
    put("latin1.yaml", "name: Brazo rob\xf3tico\n".encode("latin-1"))
    put("crlf.yaml", "convention: standard\r\njoints:\r\n  - {theta: q1, d: 0, a: 1, alpha: 0}\r\n")
    bom_json = '{"convention": "standard", "joints": [' + _ROW + "]}"
    put("bom.json", b"\xef\xbb\xbf" + bom_json.encode())
    put(
        "evil.json",
        json.dumps(
            {
                "name": "\x1b[2J\x1b[31mred\nline\u202e\x07",
                "description": "\r\x1b]0;title\x07",
                "convention": "standard",
                "joints": [{"theta": "q1", "d": 0, "a": 1, "alpha": 0, "name": "\x1b[1m"}],
            }
        ),
    )
    put("unicode.yaml", "name: 機械腕 🤖\nconvention: standard\njoints:\n  - {théta: q1}\n")
    put("long_expr.yaml", "convention: standard\njoints:\n  - {theta: '" + "q1" + " + 1" * 1000
        + "', d: 0, a: 1, alpha: 0}\n")  # fmt: skip
    put("deep_expr.json", json.dumps({"convention": "standard", "joints": [
        {"theta": "(" * 500 + "q1" + ")" * 500, "d": 0, "a": 1, "alpha": 0}]}))  # fmt: skip
    put("snake.json", json.dumps({"convention": "standard", "joints": [
        {"theta": f"q{i}", "d": 0, "a": 0.01, "alpha": 0} for i in range(1, 20_001)]}))  # fmt: skip
    put("huge_values.json", json.dumps({"convention": "standard", "joints": [
        {"theta": "q1", "d": 1e300, "a": 1e300, "alpha": 0},
        {"theta": "q2", "d": 0, "a": 1e300, "alpha": 0}]}))  # fmt: skip
    put("tiny_values.json", json.dumps({"convention": "standard", "joints": [
        {"theta": "q1", "d": 1e-300, "a": 1e-300, "alpha": 0},
        {"theta": "q2", "d": 0, "a": 5e-324, "alpha": 0}]}))  # fmt: skip
    put("radians_typo.yaml", "convention: standard\nunits: {angle: rad}\njoints:\n"
        "  - {theta: q1, d: 300, a: 0, alpha: 90, limits: [-170, 170]}\n")  # fmt: skip
    put("wrong.urdf", "<robot/>")
    put("noext", "convention: standard")
    big = folder / "big.yaml"
    with big.open("wb") as f:
        f.truncate(50_000_000)  # sparse
    files["big.yaml"] = str(big)
    (folder / "dir.yaml").mkdir()
    files["dir.yaml"] = str(folder / "dir.yaml")
    if hasattr(os, "mkfifo"):
        os.mkfifo(folder / "fifo.yaml")
        files["fifo.yaml"] = str(folder / "fifo.yaml")
    if Path("/dev/zero").exists():
        (folder / "zero.yaml").symlink_to("/dev/zero")
        files["zero.yaml"] = str(folder / "zero.yaml")
    (folder / "dangling.yaml").symlink_to(folder / "nowhere.yaml")
    files["dangling.yaml"] = str(folder / "dangling.yaml")
    put("\x1b[31mansi name.yaml", "convention: standard\njoints: []\n")
    return files


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    return _write_files(tmp_path_factory.mktemp("hostile"))


FILE_CASES = [
    "binary.yaml", "binary.json", "binary.toml", "empty.yaml", "empty.json", "empty.toml",
    "blank.json", "deep.json", "deep.yaml", "deep.toml", "deep_map.yaml", "bomb.yaml",
    "bomb_joints.yaml", "string.json", "list.yaml", "number.toml", "nan.yaml", "inf.json",
    "bigint.yaml", "latin1.yaml", "crlf.yaml", "bom.json", "evil.json", "unicode.yaml",
    "long_expr.yaml", "deep_expr.json", "snake.json", "huge_values.json", "tiny_values.json",
    "radians_typo.yaml", "wrong.urdf", "noext", "big.yaml", "dir.yaml", "fifo.yaml",
    "zero.yaml", "dangling.yaml", "\x1b[31mansi name.yaml",
]  # fmt: skip

#: Files that are valid robots (the command answers); the others are refused.
VALID = {"crlf.yaml", "bom.json", "evil.json", "huge_values.json", "tiny_values.json",
         "radians_typo.yaml"}  # fmt: skip


# --- hostile arguments ------------------------------------------------------------------

ARG_CASES: list[tuple[str, ...]] = [
    (),
    ("--help",),
    ("--version",),
    ("nonsense",),
    ("fk",),
    ("fk", "--help"),
    ("fk", "puma560"),
    ("fk", "puma560", "--q"),
    ("fk", "puma560", "--q", *["0"] * 1000),
    ("fk", "puma560", "--q", "1e308", "-1e308", "1e308", "0", "0", "0", "--json"),
    ("fk", "puma560", "--q", "1e309", *["0"] * 5),
    ("fk", "puma560", "--q", "0", "-inf", "0", "0", "0", "0", "--json"),
    ("fk", "puma560", "--q", "nan", *["0"] * 5),
    ("fk", "puma560", "--q", "0x10", *["0"] * 5),
    ("fk", "puma560", "--q", "1_0", "１２", *["0"] * 4, "--json"),
    ("fk", "puma560", "--q", "--", *["0"] * 6),
    ("fk", "puma560", "--q", *Z6, "--euler", ""),
    ("fk", "puma560", "--q", *Z6, "--euler", "ZYQ"),
    ("fk", "puma560", "--q", *Z6, "--euler", "zYz"),
    ("fk", "puma560", "--q", *Z6, "--euler", "XYZZ"),
    ("fk", "puma560", "--q", *Z6, "--euler", "\x1b[31m"),
    ("fk", "puma560", "--q", *Z6, "--euler", "ZZY"),
    ("fk", "puma560", "--q", *Z6, "--euler", "ZYZ\u0301"),
    ("fk", "puma560", "--q", *Z6, "--precision", "0"),
    ("fk", "puma560", "--q", *Z6, "--precision", "17", "--frames"),
    ("fk", "puma560", "--q", *Z6, "--units", "km"),
    ("fk", "puma560", "--q", *Z6, "--frames", "--json", "--rad", "--euler", "xyz", "--units", "mm"),
    ("fk", "stanford", "--q", "0", "0", "1e300", "0", "0", "0", "--json"),
    ("fk", "stanford", "--q", "0", "0", "1e306", "0", "0", "0", "--units", "mm", "--json"),
    ("fk", "puma560", "--q", *["1e15"] * 6, "--json"),
    ("fk", "panda", "--q", *["1e300"] * 7, "--rad", "--frames"),
    ("fk", "no-such-robot", "--q", "0"),
    ("fk", "PUMA_560", "--q", *Z6),
    ("fk", "", "--q", "0"),
    ("fk", " ", "--q", "0"),
    ("fk", "-", "--q", "0"),
    ("fk", ".", "--q", "0"),
    ("fk", "..", "--q", "0"),
    ("fk", "/", "--q", "0"),
    ("fk", "~", "--q", "0"),
    ("fk", "/nonexistent/dir/robot.yaml", "--q", "0"),
    ("fk", "x" * 5000, "--q", "0"),
    ("fk", "a\x00b.yaml", "--q", "0"),
    ("fk", "\x1b[31mred", "--q", "0"),
    ("show", "puma560", "--json", "--units", "mm", "--rad"),
    ("show", "stanford", "--euler", "xyz"),
    ("robots", "--json"),
    ("robots", "extra"),
    ("ik", "puma560"),
    ("ik", "puma560", "--pose", "1", "2"),
    ("ik", "puma560", "--pose", *Z6, "--matrix", *["0"] * 16),
    ("ik", "puma560", "--pose", "1e300", "0", "0", "0", "0", "0", "--json"),
    ("ik", "puma560", "--pose", "1.4e154", "0", "0", "0", "0", "0"),
    ("ik", "irb120", "--pose", "1e300", "1e300", "1e300", "0", "0", "0", "--json"),
    ("ik", "ur5", "--pose", "1e300", "0", "0", "0", "0", "0"),
    ("ik", "ur5", "--pose", "-1e300", "1e300", "0", "1e300", "0", "0", "--json"),
    ("ik", "panda", "--pose", "1e300", "0", "0", "0", "0", "0", "--json"),
    ("ik", "stanford", "--pose", "1e300", "0", "0", "0", "0", "0", "--json"),
    ("ik", "scara", "--position", "1e300", "0", "0", "--json"),
    ("ik", "anthropomorphic-3r", "--position", "1e-300", "0", "0", "--json"),
    ("ik", "planar-pr", "--position", "1", "2", "3", "--json"),
    ("ik", "planar-3r", "--pose", "1", "0", "0", "0", "0", "0", "--json"),
    ("ik", "puma560", "--matrix", *["0"] * 16),
    ("ik", "puma560", "--matrix", *["1e300"] * 16),
    ("ik", "puma560", "--matrix", *FAR, "--json"),
    ("ik", "puma560", "--matrix", *MIRROR),
    ("ik", "puma560", "--pose", *Z6, "--method", "magic"),
    ("ik", "panda", "--pose", "0.3", "0", "0.5", "0", "180", "0", "--method", "analytic"),
    ("ik", "puma560", "--position", "0.3", "0.2", "0.1", "--method", "analytic", "--json"),
    ("ik", "panda", "--pose", "0.3", "0", "0.5", "0", "180", "0", "--seed", "-1"),
    ("ik", "panda", "--pose", "0.3", "0", "0.5", "0", "180", "0", "--seed", "9" * 30, "--json"),
    ("ik", "panda", "--pose", "0.3", "0", "0.5", "0", "180", "0", "--q0", *["1e300"] * 7, "--json"),
    ("ik", "panda", "--pose", "0.3", "0", "0.5", "0", "180", "0", "--q0", "0"),
    ("ik", "puma560", "--pose", "0.4", "0.1", "0.3", "0", "90", "0", "--precision", "1"),
    ("ik", "iiwa14", "--pose", "0.5", "0", "0.5", "0", "180", "0", "--units", "m", "--json"),
]

# --- the checks --------------------------------------------------------------------------


class _Hang(BaseException):
    """Raised by the alarm; a BaseException so that no handler of the CLI swallows it."""


def _alarm(signum: int, frame: FrameType | None) -> None:
    raise _Hang


def _strict_json(text: str) -> Any:
    def refuse(token: str) -> None:
        raise AssertionError(f"{token} in JSON output")

    return json.loads(text, parse_constant=refuse)


def check(argv: tuple[str, ...], code: int, out: str, err: str) -> None:
    """The promises of the command line, whatever the input."""
    assert code in (0, 1, 2), (code, err)
    assert "Traceback" not in out + err
    assert "internal error" not in err, err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert all(ln.startswith("kinematica") for ln in lines), err
    errors = [ln for ln in lines if ": error: " in ln]
    assert len(errors) <= 1, err
    if code == 2 and "--help" not in argv and "--version" not in argv:
        assert len(errors) == 1, err
    assert "\x1b" not in err and "\x1b" not in out
    if "--json" in argv and code in (0, 1) and "--help" not in argv:
        _strict_json(out)


def run_in_process(
    capsys: pytest.CaptureFixture[str], argv: tuple[str, ...], hang: int = HANG
) -> tuple[int, str, str]:
    """Run ``argv``, fail if it takes ``hang`` s, check the promises; ``(code, out, err)``."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(hang)
    try:
        try:
            code = main(list(argv))
        except SystemExit as exc:  # argparse: usage errors, --help, --version
            code = exc.code if isinstance(exc.code, int) else 2
        except _Hang:
            pytest.fail(f"no answer within {hang} s: {argv}")
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    out, err = capsys.readouterr()
    check(argv, code, out, err)
    return code, out, err


def _ids(cases: list[tuple[str, ...]]) -> list[str]:
    return [" ".join(c)[:60].encode("unicode_escape").decode() or "(nothing)" for c in cases]


@pytest.mark.skipif(not hasattr(signal, "SIGALRM"), reason="needs SIGALRM")
@pytest.mark.parametrize("argv", ARG_CASES, ids=_ids(ARG_CASES))
def test_hostile_arguments(capsys: pytest.CaptureFixture[str], argv: tuple[str, ...]) -> None:
    run_in_process(capsys, argv)


def _file_commands(path: str) -> Iterator[tuple[str, ...]]:
    yield ("show", path)
    yield ("show", path, "--json")
    yield ("fk", path, "--q", "10", "20", "--json")
    yield ("ik", path, "--position", "0.5", "0.5", "0", "--json")


@pytest.mark.skipif(not hasattr(signal, "SIGALRM"), reason="needs SIGALRM")
@pytest.mark.parametrize("name", FILE_CASES, ids=_ids([(n,) for n in FILE_CASES]))
def test_hostile_files(
    capsys: pytest.CaptureFixture[str], files: dict[str, str], name: str
) -> None:
    if name not in files:
        pytest.skip(f"{name!r} cannot be made on this system")
    for argv in _file_commands(files[name]):
        run_in_process(capsys, argv)
    code = main(["show", files[name]])
    capsys.readouterr()
    assert (code == 0) == (name in VALID), name


@pytest.mark.skipif(not hasattr(signal, "SIGALRM"), reason="needs SIGALRM")
@pytest.mark.parametrize("name", km.builtin_names())
def test_every_builtin_through_every_command(capsys: pytest.CaptureFixture[str], name: str) -> None:
    dof = km.load(name).dof
    for argv in (
        ("show", name, "--json"),
        ("fk", name, "--q", *["0"] * dof, "--json", "--frames"),
        ("fk", name, "--q", *["1e300"] * dof, "--json"),
        ("ik", name, "--pose", "0.3", "0.2", "0.4", "10", "20", "30", "--json"),
        ("ik", name, "--position", "0.3", "0.2", "0.4", "--json"),
    ):
        run_in_process(capsys, argv)


# --- through the installed console script ----------------------------------------------------

# "@name" stands for the path of the hostile file "name".
SCRIPT_CASES = [
    ("show", "@fifo.yaml"),
    ("show", "@zero.yaml"),
    ("show", "@binary.yaml", "--json"),
    ("show", "@big.yaml"),
    ("fk", "@evil.json", "--q", "0"),
    ("fk", "ur5", "--q", "0", "-inf", "0", "0", "0", "0"),
    ("ik", "ur5", "--pose", "1e300", "0", "0", "0", "0", "0", "--json"),
    ("fk", "@radians_typo.yaml", "--q", "0", "--json"),
]


@pytest.mark.parametrize("argv", SCRIPT_CASES, ids=_ids(SCRIPT_CASES))
def test_hostile_input_through_the_console_script(
    files: dict[str, str], argv: tuple[str, ...]
) -> None:
    if not SCRIPT.exists():  # pragma: no cover - the venv always has it
        pytest.skip("the kinematica console script is not installed next to this python")
    names = [a[1:] for a in argv if a.startswith("@")]
    if any(n not in files for n in names):
        pytest.skip("this file cannot be made on this system")
    real = tuple(files[a[1:]] if a.startswith("@") else a for a in argv)
    proc = subprocess.run(
        [str(SCRIPT), *real], capture_output=True, text=True, timeout=HANG, check=False
    )
    check(real, proc.returncode, proc.stdout, proc.stderr)


# --- random command lines from a hostile vocabulary ---------------------------------------------

_WORDS = [
    "fk", "ik", "show", "robots", "puma560", "ur5", "stanford", "planar-pr", "panda", "irb120",
    "--q", "--q0", "--pose", "--position", "--matrix", "--json", "--rad", "--frames", "--euler",
    "--units", "--precision", "--method", "--seed", "--ignore-limits", "mm", "m", "xyz", "ZYZ",
    "numeric", "analytic", "0", "1", "-1", "90", "0.3", "1e300", "-1e300", "1e-300", "1e309",
    "nan", "-nan", "inf", "-inf", "-0", "1e154", "3", "17", "", "--", "-", "\x1b[2J", "🤖",
]  # fmt: skip


@pytest.mark.skipif(not hasattr(signal, "SIGALRM"), reason="needs SIGALRM")
@settings(
    max_examples=150,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture],  # capsys is read each time
)
@given(st.lists(st.sampled_from(_WORDS), max_size=14))
def test_random_command_lines(capsys: pytest.CaptureFixture[str], words: list[str]) -> None:
    try:
        run_in_process(capsys, tuple(words))
    except AssertionError as exc:
        if "internal error: OverflowError" in str(exc):  # pragma: no cover
            return  # the IK solvers' overflow, pinned by KNOWN_SOLVER_BUGS above
        raise


# --- extreme arguments: refused at once, exit 2, one line naming the option ----------------

TRAJ = ("trajectory", "planar-3r", "--from", "0", "0", "0", "--to", "10", "20", "30")
PLOT = ("plot", "planar-3r", "--q", "0", "30", "30", "-o", "@out.png")
ANIMATE = ("animate", "planar-3r", "--trajectory", "@path.csv", "-o", "@out.gif")
DESIGN = ("design", "@template.yaml", "--task", "@ring.csv", "-o", "@best.yaml", "--budget", "2")

# (command line, what the one error line must say); "@name" is a file in tmp_path.
REFUSED: list[tuple[tuple[str, ...], str]] = [
    ((*TRAJ, "--duration", "1e308"), "--duration must be a number of seconds greater than 0 "
     "and at most 1e+09 s, got 1e+308"),
    ((*TRAJ, "--duration", "-1"), "--duration must be a number of seconds greater than 0"),
    ((*TRAJ, "--dt", "1e-320"), "--duration/--dt gives inf samples (2 s every 1e-320 s); "
     "at most 1,000,000 are made"),
    ((*TRAJ, "--dt", "0"), "--dt must be a number of seconds greater than 0"),
    ((*TRAJ, "--vmax", "1e-320"), "--vmax gives a duration of"),
    ((*TRAJ, "--amax", "1e-320", "--profile", "cubic"), "--amax gives a duration of"),
    ((*TRAJ, "--vmax", "1e-320", "--amax", "1", "--profile", "trapezoid"), "--vmax/--amax give"),
    ((*TRAJ, "--duration", "1e5", "--dt", "1e-3", "--cartesian"), "--duration/--dt gives"),
    (("workspace", "planar-3r", "--voxel", "1e300"), "--voxel must be a length from"),
    (("workspace", "planar-3r", "--voxel", "1e-9"), "--voxel must be a length from"),
    (("workspace", "planar-3r", "--voxel", "nan"), "--voxel must be a length"),
    (("workspace", "planar-3r", "--at", "nan"), "--at needs finite numbers"),
    (("workspace", "planar-3r", "--at", "inf", "--samples", "10"), "--at needs finite numbers"),
    (("workspace", "planar-3r", "--samples", "0"), "--samples must be a whole number from 1"),
    (("workspace", "planar-3r", "--samples", "99999999999"), "--samples must be a whole number"),
    (("workspace", "planar-3r", "--seed", "-1", "--samples", "10"), "--seed must be a whole"),
    ((*PLOT, "--dpi", "-1"), "--dpi must be a number of dots per inch from 10 to 2400, got -1"),
    ((*PLOT, "--dpi", "1e308"), "--dpi must be a number of dots per inch from 10 to 2400"),
    ((*PLOT, "--size", "100000", "100000"), "--size must be a whole number from 16 to 20,000"),
    ((*PLOT, "--size", "20000", "20000"), "--size gives 4e+08 pixels; at most 40,000,000"),
    ((*PLOT, "--size", "0", "10"), "--size must be a whole number from 16"),
    ((*PLOT, "--solutions", "--size", "100000", "16"), "--size must be a whole number"),
    ((*ANIMATE, "--fps", "1e-9"), "--fps must be a number of frames a second from 0.01 to 240"),
    ((*ANIMATE, "--fps", "inf"), "--fps must be a number of frames a second"),
    ((*ANIMATE, "--max-frames", "-3"), "--max-frames must be a whole number of at least 1"),
    ((*ANIMATE, "--size", "100000", "100000"), "--size must be a whole number from 16"),
    ((*ANIMATE[:3], "@fifo.csv", *ANIMATE[4:]), "fifo.csv: is a named pipe (FIFO), not a "
     "trajectory file"),
    ((*ANIMATE[:3], "@zero.csv", *ANIMATE[4:]), "zero.csv: is a device, not a trajectory file"),
    ((*ANIMATE[:3], "@big.csv", *ANIMATE[4:]), "trajectory files of at most 67,108,864 bytes"),
    (("view", "planar-3r", "--serve", "--port", "99999"), "argument --port: expected a port "
     "number from 0 to 65535 (0: a free one), got '99999'"),
    (("view", "planar-3r", "--serve", "--port", "-1"), "argument --port: expected a port"),
    ((*DESIGN, "--checkpoint", "@zero.jsonl"), "zero.jsonl: is a device, not a checkpoint file"),
    ((*DESIGN, "--checkpoint", "@fifo.csv"), "is a named pipe (FIFO), not a checkpoint file"),
]  # fmt: skip


@pytest.fixture
def extreme_files(tmp_path: Path) -> Path:
    (tmp_path / "path.csv").write_text("t,q1,q2,q3\n0,0,0,0\n1,0.1,0.2,0.3\n")
    (tmp_path / "template.yaml").write_text(
        "convention: standard\nparameters:\n  l1: {value: 0.5, min: 0.1, max: 0.9}\n"
        "joints:\n  - {theta: q1, d: 0, a: l1, alpha: 0}\n  - {theta: q2, d: 0, a: 0.5, "
        "alpha: 0}\n"
    )
    (tmp_path / "ring.csv").write_text("x,y,z\n0.5,0,0\n0,0.5,0\n")
    with (tmp_path / "big.csv").open("wb") as f:
        f.truncate(65 * 2**20)  # sparse: takes no room
    if hasattr(os, "mkfifo"):
        os.mkfifo(tmp_path / "fifo.csv")
    if Path("/dev/zero").exists():
        (tmp_path / "zero.csv").symlink_to("/dev/zero")
        (tmp_path / "zero.jsonl").symlink_to("/dev/zero")
    return tmp_path


@pytest.mark.skipif(not hasattr(signal, "SIGALRM"), reason="needs SIGALRM")
@pytest.mark.parametrize(("argv", "message"), REFUSED, ids=_ids([a for a, _ in REFUSED]))
def test_extreme_arguments_are_refused_in_one_line(
    capsys: pytest.CaptureFixture[str], extreme_files: Path, argv: tuple[str, ...], message: str
) -> None:
    real = tuple(str(extreme_files / a[1:]) if a.startswith("@") else a for a in argv)
    special = [a[1:] for a in argv if a[1:] in ("fifo.csv", "zero.csv", "zero.jsonl")]
    if any(not (extreme_files / name).exists() for name in special):
        pytest.skip("this special file cannot be made on this system")
    # A FIFO opened for reading, or /dev/zero read whole, would hang here.
    code, _, err = run_in_process(capsys, real, hang=10)
    assert code == 2, (code, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and message in lines[0], err
    assert not any(p.name.startswith("out.") for p in extreme_files.iterdir())
