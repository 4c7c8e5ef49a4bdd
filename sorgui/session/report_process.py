"""Reading a saved report in a child process that can always be ended, under a deadline.

A report is a file from elsewhere: reading it decodes its JSON, validates every field and
checks its claims (:func:`sorgui.export.reports.read_report`), which takes seconds for a report
of megabytes (one of 8.5 MB took 4 s, and froze the window when it was read there) and may take
longer inside one C call for a crafted one. The window therefore has it read by the child of
:class:`ReportReading` (spawned, like the analysis worker, :mod:`sorgui.session.child`), which
answers each path with one message, :class:`ReportRead` or :class:`ReportNotRead` (the reason in
one line); the child is killed at the deadline, and when the window quits.

Light to import (the standard library and the session's messages): the reader of the report
(sympy, the claims) is loaded in the child only.
"""

from __future__ import annotations

import sys
import time
import traceback
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from sorgui.session.child import ChildProcess, become_child
from sorgui.session.messages import Hangup

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

    from sorgui.engine.results import Analysis


@dataclass(frozen=True)
class ReportRead:
    """The report ``path`` holds ``analysis``, its claims checked."""

    path: str
    analysis: Analysis


@dataclass(frozen=True)
class ReportNotRead:
    """The report ``path`` is not shown: unreadable, not a report, refused, or not read in time."""

    path: str
    message: str


ReportAnswer = ReportRead | ReportNotRead


def read_answer(path: str, line: int | None = None) -> ReportAnswer:
    """Read and check the report ``path`` (of a batch's results file, the one of input ``line``);
    every failure is one line."""
    from sorgui.export.reports import ReportError, read_report

    try:
        return ReportRead(path, read_report(path, line))
    except ReportError as exc:
        return ReportNotRead(path, exc.message)
    except MemoryError:
        return ReportNotRead(path, f"{path} could not be read: it ran out of memory")
    except Exception as exc:  # noqa: BLE001 - a bug still ends in one line; the details go to stderr
        traceback.print_exc(file=sys.stderr)
        return ReportNotRead(path, f"{path} could not be read: internal error ({type(exc).__name__}: {exc})")


def read_child(conn: Connection) -> None:
    """The reading process: answer every ``(path, line)`` that arrives until the pipe closes."""
    become_child()
    while True:
        try:
            path, line = conn.recv()
            conn.send(read_answer(path, line))
        except (EOFError, OSError):
            return


@dataclass
class ReportReading:
    """One :class:`ChildProcess` running :func:`read_child`, reading one report at a time by
    the deadline (``time.monotonic()``) of the path it is working on; ``limit`` is the user's
    time limit in seconds, named when a report is not read by then."""

    context: Any
    limit: float | None = None
    child: ChildProcess | None = None
    path: str | None = None
    deadline: float = float("inf")

    @property
    def busy(self) -> bool:
        return self.path is not None

    def give(self, path: str, deadline: float | None = None, line: int | None = None) -> None:
        """Read ``path`` (its input ``line``'s result, for a batch's results file; starting the
        child if there is none, ending a reading under way) by ``deadline``."""
        if self.busy:
            self.cancel()
        if self.child is None or not self.child.is_alive():
            self.child = ChildProcess(self.context, read_child, name="sorgui-report")
        self.path = path
        self.deadline = float("inf") if deadline is None else deadline
        self.child.send((path, line))

    def collect(self) -> ReportAnswer | None:
        """The answer, if it has come (without waiting); at the deadline, or when the child died,
        the child is killed and the report is not read."""
        if self.child is None or self.path is None:
            return None
        for message in self.child.messages():
            if isinstance(message, Hangup):
                return self._end(f"the process reading it died ({self.child.exit_description()})")
            if isinstance(message, (ReportRead, ReportNotRead)) and message.path == self.path:
                self.path = None
                return message
        if time.monotonic() >= self.deadline:
            limit = "" if self.limit is None else f" of {self.limit:g} s"
            return self._end(f"not read within the time limit{limit}")
        return None

    def _end(self, reason: str) -> ReportNotRead:
        assert self.child is not None and self.path is not None
        path = self.path
        self.cancel()
        return ReportNotRead(path, f"{path} is not shown: {reason}")

    def cancel(self) -> None:
        """Stop the reading under way at once (its child is killed; the next reading starts another)."""
        if self.child is not None and self.busy:
            self.child.close(wait=0.0)
            self.child = None
        self.path = None

    def close(self) -> None:
        """Kill the child."""
        self.path = None
        if self.child is not None:
            self.child.close(wait=0.0)
            self.child = None
