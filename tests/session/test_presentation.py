"""What the worker process prepares for the GUI, without Qt: exact strings read back,
typeset formulas, the scene's plain arrays, and the job protocol."""

from __future__ import annotations

import pickle
import subprocess
import sys
import threading

import numpy as np
import pytest
import sympy

from sorgui.engine.rounded import dense
from sorgui.engine.values import (
    ExpressionError,
    float_vector,
    polynomial_terms,
    rational_function_terms,
    read_expression,
)
from sorgui.examples import example_text
from sorgui.export.formulas import catalogue
from sorgui.numerics import real_roots
from sorgui.session.formulas import expression_formula, line_formula, pane_formulas, vector_formula
from sorgui.session.job import JobRequest, run_job
from sorgui.session.messages import Failed, Finished, Invalid, JobCancelled
from sorgui.session.scene_data import view_region
from sorgui.session.typesetting import PAD, Style, render

s, t = sympy.symbols("s t")


def test_reader_builds_exact_expressions_without_eval() -> None:
    assert read_expression("-sqrt(2)/2 + 3/5") == -sympy.sqrt(2) / 2 + sympy.Rational(3, 5)
    assert read_expression("(t**2 - 1)/(t**2 + 1)") == (t**2 - 1) / (t**2 + 1)
    assert read_expression("2*I*s^3") == 2 * sympy.I * s**3
    assert float_vector(("3/5", "-4/5", "0")) == pytest.approx([0.6, -0.8, 0.0])
    for bad in ("__import__('os')", "x.real", "1 +", "sqrt", "x; y", "lambda: 1"):
        with pytest.raises(ExpressionError):
            read_expression(bad)


def test_terms_from_engine_strings() -> None:
    assert sorted(polynomial_terms("x**2/2 - sqrt(2)*y*z")) == sorted([((2, 0, 0), 0.5), ((0, 1, 1), -np.sqrt(2))])
    assert sorted(polynomial_terms("3*s**2*r - r", ("s", "r"))) == [((0, 1), -1.0), ((2, 1), 3.0)]
    numerator, denominator = rational_function_terms("2*s/(s**2 + t**2 + 1)", ("s", "t"))
    assert numerator == [((1, 0), 2.0)]
    assert sorted(denominator) == [((0, 0), 1.0), ((0, 2), 1.0), ((2, 0), 1.0)]


def test_formulas_wrap_to_the_width_and_keep_exact_plain_text() -> None:
    text = " + ".join(f"{k}*x**{k}" for k in range(1, 30))
    formula = expression_formula(text, "f =")
    assert formula.plain == text and formula.text.startswith("f = x + 2x² + 3x³")
    lines, masks = render(formula.pieces, Style(width=300))
    assert len(lines) > 3
    assert lines[0].startswith("f = ") and lines[1].startswith(r"\qquad")
    assert "".join(lines).replace(r"\qquad", "") == "".join(formula.pieces)
    assert all(m.dtype == np.uint8 and m.ndim == 2 for m in masks)
    assert max(m.shape[1] for m in masks) < 300 + 200  # one piece may overhang
    wide, _masks = render(expression_formula(text).pieces, Style(width=5000))
    assert len(wide) == 1
    vector = vector_formula(("3/5", "-sqrt(2)", "0"))
    assert vector.text == "(3/5, −√2, 0)"
    assert vector.pieces == (r"\left(3/5, \right.", r"-\sqrt{2}, ", r"\left.0\right)")  # each piece balanced
    assert vector.code("LaTeX") == r"\left(3 / 5, - \sqrt{2}, 0\right)"
    assert vector_formula(("1", "2")).pieces == ("(1, ", "2)")


def test_a_line_of_long_numbers_wraps_between_its_entries() -> None:
    """The exact axis of a rounded cylinder (25-digit directions) scrolled sideways in the pane:
    the line wraps between the entries of its point and its direction, shortened or not."""
    point = ("52927/28073", "-1528367/54860", "-41935/52623")
    direction = ("1034595518194622955967539", "50599067836203377800736", "678758058548794637421372")
    formula = line_formula(point, direction)
    assert formula.shortened  # 1.034595518…×10²⁴
    lines, masks = render(formula.pieces, Style(width=300))
    assert len(lines) > 2, lines
    assert max(m.shape[1] for m in masks) <= 300 + sum(PAD[1]), lines


