"""One typeset formula in the results pane, with a visible copy menu.

The worker process rasterised each wrapped line of the formula into an alpha mask
(:mod:`sorgui.session.formulas`); here the lines are stacked into one image, tinted with the
palette's text colour and shown as one pixmap (one widget per formula keeps the pane quick to
lay out). A long formula is folded to its first :data:`FOLDED_LINES` lines with a "show all"
button; a formula wider than the pane scrolls sideways. A formula without masks (not typeset
yet, or too long to typeset) is shown as selectable plain text written as people write it (``x^12``,
``3·x``: :func:`readable_text`), elided with "show all" too.
The Copy button puts the exact text on the clipboard; the ▾ button beside it (and the context
menu) copies as text, LaTeX, Maple, Mathematica or Python.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QFontDatabase, QGuiApplication, QImage, QPixmap, QWheelEvent
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

from sorgui.session.formulas import CODE_PRINTERS, TypesetFormula

FOLDED_LINES = 6
"""Lines of a long typeset formula shown before "show all"."""

LINE_SPACING = 3
"""Device pixels between the typeset lines of a formula."""

PLAIN_PREVIEW = 1500
"""Characters of an untypeset formula shown before "show all"."""

PLAIN_LIMIT = 60_000
"""Characters shown at most even after "show all" (laying out 200 000 would freeze the
window); the copy menu always gives the whole formula."""

LANGUAGES = ("text", "LaTeX", *(name for name, _printer in CODE_PRINTERS))
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


def readable_text(text: str) -> str:
    """An engine string as people write it: ``x**12`` as ``x^12`` and ``3*x`` as ``3·x`` (what
    a formula too long to typeset shows; the copy buttons still give the exact string)."""
    return text.replace("**", "^").replace("*", "·")


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


class FormulaView(QFrame):
    """A formula, its "show all" button when folded, and a Copy button with a language menu.

    ``max_width`` is the width available to the formula (logical pixels); wider ones scroll.
    """

    def __init__(
        self, formula: TypesetFormula, parent: QWidget | None = None, ratio: float = 1.0, max_width: int = 10_000
    ) -> None:
        super().__init__(parent)
        self.formula = formula
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
        self.copy_button.setToolTip("Copy as plain text (▾: as LaTeX, Maple, Mathematica or Python)")
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

    def set_formula(self, formula: TypesetFormula) -> None:
        """Show ``formula`` instead (the typeset version of the text shown so far)."""
        self.formula = formula
        self._fill()

    def show_all(self) -> None:
        """Show the whole formula (up to :data:`PLAIN_LIMIT` characters of plain text)."""
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
                widget.setParent(None)
        self.content = QLabel()
        self.content.setContextMenuPolicy(Qt.ContextMenuPolicy.NoContextMenu)
        hidden = 0
        if formula.masks:
            masks = formula.masks if self.expanded else formula.masks[:FOLDED_LINES]
            hidden = len(formula.masks) - len(masks)
            text = self.palette().windowText().color()
            self.content.setPixmap(formula_pixmap(masks, (text.red(), text.green(), text.blue()), self._ratio))
            self.content.setToolTip(formula.plain if len(formula.plain) <= PLAIN_PREVIEW else "")
            self.show_all_button.setText(f"show all ({hidden} more lines)")
        else:
            limit = PLAIN_LIMIT if self.expanded else PLAIN_PREVIEW
            readable = readable_text(formula.plain)
            shown = readable[:limit]
            hidden = len(readable) - len(shown)
            if hidden:
                shown += f" … ({hidden:,} more characters: copy to get them all)"
            self.content.setText(shown)
            self.content.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
            self.content.setWordWrap(True)
            self.content.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            self.show_all_button.setText(f"show all ({hidden:,} more characters)")
        hint = self.content.sizeHint()
        if formula.masks and hint.width() > self._max_width:
            scroll = RowScroll()
            scroll.setWidget(self.content)
            scroll.setFrameShape(QFrame.Shape.NoFrame)
            scroll.setContextMenuPolicy(Qt.ContextMenuPolicy.NoContextMenu)
            scroll.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
            scroll.setFixedHeight(hint.height() + scroll.horizontalScrollBar().sizeHint().height() + 2)
            self._body.addWidget(scroll)
            self.scroll = scroll
        else:
            self._body.addWidget(self.content, 0, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignTop)
            self.scroll = None
        self._folded = hidden > 0 and not self.expanded
        self.show_all_button.setVisible(self._folded)
        if self._folded:
            self._body.addWidget(self.show_all_button, 0, Qt.AlignmentFlag.AlignLeft)

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
