"""The formulas of an analysis as the results pane shows them: Unicode text at once, LaTeX pieces
to typeset, the exact text to copy.

Which formulas an analysis has is the export layer's one catalogue
(:func:`sorgui.export.formulas.catalogue`); :func:`pane_formulas` makes those the results pane
shows, and nothing here adds or drops one. Each engine string is printed by
:mod:`sorgui.session.math_text` (no sympy, no evaluation): as Unicode math, which the pane shows
the moment the formula is known, and as LaTeX pieces, one per top-level term (where a long
formula may be wrapped), which the typesetting process rasterises when it gets to them
(:mod:`sorgui.session.typesetting`). Long numbers are shown short, and rounded input's
coefficients in decimals (:data:`~sorgui.session.math_text.Mode`); the exact strings are what
the copy actions give: :meth:`TypesetFormula.code` prints a formula as text, LaTeX, Maple,
Mathematica or Python (sympy's printers, as the exported files, loaded when first asked for).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any, Literal

from sorgui.engine.results import Analysis
from sorgui.export.formulas import Formula, catalogue
from sorgui.export.text import float_text
from sorgui.session import math_text
from sorgui.session.math_text import Mode, Unreadable

if TYPE_CHECKING:
    import numpy as np

MAX_CHARACTERS = 6000
MAX_TERMS = 100
"""Longer formulas are shown as text only: typesetting them would take seconds, and dozens of
typeset lines are no easier to read than the text (folded, with "show all")."""

CODE_LANGUAGES = ("Maple", "Mathematica", "Python")
"""The languages of the copy menu besides text and LaTeX, printed by sympy's printers."""

_BRACKETS = {"Maple": ("[", "]"), "Mathematica": ("{", "}"), "Python": ("(", ")")}

Shape = Literal["expression", "vector", "line", "decimal"]


@dataclass(frozen=True)
class TypesetFormula:
    """One formula as the results pane shows it: as text, and typeset once the typesetting
    process has made its masks.

    ``plain`` is the exact engine text (what Copy gives) and ``text`` the Unicode shown until
    the typeset picture arrives (numbers shortened when ``shortened``). ``pieces`` are the LaTeX
    of its top-level terms with their signs (the first with its label), the places where it
    may be wrapped; empty for a formula shown as text only. ``lines`` and ``masks`` are the
    wrapped lines and their renderings as ``(height, width) uint8`` alpha masks, both empty
    until typeset. ``source`` are the engine strings it was read from (one, the entries of a
    vector, or a line's point and direction), of the ``shape`` given, for :meth:`code`.
    """

    plain: str
    text: str
    pieces: tuple[str, ...] = ()
    lines: tuple[str, ...] = ()
    masks: tuple[np.ndarray, ...] = ()
    source: tuple[str, ...] = ()
    shape: Shape = "expression"
    shortened: bool = False
    latex: str = ""
    """The LaTeX that Copy as LaTeX gives, when it is not sympy's of :attr:`source`."""
    label: str = ""
    """The Unicode label that :attr:`text` starts with (``f = ``, ``φ = ``), if any."""

    @property
    def typeset(self) -> bool:
        return bool(self.masks)

    @property
    def vector(self) -> bool:
        return self.shape == "vector"

    def exact_text(self) -> str:
        """The Unicode with every digit (what "exact digits" shows)."""
        if not self.shortened:
            return self.text
        try:
            entries = [math_text.exact_unicode(s) for s in self.source]
        except Unreadable:
            return self.plain
        return self.label + (_joined(entries, self.shape) if self.shape != "expression" else entries[0])

    def code(self, language: str) -> str:
        """The formula in ``language`` (``"text"``, ``"LaTeX"``, ``"Maple"``, …; plain text if
        unknown). Printed when asked for (the copy menu), not for every formula shown."""
        if language == "text":
            return self.plain
        if language == "LaTeX" and self.latex:
            return self.latex
        if not self.source or self.shape == "decimal":
            return self.latex or self.plain if language == "LaTeX" else self.plain
        try:
            return _printed(self.source, self.shape, language)
        except (Unreadable, ValueError):
            return self.plain


