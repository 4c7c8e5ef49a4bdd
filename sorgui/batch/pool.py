"""The worker processes of this machine (``--jobs N``): each analyses one line at a time.

Each line is analysed in a worker process (:class:`~sorgui.session.supervised.Supervised`),
forked after the engine is imported and warmed up (:func:`warm_up`) so that each starts at
once, under the time limit of one analysis: a worker that does not answer in time is killed
with its Singular, its line answered with the stages it finished, and the worker replaced; so
is a worker that dies (killed, out of memory), its line answered with an error object. Every
worker dies with sorgui.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from multiprocessing.connection import wait
from typing import TYPE_CHECKING

from sorgui.session.messages import FinalMessage

from .answers import FAILED, Answer, error_answer
from .lines import Line

if TYPE_CHECKING:
    from sorgui.session.supervised import AnalysisRequest, Supervised

WARM_UP = (
    "x**4 + 2*x**2*y**2 + 2*x**2*z**2 + y**4 + 2*y**2*z**2 + z**4 - 74/9*x**2 + 64/9*x*y"
    " + 64/9*x*z - 26/9*y**2 + 128/9*y*z - 26/9*z**2 + 9"
)
"""A torus about the line through 0 along ``(1, 2, 2)``, expanded as the engine prints it: small,
over ``QQ``, on a tilted axis, like the equations of a parts library."""

WARM_UP_RUNS = 8
"""How often :data:`WARM_UP` is analysed before the workers are forked."""

WORKER_MEMORY = 400 * 2**20
"""Bytes of memory counted for each worker process (an analysis of degree 20 with Singular)."""

LINES_PER_WORKER = 2000
"""A worker is replaced by a new one (forked from the warmed-up parent, in milliseconds) after
this many lines, so that the memory a long batch leaves behind in it stays bounded: python-flint
0.9 leaks about 110 bytes at each ``str`` of a polynomial, and a batch prints several per line."""


def warm_up() -> None:
    """Analyse :data:`WARM_UP` a few times (recognition only, without sympy, about 12 ms): the
    modules an analysis loads when it first needs them are then loaded, and Python has
    specialised the bytecode of the recognition (the first analyses of a process otherwise run
    about 1.5 times slower), once for every worker forked after it instead of in each."""
    from sorgui.engine import analyze

    for _ in range(WARM_UP_RUNS):
        analyze(WARM_UP, recognition_only=True)


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
    """``workers`` analysis processes, each given one line at a time (a :class:`.run.Runner`)."""

    def __init__(self, workers: int, request: Callable[[str], AnalysisRequest]) -> None:
        import multiprocessing

        warm_up()  # once, before the forks, for every worker

        self.capacity = workers
        self.context = multiprocessing.get_context("fork")
        self.request = request
        self.idle: list[Supervised] = []
        self.running: dict[int, Supervised] = {}  # by the index of the line
        self.served: dict[int, int] = {}  # lines given to each worker, by id

    def busy(self) -> int:
        return len(self.running)

    def start(self, index: int, line: Line) -> Answer | None:
        """Give ``line`` to a worker; the line's error object when no worker can be started (a
        limit on processes, ``ulimit -u``)."""
        from sorgui.session.supervised import Supervised

        try:
            worker = self.idle.pop() if self.idle else Supervised(self.context)
        except OSError as exc:
            return error_answer(line, f"the analysis process could not be started: {exc.strerror or exc}", FAILED)
        worker.give(self.request(line.equation))
        self.running[index] = worker
        self.served[id(worker)] = self.served.get(id(worker), 0) + 1
        return None

    def answers(self) -> list[tuple[int, FinalMessage]]:
        """The final messages that came (waiting for one, or for the nearest deadline, at most
        1 s); :mod:`.run` makes them the lines' answers."""
        now = time.monotonic()
        nearest = min(worker.deadline for worker in self.running.values())
        wait([worker.child.conn for worker in self.running.values()], timeout=min(max(nearest - now, 0.0), 1.0))
        found = []
        for index, worker in list(self.running.items()):
            message = worker.collect()
            if message is None:
                continue
            del self.running[index]
            found.append((index, message))
            if worker.child.ended or not worker.child.is_alive() or self.served[id(worker)] >= LINES_PER_WORKER:
                del self.served[id(worker)]
                worker.close()  # killed at its deadline, died, or done its share: a new one takes the next line
            else:
                self.idle.append(worker)
        return found

    def close(self) -> None:
        for worker in [*self.idle, *self.running.values()]:
            worker.close()
        self.idle, self.running = [], {}
