"""The whole analysis of one pasted equation, stage by stage, with timings and cancellation.

Stages: engine (loading sympy, when a process has not yet) → parse → recognition (symmetry, axis,
profile) → factors → real locus (what the real
surface of a surface of revolution is, docs/math.md §3.4) → approximate (rounded input
or a given tolerance: the nearest surface of revolution, docs/math.md §8) → rationality and
parameterizations (docs/math.md §5–§6; only for a surface of revolution with a unique axis) →
conical (a cone or a cylinder over any curve, docs/math.md §10) → canal → nearest (the whole
analysis of the snapped exact surface).
Between stages the ``cancel`` event is checked, and ``progress`` is told the stage's name, so a
GUI worker can show it; Singular subprocesses are killed on cancel by :mod:`.singular.process`.
``timeout`` bounds the whole analysis (:mod:`.timelimit`): the stages not finished by then are
reported as undecided, those done are kept.

A recognition-only analysis of an equation over ``QQ`` is first tried on python-flint alone
(:mod:`.rational_path`), which gives the same result without loading sympy, and so is the full
analysis of a surface that is neither of revolution, a cone, a cylinder nor canal on its lines;
the sympy-based stages are imported only when the equation needs them. That path runs its stages
on the same clock: a time limit met there reports them as the general pipeline would (it does
not start again), and the stages the general pipeline runs again after the path declined are
timed as one.
"""

from __future__ import annotations

import threading
import time
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from .algebra.linalg import Vector
from .errors import AnalysisError, TimeLimitReached
from .limits import refuse_text_report
from .parsing import has_decimals, is_parametrization, parse_polynomial
from .recognition.symmetry import NEAREST_CANAL_NOTE, PLANE, SPHERE, revolution_canal
from .results import Analysis, Approximation, Canal, Conical
from .stages import DoneCallback, PartialCallback, ProgressCallback, StageClock
from .timelimit import skeleton, time_limit, unfinished_analysis

if TYPE_CHECKING:
    from .algebra.polys import Poly
    from .revolution.reparametrization import GivenMap
    from .rounded.precision import Rounding
    from .stage_results import Parametrization

SPHERE_NOTE = (
    "a sphere: every line through its centre is an axis; the Table 1 row, P and P² are those of the "
    "axis through the centre along z"
)
PLANE_NOTE = (
    "a plane: every line along its normal is an axis; the Table 1 row, P and P² are those of the "
    "normal through the point of the plane nearest the origin"
)
NEAREST_SINGULAR_TIMEOUT = 10.0
"""Each Singular call of the nearest exact surface's analysis stops after this many seconds (or
the analysis' own limit, if shorter). That surface can have coefficients of a hundred digits
(the rational axis nearest an irrational one), on which paraPlaneCurve runs for minutes; the
typed equation's answer must not wait for that."""


