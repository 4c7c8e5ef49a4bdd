"""An analysis in a child process, under a deadline: ``sorgui analyze`` and each line of
``--each-line``.

The child (:func:`analysis_child`, a :class:`~sorgui.session.child.ChildProcess`) runs
:func:`sorgui.engine.analyze` for each :class:`AnalysisRequest` it is sent and streams what is
known as it is known:

* :class:`~.messages.Parsed`: the equation's :func:`~sorgui.engine.timelimit.skeleton`;
* :class:`~.messages.StageStarted` and :class:`~.messages.StageDone` as each stage starts and ends;
* :class:`~.messages.AnalysisKnown`: the results known so far (after the factors, the rationality, …);
* one final message: :class:`~.messages.Finished` with the ``Analysis``,
  :class:`~.messages.Invalid` for text that is not a polynomial, or :class:`~.messages.Failed`.

The parent folds the messages into a :class:`StageLog`. The engine bounds itself by the time
limit wherever Python runs; when it does not answer :data:`GRACE` seconds after the limit
(stuck in one C call), the parent kills the child and reports the stages it finished as done
and the rest as unfinished (:meth:`StageLog.outcome`) — the same answer the engine gives.
"""

from __future__ import annotations

import sys
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from sorgui.session.child import ChildProcess, become_child
from sorgui.session.messages import (
    AnalysisKnown,
    Failed,
    FinalMessage,
    Finished,
    Hangup,
    Invalid,
    JobCancelled,
    Message,
    Parsed,
    StageDone,
    StageStarted,
)

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

    from sorgui.engine import Analysis

GRACE = 0.4
"""Seconds after its time limit that an analysis process is given to answer before it is killed."""


@dataclass(frozen=True)
class AnalysisRequest:
    """One equation and the options of :func:`sorgui.engine.analyze` (``timeout`` included)."""

    text: str
    method: str = "symmetry"
    recognition_only: bool = False
    tolerance: float | None = None
    timeout: float | None = None

    def options(self) -> dict[str, Any]:
        singular = 60.0 if self.timeout is None else self.timeout
        return {
            "method": self.method,
            "recognition_only": self.recognition_only,
            "tolerance": self.tolerance,
            "timeout": self.timeout,
            "singular_timeout": singular,
        }


@dataclass
class StageLog:
    """What an analysis process has said so far about one request (``recognition_only``: whether
    the request skipped the rationality, which decides the stages still to come)."""

    recognition_only: bool
    start: Analysis | None = None
    latest: Analysis | None = None
    timings: list[tuple[str, float]] = field(default_factory=list)
    current: str | None = None
    final: FinalMessage | None = None

    def take(self, message: Message) -> bool:
        """Fold in one message; ``True`` when it is the final one."""
        match message:
            case Parsed(analysis):
                self.start = analysis
            case StageStarted(stage):
                self.current = stage
            case StageDone(stage, seconds):
                self.timings.append((stage, seconds))
            case AnalysisKnown(analysis):
                self.latest = analysis
            case Finished() | Invalid() | Failed() | JobCancelled():
                self.final = message
                return True
        return False

    def outcome(self, reason: str) -> Finished | Failed:
        """The final message for a process that was ended (``reason``: why, in words): the stages
        it finished as done and the rest unfinished, or ``failed`` if it had not yet read the
        equation."""
        from sorgui.engine.timelimit import unfinished_analysis

        if self.start is None and self.latest is None:
            return Failed(f"{reason} (while reading the equation)")
        start = self.start if self.start is not None else self.latest
        assert start is not None
        timings = tuple(self.timings) if self.timings or self.latest is None else self.latest.timings
        return Finished(
            unfinished_analysis(
                start,
                recognition=None,
                latest=self.latest,
                timings=timings,
                current=self.current,
                message=reason,
                recognition_only=self.recognition_only,
            )
        )


def analysis_child(conn: Connection) -> None:
    """The analysis process: answer every :class:`AnalysisRequest` that arrives, streaming what
    is known, until the pipe closes."""
    become_child()

    def send(message: Message) -> None:
        conn.send(message)

    while True:
        try:
            request = conn.recv()
        except (EOFError, OSError):
            return
        try:
            conn.send(run_request(request, send))
        except (BrokenPipeError, OSError):
            return


