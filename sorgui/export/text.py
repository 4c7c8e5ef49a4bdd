"""A short human-readable report of an :class:`~sorgui.engine.results.Analysis` (the CLI's output),
and the JSON document: the report files made from the analysis alone, without sympy."""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from sorgui.engine.results import (
    MAP_NEAR_CEILING,
    MAP_NEAR_FACTOR,
    UNDECIDED,
    Analysis,
    Canal,
    Conical,
    NearestSurface,
    Recognition,
    map_near_limit,
    report_json,
)
from sorgui.engine.vocabulary import UNDECIDED_NEARNESS, canal_kind, kind_phrase
from sorgui.numerics import without_noise

if TYPE_CHECKING:
    from sorgui.engine.stage_results import BaseCurve, Parametrization, Rationality, RealLocus

TABLE_1 = (
    ("reducible", "0", "rational", "rational"),
    ("reducible", ">0", "non-rational", "non-rational"),
    ("0", "0", "rational", "depends on #components"),
    (">0", "0", "rational", "depends on #components"),
    (">0", ">0", "non-rational", "non-rational"),
)
"""Table 1 of the paper: genus(P), genus(P²), X_C, X (real); rows numbered 1–5 top to bottom."""

TABLE_1_WORDS = (
    "The profile P splits into two curves and P² has genus 0: X is rational, over ℂ and over ℝ.",
    "The profile P splits into two curves and P² has positive genus: X is not rational.",
    "The profile P is a rational curve (genus 0), so P² is too: X is rational over ℂ; over ℝ it is "
    "rational when h has at most two real roots (one real piece), otherwise only unirational.",
    "The profile P has positive genus but P² is rational: X is rational over ℂ; over ℝ it is "
    "rational when h has at most two real roots (one real piece), otherwise only unirational.",
    "Both P and P² have positive genus: X is not rational, over ℂ or over ℝ.",
)
"""Each row of Table 1 in words (tooltips and help)."""


def symmetry_name(kind: str | None) -> str:
    """The symmetry kind in the reports' words (:mod:`sorgui.engine.vocabulary`), saying so when
    the surface is not one of revolution."""
    phrase = kind_phrase(kind)
    return f"{phrase}: not a surface of revolution" if kind in ("extrusion", "none") else phrase


def _vec(v: tuple[str, ...] | None) -> str:
    return "(" + ", ".join(v) + ")" if v else "-"


def recognition_lines(rec: Recognition, indent: str = "") -> list[str]:
    """The recognition facts of one polynomial, one per line."""
    dimension = f" (dim L = {rec.symmetry_dimension})" if rec.decided else ""
    lines = [f"{indent}symmetry:  {symmetry_name(rec.symmetry)}{dimension}"]
    if rec.axis is not None:
        lines.append(f"{indent}axis:      {_vec(rec.axis.point)} + t·{_vec(rec.axis.direction)}")
        lines.append(f"{indent}Plücker:   ({' : '.join(rec.axis.plucker)})")
    if rec.center is not None:
        radius = "" if rec.radius_squared is None else f", radius² {rec.radius_squared}"
        lines.append(f"{indent}centre:    {_vec(rec.center)}{radius}")
    if rec.normal is not None:
        lines.append(f"{indent}normal:    {_vec(rec.normal)}")
    if rec.direction is not None:
        lines.append(f"{indent}direction: {_vec(rec.direction)}")
    if rec.profile is not None:
        lines.append(f"{indent}profile:   p(x, y) = {rec.profile.polynomial}")
        lines.append(f"{indent}P²:        {rec.profile.square}")
    return lines


def rationality_lines(rat: Rationality) -> list[str]:
    """The rationality facts (Table 1 row, genera, tubular surface)."""
    lines = [f"rationality: {rat.status}"]
    if rat.profile_reducible is not None:
        lines.append(f"  profile P reducible over C: {'yes' if rat.profile_reducible else 'no'}")
    lines.append(f"  {genus_line(rat)}")
    if rat.table_row is not None:
        row = TABLE_1[rat.table_row - 1]
        lines.append(f"  Table 1, row {rat.table_row}: genus(P) {row[0]}, genus(P²) {row[1]}, X_C {row[2]}, X {row[3]}")
        if rat.real_rational is False and row[3] == "rational":
            lines.append(
                "    (the table's real column is for a surface with real points: this X is not rational over R)"
            )
    for label, value in (
        ("X_C rational", rat.complex_rational),
        ("X unirational", rat.unirational),
        ("X rational (real)", rat.real_rational),
    ):
        lines.append(f"  {label}: {'undecided' if value is None else ('yes' if value else 'no')}")
    if rat.tubular_surface is not None:
        lines.append(f"  tubular surface T: {rat.tubular_surface} = 0")
        lines.append(f"  real roots of h = r̂·q̂: {rat.real_roots_of_h}")
    lines += [f"  note: {n}" for n in rat.notes]
    return lines


