"""Saves are atomic: a write that fails part-way, or a process killed while writing, leaves the
old file whole (byte for byte), says so in one line, and leaves no temporary file behind.

The failures are real ones (a file-size limit, ``RLIMIT_FSIZE``, in a child process with
SIGXFSZ ignored, so a write gets EFBIG part-way through, as on a full disk) and monkeypatched
ones (a writer that puts half its bytes in the file, then raises). The kills are SIGKILLs at
random moments of a loop of saves.
"""

from __future__ import annotations

import errno
import json
import os
import random
import signal
import stat
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.io import read_robot_file
from kinematica.motion import read_csv

# Each case writes an old (small) file with no limit, then a new (larger) one with the file-size
# limit just above the old size: the new write fails part-way. It prints the case, the file and
# the error's message as JSON, one line per case.
CHILD = textwrap.dedent(
    """
    import contextlib, io, json, resource, signal, sys
    from pathlib import Path

    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import kinematica as km
    from kinematica.cli.main import main as cli
    from kinematica.design.checkpoint import Checkpoint
    from kinematica.design.evaluate import Evaluation
    from kinematica.motion import write_csv, write_json
    from kinematica.viz import save_plot, write_trajectory

    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # the write fails with EFBIG instead
    folder = Path(sys.argv[1])
    small = km.load("planar-pr")
    big = km.load("puma560")
    general = km.Robot.from_dh(  # its long name makes its header the larger one
        [km.Revolute(d=0.1 * i, a=0.2, alpha=0.3 + 0.2 * i) for i in range(6)],
        convention="standard",
        name="general 6R arm " * 60,
    )
    t3, t300 = np.linspace(0, 1, 3), np.linspace(0, 1, 300)
    q3, q300 = np.zeros((3, 6)), np.random.default_rng(1).uniform(-1, 1, (300, 6))

    def cpp(robot, path):  # the command line's C++ export: its one line on stderr
        robot.save(folder / "cpp.yaml")
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            code = cli(["convert", str(folder / "cpp.yaml"), "--to", "cpp", "-o", str(path)])
        if code:
            raise km.KinematicaError(err.getvalue().strip())

    cases = {
        "robot.yaml": lambda r, p: r.save(p),
        "robot.json": lambda r, p: r.save(p),
        "robot.toml": lambda r, p: r.save(p),
        "robot.urdf": lambda r, p: r.to_urdf(p),
        "traj.csv": lambda r, p: write_csv(p, *((t3, q3) if r is small else (t300, q300))),
        "traj.json": lambda r, p: write_json(p, *((t3, q3) if r is small else (t300, q300))),
        "viz.csv": lambda r, p: write_trajectory(p, *((t3, q3) if r is small else (t300, q300))),
        "picture.png": lambda r, p: save_plot(r, np.zeros(r.dof), p, size=(100, 80)
                                             if r is small else (800, 700)),
        # (a general 6R arm of a long name: every header built in C++ calls the core's
        # builder, a line, and may be shorter than the planar arm's, its fields written out)
        "arm.hpp": lambda r, p: cpp(general if r is big else r, p),
    }
    infinite = resource.RLIM_INFINITY
    for name, write in cases.items():
        path = folder / name
        write(small, path)
        resource.setrlimit(resource.RLIMIT_FSIZE, (path.stat().st_size + 64, infinite))
        message = None
        try:
            write(big, path)
        except km.KinematicaError as exc:
            message = str(exc)
        finally:
            resource.setrlimit(resource.RLIMIT_FSIZE, (infinite, infinite))
        print(json.dumps({"case": name, "message": message}), flush=True)

    # a design checkpoint: an append that fails is cut back to the whole lines before it
    path = folder / "run.ckpt"
    ckpt = Checkpoint(path, "fingerprint", ("l1", "l2"))
    for k in range(3):
        ckpt.append(Evaluation({"l1": k, "l2": 0.5}, {"total_length": 1.0 + k}, 0.0))
    resource.setrlimit(resource.RLIMIT_FSIZE, (path.stat().st_size + 64, infinite))
    message = None
    try:
        ckpt.append(Evaluation({"l1": 9.0, "l2": 0.5}, {f"m{i}": 0.1 * i for i in range(40)}, 0.0))
    except km.KinematicaError as exc:
        message = str(exc)
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, (infinite, infinite))
    ckpt.close()
    print(json.dumps({"case": "run.ckpt", "message": message}), flush=True)
    """
)