def run_request(request: AnalysisRequest, send: Callable[[Message], None]) -> FinalMessage:
    """Analyse ``request``, sending every intermediate message; return the final one."""
    from sorgui.engine import ParseError, SorguiError, analyze

    try:
        analysis = analyze(
            request.text,
            **request.options(),
            progress=lambda stage: send(StageStarted(stage)),
            partial=lambda known: send(AnalysisKnown(known)),
            stage_done=lambda stage, seconds: send(StageDone(stage, seconds)),
            parsed=lambda start: send(Parsed(start)),
        )
        return Finished(analysis)
    except ParseError as exc:
        return Invalid(str(exc), exc.position)
    except SorguiError as exc:
        return Failed(exc.message)
    except MemoryError:
        return Failed("the analysis ran out of memory")
    except Exception as exc:  # noqa: BLE001 - a bug still ends in one line; the details go to stderr
        traceback.print_exc(file=sys.stderr)
        return Failed(f"internal error ({type(exc).__name__}: {exc}); please report it with the input")


class Supervised:
    """One :class:`ChildProcess` running :func:`analysis_child`, given one request at a time,
    with the deadline of the request it is working on."""

    def __init__(self, context: Any) -> None:  # noqa: ANN401 (a multiprocessing context)
        self.child = ChildProcess(context, analysis_child)
        self.request: AnalysisRequest | None = None
        self.log: StageLog | None = None
        self.deadline = float("inf")

    def give(self, request: AnalysisRequest, started: float | None = None) -> None:
        """Send ``request``; its time limit counts from ``started`` (``time.monotonic()``, by
        default now): a command line counts from its own start, so that starting Python and
        importing the engine are inside the limit too."""
        self.request = request
        self.log = StageLog(request.recognition_only)
        limit = request.timeout
        begun = time.monotonic() if started is None else started
        self.deadline = float("inf") if limit is None else begun + limit + GRACE
        self.child.send(request)

    def collect(self, timeout: float = 0.0) -> FinalMessage | None:
        """The final message of the current request if it has come (waiting at most ``timeout``
        seconds for the first message); the process's death or the deadline make one."""
        assert self.log is not None
        first = self.child.receive(min(timeout, max(self.deadline - time.monotonic(), 0.0)))
        for message in ([first] if first is not None else []) + self.child.messages():
            if isinstance(message, Hangup):
                self.child.ended = True
                return Failed(
                    f"the analysis process died ({self.child.exit_description()}); it may have run out of memory"
                )
            if self.log.take(message):
                return self.log.final
        if time.monotonic() >= self.deadline:
            self.child.kill()
            assert self.request is not None and self.request.timeout is not None
            limit = self.request.timeout
            from sorgui.engine.timelimit import limit_message

            return self.log.outcome(limit_message(limit))
        return None

    def run(self, request: AnalysisRequest, started: float | None = None) -> FinalMessage:
        """Give ``request`` and wait for its final message."""
        self.give(request, started)
        while True:
            answer = self.collect(timeout=0.5)
            if answer is not None:
                return answer

    def close(self) -> None:
        self.child.close()


def analyze_supervised(request: AnalysisRequest, started: float | None = None) -> FinalMessage:
    """Analyse ``request`` in a forked child process under its time limit, counted from
    ``started`` (``sorgui analyze``: the start of the process).

    A signal that reaches this process (Ctrl+C, ``SIGTERM``, ``SIGHUP``) unwinds through here and
    kills the child and its Singular at once."""
    import multiprocessing

    import sorgui.engine  # noqa: F401 - loaded before the fork: the child starts at once

    try:
        worker = Supervised(multiprocessing.get_context("fork"))
    except OSError as exc:  # a limit on processes (ulimit -u) or on memory
        return Failed(f"the analysis process could not be started: {exc.strerror or exc}")
    try:
        return worker.run(request, started)
    finally:
        worker.close()
