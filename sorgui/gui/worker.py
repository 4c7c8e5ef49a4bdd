"""Runs analyses in a separate process, so the window never freezes and cancel always works.

:class:`AnalysisWorker` lives on the GUI thread. Each job runs in its own process, started with
the ``spawn`` method (no forked Qt or VTK state) and running :func:`sorgui.session.job.serve`
(through the light :mod:`sorgui.session.process`, so that one can start before the window loads),
which makes it a process-group leader. A timer polls the pipe and turns messages into the Qt
signals :attr:`~AnalysisWorker.progress`, :attr:`~AnalysisWorker.finished`,
:attr:`~AnalysisWorker.failed` and :attr:`~AnalysisWorker.cancelled`.

Cancelling sets the job's :class:`~sorgui.session.process.CancelFlag` (the engine checks it between stages and
kills Singular at once); a process still alive :data:`CANCEL_GRACE_S` later is killed with its
whole tree, Singular included (:meth:`sorgui.session.child.ChildProcess.kill`, the mechanism
``sorgui analyze`` and ``--each-line`` use too). Starting a job supersedes the
running one the same way, silently. The next process is started ahead of time (a warm spare),
so an analysis does not wait for Python to import sympy, flint and VTK; it is started a little
after the previous job ends, so that it competes neither with a running job nor with the GUI
showing the result. Worker processes run at a lower priority (``nice``) than the GUI.
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.context
import signal
import time
from collections import deque
from typing import TYPE_CHECKING

from PySide6.QtCore import QObject, QTimer, Signal

from sorgui.session.child import ChildProcess
from sorgui.session.messages import (
    INTERMEDIATE,
    SUPERVISION,
    Analysed,
    AnalysisKnown,
    Failed,
    Finished,
    Hangup,
    Invalid,
    JobCancelled,
    Message,
    StageDone,
    StageStarted,
)
from sorgui.session.process import CancelFlag, worker_main
from sorgui.session.supervised import GRACE, StageLog

if TYPE_CHECKING:
    from sorgui.session.job import JobRequest

POLL_INTERVAL_MS = 15
"""How often the GUI thread looks at the pipes of running jobs."""

CANCEL_GRACE_S = 0.5
"""How long a cancelled job may take to stop by itself before it is killed."""

SPARE_DELAY_MS = 2000
"""The next worker process starts this long after a job ends, once the result is on screen."""


class _Job(ChildProcess):
    """One worker process with its cancel event, the messages not yet handed on, and the
    deadline of its analysis."""

    def __init__(self, context: multiprocessing.context.SpawnContext, niceness: int | None = None) -> None:
        self.cancel_event = CancelFlag(context)
        super().__init__(context, worker_main, (self.cancel_event, niceness))
        self.kill_at: float | None = None
        self.pending: deque[Message] = deque()
        self.deadline = float("inf")
        self.limit: float | None = None
        self.log: StageLog | None = None

    def give(self, request: JobRequest) -> None:
        """Send ``request``; an analysis must be done by its time limit plus :data:`GRACE`, else the
        process is killed (stuck inside one C call, where the engine's own limit cannot act)."""
        self.send(request)
        if request.analysis is None:
            self.limit = request.singular_timeout
            self.deadline = time.monotonic() + request.singular_timeout + GRACE
            self.log = StageLog(request.recognition_only)

    def request_cancel(self) -> None:
        if self.kill_at is None:
            self.cancel_event.set()
            self.kill_at = time.monotonic() + CANCEL_GRACE_S


class AnalysisWorker(QObject):
    """Starts, supersedes and cancels analysis processes; reports through Qt signals.

    ``first_niceness`` is the priority of the first spare worker (the window's start-up job),
    by default the worker's own. ``finished`` carries a :class:`~sorgui.session.job.JobResult`;
    ``invalid`` a parse error ``(message, position, end)``; ``failed`` a one-line message; ``busy_changed`` whether a
    job is running (for the Analyze and Cancel buttons). ``message`` carries every message of
    the current job (:mod:`sorgui.session.messages`), intermediate results and the final one
    alike: it feeds :meth:`sorgui.session.Session.handle` (the worker is the session's runner).
    """

    progress = Signal(str)
    message = Signal(object)
    finished = Signal(object)
    invalid = Signal(str, int, int)
    failed = Signal(str)
    cancelled = Signal()
    busy_changed = Signal(bool)

    def __init__(self, parent: QObject | None = None, prestart: bool = True, first_niceness: int | None = None) -> None:
        super().__init__(parent)
        self._context = multiprocessing.get_context("spawn")
        self._current: _Job | None = None
        self._retiring: list[_Job] = []
        self._spare: _Job | None = None
        self._prestart = prestart
        self._timer = QTimer(self)
        self._timer.setInterval(POLL_INTERVAL_MS)
        self._timer.timeout.connect(self._poll)
        self._spare_timer = QTimer(self)
        self._spare_timer.setSingleShot(True)
        self._spare_timer.setInterval(SPARE_DELAY_MS)
        self._spare_timer.timeout.connect(self._start_spare)
        if prestart:
            self._spare = _Job(self._context, first_niceness)

    # --- public API ---

    @property
    def is_busy(self) -> bool:
        return self._current is not None

    @property
    def current_pid(self) -> int | None:
        """The process id of the running job (for tests and diagnostics)."""
        return self._current.pid if self._current is not None else None

    def start(self, request: JobRequest) -> None:
        """Run ``request`` in a worker process, superseding (cancelling) the running job."""
        if self._current is not None:
            self._retire(self._current)
        job, self._spare = self._spare, None
        if job is None or not job.process.is_alive():
            job = _Job(self._context)
        job.give(request)
        self._current = job
        self._timer.start()
        self.busy_changed.emit(True)

    def cancel(self) -> None:
        """Ask the running job to stop; it is killed if it has not stopped within the grace time.

        ``cancelled`` is emitted once the job is over.
        """
        if self._current is not None:
            self._current.request_cancel()

    def shutdown(self, wait: float = 1.0) -> None:
        """Kill every process at once (the window is closing) and stop polling; wait at most
        ``wait`` seconds in all for the kernel to release them (none when sorgui is ending)."""
        self._timer.stop()
        self._spare_timer.stop()
        jobs = [j for j in (self._current, self._spare, *self._retiring) if j is not None]
        self._current, self._spare, self._retiring = None, None, []
        for job in jobs:
            job.kill()
        deadline = time.monotonic() + wait
        for job in jobs:
            if wait > 0:
                job.process.join(max(0.0, deadline - time.monotonic()))
            job.conn.close()

    # --- polling ---

    def _start_spare(self) -> None:
        if self._spare is None:
            self._spare = _Job(self._context)

    def _retire(self, job: _Job) -> None:
        """Stop caring about ``job``'s answer; make sure it ends."""
        job.request_cancel()
        self._retiring.append(job)

    def _poll(self) -> None:
        if self._current is not None:
            self._poll_current(self._current)
        now = time.monotonic()
        for job in list(self._retiring):
            job.messages()
            if job.kill_at is not None and now >= job.kill_at:
                job.kill()
            if job.reap():
                self._retiring.remove(job)
        if self._current is None and not self._retiring:
            self._timer.stop()

    def _poll_current(self, job: _Job) -> None:
        """Hand on the job's messages: at most one result per turn of the event loop, so that
        the window draws (and takes input) between showing the verdict, the mesh and the
        formulas."""
        job.pending.extend(job.messages())
        while job.pending:
            message = job.pending.popleft()
            if job.log is not None and not isinstance(message, Hangup):
                job.log.take(message)
            if isinstance(message, SUPERVISION):
                if isinstance(message, Analysed):
                    job.deadline = float("inf")
                continue
            if isinstance(message, StageStarted):
                self.message.emit(message)
                self.progress.emit(message.stage)
                continue
            if isinstance(message, INTERMEDIATE):
                if job.kill_at is None:
                    self.message.emit(message)
                    if not isinstance(message, StageDone):
                        return
                continue
            if job.kill_at is not None:
                message = JobCancelled()  # whatever came back after the user cancelled
            elif isinstance(message, Hangup):
                job.process.join(0.05)
                message = Failed(_exit_message(job.process.exitcode))
            self._end_current(job, message)
            return
        if job.kill_at is not None and time.monotonic() >= job.kill_at:
            job.kill()
            self._end_current(job, JobCancelled())
        elif job.kill_at is None and time.monotonic() >= job.deadline and job.log is not None:
            from sorgui.engine.timelimit import limit_message

            job.kill()  # stuck past the time limit inside one computation: what it finished stands
            outcome = job.log.outcome(limit_message(job.limit or 0.0))
            if isinstance(outcome, Finished):
                from sorgui.session.job import JobResult

                outcome = Finished(JobResult(outcome.result, None, ()))
                self.message.emit(AnalysisKnown(outcome.result.analysis))
            self._end_current(job, outcome)

    def _end_current(self, job: _Job, message: Message) -> None:
        job.ended = True
        self._current = None
        self._retiring.append(job)
        if self._prestart:
            self._spare_timer.start()  # soon, but not while the GUI shows the result
        self.message.emit(message)
        self.busy_changed.emit(False)
        match message:
            case Finished(result):
                self.finished.emit(result)
            case Invalid(text, position, end):
                self.invalid.emit(text, position, end)
            case Failed(text):
                self.failed.emit(text)
            case _:
                self.cancelled.emit()


def _exit_message(exitcode: int | None) -> str:
    if exitcode is not None and exitcode < 0:
        try:
            name = signal.Signals(-exitcode).name
        except ValueError:
            name = f"signal {-exitcode}"
        return f"the analysis process was killed ({name}); it may have run out of memory"
    return f"the analysis process stopped unexpectedly (exit status {exitcode})"