@pytest.mark.parametrize(
    "text",
    [
        "x**4 + 2*x**2*y**2 - 10*y**2 + 9",
        "-x**3 + 3*x/2 - sqrt(2)*y",
        "-(t**2 - 1)/(t**2 + 1) + 3",
        "x**2/3 - y/7 - 1",
        "-x - y",
        "2*s**2*r - r + sqrt(5)/2",
        "-2*x*z + y**2",
        "-7/3",
        "(x - 1)**2*y",
        "-x**4 + 26*x**2*y**2 - 104*x**2 + 12*x*y**4 - 48*x*y**2 + y**6 - 29*y**4 + 200*y**2 - 400",
    ],
)
def test_the_latex_copied_is_sympys_and_the_text_shown_reads_the_same(text: str) -> None:
    """Copy as LaTeX gives sympy's LaTeX (the exported files' own); the Unicode shown and the
    LaTeX typeset are printed without sympy, and read back to the same expression."""
    formula = expression_formula(text, "f =")
    assert formula.code("LaTeX") == sympy.latex(read_expression(text), fold_short_frac=True)
    assert formula.text.startswith("f = ") and "**" not in formula.text
    written = formula.text[4:].replace("−", "-").replace("√", "sqrt").replace("·", "*")
    for digit, sup in zip("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹"):
        written = written.replace(sup, "^" + digit)
    from sorgui.engine.parsing import parse_polynomial

    if any(v in text for v in "xyz") and "t" not in text:  # the editor's parser reads polynomials in x, y, z
        shown = parse_polynomial(written.replace("sqrt5", "sqrt(5)").replace("sqrt2", "sqrt(2)")).polynomial
        assert shown == parse_polynomial(text).polynomial


def test_long_numbers_are_shown_short_and_rounded_inputs_in_decimals() -> None:
    """``7.914…×10³⁸`` for a 39-digit integer; rounded input's coefficients in decimals, as typed;
    the exact digits on "exact digits" and on Copy."""
    big = "7914" + "0" * 34 + "1"
    formula = expression_formula(f"{big}*x**2 - 3/5")
    assert formula.text == "7.914…×10³⁸·x² − 3/5" and formula.shortened
    assert formula.exact_text() == f"{big}x² − 3/5" and formula.plain == f"{big}*x**2 - 3/5"
    rounded = expression_formula("1244852143/250000000*x**2 - 386/25*z + 1/3", mode="decimal")
    assert rounded.text == "4.979408572x² − 15.44z + 0.3333333333…"
    assert rounded.pieces[0] == r"4.979408572 x^{2}"


def test_every_formula_typesets_or_is_kept_as_text() -> None:
    """The typesetting process' answer: the lines and masks of a formula, none (and no error)
    for LaTeX that mathtext rejects."""
    from sorgui.session.typesetting import typeset

    style = Style(width=260, size=10.5)
    good = typeset(expression_formula(" + ".join(f"{j}*x**{j}*y" for j in range(1, 12)), "f =").pieces, style)
    assert len(good.lines) > 1 and len(good.masks) == len(good.lines)
    bad = typeset((r"\frac{", "x"), style)
    assert bad.masks == () and bad.lines == ()


def test_the_factor_of_a_power_has_its_formulas() -> None:
    """``(x² + y² + z² − 1)²`` is listed with its one factor and that factor's centre (the pane
    showed the keys ``factor.0`` and ``factor.0.center`` as text)."""
    from sorgui.engine import analyze

    shown = pane_formulas(analyze("(x^2 + y^2 + z^2 - 1)^2"))
    assert shown["factor.0"].plain == "x**2 + y**2 + z**2 - 1" and shown["factor.0.center"].vector