def test_a_write_that_fails_part_way_leaves_the_old_file(tmp_path):
    pytest.importorskip("matplotlib")
    folder = tmp_path / "out"
    folder.mkdir()
    proc = subprocess.run(
        [sys.executable, "-c", CHILD, str(folder)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    results = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    assert len(results) == 10, proc.stdout
    for r in results:
        name, message = r["case"], r["message"]
        assert message is not None, f"{name}: the write did not fail"
        assert "\n" not in message
        if name == "run.ckpt":
            assert "the evaluations before it are kept" in message
        else:
            assert "the old file is unchanged" in message, message
            assert name in message
    # the old files, byte for byte: what the small versions are, written again here
    small = km.load("planar-pr")
    for suffix in ("yaml", "json", "toml"):
        again = tmp_path / f"again.{suffix}"
        small.save(again)
        assert (folder / f"robot.{suffix}").read_bytes() == again.read_bytes()
    assert (folder / "robot.urdf").read_text() == small.to_urdf()
    t3, q3 = read_csv(folder / "traj.csv")
    np.testing.assert_array_equal(t3, np.linspace(0, 1, 3))
    assert q3.shape == (3, 6)
    assert len(json.loads((folder / "traj.json").read_text())["t"]) == 3
    assert len((folder / "viz.csv").read_text().splitlines()) == 4
    assert (folder / "picture.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert small.name in (folder / "arm.hpp").read_text()
    lines = (folder / "run.ckpt").read_text().split("\n")
    assert lines[-1] == ""  # ends with a whole line
    assert [json.loads(line)["x"] for line in lines[1:-1]] == [[0, 0.5], [1, 0.5], [2, 0.5]]
    # no temporary file left
    expected = {r["case"] for r in results} | {"cpp.yaml"}
    assert {p.name for p in folder.iterdir()} == expected


def half_then_fail(original):
    """A writer that puts half of what it was given into the file, then fails as a full disk."""

    def write(self, data, *args, **kwargs):
        original(self, data[: len(data) // 2], *args, **kwargs)
        raise OSError(errno.ENOSPC, "No space left on device")

    return write


@pytest.mark.parametrize("suffix", [".yaml", ".json", ".toml"])
def test_a_robot_file_write_that_raises_part_way(tmp_path, monkeypatch, suffix):
    path = tmp_path / f"arm{suffix}"
    km.load("puma560").save(path)
    old = path.read_bytes()
    monkeypatch.setattr(Path, "write_text", half_then_fail(Path.write_text))
    with pytest.raises(km.RobotFileError) as info:
        km.load("stanford").save(path)
    message = str(info.value)
    assert "\n" not in message
    assert str(path) in message
    assert "No space left on device; the old file is unchanged" in message
    assert path.read_bytes() == old
    assert [p.name for p in tmp_path.iterdir()] == [path.name]


def test_a_picture_whose_drawing_fails_part_way(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    from kinematica.viz import VizError, save_plot

    robot = km.load("puma560")
    path = tmp_path / "arm.png"
    save_plot(robot, np.zeros(6), path, size=(120, 100))
    old = path.read_bytes()
    original = Figure.savefig

    def savefig(self, fname, *args, **kwargs):
        original(self, fname, *args, **kwargs)
        with open(fname, "r+b") as f:  # as if the disk filled up half-way
            f.truncate(os.path.getsize(fname) // 2)
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(Figure, "savefig", savefig)
    with pytest.raises(VizError, match="the old file is unchanged"):
        save_plot(robot, np.full(6, 0.5), path, size=(300, 200))
    assert path.read_bytes() == old
    assert [p.name for p in tmp_path.iterdir()] == ["arm.png"]


def test_a_new_file_that_fails_says_nothing_was_written(tmp_path, monkeypatch):
    monkeypatch.setattr(Path, "write_text", half_then_fail(Path.write_text))
    with pytest.raises(km.RobotFileError, match="nothing was written"):
        km.load("puma560").save(tmp_path / "new.yaml")
    assert list(tmp_path.iterdir()) == []


def test_permissions_and_links_of_a_replaced_file_are_kept(tmp_path):
    robot = km.load("puma560")
    path = tmp_path / "arm.yaml"
    robot.save(path)
    os.chmod(path, 0o640)
    km.load("stanford").save(path)
    assert stat.S_IMODE(path.stat().st_mode) == 0o640
    assert read_robot_file(path).name == km.load("stanford").name
    # a new file: what open(..., "w") gives under the umask
    umask = os.umask(0o027)
    try:
        robot.save(tmp_path / "new.yaml")
    finally:
        os.umask(umask)
    assert stat.S_IMODE((tmp_path / "new.yaml").stat().st_mode) == 0o640
    # a link: the file it names is replaced, the link stays a link
    link = tmp_path / "link.yaml"
    link.symlink_to("arm.yaml")
    robot.save(link)
    assert link.is_symlink()
    assert read_robot_file(path).name == robot.name


def _save_forever(robots: list[km.Robot], path: Path) -> None:
    """The child's loop: save the robots in turn until killed."""
    try:
        k = 0
        while True:
            robots[k % len(robots)].save(path)
            k += 1
    finally:
        os._exit(1)  # never return into the test runner


def test_a_save_killed_at_random_moments_never_leaves_a_cut_file(tmp_path):
    robots = [km.load("puma560"), km.load("stanford"), km.load("scara")]
    rng = random.Random(21)
    start = time.monotonic()
    kills = 0
    for k in range(21):
        path = tmp_path / f"arm.{('yaml', 'json', 'toml')[k % 3]}"
        robots[0].save(path)
        versions = [read_robot_file_text(r, path) for r in robots]
        pid = os.fork()
        if pid == 0:
            _save_forever(robots, path)
        time.sleep(rng.uniform(0.0, 0.05))
        os.kill(pid, signal.SIGKILL)
        _, status = os.waitpid(pid, 0)
        assert os.WIFSIGNALED(status), "the saving child ended by itself"
        kills += 1
        text = path.read_text(encoding="utf-8")
        assert text in versions, f"kill {k}: the file is not one of the versions ({len(text)} B)"
        assert read_robot_file(path).name in {r.name for r in robots}
    assert kills == 21
    assert time.monotonic() - start < 10.0
    for suffix in ("yaml", "json", "toml"):  # a save of each removes what the kills left
        robots[1].save(tmp_path / f"arm.{suffix}")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.json", "arm.toml", "arm.yaml"]


def read_robot_file_text(robot: km.Robot, like: Path) -> str:
    """The exact text ``robot.save`` writes to a file named like ``like``."""
    other = like.with_name(f"version{like.suffix}")
    robot.save(other)
    text = other.read_text(encoding="utf-8")
    other.unlink()
    return text


# A child that starts a save of argv[1] and is killed in the middle of it: it has
# written part of its temporary file when it says so.
MIDSAVE = textwrap.dedent(
    """
    import sys, time
    from kinematica.io.atomic import atomic_path

    with atomic_path(sys.argv[1]) as tmp:
        tmp.write_text("name: half a robot fi")
        print(tmp, flush=True)
        time.sleep(60)
    """
)


def _start_midsave(path: Path) -> tuple[subprocess.Popen[str], Path]:
    child = subprocess.Popen(
        [sys.executable, "-c", MIDSAVE, str(path)], stdout=subprocess.PIPE, text=True
    )
    assert child.stdout is not None
    tmp = Path(child.stdout.readline().strip())
    assert tmp.parent == path.parent and tmp.exists()
    return child, tmp


def _leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if ".tmp" in p.name)


def test_a_save_killed_midway_leaves_a_file_the_next_save_removes(tmp_path: Path) -> None:
    path = tmp_path / "arm.yaml"
    km.load("scara").save(path)
    old = path.read_text(encoding="utf-8")
    child, tmp = _start_midsave(path)
    child.kill()
    child.wait()
    assert tmp.exists() and path.read_text(encoding="utf-8") == old  # what a kill leaves
    assert f"-{child.pid}-" in tmp.name
    other = tmp_path / "other.yaml"  # another file's save leaves it
    km.load("puma560").save(other)
    assert _leftovers(tmp_path) == [tmp.name]
    km.load("puma560").save(path)  # the next save of the same file removes it
    assert _leftovers(tmp_path) == []
    assert read_robot_file(path).name == km.load("puma560").name


def test_a_running_writers_file_is_left_alone(tmp_path: Path) -> None:
    path = tmp_path / "arm.json"
    child, tmp = _start_midsave(path)
    try:
        km.load("puma560").save(path)  # the other writer runs: its file stays
        assert _leftovers(tmp_path) == [tmp.name]
        assert read_robot_file(path).name == km.load("puma560").name
    finally:
        child.kill()
        child.wait()
    km.load("scara").save(path)
    assert _leftovers(tmp_path) == []


def test_leftovers_by_age_on_both_sides_of_stale_age(tmp_path: Path) -> None:
    from kinematica.io.atomic import STALE_AGE

    path = tmp_path / "arm.toml"
    now = time.time()
    names = {
        # a process of another machine (its host hash), or a running one here: by age
        "other host, old": (".arm.toml.~km-00000000-123-abcd1234.tmp.toml", STALE_AGE + 60),
        "other host, young": (".arm.toml.~km-00000000-124-abcd1234.tmp.toml", STALE_AGE - 60),
        "running, old": (f".arm.toml.~km-HOST-{os.getpid()}-abcd1234.tmp.toml", STALE_AGE + 60),
        "running, young": (f".arm.toml.~km-HOST-{os.getppid()}-abcd1234.tmp.toml", 1.0),
        # the form before writers were named: by age
        "unnamed, old": (".arm.toml.ab_d1234.tmp.toml", STALE_AGE + 60),
        "unnamed, young": (".arm.toml.ab_d1235.tmp.toml", STALE_AGE - 60),
        # not ours: never
        "a user's file": (".arm.toml.notes.tmp.toml", STALE_AGE * 10),
    }
    host = f"{__import__('zlib').crc32(os.uname().nodename.encode()):08x}"
    for name, age in names.values():
        leftover = tmp_path / name.replace("HOST", host)
        leftover.write_text("x")
        os.utime(leftover, (now - age, now - age))
    km.load("scara").save(path)
    kept = {label for label, (name, _) in names.items()
            if (tmp_path / name.replace("HOST", host)).exists()}  # fmt: skip
    assert kept == {"other host, young", "running, young", "unnamed, young", "a user's file"}
