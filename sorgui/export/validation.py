"""What a report file may hold: every value checked against what sorgui itself writes.

A report (``*.sorgui.json``) is a file people send each other, so :func:`validate` checks the
:class:`~sorgui.engine.results.Analysis` decoded from one before anything shows or exports it:

* every field has the type sorgui writes (a bool where a bool goes, a tuple of three strings
  for a point, …);
* every exact number and polynomial is read by the engine's reader of machine-written formulas
  (:mod:`sorgui.engine.expressions`), with only the variables, functions and constants sorgui's
  results use (:data:`NAMES`), and without a number too large to hold;
* the parameters of a map are among :data:`NAMES`, a field is ``QQ`` or ``QQ(…)`` of exact
  numbers, the kinds (symmetry, real locus, canal kinds and certificates, stages) come from
  fixed lists;
* the equation is read by the project's parser, as if it had been typed;
* every other string (notes, statements, methods) is one line of printable text of bounded
  length: no control character, so no newline that could end a comment in an exported file.

A report that does not validate is refused with one line naming the field
(:class:`ReportInvalid`). The exporters quote every value in their format's own way as well.
"""

from __future__ import annotations

import re
import sys
import typing
import unicodedata
from dataclasses import fields, is_dataclass
from types import NoneType, UnionType
from typing import Any

import sympy

from sorgui.engine import results
from sorgui.engine.errors import ExpressionError, ParseError, SorguiError
from sorgui.engine.expressions import Syntax, read

NAMES = ("x", "y", "z", "s", "t", "w", "r", "u", "v", "m1", "m2", "m3", "theta", "tau", "a", "h", "rho")
"""The variables of sorgui's results: space, the parameters of maps and profiles, the SMAT
coordinates of canal surfaces, the parameter of a witness line, the ring parameter of
Singular's fields, and the height and squared distance of a parametrization's profile curve."""

EXACT = Syntax(
    powers=("**", "^"),
    decimals=False,
    rational_exponents=True,
    functions={"sqrt": sympy.sqrt, "sin": sympy.sin, "cos": sympy.cos},
    constants={"I": sympy.I},
    names={name: sympy.Symbol(name) for name in NAMES},
)
"""The syntax of every exact string sorgui writes into a report."""

MAX_TEXT = 20_000
"""Characters of one line of text (a note, a statement) at most."""

MAX_EXPRESSION = 2_000_000
"""Characters of one exact expression at most (sorgui's largest are a few hundred thousand)."""

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

EXPRESSIONS: dict[str, frozenset[str]] = {
    "Axis": frozenset({"point", "direction", "plucker"}),
    "Profile": frozenset(
        {"polynomial", "square", "rational", "rational_square", "frame_point", "frame_direction", "frame_normal"}
    ),
    "Recognition": frozenset({"polynomial", "symmetry_basis", "center", "normal", "direction", "radius_squared"}),
    "Factor": frozenset({"polynomial"}),
    "Rationality": frozenset({"absolute_factors", "square_parametrization", "tubular_surface", "h", "tau"}),
    "Parametrization": frozenset({"coordinates"}),
    "NearestSurface": frozenset({"polynomial", "center", "normal"}),
    "CanalFamily": frozenset(
        {
            "equations",
            "spine_equations",
            "plane_model",
            "parametrization",
            "radius_squared",
            "circle_center",
            "circle_radius_squared",
            "circle_normal",
            "radical_spine",
            "radical_radius_squared",
        }
    ),
    "CanalEvidence": frozenset({"point", "direction", "restriction"}),
    "Analysis": frozenset({"squarefree"}),
    "Conical": frozenset({"apex", "direction"}),
    "BaseCurve": frozenset({"polynomial", "frame_point", "frame_u", "frame_w"}),
    "ParametricInput": frozenset({"map", "symmetry_basis", "apex", "directions", "profile_curve"}),
}
"""Fields that hold exact numbers or polynomials (each string read by :data:`EXACT`)."""

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


class ReportInvalid(SorguiError):
    """A value of a report is not one sorgui writes; the message names the field."""


def validate(analysis: results.Analysis) -> None:
    """Raise :class:`ReportInvalid` unless every value of ``analysis`` is one sorgui writes."""
    try:
        _check_object(analysis, "report")
    except RecursionError:
        raise ReportInvalid("the report is nested too deeply") from None


