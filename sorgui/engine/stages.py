"""The stages of an analysis: their names, and the clock that times them.

The pipeline (:mod:`.analysis`) and the recognition-only pipeline over ``QQ``
(:mod:`.rational_path`) both run their stages on a :class:`StageClock`, which reports each stage
as it starts and ends, hands the analysis known so far to a caller, and stops at a set cancel
event.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import replace

from .errors import Cancelled
from .results import Analysis, Recognition

ProgressCallback = Callable[[str], None]
PartialCallback = Callable[[Analysis], None]
DoneCallback = Callable[[str, float], None]

STAGES = (
    "engine",
    "parse",
    "parametric",
    "implicit equation",
    "properness",
    "recognition",
    "factors",
    "real locus",
    "approximate",
    "rationality",
    "parametrizations",
    "conical",
    "canal",
    "nearest",
)


class StageClock:
    """Times named stages, reports them to ``progress`` and stops at a set ``cancel`` event.

    ``partial`` is given the :class:`Analysis` known so far whenever a group of stages is done
    (after the factors, then at the end), so that a window can show the verdict and the axis
    while Singular still runs; ``done`` the name and seconds of every stage as it ends;
    ``parsed`` the equation's skeleton (:func:`~.timelimit.skeleton`) once it is read, and again
    with the recognition once that is known: what a supervising parent that ends the analysis
    reports.

    A stage run a second time (the flint path, :mod:`.rational_path`, declined after it and the
    general pipeline runs it again) is one stage: its seconds add up, in the place of its last run.
    """

    def __init__(
        self,
        progress: ProgressCallback | None,
        cancel: threading.Event | None,
        partial: PartialCallback | None = None,
        done: DoneCallback | None = None,
        parsed: PartialCallback | None = None,
    ) -> None:
        self.progress = progress
        self.cancel = cancel
        self.partial = partial
        self.done = done
        self.parsed = parsed
        self.timings: list[tuple[str, float]] = []
        self.current: str | None = None
        self.start: Analysis | None = None  # the skeleton, for a time limit met before any result
        self.recognition: Recognition | None = None  # kept for a time limit met before publish
        self.latest: Analysis | None = None
        self.decorate: Callable[[Analysis], Analysis] | None = None
        """What every published analysis is completed with (a parametrization's own results)."""

    def publish(self, analysis: Analysis) -> None:
        """Hand the analysis known so far to ``partial`` (if any), and keep it."""
        if self.decorate is not None:
            analysis = self.decorate(analysis)
        self.latest = analysis
        if self.partial is not None:
            self.partial(analysis)

    def read(self, start: Analysis) -> None:
        """The equation is read: keep its skeleton ``start`` and hand it to ``parsed``."""
        self.start = start
        if self.parsed is not None:
            self.parsed(start)

    def recognized(self, recognition: Recognition) -> None:
        """The recognition is done: keep it, and hand ``parsed`` the skeleton with it (the verdict
        and the axis outlive a stage after it that is ended from outside)."""
        self.recognition = recognition
        if self.start is not None and self.parsed is not None:
            self.parsed(replace(self.start, recognition=recognition, squarefree=recognition.polynomial))

    def check(self) -> None:
        """Raise :class:`Cancelled` when the caller asked to stop."""
        if self.cancel is not None and self.cancel.is_set():
            raise Cancelled("the analysis was cancelled")

    @contextmanager
    def stage(self, name: str) -> Iterator[None]:
        """Run one stage: check for cancellation, announce it, and record its duration."""
        self.check()
        self.current = name
        if self.progress is not None:
            self.progress(name)
        start = time.perf_counter()
        yield
        seconds = time.perf_counter() - start
        earlier = [before for done, before in self.timings if done == name]
        if earlier:
            self.timings = [(done, before) for done, before in self.timings if done != name]
            seconds += earlier[0]
        self.timings.append((name, seconds))
        if self.done is not None:
            self.done(name, seconds)