def genus_line(rat: Rationality) -> str:
    """The genera of ``P`` and ``P²``, or what stands in their place: a reducible curve has no
    genus of its own (Table 1 then reads "reducible"), and a stage not reached computes none."""
    if rat.profile_reducible is None and rat.genus_profile_square is None:
        return "genus(P), genus(P²): not computed"
    if rat.profile_reducible:
        first = "P is reducible over C (no genus)"
    else:
        first = "genus(P) not computed" if rat.genus_profile is None else f"genus(P) = {rat.genus_profile}"
    if rat.genus_profile_square is not None:
        second = f"genus(P²) = {rat.genus_profile_square}"
    else:
        second = "P² is reducible over C (no genus)" if rat.profile_reducible is not None else "genus(P²) not computed"
    return f"{first}, {second}"


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}" if n == 1 else f"{n} {noun}s"


def real_locus_line(real: RealLocus) -> str:
    """What the real points of ``X`` are, in words (docs/math.md §3.4)."""
    if real.kind == "empty":
        return "real points: none (X has no real point)"
    if real.kind == "surface":
        return "real points: a real surface"
    if real.kind == "undecided":
        return "real points: undecided (the profile is too large for the exact decision)"
    if real.kind == "points":
        return f"real points: only {_count(real.points or 0, 'point')} (no real surface)"
    parts = ["the axis line"] if real.axis_line else []
    if real.circles:
        parts.append(_count(real.circles, "circle") + " about the axis")
    if real.points:
        parts.append(_count(real.points, "isolated point"))
    pieces = ", ".join(parts[:-1]) + " and " + parts[-1] if len(parts) > 1 else "".join(parts)
    return f"real points: only a curve (no real surface): {pieces}"


def parametric_lines(analysis: Analysis) -> list[str]:
    """What a typed parametrization says of itself (docs/math.md §13), before the implicit
    analysis: the map, the decision from its normal lines, the implicit equation's route, properness."""
    record = analysis.parametric
    if record is None:
        return []
    names = ", ".join(record.parameters)
    lines = [f"parametrization in {names} (over {record.field}, degree {record.degree}):"]
    lines += [f"  {c} = {value}" for c, value in zip("xyz", record.components)]
    decided = "undecided" if record.symmetry == UNDECIDED else symmetry_name(record.symmetry)
    lines.append(f"from the map's normal lines: {decided} (dim L = {record.symmetry_dimension})")
    if record.conical == "cone" and record.apex is not None:
        lines.append(f"  a cone: every tangent plane passes through the apex {_vec(record.apex)}")
    elif record.conical == "cylinder" and record.directions:
        lines.append(f"  a cylinder: every tangent plane contains the direction {_vec(record.directions[0])}")
    if record.profile_check is not None:
        u, v = record.map_parameters
        lines.append(f"  cross-check ∂(h, ρ)/∂({u}, {v}) ≡ 0 about the axis: {'yes' if record.profile_check else 'NO'}")
    if record.profile_curve is not None:
        lines.append(f"  profile curve (h, ρ): {record.profile_curve} = 0")
    if record.implicit_status:
        lines.append(f"implicit equation: {record.implicit_status}")
    if record.proper is not None:
        lines.append(
            f"the given map is {'proper' if record.proper else 'not proper'}: {record.fibre} parameter point(s)"
            f" over a point of X ({record.proper_method})"
        )
    elif record.proper_method:
        lines.append(f"properness of the given map: {record.proper_method}")
    lines += [f"note: {note}" for note in record.notes]
    return lines


PLAIN_SUFFIXES = (".json", ".txt")
"""The report files written from the analysis alone, in milliseconds and without sympy: the
command line writes them itself (:func:`json_report`, :func:`text_report`)."""


def json_report(analysis: Analysis) -> str:
    """The JSON document of ``sorgui analyze --json``."""
    return json.dumps(report_json(analysis), indent=1) + "\n"


def text_report(analysis: Analysis) -> str:
    """The command line's report, as it prints it."""
    return plain_text(analysis)


