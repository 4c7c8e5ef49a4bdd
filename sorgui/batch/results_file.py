"""``--each-line -o RESULTS.jsonl [--resume]``: the JSON Lines written to a file that survives
a crash.

Lines are written in input order, each whole (one ``write``), and flushed to the disk at least
every :data:`SYNC_EVERY` seconds and at the end. A batch killed by ``SIGKILL`` or a power cut
and started again with ``--resume`` keeps every line of the file that is whole, valid JSON
and belongs to the input as it is now: the file's lines are matched, in order, with the
input's lines by line number and :func:`.lines.line_hash`; the lines it holds are not analysed
again, and the rest are appended. A last line of sorgui's that is cut short (or the zeros a
power cut leaves) is dropped and redone; other text without its newline is refused, as any
other line is. The result is the file one uninterrupted run writes.

Nothing is lost or mixed silently: without ``--resume`` a file that holds results is refused,
and with it a file whose lines do not match the input (the input was edited, or it is another
batch's file), or were analysed with other options (``--recognition-only``, ``--method``,
``--tolerance``, ``--timeout``: each line's ``"options"``), is refused before anything is
changed.
"""

from __future__ import annotations

import json
import os
import stat
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any, BinaryIO

from .answers import ANALYSED, FAILED, NOT_A_POLYNOMIAL, Answer, Options, kind_of, options_text
from .errors import BatchError
from .lines import Line

Entry = tuple[int, str, str, Any, int]
"""A results file's line: its number, ``line_hash``, kind (:data:`.answers.KINDS`), options and
status (:data:`.answers.ANALYSED` and the others)."""
SYNC_EVERY = 1.0
"""Seconds between two flushes of the results file to the disk (``fsync``)."""


class ResultsFile:
    """The ``-o`` file of a batch: its kept lines (with ``--resume``) and the lines written."""

    def __init__(self, path: Path, resume: bool, inputs: list[os.stat_result], options: Options) -> None:
        self.path = path
        self.options = options
        self.kept: dict[str, int] = {}
        """How many kept lines count as each kind (:data:`.answers.KINDS`)."""
        self.kept_statuses: set[int] = set()
        """The statuses of the kept lines: the batch's exit status counts them as the run that wrote them did."""
        self.written = 0
        """The lines written by this run."""
        self._fd: int | None = None
        self._synced = time.monotonic()
        status = _status(path, inputs)
        regular = status is not None and stat.S_ISREG(status.st_mode)
        if resume and status is not None and not regular:
            raise BatchError(f"cannot resume {path}: it is not a regular file")
        if not resume and regular and status is not None and status.st_size > 0:
            raise BatchError(
                f"{path} already exists and is not empty: add --resume to continue a batch's results, "
                "or remove it first"
            )
        self._entries: Iterator[Entry] | None = None
        self._next: Entry | None = None
        self._valid_end = 0
        if resume and regular:
            self._reader: BinaryIO | None = open(path, "rb")  # noqa: SIM115 - closed when the prefix is read
            self._entries = self._scan(self._reader)
            self._next = next(self._entries, None)
        else:
            self._reader = None
            self._open(truncate=True)

    def keeps(self, line: Line) -> bool:
        """Whether ``line`` is already in the file (``--resume``): the file's next line must be
        ``line``'s, with the same hash; once the file's lines are all matched, the file is
        opened to append to. Raises :class:`BatchError` for a file that does not match."""
        if self._fd is not None:
            return False
        entry = self._next
        if entry is None:
            self._open(truncate=False)
            return False
        number, digest, kind, options, status = entry
        if options is not None and options != self.options:  # an older sorgui's lines have none
            raise BatchError(
                f"cannot resume {self.path}: its line {number} was analysed with {options_text(options)}, "
                f"this run has {options_text(self.options)}; give the same options, or start a new results file"
            )
        if number != line.number or digest != line.digest:
            where = (
                f"line {number}" if number == line.number else f"line {number} (the input's next is line {line.number})"
            )
            raise BatchError(
                f"cannot resume {self.path}: its {where} is not the input's line {line.number} as it is now; "
                "start a new results file"
            )
        self.kept[kind] = self.kept.get(kind, 0) + 1
        self.kept_statuses.add(status)
        assert self._entries is not None
        self._next = next(self._entries, None)
        return True

    def finish_reading(self) -> None:
        """The input has ended: every line of the file must have been matched."""
        if self._fd is not None:
            return
        if self._next is not None:
            raise BatchError(
                f"cannot resume {self.path}: it holds line {self._next[0]}, which the input no longer has; "
                "start a new results file"
            )
        self._open(truncate=False)

    def write(self, answer: Answer) -> None:
        """Append one line, whole; flush to the disk when :data:`SYNC_EVERY` seconds have passed."""
        assert self._fd is not None
        data = memoryview((answer.text + "\n").encode("utf-8"))
        while data:
            data = data[os.write(self._fd, data) :]
        self.written += 1
        if time.monotonic() - self._synced >= SYNC_EVERY:
            self._sync()

    def lines(self) -> int:
        """The lines the file holds: those kept and those written by this run."""
        return sum(self.kept.values()) + self.written

    def close(self) -> None:
        """Flush the file to the disk and close it."""
        if self._reader is not None:
            self._reader.close()
            self._reader = None
        if self._fd is not None:
            try:
                self._sync()
            finally:
                os.close(self._fd)
                self._fd = None

    def _sync(self) -> None:
        assert self._fd is not None
        try:
            os.fsync(self._fd)
        except OSError:
            pass  # a pipe or a character device (-o /dev/stdout) has nothing to flush
        self._synced = time.monotonic()

    def _open(self, truncate: bool) -> None:
        """Open the file for writing: a new or emptied file, or (resuming) the file cut after its
        last whole line, for appending."""
        if self._reader is not None:
            self._reader.close()
            self._reader = None
        flags = os.O_WRONLY | os.O_CREAT | os.O_APPEND | getattr(os, "O_CLOEXEC", 0)
        try:
            self._fd = os.open(self.path, flags, 0o666)
            status = os.fstat(self._fd)
            if stat.S_ISREG(status.st_mode) and (truncate or status.st_size > self._valid_end):
                os.ftruncate(self._fd, 0 if truncate else self._valid_end)
        except OSError as exc:
            raise BatchError(f"cannot write {self.path}: {exc.strerror or exc}") from None

    def _scan(self, reader: BinaryIO) -> Iterator[Entry]:
        """The :data:`Entry` of each whole line of the file, in order, recording where the
        last one ends. Only the end of the file may be what a crash leaves (a line cut short,
        without its newline, or the zeros of a power cut), which is dropped and redone; any
        other line that is not a line of sorgui's output, in order, is refused (a notes file
        of one line was taken for a cut-short line and replaced)."""
        offset = 0
        previous = 0
        debris = False
        for number, raw in enumerate(reader, start=1):
            entry = _entry(raw) if raw.endswith(b"\n") else None
            if entry is not None and not debris and entry[0] > previous:
                offset += len(raw)
                self._valid_end = offset
                previous = entry[0]
                yield entry
            elif not raw.strip(b"\0\n") or (not raw.endswith(b"\n") and _cut_short(raw)):
                debris = True  # zeros, or a line of ours cut short: the end of the file as a crash left it
            else:
                raise BatchError(
                    f"cannot resume {self.path}: its line {number} is not a line of sorgui's output in order; "
                    "give another results file, or remove it first"
                )


