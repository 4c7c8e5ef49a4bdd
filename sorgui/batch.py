"""``sorgui analyze --each-line``: one equation per line, one JSON object per line (JSON Lines).

Every non-blank line is analysed on its own (``#`` starts a comment: no equation contains it).
Its line of output is the analysis JSON of ``sorgui analyze --json`` with ``"line"`` (1-based)
added, or ``{"line", "input", "error": {"message", "position"}}``; a bad line never stops the
others. The output keeps the order of the input. The input is read as it is analysed, a line
at a time: the length limit of one equation applies to each line, not to the file.

Each line is analysed in a worker process (:class:`~sorgui.session.supervised.Supervised`,
``--jobs`` of them, forked after the engine is imported and warmed up so that each starts at
once, :func:`warm_up`) under the
time limit of one analysis: a worker that does not answer in time is killed with its Singular,
its line answered with the stages it finished, and the worker replaced; so is a worker that
dies (killed, out of memory), its line answered with an error object. Every worker dies with
sorgui. When stderr is a terminal, a progress bar is drawn there.

Exit status: 0 when every line was analysed, 1 when an analysis failed, else 2 when a line was
not a polynomial.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections.abc import Callable, Generator, Iterable, Iterator
from multiprocessing.connection import wait
from typing import TYPE_CHECKING, Any, TextIO

from sorgui.session.messages import Failed, FinalMessage, Finished, Invalid

if TYPE_CHECKING:
    from sorgui.session.supervised import AnalysisRequest, Supervised

Job = tuple[int, str]
"""(line number, equation)."""

Answer = tuple[str, int]
"""A line's JSON text and its status (0 analysed, 1 failed, 2 not a polynomial)."""


def read_lines(stream: TextIO, limit: int) -> Iterator[str]:
    """The lines of ``stream`` as they are read; a line longer than ``limit`` characters is
    given as its first ``limit + 1`` characters (the rest of it is skipped)."""
    while True:
        line = stream.readline(limit + 1)
        if not line:
            return
        if len(line) > limit and not line.endswith("\n"):
            while (rest := stream.readline(limit + 1)) and not rest.endswith("\n"):
                pass
        yield line.rstrip("\n")


def equations(lines: str | Iterable[str]) -> Iterator[Job] | list[Job]:
    """The equations of ``lines`` with their 1-based line numbers (comments and blank lines
    dropped); a list for a text, a lazy iterator for lines being read."""
    if isinstance(lines, str):
        return list(_equations(lines.splitlines()))
    return _equations(lines)


def _equations(lines: Iterable[str]) -> Iterator[Job]:
    for number, line in enumerate(lines, 1):
        equation = line.split("#", 1)[0].strip()
        if equation:
            yield number, equation


def _line_json(number: int, text: str, message: FinalMessage) -> Answer:
    """The output line of a final message of an analysis process."""
    match message:
        case Finished(analysis):
            return json.dumps({"line": number, **analysis.to_json()}), 0
        case Invalid(text_of, position):
            return json.dumps(_error(number, text, text_of, position)), 2
        case Failed(reason):
            return json.dumps(_error(number, text, reason, None)), 1
    return json.dumps(_error(number, text, "the analysis was cancelled", None)), 1


def _error(number: int, text: str, message: str, position: int | None) -> dict[str, Any]:
    return {"line": number, "input": text, "error": {"message": message, "position": position}}


class _Progress:
    """A one-line progress bar on stderr: ``[#####.....] 37/100`` (``37`` when the total is not
    known yet, the input still being read)."""

    WIDTH = 30

    def __init__(self) -> None:
        self.done = 0

    def step(self, total: int | None) -> None:
        self.done += 1
        if total is None:
            sys.stderr.write(f"\r{self.done} analysed")
        else:
            filled = self.WIDTH * self.done // max(total, 1)
            sys.stderr.write(f"\r[{'#' * filled}{'.' * (self.WIDTH - filled)}] {self.done}/{total}")
        sys.stderr.flush()

    def close(self) -> None:
        sys.stderr.write("\n")
        sys.stderr.flush()


WARM_UP = (
    "x**4 + 2*x**2*y**2 + 2*x**2*z**2 + y**4 + 2*y**2*z**2 + z**4 - 74/9*x**2 + 64/9*x*y"
    " + 64/9*x*z - 26/9*y**2 + 128/9*y*z - 26/9*z**2 + 9"
)
"""A torus about the line through 0 along ``(1, 2, 2)``, expanded as the engine prints it: small,
over ``QQ``, on a tilted axis, like the equations of a parts library."""

WARM_UP_RUNS = 8
"""How often :data:`WARM_UP` is analysed before the workers are forked."""


