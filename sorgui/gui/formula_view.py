"""One typeset formula in the results pane, with copy actions.

The worker process rasterised each wrapped line of the formula into an alpha mask
(:mod:`sorgui.gui.formulas`); here the lines are stacked into one image, tinted with the
palette's text colour and shown as one pixmap (one widget per formula keeps the pane quick to
lay out). Only a formula taller or wider than the pane gets a scroll area. A formula without
masks is shown as selectable plain text, shortened if it is huge. The copy button puts the
exact plain text on the clipboard; the context menu also offers LaTeX.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QFontDatabase, QGuiApplication, QIcon, QImage, QPixmap
from PySide6.QtWidgets import QFrame, QHBoxLayout, QLabel, QMenu, QScrollArea, QToolButton, QWidget

from sorgui.gui.formulas import Formula

MAX_HEIGHT = 300
"""Taller formulas scroll (logical pixels), so that one polynomial cannot fill the pane."""

LINE_SPACING = 3
"""Device pixels between the typeset lines of a formula."""

PLAIN_PREVIEW = 1500
"""Characters of an untypeset formula shown (laying out 200 000 would freeze the window)."""


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


class FormulaView(QFrame):
    """A formula, a copy button and a Copy plain text / Copy LaTeX menu.

    ``max_width`` is the width available to the formula (logical pixels); wider ones scroll.
    """

    def __init__(
        self, formula: Formula, parent: QWidget | None = None, ratio: float = 1.0, max_width: int = 10_000
    ) -> None:
        super().__init__(parent)
        self.formula = formula
        self.setObjectName("formulaView")
        self.setContextMenuPolicy(Qt.ContextMenuPolicy.CustomContextMenu)
        self.customContextMenuRequested.connect(self._on_context_menu_change)

        self.content = QLabel()
        self.content.setContextMenuPolicy(Qt.ContextMenuPolicy.NoContextMenu)
        if formula.masks:
            text = self.palette().windowText().color()
            self.content.setPixmap(formula_pixmap(formula.masks, (text.red(), text.green(), text.blue()), ratio))
            self.content.setToolTip(formula.plain if len(formula.plain) <= PLAIN_PREVIEW else "")
        else:
            shown = formula.plain
            if len(shown) > PLAIN_PREVIEW:
                rest = len(shown) - PLAIN_PREVIEW
                shown = f"{shown[:PLAIN_PREVIEW]} … ({rest:,} more characters: copy to get them all)"
            self.content.setText(shown)
            self.content.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
            self.content.setWordWrap(True)
            self.content.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        body: QWidget = self.content
        hint = self.content.sizeHint()
        if formula.masks and (hint.height() > MAX_HEIGHT or hint.width() > max_width):
            scroll = QScrollArea()
            scroll.setWidget(self.content)
            scroll.setFrameShape(QFrame.Shape.NoFrame)
            scroll.setContextMenuPolicy(Qt.ContextMenuPolicy.NoContextMenu)
            bar = scroll.horizontalScrollBar().sizeHint().height() if hint.width() > max_width else 0
            scroll.setFixedHeight(min(hint.height(), MAX_HEIGHT) + bar + 2)
            body = scroll

        self.copy_button = QToolButton(self)
        icon = QIcon.fromTheme("edit-copy")
        if icon.isNull():
            self.copy_button.setText("Copy")
        else:
            self.copy_button.setIcon(icon)
        self.copy_button.setAutoRaise(True)
        self.copy_button.setToolTip("Copy as plain text (right-click for LaTeX)")
        self.copy_button.clicked.connect(self.copy_plain)

        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(2)
        if body is self.content:
            layout.addWidget(body, 1, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignTop)
        else:
            layout.addWidget(body, 1)  # a scroll area takes the whole width (its size hint is small)
        layout.addWidget(self.copy_button, 0, Qt.AlignmentFlag.AlignTop)

    def copy_plain(self) -> None:
        """Put the formula's plain text (the engine's exact string) on the clipboard."""
        QGuiApplication.clipboard().setText(self.formula.plain)

    def copy_latex(self) -> None:
        """Put the formula's LaTeX on the clipboard."""
        QGuiApplication.clipboard().setText(self.formula.latex)

    def _on_context_menu_change(self, position: QPoint) -> None:
        menu = QMenu(self)
        menu.addAction("Copy as plain text", self.copy_plain)
        menu.addAction("Copy as LaTeX", self.copy_latex)
        menu.popup(self.mapToGlobal(position))