def plain_text(analysis: Analysis) -> str:
    """The whole report as text (ending with a newline)."""
    rec = analysis.recognition
    equation = rec.polynomial or "(the implicit equation is not known)"
    lines = [*parametric_lines(analysis), f"f = {equation}", *analysis_lines(analysis)]
    timing = ", ".join(f"{name} {seconds:.3f} s" for name, seconds in analysis.timings)
    lines.append(f"timings: {timing}")
    return "\n".join(lines) + "\n"


NEAR_KINDS = {
    "revolution": "a surface of revolution",
    "cylinder_of_revolution": "a cylinder of revolution",
    "sphere": "a sphere",
    "plane": "a plane",
    "extrusion": "an extrusion",
}


def float_text(values: Sequence[float], digits: int, tolerance: float | None = None) -> str:
    """``(a, b, c)`` with ``digits`` significant digits and no rounding noise (:func:`without_noise`)."""
    return "(" + ", ".join(f"{c:.{digits}g}" for c in without_noise(values, tolerance)) + ")"


def _floats(v: tuple[float, ...], tolerance: float | None = None) -> str:
    """An approximate vector in the report: 9 significant digits, no rounding noise."""
    return float_text(v, 9, tolerance)


def unit_text(v: Sequence[float], digits: int, tolerance: float | None) -> str:
    """An approximate unit vector (an axis, a normal) with ``digits`` significant digits: its
    components within the rounding ``tolerance`` dropped (:func:`without_noise`), and the rest
    scaled back to length 1 (a tilt of 1.7° within a tolerance of 0.033 was printed
    ``(0, 0, 0.999550219)``, no unit vector, beside the JSON's ``(-0.02999, 0, 0.99955)``)."""
    kept = without_noise(v, tolerance)
    length = math.sqrt(sum(c * c for c in kept))
    if kept != list(v) and length > 0:
        kept = [c / length for c in kept]
    return float_text(kept, digits)


def approximation_lines(analysis: Analysis, nested: bool = True) -> list[str]:
    """The rounded-input verdict in words (docs/math.md §8), with the nearest exact surface and,
    when ``nested``, that surface's whole analysis."""
    ap = analysis.approximate
    if ap is None:
        return []
    source = "from the printed digits" if ap.tolerance_source == "input" else "given"
    tolerance = "beyond floating point" if ap.tolerance is None else f"{ap.tolerance:.2g}"
    lines = [f"rounded input: tolerance {tolerance} (relative, {source})"]
    where = ""
    if ap.axis is not None:
        direction = unit_text(ap.axis.direction, 9, ap.tolerance)
        where = f" about the axis {_floats(ap.axis.point, ap.tolerance)} + t·{direction}"
    elif ap.center is not None:
        where = f" centred at {_floats(ap.center, ap.tolerance)}"
    elif ap.normal is not None:
        across = "along" if ap.kind == "extrusion" else "with normal"  # an extrusion's vector is its direction
        where = f" {across} {unit_text(ap.normal, 9, ap.tolerance)}"
    kind = NEAR_KINDS.get(ap.kind or "", "a surface of revolution")
    exact = analysis.recognition.symmetry
    if ap.near_sor and analysis.is_sor and (ap.kind or exact) == exact:
        lines.append(f"  exactly {kind}, and within the tolerance{where}")
    elif ap.near_sor and analysis.is_sor:  # x² + 1.0001y² + z² − 1: an exact ellipsoid of revolution, nearly a sphere
        exact_kind = NEAR_KINDS.get(exact, "a surface of revolution")
        lines.append(f"  exactly {exact_kind}; within the tolerance, nearly {kind}{where}")
    elif ap.near_sor:
        lines.append(f"  not exactly, but within {ap.relative_distance:.2g} (relative) of {kind}{where}")
    elif ap.kind is not None:
        lines.append(
            f"  not near a surface of revolution; within {ap.relative_distance:.2g} (relative) of {kind}{where}"
        )
    elif ap.residual is None and not ap.singular_values:
        lines.append("  nearness not decided")
    else:
        lines.append("  not near a surface of revolution within the tolerance")
    if ap.residual is not None:
        tried = ap.near_sor or ap.kind not in (None, "none") or ap.residual > 1
        scale = "at most 1: within it" if tried else "no kind of symmetry was tried, see the notes"
        if ap.near_sor and ap.residual > 1:  # a fit excused up to one more rounding of float noise (§8.2)
            scale = "over 1, by less than floating point's own error in the fit: within it"
        unit = (
            f"{_map_limit(ap.tolerance, 'the tolerance')}, a map's limit of nearness"
            if analysis.input_kind == "parametrization"
            else "the rounding"
        )
        lines.append(
            f"  residual {ap.residual:.3g} times {unit} ({scale}); singular values "
            f"of (★): {', '.join(f'{v:.2g}' for v in ap.singular_values)}"
        )
    lines += [f"  note: {note}" for note in ap.notes]
    near = ap.nearest
    if near is not None and not near.within_rounding:
        # Not the part that was meant: said plainly, its analysis only in the JSON (on request).
        deviation = "-" if near.max_deviation is None else f"{near.max_deviation:.2g}"
        lines.append(
            "  no simple exact surface was found within the rounding: the nearest one found lies "
            f"outside it ({outside_words(near)}; relative distance {near.relative_distance:.2g}, "
            f"largest deviation of the zero sets {deviation}); its exact analysis is in the JSON report"
        )
    elif near is not None:
        deviation = "-" if near.max_deviation is None else f"{near.max_deviation:.2g}"
        lines.append(f"  nearest exact surface: g = {near.polynomial}")
        lines.append(
            f"    relative distance {near.relative_distance:.2g}, largest deviation of the zero sets "
            f"{deviation} (length units), every coefficient within the rounding: "
            f"{'yes' if near.within_rounding else 'no'}"
        )
        if near.analysis is not None and nested:
            lines.append("  the analysis of the nearest exact surface:")
            lines += ["    " + line for line in analysis_lines(near.analysis)]
        elif near.analysis is None:
            lines += ["    " + line for line in recognition_lines_of_nearest(near)]
    return lines


