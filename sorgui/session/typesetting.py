"""The typesetting process: LaTeX pieces to mathtext pictures, in the background, in the order asked.

The results pane shows every formula as text at once (:mod:`sorgui.session.formulas`) and asks
this process, which the window starts once and keeps, to typeset them: the rows on screen first,
then the others. It never stands between the engine and the window: it is a process of its own
at a low priority, and each request replaces the previous one (the pane always sends the whole
list of what it still lacks, visible rows first), so a scrolled pane or a new analysis is served
next. Each piece is typeset once and kept (a new run of the same equation, or another zoom step,
is served from memory).

A formula is typeset with matplotlib's mathtext (Computer Modern) into 8-bit alpha masks: whole
when it fits the pane's width, else piece by piece, the pieces set side by side on one baseline
and wrapped between them (mathtext's cost is mostly per parse, so each piece is typeset once).
A formula mathtext cannot typeset is answered without masks: the pane keeps its text.

No Qt and no sympy here: the window's side is :mod:`sorgui.gui.typesetter`.
"""

from __future__ import annotations

import contextlib
import gc
from collections.abc import Sequence
from dataclasses import dataclass
from multiprocessing.connection import Connection

import numpy as np

CONTINUATION = r"\qquad"
"""The indent of the second and later lines of a wrapped formula."""

PAD = ((2, 2), (2, 6))
"""Blank rows (top, bottom) and columns (left, right) around a mask: delimiters may reach past
mathtext's box."""

BINARY_CONTEXT = "{}"
"""Put before a piece that starts with ``+``/``-`` so that mathtext spaces the sign as the binary
operator it is in the whole formula (an empty group is an operand)."""

WARM_UP = (
    r"f = x^{4} + 2 x^{2} y^{2} - \frac{3 t^{2} + 1}{\sqrt{5} \left(t - 7\right)^{6}} "
    r"\left(0 : 1, -\frac{8}{9}\right) \varphi \rho \tau_{x} \tilde{p}(s, r) P^{2} \qquad "
    r"0123456789 abcdefghijklmnopqrstuvwxyz x^{0123456789 abcdefghijklmnopqrstuvwxyz} "
    r"\frac{0123456789 abcdefghijklmnopqrstuvwxyz + - ( )}{0123456789 abcdefghijklmnopqrstuvwxyz + - ( )} "
    r"\frac{x^{0123456789}}{y^{0123456789}} \sqrt{0123456789} 1.2\ldots\times 10^{38}"
)
"""Typeset once when the process starts, so that loading mathtext's glyphs is not paid by the
first formulas."""


@dataclass(frozen=True)
class Style:
    """How formulas are typeset: dots per inch (≈ 96 × the screen's device pixel ratio), font
    size in points, and the width of a line in device pixels."""

    dpi: float = 96.0
    size: float = 11.0
    width: float = 420.0


@dataclass(frozen=True)
class Request:
    """Typeset these formulas (each given by its LaTeX pieces), in this order, in ``style``;
    it replaces the previous request."""

    style: Style
    formulas: tuple[tuple[str, ...], ...]


@dataclass(frozen=True)
class Typeset:
    """One formula typeset: its pieces (as asked), the wrapped lines and their alpha masks
    (both empty when mathtext cannot typeset it)."""

    style: Style
    pieces: tuple[str, ...]
    lines: tuple[str, ...]
    masks: tuple[np.ndarray, ...]


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
"""Every piece typeset in this process, by LaTeX and style."""

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
    (one piece may be wider); the second and later lines are indented by :data:`CONTINUATION`.

    A piece that starts with a space (a term's `` + …``, a line's `` + t·a``) starts a group
    with the pieces after it that do not (a vector's entries): lines break between groups, and
    inside a group only where it is wider than a line, so ``c + t·a`` breaks before ``+ t``
    first and between the entries of ``c`` or ``a`` only if one is wider than the pane."""
    boxes = _piece_boxes(pieces, style)
    indent = _box(CONTINUATION, style).width
    lines: list[list[int]] = [[]]
    width = 0.0
    for group in _groups(pieces):
        if lines[-1] and width + sum(boxes[i].width for i in group) > style.width:
            lines.append([])
            width = indent
        for index in group:
            if lines[-1] and width + boxes[index].width > style.width:
                lines.append([])
                width = indent
            lines[-1].append(index)
            width += boxes[index].width
    return tuple(tuple(line) for line in lines)


def _groups(pieces: Sequence[str]) -> list[list[int]]:
    """The indices of ``pieces`` in groups, each starting at the first piece or at one that
    starts with a space (:func:`wrap`)."""
    groups: list[list[int]] = []
    for index, piece in enumerate(pieces):
        if not groups or piece.startswith(" "):
            groups.append([])
        groups[-1].append(index)
    return groups


LATEX_PIXELS_PER_CHARACTER = 5.0
"""About how wide a character of a polynomial's LaTeX typesets at 11 pt and 96 dpi (fractions
are narrower): a formula estimated wider than the line is typeset piece by piece at once."""


def _likely_fits(pieces: Sequence[str], style: Style) -> bool:
    """Whether to typeset a formula whole first (one parse; mathtext's cost is mostly per
    parse) rather than piece by piece (what a wrapped formula needs)."""
    pixels = LATEX_PIXELS_PER_CHARACTER * style.size / 11.0 * style.dpi / 96.0
    return len(pieces) == 1 or sum(map(len, pieces)) * pixels <= style.width


def render(pieces: tuple[str, ...], style: Style) -> tuple[tuple[str, ...], tuple[np.ndarray, ...]]:
    """A formula's lines and masks: whole on one line if it fits, else its pieces typeset once
    each and set side by side, wrapped between pieces; ``ValueError`` if mathtext cannot."""
    if _likely_fits(pieces, style):
        whole = "".join(pieces)
        box = _box(whole, style)
        if box.width <= style.width or len(pieces) == 1:
            return (whole,), (np.pad(box.image, PAD),)
    boxes = _piece_boxes(pieces, style)
    indent = _box(CONTINUATION, style).width
    lines, masks = [], []
    for number, indices in enumerate(wrap(pieces, style)):
        text = "".join(pieces[i] for i in indices)
        lines.append(text if number == 0 else CONTINUATION + text)
        masks.append(_compose([boxes[i] for i in indices], 0.0 if number == 0 else indent))
    return tuple(lines), tuple(masks)


def typeset(pieces: tuple[str, ...], style: Style) -> Typeset:
    """The answer for one formula (no masks when mathtext rejects it)."""
    try:
        lines, masks = render(pieces, style)
    except (ValueError, RuntimeError):
        return Typeset(style, pieces, (), ())
    return Typeset(style, pieces, lines, masks)


def serve(conn: Connection) -> None:
    """The typesetting process: warm mathtext up, then typeset what is asked, one formula at a
    time, taking a newer request (which replaces the list) between formulas; it ends when the
    window closes the pipe."""
    with contextlib.suppress(ValueError, RuntimeError):
        render_line(WARM_UP, Style())
    gc.collect()
    gc.freeze()  # the collections then walk only the formulas' objects, not matplotlib's
    waiting: list[tuple[str, ...]] = []
    style = Style()
    try:
        while True:
            while not waiting or conn.poll():
                request = conn.recv()
                if isinstance(request, Request):
                    style, waiting = request.style, list(request.formulas)
            conn.send(typeset(waiting.pop(0), style))
    except (EOFError, OSError):
        return
