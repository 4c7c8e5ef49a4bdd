"""One time limit for the whole analysis, and what is reported when it is reached.

The Python stages (recognition, factors over ``K``, parameterizations) can run for minutes
inside sympy, where no cancel event is looked at. In the main thread, :func:`time_limit`
therefore arms a one-shot ``SIGALRM`` timer whose handler raises :class:`TimeLimitReached`
wherever the analysis is; a Singular call it interrupts kills Singular on the way out
(:mod:`.singular.process`). In other threads only the Singular calls are bounded (by the time left).
:func:`unfinished_analysis` then reports the stages that did not finish as
undecided and keeps those that did.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from types import FrameType
from typing import TYPE_CHECKING

from .errors import TimeLimitReached
from .results import UNDECIDED, Analysis, Recognition

if TYPE_CHECKING:
    from .algebra.polys import Poly


def limit_message(seconds: float) -> str:
    """The words of a time limit that was reached, by the engine's alarm or by a parent that
    ended the analysis process (:mod:`sorgui.session.supervised`)."""
    return f"the analysis did not finish within the time limit of {seconds:g} s"


LONGEST_ALARM = 1e8
"""Seconds (three years): a longer limit (``--timeout 1e10``) is this one, which the system's
timer can hold."""


@contextmanager
def time_limit(seconds: float | None, stated: float | None = None) -> Iterator[None]:
    """Raise :class:`TimeLimitReached` inside the block once ``seconds`` have passed (main thread
    only, where signals are delivered; elsewhere, and for ``None``, the block is not bounded).
    The message names the ``stated`` limit (the caller's, of which ``seconds`` may be the rest)."""
    usable = hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
    if seconds is None or not usable:
        yield
        return

    def expire(_signum: int, _frame: FrameType | None) -> None:
        raise TimeLimitReached(limit_message(stated or seconds))

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, min(seconds, LONGEST_ALARM))
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def skeleton(f: Poly, *, text: str, method: str) -> Analysis:
    """The analysis of ``f`` before any stage has finished: its polynomial, degree and field, with
    the symmetry :data:`UNDECIDED`. What a time limit met before the recognition reports; an
    analysis process sends it to its parent as soon as the equation is read."""
    from .algebra.polys import field_name, poly_str, total_degree

    return printed_skeleton(poly_str(f), total_degree(f), field_name(f.ring.domain), text=text, method=method)


def printed_skeleton(printed: str, degree: int, field: str, *, text: str, method: str) -> Analysis:
    """The :func:`skeleton` of the polynomial ``printed`` of total degree ``degree`` over
    ``field``, without sympy (the flint path's, :mod:`.rational_path`)."""
    recognition = Recognition(
        polynomial=printed,
        degree=degree,
        is_sor=False,
        symmetry=UNDECIDED,
        symmetry_dimension=0,
        symmetry_basis=(),
    )
    return Analysis(
        input=text,
        field=field,
        method=method,
        recognition=recognition,
        factors=(),
        squarefree=printed,
    )


def unfinished_analysis(
    start: Analysis,
    *,
    recognition: Recognition | None,
    latest: Analysis | None,
    timings: tuple[tuple[str, float], ...],
    current: str | None,
    message: str,
    recognition_only: bool,
) -> Analysis:
    """The analysis as far as it got: ``latest`` (the last complete group of stages), else
    ``start`` (the :func:`skeleton`) with the ``recognition`` if there is one; ``unfinished``
    lists the stage that was running (``current``) and the stages of the equation's analysis
    (:func:`~.analysis.analyze_polynomial`) that were still to come, the cone and canal ones
    included, and a map's properness and implicit equation before them (a map stopped in its
    properness said nothing of its implicit equation).

    Needs no sympy: the parent of a killed analysis process composes it from what the process
    sent before it was ended."""
    if latest is None:
        latest = (
            start if recognition is None else replace(start, recognition=recognition, squarefree=recognition.polynomial)
        )
    rec = latest.recognition
    may_be_sor = rec.symmetry == UNDECIDED or rec.is_sor
    needs_rationality = not recognition_only and (rec.symmetry == UNDECIDED or (rec.is_sor and rec.profile is not None))
    # A map's verdicts come from the map itself (docs/math.md §13): its symmetry and its cone or
    # cylinder are decided, whatever is left of the analysis of its implicit equation.
    from_map = latest.input_kind == "parametrization" and rec.symmetry != UNDECIDED
    # A map's own stages before those of its implicit equation (:mod:`.parametric.pipeline`).
    of_map = latest.input_kind == "parametrization"
    pipeline = [
        *(("properness",) if of_map and not recognition_only else ()),
        *(("implicit equation",) if of_map else ()),
        "recognition",
        "factors",
        *(("real locus",) if not recognition_only and may_be_sor else ()),
        *(("approximate",) if not rec.is_sor and latest.approximate is None and _rounded(latest.input) else ()),
        *(("rationality", "parametrizations") if needs_rationality else ()),
        *(() if recognition_only else ("conical",)),
        "canal",
    ]
    done = {name for name, _ in timings}
    if from_map:
        done |= {"recognition"} | ({"conical"} if latest.conical is not None else set())
    unfinished = [s for s in pipeline if s not in done]
    if current is not None and current not in done and current not in unfinished:
        unfinished.insert(0, current)
    rationality = latest.rationality
    if rationality is None and needs_rationality:
        from .stage_results import Rationality  # loaded only when a rationality stage was to come

        rationality = Rationality(status=f"undecided: {message}")
    elif rationality is not None and "parametrizations" in unfinished:
        rationality = replace(rationality, notes=(*rationality.notes, f"no parameterizations: {message}"))
    return replace(latest, rationality=rationality, timings=timings, unfinished=tuple(unfinished))


def _rounded(text: str) -> bool:
    """Whether ``text`` prints decimals: its rounding is analysed (the stage ``approximate``)."""
    from .parsing import has_decimals  # flint: only for an analysis that met its limit

    return has_decimals(text)
