"""Import nesting of the render layer (STYLE.md: engine → render → export → gui)."""

from __future__ import annotations

import json
import subprocess
import sys


def loaded_after(statement: str) -> set[str]:
    """The names of the modules loaded by ``statement`` in a fresh interpreter."""
    code = f"import json, sys\n{statement}\nprint(json.dumps(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


def test_render_layer_imports_neither_qt_nor_gui_nor_engine_nor_sympy():
    modules = loaded_after("import sorgui.render, sorgui.render.mesh, sorgui.render.scene, sorgui.render.picking")
    for forbidden in ("PySide6", "pyvistaqt", "qtpy", "sorgui.gui", "sorgui.engine", "sympy"):
        assert forbidden not in modules, forbidden


def test_building_meshes_does_not_need_pyvista():
    modules = loaded_after(
        "from sorgui.render.mesh import surface_mesh\n"
        "surface_mesh([((2, 0, 0), 1.0), ((0, 2, 0), 1.0), ((0, 0, 2), 1.0), ((0, 0, 0), -1.0)],"
        " (-2, 2, -2, 2, -2, 2), 20)"
    )
    assert "pyvista" not in modules and "vtkmodules.vtkFiltersCore" in modules