def test_a_line_wider_than_the_pane_wraps_before_its_direction() -> None:
    """The axis ``c + t·a`` of rounded input (decimals) or of a large exact line: two lines in a
    narrow pane, the second starting ``+ t``; one line when it fits."""
    from sorgui.session.formulas import decimal_line_formula, line_formula
    from sorgui.session.typesetting import CONTINUATION

    decimal = decimal_line_formula((0.633333, -0.533333, 0.866667), (-0.436436, -0.872872, -0.218218))
    exact = line_formula(("3/10", "-6/5", "7/10"), ("123456789/1000", "4", "1"))
    for formula in (decimal, exact):
        assert sum(piece.startswith(r" + t\,") for piece in formula.pieces) == 1
        lines, masks = render(formula.pieces, Style(width=200, size=10.5))
        assert len(lines) == len(masks) == 2 and lines[1].startswith(CONTINUATION + r" + t\,")
        assert len(render(formula.pieces, Style(width=2000, size=10.5))[0]) == 1
    assert decimal.latex == "".join(decimal.pieces) and decimal.text.startswith("(0.633333, -0.533333, 0.866667) + t·(")


def test_the_pane_shows_the_catalogues_formulas_and_reads_them_without_sympy(monkeypatch) -> None:
    """The pane's formulas are those of the export catalogue with a key (a vector with rows one
    per entry), printed without reading any string with sympy's reader."""
    from sorgui.engine import analyze

    analysis = analyze(example_text("torus"))
    keys = []
    for formula in catalogue(analysis):
        if formula.key:
            keys += [f"{formula.key}.{suffix}" for suffix, _label in formula.rows] or [formula.key]

    def unread(text: str) -> None:
        raise AssertionError(f"read {text!r}")

    monkeypatch.setattr("sorgui.engine.values.read_expression", unread)
    shown = pane_formulas(analysis)
    assert list(shown) == keys
    assert shown["polynomial"].pieces[0].startswith("f = ") and shown["canal.0.spine"].vector
    assert shown["parametrization.0.x"].source == analysis.parametrizations[0].coordinates[:1]
    assert shown["polynomial"].text == "f = x⁴ + 2x²y² + 2x²z² + y⁴ + 2y²z² + z⁴ − 10x² − 10y² + 6z² + 9"


def test_view_region_frames_the_bounded_part() -> None:
    torus = polynomial_terms("(x^2 + y^2 + z^2 + 3)^2 - 16*(x^2 + y^2)")
    array = dense.from_terms({tuple(e): float(c) for e, c in torus}, 4)
    line = dense.restriction_to_line(array, np.zeros(3), np.array([1.0, 0.0, 0.0]))
    assert sorted(np.round(real_roots(line), 9)) == [-3.0, -1.0, 1.0, 3.0]
    region = view_region(torus, np.zeros(3), np.array([0.0, 0.0, 1.0]))
    assert region.center == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    assert 3.0 < region.radius < 4.5


def test_a_small_sphere_far_from_the_origin_is_framed_at_its_own_size() -> None:
    """A sphere of radius 1 mm about ``(10, 0, 0)``: the floor of the ball's radius, the part's
    size, was measured about the origin (10), clamped to 1, and the mesh of that ball had no
    point of the sphere ("no real points that can be drawn")."""
    terms = polynomial_terms("(x-10)^2+y^2+z^2-0.001^2")
    region = view_region(terms, np.array([10.0, 0.0, 0.0]))
    assert region.radius == pytest.approx(0.00125, rel=1e-6)


@pytest.mark.parametrize("text", ["(x-10^17)^2+y^2+z^2-1", "(x-10^12)^2+y^2+z^2-1/10^6"])
def test_a_part_too_small_for_its_distance_is_not_drawn_and_says_why(text: str) -> None:
    """About ``(10¹², 0, 0)`` a sphere of radius 10⁻³ was meshed as a flat disc 17 000 across;
    about ``(10¹⁷, 0, 0)`` the ball's bounds collapsed in floating point and the drawing stage
    failed with an internal error, which skipped every later stage of the window's run."""
    from sorgui.engine import analyze
    from sorgui.session.scene_data import build_scene

    scene = build_scene(analyze(text))
    assert scene.surface.is_empty
    assert scene.notes and "cannot be drawn in floating point" in scene.notes[0]


