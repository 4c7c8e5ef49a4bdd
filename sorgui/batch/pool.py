"""The worker processes of this machine (``--jobs N``): each analyses one line at a time.

Each line is analysed in a worker process (:class:`~sorgui.session.supervised.Supervised`),
started as soon as the batch begins: it loads the engine itself (:func:`ready`) while this
process reads the input, and this process never loads the engine. Each line is under
the time limit of one analysis: a worker that does not answer in time is killed with its
Singular, its line answered with the stages it finished, and the worker replaced; so is a worker
that dies (killed, out of memory), its line answered with an error object. A worker has the next
line waiting in its pipe while it works, so that it never waits for this process between lines;
a line waiting behind one whose worker is ended goes to another worker. Every worker dies with
sorgui.
"""

from __future__ import annotations

import os
import time
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING

from .answers import FAILED, Answer, error_answer, options_of
from .lines import Line

if TYPE_CHECKING:
    from sorgui.session.messages import FinalMessage
    from sorgui.session.supervised import AnalysisRequest, Supervised

WARM_UP = (
    "x**4 + 2*x**2*y**2 + 2*x**2*z**2 + y**4 + 2*y**2*z**2 + z**4 - 74/9*x**2 + 64/9*x*y"
    " + 64/9*x*z - 26/9*y**2 + 128/9*y*z - 26/9*z**2 + 9"
)
"""A torus about the line through 0 along ``(1, 2, 2)``, expanded as the engine prints it: small,
over ``QQ``, on a tilted axis, like the equations of a parts library."""

WARM_UP_RUNS = 8
"""How often a process that forks analysis processes (a Dask worker) analyses :data:`WARM_UP`
before it forks them."""

WORKER_MEMORY = 400 * 2**20
"""Bytes of memory counted for each worker process (an analysis of degree 20 with Singular)."""

LINES_PER_WORKER = 2000
"""A worker is replaced by a new one (which loads the engine in about 50 ms, a few microseconds a line) after
this many lines, so that the memory a long batch leaves behind in it stays bounded: python-flint
0.9 leaks about 110 bytes at each ``str`` of a polynomial, and a batch prints several per line."""


def warm_up(runs: int = WARM_UP_RUNS) -> None:
    """Analyse :data:`WARM_UP` ``runs`` times (recognition only, without sympy, about 0.7 ms a
    run): the modules an analysis loads when it first needs them are then loaded, and after a
    few runs Python has specialised the bytecode of the recognition (the first analyses of a
    process otherwise run about 1.5 times slower). A Dask worker does it once for all the
    analysis processes it forks; a batch's worker, which is not forked from a warm process, runs
    it once (:func:`ready`): more runs would only do what its first lines do anyway (10 lines of
    degree 10 take 36 ms after one run and 41 ms after eight)."""
    from sorgui.engine import analyze

    for _ in range(runs):
        analyze(WARM_UP, recognition_only=True)


def ready() -> None:
    """What a batch's worker does when it starts: load the engine (:func:`warm_up` once)."""
    warm_up(1)


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