def _printed(source: tuple[str, ...], shape: Shape, language: str) -> str:
    """``source`` printed by sympy's printer for ``language`` (sympy loaded here, when a copy
    in that language is first asked for)."""
    import sympy
    from sympy.printing.maple import maple_code
    from sympy.printing.mathematica import mathematica_code
    from sympy.printing.pycode import pycode

    from sorgui.engine.values import ExpressionError, read_expression

    printers: dict[str, Any] = {
        "LaTeX": lambda e: sympy.latex(e, fold_short_frac=True),
        "Maple": maple_code,
        "Mathematica": mathematica_code,
        "Python": pycode,
    }
    printer = printers.get(language)
    if printer is None:
        raise ValueError(language)
    try:
        parts = [str(printer(read_expression(text))) for text in source]
    except ExpressionError as exc:
        raise ValueError(str(exc)) from None
    if shape == "expression":
        return parts[0]
    if language == "LaTeX":
        if shape == "line":
            return rf"\left({', '.join(parts[:3])}\right) + t\,\left({', '.join(parts[3:])}\right)"
        return r"\left(" + (" : " if len(parts) == 6 else ", ").join(parts) + r"\right)"
    left, right = _BRACKETS[language]
    if shape == "line":
        return f"{left}{', '.join(parts[:3])}{right} + t*{left}{', '.join(parts[3:])}{right}"
    return left + ", ".join(parts) + right


def _joined(entries: Sequence[str], shape: Shape) -> str:
    if shape == "line":
        return f"({', '.join(entries[:3])}) + t·({', '.join(entries[3:])})"
    return "(" + (" : " if len(entries) == 6 else ", ").join(entries) + ")"


def text_formula(text: str) -> TypesetFormula:
    """``text`` shown as it is (not typeset)."""
    return TypesetFormula(text, text)


@lru_cache(maxsize=4096)
def expression_formula(text: str, prefix: str = "", mode: Mode = "exact") -> TypesetFormula:
    """The engine string ``text`` (a number, polynomial or rational function) as a formula,
    labelled ``prefix`` (LaTeX) when typeset. Cached: an analysis is shown after every stage."""
    label = math_text.unicode_label(prefix) + " " if prefix else ""
    try:
        shown = math_text.printed(text, mode, latex=len(text) <= MAX_CHARACTERS)
    except Unreadable:
        return TypesetFormula(text, text)
    pieces = shown.pieces if len(shown.pieces) <= MAX_TERMS else ()
    if pieces and prefix:
        pieces = (f"{prefix} {pieces[0]}", *pieces[1:])
    return TypesetFormula(text, label + shown.unicode, pieces, source=(text,), shortened=shown.shortened, label=label)


def vector_formula(values: Sequence[str], prefix: str = "", mode: Mode = "exact") -> TypesetFormula:
    """A tuple of exact numbers ``(a, b, c)`` (or Plücker coordinates ``(a : … : f)``)."""
    return _vector_formula(tuple(values), prefix, mode)


@lru_cache(maxsize=1024)
def _vector_formula(values: tuple[str, ...], prefix: str, mode: Mode) -> TypesetFormula:
    plain = _vector_text(values)
    try:
        entries = [math_text.printed(v, mode, fold=True) for v in values]
    except Unreadable:
        return TypesetFormula(plain, plain)
    separator = " : " if len(values) == 6 else ", "
    label = math_text.unicode_label(prefix) + " " if prefix else ""
    text = label + "(" + separator.join(e.unicode for e in entries) + ")"
    return TypesetFormula(
        plain,
        text,
        _vector_pieces([e.latex for e in entries], separator, prefix),
        source=values,
        shape="vector",
        shortened=any(e.shortened for e in entries),
        label=label,
    )


def _vector_pieces(entries: list[str], separator: str, prefix: str) -> tuple[str, ...]:
    r"""A vector's LaTeX, one piece per entry, so that a vector wider than the pane wraps between
    its entries (a line of 25-digit directions, shortened or not, scrolled sideways).

    mathtext sizes ``\left(`` by the content: around digits and colons it draws parentheses
    smaller than the text's, so plain ones are typeset unless an entry is tall; then each piece
    is balanced on its own (``\left( … \right.`` and ``\left. … \right)``), as mathtext needs."""
    tall = any(mark in e for e in entries for mark in ("\\frac", "\\sqrt", "^"))
    opening, closing = (r"\left(", r"\right)") if tall else ("(", ")")
    if len(entries) == 1:
        pieces = [opening + entries[0] + closing]
    else:
        first, last = (r"\right.", r"\left.") if tall else ("", "")
        middle = [entry + separator for entry in entries[1:-1]]
        pieces = [opening + entries[0] + separator + first, *middle, last + entries[-1] + closing]
    if prefix:
        pieces[0] = f"{prefix} {pieces[0]}"
    return tuple(pieces)