def _check_object(obj: Any, path: str) -> None:
    if not is_dataclass(obj) or isinstance(obj, type):
        raise ReportInvalid(f"{path} is not an object sorgui writes")
    cls = type(obj)
    hints = typing.get_type_hints(cls, vars(results))
    for item in fields(cls):
        value = getattr(obj, item.name)
        where = f"{path}.{item.name}"
        _check_type(value, hints[item.name], where)
        _check_strings(cls.__name__, item.name, value, where)
    if isinstance(obj, results.Analysis):
        _check_input(obj, path)
        for stage in obj.unfinished:
            _check_stage(stage, f"{path}.unfinished")
        for stage, _seconds in obj.timings:
            _check_stage(stage, f"{path}.timings")
    if isinstance(obj, results.CanalEvidence) and not set(obj.method.split("+")) <= CERTIFICATE_METHODS:
        raise ReportInvalid(f"{path}.method is not a method sorgui uses: {_shown(obj.method)}")


def _check_type(value: Any, hint: Any, where: str) -> None:
    """``value`` against the annotation ``hint`` (dataclasses, unions, tuples, scalars)."""
    origin = typing.get_origin(hint)
    if origin in (UnionType, typing.Union):
        options = [o for o in typing.get_args(hint) if o is not NoneType]
        if value is None and len(options) < len(typing.get_args(hint)):
            return
        if len(options) != 1:
            raise ReportInvalid(f"{where} has a type sorgui does not write")
        _check_type(value, options[0], where)
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
                _check_type(item, args[0], f"{where}[{i}]")
        elif len(args) != len(value):
            raise ReportInvalid(f"{where} must have {len(args)} entries, not {len(value)}")
        else:
            for i, (item, arg) in enumerate(zip(value, args)):
                _check_type(item, arg, f"{where}[{i}]")
        return
    if isinstance(hint, type) and is_dataclass(hint):
        if not isinstance(value, hint):
            raise ReportInvalid(f"{where} must be an object")
        _check_object(value, where)
        return
    if hint is bool:
        if not isinstance(value, bool):
            raise ReportInvalid(f"{where} must be true or false")
    elif hint is int:
        if isinstance(value, bool) or not isinstance(value, int) or abs(value) > 10**9:
            raise ReportInvalid(f"{where} must be a whole number")
    elif hint is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or abs(value) > sys.float_info.max:
            raise ReportInvalid(f"{where} must be a number")
    elif hint is str:
        if not isinstance(value, str):
            raise ReportInvalid(f"{where} must be a string")
    else:
        raise ReportInvalid(f"{where} has a type sorgui does not write")


def _strings(value: Any) -> list[str]:
    if isinstance(value, str):
        return [value]
    if isinstance(value, tuple):
        return [s for item in value for s in _strings(item)]
    return []


def _check_strings(cls: str, name: str, value: Any, where: str) -> None:
    """The strings of one field, by what the field holds."""
    if is_dataclass(value) or (isinstance(value, tuple) and any(is_dataclass(v) for v in value)):
        return  # checked as objects
    strings = _strings(value)
    if (cls, name) == ("Rationality", "absolute_factors"):
        for text in strings:  # "a*s - r  where a**2 - 2 = 0": a factor over QQ(a)
            factor, _, field = text.partition("  where ")
            check_expression(factor, where)
            if field:
                check_expression(field.removesuffix(" = 0"), where)
    elif name in EXPRESSIONS.get(cls, ()):
        for text in strings:
            if text or (cls, name) not in UNKNOWN_EQUATION:
                check_expression(text, where)
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
            _check_field(text, where)
    elif not (cls == "Analysis" and name in ("input", "unfinished", "timings")) and not (
        cls == "ParametricInput" and name in ("components", "parameters")
    ):
        for text in strings:
            check_text(text, where)


def check_expression(text: str, where: str) -> None:
    """``text`` must be an exact expression in :data:`EXACT`."""
    if len(text) > MAX_EXPRESSION:
        raise ReportInvalid(f"{where} is too long ({len(text):,} characters)")
    try:
        read(text, EXACT)
    except ExpressionError as exc:
        raise ReportInvalid(f"{where} is not an exact expression sorgui writes: {exc.message}") from None
    except RecursionError:
        raise ReportInvalid(f"{where} is nested too deeply") from None


def check_text(text: str, where: str) -> None:
    """``text`` must be one line of printable text of at most :data:`MAX_TEXT` characters."""
    if len(text) > MAX_TEXT:
        raise ReportInvalid(f"{where} is too long ({len(text):,} characters)")
    for char in text:
        if unicodedata.category(char) in ("Cc", "Cf", "Zl", "Zp", "Cs", "Co", "Cn"):
            raise ReportInvalid(f"{where} holds the control character U+{ord(char):04X}")


def _check_field(text: str, where: str) -> None:
    match = _FIELD.fullmatch(text)
    if match is None:
        raise ReportInvalid(f"{where} is not a field sorgui writes: {_shown(text)}")
    generators = match.group("generators")
    for generator in [] if generators is None else generators.split(","):
        check_expression(generator.strip(), where)


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
