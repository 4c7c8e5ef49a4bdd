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
    while Singular still runs; ``done`` the name and seconds of every stage as it ends.
    """

    def __init__(
        self,
        progress: ProgressCallback | None,
        cancel: threading.Event | None,
        partial: PartialCallback | None = None,
        done: DoneCallback | None = None,
    ) -> None:
        self.progress = progress
        self.cancel = cancel
        self.partial = partial
        self.done = done
        self.timings: list[tuple[str, float]] = []
        self.current: str | None = None
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
        self.timings.append((name, seconds))
        if self.done is not None:
            self.done(name, seconds)
