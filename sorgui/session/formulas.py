"""The formulas of an analysis as mathematics: LaTeX, wrapped lines and mathtext images.

Which formulas an analysis has is the export layer's one catalogue
(:func:`sorgui.export.formulas.catalogue`); :func:`pane_formulas` makes those the results pane
shows ready to typeset, and nothing here adds or drops one. The pane shows every polynomial,
vector and parameterization typeset, not as Python text. Each engine string is read exactly
(:mod:`sorgui.engine.values`) and printed with ``sympy.latex``, one piece per top-level term.
:func:`render_formulas` then rasterises it with matplotlib's mathtext (Computer Modern) into
8-bit alpha masks: whole when it fits the pane's width, else piece by piece, the pieces set side
by side on one baseline and wrapped between them (mathtext's cost is mostly per parse, so each
piece is typeset once; the worker process shares the parsing with a forked helper, see
:func:`start_helper`). This runs in the analysis worker process (it has no Qt), so the GUI
thread only colours ready-made masks; a formula mathtext cannot typeset is shown as plain text
instead. :meth:`TypesetFormula.code` prints a formula for Maple, Mathematica or Python (sympy's
printers, as the exported files) when the copy menu asks.
"""

from __future__ import annotations

import contextlib
import gc
import os
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from functools import lru_cache
from multiprocessing import Pipe
from multiprocessing.connection import Connection
from typing import NoReturn

import numpy as np
import sympy
from sympy.printing.maple import maple_code
from sympy.printing.mathematica import mathematica_code
from sympy.printing.pycode import pycode

from sorgui.engine.results import Analysis
from sorgui.engine.values import ExpressionError, float_vector, read_expression
from sorgui.export.formulas import Formula, catalogue
from sorgui.export.text import float_text

MAX_CHARACTERS = 6000
MAX_TERMS = 100
"""Longer formulas are shown as plain text only: typesetting them would take seconds, and
dozens of typeset lines are no easier to read than the exact text one can copy."""

CONTINUATION = r"\qquad"
"""The indent of the second and later lines of a wrapped formula."""


@dataclass(frozen=True)
class TypesetFormula:
    """One formula as the results pane shows it: untypeset, or typeset by :func:`render_formulas`.

    ``plain`` and ``latex`` are what the copy actions put on the clipboard. ``pieces`` are the
    LaTeX of its top-level terms with their signs (the first with its label), the places
    where it may be wrapped; ``lines`` and ``masks`` are the wrapped lines and their renderings
    as ``(height, width) uint8`` alpha masks, both empty until :func:`render_formulas`.
    """

    plain: str
    latex: str
    pieces: tuple[str, ...]
    lines: tuple[str, ...] = ()
    masks: tuple[np.ndarray, ...] = ()
    source: tuple[str, ...] = ()
    """The engine strings it was read from (one, or the entries of a vector), for :meth:`code`."""
    vector: bool = False

    def code(self, language: str) -> str:
        """The formula in ``language`` (``"text"``, ``"LaTeX"``, ``"Maple"``, …; plain text if
        unknown). Printed when asked for (the copy menu), not for every formula shown."""
        if language == "LaTeX":
            return self.latex
        printer = dict(CODE_PRINTERS).get(language)
        if printer is None or not self.source:
            return self.plain
        try:
            parts = [printer(read_expression(text)) for text in self.source]
        except ExpressionError:
            return self.plain
        if not self.vector:
            return str(parts[0])
        left, right = _BRACKETS[language]
        return left + ", ".join(parts) + right


@dataclass(frozen=True)
class Style:
    """How the worker typesets formulas: dots per inch (≈ 96 × the screen's device pixel
    ratio), font size in points, and the width of a line in device pixels."""

    dpi: float = 96.0
    size: float = 11.0
    width: float = 420.0


def _latex(expr: sympy.Expr) -> str:
    return str(sympy.latex(expr, fold_short_frac=True))


CODE_PRINTERS = (("Maple", maple_code), ("Mathematica", mathematica_code), ("Python", pycode))
"""The languages of the copy menu, with sympy's printers."""

_BRACKETS = {"Maple": ("[", "]"), "Mathematica": ("{", "}"), "Python": ("(", ")")}


def plain_formula(text: str) -> TypesetFormula:
    """``text`` as an untypeset formula (shown as text until the typeset one arrives)."""
    return TypesetFormula(text, text, ())


