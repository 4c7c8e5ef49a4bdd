"""The geometry of CAD export without Open CASCADE: Bernstein forms, exact profiles, analytic kinds."""

from __future__ import annotations

import importlib.util
import math
import re
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sorgui import cli
from sorgui.cad import INSTALL_HINT
from sorgui.cad.geometry import (
    analytic_surfaces,
    axis_frame,
    bernstein,
    exact_profile,
    surface_distance,
)
from sorgui.engine import analyze
from sorgui.engine.values import polynomial_terms
from sorgui.session.scene_data import build_scene


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.integers(-20, 20), min_size=1, max_size=9),
    st.floats(-3, 3),
    st.floats(0.1, 3),
    st.floats(0, 1),
)
def test_the_bernstein_form_is_the_same_polynomial(
    coefficients: list[int], start: float, length: float, lam: float
) -> None:
    """``Σ b_k C(n,k) μ^(n-k) λ^k = F(μA + λB)`` on a segment of the projective line."""
    form = [mpmath.mpf(c) for c in coefficients]
    n = len(form) - 1
    A, B = (math.sin(start / 2), math.cos(start / 2)), (math.sin((start + length) / 2), math.cos((start + length) / 2))
    b = bernstein(form, A, B)
    mu = 1 - lam
    T, W = mu * A[0] + lam * B[0], mu * A[1] + lam * B[1]
    direct = sum(float(c) * T**i * W ** (n - i) for i, c in enumerate(form))
    via = sum(float(b[k]) * math.comb(n, k) * mu ** (n - k) * lam**k for k in range(n + 1))
    assert via == pytest.approx(direct, abs=1e-9 * max(1.0, sum(abs(c) for c in coefficients)))


@pytest.mark.parametrize(
    ("text", "arcs"),
    [("x^2+y^2-z", 1), ("x^2+y^2-z^2+1", 2), ("4*x^2+4*y^2+z^2-4", 1), ("9*x^2+9*y^2-(z-1)^2*(z+2)-4", None)],
)
def test_the_exact_profile_lies_on_the_surface_in_one_half_plane(text: str, arcs: int | None) -> None:
    analysis = analyze(text)
    scene = build_scene(analysis)
    assert analysis.recognition.profile is not None
    frame = axis_frame(analysis.recognition.profile)
    curves = exact_profile(analysis, frame, scene.region, scene.region.radius)
    if arcs is None:
        assert curves is None or all(len(c.poles) for c in curves)
        return
    assert curves is not None and len(curves) == arcs
    terms = polynomial_terms(analysis.recognition.polynomial)
    for curve in curves:
        assert np.all(curve.weights > 0)
        points = curve.points(50)
        assert surface_distance(terms, points).max() <= 1e-12 * scene.region.radius
        assert frame.to_plane(points)[:, 1].min() >= -1e-12, "the half-plane y >= 0"
        assert np.linalg.norm(points - scene.region.center, axis=1).max() <= scene.region.radius * (1 + 1e-9)


def test_the_analytic_kinds_are_read_from_the_exact_profile() -> None:
    cases = {
        "(x^2+y^2+z^2+21)^2-100*(x^2+y^2)": ("torus", 5.0, 2.0),
        "x^2+y^2-2": ("cylinder", math.sqrt(2), 0.0),
        "x^2+y^2-3*(z-1)^2": ("cone", 0.0, 0.0),
        "x^2+y^2+(z-1)^2-4": ("sphere", 2.0, 0.0),
        "x+2*y-3": ("plane", 0.0, 0.0),
        "x^2+y^2-z": (None, 0.0, 0.0),
        "(x^2+y^2+z^2-1)^2-4*(x^2+y^2)": ("torus", 1.0, math.sqrt(2.0)),  # a spindle torus: R < r
        "x^3+y^3+z^3-3*x*y*z-1": (None, 0.0, 0.0),  # P² = x·w − c: a cubic, not a quadric (it was "nan across")
    }
    for text, (kind, radius, minor) in cases.items():
        analysis = analyze(text)
        specs = analytic_surfaces(analysis, build_scene(analysis).region)
        spec = specs[0] if specs else None
        assert (spec.kind if spec else None) == kind, text
        if spec is not None and kind in ("torus", "cylinder", "sphere"):
            assert spec.radius == pytest.approx(radius, rel=1e-15) and spec.minor_radius == pytest.approx(
                minor, rel=1e-15
            )
        if spec is not None and kind == "cone":
            assert spec.semi_angle == pytest.approx(math.atan(math.sqrt(3)), rel=1e-15)
            assert np.allclose(spec.origin, [0, 0, 1])


