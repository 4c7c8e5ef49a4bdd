"""The formulas of an analysis as mathematics: LaTeX, wrapped lines and mathtext images.

The results pane shows every polynomial, vector and parameterization typeset, not as Python
text. Each engine string is read exactly (:mod:`sorgui.export.exact`) and printed with
``sympy.latex``, one piece per top-level term. :func:`render_formulas` then wraps the pieces
into lines no wider than the pane (measured with mathtext itself) and rasterises each line with
matplotlib's mathtext (Computer Modern) into an 8-bit alpha mask. This runs in the analysis
worker process (it has no Qt), so the GUI thread only colours ready-made masks; a formula
mathtext cannot typeset is shown as plain text instead. Each formula also carries its Maple,
Mathematica and Python forms (sympy's printers, as the exported files), for the copy menu.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import sympy
from sympy.printing.maple import maple_code
from sympy.printing.mathematica import mathematica_code
from sympy.printing.pycode import pycode

from sorgui.engine.report import Analysis, Recognition
from sorgui.export.exact import ExpressionError, read_expression

MAX_CHARACTERS = 6000
MAX_TERMS = 100
"""Longer formulas are shown as plain text only: typesetting them would take seconds, and
dozens of typeset lines are no easier to read than the exact text one can copy."""

CONTINUATION = r"\qquad"
"""The indent of the second and later lines of a wrapped formula."""


@dataclass(frozen=True)
class Formula:
    """One displayed formula.

    ``plain`` and ``latex`` are what the copy actions put on the clipboard. ``pieces`` are the
    LaTeX of its top-level terms with their signs (the first with its ``prefix``), the places
    where it may be wrapped; ``lines`` and ``masks`` are the wrapped lines and their renderings
    as ``(height, width) uint8`` alpha masks, both empty until :func:`render_formulas`.
    """

    plain: str
    latex: str
    pieces: tuple[str, ...]
    lines: tuple[str, ...] = ()
    masks: tuple[np.ndarray, ...] = ()
    codes: tuple[tuple[str, str], ...] = ()
    """``(language, text)`` for Maple, Mathematica and Python (empty if not readable)."""

    def code(self, language: str) -> str:
        """The formula in ``language`` (``"text"``, ``"LaTeX"``, ``"Maple"``, …; plain text if unknown)."""
        if language == "LaTeX":
            return self.latex
        return dict(self.codes).get(language, self.plain)


@dataclass(frozen=True)
class Style:
    """How the worker typesets formulas: dots per inch (≈ 96 × the screen's device pixel
    ratio), font size in points, and the width of a line in device pixels."""

    dpi: float = 96.0
    size: float = 11.0
    width: float = 420.0


def _latex(expr: sympy.Expr) -> str:
    return sympy.latex(expr, fold_short_frac=True)


CODE_PRINTERS = (("Maple", maple_code), ("Mathematica", mathematica_code), ("Python", pycode))
"""The languages of the copy menu, with sympy's printers."""

_BRACKETS = {"Maple": ("[", "]"), "Mathematica": ("{", "}"), "Python": ("(", ")")}


def _codes(exprs: Sequence[sympy.Expr], vector: bool) -> tuple[tuple[str, str], ...]:
    """The expression (or the vector of ``exprs``) in each language of :data:`CODE_PRINTERS`."""
    out = []
    for language, printer in CODE_PRINTERS:
        parts = [printer(e) for e in exprs]
        if vector:
            left, right = _BRACKETS[language]
            out.append((language, left + ", ".join(parts) + right))
        else:
            out.append((language, parts[0]))
    return tuple(out)


def plain_formula(text: str) -> Formula:
    """``text`` as an untypeset formula (shown as text until the typeset one arrives)."""
    return Formula(text, text, ())