def line_formula(point: Sequence[str], direction: Sequence[str], mode: Mode = "exact") -> TypesetFormula:
    """The parametric line ``c + t·a``, wrapped (when wider than the pane) before ``+ t·a``, and
    between the entries of ``c`` and ``a`` when one is wider."""
    c, a = vector_formula(point, mode=mode), vector_formula(direction, mode=mode)
    pieces = (*c.pieces, f" + t\\,{a.pieces[0]}", *a.pieces[1:]) if c.pieces and a.pieces else ()
    return TypesetFormula(
        f"{c.plain} + t*{a.plain}",
        f"{c.text} + t·{a.text}",
        pieces,
        source=(*point, *direction),
        shape="line",
        shortened=c.shortened or a.shortened,
    )


def decimal_line_formula(
    point: Sequence[float], direction: Sequence[float], tolerance: float | None = None
) -> TypesetFormula:
    """The line ``c + t·a`` in decimals, ``a`` a unit vector: shown with 6 significant digits,
    copied with 16 (a double's precision); entries below the rounding ``tolerance`` (or 1e-12)
    of the largest are 0. Wrapped (when wider than the pane) before ``+ t·a``."""
    norm = math.sqrt(sum(v * v for v in direction)) or 1.0
    unit = [v / norm for v in direction]
    plain = f"{float_text(point, 16, tolerance)} + t*{float_text(unit, 16, tolerance)}"
    c, a = float_text(point, 6, tolerance), float_text(unit, 6, tolerance)
    pieces = (_decimal_latex(c), r" + t\," + _decimal_latex(a))
    return TypesetFormula(plain, f"{c} + t·{a}", pieces, shape="decimal", latex="".join(pieces))


def _decimal_latex(text: str) -> str:
    """Decimals as mathtext typesets them (``1e-05``: the exponent upright)."""
    return text.replace("e-", r"\mathrm{e}{-}").replace("e+", r"\mathrm{e}{+}")


def decimals(values: Sequence[str]) -> tuple[float, ...] | None:
    """Exact engine numbers (rationals, square roots of them) as floats; ``None`` if one is not
    such a number."""
    try:
        return tuple(math_text.evaluate(math_text.read(v)) for v in values)
    except (Unreadable, ValueError, ZeroDivisionError, OverflowError):
        return None


# --- the pane's formulas of an analysis -----------------------------------------------------


def formula_mode(analysis: Analysis) -> Mode:
    """How an analysis' numbers are shown: in decimals for rounded input (its coefficients are
    decimals as typed), exact otherwise."""
    from sorgui.engine.parsing import has_decimals

    return "decimal" if analysis.approximate is not None or has_decimals(analysis.input) else "exact"


def pane_formulas(analysis: Analysis, mode: Mode | None = None) -> dict[str, TypesetFormula]:
    """Every formula the results pane shows, by key (``"axis.point"``, ``"factor.0"``, …): those of
    the catalogue (:func:`sorgui.export.formulas.catalogue`) with a key, printed in ``mode``
    (default :func:`formula_mode`), ready to show and to typeset."""
    chosen = formula_mode(analysis) if mode is None else mode
    return {key: shown for formula in catalogue(analysis) if formula.key for key, shown in _shown(formula, chosen)}


def _shown(formula: Formula, mode: Mode) -> Iterator[tuple[str, TypesetFormula]]:
    """The pane's formulas of one catalogue ``formula``: one per row for a vector shown in rows;
    none for a line in decimals whose decimals cannot be read."""
    source, label = formula.source, formula.label
    if formula.rows:
        for (suffix, row_label), text in zip(formula.rows, source):
            yield f"{formula.key}.{suffix}", expression_formula(text, row_label, mode)
        return
    match formula.kind:
        case "expression":
            yield formula.key, expression_formula(source[0], label, mode)
        case "vector":
            yield formula.key, vector_formula(source, label, mode)
        case "line":
            yield formula.key, line_formula(source[:3], source[3:], mode)
        case "approximate line":
            numbers = formula.numbers
            yield formula.key, decimal_line_formula(numbers[:3], numbers[3:], formula.tolerance)
        case "decimal line":
            point_floats, direction_floats = decimals(source[:3]), decimals(source[3:])
            if point_floats is not None and direction_floats is not None:
                yield formula.key, decimal_line_formula(point_floats, direction_floats)


def _vector_text(values: Sequence[str]) -> str:
    return "(" + (" : " if len(values) == 6 else ", ").join(values) + ")"
