"""View → Cut to a Box: the axis-aligned box the 3D view, the meshes and the CAD files are cut to
(``sorgui analyze --region X0:X1,Y0:Y1,Z0:Z1`` on the command line, docs/math.md §11)."""

from __future__ import annotations

from collections.abc import Sequence

from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QDoubleSpinBox,
    QGridLayout,
    QLabel,
    QVBoxLayout,
    QWidget,
)

Bounds = tuple[float, float, float, float, float, float]

LIMIT = 1e12
"""The largest coordinate a side of the box may have."""


class BoxDialog(QDialog):
    """Six numbers, ``x``, ``y`` and ``z`` from low to high; OK only while each side has a
    positive length."""

    def __init__(self, bounds: Sequence[float], parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Cut to a Box")
        layout = QVBoxLayout(self)
        layout.addWidget(
            QLabel("The surface is drawn, meshed and written to CAD files inside this box\n(in the ball around it).")
        )
        grid = QGridLayout()
        grid.addWidget(QLabel("from"), 0, 1)
        grid.addWidget(QLabel("to"), 0, 2)
        self.boxes: list[QDoubleSpinBox] = []
        for row, name in enumerate("xyz", start=1):
            grid.addWidget(QLabel(name), row, 0)
            for column in (1, 2):
                box = QDoubleSpinBox()
                box.setRange(-LIMIT, LIMIT)
                box.setDecimals(4)
                box.setValue(float(bounds[2 * (row - 1) + column - 1]))
                box.valueChanged.connect(self._check)
                grid.addWidget(box, row, column)
                self.boxes.append(box)
        layout.addLayout(grid)
        self.problem = QLabel()
        layout.addWidget(self.problem)
        self.buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel)
        self.buttons.accepted.connect(self.accept)
        self.buttons.rejected.connect(self.reject)
        layout.addWidget(self.buttons)
        self._check()

    def bounds(self) -> Bounds:
        """``(xmin, xmax, ymin, ymax, zmin, zmax)`` as entered."""
        x0, x1, y0, y1, z0, z1 = (box.value() for box in self.boxes)
        return x0, x1, y0, y1, z0, z1

    def _check(self) -> None:
        values = self.bounds()
        empty = [name for name, low, high in zip("xyz", values[0::2], values[1::2]) if not high > low]
        self.problem.setText(f"Each side goes from low to high: not {', '.join(empty)}." if empty else "")
        self.buttons.button(QDialogButtonBox.StandardButton.Ok).setEnabled(not empty)
