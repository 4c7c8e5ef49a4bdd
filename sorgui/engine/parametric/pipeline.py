"""The analysis of a surface typed as a rational parametrization (docs/math.md §13).

Stages, after the engine and the parse (:func:`~sorgui.engine.analyze`): parametric (the exact
decision from the map: the symmetry algebra of its normal lines, the apex, the cylinder
directions, the cross-check of the profile) → approximate (rounded coefficients: the same
systems by least squares) → properness → implicit equation → the stages of the implicit
equation's own analysis (:func:`~sorgui.engine.analysis.analyze_polynomial`: recognition,
factors, real locus, rationality and parameterizations, conical, canal), so that the answer has
the keys of an equation's. Every analysis published on the way carries the parametrization's
own results (``StageClock.decorate``); the given map is the first of the parameterizations. The
two exact decisions, from the map and from the implicit equation, must agree (the same kind,
axis, centre, normal or direction; the same apex).

A surface with no symmetry and no apex gets its equation from Singular's elimination, given
:data:`IMPLICIT_TIMEOUT` seconds at most: a bicubic patch has an equation of degree 18 that
Singular does not find in minutes, and the verdict must not wait for it.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Protocol

from ..algebra.linalg import Vector
from ..algebra.polys import Poly, field_name, poly_str, to_str
from ..conical.detect import Conicity
from ..errors import AnalysisError, SingularError, SingularTimeout, TimeLimitReached
from ..parsing import has_decimals
from ..recognition.recognize import axis_report
from ..recognition.symmetry import Symmetry
from ..results import UNDECIDED, Analysis, Approximation, Canal, Conical, Factor, Recognition, Triple
from ..stage_results import BEING_COMPUTED, GIVEN_MAP, ParametricInput, Parametrization
from ..stages import PartialCallback, StageClock
from ..timelimit import time_limit, unfinished_analysis
from .maps import ParameterRing, RationalMap, fraction_text

if TYPE_CHECKING:
    from sympy.polys.domains.domain import Domain

    from ..revolution.reparametrization import GivenMap

IMPLICIT_TIMEOUT = 30.0
"""Seconds Singular's elimination may take at most (or the analysis' time left, if shorter)."""
PROPER_TIMEOUT = 1.0
"""Seconds for the generic fibre over ``QQ(s₀, t₀)`` before one fibre over a point is counted."""
MAP_PARAMETERS = frozenset({"s", "t", "u", "v", "w", "r", "theta", "tau"})
"""Typed parameter names the exported map keeps (the names sorgui's reports use)."""


class TypedMap(Protocol):
    """A parsed parametrization (:class:`~sorgui.engine.parametric_parsing.TypedMap`)."""

    @property
    def text(self) -> str: ...

    @property
    def components(self) -> tuple[str, str, str]: ...

    @property
    def parameters(self) -> tuple[str, str]: ...

    @property
    def map(self) -> RationalMap: ...

    @property
    def field(self) -> Domain: ...

    @property
    def names(self) -> tuple[str, str] | None: ...

    @property
    def notes(self) -> tuple[str, ...]: ...


ImplicitAnalysis = Callable[[Poly, tuple[Any, Any, Any] | None, "GivenMap | None"], Analysis]
"""The analysis of the implicit equation on the same clock, given a rational curve on ``X`` that
may parameterize its ``P²`` and the typed map itself, whose reparametrizations are not listed
again (:func:`~sorgui.engine.analysis.analyze_polynomial`)."""


def analyze_parametrization(
    source: TypedMap,
    implicit: ImplicitAnalysis,
    *,
    method: str,
    recognition_only: bool,
    singular_timeout: float,
    clock: StageClock,
    tolerance: float | None,
    timeout: float | None,
    stated_timeout: float | None,
    parsed: PartialCallback | None,
    start: float,
) -> Analysis:
    """The analysis of the parametrization ``source``, read at ``start`` (``time.monotonic()``),
    with the options of :func:`~sorgui.engine.analyze`."""
    record = _record(source, None, None)
    opening = _decorated(_undecided(source, method), source.text, record, None)
    if parsed is not None:
        parsed(opening)
    remaining = None if timeout is None else max(timeout - (time.monotonic() - start), 0.001)
    try:
        with time_limit(remaining, stated_timeout or timeout):
            return _analyze(
                source,
                implicit,
                recognition_only=recognition_only,
                singular_timeout=singular_timeout if remaining is None else min(singular_timeout, remaining),
                clock=clock,
                tolerance=tolerance,
                method=method,
            )
    except TimeLimitReached as exc:
        ended = unfinished_analysis(
            opening,
            recognition=None,
            latest=clock.latest,
            timings=tuple(clock.timings),
            current=clock.current,
            message=exc.message,
            recognition_only=recognition_only,
        )
        kept = ended.parametric
        if kept is not None and kept.implicit_status == BEING_COMPUTED:
            ended = replace(ended, parametric=replace(kept, implicit_status=f"not found: {exc.message}"))
        return ended


@dataclass
class _Known:
    """What the map itself has said so far (changes as the stages end)."""

    record: ParametricInput
    approximate: Approximation | None = None
    near: Any = None


def _analyze(
    source: TypedMap,
    implicit: ImplicitAnalysis,
    *,
    method: str,
    recognition_only: bool,
    singular_timeout: float,
    clock: StageClock,
    tolerance: float | None,
) -> Analysis:
    from .detect import conicity, parametric_symmetry, profile_is_a_curve
    from .implicit import implicit_equation

    surface, text = source.map, source.text
    with clock.stage("parametric"):
        symmetry = parametric_symmetry(surface)
        cones = conicity(surface)
        check = None
        if symmetry.axis_point is not None and symmetry.axis_direction is not None:
            check = profile_is_a_curve(surface, symmetry.axis_point, symmetry.axis_direction)
            if not check:
                raise AnalysisError("the axis of the normal lines fails the profile cross-check (internal error)")
        known = _Known(_record(source, symmetry, cones, profile_check=check))
    if tolerance is not None or has_decimals(text):
        with clock.stage("approximate"):
            _approximate(known, surface, text, tolerance)
    decided = _decided(source, symmetry, cones, method)
    clock.decorate = lambda analysis: _decorated(analysis, text, known.record, known.approximate, known.near)
    clock.publish(decided)
    if not recognition_only:
        with clock.stage("properness"):
            known.record = replace(
                known.record,
                **_properness(surface, known.record.map_parameters, singular_timeout, clock.cancel),
            )
        clock.publish(decided)
    with clock.stage("implicit equation"):
        found, status = None, "not computed (recognition only)"
        if not recognition_only or symmetry.kind != "none" or cones.kind != "none":
            try:
                found = implicit_equation(
                    surface, symmetry, cones, timeout=min(IMPLICIT_TIMEOUT, singular_timeout), cancel=clock.cancel
                )
                status = _status(found)
            except SingularTimeout:
                limit = min(IMPLICIT_TIMEOUT, singular_timeout)
                status = f"not found: Singular's elimination did not finish within {limit:g} s"
            except SingularError as exc:
                status = f"not found: {exc.message}"
        known.record = replace(
            known.record,
            implicit_status=status,
            implicit_method=None if found is None else found.method,
            profile_curve=None if found is None or found.profile is None else poly_str(found.profile),
        )
    if found is None:
        reason = status.removeprefix("not found: ")
        final = replace(decided, canal=Canal(None, f"undecided: the implicit equation was not found ({reason})"))
        clock.decorate = None
        return _decorated(
            replace(final, timings=tuple(clock.timings)), text, known.record, known.approximate, known.near
        )
    given = None if recognition_only or not symmetry.is_sor else _given(surface, known.record.map_parameters)
    analysis = implicit(found.polynomial, found.section, given)
    clock.decorate = None
    _agree(analysis, decided)
    if analysis.conical is None:  # recognition only: the map's own apex or directions
        analysis = replace(analysis, conical=decided.conical)
    return _decorated(analysis, text, known.record, known.approximate, known.near)


def _status(found: Any) -> str:
    if found is None:
        return "not found: Singular's elimination runs over QQ only"
    return {
        "profile curve": "found from the profile curve (h, ρ) by a resultant",
        "sphere": "found: |P − c|² is constant",
        "plane": "found: n·P is constant",
        "cylinder base curve": "found from the base curve across the direction by a resultant",
        "cone base curve": "found from the curve of directions from the apex by a resultant",
        "elimination": "found by Singular's elimination",
    }[found.method]


def _approximate(known: _Known, surface: RationalMap, text: str, tolerance: float | None) -> None:
    """The least-squares systems for rounded coefficients (or a given tolerance)."""
    from .nearly import COARSEST, nearly, printed_tolerance

    tau = tolerance if tolerance is not None else printed_tolerance(text)
    if tau is None or tau > COARSEST:
        note = "the decimals are too few to mean a rounding: the coefficients are taken as exact"
        known.record = replace(known.record, notes=(*known.record.notes, note))
        return
    known.approximate, known.near = nearly(surface, tau, "given" if tolerance is not None else "input")


def _properness(
    surface: RationalMap, names: tuple[str, str], timeout: float, cancel: threading.Event | None
) -> dict[str, Any]:
    """``fibre``, ``proper`` and ``proper_method``: the generic fibre if Singular counts it within
    :data:`PROPER_TIMEOUT`, else the fibre over one point of a fixed, unremarkable parameter value
    (named with the typed parameters ``names``)."""
    from ..singular.surfaces import fibre_size

    ring = surface.ring
    if not ring.is_flint:
        return {"proper_method": "not decided: Singular's fibres are counted over QQ only"}
    X, W = [ring.to_sympy(c) for c in surface.X], ring.to_sympy(surface.W)
    try:
        size = fibre_size(X, W, timeout=min(PROPER_TIMEOUT, timeout), cancel=cancel)
        method = "the generic fibre (Singular, over QQ(s0, t0))"
    except SingularTimeout:
        point = surface.sample_points(1, batch=2)[0]
        try:
            size = fibre_size(X, W, (point[0], point[1]), timeout=timeout, cancel=cancel)
        except SingularError as exc:
            return {"proper_method": f"not decided: {exc.message}"}
        method = f"the fibre over the image of ({names[0]}, {names[1]}) = ({point[0]}, {point[1]}) (Singular)"
    except SingularError as exc:
        return {"proper_method": f"not decided: {exc.message}"}
    if size < 1:
        return {"proper_method": f"not decided: {method} is not finite"}
    return {"fibre": size, "proper": size == 1, "proper_method": method}


# --- the analysis objects -----------------------------------------------------------------------


def _triple(K: Any, v: Vector | None) -> Triple | None:
    if v is None:
        return None
    return to_str(K, v[0]), to_str(K, v[1]), to_str(K, v[2])


def _names(source: TypedMap) -> tuple[str, str]:
    """The parameter names of the exported map: the typed ones when reports use them (an
    angle's replaced by its ``tan(u/2)``'s)."""
    names = source.names or source.parameters
    return names if set(names) <= MAP_PARAMETERS else ("s", "t")


def _record(
    source: TypedMap,
    symmetry: Symmetry | None,
    cones: Conicity | None,
    profile_check: bool | None = None,
) -> ParametricInput:
    K = source.field
    ring: ParameterRing = source.map.ring
    names = _names(source)
    components = [fraction_text(ring, n, d, names) for n, d in source.map.fractions()]
    return ParametricInput(
        components=source.components,
        parameters=source.parameters,
        map=(components[0], components[1], components[2]),
        map_parameters=names,
        field=field_name(K),
        degree=source.map.degree,
        symmetry=UNDECIDED if symmetry is None else symmetry.kind,
        symmetry_dimension=0 if symmetry is None else symmetry.dimension,
        symmetry_basis=()
        if symmetry is None
        else tuple(tuple(to_str(K, c) for c in m.a + m.b) for m in symmetry.basis),
        conical="none" if cones is None else cones.kind,
        apex=None if cones is None else _triple(K, cones.apex),
        directions=() if cones is None else tuple(t for d in cones.directions if (t := _triple(K, d)) is not None),
        profile_check=profile_check,
        implicit_status=BEING_COMPUTED if symmetry is not None else "",
        notes=source.notes,
    )


def _given(surface: RationalMap, names: tuple[str, str]) -> GivenMap:
    """The typed map in sympy's ``K[s, t]`` (the engine's names of its parameters) with the names
    the user gave them."""
    from ..revolution.reparametrization import GivenMap

    x, y, z = (surface.ring.to_sympy(c) for c in surface.X)
    return GivenMap((x, y, z), surface.ring.to_sympy(surface.W), names)


def _undecided(source: TypedMap, method: str) -> Analysis:
    """The analysis before any stage after the parse has ended (what a time limit then reports)."""
    recognition = Recognition("", 0, False, UNDECIDED, 0, ())
    return Analysis(
        input=source.text,
        field=field_name(source.field),
        method=method,
        recognition=recognition,
        factors=(Factor("", 1, recognition),),
        squarefree="",
    )


def _decided(source: TypedMap, symmetry: Symmetry, cones: Conicity, method: str) -> Analysis:
    """The analysis from the map alone: the verdict, the axis, centre, normal or direction, the
    apex; the implicit equation is not known yet (``""``). The image of a rational map is
    irreducible: its one factor is itself."""
    K = source.field
    axis = None
    if symmetry.axis_point is not None and symmetry.axis_direction is not None:
        axis = axis_report(symmetry.axis_point, symmetry.axis_direction, K)
    recognition = Recognition(
        polynomial="",
        degree=0,
        is_sor=symmetry.is_sor,
        symmetry=symmetry.kind,
        symmetry_dimension=symmetry.dimension,
        symmetry_basis=tuple(tuple(to_str(K, c) for c in m.a + m.b) for m in symmetry.basis),
        axis=axis,
        center=_triple(K, symmetry.center),
        normal=_triple(K, symmetry.normal),
        direction=_triple(K, symmetry.direction),
    )
    conical = Conical(
        kind=cones.kind,
        apex=_triple(K, cones.apex),
        direction=_triple(K, cones.directions[0]) if cones.directions else None,
        rational=True if cones.kind != "none" else None,
        notes=("decided from the parametrization; the base curve comes with the implicit equation",)
        if cones.kind != "none"
        else (),
    )
    return Analysis(
        input=source.text,
        field=field_name(K),
        method=method,
        recognition=recognition,
        factors=(Factor("", 1, recognition),),
        squarefree="",
        conical=conical,
    )


PROPER_AS_LEFT_OUT = (
    "a proper map of the analysis is the given map after bijections of the parameters, and was left out for it"
)
"""How a typed map is known to be proper when Singular did not decide it (docs/math.md §6)."""


def _decorated(
    analysis: Analysis,
    text: str,
    record: ParametricInput,
    approximate: Approximation | None,
    near: Any = None,
) -> Analysis:
    """``analysis`` as the answer for the typed parametrization: its text, kind and record, the
    given map first among the parameterizations, the least-squares results of rounded input.
    A record whose properness Singular left undecided is proper when the analysis left out a
    proper map that is the given one after bijections of the parameters."""
    rationality = analysis.rationality
    if record.proper is None and rationality is not None and rationality.given_map_proper:
        record = replace(record, fibre=1, proper=True, proper_method=PROPER_AS_LEFT_OUT)
    given = Parametrization(
        coordinates=record.map,
        parameters=record.map_parameters,
        field=record.field,
        real=True,
        proper=record.proper,
        method=GIVEN_MAP,
        verified=True,
        verification="the typed map itself: X is the closure of its image (real parameters may reach part of it only)",
    )
    conical = analysis.conical
    if near is not None and conical is not None and conical.kind == "none":
        conical = replace(conical, near_apex=near.apex, near_direction=near.direction, near_residual=near.residual)
    return replace(
        analysis,
        input=text,
        input_kind="parametrization",
        parametric=record,
        parametrizations=(given, *analysis.parametrizations),
        approximate=approximate if approximate is not None else analysis.approximate,
        conical=conical,
    )


def _agree(analysis: Analysis, decided: Analysis) -> None:
    """The implicit equation's exact recognition must say what the map's did: the same kind and
    axis, centre, normal or direction, and the same apex of a cone."""
    mine, theirs = decided.recognition, analysis.recognition

    def facts(r: Recognition) -> tuple[Any, ...]:
        return (r.symmetry, r.axis, r.center, r.normal, r.direction)

    cones = [c for c in (decided.conical, analysis.conical) if c is not None]
    apexes = len(cones) < 2 or "cone" not in {c.kind for c in cones} or cones[0].apex == cones[1].apex
    if facts(mine) != facts(theirs) or not apexes:
        raise AnalysisError(
            f"the map says {mine.symmetry}, its implicit equation {theirs.symmetry} with other data (internal error)"
        )