@lru_cache(maxsize=4096)
def expression_formula(text: str, prefix: str = "") -> TypesetFormula:
    """The engine string ``text`` (a number, polynomial or rational function) as a formula.

    Cached: a job presents its analysis after every stage, and most formulas are the same."""
    if len(text) > MAX_CHARACTERS:
        return TypesetFormula(text, text, ())
    try:
        expr = read_expression(text)
    except ExpressionError:
        return TypesetFormula(text, text, ())
    terms = expr.as_ordered_terms() if isinstance(expr, sympy.Add) else [expr]
    if len(terms) > MAX_TERMS:
        return TypesetFormula(text, _latex(expr), (), source=(text,))
    pieces = []
    for index, term in enumerate(terms):
        negative = term.could_extract_minus_sign()
        body = _latex(-term if negative else term)
        sign = ("- " if negative else "") if index == 0 else (" - " if negative else " + ")
        pieces.append(sign + body)
    latex = "".join(pieces) if len(pieces) > 1 else _latex(expr)  # what sympy.latex prints for a sum
    if prefix:
        pieces[0] = f"{prefix} {pieces[0]}"
    return TypesetFormula(text, latex, tuple(pieces), source=(text,))


def vector_formula(values: Sequence[str], prefix: str = "") -> TypesetFormula:
    """A tuple of exact numbers ``(a, b, c)`` (or Plücker coordinates ``(a : … : f)``)."""
    return _vector_formula(tuple(values), prefix)


@lru_cache(maxsize=1024)
def _vector_formula(values: tuple[str, ...], prefix: str) -> TypesetFormula:
    separator = " : " if len(values) == 6 else ", "
    plain = "(" + separator.join(values) + ")"
    try:
        exprs = [read_expression(v) for v in values]
    except ExpressionError:
        return TypesetFormula(plain, plain, ())
    entries = [_latex(e) for e in exprs]
    body = separator.join(entries)
    latex = r"\left(" + body + r"\right)"
    # mathtext sizes \left( by the content: around digits and colons it draws parentheses
    # smaller than the text's, so plain ones are typeset unless an entry is tall
    tall = any(mark in entry for entry in entries for mark in ("\\frac", "\\sqrt", "^"))
    shown = latex if tall else "(" + body + ")"
    return TypesetFormula(plain, latex, ((prefix + " " if prefix else "") + shown,), source=values, vector=True)


def line_formula(point: Sequence[str], direction: Sequence[str]) -> TypesetFormula:
    """The parametric line ``c + t·a``."""
    c, a = vector_formula(point), vector_formula(direction)
    latex = f"{c.latex} + t\\,{a.latex}"
    shown = f"{c.pieces[0]} + t\\,{a.pieces[0]}" if c.pieces and a.pieces else latex
    return TypesetFormula(f"{c.plain} + t*{a.plain}", latex, (shown,))


def decimal_line_formula(
    point: Sequence[float], direction: Sequence[float], tolerance: float | None = None
) -> TypesetFormula:
    """The line ``c + t·a`` in decimals: shown with 6 significant digits, copied with 16 (a
    double's precision); entries below the rounding ``tolerance`` (or 1e-12) of the largest are 0."""

    plain = f"{float_text(point, 16, tolerance)} + t*{float_text(direction, 16, tolerance)}"
    shown = f"{float_text(point, 6, tolerance)} + t\\,{float_text(direction, 6, tolerance)}"
    return TypesetFormula(plain, shown, (shown,))


def decimals(values: Sequence[str], evaluate: bool = True) -> tuple[float, ...] | None:
    """Exact engine numbers as floats (:func:`~sorgui.engine.values.float_vector`; without
    ``evaluate`` only rationals, read without sympy); ``None`` if one is not such a number."""
    try:
        if evaluate:
            return tuple(float(v) for v in float_vector(values))
        return tuple(float(Fraction(v)) for v in values)
    except (ExpressionError, ValueError, ZeroDivisionError, TypeError):
        return None


# --- the pane's formulas of an analysis -----------------------------------------------------


def pane_formulas(analysis: Analysis, plain: bool = False) -> dict[str, TypesetFormula]:
    """Every formula the results pane shows, by key (``"axis.point"``, ``"factor.0"``, …): those of
    the catalogue (:func:`sorgui.export.formulas.catalogue`) with a key, ready to typeset.

    ``plain`` gives them as untypeset text at once (no sympy), for the GUI thread to show until
    the typeset ones arrive.
    """
    return {key: shown for formula in catalogue(analysis) if formula.key for key, shown in _shown(formula, plain)}


