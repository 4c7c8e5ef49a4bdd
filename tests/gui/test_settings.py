"""What sorgui remembers (in a temporary settings folder), and equation files."""

from __future__ import annotations

from pathlib import Path

import pytest

from sorgui.examples import example_text
from sorgui.gui.settings import (
    EquationFileError,
    Settings,
    read_equation,
    write_equation,
)


def test_settings_live_in_the_test_folder(settings_folder: Path) -> None:
    settings = Settings()
    settings.equation = "x^2 + y^2 - 1"
    settings.sync()
    assert Path(settings.file_name).is_relative_to(settings_folder)
    assert Settings().equation == "x^2 + y^2 - 1"


def test_recent_files_are_newest_first_and_unique(tmp_path: Path) -> None:
    settings = Settings()
    changes: list[None] = []
    settings.recent_files_changed.connect(lambda: changes.append(None))
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    settings.add_recent_file(a)
    settings.add_recent_file(b)
    settings.add_recent_file(a)
    assert settings.recent_files == [str(a.resolve()), str(b.resolve())]
    settings.remove_recent_file(str(b.resolve()))
    assert settings.recent_files == [str(a.resolve())]
    assert len(changes) == 4


def test_equation_files_round_trip_and_refuse_junk(tmp_path: Path) -> None:
    path = tmp_path / "eq.txt"
    write_equation(path, "x^2 + y^2 - z\n\n")
    assert path.read_text(encoding="utf-8") == "x^2 + y^2 - z\n"
    assert read_equation(path) == "x^2 + y^2 - z"
    (tmp_path / "bin.txt").write_bytes(b"\xff\xfe\x00x")
    with pytest.raises(EquationFileError, match="UTF-8"):
        read_equation(tmp_path / "bin.txt")
    with pytest.raises(EquationFileError, match="cannot read"):
        read_equation(tmp_path / "missing.txt")


@pytest.mark.gui
def test_editor_content_is_restored_on_the_next_start(make_window, qtbot, settings_folder) -> None:
    first = make_window(prestart_worker=False)
    first.set_equation("x^2 + 2y^2 + 3z^2 - 1")
    first.close()
    second = make_window()
    with qtbot.waitSignal(second.result_shown, timeout=90_000):
        second.load_startup_equation(None)
    assert second.editor.text() == "x^2 + 2y^2 + 3z^2 - 1"
    assert second.results.analysis.recognition.symmetry == "none"


@pytest.mark.gui
def test_open_save_and_recent_files(window, qtbot, tmp_path: Path) -> None:
    path = tmp_path / "cone.txt"
    path.write_text(example_text("cone") + "\n", encoding="utf-8")
    with qtbot.waitSignal(window.result_shown, timeout=90_000):
        assert window.open_file(str(path))
    assert window.editor.text() == example_text("cone")
    assert window.windowTitle().startswith("cone.txt")
    actions = [a for a in window.recent_menu.actions() if a.data()]
    assert [a.data() for a in actions] == [str(path.resolve())]

    window.editor.set_text("y^2 - 2*x*z")
    copy = tmp_path / "copy.txt"
    assert window.save_file(str(copy))
    assert copy.read_text(encoding="utf-8") == "y^2 - 2*x*z\n"
    assert [a.data() for a in window.recent_menu.actions() if a.data()][0] == str(copy.resolve())
    assert not window.isWindowModified()


def test_the_last_sessions_opengl_sets_the_first_mesh(make_window, run_analysis) -> None:
    """The first analysis starts before the render window exists: its mesh is as fine as the
    OpenGL found in the last session allows (coarse in software, as under Xvfb)."""
    from sorgui.gui.viewport import HARDWARE_RESOLUTION, SOFTWARE_RESOLUTION

    first = make_window(prestart_worker=False)
    assert first.viewport.mesh_resolution() == SOFTWARE_RESOLUTION  # nothing known: the worst
    run_analysis(first, example_text("sphere"))
    assert first.viewport.detected_software is True  # Mesa's llvmpipe under Xvfb
    first.close()
    assert Settings().software_rendering is True
    Settings().software_rendering = False  # as a machine with a graphics card would have found
    second = make_window(prestart_worker=False)
    assert not second.viewport.rendering and second.viewport.mesh_resolution() == HARDWARE_RESOLUTION


def test_the_time_limit_and_the_tolerance_are_settings(make_window, monkeypatch) -> None:
    """Analysis → Time Limit… and Rounding Tolerance… set what ``--timeout`` and ``--tolerance`` set
    on the command line, for the next analyses and the next start."""
    from PySide6.QtWidgets import QInputDialog

    window = make_window(prestart_worker=False)
    monkeypatch.setattr(QInputDialog, "getDouble", lambda *_args: (15.0, True))
    window.ask_time_limit()
    monkeypatch.setattr(QInputDialog, "getText", lambda *_args, **_kw: ("1e-6", True))
    window.ask_tolerance()
    assert (window.time_limit, window.tolerance) == (15.0, 1e-6)
    again = make_window(prestart_worker=False)
    assert (again.time_limit, again.tolerance) == (15.0, 1e-6)
    monkeypatch.setattr(QInputDialog, "getText", lambda *_args, **_kw: ("auto", True))
    again.ask_tolerance()
    assert again.tolerance is None and make_window(prestart_worker=False).tolerance is None


def test_the_tolerance_of_the_window_reaches_the_engine() -> None:
    from sorgui.gui.main_window import parse_tolerance
    from sorgui.session.job import JobRequest, run_job
    from sorgui.session.messages import Finished

    assert [parse_tolerance(t) for t in ("auto", "", "1e-8", "2", "x")] == [None, None, 1e-8, False, False]
    final = run_job(JobRequest("x^2 + y^2 - z", tolerance=1e-8, resolution=20))
    assert isinstance(final, Finished) and final.result.analysis.approximate.tolerance == 1e-8


def test_two_recent_files_of_one_name_show_their_folders() -> None:
    """Two ``eq.sor`` in different folders both read "eq.sor" in File ▸ Open Recent (a menu shows
    no tool tip): each now names its folder."""
    from sorgui.gui.settings import recent_label

    files = ["/work/a/eq.sor", "/work/b/eq.sor", "/work/c/torus.sor"]
    assert [recent_label(name, files) for name in files] == ["eq.sor  (a)", "eq.sor  (b)", "torus.sor"]
