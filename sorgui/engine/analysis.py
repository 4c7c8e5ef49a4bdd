"""The whole analysis of one pasted equation, stage by stage, with timings and cancellation.

Stages: parse → recognition (symmetry, axis, profile) → factors → rationality and
parameterizations (docs/math.md §5–§6; only for a surface of revolution with a unique axis).
Between stages the ``cancel`` event is checked, and ``progress`` is told the stage's name, so a
GUI worker can show it; Singular subprocesses are killed on cancel by :mod:`.singular`.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import replace

from .errors import Cancelled
from .parsing import parse_polynomial
from .polys import Poly, field_name, poly_str
from .profile import profile_curve
from .rationality import analyze_rationality, parametrizations
from .real_locus import real_locus
from .recognition import factor_reports, recognize
from .report import Analysis, Parametrization, Rationality

ProgressCallback = Callable[[str], None]
PartialCallback = Callable[[Analysis], None]

STAGES = ("parse", "recognition", "factors", "real locus", "rationality", "parametrizations")


class StageClock:
    """Times named stages, reports them to ``progress`` and stops at a set ``cancel`` event.

    ``partial`` is given the :class:`Analysis` known so far whenever a group of stages is done
    (after the factors, then at the end), so that a window can show the verdict and the axis
    while Singular still runs.
    """

    def __init__(
        self,
        progress: ProgressCallback | None,
        cancel: threading.Event | None,
        partial: PartialCallback | None = None,
    ) -> None:
        self.progress = progress
        self.cancel = cancel
        self.partial = partial
        self.timings: list[tuple[str, float]] = []

    def publish(self, analysis: Analysis) -> None:
        """Hand the analysis known so far to ``partial`` (if any)."""
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
        if self.progress is not None:
            self.progress(name)
        start = time.perf_counter()
        yield
        self.timings.append((name, time.perf_counter() - start))


def analyze(
    text: str,
    *,
    method: str = "symmetry",
    recognition_only: bool = False,
    singular_timeout: float = 60.0,
    cancel: threading.Event | None = None,
    progress: ProgressCallback | None = None,
    partial: PartialCallback | None = None,
) -> Analysis:
    """Analyse the equation ``text`` exactly and return the immutable :class:`Analysis`.

    ``partial`` receives the results known so far as they arrive (see :class:`StageClock`).
    Raises :class:`~sorgui.engine.errors.ParseError` for bad input, :class:`Cancelled` when
    ``cancel`` is set; every other engine failure is a :class:`SorguiError` too.
    """
    clock = StageClock(progress, cancel, partial)
    with clock.stage("parse"):
        parsed = parse_polynomial(text)
    return analyze_polynomial(
        parsed.polynomial,
        text=text,
        method=method,
        recognition_only=recognition_only,
        singular_timeout=singular_timeout,
        clock=clock,
    )


def analyze_polynomial(
    f: Poly,
    *,
    text: str | None = None,
    method: str = "symmetry",
    recognition_only: bool = False,
    singular_timeout: float = 60.0,
    clock: StageClock | None = None,
) -> Analysis:
    """The analysis of a polynomial over ``K`` that is already parsed (``text`` defaults to it)."""
    clock = clock or StageClock(None, None)
    cancel = clock.cancel
    with clock.stage("recognition"):
        recognition, symmetry, profile = recognize(f, method)
    with clock.stage("factors"):
        factors, distinct = factor_reports(f, recognition, method)
    real = None
    if not recognition_only and recognition.is_sor:
        with clock.stage("real locus"):
            real = real_locus(f, symmetry, profile)

    def result(rationality: Rationality | None, found: tuple[Parametrization, ...]) -> Analysis:
        return Analysis(
            input=poly_str(f) if text is None else text,
            field=field_name(f.ring.domain),
            method=method,
            recognition=recognition,
            factors=factors,
            squarefree=poly_str(_product(distinct)),
            rationality=rationality,
            parametrizations=found,
            timings=tuple(clock.timings),
            real_locus=real,
        )

    rationality = None
    found: tuple[Parametrization, ...] = ()
    clock.publish(result(rationality, found))
    if not recognition_only and profile is not None:
        if len(distinct) > 1:
            rationality = Rationality(status="not analysed: X is reducible over K; see its factors")
        else:
            g = distinct[0]
            if g != f:
                profile = profile_curve(g, symmetry.axis_point, symmetry.axis_direction)
            with clock.stage("rationality"):
                rationality, tube = analyze_rationality(profile, timeout=singular_timeout, cancel=cancel)
            clock.publish(result(rationality, found))
            with clock.stage("parametrizations"):
                found, notes = parametrizations(g, profile, rationality, tube, timeout=singular_timeout, cancel=cancel)
            rationality = replace(rationality, notes=rationality.notes + notes)
    clock.check()
    return result(rationality, found)


def _product(polys: list[Poly]) -> Poly:
    """The product of the distinct factors: the square-free part of ``f`` (used for meshing)."""
    result = polys[0]
    for g in polys[1:]:
        result *= g
    return result
