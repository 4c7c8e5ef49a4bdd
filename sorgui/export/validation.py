"""What a report file may hold: every value checked against what sorgui itself writes.

A report (``*.sorgui.json``) is a file people send each other, so :func:`validate` checks the
:class:`~sorgui.engine.results.Analysis` decoded from one before anything shows or exports it;
its claims are then checked against its polynomial by the engine
(:func:`sorgui.engine.claims.report.check_report`):

* every field has the type sorgui writes (a bool where a bool goes, a tuple of three strings
  for a point, a finite number where a number goes: JSON's ``NaN`` is no number);
* every exact string is read by the engine's reader of machine-written formulas
  (:mod:`sorgui.engine.expressions`) and must be of its field's :class:`Form`: a number (no
  variable, no ``I``), a polynomial or a rational function in the field's own variables (a
  map's parameters, a family's parameter), ``I`` only in complex maps, ``cos``/``sin`` of the
  angle and square roots of polynomials only in the circles of a canal surface; bounded as
  typed input is bounded: the polynomials of the surface and its profile of degree at most
  :data:`~sorgui.engine.parsing.MAX_DEGREE`, every other formula at most :data:`MAP_DEGREE`,
  and the numbers their expansion makes at most :data:`MAX_HEIGHT_BITS` bits;
* a field is ``QQ`` or ``QQ(…)`` of square roots of rationals (real ones for ``K``), the kinds
  (symmetry, real locus, canal kinds and certificates, stages) come from fixed lists;
* the equation is read by the project's parser, as if it had been typed;
* every other string (notes, statements, methods) is one line of printable text of bounded
  length: no control character, so no newline that could end a comment in an exported file.

A report that does not validate is refused with one line naming the field
(:class:`ReportInvalid`). The exporters quote every value in their format's own way as well.
"""

from __future__ import annotations

import math
import re
import typing
import unicodedata
from dataclasses import dataclass, fields, is_dataclass
from types import NoneType, UnionType
from typing import Any

import sympy

from sorgui.engine import results, stage_results
from sorgui.engine.claims.formulas import NAMES, REPORT_SYNTAX, formula
from sorgui.engine.errors import ExpressionError, ParseError, SorguiError
from sorgui.engine.parsing import MAX_DEGREE

EXACT = REPORT_SYNTAX
"""The syntax of every exact string sorgui writes into a report."""

MAX_TEXT = 20_000
"""Characters of one line of text (a note, a statement) at most."""

MAX_EXPRESSION = 16_000_000
"""Characters of one exact expression at most (sorgui's largest are a few million: the
parameterization of the envelope of a family of spheres of degree 6 prints 3 MB)."""

MAP_DEGREE = 4 * MAX_DEGREE
"""The largest degree (numerator and denominator together) of a map, a family's formula or an
equation of a report other than the surface's and its profile's."""

MAX_HEIGHT_BITS = 2_000_000
"""The largest size, in bits, of the numbers a formula's expansion can hold (a bound computed
from its tree: ``(10^300·x + 1)^240`` would expand to numbers of 72,000 digits)."""

SYMMETRIES = frozenset({"revolution", "cylinder_of_revolution", "sphere", "plane", "extrusion", "none", "undecided"})
VOCABULARY: dict[tuple[str, str], frozenset[str]] = {
    ("Recognition", "symmetry"): SYMMETRIES,
    ("Analysis", "method"): frozenset({"symmetry", "paper"}),
    ("RealLocus", "kind"): frozenset({"empty", "points", "curve", "surface", "undecided"}),
    ("Canal", "kinds"): frozenset({"pipe", "revolution", "dupin", "developable"}),
    ("Approximation", "kind"): SYMMETRIES,
    ("Approximation", "tolerance_source"): frozenset({"input", "given"}),
    ("NearestSurface", "kind"): SYMMETRIES,
    ("Conical", "kind"): frozenset({"cone", "cylinder", "none"}),
    ("BaseCurve", "chart"): frozenset({"x = 1", "y = 1", "z = 1"}),
    ("Analysis", "input_kind"): frozenset({"equation", "parametrization"}),
    ("ParametricInput", "symmetry"): SYMMETRIES,
    ("ParametricInput", "conical"): frozenset({"cone", "cylinder", "none"}),
    ("ParametricInput", "implicit_method"): frozenset(
        {"profile curve", "sphere", "plane", "cylinder base curve", "cone base curve", "elimination"}
    ),
}
"""Fields whose every string comes from a fixed list."""