def warm_up() -> None:
    """Analyse :data:`WARM_UP` a few times (recognition only, without sympy, about 12 ms): the
    modules an analysis loads when it first needs them are then loaded, and Python has
    specialised the bytecode of the recognition (the first analyses of a process otherwise run
    about 1.5 times slower), once for every worker forked after it instead of in each."""
    from sorgui.engine import analyze

    for _ in range(WARM_UP_RUNS):
        analyze(WARM_UP, recognition_only=True)


class _Pool:
    """Analysis processes, each given one line at a time (the caller bounds how many are busy)."""

    def __init__(self, request: Callable[[str], AnalysisRequest]) -> None:
        import multiprocessing

        warm_up()  # once, before the forks, for every worker

        self.context = multiprocessing.get_context("fork")
        self.request = request
        self.idle: list[Supervised] = []
        self.busy: dict[int, tuple[Supervised, Job]] = {}  # by the index of the job

    def start(self, index: int, job: Job) -> Answer | None:
        """Give ``job`` to a worker; the line's error object when no worker can be started (a
        limit on processes, ``ulimit -u``)."""
        from sorgui.session.supervised import Supervised

        try:
            worker = self.idle.pop() if self.idle else Supervised(self.context)
        except OSError as exc:
            message = f"the analysis process could not be started: {exc.strerror or exc}"
            return json.dumps(_error(job[0], job[1], message, None)), 1
        worker.give(self.request(job[1]))
        self.busy[index] = (worker, job)
        return None

    def answers(self) -> list[tuple[int, Answer]]:
        """The answers that came (waiting for one, or for the nearest deadline)."""
        now = time.monotonic()
        nearest = min(worker.deadline for worker, _job in self.busy.values())
        wait([worker.child.conn for worker, _job in self.busy.values()], timeout=min(max(nearest - now, 0.0), 1.0))
        found = []
        for index, (worker, job) in list(self.busy.items()):
            message = worker.collect()
            if message is None:
                continue
            del self.busy[index]
            found.append((index, _line_json(*job, message)))
            if worker.child.ended or not worker.child.is_alive():
                worker.close()  # killed at its deadline, or died: a new one takes the next line
            else:
                self.idle.append(worker)
        return found

    def close(self) -> None:
        for worker in [*self.idle, *(w for w, _job in self.busy.values())]:
            worker.close()
        self.idle, self.busy = [], {}


def _results(
    jobs: Iterator[Job], workers: int, request: Callable[[str], AnalysisRequest]
) -> Generator[Answer, None, None]:
    """The answers in input order, ``workers`` lines at a time."""
    pool = _Pool(request)
    answers: dict[int, Answer] = {}
    emitted = 0

    def in_order() -> Iterator[Answer]:
        nonlocal emitted
        while emitted in answers:
            yield answers.pop(emitted)
            emitted += 1

    try:
        for index, job in enumerate(jobs):
            refused = pool.start(index, job)
            if refused is not None:
                answers[index] = refused
            while len(pool.busy) >= workers:
                answers.update(pool.answers())
                yield from in_order()
        while pool.busy:
            answers.update(pool.answers())
            yield from in_order()
        yield from in_order()
    finally:
        pool.close()  # Ctrl+C, a signal, a closed pipe, or done: the workers go too


WORKER_MEMORY = 400 * 2**20
"""Bytes of memory counted for each worker process (an analysis of degree 20 with Singular)."""


def worker_count(requested: int) -> tuple[int, str]:
    """``--jobs`` bounded by twice the cores and by the available memory, and why, if lowered."""
    cores = os.cpu_count() or 1
    try:
        available = os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        available = WORKER_MEMORY * 2 * cores
    allowed = max(1, min(2 * cores, available // WORKER_MEMORY))
    if requested <= allowed:
        return requested, ""
    return allowed, (
        f"--jobs {requested} lowered to {allowed} ({cores} cores, {available / 2**30:.1f} GB of memory available)"
    )


def run_batch(
    lines: Iterable[str], args: argparse.Namespace, emit: Callable[[str], None], total: int | None = None
) -> int:
    """Analyse every line of ``lines`` with the options of ``args``; ``emit`` writes a line.
    ``total`` (the number of equations, when known) sizes the progress bar."""
    from sorgui.session.supervised import AnalysisRequest

    jobs, lowered = worker_count(args.jobs)
    if lowered:
        print(f"sorgui: {lowered}", file=sys.stderr, flush=True)

    def request(text: str) -> AnalysisRequest:
        return AnalysisRequest(
            text,
            method=args.method,
            recognition_only=args.recognition_only,
            tolerance=args.tolerance,
            timeout=args.timeout,
        )

    progress = _Progress() if sys.stderr.isatty() else None
    statuses: set[int] = set()
    answers = _results(iter(equations(lines)), jobs, request)
    try:
        for line, status in answers:
            emit(line)
            statuses.add(status)
            if progress is not None:
                progress.step(total)
    finally:
        answers.close()  # ends the workers now, also when emit failed
        if progress is not None:
            progress.close()
    return 1 if 1 in statuses else (2 if 2 in statuses else 0)
