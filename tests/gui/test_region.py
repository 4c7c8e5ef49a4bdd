"""View → Cut to a Box: the window's mesh and its CAD export are cut to the box the user gives
(the command line's ``--region X0:X1,Y0:Y1,Z0:Z1``). Real window, worker and export process."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtWidgets import QDialogButtonBox

from sorgui.gui.region_dialog import BoxDialog

pytestmark = pytest.mark.gui

TORUS = "(x^2 + y^2 + z^2 + 8)^2 - 36(x^2 + y^2)"
BOX = (0.0, 5.0, -5.0, 5.0, -0.5, 2.0)


def test_a_box_cuts_the_drawn_mesh_and_the_exported_step_file(window, run_analysis, qtbot, tmp_path) -> None:
    pytest.importorskip("OCP")
    run_analysis(window, TORUS)
    assert window.cut_to_box(BOX)
    qtbot.waitUntil(lambda: window.viewport.scene is not None and window.viewport.scene.box is not None, timeout=60_000)
    low, high = np.array(BOX[0::2]), np.array(BOX[1::2])
    points = window.viewport.scene.surface.points
    assert len(points) > 100 and np.all(points >= low - 1e-9) and np.all(points <= high + 1e-9)
    assert points[:, 2].min() < -0.45 and points[:, 0].max() > 3.9, "the mesh reaches the box's sides"
    assert "in the box (0, -5, -0.5) to (5, 5, 2)" in window.viewport.scene.summary()

    path = tmp_path / "half.step"
    with qtbot.waitSignal(window.cad_export.written, timeout=120_000):
        window.export_in_background(path)
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    from sorgui.cad.writers import read_shape

    bounds = Bnd_Box()
    BRepBndLib.AddOptimal_s(read_shape(path), bounds, False, False)
    assert np.all(np.array(bounds.CornerMin().Coord()) >= low - 1e-6)
    assert np.all(np.array(bounds.CornerMax().Coord()) <= high + 1e-6)
    assert "TOROIDAL_SURFACE" in path.read_text(encoding="ascii") and "cut to the box" in path.read_text("ascii")

    assert window.whole_ball()
    qtbot.waitUntil(lambda: window.viewport.scene is not None and window.viewport.scene.box is None, timeout=60_000)


def test_the_box_dialog_accepts_only_sides_from_low_to_high(qtbot) -> None:
    dialog = BoxDialog(BOX)
    qtbot.addWidget(dialog)
    ok = dialog.buttons.button(QDialogButtonBox.StandardButton.Ok)
    assert ok.isEnabled() and dialog.bounds() == BOX
    dialog.boxes[3].setValue(-6.0)  # y from -5 to -6
    assert not ok.isEnabled() and "not y" in dialog.problem.text()


def test_the_camera_frames_the_box_not_the_ball_that_holds_it(window, run_analysis, qtbot) -> None:
    """A box 2 across on a torus 580 across was framed in the ball about the axis holding it
    (radius 291): the piece was a speck in the middle of an empty view."""
    big = "((x-1000)^2+(y+200)^2+(z-50)^2+250^2-40^2)^2-4*250^2*((x-1000)^2+(y+200)^2)"
    run_analysis(window, big)
    box = (1289.0, 1291.0, -201.0, -199.0, 49.0, 51.0)
    assert window.cut_to_box(box)
    qtbot.waitUntil(lambda: window.viewport.scene is not None and window.viewport.scene.box is not None, timeout=60_000)
    assert window.viewport.scene.surface.n_faces > 100
    camera = window.viewport.plotter.renderer.GetActiveCamera()
    assert np.allclose(camera.GetFocalPoint(), (1290.0, -200.0, 50.0), atol=1e-6)
    assert np.linalg.norm(np.array(camera.GetPosition()) - (1290.0, -200.0, 50.0)) < 20
