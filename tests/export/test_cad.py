"""CAD export (STEP, IGES, BRep): every file read back with Open CASCADE's own readers.

Each face must be valid (``BRepCheck_Analyzer``) and keep its kind (a surface of revolution, or
the analytic surface); at 1000 sampled ``(u, v)`` points of the read-back faces ``|f|/|∇f|`` is at
most 1e-9 of the drawn ball's radius for exact profiles, and within the stated tolerance for
fitted ones. The analyses come from the real engine (Singular included).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from sorgui.engine import analyze
from sorgui.engine.results import Analysis
from sorgui.engine.values import polynomial_terms
from sorgui.examples import example_text
from sorgui.export.files import export_analysis
from sorgui.session.scene_data import SceneData, build_scene

pytest.importorskip("OCP")

from OCP.BRep import BRep_Tool  # noqa: E402
from OCP.BRepCheck import BRepCheck_Analyzer  # noqa: E402
from OCP.BRepGProp import BRepGProp  # noqa: E402
from OCP.BRepTools import BRepTools  # noqa: E402
from OCP.GeomAbs import GeomAbs_SurfaceType  # noqa: E402
from OCP.GeomAdaptor import GeomAdaptor_Surface  # noqa: E402
from OCP.GProp import GProp_GProps  # noqa: E402
from OCP.TopAbs import TopAbs_FACE  # noqa: E402
from OCP.TopExp import TopExp_Explorer  # noqa: E402
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape  # noqa: E402

from sorgui.export.cad.geometry import surface_distance  # noqa: E402
from sorgui.export.cad.writers import read_shape  # noqa: E402

FORMATS = (".step", ".iges", ".brep")

CASES = {
    "torus": "(x^2+y^2+z^2+3)^2-16*(x^2+y^2)",
    "paraboloid": "x^2+y^2-z",
    "two-sheets": "x^2+y^2-z^2+1",
    "ellipsoid-of-revolution": "4*x^2+4*y^2+z^2-4",
    "tilted-torus": "((x-1)^2+(y-2)^2+(z-3)^2+3)^2-16*((x-1)^2+(y-2)^2)",
    "cone": "x^2+y^2-(z-1)^2",
    "example-1": example_text("paper-example-1"),
    "dupin": example_text("dupin-cyclide"),
}


@pytest.fixture(scope="module")
def cases() -> dict[str, tuple[Analysis, SceneData]]:
    out = {}
    for name, text in CASES.items():
        analysis = analyze(text)
        out[name] = (analysis, build_scene(analysis))
    return out


def faces(shape: TopoDS_Shape) -> list[TopoDS_Face]:
    found = []
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        found.append(TopoDS.Face(explorer.Current()))
        explorer.Next()
    return found


def kinds(shape: TopoDS_Shape) -> set[str]:
    return {GeomAdaptor_Surface(BRep_Tool.Surface_s(f)).GetType().name for f in faces(shape)}


def sampled_distance(shape: TopoDS_Shape, polynomial: str, count: int = 1000) -> float:
    """The largest ``|f|/|∇f|`` at ``count`` points spread over the faces' parameter boxes."""
    terms = polynomial_terms(polynomial)
    found = faces(shape)
    side = math.ceil(math.sqrt(count / len(found)))
    worst = 0.0
    for face in found:
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        points = []
        for u in np.linspace(u0, u1, side):
            for v in np.linspace(v0, v1, side):
                p = surface.Value(float(u), float(v))
                points.append((p.X(), p.Y(), p.Z()))
        worst = max(worst, float(surface_distance(terms, np.array(points)).max()))
    return worst


def area(shape: TopoDS_Shape) -> float:
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props, 1e-12)
    return props.Mass()


def exported(tmp_path: Path, case: tuple[Analysis, SceneData], name: str) -> TopoDS_Shape:
    analysis, scene = case
    path = export_analysis(analysis, tmp_path / name, scene=scene)
    return read_shape(path)


@pytest.mark.parametrize("suffix", FORMATS)
def test_the_torus_is_an_analytic_torus_of_the_exact_area(tmp_path: Path, cases, suffix: str) -> None:
    shape = exported(tmp_path, cases["torus"], f"torus{suffix}")
    assert all(BRepCheck_Analyzer(f).IsValid() for f in faces(shape))
    revolution = GeomAbs_SurfaceType.GeomAbs_SurfaceOfRevolution.name
    expected = {GeomAbs_SurfaceType.GeomAbs_Torus.name} if suffix != ".iges" else {revolution}
    assert kinds(shape) == expected, "IGES faces have no torus entity: it is a surface of revolution (120)"
    assert area(shape) == pytest.approx(4 * math.pi**2 * 2 * 1, rel=1e-9)
    assert sampled_distance(shape, cases["torus"][0].recognition.polynomial) <= 1e-9 * cases["torus"][1].region.radius