@pytest.mark.parametrize("radius", [0.5, 0.05])
def test_a_small_ball_on_a_large_part_far_from_the_origin_is_drawn(radius: float) -> None:
    """A ball of radius 0.5 on a torus of radii 250 and 40 centred a thousand from the origin was
    refused as beyond floating point (the spread of ``f`` in the ball was taken as ``r⁴``, not
    measured), and told to move the part nearer the origin; a box of 2 there meshed."""
    from sorgui.engine import analyze
    from sorgui.render.geometry import ClipSphere
    from sorgui.session.scene_data import build_scene

    torus = "((x-1000)^2+(y+200)^2+(z-50)^2+250^2-40^2)^2-4*250^2*((x-1000)^2+(y+200)^2)"
    scene = build_scene(
        analyze(torus, recognition_only=True), region=ClipSphere(np.array([1290.0, -200.0, 50.0]), radius)
    )
    assert not scene.surface.is_empty and not scene.notes


@pytest.mark.parametrize("scale", [1e-2, 1e-4])
def test_a_small_part_is_framed_at_its_own_size(scale: float) -> None:
    """A torus 4 cm across written in metres (``R = 0.03``, ``r = 0.01``) was drawn a speck in a
    ball of radius 2, and one of 0.4 mm not at all (the ball's radius was at least 1): the ball
    now fits the part, and its mesh has points."""
    from sorgui.engine import analyze
    from sorgui.session.scene_data import build_scene

    R2, r2 = (3 * scale) ** 2, scale**2
    torus = f"(x^2 + y^2 + z^2 + {R2!r} - {r2!r})^2 - 4*{R2!r}*(x^2 + y^2)"
    scene = build_scene(analyze(torus, recognition_only=True))
    assert 4 * scale < scene.region.radius < 6 * scale
    assert not scene.surface.is_empty


TURNED_CONE_APEX = np.array([10.0, -20.0, 5.0])


def turned_cone() -> str:
    """A CAD cone of 15° about :data:`TURNED_CONE_APEX`, on a turned axis, printed with 6 digits."""
    from tests.engine.test_rounded_quadrics import turned_cone as cone

    x, y, z = TURNED_CONE_APEX
    return cone(15.0, (17.0, 41.0), ".6g", (float(x), float(y), float(z)))


@pytest.mark.parametrize(
    ("equation", "rounded"),
    [
        ("(x - 30)^2 + (y - 40)^2 - (z - 1)^2/50", False),  # the apex next to the foot of the origin
        ("x^2 + y^2 - (z - 50)^2/9", False),
        (None, True),  # a cone about (10, -20, 5) on a turned axis, printed with 6 digits
    ],
)
def test_a_cone_is_drawn_about_its_apex(equation: str | None, rounded: bool) -> None:
    """The lines through the foot of the origin on a cone's axis see no size when the apex is
    next to that foot (a ball of radius 1, and 3 units² of cone in the CAD part), and leave the
    apex out when it is far: the ball holds the apex and the ball about it of half its distance
    from the origin."""
    from sorgui.engine import analyze
    from sorgui.session.scene_data import build_scene

    apex = None
    if rounded:
        apex, equation = TURNED_CONE_APEX, turned_cone()
    assert equation is not None
    analysis = analyze(equation)
    conical = analysis.conical
    assert conical is not None
    if apex is None:
        assert conical.kind == "cone" and conical.apex is not None
        apex = float_vector(conical.apex)
    else:
        assert conical.near_apex == pytest.approx(apex, abs=1e-3)
    region = build_scene(analysis, resolution=30).region
    held = 0.5 * float(np.linalg.norm(apex))
    assert float(np.linalg.norm(np.asarray(region.center) - apex)) + held <= region.radius + 1e-3


