"""The formulas of an analysis as mathematics: LaTeX, wrapped lines and mathtext images.

The results pane shows every polynomial, vector and parameterization typeset, not as Python
text. Each engine string is read exactly (:mod:`sorgui.export.exact`) and printed with
``sympy.latex``, one piece per top-level term. :func:`render_formulas` then wraps the pieces
into lines no wider than the pane (measured with mathtext itself) and rasterises each line with
matplotlib's mathtext (Computer Modern) into an 8-bit alpha mask. This runs in the analysis
worker process (it has no Qt), so the GUI thread only colours ready-made masks; a formula
mathtext cannot typeset is shown as plain text instead.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import sympy

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


@dataclass(frozen=True)
class Style:
    """How the worker typesets formulas: dots per inch (≈ 96 × the screen's device pixel
    ratio), font size in points, and the width of a line in device pixels."""

    dpi: float = 96.0
    size: float = 11.0
    width: float = 420.0


def _latex(expr: sympy.Expr) -> str:
    return sympy.latex(expr, fold_short_frac=True)


def expression_formula(text: str, prefix: str = "") -> Formula:
    """The engine string ``text`` (a number, polynomial or rational function) as a formula."""
    if len(text) > MAX_CHARACTERS:
        return Formula(text, text, ())
    try:
        expr = read_expression(text)
    except ExpressionError:
        return Formula(text, text, ())
    terms = expr.as_ordered_terms() if isinstance(expr, sympy.Add) else [expr]
    if len(terms) > MAX_TERMS:
        return Formula(text, _latex(expr), ())
    pieces = []
    for index, term in enumerate(terms):
        negative = term.could_extract_minus_sign()
        body = _latex(-term if negative else term)
        sign = ("-" if negative else "") if index == 0 else (" - " if negative else " + ")
        pieces.append(sign + body)
    if prefix:
        pieces[0] = f"{prefix} {pieces[0]}"
    return Formula(text, _latex(expr), tuple(pieces))


def vector_formula(values: Sequence[str], prefix: str = "") -> Formula:
    """A tuple of exact numbers ``(a, b, c)`` (or Plücker coordinates ``(a : … : f)``)."""
    separator = " : " if len(values) == 6 else ", "
    plain = "(" + separator.join(values) + ")"
    try:
        parts = [_latex(read_expression(v)) for v in values]
    except ExpressionError:
        return Formula(plain, plain, ())
    latex = r"\left(" + separator.join(parts) + r"\right)"
    return Formula(plain, latex, ((prefix + " " if prefix else "") + latex,))


def line_formula(point: Sequence[str], direction: Sequence[str]) -> Formula:
    """The parametric line ``c + t·a``."""
    c, a = vector_formula(point), vector_formula(direction)
    latex = f"{c.latex} + t\\,{a.latex}"
    return Formula(f"{c.plain} + t*{a.plain}", latex, (latex,))


# --- all formulas of an analysis ------------------------------------------------------------


def _recognition_formulas(rec: Recognition, key: str) -> Iterable[tuple[str, Formula]]:
    if rec.axis is not None:
        yield f"{key}axis.point", vector_formula(rec.axis.point)
        yield f"{key}axis.direction", vector_formula(rec.axis.direction)
        yield f"{key}axis.plucker", vector_formula(rec.axis.plucker)
        yield f"{key}axis.line", line_formula(rec.axis.point, rec.axis.direction)
    for name in ("center", "normal", "direction"):
        value = getattr(rec, name)
        if value is not None:
            yield f"{key}{name}", vector_formula(value)


def analysis_formulas(analysis: Analysis) -> dict[str, Formula]:
    """Every formula the results pane shows, by key (``"axis.point"``, ``"factor.0"``, …)."""
    rec = analysis.recognition
    out: dict[str, Formula] = {"polynomial": expression_formula(rec.polynomial, "f =")}
    out.update(_recognition_formulas(rec, ""))
    if rec.profile is not None:
        profile = rec.profile
        out["profile.polynomial"] = expression_formula(profile.polynomial, "p(x, y) =")
        out["profile.square"] = expression_formula(profile.square, "P^2(x, y) =")
        out["profile.rational"] = expression_formula(profile.rational, r"\tilde{p}(s, r) =")
        out["profile.frame_point"] = vector_formula(profile.frame_point, "c =")
        out["profile.frame_direction"] = vector_formula(profile.frame_direction, "a =")
        out["profile.frame_normal"] = vector_formula(profile.frame_normal, "u =")
    if len(analysis.factors) > 1:
        for index, factor in enumerate(analysis.factors):
            out[f"factor.{index}"] = expression_formula(factor.polynomial)
            out.update(_recognition_formulas(factor.recognition, f"factor.{index}."))
    rationality = analysis.rationality
    if rationality is not None:
        if rationality.tubular_surface:
            out["rationality.tubular_surface"] = expression_formula(rationality.tubular_surface, "T:")
        if rationality.h:
            out["rationality.h"] = expression_formula(rationality.h, "h =")
        if rationality.square_parametrization:
            phi, rho = rationality.square_parametrization
            out["rationality.square_parametrization.0"] = expression_formula(phi, r"\varphi =")
            out["rationality.square_parametrization.1"] = expression_formula(rho, r"\rho =")
        if rationality.tau:
            for name, value in zip("xyz", rationality.tau):
                out[f"rationality.tau.{name}"] = expression_formula(value, rf"\tau_{name} =")
    for index, param in enumerate(analysis.parametrizations):
        for name, value in zip("xyz", param.coordinates):
            out[f"parametrization.{index}.{name}"] = expression_formula(value, f"{name} =")
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


def render_formulas(formulas: dict[str, Formula], style: Style) -> dict[str, Formula]:
    """``formulas`` wrapped and rasterised; a formula mathtext rejects keeps no masks."""
    out = {}
    for key, formula in formulas.items():
        try:
            lines = wrap(formula.pieces, style) if formula.pieces else ()
            out[key] = replace(formula, lines=lines, masks=tuple(render_line(ln, style) for ln in lines))
        except (ValueError, RuntimeError):
            out[key] = formula
    return out
