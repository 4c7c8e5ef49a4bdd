"""``sorgui analyze --each-line``: one equation per line, one JSON object per line (JSON Lines).

Every non-blank line is analysed on its own (``#`` starts a comment: no equation contains it).
Its line of output is the analysis JSON of ``sorgui analyze --json`` with ``"line"`` (1-based)
added, or ``{"line", "input", "error": {"message", "position"}}``; a bad line never stops the
others. The output keeps the order of the input. ``--jobs N`` analyses in N worker processes,
forked after the engine is imported (so each starts at once); each worker dies with sorgui
(``PR_SET_PDEATHSIG``) and, on ``SIGTERM``, unwinds so that its Singular is killed. A worker
that dies (killed, out of memory) is replaced, and its line answered with an error object. When stderr is a terminal, a progress bar is drawn there.

Exit status: 0 when every line was analysed, 1 when an analysis failed, else 2 when a line was
not a polynomial.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import signal
import sys
from collections.abc import Callable, Generator
from multiprocessing.connection import Connection, wait
from typing import Any

Job = tuple[int, str, dict[str, Any]]
"""(line number, equation, options of :func:`sorgui.engine.analyze`)."""


def equations(text: str) -> list[tuple[int, str]]:
    """The equations of ``text`` with their 1-based line numbers (comments and blank lines
    dropped)."""
    found = []
    for number, line in enumerate(text.splitlines(), 1):
        equation = line.split("#", 1)[0].strip()
        if equation:
            found.append((number, equation))
    return found


def analyze_line(job: Job) -> tuple[str, int]:
    """One line's JSON text and exit status (0 analysed, 1 failed, 2 not a polynomial)."""
    from sorgui.engine import ParseError, SorguiError, analyze

    number, text, options = job
    try:
        data = {"line": number, **analyze(text, **options).to_json()}
        status = 0
    except ParseError as exc:
        data, status = _error(number, text, str(exc), exc.position), 2
    except SorguiError as exc:
        data, status = _error(number, text, exc.message, None), 1
    except Exception as exc:  # noqa: BLE001 - one bad line must not stop the others
        data, status = _error(number, text, f"internal error ({type(exc).__name__}: {exc})", None), 1
    return json.dumps(data), status


def _error(number: int, text: str, message: str, position: int | None) -> dict[str, Any]:
    return {"line": number, "input": text, "error": {"message": message, "position": position}}


def _worker_start() -> None:
    """A worker leaves Ctrl+C to sorgui, dies with it, and unwinds on ``SIGTERM``."""
    from sorgui.engine.singular import die_with_parent

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _exit_on_signal)
    signal.signal(signal.SIGHUP, _exit_on_signal)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, _ENDING)  # blocked across the fork (see _Worker)
    die_with_parent(signal.SIGTERM)


_ENDING = {signal.SIGTERM, signal.SIGHUP}


def _exit_on_signal(signum: int, _frame: Any) -> None:
    raise SystemExit(128 + signum)


class _Progress:
    """A one-line progress bar on stderr: ``[#####.....] 37/100``."""

    WIDTH = 30

    def __init__(self, total: int) -> None:
        self.total = max(total, 1)
        self.done = 0

    def step(self) -> None:
        self.done += 1
        filled = self.WIDTH * self.done // self.total
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (self.WIDTH - filled)}] {self.done}/{self.total}")
        sys.stderr.flush()

    def close(self) -> None:
        sys.stderr.write("\n")
        sys.stderr.flush()


class _Worker:
    """A forked worker process that analyses one line at a time, sent through its pipe."""

    def __init__(self, context: multiprocessing.context.ForkContext) -> None:
        self.conn, child = context.Pipe()
        self.process = context.Process(target=_serve, args=(child,), name="sorgui-batch", daemon=True)
        # The child starts with sorgui's own SIGTERM handler, which unwinds sorgui's stack: a
        # SIGTERM before the worker installs its own would print a traceback from the fork's
        # clean-up. Blocked here, such a signal waits for the worker's handler.
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, _ENDING)
        try:
            self.process.start()
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, previous)
        child.close()
        self.index: int | None = None  # the job it is analysing

    def give(self, index: int, job: Job) -> None:
        self.index = index
        self.conn.send(job)

    def answer(self, job: Job) -> tuple[str, int]:
        """The worker's answer to ``job``; if the process died instead (killed, out of memory),
        an error object for the line, and the worker is to be replaced."""
        try:
            return self.conn.recv()
        except (EOFError, OSError):
            self.process.join(10)  # its pipe closes a moment before it can be reaped
            code = self.process.exitcode
            how = f"signal {-code}" if code is not None and code < 0 else f"exit status {code}"
            message = f"the analysis process died ({how}); it may have run out of memory"
            return json.dumps(_error(job[0], job[1], message, None)), 1

    def stop(self) -> None:
        """``SIGTERM`` (the worker unwinds: its Singular is killed), then ``SIGKILL`` if needed."""
        self.conn.close()
        if self.process.is_alive():
            self.process.terminate()
            self.process.join(5)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()


def _serve(conn: Connection) -> None:
    """A worker's loop: analyse every job that arrives until the pipe closes."""
    _worker_start()
    while True:
        try:
            job = conn.recv()
        except (EOFError, OSError):
            return
        conn.send(analyze_line(job))


def _results(jobs: list[Job], workers: int) -> Generator[tuple[str, int], None, None]:
    """The answers in input order, from this process or from ``workers`` forked processes; a
    worker that dies is replaced, and its line answered with an error object."""
    if workers == 1 or len(jobs) <= 1:
        yield from map(analyze_line, jobs)
        return
    import sorgui.engine  # noqa: F401 - loaded once, before the fork, for every worker

    context = multiprocessing.get_context("fork")
    todo = list(enumerate(jobs))[::-1]
    pool: list[_Worker] = []
    answers: dict[int, tuple[str, int]] = {}
    emitted = 0
    try:
        pool = [_Worker(context) for _ in range(min(workers, len(jobs)))]
        for worker in pool:
            worker.give(*todo.pop())
        while emitted < len(jobs):
            busy = {worker.conn: worker for worker in pool if worker.index is not None}
            for conn in wait(list(busy)):
                worker = busy[conn]
                index = worker.index
                answers[index] = worker.answer(jobs[index])
                worker.index = None
                if not worker.process.is_alive():
                    worker.stop()
                    pool[pool.index(worker)] = worker = _Worker(context)
                if todo:
                    worker.give(*todo.pop())
            while emitted in answers:
                yield answers.pop(emitted)
                emitted += 1
    finally:
        for worker in pool:  # Ctrl+C, a signal, a closed pipe, or done: the workers go too
            worker.stop()


def run_batch(text: str, args: argparse.Namespace, emit: Callable[[str], None]) -> int:
    """Analyse every line of ``text`` with the options of ``args``; ``emit`` writes a line."""
    options = {"method": args.method, "recognition_only": args.recognition_only, "tolerance": args.tolerance,
               "singular_timeout": args.timeout, "timeout": args.timeout}
    jobs = [(number, equation, options) for number, equation in equations(text)]
    progress = _Progress(len(jobs)) if sys.stderr.isatty() else None
    statuses: set[int] = set()
    answers = _results(jobs, args.jobs)
    try:
        for line, status in answers:
            emit(line)
            statuses.add(status)
            if progress is not None:
                progress.step()
    finally:
        answers.close()  # ends the workers now, also when emit failed
        if progress is not None:
            progress.close()
    return 1 if 1 in statuses else (2 if 2 in statuses else 0)