CERTIFICATE_METHODS = frozenset(
    {"profile", "resultant", "incidence", "elimination", "rotation", "symmetry", "line", "components"}
)


@dataclass(frozen=True)
class Form:
    """What the exact strings of one field are: ``kind`` ``number`` (of a field), ``polynomial``,
    ``rational`` (a rational function) or ``circles`` (a rational function of a parameter and of
    ``cos θ``, ``sin θ``, with square roots of polynomials of the parameter); ``variables`` are
    the names it may use, or the sibling field that gives them (``"parameters"``); ``degree``
    bounds it; ``complex`` allows ``I``."""

    kind: str
    variables: tuple[str, ...] | str = ()
    degree: int = MAP_DEGREE
    complex: bool = False


NUMBER = Form("number", degree=0)
XYZ = ("x", "y", "z")
SURFACE = Form("polynomial", XYZ, MAX_DEGREE)
FORMS: dict[tuple[str, str], Form] = {
    ("Axis", "point"): NUMBER,
    ("Axis", "direction"): NUMBER,
    ("Axis", "plucker"): NUMBER,
    ("Profile", "polynomial"): Form("polynomial", ("x", "y"), MAX_DEGREE),
    ("Profile", "square"): Form("polynomial", ("x", "y"), MAX_DEGREE),
    ("Profile", "rational"): Form("polynomial", ("s", "r"), MAX_DEGREE),
    ("Profile", "rational_square"): Form("polynomial", ("s", "w"), MAX_DEGREE),
    ("Profile", "frame_point"): NUMBER,
    ("Profile", "frame_direction"): NUMBER,
    ("Profile", "frame_normal"): NUMBER,
    ("Recognition", "polynomial"): SURFACE,
    ("Recognition", "symmetry_basis"): NUMBER,
    ("Recognition", "center"): NUMBER,
    ("Recognition", "normal"): NUMBER,
    ("Recognition", "direction"): NUMBER,
    ("Recognition", "radius_squared"): NUMBER,
    ("Factor", "polynomial"): SURFACE,
    ("Analysis", "squarefree"): SURFACE,
    ("Rationality", "square_parametrization"): Form("rational", ("t",), complex=True),
    ("Rationality", "tubular_surface"): Form("rational", XYZ, complex=True),
    ("Rationality", "h"): Form("polynomial", ("t",), complex=True),
    ("Rationality", "tau"): Form("rational", XYZ, complex=True),
    ("Parametrization", "coordinates"): Form("rational", "parameters", complex=True),
    ("NearestSurface", "polynomial"): SURFACE,
    ("NearestSurface", "center"): NUMBER,
    ("NearestSurface", "normal"): NUMBER,
    ("CanalFamily", "equations"): Form("polynomial", ("m1", "m2", "m3", "r"), 2 * MAX_DEGREE),
    ("CanalFamily", "spine_equations"): Form("polynomial", ("m1", "m2", "m3"), 2 * MAX_DEGREE),
    ("CanalFamily", "plane_model"): Form("polynomial", ("u", "v"), 2 * MAX_DEGREE),
    ("CanalFamily", "parametrization"): Form("rational", "parameter"),
    ("CanalFamily", "radius_squared"): Form("rational", "parameter"),
    ("CanalFamily", "circle_center"): Form("rational", "parameter"),
    ("CanalFamily", "circle_radius_squared"): Form("rational", "parameter"),
    ("CanalFamily", "circle_normal"): Form("rational", "parameter"),
    ("CanalFamily", "radical_spine"): Form("circles", ("t",)),
    ("CanalFamily", "radical_radius_squared"): Form("circles", ("t",)),
    ("CanalEvidence", "point"): NUMBER,
    ("CanalEvidence", "direction"): NUMBER,
    ("CanalEvidence", "restriction"): Form("polynomial", ("tau",), MAX_DEGREE),
    ("Conical", "apex"): NUMBER,
    ("Conical", "direction"): NUMBER,
    ("BaseCurve", "polynomial"): Form("polynomial", "variables", MAX_DEGREE),
    ("BaseCurve", "frame_point"): NUMBER,
    ("BaseCurve", "frame_u"): NUMBER,
    ("BaseCurve", "frame_w"): NUMBER,
    ("ParametricInput", "map"): Form("rational", "map_parameters"),
    ("ParametricInput", "symmetry_basis"): NUMBER,
    ("ParametricInput", "apex"): NUMBER,
    ("ParametricInput", "directions"): NUMBER,
    ("ParametricInput", "profile_curve"): Form("polynomial", ("h", "rho"), MAX_DEGREE),
}
"""The form of every field that holds exact numbers or formulas."""