def outside_words(near: NearestSurface) -> str:
    """How far outside the rounding a nearest surface is: its coefficient farthest off, in units
    of that coefficient's own rounding (a relative distance below the tolerance can still have
    one coefficient beyond it), or its zero set far from the typed one."""
    if near.largest_residual is None:
        return "a coefficient is off by more than its rounding"
    if near.largest_residual <= 1.0:  # the coefficients are within it, the zero sets far apart
        return "its coefficients are within the rounding, but its zero set is far from the typed one"
    return f"one coefficient is off by {near.largest_residual:.2g} times its own rounding"


def recognition_lines_of_nearest(near: NearestSurface) -> list[str]:
    """The exact axis of the nearest surface when its whole analysis was not run."""
    if near.axis is None:
        return [f"kind: {NEAR_KINDS.get(near.kind, near.kind)}"]
    return [f"axis: {_vec(near.axis.point)} + t·{_vec(near.axis.direction)}"]


def within_words(analysis: Analysis) -> str:
    """What rounded input is near a surface within: the rounding of its digits, or the tolerance
    given with ``--tolerance`` (finer than the digits, it said "the rounding of the input"); a
    map within :data:`~sorgui.engine.results.MAP_NEAR_FACTOR` times that (its deviation 1.8 times
    the tolerance was said to be "within the rounding")."""
    approx = analysis.approximate
    given = approx is not None and approx.tolerance_source == "given"
    words = "the tolerance given" if given else "the rounding of the input"
    if analysis.input_kind != "parametrization" or approx is None:
        return words
    return _map_limit(approx.tolerance, words)


def _map_limit(tolerance: float | None, words: str) -> str:
    """A map's limit of nearness (:func:`~sorgui.engine.results.map_near_limit`) in words: so many
    times ``words`` (the tolerance), or the ceiling when that is coarser."""
    if tolerance is not None and map_near_limit(tolerance) < MAP_NEAR_FACTOR * tolerance:
        return f"{MAP_NEAR_CEILING:g} (relative; {MAP_NEAR_FACTOR:g} times {words} is coarser)"
    return f"{MAP_NEAR_FACTOR:g} times {words}"