@pytest.mark.parametrize(
    ("text", "kinds"),
    [
        ("(x^2+y^2-1)*(z-1)", ["cylinder", "plane"]),
        ("(x^2+y^2)^2 - 2*(x^2+y^2)*(z^2+1) + (z^2-1)^2", ["cone", "cone"]),  # (r² − (z+1)²)(r² − (z−1)²)
        ("(x^2+y^2+z^2-1)*(x^2+y^2-4)", ["cylinder", "sphere"]),
        ("(x^2+y^2-1)*(x^2+y^2-z^3)", None),  # a cubic factor: the exact or fitted profile
    ],
)
def test_a_reducible_surface_of_analytic_factors_is_their_union(text: str, kinds: list[str] | None) -> None:
    """A surface of revolution whose factors are each analytic is written as their analytic
    surfaces (its fitted profile strayed where they cross, and the STEP file was refused); its
    part is valid."""
    analysis = analyze(text)
    scene = build_scene(analysis)
    specs = analytic_surfaces(analysis, scene.region)
    assert (sorted(spec.kind for spec in specs) if specs is not None else None) == kinds
    if kinds is not None and importlib.util.find_spec("OCP") is not None:
        from OCP.BRepCheck import BRepCheck_Analyzer

        from sorgui.cad.model import surface_model

        model = surface_model(analysis, scene)
        assert model.route == "analytic" and BRepCheck_Analyzer(model.shape).IsValid()


@pytest.mark.parametrize(
    ("text", "parts", "faces"),
    [
        ("(x^2+y^2-z^4-1)*(2*z-1)", ["x^2+y^2-z^4-1", "2*z-1"], 2),  # a quartic and the plane across it
        ("(x^2+y^2-1)*(x^2+y^2-z^3)", ["x^2+y^2-1", "x^2+y^2-z^3"], 2),
        ("(x^2+y^2-z^4-1)*(x^2+y^2-z^3-2)", ["x^2+y^2-z^4-1", "x^2+y^2-z^3-2"], 2),
        ("(x^2+y^2-z^4-1)^2*(z-100)", ["x^2+y^2-z^4-1"], 1),  # the plane misses the ball
    ],
)
def test_a_reducible_surface_is_the_union_of_its_factors_parts(text: str, parts: list[str], faces: int) -> None:
    """A reducible surface of revolution with a factor that is not analytic: its fitted profile
    strayed where the factors cross, and the STEP file was refused. Each factor now gets its own
    route in the same ball; the part is valid and as large as the factors' parts together."""
    pytest.importorskip("OCP")
    from OCP.BRepCheck import BRepCheck_Analyzer

    from sorgui.cad.model import surface_model
    from tests.cad.readback import area

    analysis = analyze(text)
    scene = build_scene(analysis)
    model = surface_model(analysis, scene)
    assert BRepCheck_Analyzer(model.shape).IsValid() and model.faces == faces
    alone = 0.0
    for part in parts:
        own = analyze(part)
        alone += area(surface_model(own, build_scene(own, region=scene.region)).shape)
    assert area(model.shape) == pytest.approx(alone, rel=1e-4)