LINE_START = b'{"line": '
"""How every line of a results file begins (:attr:`.answers.Answer.text`)."""


def _cut_short(raw: bytes) -> bool:
    """Whether ``raw``, a last line without its newline, is the start of one of sorgui's lines
    (a crash cut it; the zeros of a power cut may follow), not another file's text (a notes file
    of one line without a newline was replaced by a batch's results)."""
    text = raw.rstrip(b"\0")
    return text.startswith(LINE_START) or LINE_START.startswith(text)


def _entry(raw: bytes) -> Entry | None:
    """The :data:`Entry` of one line of a results file, ``None`` if it is not one."""
    try:
        data: Any = json.loads(raw)
    except (ValueError, UnicodeDecodeError):
        return None
    if not isinstance(data, dict):
        return None
    number, digest = data.get("line"), data.get("line_hash")
    if not isinstance(number, int) or not isinstance(digest, str):
        return None
    return number, digest, kind_of(data), data.get("options"), _status_of(data)


def _status_of(data: dict[str, Any]) -> int:
    """The status of a results file's line: an error object's ``exit_status``; an older sorgui's
    error objects have none, and a line that was not a polynomial has the position of the fault."""
    error = data.get("error")
    if not isinstance(error, dict):
        return ANALYSED
    status = error.get("exit_status")
    if status in (FAILED, NOT_A_POLYNOMIAL):
        return int(status)
    return NOT_A_POLYNOMIAL if isinstance(error.get("position"), int) else FAILED


def _status(path: Path, inputs: list[os.stat_result]) -> os.stat_result | None:
    """The file's status (``None`` if it does not exist), after the checks of a target: its folder
    exists, it is not a folder and not the input."""
    try:
        status = os.stat(path)
    except FileNotFoundError:
        status = None
    except OSError as exc:
        raise BatchError(f"cannot write {path}: {exc.strerror or exc}") from None
    if not path.parent.is_dir():
        raise BatchError(f"cannot write {path}: the folder {path.parent} does not exist")
    if status is None:
        return None
    if stat.S_ISDIR(status.st_mode):
        raise BatchError(f"cannot write {path}: it is a folder")
    if any((status.st_dev, status.st_ino) == (i.st_dev, i.st_ino) for i in inputs):
        raise BatchError(f"refusing to overwrite the input file {path}")
    return status
