"""One formula in the results pane, with a visible copy menu.

A formula is shown as Unicode math the moment its row is built (``x⁴ + 2x²y² − 6x³/5``, long
numbers shortened: ``7.914…×10³⁸``), selectable, folded after :data:`TEXT_PREVIEW`
characters with a "show all" button. When the typesetting process has typeset it
(:mod:`sorgui.session.typesetting`), its wrapped lines, rasterised into alpha masks, are
stacked into one image, tinted with the palette's text colour and shown as one pixmap instead
(one widget per formula keeps the pane quick to lay out), folded to its first
:data:`FOLDED_LINES` lines; a formula wider than the pane scrolls sideways. A formula whose
numbers are shown short has an "exact digits" button that shows every digit. The Copy button
puts the exact text on the clipboard; the ▾ button beside it (and the context menu) copies as
text, LaTeX, Maple, Mathematica or Python.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QGuiApplication, QImage, QPixmap, QWheelEvent
from PySide6.QtWidgets import (
    QFrame,
    QHBoxLayout,
    QLabel,
    QMenu,
    QScrollArea,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from sorgui.session.formulas import CODE_LANGUAGES, TypesetFormula
from sorgui.session.typesetting import Style, Typeset

FOLDED_LINES = 6
"""Lines of a long typeset formula shown before "show all"."""

LINE_SPACING = 3
"""Device pixels between the typeset lines of a formula."""

TEXT_PREVIEW = 320
"""Characters of a formula shown as text before "show all" (about as much as six typeset lines)."""

PLAIN_LIMIT = 60_000
"""Characters shown at most even after "show all" (laying out 200 000 would freeze the
window); the copy menu always gives the whole formula."""

LANGUAGES = ("text", "LaTeX", *CODE_LANGUAGES)
"""The entries of the copy menu."""


def formula_pixmap(masks: tuple[np.ndarray, ...], color: tuple[int, int, int], ratio: float) -> QPixmap:
    """The alpha ``masks`` (one per line) stacked and painted in ``color``, for a screen of
    device pixel ``ratio``."""
    width = max(mask.shape[1] for mask in masks)
    height = sum(mask.shape[0] for mask in masks) + LINE_SPACING * (len(masks) - 1)
    rgba = np.zeros((height, width, 4), dtype=np.uint8)
    rgba[..., :3] = color
    top = 0
    for mask in masks:
        rgba[top : top + mask.shape[0], : mask.shape[1], 3] = mask
        top += mask.shape[0] + LINE_SPACING
    image = QImage(rgba.data, width, height, 4 * width, QImage.Format.Format_RGBA8888).copy()
    pixmap = QPixmap.fromImage(image)
    pixmap.setDevicePixelRatio(ratio)
    return pixmap


class RowScroll(QScrollArea):
    """The horizontal scroll area of one long formula: a vertical turn of the wheel scrolls the
    results pane (it goes on to the parent), only a horizontal one (or Shift+wheel) this row."""

    def wheelEvent(self, event: QWheelEvent) -> None:  # noqa: N802 (Qt override)
        delta = event.angleDelta()
        sideways = abs(delta.x()) > abs(delta.y()) or bool(event.modifiers() & Qt.KeyboardModifier.ShiftModifier)
        if sideways:
            super().wheelEvent(event)
        else:
            event.ignore()


def retire(widget: QWidget) -> None:
    """Take ``widget`` off the screen and out of its parent's children now, and have Qt delete
    it on the GUI thread at the next turn of the event loop (a widget may be retired from its
    own signal). It is moved under its window, never left without a parent: a widget without
    one belongs to Python, to be deleted when its last reference goes (by the cycle collector,
    on whichever thread runs it), and one also given to ``deleteLater`` crashed PySide6
    (``releaseWrapper``, SIGSEGV) in a test run."""
    widget.hide()
    holder = widget.window()
    if holder is not widget:
        widget.setParent(holder)
    widget.deleteLater()


class FormulaView(QFrame):
    """A formula, its "show all" (or "exact digits") button, and a Copy button with a language
    menu. ``typeset`` is its picture, when the typesetting process has made it already.

    ``max_width`` is the width available to the formula (logical pixels); wider ones scroll.
    """

    def __init__(
        self,
        formula: TypesetFormula,
        parent: QWidget | None = None,
        ratio: float = 1.0,
        max_width: int = 10_000,
        typeset: Typeset | None = None,
    ) -> None:
        super().__init__(parent)
        self.formula = formula
        self.typeset: Typeset | None = typeset if typeset is not None and typeset.masks else None
        self.typeset_style: Style | None = typeset.style if typeset is not None else None
        """The style of the typesetting process' answer, when it came (without masks: rejected)."""
        self._ratio = ratio
        self._max_width = max_width
        self.expanded = False
        self._folded = False
        self.setObjectName("formulaView")
        self.setContextMenuPolicy(Qt.ContextMenuPolicy.CustomContextMenu)
        self.customContextMenuRequested.connect(self._show_context_menu)

        self.content = QLabel()
        self.content.setContextMenuPolicy(Qt.ContextMenuPolicy.NoContextMenu)
        # An attribute over the method QWidget.scroll(dx, dy), which nothing here calls.
        self.scroll: QScrollArea | None = None  # type: ignore[assignment]
        self.show_all_button = QToolButton(self)
        self.show_all_button.setObjectName("showAll")
        self.show_all_button.setAutoRaise(True)
        self.show_all_button.clicked.connect(self.show_all)
        self.show_all_button.setVisible(False)

        self.copy_button = QToolButton(self)
        self.copy_button.setObjectName("copyButton")
        self.copy_button.setText("Copy")
        self.copy_button.setAutoRaise(True)
        self.copy_button.setToolTip("Copy the exact formula as plain text (▾: as LaTeX, Maple, Mathematica or Python)")
        self.copy_button.clicked.connect(self.copy_plain)
        self.languages_button = QToolButton(self)
        self.languages_button.setObjectName("copyAsButton")
        self.languages_button.setText("▾")
        self.languages_button.setAutoRaise(True)
        self.languages_button.setToolTip("Copy as text, LaTeX, Maple, Mathematica or Python")
        self.languages_button.clicked.connect(self._on_languages_change)
        self._copy_menu: QMenu | None = None

        self._body = QVBoxLayout()
        self._body.setContentsMargins(0, 0, 0, 0)
        self._body.setSpacing(0)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(2)
        layout.addLayout(self._body, 1)
        layout.addWidget(self.copy_button, 0, Qt.AlignmentFlag.AlignTop)
        layout.addWidget(self.languages_button, 0, Qt.AlignmentFlag.AlignTop)
        self._fill()

    # --- public API ---

    @property
    def folded(self) -> bool:
        """Whether part of the formula is hidden behind "show all"."""
        return self._folded

    @property
    def shows_typeset(self) -> bool:
        """Whether the typeset picture is shown (not the text)."""
        return self.typeset is not None and not (self.expanded and self.formula.shortened)

    def set_typeset(self, typeset: Typeset) -> None:
        """Show ``typeset``, the typesetting process' picture of the formula, instead of its text
        (an answer without masks, which mathtext could not typeset, leaves the text)."""
        self.typeset_style = typeset.style
        if not typeset.masks or typeset is self.typeset:
            return
        self.typeset = typeset
        self._fill()

    def show_all(self) -> None:
        """Show the whole formula, every digit (up to :data:`PLAIN_LIMIT` characters of text)."""
        self.expanded = True
        self._fill()

    def copy(self, language: str) -> None:
        """Put the formula on the clipboard in ``language`` (one of :data:`LANGUAGES`)."""
        QGuiApplication.clipboard().setText(self.formula.code(language))

    def copy_plain(self) -> None:
        """Put the formula's plain text (the engine's exact string) on the clipboard."""
        self.copy("text")

    def copy_latex(self) -> None:
        """Put the formula's LaTeX on the clipboard."""
        self.copy("LaTeX")

    # --- helpers ---

    def _fill(self) -> None:
        formula = self.formula
        while self._body.count():
            item = self._body.takeAt(0)
            assert item is not None  # count() > 0
            widget = item.widget()
            if widget is not None and widget is not self.show_all_button:
                retire(widget)
        self.content = QLabel()
        self.content.setContextMenuPolicy(Qt.ContextMenuPolicy.NoContextMenu)
        hidden = 0
        typeset = self.typeset if self.shows_typeset else None
        if typeset is not None:
            masks = typeset.masks if self.expanded else typeset.masks[:FOLDED_LINES]
            hidden = len(typeset.masks) - len(masks)
            text = self.palette().windowText().color()
            self.content.setPixmap(formula_pixmap(masks, (text.red(), text.green(), text.blue()), self._ratio))
            self.content.setToolTip(formula.text if len(formula.text) <= TEXT_PREVIEW else "")
            self.show_all_button.setText(f"show all ({hidden} more lines)" if hidden else "exact digits")
        else:
            shown_text = formula.exact_text() if self.expanded else formula.text
            limit = PLAIN_LIMIT if self.expanded else TEXT_PREVIEW
            shown = shown_text[:limit]
            hidden = len(shown_text) - len(shown)
            if hidden:
                shown += " …"  # the button below says how much more, and Copy gives it all
            self.content.setText(shown)
            self.content.setTextFormat(Qt.TextFormat.PlainText)
            # wrapped only when it does not fit: a wrapped label is given a width of Qt's choosing
            self.content.setWordWrap(self.content.fontMetrics().horizontalAdvance(shown) > self._max_width)
            self.content.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            # short: a wider button made the narrowest pane scroll sideways
            self.show_all_button.setText(f"show all ({hidden:,} more characters)" if hidden else "exact digits")
            if hidden:
                self.show_all_button.setToolTip("Show the whole formula (Copy gives it all)")
        hint = self.content.sizeHint()
        if typeset is not None and hint.width() > self._max_width:
            scroll = RowScroll()
            scroll.setWidget(self.content)
            scroll.setFrameShape(QFrame.Shape.NoFrame)
            scroll.setContextMenuPolicy(Qt.ContextMenuPolicy.NoContextMenu)
            scroll.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
            scroll.setFixedHeight(hint.height() + scroll.horizontalScrollBar().sizeHint().height() + 2)
            self._body.addWidget(scroll)
            self.scroll = scroll
        elif self.content.wordWrap():  # the whole width, so that its height follows it
            self._body.addWidget(self.content)
            self.scroll = None
        else:
            self._body.addWidget(self.content, 0, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignTop)
            self.scroll = None
        self._folded = hidden > 0 and not self.expanded
        exact_digits = formula.shortened and not self.expanded
        self.show_all_button.setVisible(self._folded or exact_digits)
        if self._folded or exact_digits:
            if not self._folded:
                self.show_all_button.setToolTip("Show the exact numbers, every digit (Copy gives them too)")
            self._body.addWidget(self.show_all_button, 0, Qt.AlignmentFlag.AlignLeft)
        self.updateGeometry()

    @property
    def copy_menu(self) -> QMenu:
        """The menu of languages, built the first time it is needed (a pane holds many formulas)."""
        if self._copy_menu is None:
            self._copy_menu = QMenu(self)
            for language in LANGUAGES:

                def copy_as(lang: str = language) -> None:
                    self.copy(lang)

                self._copy_menu.addAction(f"Copy as {language}", copy_as)
        return self._copy_menu

    def _on_languages_change(self) -> None:
        self.copy_menu.popup(self.languages_button.mapToGlobal(self.languages_button.rect().bottomLeft()))

    def _show_context_menu(self, position: QPoint) -> None:
        self.copy_menu.popup(self.mapToGlobal(position))