def _shown(formula: Formula, plain: bool) -> Iterator[tuple[str, TypesetFormula]]:
    """The pane's formulas of one catalogue ``formula``: one per row for a vector shown in rows;
    none for a line in decimals whose decimals are unknown (``plain`` reads only rationals)."""
    source, label = formula.source, formula.label
    if formula.rows:
        for (suffix, row_label), text in zip(formula.rows, source):
            yield f"{formula.key}.{suffix}", plain_formula(text) if plain else expression_formula(text, row_label)
        return
    match formula.kind:
        case "expression":
            yield formula.key, plain_formula(source[0]) if plain else expression_formula(source[0], label)
        case "vector":
            yield formula.key, plain_formula(_vector_text(source)) if plain else vector_formula(source, label)
        case "line":
            point, direction = source[:3], source[3:]
            text = f"{_vector_text(point)} + t*{_vector_text(direction)}"
            yield formula.key, plain_formula(text) if plain else line_formula(point, direction)
        case "approximate line":
            numbers = formula.numbers
            yield formula.key, decimal_line_formula(numbers[:3], numbers[3:], formula.tolerance)
        case "decimal line":
            point_floats, direction_floats = decimals(source[:3], not plain), decimals(source[3:], not plain)
            if point_floats is not None and direction_floats is not None:
                yield formula.key, decimal_line_formula(point_floats, direction_floats)


def _vector_text(values: Sequence[str]) -> str:
    return "(" + (" : " if len(values) == 6 else ", ").join(values) + ")"


# --- mathtext images ------------------------------------------------------------------------

PAD = ((2, 2), (2, 6))
"""Blank rows (top, bottom) and columns (left, right) around a mask: delimiters may reach past
mathtext's box."""

PARALLEL_MINIMUM = 4
"""Fewer pieces than this are typeset in the worker process alone (asking the helper and
pickling its answer cost about a millisecond)."""

BINARY_CONTEXT = "{}"
"""Put before a piece that starts with ``+``/``-`` so that mathtext spaces the sign as the binary
operator it is in the whole formula (an empty group is an operand)."""

WARM_UP = (
    r"f = x^{4} + 2 x^{2} y^{2} - \frac{3 t^{2} + 1}{\sqrt{5} \left(t - 7\right)^{6}} "
    r"\left(0 : 1, -\frac{8}{9}\right) \varphi \rho \tau_{x} \tilde{p}(s, r) P^{2} \qquad "
    r"0123456789 abcdefghijklmnopqrstuvwxyz x^{0123456789 abcdefghijklmnopqrstuvwxyz} "
    r"\frac{0123456789 abcdefghijklmnopqrstuvwxyz + - ( )}{0123456789 abcdefghijklmnopqrstuvwxyz + - ( )} "
    r"\frac{x^{0123456789}}{y^{0123456789}} \sqrt{0123456789}"
)
"""Typeset once when a worker process starts, so that loading mathtext's glyphs is not paid
by the first analysis."""

WARM_UP_EXPRESSION = "-(3*t**2 + 1)/(sqrt(5)*(7*t - 1)**6) + x**4 + 2*x**2*y**2"
"""Made a formula once when a worker process starts: sympy imports its tensor and
combinatorics modules (about 50 ms) the first time it adds terms of this kind."""


@dataclass(frozen=True)
class _Box:
    """A typeset piece: its alpha mask, advance width and depth below the baseline (pixels)."""

    image: np.ndarray
    width: float
    depth: int

    @property
    def ascent(self) -> int:
        return int(self.image.shape[0]) - self.depth


_BOXES: dict[tuple[str, Style], _Box] = {}
"""Every piece typeset in this process, by LaTeX and style (a job typesets each piece once)."""

MAX_BOXES = 20_000
"""The cache starts again when it holds this many pieces (a long-lived process)."""


def _typeset(latex: str, style: Style) -> _Box:
    from matplotlib.font_manager import FontProperties
    from matplotlib.mathtext import MathTextParser

    prop = FontProperties(size=style.size, math_fontfamily="cm")
    parsed = MathTextParser("agg").parse(f"${latex}$", dpi=style.dpi, prop=prop)
    image = np.asarray(parsed.image, dtype=np.uint8)
    return _Box(image, float(parsed.width), min(int(round(parsed.depth)), image.shape[0]))