CIRCLES = Form("circles", "parameters", complex=True)
"""The coordinates of a canal surface's parameterizations by its characteristic circles."""

PARAMETER_FIELDS = {
    ("Parametrization", "parameters"),
    ("CanalFamily", "parameter"),
    ("CanalFamily", "radical_parameter"),
    ("BaseCurve", "variables"),
    ("ParametricInput", "map_parameters"),
}
FIELD_FIELDS = {
    ("Analysis", "field"),
    ("Parametrization", "field"),
    ("CanalFamily", "field"),
    ("ParametricInput", "field"),
}
UNKNOWN_EQUATION = {("Recognition", "polynomial"), ("Factor", "polynomial"), ("Analysis", "squarefree")}
"""Fields that are empty when the implicit equation of a parametrization was not found."""
_FIELD = re.compile(r"QQ(?:\((?P<generators>.+)\))?")
_STAGE = re.compile(r"[a-z][a-z ]{0,39}")


_NAMES = {**vars(stage_results), **vars(results)}
"""The names the annotations of the result objects use: those of :mod:`.results` name classes of
:mod:`.stage_results`, which it imports for type checking only."""


class ReportInvalid(SorguiError):
    """A value of a report is not one sorgui writes; the message names the field."""


def validate(analysis: results.Analysis) -> None:
    """Raise :class:`ReportInvalid` unless every value of ``analysis`` is one sorgui writes."""
    try:
        _check_object(analysis, "", circles=False)
    except RecursionError:
        raise ReportInvalid("it is nested too deeply") from None


def _check_object(obj: Any, path: str, circles: bool) -> None:  # noqa: ANN401
    if not is_dataclass(obj) or isinstance(obj, type):
        raise ReportInvalid(f"{path} is not an object sorgui writes")
    cls = type(obj)
    hints = typing.get_type_hints(cls, _NAMES)
    inside = circles or isinstance(obj, results.Canal)
    for item in fields(cls):
        value = getattr(obj, item.name)
        flat = isinstance(obj, results.Analysis) and item.name == "recognition"  # its keys are the report's own
        where = path if flat else f"{path}.{item.name}".lstrip(".")
        _check_type(value, hints[item.name], where, inside)
        _check_strings(obj, item.name, value, where, inside)
    prefix = f"{path}." if path else ""
    if isinstance(obj, results.Analysis):
        _check_input(obj, prefix)
        for stage in obj.unfinished:
            _check_stage(stage, f"{prefix}unfinished")
        for stage, _seconds in obj.timings:
            _check_stage(stage, f"{prefix}timings")
    if isinstance(obj, results.CanalEvidence) and not set(obj.method.split("+")) <= CERTIFICATE_METHODS:
        raise ReportInvalid(f"{prefix}method is not a method sorgui uses: {_shown(obj.method)}")