def test_without_open_cascade_the_command_line_says_how_to_install_it(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    real = cli.importlib.util.find_spec
    monkeypatch.setattr(cli.importlib.util, "find_spec", lambda name, *a: None if name == "OCP" else real(name, *a))
    with pytest.raises(cli.UsageError, match=re.escape(INSTALL_HINT)):
        cli.check_outputs([tmp_path / "part.step"], None)


def test_without_open_cascade_an_export_fails_in_one_line(tmp_path: Path) -> None:
    script = (
        "import sys; sys.modules['OCP'] = None\n"
        "from sorgui.engine import analyze\n"
        "from sorgui.session.scene_data import build_scene\n"
        "from sorgui.export.files import export_analysis\n"
        "a = analyze('x^2+y^2-z')\n"
        "try:\n"
        f"    export_analysis(a, {str(tmp_path / 'p.step')!r}, scene=build_scene(a))\n"
        "except ValueError as exc:\n"
        "    print(exc)\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert out.stdout.strip() == INSTALL_HINT, out.stderr
    assert not (tmp_path / "p.step").exists()


def test_the_command_line_lists_the_cad_formats_and_units() -> None:
    from sorgui.cad import CAD_SUFFIXES, UNITS
    from sorgui.export.formats import FORMATS

    assert cli.CAD_SUFFIXES == CAD_SUFFIXES == tuple(s for s, f in FORMATS.items() if f.kind == "cad")
    assert cli.CAD_UNITS == UNITS


def test_coefficients_beyond_the_range_of_floats_keep_their_zero_set() -> None:
    """A product with 300-digit coefficients: all floats scaled by one power of two, none infinite."""
    from sorgui.engine.values import polynomial_terms

    big = 10**400
    terms = dict(polynomial_terms(f"{big}*x^2 + {big}*y^2 - {3 * big}*z + 1"))
    assert all(math.isfinite(c) for c in terms.values())
    assert terms[(2, 0, 0)] == terms[(0, 2, 0)] and terms[(0, 0, 1)] == pytest.approx(-3 * terms[(2, 0, 0)], rel=1e-15)
    assert dict(polynomial_terms("2*x^2 - 1/3")) == {(2, 0, 0): 2.0, (0, 0, 0): -1 / 3}


def test_an_unfinished_analysis_is_not_called_a_surface_that_is_not_of_revolution() -> None:
    import dataclasses

    pytest.importorskip("OCP")
    from sorgui.cad.geometry import CadGeometryError
    from sorgui.cad.model import surface_model

    analysis = analyze("x^2+y^2-z")
    undecided = dataclasses.replace(
        analysis, recognition=dataclasses.replace(analysis.recognition, symmetry="undecided", is_sor=False)
    )
    with pytest.raises(CadGeometryError, match="did not finish"):
        surface_model(undecided, build_scene(analysis))


def test_a_map_whose_weights_vanish_on_a_drawn_arc_leaves_the_profile_to_the_fit() -> None:
    """A 6-digit hyperboloid of one sheet about (1, 1, 1), exactly of revolution as typed: its
    parameterization's denominator changes sign on an arc in the ball, so its arcs cannot be
    drawn exactly; the next map or the fitted profile makes the part (the export failed)."""
    pytest.importorskip("OCP")
    from OCP.BRepCheck import BRepCheck_Analyzer

    from sorgui.cad.model import surface_model

    text = (
        "+3.33333e-01*x^2 -1.33333e+00*x*y -1.33333e+00*x*z +3.33333e-01*y^2 -1.33333e+00*y*z "
        "+3.33333e-01*z^2 -1.00000e+00"
    )
    analysis = analyze(text)
    assert analysis.is_sor and analysis.parametrizations
    model = surface_model(analysis, build_scene(analysis))
    assert BRepCheck_Analyzer(model.shape).IsValid()


def test_a_typed_map_turning_along_its_second_parameter_gives_the_exact_profile() -> None:
    """The README's map turns about the axis along ``t`` (``z = s²``): its meridian is the curve
    ``t = 0``, and the part's profile is that exact rational curve, not a fit (it is the only map
    listed: the rotated profile's is the typed one again, docs/math.md §6)."""
    pytest.importorskip("OCP")
    from OCP.BRepCheck import BRepCheck_Analyzer

    from sorgui.cad.model import surface_model

    analysis = analyze("x = (1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s^2")
    assert [p.method for p in analysis.parametrizations] == ["the given parametrization"]
    model = surface_model(analysis, build_scene(analysis))
    assert model.route == "exact"
    assert BRepCheck_Analyzer(model.shape).IsValid()


def test_a_rounded_map_near_a_surface_of_revolution_says_why_it_has_no_part() -> None:
    """Not "no exact surface with a rational or quadratic axis was found within its rounding":
    for a typed map none is looked for."""
    pytest.importorskip("OCP")
    from sorgui.cad.model import surface_model

    analysis = analyze("x = 2*s/(1+s^2+t^2), y = 2.000001*t/(1+s^2+t^2), z = 1.5*(s^2+t^2-1)/(1+s^2+t^2)")
    assert analysis.approximate is not None and analysis.approximate.near_sor and not analysis.is_sor
    with pytest.raises(ValueError, match="no nearest exact surface is computed for a parametrization"):
        surface_model(analysis, build_scene(analysis))


def test_a_rounded_cone_s_patch_is_written_without_float_warnings(tmp_path: Path) -> None:
    """Its map's normals at the far corners of a wide parameter box overflow floating point;
    they printed numpy's RuntimeWarnings on standard error (errors under the suite's filter)."""
    pytest.importorskip("OCP")
    from sorgui.export.files import export_analysis

    text = (
        "(0.92133)*x^2 + (0.1868)*x*y + (-0.577667)*x*z + (-1.0516)*x + (0.889112)*y^2 + (0.68583)*y*z"
        " + (-0.438328)*y + (-0.0604417)*z^2 + (1.4849)*z + (-1.02902)"
    )
    analysis = analyze(text)
    assert export_analysis(analysis, tmp_path / "cone.patch.step", scene=build_scene(analysis)).stat().st_size


def test_the_default_ball_holds_every_bounded_factor() -> None:
    """A torus about a thin coaxial cylinder: the cylinder's many near points made the torus's
    look like far branches, and the ball, the picture and the CAD file held the cylinder alone."""
    analysis = analyze("((x^2+y^2+z^2+8)^2-36*(x^2+y^2))*(4*x^2+4*y^2-1)")
    scene = build_scene(analysis)
    assert scene.region.radius >= 4
    radial = np.hypot(scene.surface.points[:, 0], scene.surface.points[:, 1])
    assert radial.max() > 3.9 and radial.min() < 0.6  # the torus's outer equator and the cylinder


def test_a_ball_through_a_torus_s_tube_gives_a_valid_part() -> None:
    """Open CASCADE's Boolean of the analytic torus with a ball through its tube left a part
    that failed its own check, and no file was written; the exact profile cut to the ball's disk
    and turned is valid."""
    pytest.importorskip("OCP")
    from OCP.BRepCheck import BRepCheck_Analyzer

    from sorgui.cad.model import surface_model
    from tests.cad.readback import Surface, part_to_surface

    analysis = analyze(  # a torus about a turned axis, rational coefficients
        "x^4 - 26*x^3/5 + 2*x^2*y^2 + 14*x^2*y/5 + 2*x^2*z^2 - 42*x^2*z/5 + 38693*x^2/8450 - 26*x*y^2/5"
        " - 125958*x*y/4225 - 26*x*z^2/5 + 9898*x*z/325 - 1191223*x/42250 + y^4 + 14*y^3/5 + 2*y^2*z^2"
        " - 42*y^2*z/5 + 190133*y^2/8450 + 14*y*z^2/5 - 10622*y*z/325 + 4308997*y/42250 + z^4 - 42*z^3/5"
        " + 741*z^2/50 - 45507*z/3250 + 150911089/1690000"
    )
    scene = build_scene(analysis, radius=2.5)
    model = surface_model(analysis, scene)
    assert BRepCheck_Analyzer(model.shape).IsValid() and model.faces >= 1
    assert part_to_surface(model.shape, Surface(analysis.squarefree, scene.region.center), 2.5, 500) <= 1e-9


def test_a_rounded_cylinder_over_a_curve_says_it_is_nearly_one() -> None:
    """An elliptic cylinder printed with 6 digits is "nearly a cylinder" in the report; its CAD
    file's refusal said it was "not ... a cylinder or cone over a rational curve"."""
    pytest.importorskip("OCP")
    from sorgui.cad.model import surface_model

    analysis = analyze(
        "(0.936361)*x^2 + (0.15111)*x*y + (-0.461211)*x*z + (-1.36022)*x + (0.910298)*y^2 + (0.547569)*y*z"
        " + (-0.071919)*y + (0.151344)*z^2 + (0.347228)*z + (-1.75562)"
    )
    assert analysis.conical is not None and analysis.conical.near_direction is not None
    with pytest.raises(ValueError, match="nearly a cylinder over a curve, not exactly one"):
        surface_model(analysis, build_scene(analysis))


ROUNDED_CONE = (
    "+1.76768e+01 +1.06327e+00*z +7.62636e-03*z^2 +2.32155e-01*y -2.04920e+00*y*z -5.78760e-02*y^2"
    " -1.85815e+01*x +3.42184e+00*x*z +3.53297e+00*x*y -1.94975e+00*x^2"
)
"""The cone ``r = 2h`` turned by a random rotation, its apex at about (2.16, 4.15, 3.60), printed
with 6 significant digits (``sorgui.samples.printed``)."""


def test_a_rounded_cone_s_typed_deviation_is_its_distance_from_the_typed_surface() -> None:
    """The typed quadric is ``(p − c)ᵀA(p − c) + f(c)`` about its centre ``c``, within 10⁻⁶ of the
    exact cone's apex: a hyperboloid whose distance from ``c`` is ``√(|f(c)|/|λ|)`` (``λ`` the
    eigenvalue of ``A`` of largest size and the sign opposite to ``f(c)``), 0.0025 here (the
    square root of the rounding: the apex is where it moves the zero set most). No point of the
    part is farther from it (at most 1% more is allowed). The first-order distance ``|f|/|∇f|``
    is ``10¹⁰`` at ``c`` and gave 0.18 from a sample 2e-5 from the apex. A typed surface that
    really is elsewhere is measured as far as it is: the exact cone shifted 0.05 along its axis
    lies ``0.05·sin(atan 2) = 0.0447`` from the part, and one with no real points at all (no foot
    settles, the first-order distance is kept) more than 1."""
    pytest.importorskip("OCP")
    import sympy

    from sorgui.cad.model import surface_model
    from sorgui.cad.nearest import foot_distances, typed_deviation
    from sorgui.engine.values import float_vector
    from sorgui.render.sampling import evaluate_points, first_order_distance

    analysis = analyze(ROUNDED_CONE)
    nearest = analysis.approximate.nearest if analysis.approximate else None
    assert nearest is not None and nearest.within_rounding and nearest.analysis is not None
    scene = build_scene(analysis)
    model = surface_model(analysis, scene)
    terms = polynomial_terms(analysis.squarefree)
    quadratic, linear = np.zeros((3, 3)), np.zeros(3)
    for exponents, c in terms:
        variables = [v for v in range(3) for _ in range(exponents[v])]
        if len(variables) == 2:
            quadratic[variables[0], variables[1]] += c / 2
            quadratic[variables[1], variables[0]] += c / 2
        elif len(variables) == 1:
            linear[variables[0]] += c
    centre = np.linalg.solve(quadratic, -linear / 2)
    value = evaluate_points(terms, centre[None])[0]
    eigenvalues = np.linalg.eigvalsh(quadratic)
    gap = math.sqrt(abs(value) / np.abs(eigenvalues[np.sign(eigenvalues) == -np.sign(value)]).max())
    assert 0.002 < gap < 0.003
    assert foot_distances(terms, centre[None], scene.region.radius)[0] == pytest.approx(gap, rel=1e-6)
    assert first_order_distance(terms, centre[None])[0] > 1e6 * gap
    assert model.typed_deviation is not None and model.typed_deviation <= 1.01 * gap

    axis = float_vector(nearest.analysis.recognition.axis.direction)
    axis /= np.linalg.norm(axis)
    x, y, z = sympy.symbols("x y z")
    shift = dict(zip((x, y, z), (x - 0.05 * axis[0], y - 0.05 * axis[1], z - 0.05 * axis[2])))
    shifted = sympy.expand(sympy.sympify(nearest.polynomial).subs(shift, simultaneous=True))
    assert typed_deviation(model.shape, str(shifted), scene) == pytest.approx(0.05 * 2 / math.sqrt(5), rel=0.01)
    assert typed_deviation(model.shape, "x^2 + y^2 + z^2 + 1", scene) > 1