def analysis_lines(analysis: Analysis) -> list[str]:
    """Everything the report says of one analysis but the polynomial and the timings."""
    rec = analysis.recognition
    verdict = {
        "sor": "YES",
        "not": "NO",
        "near": f"NO exactly, but NEARLY: within {within_words(analysis)} (see below)",
        "not exactly": f"NO exactly; {UNDECIDED_NEARNESS}",
        "undecided": "undecided",
    }[analysis.verdict]
    lines = [
        f"field K = {analysis.field}, degree {rec.degree if rec.polynomial else 'unknown'}, method {analysis.method}",
        f"surface of revolution: {verdict}",
        *recognition_lines(rec),
    ]
    if analysis.real_locus is not None:
        lines.append(real_locus_line(analysis.real_locus))
    if len(analysis.factors) > 1 or (analysis.factors and analysis.factors[0].multiplicity > 1):
        lines.append(f"factors over K ({len(analysis.factors)}):")
        for factor in analysis.factors:
            lines.append(f"  [{factor.multiplicity}] {factor.polynomial}")
            lines += recognition_lines(factor.recognition, indent="      ")
    if analysis.rationality is not None:
        lines += rationality_lines(analysis.rationality)
    for i, par in enumerate(analysis.parametrizations, 1):
        lines += map_lines(f"parametrization {i}", par)
    if analysis.conical is not None:
        lines += conical_lines(analysis.conical)
    if analysis.canal is not None:
        lines += canal_lines(analysis.canal)
        nearly = nearly_canal(analysis) or typed_canal_note(analysis)
        if nearly:
            lines.append(f"  rounded input: {nearly}")
    if analysis.unfinished:
        lines.append(f"not finished within the time limit (undecided): {', '.join(analysis.unfinished)}")
    lines += approximation_lines(analysis)
    return lines


def typed_canal_note(analysis: Analysis) -> str:
    """For rounded input that is not exactly canal nor near a surface of revolution: that the
    verdict is of the typed coefficients (a Dupin cyclide printed in decimals was told "not
    canal" and nothing more); empty otherwise."""
    approx, canal = analysis.approximate, analysis.canal
    if approx is None or canal is None or canal.is_canal is not False or approx.near_sor:
        return ""
    return (
        "the verdict is of the typed coefficients: a canal surface printed in decimals is seldom exactly canal, "
        "and nearness to a canal surface that is not of revolution is not decided"
    )


def nearly_canal(analysis: Analysis) -> str:
    """For rounded input that is not exactly canal but near a surface of revolution: that its
    nearest exact surface is canal, in words (empty otherwise)."""
    approx, canal = analysis.approximate, analysis.canal
    if approx is None or canal is None or canal.is_canal is not False or approx.nearest is None:
        return ""
    nearest = approx.nearest.analysis
    if nearest is None or nearest.canal is None or not nearest.canal.is_canal:
        return ""
    where = "within the rounding" if approx.nearest.within_rounding else "outside the rounding"
    return (
        "not exactly canal, but nearly: its nearest exact surface (" + where + ") is a surface of "
        "revolution, canal by its symmetry"
    )


def map_lines(title: str, par: Parametrization, indent: str = "", qualities: bool = True) -> list[str]:
    """A verified map to space: its heading (method, real or complex and properness when
    ``qualities``, field, check) and its three coordinates."""
    check = par.verification if par.verified else "NOT verified"
    facts = f"{par.method}; over {par.field}; {check}"
    if qualities:
        kind = "real" if par.real else "complex"
        proper = {True: "proper", False: "not proper", None: "properness unknown"}[par.proper]
        facts = f"{par.method}; {kind}, {proper}, over {par.field}; {check}"
    names = ", ".join(par.parameters)
    return [f"{indent}{title} ({facts}):", *(f"{indent}  {n}({names}) = {c}" for n, c in zip("xyz", par.coordinates))]


def component_words(curve: BaseCurve) -> str:
    """A component of a reducible base curve: its equation, degree, genus and what that makes
    of the component of the surface over it."""
    power = f" (multiplicity {curve.multiplicity})" if curve.multiplicity > 1 else ""
    if curve.genus is not None:
        kind = "rational" if curve.genus == 0 else "not rational"
        facts = f"genus {curve.genus}: its {kind} component"
    elif curve.absolutely_irreducible is False:
        facts = "irreducible over K but not over C"
    else:
        facts = "genus undecided"
    return f"{curve.polynomial} = 0{power}, degree {curve.degree}, {facts}"