def _check_type(value: Any, hint: Any, where: str, circles: bool) -> None:  # noqa: ANN401
    """``value`` against the annotation ``hint`` (dataclasses, unions, tuples, scalars)."""
    origin = typing.get_origin(hint)
    if origin in (UnionType, typing.Union):
        options = [o for o in typing.get_args(hint) if o is not NoneType]
        if value is None and len(options) < len(typing.get_args(hint)):
            return
        if len(options) != 1:
            raise ReportInvalid(f"{where} has a type sorgui does not write")
        _check_type(value, options[0], where, circles)
        return
    if hint is NoneType:
        if value is not None:
            raise ReportInvalid(f"{where} must be null")
        return
    if origin is tuple:
        args = typing.get_args(hint)
        if not isinstance(value, tuple):
            raise ReportInvalid(f"{where} must be a list")
        if len(args) == 2 and args[1] is Ellipsis:
            for i, item in enumerate(value):
                _check_type(item, args[0], f"{where}[{i}]", circles)
        elif len(args) != len(value):
            raise ReportInvalid(f"{where} must have {len(args)} entries, not {len(value)}")
        else:
            for i, (item, arg) in enumerate(zip(value, args)):
                _check_type(item, arg, f"{where}[{i}]", circles)
        return
    if isinstance(hint, type) and is_dataclass(hint):
        if not isinstance(value, hint):
            raise ReportInvalid(f"{where} must be an object")
        _check_object(value, where, circles)
        return
    if hint is bool:
        if not isinstance(value, bool):
            raise ReportInvalid(f"{where} must be true or false")
    elif hint is int:
        if isinstance(value, bool) or not isinstance(value, int) or abs(value) > 10**9:
            raise ReportInvalid(f"{where} must be a whole number")
    elif hint is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ReportInvalid(f"{where} must be a finite number")
    elif hint is str:
        if not isinstance(value, str):
            raise ReportInvalid(f"{where} must be a string")
    else:
        raise ReportInvalid(f"{where} has a type sorgui does not write")


def _strings(value: Any) -> list[str]:  # noqa: ANN401
    if isinstance(value, str):
        return [value]
    if isinstance(value, tuple):
        return [s for item in value for s in _strings(item)]
    return []


def _check_strings(obj: Any, name: str, value: Any, where: str, circles: bool) -> None:  # noqa: ANN401
    """The strings of one field, by what the field holds."""
    if is_dataclass(value) or (isinstance(value, tuple) and any(is_dataclass(v) for v in value)):
        return  # checked as objects
    cls = type(obj).__name__
    strings = _strings(value)
    form = FORMS.get((cls, name))
    if (cls, name) == ("Parametrization", "coordinates") and circles:
        form = CIRCLES
    if (cls, name) == ("Rationality", "absolute_factors"):
        for text in strings:  # "a*s - r  where a**2 - 2 = 0": a factor over QQ(a)
            factor, _, field = text.partition("  where ")
            check_expression(factor, where, Form("polynomial", ("s", "r", "a"), MAX_DEGREE))
            if field:
                check_expression(field.removesuffix(" = 0"), where, Form("polynomial", ("a",), MAX_DEGREE))
    elif form is not None:
        if isinstance(form.variables, tuple):
            variables = form.variables
        else:
            sibling = f"{where.rpartition('.')[0]}.{form.variables}"
            variables = _names(getattr(obj, form.variables), sibling)
        for text in strings:
            if text or (cls, name) not in UNKNOWN_EQUATION:
                check_expression(text, where, Form(form.kind, variables, form.degree, form.complex))
    elif (cls, name) in VOCABULARY:
        allowed = VOCABULARY[(cls, name)]
        for text in strings:
            if text not in allowed:
                raise ReportInvalid(f"{where} is not one of sorgui's values: {_shown(text)}")
    elif (cls, name) in PARAMETER_FIELDS:
        for text in strings:
            if text not in NAMES:
                raise ReportInvalid(f"{where} is not a parameter name sorgui uses: {_shown(text)}")
    elif (cls, name) in FIELD_FIELDS:
        for text in strings:
            _check_field(text, where, real=cls in ("Analysis", "ParametricInput"))
    elif not (cls == "Analysis" and name in ("input", "unfinished", "timings")) and not (
        cls == "ParametricInput" and name in ("components", "parameters")
    ):
        for text in strings:
            check_text(text, where)


