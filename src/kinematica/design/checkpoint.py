"""Checkpoint files: every finished evaluation, so a killed run loses none.

A checkpoint is a text file of JSON lines. The first line says what the
evaluations are of (a hash of the template file's content and bounds, of the
task's targets, and the version of the measures); each further line is one
finished evaluation, written and flushed as soon as it is known. Floats are
written with ``repr``, so they read back bit for bit.

A new checkpoint is made whole (its header line written to a temporary file
and renamed into place, :mod:`kinematica.io.atomic`); evaluations are then
appended. An append that fails (a full disk) is cut back to the lines before
it, so the file always ends with a whole line.

A resumed run replays the optimiser from its seed and takes every evaluation
it finds here instead of computing it again: the optimiser sees the same
numbers, takes the same steps and ends with the same result. A line cut short
by a kill is dropped (and the file trimmed back to its last whole line).
Evaluations hold every measure, so a checkpoint also serves a run with another
objective, budget or seed on the same template and task.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
from pathlib import Path
from typing import Any, Final

from kinematica.design.evaluate import Evaluation
from kinematica.errors import KinematicaError
from kinematica.io.atomic import write_failed, write_text_atomic
from kinematica.io.reading import read_limited

__all__ = ["Checkpoint", "CheckpointError"]

#: The first key of a checkpoint's header line.
FORMAT: Final = "kinematica-design-checkpoint"
#: Largest checkpoint read (256 MiB): about a million evaluations.
MAX_BYTES = 256 * 2**20
#: Bumped whenever what an evaluation holds, or how it is computed, changes.
VERSION: Final = 3

Key = tuple[float, ...]


class CheckpointError(KinematicaError):
    """A checkpoint file is unreadable or belongs to another problem."""


class Checkpoint:
    """An open checkpoint file: the evaluations it holds, and appending to it.

    Args:
        path: The file; created if missing.
        fingerprint: What the evaluations are of (template, task, version).
        names: The design variables, in order.

    Raises:
        CheckpointError: The file exists but is not a checkpoint, or is one
            for another template or task.
    """

    def __init__(self, path: str | os.PathLike[str], fingerprint: str, names: tuple[str, ...]):
        self.path = Path(path)
        self.names = names
        self.found: dict[Key, Evaluation] = {}
        header: dict[str, Any] = {
            "format": FORMAT,
            "version": VERSION,
            "fingerprint": fingerprint,
            "parameters": list(names),
        }
        text = self._read()
        lines = text.split("\n")
        whole = lines[:-1]  # the part after the last newline is empty or cut short
        if not whole:
            try:
                write_text_atomic(self.path, json.dumps(header) + "\n")
            except OSError as exc:
                raise CheckpointError(write_failed(self.path, exc, "the checkpoint")) from exc
            self._file = self._open()
            self._file.seek(0, os.SEEK_END)
            return
        first = self._parse(whole[0], 1)
        if first.get("format") != FORMAT:
            raise CheckpointError(f"{self.path}: not a kinematica design checkpoint")
        if first.get("version") != VERSION or first.get("fingerprint") != fingerprint:
            raise CheckpointError(
                f"{self.path}: this checkpoint belongs to another template or task "
                "(or an older kinematica); remove it or give another file"
            )
        for number, line in enumerate(whole[1:], start=2):
            ev = self._evaluation(self._parse(line, number), number)
            self.found[ev.x] = ev
        self._file = self._open()
        self._file.truncate(len("\n".join(whole).encode()) + 1)  # drop a cut line
        self._file.seek(0, os.SEEK_END)

    def _read(self) -> str:
        data = read_limited(
            self.path,
            MAX_BYTES,
            "checkpoint file",
            lambda reason: CheckpointError(f"{self.path}: {reason}"),
            missing_ok=True,
        )
        try:
            return data.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise CheckpointError(f"{self.path}: cannot read the checkpoint: {exc}") from exc

    def _open(self) -> io.FileIO:
        try:
            return io.FileIO(self.path, "r+")
        except OSError as exc:
            raise CheckpointError(
                f"{self.path}: cannot write the checkpoint: {exc.strerror or exc}"
            ) from exc

    def _parse(self, line: str, number: int) -> dict[str, Any]:
        try:
            data = json.loads(line)
        except json.JSONDecodeError as exc:
            raise CheckpointError(f"{self.path}, line {number}: not a checkpoint line") from exc
        if not isinstance(data, dict):
            raise CheckpointError(f"{self.path}, line {number}: not a checkpoint line")
        return data

    def _evaluation(self, data: dict[str, Any], number: int) -> Evaluation:
        try:
            x = [float(v) for v in data["x"]]
            measures = {str(k): float(v) for k, v in data["measures"].items()}
            violation = float(data["violation"])
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise CheckpointError(f"{self.path}, line {number}: malformed evaluation") from exc
        if len(x) != len(self.names):
            raise CheckpointError(
                f"{self.path}, line {number}: {len(x)} values for {len(self.names)} parameters"
            )
        return Evaluation(dict(zip(self.names, x, strict=True)), measures, violation)

    def _write(self, data: dict[str, Any]) -> None:
        # json writes floats with repr (exact); NaN/inf as NaN/Infinity, which it reads back.
        line = memoryview((json.dumps(data) + "\n").encode("utf-8"))
        end = self._file.tell()
        try:
            while line:  # unbuffered: each write goes to the file at once, or raises
                line = line[self._file.write(line) or 0 :]
        except OSError as exc:
            with contextlib.suppress(OSError):  # drop the part of the line written
                self._file.truncate(end)
                self._file.seek(end)
            raise CheckpointError(
                f"{self.path}: cannot write the checkpoint ({exc.strerror or exc}); "
                "the evaluations before it are kept"
            ) from exc

    def append(self, ev: Evaluation) -> None:
        """Write one finished evaluation (flushed at once)."""
        self._write({"x": list(ev.x), "violation": ev.violation, "measures": dict(ev.measures)})

    def close(self) -> None:
        """Close the file."""
        self._file.close()
