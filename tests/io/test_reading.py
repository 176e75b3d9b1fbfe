"""Reading a whole file safely (``io/reading.py``): FIFOs, devices and folders refused at once."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import kinematica as km
from kinematica.errors import RobotFileError
from kinematica.io import read_robot_file


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
def test_a_fifo_is_refused_without_waiting_for_a_writer(tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    with pytest.raises(RobotFileError, match=r"pipe\.yaml: is a named pipe \(FIFO\), not a robot"):
        read_robot_file(fifo)  # opening it would block until a writer came


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero")
def test_a_device_is_refused_without_reading_it(tmp_path: Path) -> None:
    link = tmp_path / "zero.yaml"
    link.symlink_to("/dev/zero")
    with pytest.raises(RobotFileError, match=r"zero\.yaml: is a device, not a robot file"):
        read_robot_file(link)  # reading it would never end


def test_a_directory_is_refused_by_load_and_by_write(tmp_path: Path) -> None:
    folder = tmp_path / "x.yaml"
    folder.mkdir()
    with pytest.raises(RobotFileError, match=r"x\.yaml: is a directory, not a robot file"):
        km.load(folder)
    with pytest.raises(RobotFileError, match="is a directory, not a robot file: not written"):
        km.load("puma560").save(folder)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
def test_saving_to_a_fifo_is_refused_without_waiting_for_a_reader(tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.json"
    os.mkfifo(fifo)
    with pytest.raises(RobotFileError, match="is a named pipe"):
        km.load("planar-3r").save(fifo)