def _names(value: Any, where: str) -> tuple[str, ...]:  # noqa: ANN401
    """The variables a sibling field names (a map's parameters), each one sorgui uses."""
    names = (value,) if isinstance(value, str) else tuple(value or ())
    for name in names:
        if not isinstance(name, str) or name not in NAMES:
            raise ReportInvalid(f"{where} is not a parameter name sorgui uses: {_shown(str(name))}")
    return names


def check_expression(text: str, where: str, form: Form = Form("rational", NAMES, complex=True)) -> sympy.Expr:
    """``text`` must be an exact expression of ``form`` (:data:`EXACT`, its variables, its kind,
    its degree, numbers of bounded size); the expression read."""
    if len(text) > MAX_EXPRESSION:
        raise ReportInvalid(f"{where} is too long ({len(text):,} characters)")
    try:
        expr = formula(text)  # the checks of the claims read it again: cached
        degree, _bits = _bounds(expr, form, where)
    except ExpressionError as exc:
        raise ReportInvalid(f"{where} is not an exact expression sorgui writes: {exc.message}") from None
    except RecursionError:
        raise ReportInvalid(f"{where} is nested too deeply") from None
    if degree > form.degree:
        kind = "a number" if form.kind == "number" else f"of degree at most {form.degree}"
        raise ReportInvalid(f"{where} must be {kind}, not of degree {degree}")
    return expr


def _bounds(expr: sympy.Basic, form: Form, where: str) -> tuple[int, int]:
    """Upper bounds of the degree and of the size in bits of the numbers of ``expr`` expanded,
    read off its tree; refuses what ``form`` does not allow (:class:`ReportInvalid`)."""
    memo: dict[sympy.Basic, tuple[int, int]] = {}

    def visit(e: sympy.Basic) -> tuple[int, int]:
        if e in memo:
            return memo[e]
        if e.is_Rational:
            value = sympy.Rational(e)
            found = (0, int(value.p).bit_length() + int(value.q).bit_length())
        elif e is sympy.I:
            if not form.complex:
                raise ReportInvalid(f"{where} holds I, but its values are real")
            found = (0, 1)
        elif e.is_Symbol:
            if str(e) not in form.variables or form.kind == "number":
                allowed = ", ".join(form.variables) if form.variables else "none: it is a number"
                raise ReportInvalid(f"{where} holds the name {str(e)!r}, which is not one of its variables ({allowed})")
            found = (1, 0)
        elif e.is_Add:
            parts = [visit(a) for a in e.args]
            found = (max(d for d, _ in parts), max(b for _, b in parts) + len(parts).bit_length())
        elif e.is_Mul:
            parts = [visit(a) for a in e.args]
            found = (sum(d for d, _ in parts), sum(b for _, b in parts))
        elif e.is_Pow:
            found = _power(e, visit)
        elif isinstance(e, (sympy.sin, sympy.cos)):
            if form.kind != "circles" or e.args != (sympy.Symbol("theta"),):
                raise ReportInvalid(f"{where} holds {type(e).__name__}, which only a canal surface's circles have")
            found = (1, 1)
        else:
            raise ReportInvalid(f"{where} holds {type(e).__name__}, which sorgui does not write")
        if found[1] > MAX_HEIGHT_BITS:
            raise ReportInvalid(f"{where} holds numbers too large (more than {MAX_HEIGHT_BITS:,} bits)")
        memo[e] = found
        return found

    def _power(e: sympy.Basic, visit: typing.Callable[[sympy.Basic], tuple[int, int]]) -> tuple[int, int]:
        base, exponent = e.args
        degree, bits = visit(base)
        if exponent.is_Integer:
            if exponent < 0 and base.free_symbols and form.kind not in ("rational", "circles"):
                raise ReportInvalid(f"{where} divides by a polynomial, but it must be a polynomial")
            n = abs(int(exponent))
            return degree * n, (bits + 1) * n
        if exponent.is_Rational and exponent.q == 2:
            if base.free_symbols and (form.kind != "circles" or len(base.free_symbols) > 1):
                raise ReportInvalid(
                    f"{where} takes the square root of a polynomial, which only a canal surface's circles do"
                )
            n = abs(int(exponent.p))
            return degree * n, (bits + 1) * n
        raise ReportInvalid(f"{where} holds a power sorgui does not write (exponent {exponent})")

    return visit(expr)


