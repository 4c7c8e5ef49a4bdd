"""The Examples menu: the bundled equations of :mod:`sorgui.examples`, one action each.

The equations live in ``sorgui/resources/examples/*.txt`` (package data, shared with the CLI);
choosing one puts its text into the editor and analyses it.
"""

from __future__ import annotations

from PySide6.QtCore import Signal
from PySide6.QtGui import QAction
from PySide6.QtWidgets import QMenu, QWidget

from sorgui.examples import EXAMPLES, example_text


class ExamplesMenu(QMenu):
    """A menu with one action per bundled example; :attr:`example_chosen` carries its text."""

    example_chosen = Signal(str, str)
    """``(title, equation text)`` of the chosen example."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("&Examples", parent)
        for index, example in enumerate(EXAMPLES):
            action = QAction(example.title, self)
            action.setObjectName(f"example-{example.name}")
            action.setData(example.name)
            if index < 9:
                action.setShortcut(f"Ctrl+{index + 1}")
            action.triggered.connect(lambda _checked=False, e=example: self._choose_example(e.name, e.title))
            self.addAction(action)

    def example_actions(self) -> list[QAction]:
        """The example actions, in menu order (for tests)."""
        return [a for a in self.actions() if a.data()]

    def _choose_example(self, name: str, title: str) -> None:
        self.example_chosen.emit(title, example_text(name))