class Pool:
    """``workers`` analysis processes (a :class:`.run.Runner`), each working on one line with a
    second one waiting behind it in its pipe (:meth:`Supervised.queue`): a worker goes from one
    line to the next without waiting for this process to read its answer and send the next
    line. Lines that no worker can take yet wait here, in order; a line queued on a worker that
    is ended (its line's time limit, its death) goes back to the front."""

    def __init__(self, workers: int, request: Callable[[str], AnalysisRequest]) -> None:
        import gc

        self.workers = workers
        self.capacity = 2 * workers
        self.request = request
        self.idle: list[Supervised] = []
        self.working: dict[int, Supervised] = {}  # by id
        self.lines: dict[int, list[int]] = {}  # each working worker's lines, by its id: current, then queued
        self.given: dict[int, Line] = {}  # the lines sent to a worker, by index
        self.waiting: deque[tuple[int, Line]] = deque()  # the lines no worker has taken yet
        self.refused: list[tuple[int, Answer]] = []  # lines for which no worker could be started
        self.served: dict[int, int] = {}  # lines given to each worker, by id
        gc.freeze()  # what is loaded now is shared with the workers: no collection of theirs copies its pages
        for _ in range(workers):
            try:
                self.idle.append(self._worker())
            except OSError:
                break  # the line that cannot be started says so
        # While the workers get ready, what this process needs to read their answers.
        import sorgui.engine.results  # noqa: F401
        import sorgui.session.messages  # noqa: F401

    def _worker(self) -> Supervised:
        """A new worker process: it loads the engine itself (:func:`ready`), while this process
        goes on (it never loads the engine)."""
        from sorgui.session.child import FORK
        from sorgui.session.supervised import Supervised

        return Supervised(FORK, ready)

    def busy(self) -> int:
        return len(self.given) + len(self.waiting) + len(self.refused)

    def start(self, index: int, line: Line) -> Answer | None:
        """Take ``line``: it goes to a worker at once if one can take it, else it waits its turn."""
        self.waiting.append((index, line))
        self._dispatch()
        return None

    def _dispatch(self) -> None:
        """Send the waiting lines, in order, each to an idle worker, else behind the line of a
        working one, else to a new worker while fewer than ``workers``
        live; a line for which no worker can be started (a limit on processes, ``ulimit -u``)
        gets its error object."""
        while self.waiting:
            index, line = self.waiting[0]
            request = self.request(line.equation)
            behind = None if self.idle else self._free_queue()
            if self.idle:
                worker = self.idle.pop()
                worker.give(request)
            elif behind is not None:
                worker = behind
                worker.queue(request)
            elif len(self.working) + len(self.idle) < self.workers:
                try:
                    worker = self._worker()
                except OSError as exc:
                    self.waiting.popleft()
                    message = f"the analysis process could not be started: {exc.strerror or exc}"
                    self.refused.append((index, error_answer(line, message, FAILED, options_of(request))))
                    continue
                worker.give(request)
            else:
                return
            self.waiting.popleft()
            self.given[index] = line
            self.working[id(worker)] = worker
            self.lines.setdefault(id(worker), []).append(index)
            self.served[id(worker)] = self.served.get(id(worker), 0) + 1

    def _free_queue(self) -> Supervised | None:
        """A working worker with no line queued that may take one behind its own."""
        for worker in self.working.values():
            if worker.queued is None and self.served[id(worker)] < LINES_PER_WORKER:
                return worker
        return None

    def answers(self) -> list[tuple[int, Answer | FinalMessage]]:
        """The final messages that came (waiting for one, or for the nearest deadline, at most
        1 s); :mod:`.run` makes them the lines' answers."""
        from sorgui.session.child import wait_for_any

        found: list[tuple[int, Answer | FinalMessage]] = [*self.refused]
        self.refused = []
        working = list(self.working.values())
        if found or not working:
            return found
        nearest = min(worker.deadline for worker in working)
        if not any(worker.backlog for worker in working):
            wait_for_any([worker.child for worker in working], min(max(nearest - time.monotonic(), 0.0), 1.0))
        for worker in working:
            lines = self.lines[id(worker)]
            while lines:
                message = worker.collect()
                if message is None:
                    break
                index = lines.pop(0)
                del self.given[index]
                found.append((index, message))
                if worker.child.ended or not worker.child.is_alive():
                    break
            if worker.child.ended or not worker.child.is_alive():
                self._retire(worker)  # killed at its deadline, or died: the line queued on it goes first
                self.waiting.extendleft((index, self.given.pop(index)) for index in reversed(lines))
            elif not lines:
                if self.served[id(worker)] >= LINES_PER_WORKER:
                    self._retire(worker)  # done its share: a new one takes the next line
                else:
                    del self.working[id(worker)], self.lines[id(worker)]
                    self.idle.append(worker)
        self._dispatch()
        found += self.refused
        self.refused = []
        return found

    def _retire(self, worker: Supervised) -> None:
        """End ``worker`` (killed at its deadline, died, or done its share)."""
        self.working.pop(id(worker), None)
        self.lines.pop(id(worker), None)
        self.served.pop(id(worker), None)
        worker.close()

    def close(self) -> None:
        """Kill every worker (and its Singular) without waiting for the kernel to free them."""
        for worker in [*self.idle, *self.working.values()]:
            worker.close(wait=0.0)
        self.idle, self.working, self.lines, self.given = [], {}, {}, {}
        self.waiting.clear()