def analyze(
    text: str,
    *,
    method: str = "symmetry",
    recognition_only: bool = False,
    singular_timeout: float = 60.0,
    cancel: threading.Event | None = None,
    progress: ProgressCallback | None = None,
    partial: PartialCallback | None = None,
    tolerance: float | None = None,
    timeout: float | None = None,
    stated_timeout: float | None = None,
    stage_done: DoneCallback | None = None,
    parsed: PartialCallback | None = None,
    quick_stages: bool = True,
) -> Analysis:
    """Analyse the equation ``text`` exactly and return the immutable :class:`Analysis`; a
    rational parametrization ``x = X(s, t), y = …, z = …`` is analysed as its surface.

    ``timeout`` (seconds) bounds the whole analysis; each Singular call is bounded by it too.
    The words of a limit that is reached name ``stated_timeout`` when given (the user's limit, of
    which ``timeout`` is what is left after starting the program).
    Inside one long C call (flint, sympy's compiled parts) that bound waits for the call to
    return: a caller that must stop at once runs the analysis in a process it can kill
    (:mod:`sorgui.session.supervised`), which ``stage_done`` (each stage's name and seconds as
    it ends) and ``parsed`` (the :func:`~.timelimit.skeleton` of the equation once it is read,
    again with the recognition once that is done) keep informed.

    ``tolerance`` (relative) asks whether ``f`` is near a surface of revolution; without it,
    that is asked whenever ``text`` prints decimals, with the tolerance their digits give.

    ``partial`` receives the results known so far as they arrive (see :class:`StageClock`).
    ``quick_stages=False`` keeps the stages of the flint-only path (:mod:`.rational_path`, a few
    milliseconds) from the callbacks: a batch's worker analyses hundreds of lines a second, and
    a message for each of their stages made a line a third slower.
    Raises :class:`~sorgui.engine.errors.ParseError` for bad input, :class:`Cancelled` when
    ``cancel`` is set; every other engine failure is a :class:`SorguiError` too.
    """
    clock = StageClock(progress, cancel, partial, stage_done, parsed)
    start = time.monotonic()
    refuse_text_report(text)
    if is_parametrization(text):  # x = X(s, t), y = …, z = …: docs/math.md §13
        from .parametric.pipeline import analyze_parametrization
        from .parametric_parsing import parse_parametrization

        with clock.stage("engine"):
            load_engine()
        with clock.stage("parse"):
            source = parse_parametrization(text)
        limit = singular_timeout

        def implicit(f: Poly, section: tuple[Any, Any, Any] | None, given: GivenMap | None) -> Analysis:
            return analyze_polynomial(
                f,
                method=method,
                recognition_only=recognition_only,
                singular_timeout=limit,
                clock=clock,
                section=section,
                given=given,
            )

        return analyze_parametrization(
            source,
            implicit,
            method=method,
            recognition_only=recognition_only,
            singular_timeout=singular_timeout,
            clock=clock,
            tolerance=tolerance,
            timeout=timeout,
            stated_timeout=stated_timeout,
            parsed=parsed,
            start=start,
        )
    if method == "symmetry" and tolerance is None:
        from .rational_path import full_analysis, recognition_only_analysis

        flint_only = recognition_only_analysis if recognition_only else full_analysis
        quick_clock = clock if quick_stages else StageClock(None, cancel)
        try:
            with time_limit(timeout, stated_timeout):
                quick = flint_only(text, quick_clock)
        except TimeLimitReached as exc:  # the general pipeline would only run the same stages again
            if quick_clock.start is None:
                raise TimeLimitReached(f"{exc.message} (while reading the equation)") from None
            return _unfinished(quick_clock, quick_clock.start, exc.message, recognition_only)
        if quick is not None:
            clock.publish(quick)
            return quick
    with clock.stage("engine"):
        load_engine()
    with clock.stage("parse"):
        f = parse_polynomial(text).polynomial
    if clock.start is None and parsed is not None:  # printing f costs at high degree: only for a caller that asks
        clock.read(skeleton(f, text=text, method=method))
    remaining = None if timeout is None else max(timeout - (time.monotonic() - start), 0.001)
    try:
        with time_limit(remaining, stated_timeout or timeout):
            return analyze_polynomial(
                f,
                text=text,
                method=method,
                recognition_only=recognition_only,
                singular_timeout=singular_timeout if remaining is None else min(singular_timeout, remaining),
                clock=clock,
                tolerance=tolerance,
            )
    except TimeLimitReached as exc:
        return _unfinished(clock, clock.start or skeleton(f, text=text, method=method), exc.message, recognition_only)


def _unfinished(clock: StageClock, start: Analysis, message: str, recognition_only: bool) -> Analysis:
    """The analysis as far as ``clock`` saw it when the time limit was met (``message``), from the
    equation's skeleton ``start`` (:func:`~.timelimit.unfinished_analysis`)."""
    return unfinished_analysis(
        start,
        recognition=clock.recognition,
        latest=clock.latest,
        timings=tuple(clock.timings),
        current=clock.current,
        message=message,
        recognition_only=recognition_only,
    )