@pytest.mark.parametrize("suffix", FORMATS)
@pytest.mark.parametrize(("name", "count"), [("paraboloid", 1), ("two-sheets", 2), ("ellipsoid-of-revolution", 1)])
def test_an_exact_profile_is_a_surface_of_revolution_on_the_surface(
    tmp_path: Path, cases, suffix: str, name: str, count: int
) -> None:
    analysis, scene = cases[name]
    shape = exported(tmp_path, cases[name], f"{name}{suffix}")
    assert len(faces(shape)) == count, "one face per real branch of the profile in the ball"
    assert all(BRepCheck_Analyzer(f).IsValid() for f in faces(shape))
    assert kinds(shape) == {GeomAbs_SurfaceType.GeomAbs_SurfaceOfRevolution.name}
    assert sampled_distance(shape, analysis.recognition.polynomial) <= 1e-9 * scene.region.radius


def test_the_analytic_kinds(tmp_path: Path, cases) -> None:
    cone = exported(tmp_path, cases["cone"], "cone.step")
    assert kinds(cone) == {GeomAbs_SurfaceType.GeomAbs_Cone.name} and len(faces(cone)) == 2
    tilted = exported(tmp_path, cases["tilted-torus"], "tilted.step")
    assert kinds(tilted) == {GeomAbs_SurfaceType.GeomAbs_Torus.name}
    for text, kind in [
        ("x^2+y^2-2", GeomAbs_SurfaceType.GeomAbs_Cylinder),
        ("x^2+y^2+(z-1)^2-4", GeomAbs_SurfaceType.GeomAbs_Sphere),
        ("x+2*y-3", GeomAbs_SurfaceType.GeomAbs_Plane),
    ]:
        analysis = analyze(text)
        scene = build_scene(analysis)
        shape = read_shape(export_analysis(analysis, tmp_path / "kind.step", scene=scene))
        assert kinds(shape) == {kind.name}, text
        assert sampled_distance(shape, analysis.recognition.polynomial) <= 1e-9 * scene.region.radius, text


@pytest.mark.parametrize("suffix", FORMATS)
def test_example_1_is_fitted_within_the_stated_tolerance(tmp_path: Path, cases, suffix: str) -> None:
    """genus(P) > 0: no rational profile, so a B-spline fitted within 1e-7 of the ball's radius."""
    analysis, scene = cases["example-1"]
    path = export_analysis(analysis, tmp_path / f"example-1{suffix}", scene=scene)
    shape = read_shape(path)
    assert all(BRepCheck_Analyzer(f).IsValid() for f in faces(shape))
    assert kinds(shape) == {GeomAbs_SurfaceType.GeomAbs_SurfaceOfRevolution.name}
    assert sampled_distance(shape, analysis.recognition.polynomial) <= 1e-7 * scene.region.radius
    if suffix == ".step":
        assert "measured deviation" in path.read_text(encoding="ascii")


def test_a_dupin_cyclide_is_written_as_its_rational_patch(tmp_path: Path, cases) -> None:
    analysis, scene = cases["dupin"]
    shape = exported(tmp_path, cases["dupin"], "dupin.patch.step")
    assert all(BRepCheck_Analyzer(f).IsValid() for f in faces(shape))
    assert kinds(shape) == {GeomAbs_SurfaceType.GeomAbs_BSplineSurface.name}
    assert sampled_distance(shape, analysis.recognition.polynomial) <= 1e-9 * scene.region.radius


def test_a_surface_that_is_not_of_revolution_is_refused_in_one_sentence(tmp_path: Path, cases) -> None:
    analysis, scene = cases["dupin"]
    with pytest.raises(ValueError, match="not a surface of revolution.*patch"):
        export_analysis(analysis, tmp_path / "dupin.step", scene=scene)
    assert not (tmp_path / "dupin.step").exists()


def test_sorgui_analyze_json_with_a_cad_file_prints_only_the_json(tmp_path: Path) -> None:
    """Open CASCADE's transfer statistics must not reach standard output, which carries the JSON."""
    import json
    import subprocess
    import sys

    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "sorgui.cli",
            "analyze",
            "--json",
            "x^2+y^2-z",
            "-o",
            str(tmp_path / "p.step"),
            "-o",
            str(tmp_path / "p.igs"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["is_sor"]
    assert read_shape(tmp_path / "p.step") is not None and read_shape(tmp_path / "p.igs") is not None