def expression_formula(text: str, prefix: str = "") -> Formula:
    """The engine string ``text`` (a number, polynomial or rational function) as a formula."""
    if len(text) > MAX_CHARACTERS:
        return Formula(text, text, ())
    try:
        expr = read_expression(text)
    except ExpressionError:
        return Formula(text, text, ())
    terms = expr.as_ordered_terms() if isinstance(expr, sympy.Add) else [expr]
    codes = _codes([expr], vector=False)
    if len(terms) > MAX_TERMS:
        return Formula(text, _latex(expr), (), codes=codes)
    pieces = []
    for index, term in enumerate(terms):
        negative = term.could_extract_minus_sign()
        body = _latex(-term if negative else term)
        sign = ("-" if negative else "") if index == 0 else (" - " if negative else " + ")
        pieces.append(sign + body)
    if prefix:
        pieces[0] = f"{prefix} {pieces[0]}"
    return Formula(text, _latex(expr), tuple(pieces), codes=codes)


def vector_formula(values: Sequence[str], prefix: str = "") -> Formula:
    """A tuple of exact numbers ``(a, b, c)`` (or Plücker coordinates ``(a : … : f)``)."""
    separator = " : " if len(values) == 6 else ", "
    plain = "(" + separator.join(values) + ")"
    try:
        exprs = [read_expression(v) for v in values]
    except ExpressionError:
        return Formula(plain, plain, ())
    latex = r"\left(" + separator.join(_latex(e) for e in exprs) + r"\right)"
    return Formula(plain, latex, ((prefix + " " if prefix else "") + latex,), codes=_codes(exprs, vector=True))


def line_formula(point: Sequence[str], direction: Sequence[str]) -> Formula:
    """The parametric line ``c + t·a``."""
    c, a = vector_formula(point), vector_formula(direction)
    latex = f"{c.latex} + t\\,{a.latex}"
    return Formula(f"{c.plain} + t*{a.plain}", latex, (latex,))


# --- all formulas of an analysis ------------------------------------------------------------


@dataclass(frozen=True)
class _Builders:
    expression: Callable[..., Formula]
    vector: Callable[..., Formula]
    line: Callable[..., Formula]


def _plain_vector(values: Sequence[str], prefix: str = "") -> Formula:
    return plain_formula("(" + (" : " if len(values) == 6 else ", ").join(values) + ")")


def _plain_line(point: Sequence[str], direction: Sequence[str]) -> Formula:
    return plain_formula(f"{_plain_vector(point).plain} + t*{_plain_vector(direction).plain}")


_EXACT = _Builders(expression_formula, vector_formula, line_formula)
_PLAIN = _Builders(lambda text, prefix="": plain_formula(text), _plain_vector, _plain_line)


def _recognition_formulas(rec: Recognition, key: str, make: _Builders) -> Iterable[tuple[str, Formula]]:
    if rec.axis is not None:
        yield f"{key}axis.point", make.vector(rec.axis.point)
        yield f"{key}axis.direction", make.vector(rec.axis.direction)
        yield f"{key}axis.plucker", make.vector(rec.axis.plucker)
        yield f"{key}axis.line", make.line(rec.axis.point, rec.axis.direction)
    for name in ("center", "normal", "direction"):
        value = getattr(rec, name)
        if value is not None:
            yield f"{key}{name}", make.vector(value)