def check_text(text: str, where: str) -> None:
    """``text`` must be one line of printable text of at most :data:`MAX_TEXT` characters."""
    if len(text) > MAX_TEXT:
        raise ReportInvalid(f"{where} is too long ({len(text):,} characters)")
    for char in text:
        if unicodedata.category(char) in ("Cc", "Cf", "Zl", "Zp", "Cs", "Co", "Cn"):
            raise ReportInvalid(f"{where} holds the control character U+{ord(char):04X}")


def _check_field(text: str, where: str, real: bool) -> None:
    """``QQ`` or ``QQ(sqrt(n), …)``, square roots of rationals (of positive ones for ``K``)."""
    match = _FIELD.fullmatch(text)
    if match is None:
        raise ReportInvalid(f"{where} is not a field sorgui writes: {_shown(text)}")
    generators = match.group("generators")
    for generator in [] if generators is None else generators.split(","):
        expr = check_expression(generator.strip(), where, Form("number", (), 0, complex=not real))
        if expr.is_Rational or not sympy.expand(expr**2).is_Rational:
            raise ReportInvalid(f"{where} is not a field of square roots: {_shown(text)}")


def _check_stage(stage: str, where: str) -> None:
    if not isinstance(stage, str) or _STAGE.fullmatch(stage) is None:
        raise ReportInvalid(f"{where} names a stage sorgui does not have: {_shown(str(stage))}")


def _check_input(analysis: results.Analysis, path: str) -> None:
    """The equation must be one the project's parser reads (as if typed); a parametrization's
    text must be read by the parametrization reader into the very components and parameters the
    report names, and only its implicit equation may be missing."""
    from sorgui.engine.parametric_parsing import parse_parametrization
    from sorgui.engine.parsing import parse_polynomial

    where = f"{path}.input"
    record = analysis.parametric
    if analysis.input_kind == "equation":
        if record is not None or not analysis.recognition.polynomial:
            raise ReportInvalid(f"{path} is an equation's report with a parametrization's fields")
        reader: Any = parse_polynomial
    else:
        if record is None:
            raise ReportInvalid(f"{path}.parametric is missing for a parametrization")
        reader = parse_parametrization
    try:
        parsed = reader(analysis.input)
    except ParseError as exc:
        raise ReportInvalid(f"{where} is not an equation sorgui reads: {exc.message}") from None
    if record is not None and (parsed.components, parsed.parameters) != (record.components, record.parameters):
        raise ReportInvalid(f"{path}.parametric does not hold the components of its input")


def _shown(text: str) -> str:
    """``text`` quoted for a one-line message, shortened."""
    return repr(text if len(text) <= 40 else text[:40] + "…")
