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

The parent folds the messages into a :class:`StageLog`. The time limit is the user's: it counts
from when the command started (for ``sorgui analyze``, the start of the process), and the answer
must be out by then, so the engine is asked to stop :data:`ANSWER_MARGIN` seconds before the
limit (:attr:`AnalysisRequest.deadline`) and bounds itself wherever Python runs; when it has not
answered :data:`GRACE` seconds later (stuck in one C call), the parent kills the child and
reports the stages it finished as done and the rest as unfinished (:meth:`StageLog.outcome`) —
the same answer the engine gives. What is left of the limit after that is for the teardown:
writing the answer and ending the process, a second or more on a busy machine.
"""

from __future__ import annotations

import sys
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from sorgui.session.child import FORK, ChildProcess, become_child
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

ANSWER_MARGIN = 0.7
"""Seconds before the user's time limit at which the engine is asked to have answered."""
GRACE = 0.4
"""Seconds after the engine's deadline that an analysis process is given to answer before it is
killed: the kill comes ``ANSWER_MARGIN - GRACE`` seconds before the user's limit."""
SHORT_SHARE = 0.3
"""A short limit keeps at most this share of itself for the margins (``--timeout 1`` left the
engine 0.3 s, most of it the start of Python, and ended "while reading the equation")."""


def margins(limit: float) -> tuple[float, float]:
    """``(answer margin, grace)`` for a time limit of ``limit`` seconds: :data:`ANSWER_MARGIN`
    and :data:`GRACE`, scaled down together for a limit under ``ANSWER_MARGIN / SHORT_SHARE``."""
    if SHORT_SHARE * limit >= ANSWER_MARGIN:
        return ANSWER_MARGIN, GRACE
    answer = SHORT_SHARE * limit
    return answer, GRACE * answer / ANSWER_MARGIN


@dataclass(frozen=True)
class AnalysisRequest:
    """One equation and the options of :func:`sorgui.engine.analyze` (``timeout`` included)."""

    text: str
    method: str = "symmetry"
    recognition_only: bool = False
    tolerance: float | None = None
    timeout: float | None = None
    deadline: float | None = None
    """The ``time.monotonic()`` by which the engine is to have answered (the clock is the
    machine's, the same in the child), set by :meth:`Supervised.give`; ``None``: ``timeout``
    seconds less :data:`ANSWER_MARGIN` from when the child starts on the request (a request
    queued behind another, :meth:`Supervised.queue`)."""
    quick_stages: bool = True
    """Whether the stages of the engine's flint-only path are reported (``analyze``'s
    ``quick_stages``): not for a batch's lines, each a few milliseconds."""

    def options(self) -> dict[str, Any]:
        """The keywords of :func:`sorgui.engine.analyze`, the time limit being what is left of
        ``timeout`` until the ``deadline`` (asked in the child, when the analysis starts)."""
        left = self.timeout
        if self.deadline is not None:
            left = max(self.deadline - time.monotonic(), 0.001)
        elif left is not None:
            left = max(left - margins(left)[0], 0.001)
        return {
            "method": self.method,
            "recognition_only": self.recognition_only,
            "tolerance": self.tolerance,
            "timeout": left,
            "stated_timeout": self.timeout,
            "singular_timeout": 60.0 if left is None else left,
            "quick_stages": self.quick_stages,
        }