def conical_lines(conical: Conical) -> list[str]:
    """Whether ``X`` is a cone or a cylinder over some curve (docs/math.md §10), in words: the
    apex or the direction, the base curve with its genus, and the parameterizations."""
    if conical.kind == "none" and conical.near_apex is not None:
        return [
            f"cone or cylinder over a curve: NO exactly, but nearly a cone about {float_text(conical.near_apex, 6)} "
            f"within the rounding (relative residual {conical.near_residual:.2g})"
        ]
    if conical.kind == "none" and conical.near_direction is not None:
        along = float_text(conical.near_direction, 6)
        return [
            f"cone or cylinder over a curve: NO exactly, but nearly a cylinder along {along} "
            f"within the rounding (relative residual {conical.near_residual:.2g})"
        ]
    if conical.kind == "none" and conical.notes:
        return [f"cone or cylinder over a curve: {note}" for note in conical.notes]
    if conical.kind == "none":
        return ["cone or cylinder over a curve: NO (no apex, no direction of translation)"]
    if conical.kind == "cone":
        lines = [f"cone over a curve: YES, apex {_vec(conical.apex)} (every line through it)"]
    else:
        lines = [f"cylinder over a curve: YES, direction {_vec(conical.direction)} (every line along it)"]
        if conical.apex is not None:
            lines.append(f"  and a cone with apex {_vec(conical.apex)}: planes through the line there")
    base = conical.base_curve
    if base is not None:
        u, v = base.variables
        where = (
            f"in the chart {base.chart}"
            if base.chart is not None
            else f"in the plane {_vec(base.frame_point)} + {u}·{_vec(base.frame_u)} + {v}·{_vec(base.frame_w)}"
        )
        lines.append(f"  base curve ({where}): {base.polynomial} = 0, degree {base.degree}")
        rational = {True: "rational", False: "not rational", None: "undecided whether rational"}[conical.rational]
        if base.reducible:
            lines.append("  reducible over K: so is the surface, one component over each factor")
            lines += [f"    component {i}: {component_words(c)}" for i, c in enumerate(conical.components, 1)]
        elif base.genus is not None:
            lines.append(f"  genus {base.genus}: the surface is {rational}")
        elif base.absolutely_irreducible is False:
            lines.append("  irreducible over K but not over C: so is the surface")
        else:
            lines.append(f"  genus undecided: the surface is {rational}")
    for i, par in enumerate(conical.parametrizations, 1):
        lines += map_lines(f"parametrization {i}", par, "  ")
    lines += [f"  note: {note}" for note in conical.notes]
    return lines


def canal_lines(canal: Canal) -> list[str]:
    """The canal verdict in words (docs/math.md §9): kinds, spines, certificate or witness."""
    verdict = {True: "YES", False: "NO", None: "undecided"}[canal.is_canal]
    lines = [f"canal surface: {verdict} ({canal.status})"]
    if canal.kinds:
        lines.append("  kinds: " + "; ".join(canal_kind(k) for k in canal.kinds))
    for i, fam in enumerate(canal.families, 1):
        shape = "a line" if fam.on_line else ("planar" if fam.planar else "not planar")
        genus = "undecided" if fam.genus is None else str(fam.genus)
        radius = "constant" if fam.pipe else "varying"
        lines.append(
            f"  sphere family {i}: spine of degree {fam.degree} ({shape}), SMAT genus {genus}, radius {radius}"
        )
        lines.append(f"    SMAT equations (m1, m2, m3 centre, r = radius²): {', '.join(fam.equations)}")
        if fam.parametrization is not None:
            check = "verified" if fam.verified else "NOT verified"
            lines.append(
                f"    m(t) = ({', '.join(fam.parametrization)}), r²(t) = {fam.radius_squared} "
                f"(over {fam.field}; {check})"
            )
        elif fam.radical_spine is not None:
            lines.append(
                f"    m(t) in square roots (t = {fam.radical_parameter}) = ({', '.join(fam.radical_spine)}), "
                f"r²(t) = {fam.radical_radius_squared} (verified on the SMAT equations)"
            )
        elif fam.pipe:
            lines.append(f"    r² = {fam.radius_squared} (radius squared)")
        if fam.circle_center is not None:
            lines.append(
                f"    characteristic circles: centre ({', '.join(fam.circle_center)}), "
                f"radius² {fam.circle_radius_squared}, plane normal ({', '.join(fam.circle_normal or ())})"
            )
    if canal.certificate is not None:
        check = "checked" if canal.certificate.verified else "FAILED"
        lines.append(f"  certificate ({canal.certificate.method}, {check}): {canal.certificate.statement}")
    if canal.witness is not None:
        w = canal.witness
        lines.append(f"  witness line ({', '.join(w.point or ())}) + τ·({', '.join(w.direction or ())}): {w.statement}")
    for i, par in enumerate(canal.parametrizations, 1):
        lines += map_lines(f"canal parametrization {i}", par, "  ", qualities=False)
    lines += [f"  note: {n}" for n in canal.notes]
    return lines