def load_engine() -> None:
    """Import sympy and the engine's sympy-based modules: the stage ``engine``, so that their
    import (a few tenths of a second in a new process) is not charged to reading the equation."""
    from .algebra import polys  # noqa: F401 - imported for their side effect of loading
    from .recognition import recognize  # noqa: F401


def analyze_polynomial(
    f: Poly,
    *,
    text: str | None = None,
    method: str = "symmetry",
    recognition_only: bool = False,
    singular_timeout: float = 60.0,
    clock: StageClock | None = None,
    tolerance: float | None = None,
    frame: tuple[Vector, Vector, Vector] | None = None,
    canal: bool = True,
    section: tuple[Any, Any, Any] | None = None,
    given: GivenMap | None = None,
) -> Analysis:
    """The analysis of a polynomial over ``K`` that is already parsed (``text`` defaults to it).

    The tolerance is read off ``text``'s digits unless ``tolerance`` is given (docs/math.md §8);
    ``frame`` is a preferred axis frame for the profile (see :func:`.recognition.recognize.recognize`).
    ``canal=False`` skips the canal stage (the nearest exact surface is a surface of revolution,
    hence canal; the typed equation's canal analysis is the one shown). ``section`` is a rational
    curve on ``X`` that may parameterize ``P²`` (a typed parametrization's, docs/math.md §13);
    ``given`` the typed map itself, whose reparametrizations are not listed again (docs/math.md §6).
    """
    from .algebra.linalg import perpendicular
    from .algebra.polys import field_name, poly_str, total_degree
    from .recognition.profile import plane_foot, power_profile, profile_curve
    from .recognition.recognize import factor_reports, profile_report, recognize
    from .revolution.real_locus import real_locus
    from .stage_results import Rationality

    clock = clock or StageClock(None, None)
    cancel = clock.cancel
    with clock.stage("recognition"):
        recognition, symmetry, profile = recognize(f, method, frame)
    clock.recognized(recognition)
    with clock.stage("factors"):
        factors, distinct = factor_reports(f, recognition, method)
    real = None
    own_profile = profile  # the real locus reads a sphere or a plane as such, not about one axis
    # A quadric sphere (or a power of one): every line through the centre is an axis, Table 1 is read
    # about the one along z (concentric spheres are unions of circles in any meridian plane: not read).
    kept = total_degree(distinct[0]) if len(distinct) == 1 else None  # the degree of the zero set's equation
    centre = symmetry.center if profile is None and symmetry.kind == SPHERE and kept == 2 else None
    sphere = centre is not None
    if centre is not None and not recognition_only:
        K = f.ring.domain
        profile = power_profile(f, distinct[0], centre, (K.zero, K.zero, K.one), (K.one, K.zero, K.zero))
        recognition = replace(recognition, profile=profile_report(profile, K))
    # A plane likewise: every normal line is an axis, Table 1 is read about one of them.
    plane = profile is None and symmetry.kind == PLANE and kept == 1
    if plane and not recognition_only:
        K = f.ring.domain
        foot, normal = plane_foot(distinct[0])  # the plane itself, not a power of it
        profile = power_profile(f, distinct[0], foot, normal, perpendicular(normal, K))
        recognition = replace(recognition, profile=profile_report(profile, K))
    approximation: Approximation | None = None
    near = None
    canal_result: Canal | None = None
    conical_result: Conical | None = None

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
            approximate=approximation,
            canal=canal_result,
            conical=conical_result,
        )

    if not recognition_only and recognition.is_sor:
        # The exact verdict goes out before the real locus, which may outlast the time limit
        # inside one C call: a process killed there had said nothing of its verdict.
        clock.publish(result(None, ()))
        with clock.stage("real locus"):
            real = real_locus(f, symmetry, own_profile)
    rounding: Rounding | None = None
    if tolerance is not None or (text is not None and has_decimals(text)):
        clock.publish(result(None, ()))  # the exact verdict at once: the rounding takes seconds at high degree
        from .rounded.approximate import (  # numpy: only for rounded input
            approximate_symmetry,
            rounding_of,
        )

        with clock.stage("approximate"):
            rounding, rounding_notes = rounding_of(f, text, tolerance)
            assert rounding is not None  # a tolerance is given, or ``text`` prints decimals
            near = approximate_symmetry(
                f,
                rounding,
                notes=rounding_notes,
                snap_exact=not recognition.is_sor,
                sphere=recognition.symmetry == SPHERE,
            )
        approximation = near.approximation

    rationality = None
    tube = None
    found: tuple[Parametrization, ...] = ()
    clock.publish(result(rationality, found))
    if not recognition_only and profile is not None:
        if len(distinct) > 1:
            rationality = Rationality(status="not analysed: X is reducible over K; see its factors")
        else:
            from .revolution.parametrization import plane_map
            from .revolution.rationality import (  # Singular's layer: only here
                analyze_rationality,
                parametrizations,
            )

            g = distinct[0]
            if g != f:
                profile = profile_curve(g, profile.frame.point, profile.frame.direction, profile.frame.normal)
            with clock.stage("rationality"):
                rationality, tube = analyze_rationality(
                    profile, timeout=singular_timeout, cancel=cancel, section=section
                )
            clock.publish(result(rationality, found))
            with clock.stage("parametrizations"):
                found, notes, given_proper = parametrizations(
                    g, profile, rationality, tube, timeout=singular_timeout, cancel=cancel, given=given
                )
                if plane:
                    found = (plane_map(g, profile.frame.point, profile.frame.direction), *found)
            if sphere or plane:
                notes = (SPHERE_NOTE if sphere else PLANE_NOTE, *notes)
            rationality = replace(
                rationality, notes=rationality.notes + notes, given_map_proper=True if given_proper else None
            )
    if canal and not recognition_only:
        from .conical.base_curve import analyze_conical  # Singular's layer: only here

        clock.publish(result(rationality, found))
        with clock.stage("conical"):
            in_force = rounding if approximation is not None else None
            conical_result = analyze_conical(f, timeout=singular_timeout, cancel=cancel, rounding=in_force)
    if canal and recognition_only and recognition.is_sor:
        with clock.stage("canal"):
            canal_result = revolution_canal(recognition.degree)
    elif canal:
        from .canal.verdict import analyze_canal  # Singular's layer: only here

        clock.publish(result(rationality, found))
        with clock.stage("canal"):
            canal_result = analyze_canal(
                f,
                is_sor=recognition.is_sor,
                full=not recognition_only,
                timeout=singular_timeout,
                cancel=cancel,
                profile=None if sphere or plane else profile,  # their families are their own (no axis of their own)
                square=None
                if sphere or plane or tube is None or tube.field
                else (tube.phi, tube.d**2 * tube.h / tube.q**2),
            )
    if (
        near is not None
        and near.nearest is not None
        and near.approximation.nearest is not None
        and not recognition_only
    ):
        clock.publish(result(rationality, found))
        with clock.stage("nearest"):
            try:
                of_nearest = analyze_polynomial(
                    near.nearest,
                    method=method,
                    clock=StageClock(None, cancel),
                    singular_timeout=min(singular_timeout, NEAREST_SINGULAR_TIMEOUT),
                    frame=near.frame,
                    canal=False,
                )
            except AnalysisError as exc:  # the typed equation's answer stands without it
                note = f"the nearest exact surface was not analysed: {exc.message}"
                approximation = replace(near.approximation, notes=(*near.approximation.notes, note))
            else:
                if of_nearest.is_sor:  # canal by its symmetry: said without a line test or Singular
                    of_nearest = replace(
                        of_nearest, canal=revolution_canal(of_nearest.recognition.degree, NEAREST_CANAL_NOTE)
                    )
                approximation = replace(
                    near.approximation, nearest=replace(near.approximation.nearest, analysis=of_nearest)
                )
    clock.check()
    return result(rationality, found)


def _product(polys: list[Poly]) -> Poly:
    """The product of the distinct factors: the square-free part of ``f`` (used for meshing)."""
    result = polys[0]
    for g in polys[1:]:
        result *= g
    return result
