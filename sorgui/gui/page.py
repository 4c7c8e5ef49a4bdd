"""The results pane's page: a column of blocks (the verdict banner, the sections, Table 1) that
survive from one stage of an analysis to the next.

An analysis is shown again after every stage with a little more in it. Building every row's
widgets anew each time cost the GUI thread tens of milliseconds per stage (hundreds on a loaded
machine) and threw away what the user had done (a formula unfolded, a picture typeset). So the
pane describes the page it wants, block by block (:meth:`Page.section`, :meth:`Page.block`),
and :meth:`Page.end` keeps every block whose content is the same as one already shown,
builds only the new ones, drops those no longer wanted and lays the column out at once (built
on screen, a new block would be drawn over the others until the next turn of the event loop).
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass, field

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QGridLayout, QLabel, QTableWidget, QVBoxLayout, QWidget

from sorgui.gui.formula_view import FormulaView, retire
from sorgui.gui.wording import breakable, short_numbers
from sorgui.session.formulas import TypesetFormula

CAPTION_WIDTH = 130
"""Width of the caption column, the same in every section so that formulas line up."""

Row = tuple[str, "str | tuple[str, TypesetFormula]"]
"""A section's row: a caption and a text, or a caption and a formula with its key."""

ViewMaker = Callable[[TypesetFormula, str], FormulaView]
"""Makes the view of a formula (its caption given, for the tooltip)."""


@dataclass
class Block:
    """One block of the page: what it shows (``signature``), its widget, its formula views."""

    signature: Hashable
    widget: QWidget
    views: dict[str, FormulaView] = field(default_factory=dict)


class Page(QWidget):
    """The column of blocks; :attr:`views` are the formula views shown, by key."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("resultsPage")
        self.column = QVBoxLayout(self)
        self.column.setContentsMargins(10, 10, 10, 10)
        self.column.setSpacing(6)
        self.column.addStretch(1)
        self.blocks: list[Block] = []
        self.views: dict[str, FormulaView] = {}
        self._wanted: list[tuple[Hashable, Callable[[], Block]]] = []

    # --- describing the page ---

    def begin(self) -> None:
        """Start describing the page anew (nothing changes on screen until :meth:`end`)."""
        self._wanted = []

    def block(self, signature: Hashable, build: Callable[[], QWidget]) -> None:
        """A block showing ``signature``, built by ``build`` unless one shows it already."""
        self._wanted.append((signature, lambda: Block(signature, build())))

    def section(self, heading: str, rows: Sequence[Row], make_view: ViewMaker, tip: Callable[[str], str]) -> None:
        """A heading and a grid of rows: a caption (with its tooltip ``tip``), then a text or
        a formula's view (made by ``make_view``)."""
        signature = ("section", heading, tuple(rows))
        self._wanted.append((signature, lambda: _section(signature, heading, rows, make_view, tip)))

    def end(self) -> None:
        """Show the blocks described since :meth:`begin`, in order: the same ones kept where
        they are, new ones built and put in place, the others dropped; the column is laid out
        before anything is drawn. (Blocks are moved in the layout one by one, never all taken
        out and put back: a widget taken out keeps pointing at its old layout item, whose cached
        size then hides the widget's growth, e.g. a formula replaced by its taller picture.)"""
        kept: dict[Hashable, list[Block]] = {}
        for old in self.blocks:
            kept.setdefault(old.signature, []).append(old)
        blocks = [kept[signature].pop(0) if kept.get(signature) else build() for signature, build in self._wanted]
        fresh = [block for block in blocks if block.widget.parent() is not self]
        for leftovers in kept.values():
            for old in leftovers:
                self.column.removeWidget(old.widget)
                retire(old.widget)
        for index, block in enumerate(blocks):
            item = self.column.itemAt(index)
            if item is not None and item.widget() is block.widget:
                continue
            if block.widget.parent() is self:
                self.column.removeWidget(block.widget)
            self.column.insertWidget(index, block.widget)
        for block in fresh:
            block.widget.show()  # now, not at the next turn: a hidden block would be laid out as empty
        self.column.activate()
        self.blocks = blocks
        self.views = {key: view for block in blocks for key, view in block.views.items()}
        self._wanted = []

    # --- what is shown ---

    def widget_named(self, name: str) -> QWidget | None:
        """The block widget with this object name (the banner, Table 1), if shown."""
        return next((b.widget for b in self.blocks if b.widget.objectName() == name), None)

    @property
    def table(self) -> QTableWidget | None:
        widget = self.widget_named("table1")
        return widget if isinstance(widget, QTableWidget) else None


def _section(
    signature: Hashable, heading: str, rows: Sequence[Row], make_view: ViewMaker, tip: Callable[[str], str]
) -> Block:
    box = QWidget()
    layout = QVBoxLayout(box)
    layout.setContentsMargins(0, 0, 0, 0)
    layout.setSpacing(6)
    title = QLabel(short_numbers(heading))
    title.setObjectName("sectionHeading")
    font = title.font()
    font.setBold(True)
    font.setPointSizeF(font.pointSizeF() * 1.1)
    title.setFont(font)
    title.setContentsMargins(0, 8, 0, 0)
    layout.addWidget(title)
    grid = QGridLayout()
    grid.setHorizontalSpacing(10)
    grid.setVerticalSpacing(4)
    grid.setColumnStretch(1, 1)
    grid.setColumnMinimumWidth(0, CAPTION_WIDTH)
    views: dict[str, FormulaView] = {}
    for index, (caption, value) in enumerate(rows):
        label = QLabel(caption)
        label.setObjectName("caption")
        label.setToolTip(tip(caption))
        label.setStyleSheet("color: #546e7a;")
        label.setWordWrap(True)
        label.setFixedWidth(CAPTION_WIDTH)
        grid.addWidget(label, index, 0, Qt.AlignmentFlag.AlignTop)
        if isinstance(value, tuple):
            key, formula = value
            view = make_view(formula, caption)
            views[key] = view
            grid.addWidget(view, index, 1)
        else:
            text = QLabel(breakable(short_numbers(value)))
            text.setWordWrap(True)
            text.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            grid.addWidget(text, index, 1)
    layout.addLayout(grid)
    return Block(signature, box, views)