def _box(latex: str, style: Style) -> _Box:
    """``latex`` typeset by mathtext (Computer Modern); ``ValueError`` if it cannot."""
    key = (latex, style)
    box = _BOXES.get(key)
    if box is None:
        if len(_BOXES) >= MAX_BOXES:
            _BOXES.clear()
        box = _BOXES[key] = _typeset(latex, style)
    return box


_HELPER: Connection | None = None
"""This process' typesetting helper (see :func:`start_helper`), once started."""


def start_helper() -> Connection | None:
    """Fork the typesetting helper, once per process, and return the pipe it answers on
    (``None`` where there is no ``fork``).

    The helper is a copy of this process taken after mathtext is warm: it typesets the lists
    of LaTeX it is sent and answers with their boxes (a piece mathtext rejects is left out;
    the parent typesets it again and reports the error). It exits when the pipe closes, so it
    ends with the worker process however that ends; the worker's process group takes it along
    when a job is cancelled. Forking once, not once per stage, saves the fork and the copying
    of the parent's pages that follows each one.
    """
    global _HELPER
    if _HELPER is None and hasattr(os, "fork"):
        mine, theirs = Pipe()
        # The helper's collections then walk (and copy) none of this process' objects. They
        # stay frozen here too: this runs in the worker process, which serves one job and exits.
        gc.freeze()
        try:
            pid = os.fork()
        except OSError:
            mine.close()
            theirs.close()
            return None
        if pid == 0:
            mine.close()
            _serve_helper(theirs)
        theirs.close()
        _HELPER = mine
    return _HELPER


def _serve_helper(conn: Connection) -> NoReturn:
    """The helper's loop (see :func:`start_helper`): no cleanup of the parent's state at exit."""
    gc.disable()
    try:
        while True:
            latexes, style = conn.recv()
            boxes = {}
            for latex in latexes:
                with contextlib.suppress(ValueError, RuntimeError):
                    boxes[latex] = _typeset(latex, style)
            conn.send(boxes)
    except (EOFError, OSError):
        pass
    finally:
        os._exit(0)


def _ask_helper(helper: Connection, latexes: list[str], style: Style) -> bool:
    """Send ``latexes`` to the helper; ``False`` (and the helper forgotten) if it is gone."""
    global _HELPER
    try:
        helper.send((latexes, style))
    except OSError:
        _HELPER = None
        return False
    return True


def _helper_boxes(helper: Connection, style: Style) -> None:
    """Take the helper's answer into :data:`_BOXES` (nothing, and the helper forgotten, if it
    died: the parent then typesets what is missing)."""
    global _HELPER
    try:
        boxes = helper.recv()
    except (EOFError, OSError):
        _HELPER = None
        return
    for latex, box in boxes.items():
        _BOXES[(latex, style)] = box


def prepare(latexes: Iterable[str], style: Style, processes: int = 1) -> None:
    """Typeset the pieces of ``latexes`` not typeset yet, with ``processes`` processes: on a
    machine with two cores or more the worker process shares them with its helper (see
    :func:`start_helper`), which halves the typesetting of a results pane (mathtext's parser
    is pure Python)."""
    todo = list(dict.fromkeys(latex for latex in latexes if (latex, style) not in _BOXES))
    helper, mine = None, todo
    if processes > 1 and len(todo) >= PARALLEL_MINIMUM:
        halves: tuple[list[str], list[str]] = ([], [])
        for latex in sorted(todo, key=len, reverse=True):  # parsing time grows with the length
            min(halves, key=lambda half: sum(map(len, half))).append(latex)
        helper = start_helper()
        if helper is not None and _ask_helper(helper, halves[1], style):
            mine = halves[0]
        else:
            helper = None
    for latex in mine:
        with contextlib.suppress(ValueError, RuntimeError):  # raised again when it is composed
            _box(latex, style)
    if helper is not None:
        _helper_boxes(helper, style)


def _compose(boxes: Sequence[_Box], indent: float = 0.0) -> np.ndarray:
    """The boxes side by side on one baseline, after ``indent`` blank pixels, padded."""
    ascent = max(b.ascent for b in boxes)
    depth = max(b.depth for b in boxes)
    lefts, x = [], indent
    for b in boxes:
        lefts.append(int(round(x)))
        x += b.width
    width = max(left + b.image.shape[1] for left, b in zip(lefts, boxes))
    canvas = np.zeros((ascent + depth, width), dtype=np.uint8)
    for left, b in zip(lefts, boxes):
        top = ascent - b.ascent
        h, w = b.image.shape
        region = canvas[top : top + h, left : left + w]
        np.maximum(region, b.image, out=region)
    return np.pad(canvas, PAD)