@dataclass
class StageLog:
    """What an analysis process has said so far about one request (``recognition_only``: whether
    the request skipped the rationality, which decides the stages still to come;
    ``quick_stages``: whether the flint-only path reports its stages, :class:`AnalysisRequest`)."""

    recognition_only: bool
    quick_stages: bool = True
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
            case StageDone(stage, seconds):  # a stage run again is timed as one (StageClock)
                self.timings = [(done, before) for done, before in self.timings if done != stage]
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
        equation (naming the stage, the engine's loading or the reading)."""
        from sorgui.engine.timelimit import unfinished_analysis

        if self.start is None and self.latest is None:
            if not self.quick_stages:  # a batch's line: its first stages are not reported
                return Failed(f"{reason} (before it reported a stage)")
            doing = "loading the engine" if self.current == "engine" else "reading the equation"
            return Failed(f"{reason} (while {doing})")
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


def analysis_child(conn: Connection, prepare: Callable[[], None] | None = None) -> None:
    """The analysis process: run ``prepare`` (a batch's worker loads the engine itself, while its
    parent goes on), then answer every :class:`AnalysisRequest` that arrives,
    streaming what is known, until the pipe closes."""
    become_child()
    if prepare is not None:
        prepare()

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
    """Analyse ``request``, sending every intermediate message; return the final one.

    The analysis known so far goes out with the next message, not at once: the engine publishes
    it just before a stage starts (which sends that message) or just before the end, where the
    final message holds it anyway; a line of a batch then costs one message, not two copies of
    its analysis (several hundred kB at degree 20)."""
    from sorgui.engine import ParseError, SorguiError, analyze

    known: list[AnalysisKnown] = []

    def now(message: Message) -> None:
        if known:
            send(known.pop())
        send(message)

    def later(analysis: Analysis) -> None:
        known[:] = [AnalysisKnown(analysis)]

    try:
        analysis = analyze(
            request.text,
            **request.options(),
            progress=lambda stage: now(StageStarted(stage)),
            partial=later,
            stage_done=lambda stage, seconds: now(StageDone(stage, seconds)),
            parsed=lambda start: now(Parsed(start)),
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
    """One :class:`ChildProcess` running :func:`analysis_child` (after ``prepare``, in the child),
    given one request at a time, with the deadline of the request it is working on; a second
    request may wait behind it in the pipe (:meth:`queue`), so that the child starts it without
    waiting for this process to read the first answer and send it."""

    def __init__(self, context: Any, prepare: Callable[[], None] | None = None) -> None:  # noqa: ANN401 (a multiprocessing context)
        self.child = ChildProcess(context, analysis_child, (prepare,))
        self.request: AnalysisRequest | None = None
        self.log: StageLog | None = None
        self.deadline = float("inf")
        self.queued: AnalysisRequest | None = None
        self.backlog: list[Message] = []  # read from the pipe after the current request's final message

    def give(self, request: AnalysisRequest, started: float | None = None) -> None:
        """Send ``request``; its time limit counts from ``started`` (``time.monotonic()``, by
        default now): a command line counts from its own start, so that starting Python and
        importing the engine are inside the limit too. The engine is to answer
        :data:`ANSWER_MARGIN` seconds before the limit, and is killed :data:`GRACE` seconds after that."""
        limit = request.timeout
        if limit is not None:
            begun = time.monotonic() if started is None else started
            request = replace(request, deadline=begun + limit - margins(limit)[0])
        self._begin(request)
        self.child.send(request)

    def queue(self, request: AnalysisRequest) -> None:
        """Send ``request`` to follow the current one: the child starts it once it has answered
        that one, and its time limit counts from then (in the child, and here from when that
        answer is read)."""
        assert self.request is not None and self.queued is None
        self.queued = replace(request, deadline=None)
        self.child.send(self.queued)

    def _begin(self, request: AnalysisRequest) -> None:
        self.request = request
        self.log = StageLog(request.recognition_only, request.quick_stages)
        if request.deadline is not None:
            grace = GRACE if request.timeout is None else margins(request.timeout)[1]
            self.deadline = request.deadline + grace
        elif request.timeout is not None:
            answer, grace = margins(request.timeout)
            self.deadline = time.monotonic() + request.timeout - answer + grace
        else:
            self.deadline = float("inf")

    def collect(self, timeout: float = 0.0) -> FinalMessage | None:
        """The final message of the current request if it has come (waiting at most ``timeout``
        seconds for the first message); the process's death or the deadline make one. After it,
        a queued request is the current one."""
        assert self.log is not None
        backlog, self.backlog = self.backlog, []
        first = None if backlog else self.child.receive(min(timeout, max(self.deadline - time.monotonic(), 0.0)))
        messages = backlog + ([first] if first is not None else []) + self.child.messages()
        for i, message in enumerate(messages):
            if isinstance(message, Hangup):
                self.child.ended = True
                return Failed(
                    f"the analysis process died ({self.child.exit_description()}); it may have run out of memory"
                )
            if self.log.take(message):
                final = self.log.final
                if self.queued is not None:
                    self._begin(self.queued)
                    self.queued = None
                self.backlog = messages[i + 1 :]
                return final
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

    def close(self, wait: float = 1.0) -> None:
        """Kill the child, waiting at most ``wait`` seconds for the kernel to release it."""
        self.child.close(wait)


def analyze_supervised(request: AnalysisRequest, started: float | None = None) -> FinalMessage:
    """Analyse ``request`` in a forked child process under its time limit, counted from
    ``started`` (``sorgui analyze``: the start of the process).

    A signal that reaches this process (Ctrl+C, ``SIGTERM``, ``SIGHUP``) unwinds through here and
    kills the child and its Singular at once."""
    import sorgui.engine  # noqa: F401 - loaded before the fork: the child starts at once

    try:
        worker = Supervised(FORK)
    except OSError as exc:  # a limit on processes (ulimit -u) or on memory
        return Failed(f"the analysis process could not be started: {exc.strerror or exc}")
    try:
        return worker.run(request, started)
    finally:
        worker.close(wait=0.0)  # killed: the answer need not wait for the kernel to free its memory
