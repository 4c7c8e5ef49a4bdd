"""Layering: the exact engine and the session model load neither Qt nor VTK (checked in a fresh
interpreter, like MNE)."""

from __future__ import annotations

import json
import subprocess
import sys

FORBIDDEN = ("PySide6", "shiboken6", "pyvista", "pyvistaqt", "vtk", "vtkmodules", "qtpy", "matplotlib")


def loaded_modules(statement: str) -> set[str]:
    code = f"import sys, json; {statement}; print(json.dumps(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120)
    return set(json.loads(out.stdout))


def test_engine_imports_neither_qt_nor_vtk() -> None:
    modules = loaded_modules(
        "import sorgui.engine; from sorgui.engine import analyze; analyze('x^2+y^2-z^2', recognition_only=True)"
    )
    top = {m.split(".")[0] for m in modules}
    assert not top & set(FORBIDDEN), sorted(top & set(FORBIDDEN))


def test_command_line_imports_neither_qt_nor_vtk() -> None:
    modules = loaded_modules("import sorgui.cli, sorgui.export.text")
    top = {m.split(".")[0] for m in modules}
    assert not top & set(FORBIDDEN), sorted(top & set(FORBIDDEN))


def test_session_imports_neither_qt_nor_vtk() -> None:
    statement = (
        "import sorgui.session; from sorgui.session import Session, Run, StageState; "
        "import sorgui.session.formulas, sorgui.session.events, sorgui.session.job; Session()"
    )
    modules = loaded_modules(statement)
    top = {m.split(".")[0] for m in modules}
    assert not top & set(FORBIDDEN), sorted(top & set(FORBIDDEN))


def test_recognition_only_over_the_rationals_loads_no_sympy() -> None:
    """The rational path (docs/benchmarks.md, "the start of one process"): a surface of revolution
    over QQ is recognised, its profile and canal answer given, with flint alone."""
    modules = loaded_modules(
        "from sorgui.engine import analyze; "
        "assert analyze('(x^2+y^2+z^2+3)^2-16(x^2+y^2)', recognition_only=True).recognition.is_sor"
    )
    assert "sympy" not in modules and "numpy" not in modules


def test_an_exact_analysis_and_its_report_load_no_numpy() -> None:
    """Numpy (about 50 ms to import) is for rounded input and meshes: the full analysis of an
    exact surface of revolution, a cone among its stages, and its text report do without it."""
    modules = loaded_modules(
        "from sorgui.engine import analyze; from sorgui.export.text import plain_text; "
        "a = analyze('(x^2+y^2+z^2+3)^2-16(x^2+y^2)'); assert a.rationality is not None; "
        "assert 'YES' in plain_text(a); assert 'cone' in plain_text(analyze('x^2+y^2-z^2'))"
    )
    assert "sympy" in modules and "numpy" not in modules


def test_the_render_layer_loads_no_sympy() -> None:
    """The render layer, the touching spheres of a canal family included (their real roots come
    from ``sorgui.numerics``, numpy only), loads neither sympy nor the engine."""
    modules = loaded_modules("import sorgui.render, sorgui.render.canal_touch, sorgui.render.canal_scene")
    assert "sympy" not in modules and "sorgui.engine" not in modules


def test_the_window_starts_without_sympy_the_exporters_and_vtk() -> None:
    """The window's modules load neither sympy, the export writers nor VTK (docs/benchmarks.md,
    "The window beside the command line"): the exporters are loaded at export time, sympy where
    a result needs it (in the worker process, a copy as code), VTK with the render window, once
    the window is drawn. Checking the startup equation over QQ needs flint alone."""
    modules = loaded_modules(
        "import sorgui.gui.main_window; from sorgui.gui.editor import summary; "
        "assert summary('(x^2+y^2+z^2+21)^2-100(x^2+y^2)') == '✓ degree 4 over QQ'"
    )
    loaded = {"sympy", "vtkmodules", "pyvista", "sorgui.export.files", "sorgui.export.cas"} & modules
    assert not loaded, sorted(loaded)