def render_line(latex: str, style: Style) -> np.ndarray:
    """One LaTeX line as an alpha mask (mathtext, Computer Modern); ``ValueError`` if mathtext
    cannot typeset it."""
    return np.pad(_box(latex, style).image, PAD)


def _piece_boxes(pieces: Sequence[str], style: Style) -> list[_Box]:
    """Each piece typeset on its own, the later ones in binary context (see
    :data:`BINARY_CONTEXT`): a formula costs one parse of each piece and nothing more."""
    return [_box(piece if index == 0 else BINARY_CONTEXT + piece, style) for index, piece in enumerate(pieces)]


def wrap(pieces: Sequence[str], style: Style) -> tuple[tuple[int, ...], ...]:
    """Greedy lines of ``pieces`` (as tuples of piece indices) no wider than ``style.width``
    (one piece may be wider); the second and later lines are indented by :data:`CONTINUATION`."""
    boxes = _piece_boxes(pieces, style)
    indent = _box(CONTINUATION, style).width
    lines: list[list[int]] = [[]]
    width = 0.0
    for index, box in enumerate(boxes):
        if lines[-1] and width + box.width > style.width:
            lines.append([])
            width = indent
        lines[-1].append(index)
        width += box.width
    return tuple(tuple(line) for line in lines)


LATEX_PIXELS_PER_CHARACTER = 5.0
"""About how wide a character of a polynomial's LaTeX typesets at 11 pt and 96 dpi (fractions
are narrower): a formula estimated wider than the line is typeset piece by piece at once."""


def _likely_fits(formula: TypesetFormula, style: Style) -> bool:
    """Whether to typeset ``formula`` whole first (one parse; mathtext's cost is mostly per
    parse) rather than piece by piece (what a wrapped formula needs)."""
    pixels = LATEX_PIXELS_PER_CHARACTER * style.size / 11.0 * style.dpi / 96.0
    return len(formula.pieces) == 1 or sum(map(len, formula.pieces)) * pixels <= style.width


def _wanted(formula: TypesetFormula, style: Style) -> list[str]:
    """The LaTeX strings :func:`render_formula` will most likely typeset for ``formula``."""
    if not formula.pieces:
        return []
    if _likely_fits(formula, style):
        return ["".join(formula.pieces)]
    return [
        CONTINUATION,
        *(piece if index == 0 else BINARY_CONTEXT + piece for index, piece in enumerate(formula.pieces)),
    ]


def render_formula(formula: TypesetFormula, style: Style) -> TypesetFormula:
    """``formula`` rasterised: whole on one line if it fits, else its pieces typeset once each
    and set side by side, wrapped between pieces; ``ValueError`` if mathtext cannot typeset it."""
    if not formula.pieces:
        return formula
    if _likely_fits(formula, style):
        whole = "".join(formula.pieces)
        box = _box(whole, style)
        if box.width <= style.width or len(formula.pieces) == 1:
            return replace(formula, lines=(whole,), masks=(np.pad(box.image, PAD),))
    boxes = _piece_boxes(formula.pieces, style)
    indent = _box(CONTINUATION, style).width
    lines, masks = [], []
    for number, indices in enumerate(wrap(formula.pieces, style)):
        text = "".join(formula.pieces[i] for i in indices)
        lines.append(text if number == 0 else CONTINUATION + text)
        masks.append(_compose([boxes[i] for i in indices], 0.0 if number == 0 else indent))
    return replace(formula, lines=tuple(lines), masks=tuple(masks))


def render_formulas(formulas: dict[str, TypesetFormula], style: Style, processes: int = 1) -> dict[str, TypesetFormula]:
    """``formulas`` wrapped and rasterised (their pieces typeset by ``processes`` processes, see
    :func:`prepare`); a formula mathtext rejects keeps no masks."""
    prepare([latex for formula in formulas.values() for latex in _wanted(formula, style)], style, processes)
    out = {}
    for key, formula in formulas.items():
        try:
            out[key] = render_formula(formula, style)
        except (ValueError, RuntimeError):
            out[key] = formula
    return out
