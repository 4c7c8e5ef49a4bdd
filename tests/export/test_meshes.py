"""Mesh files reload with pyvista: same points and cells, points on f = 0, header facts."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
import pyvista
import sympy

from sorgui.engine.results import Analysis
from sorgui.engine.values import polynomial_terms
from sorgui.export.files import export_analysis
from sorgui.export.formulas import analysis_formulas
from sorgui.export.meshes import MESH_SUFFIXES, mesh_polydata
from sorgui.render import MeshData, PatchData, parametric_patch, surface_mesh
from sorgui.render.sampling import value_and_gradient
from tests.export.conftest import relative_residual

SURFACE_TOLERANCE = 0.05
"""Surface vertices lie within this fraction of the grid spacing of f = 0 (first-order distance
|f|/|∇f|; one Newton step puts them far closer, and float32 formats round them to ~1e-7)."""

PATCH_TOLERANCE = 1e-6
"""Patch points are exact parameter values evaluated in floating point: |f(p)| / Σ|c·p^m| at
most this (the float32 coordinates of STL and PLY limit it, not the parameterization)."""


@dataclass(frozen=True)
class Scene:
    surface: MeshData
    patch: PatchData | None
    notes: tuple[str, ...] = ()


@pytest.fixture(scope="module")
def torus(analyses) -> tuple[Analysis, Scene]:
    analysis = analyses["torus"]
    surface = surface_mesh(polynomial_terms(analysis.squarefree), (-4.0, 4.0, -4.0, 4.0, -1.5, 1.5), resolution=60)
    formula = {f.name: f for f in analysis_formulas(analysis)}["X1"]
    functions = [sympy.lambdify(formula.parameters, c, "numpy") for c in formula.value]
    patch = parametric_patch(*functions, (-3.0, 3.0), (-3.0, 3.0), n=(25, 21))
    return analysis, Scene(surface, patch)


def distances(analysis: Analysis, points: np.ndarray) -> np.ndarray:
    value, gradient = value_and_gradient(polynomial_terms(analysis.squarefree), points)
    return np.abs(value) / np.linalg.norm(gradient, axis=1)


@pytest.mark.parametrize("suffix", MESH_SUFFIXES)
def test_surface_mesh_round_trips(torus, tmp_path, suffix: str) -> None:
    analysis, scene = torus
    path = export_analysis(analysis, tmp_path / f"torus{suffix}", scene=scene)
    mesh = pyvista.read(path)
    expected = mesh_polydata(scene, patch=False)
    assert mesh.n_cells == expected.n_cells == scene.surface.n_faces
    assert mesh.n_points == expected.n_points  # STL repeats corners; VTK's reader merges them again
    spacing = scene.surface.spacing
    assert distances(analysis, np.asarray(mesh.points, dtype=np.float64)).max() <= SURFACE_TOLERANCE * spacing


@pytest.mark.parametrize("suffix", MESH_SUFFIXES)
def test_patch_round_trips(torus, tmp_path, suffix: str) -> None:
    analysis, scene = torus
    path = export_analysis(analysis, tmp_path / f"torus.patch{suffix}", scene=scene)
    mesh = pyvista.read(path)
    expected = mesh_polydata(scene, patch=True)
    assert (mesh.n_points, mesh.n_cells) == (expected.n_points, expected.n_cells)
    assert expected.n_cells == 2 * 24 * 20  # every quad of the 25 × 21 grid, split in two
    points = np.asarray(mesh.points, dtype=np.float64)
    assert relative_residual(analysis.recognition.polynomial, points).max() <= PATCH_TOLERANCE
    if suffix == ".stl":
        assert path.read_bytes()[:80].decode("ascii").startswith("sorgui parametric patch; input units; bbox ")


def test_a_map_without_its_equation_names_the_patch_file_to_write(tmp_path) -> None:
    """Its mesh of f = 0 cannot be made; the message named NAME.patch.stl as if it held the patch
    already ("m.patch.stl holds the given map's patch"), though nothing was written."""
    from sorgui.engine import analyze
    from sorgui.export.files import export_analysis
    from sorgui.session.scene_data import build_scene

    analysis = analyze("(sqrt(2)*s, t, s*t)", recognition_only=True)
    with pytest.raises(ValueError, match=r"write m\.patch\.stl for the given map's patch"):
        export_analysis(analysis, tmp_path / "m.stl", scene=build_scene(analysis))
    assert not (tmp_path / "m.patch.stl").exists()


def test_headers_state_units_bounds_and_equation(torus, tmp_path) -> None:
    analysis, scene = torus
    paths = {s: export_analysis(analysis, tmp_path / f"t{s}", scene=scene) for s in MESH_SUFFIXES}
    header = paths[".stl"].read_bytes()[:80].decode("ascii")
    assert header.startswith("sorgui f=0 surface; input units; bbox ")
    obj = paths[".obj"].read_text(encoding="utf-8").splitlines()
    assert obj[1] == f"# equation: {analysis.recognition.polynomial} = 0"
    assert obj[2].startswith("# units:") and obj[3].startswith("# bounding box: x [")
    ply = paths[".ply"].read_bytes().split(b"end_header")[0].decode("ascii")
    assert f"comment equation: {analysis.recognition.polynomial} = 0" in ply and "comment units:" in ply
    vtp = pyvista.read(paths[".vtp"])
    assert str(vtp.field_data["equation"][0]) == analysis.recognition.polynomial
    assert "x [" in str(vtp.field_data["bounds"][0])


def test_an_empty_mesh_is_refused(analyses, tmp_path) -> None:
    analysis = analyses["torus"]
    empty = Scene(MeshData.empty(), None)
    with pytest.raises(ValueError, match="no real points"):
        export_analysis(analysis, tmp_path / "x.stl", scene=empty)
    with pytest.raises(ValueError, match="no parametric patch"):
        export_analysis(analysis, tmp_path / "x.patch.obj", scene=empty)
    with pytest.raises(ValueError, match="needs the drawn scene"):
        export_analysis(analysis, tmp_path / "x.ply")
    assert not list(tmp_path.iterdir())