def test_the_window_draws_a_rounded_cone_again_once_its_apex_is_known() -> None:
    """The window's first scene of rounded input is drawn once the rounding is known, before the
    cone stage: a turned CAD cone's ball about the foot of the origin on its axis left the apex
    out. Once the apex is known, the scene is drawn again in a ball that holds it."""
    final = run_job(JobRequest(turned_cone(), resolution=30))
    assert isinstance(final, Finished)
    region = final.result.scene.region
    assert final.result.analysis.conical.near_apex == pytest.approx(TURNED_CONE_APEX, abs=1e-3)
    assert float(np.linalg.norm(np.asarray(region.center) - TURNED_CONE_APEX)) < region.radius
    assert final.result.nearest_scene.region == region  # the nearest exact cone, in the same ball


def test_job_returns_plain_picklable_data() -> None:
    final = run_job(JobRequest(example_text("cylinder"), resolution=40))
    assert isinstance(final, Finished)
    result = final.result
    blob = pickle.loads(pickle.dumps(result))
    assert blob.analysis.recognition.symmetry == "cylinder_of_revolution"
    assert not blob.scene.surface.is_empty and not blob.scene.axis_segment.is_empty
    assert [name for name, _ in blob.timings][:1] == ["scene"]


def test_job_reports_errors_as_messages() -> None:
    invalid = run_job(JobRequest("x^2+*y"))
    assert isinstance(invalid, Invalid) and invalid.position == 4 and invalid.end > invalid.position
    assert invalid.message
    cancel = threading.Event()
    cancel.set()
    assert run_job(JobRequest(example_text("torus")), cancel) == JobCancelled()
    failed = run_job(JobRequest("x", analysis="not an analysis"))  # type: ignore[arg-type]
    assert isinstance(failed, Failed) and failed.message.startswith("internal error")
    assert "Traceback" not in failed.message