def analysis_formulas(analysis: Analysis, plain: bool = False) -> dict[str, Formula]:
    """Every formula the results pane shows, by key (``"axis.point"``, ``"factor.0"``, …).

    ``plain`` gives them as untypeset text at once (no sympy), for the GUI thread to show until
    the typeset ones arrive.
    """
    make = _PLAIN if plain else _EXACT
    rec = analysis.recognition
    out: dict[str, Formula] = {"polynomial": make.expression(rec.polynomial, "f =")}
    out.update(_recognition_formulas(rec, "", make))
    if rec.profile is not None:
        profile = rec.profile
        out["profile.polynomial"] = make.expression(profile.polynomial, "p(x, y) =")
        out["profile.square"] = make.expression(profile.square, "P^2(x, y) =")
        out["profile.rational"] = make.expression(profile.rational, r"\tilde{p}(s, r) =")
        out["profile.frame_point"] = make.vector(profile.frame_point, "c =")
        out["profile.frame_direction"] = make.vector(profile.frame_direction, "a =")
        out["profile.frame_normal"] = make.vector(profile.frame_normal, "u =")
    if len(analysis.factors) > 1:
        for index, factor in enumerate(analysis.factors):
            out[f"factor.{index}"] = make.expression(factor.polynomial)
            out.update(_recognition_formulas(factor.recognition, f"factor.{index}.", make))
    rationality = analysis.rationality
    if rationality is not None:
        if rationality.tubular_surface:
            out["rationality.tubular_surface"] = make.expression(rationality.tubular_surface, "T:")
        if rationality.h:
            out["rationality.h"] = make.expression(rationality.h, "h =")
        if rationality.square_parametrization:
            phi, rho = rationality.square_parametrization
            out["rationality.square_parametrization.0"] = make.expression(phi, r"\varphi =")
            out["rationality.square_parametrization.1"] = make.expression(rho, r"\rho =")
        if rationality.tau:
            for name, value in zip("xyz", rationality.tau):
                out[f"rationality.tau.{name}"] = make.expression(value, rf"\tau_{name} =")
    for index, param in enumerate(analysis.parametrizations):
        for name, value in zip("xyz", param.coordinates):
            out[f"parametrization.{index}.{name}"] = make.expression(value, f"{name} =")
    canal = analysis.canal
    if canal is not None:
        for index, family in enumerate(canal.families):
            if family.parametrization is not None:
                out[f"canal.{index}.spine"] = make.vector(family.parametrization, "m(t) =")
            if family.radius_squared is not None:
                out[f"canal.{index}.radius"] = make.expression(family.radius_squared, r"\rho(t) =")
    nearest = analysis.approximate.nearest if analysis.approximate is not None else None
    if nearest is not None:
        out["approximate.nearest"] = make.expression(nearest.polynomial, "g =")
        if nearest.axis is not None:
            out["approximate.nearest.axis"] = make.line(nearest.axis.point, nearest.axis.direction)
    return out


# --- mathtext images ------------------------------------------------------------------------


def _parse(latex: str, style: Style):  # noqa: ANN202 (matplotlib's RasterParse)
    from matplotlib.font_manager import FontProperties
    from matplotlib.mathtext import MathTextParser

    prop = FontProperties(size=style.size, math_fontfamily="cm")
    return MathTextParser("agg").parse(f"${latex}$", dpi=style.dpi, prop=prop)


def render_line(latex: str, style: Style) -> np.ndarray:
    """One LaTeX line as an alpha mask (mathtext, Computer Modern); ``ValueError`` if mathtext
    cannot typeset it."""
    mask = np.asarray(_parse(latex, style).image)
    return np.pad(mask, ((2, 2), (2, 6)))  # delimiters may reach past mathtext's box


def wrap(pieces: Sequence[str], style: Style) -> tuple[str, ...]:
    """Greedy lines of ``pieces`` no wider than ``style.width`` (one piece may be wider).

    A piece is measured after an ``x``, so that the spacing of its leading ``+``/``-`` as a
    binary operator is counted.
    """
    indent = _parse(CONTINUATION, style).width
    anchor = _parse("x", style).width
    lines: list[str] = []
    current, width = "", 0.0
    for piece in pieces:
        size = _parse("x" + piece, style).width - anchor
        if current and width + size > style.width:
            lines.append(current)
            current, width = CONTINUATION + piece, indent
        else:
            current += piece
        width += size
    lines.append(current)
    return tuple(lines)


def render_formula(formula: Formula, style: Style) -> Formula:
    """``formula`` rasterised: on one line if it fits (one mathtext parse, the common case),
    else wrapped at its terms; ``ValueError`` if mathtext cannot typeset it."""
    if not formula.pieces:
        return formula
    whole = "".join(formula.pieces)
    parsed = _parse(whole, style)
    if parsed.width <= style.width or len(formula.pieces) == 1:
        mask = np.pad(np.asarray(parsed.image), ((2, 2), (2, 6)))
        return replace(formula, lines=(whole,), masks=(mask,))
    lines = wrap(formula.pieces, style)
    return replace(formula, lines=lines, masks=tuple(render_line(line, style) for line in lines))


def render_formulas(formulas: dict[str, Formula], style: Style) -> dict[str, Formula]:
    """``formulas`` wrapped and rasterised; a formula mathtext rejects keeps no masks."""
    out = {}
    for key, formula in formulas.items():
        try:
            out[key] = render_formula(formula, style)
        except (ValueError, RuntimeError):
            out[key] = formula
    return out