def test_worker_process_imports_no_qt() -> None:
    """The worker process (sorgui.session.job) must start without PySide6: it would only slow it."""
    code = (
        "import sys, sorgui.session.job; "
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('PySide6', 'pyvistaqt', 'shiboken6')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_a_rounded_surface_is_drawn_in_the_ball_about_its_approximate_axis() -> None:
    """Rounded input has no exact axis: its view ball is found about the approximate axis, the
    same ball as the exact surface it rounds (an origin-centred probe can leave parts out)."""
    import math

    from sorgui.engine import analyze
    from sorgui.samples import printed
    from sorgui.session.scene_data import natural_center, view_region
    from tests.engine.test_approximate import _turned_torus

    array, direction, point = _turned_torus()
    rounded = analyze(printed(array, 10), recognition_only=True)
    assert rounded.recognition.axis is None and rounded.approximate.axis is not None
    center, axis = natural_center(rounded.recognition, rounded.approximate)
    assert axis is not None and abs(abs(float(np.dot(axis, direction))) - 1) < 1e-8
    exact_center = point - float(np.dot(point, direction)) * direction  # the foot of the origin on the axis
    assert np.linalg.norm(center - exact_center) < 1e-6
    terms = polynomial_terms(rounded.squarefree)  # the exact rationals the engine read off the decimals
    ball = view_region(terms, center, axis)
    exact = view_region(terms, exact_center, direction)
    assert math.isclose(ball.radius, exact.radius, rel_tol=1e-6)


def test_the_status_summary_shows_no_rounding_noise() -> None:
    """The drawn ball's centre of a torus about the origin, computed in floats, is ``(0, 0, 0)``."""
    from dataclasses import replace

    from sorgui.engine import analyze
    from sorgui.render import ClipSphere
    from sorgui.session.scene_data import build_scene

    scene = build_scene(analyze(example_text("torus")), resolution=20)
    noisy = replace(scene, region=ClipSphere((1.11e-16, 1.67e-16, -5.55e-17), 3.75))
    assert noisy.summary().endswith("in a ball of radius 3.75 about (0, 0, 0)")


@pytest.mark.parametrize(
    ("text", "point", "gradient"),
    [
        # Decimals: the square-free part is the typed f times 2·10⁴.
        ("0.5*x^2 + 0.5*y^2 - 1.5e-3*z - 0.5", (1.0, 0.0, 0.0), (1.0, 0.0, -1.5e-3)),
        # A multiple: the square-free part is 9x² + 4y² + 36z² − 36.
        ("x^2/4 + y^2/9 + z^2 - 1", (2.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
    ],
)
def test_a_pick_reports_the_gradient_of_the_equation_as_typed(
    text: str, point: tuple[float, float, float], gradient: tuple[float, float, float]
) -> None:
    """The pick's ``f(p)`` and ``∇f(p)`` are those of what the user typed, not of the integer
    square-free part the surface is drawn from (10¹⁰ times larger for 10-digit decimals)."""
    from sorgui.engine import analyze
    from sorgui.render.picking import pick_info
    from sorgui.session.scene_data import build_scene

    scene = build_scene(analyze(text), resolution=20)
    info = pick_info(scene.terms, point, axis=scene.axis, typed_terms=scene.typed_terms)
    assert np.allclose(info.gradient, gradient, rtol=1e-12, atol=1e-15)
    assert info.value == pytest.approx(0.0, abs=1e-15)
    assert f"∇f = ({gradient[0]:.3g}, {gradient[1]:.3g}, {gradient[2]:.3g})" in info.summary()


def test_a_rounded_cylinder_is_drawn_in_the_ball_of_its_nearest_exact_surface() -> None:
    """Printed with 6 digits a cylinder of radius 1 is an ellipsoid 1,500 times longer than wide:
    its own ball (radius 1,862) left the mesh a few triangles and the CAD part 370 units past the
    typed surface. The ball of the nearest exact cylinder is drawn instead."""
    from pathlib import Path

    from sorgui.engine import analyze
    from sorgui.session.scene_data import build_scene

    text = (Path(__file__).resolve().parent.parent / "data" / "rounded-cylinder-6-digits.txt").read_text()
    scene = build_scene(analyze(text), resolution=40)
    assert scene.region.radius < 10 and scene.surface.n_faces > 1000


def test_a_sphere_without_real_points_draws_no_centre() -> None:
    """``x² + y² + z² + 1`` drew a lone red dot at its centre, which is not a point of it; the
    point sphere ``x² + y² + z² = 0`` is its centre, and draws it."""
    from sorgui.engine import analyze
    from sorgui.session.scene_data import build_scene

    assert build_scene(analyze("x^2+y^2+z^2+1")).center_marker is None
    assert build_scene(analyze("x^2+y^2+z^2")).center_marker is not None


def test_the_view_ball_of_a_sphere_is_centred_on_its_exact_centre() -> None:
    """The ball's middle came out 4e-16 off the sphere's centre, and the sphere's CAD part in a
    ball of its own radius (``--region=2``) was cut into 2 faces, with ``0,0,0,2`` 1."""
    from sorgui.engine import analyze
    from sorgui.session.scene_data import build_scene

    assert build_scene(analyze("x^2+y^2+z^2-4")).region.center == (0.0, 0.0, 0.0)
    assert build_scene(analyze("(x^2+y^2+z^2+3)^2-16(x^2+y^2)")).region.center == (0.0, 0.0, 0.0)


def test_the_status_bar_places_a_small_region_far_from_the_origin_to_its_own_scale() -> None:
    """A box from 1289 to 1291 was said "(1.29e+03, -201, 49) to (1.29e+03, -199, 51)"."""
    from sorgui.session.scene import digits_at_scale

    assert digits_at_scale([1289, -201, 49, 1291, -199, 51], 2) == 6
    assert f"{1289:.{digits_at_scale([1289, 1291], 2)}g}" == "1289"
    assert digits_at_scale([0.5, 0.2], 2) == 3 and digits_at_scale([1e6], 1e-6) == 12


@pytest.mark.parametrize("text", ["x^2+y^2-20000^2", "x^2+y^2-100000*z", "x^2+y^2-z^2-10000^2"])
def test_a_large_unbounded_part_is_drawn_in_a_ball_of_its_size(text: str) -> None:
    """A cylinder of radius 20,000 (and a paraboloid, a hyperboloid of that size) had the ball of
    radius 10,000 that every unbounded surface was capped at: none of it inside, no file."""
    from sorgui.engine import analyze
    from sorgui.session.scene_data import build_scene

    scene = build_scene(analyze(text, recognition_only=True))
    assert not scene.surface.is_empty and scene.region.radius > 10_000
