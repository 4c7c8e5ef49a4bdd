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
from sorgui.session.formulas import (
    Style,
    expression_formula,
    pane_formulas,
    render_formulas,
    vector_formula,
)
from sorgui.session.job import JobRequest, run_job
from sorgui.session.messages import Failed, Finished, Invalid, JobCancelled
from sorgui.session.scene_data import view_region

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
    narrow = render_formulas({"f": expression_formula(text, "f =")}, Style(width=300))["f"]
    assert narrow.plain == text and len(narrow.lines) > 3
    assert narrow.lines[0].startswith("f = ") and narrow.lines[1].startswith(r"\qquad")
    assert "".join(narrow.lines).replace(r"\qquad", "") == "".join(narrow.pieces)
    assert all(m.dtype == np.uint8 and m.ndim == 2 for m in narrow.masks)
    assert max(m.shape[1] for m in narrow.masks) < 300 + 200  # one piece may overhang
    wide = render_formulas({"f": expression_formula(text)}, Style(width=5000))["f"]
    assert len(wide.lines) == 1
    vector = vector_formula(("3/5", "-sqrt(2)", "0"))
    assert vector.latex == r"\left(3 / 5, - \sqrt{2}, 0\right)"


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
def test_a_sums_latex_is_sympys(text: str) -> None:
    """The LaTeX copied is sympy's own, also where it is put together from the pieces."""
    assert expression_formula(text, "f =").latex == sympy.latex(read_expression(text), fold_short_frac=True)


def test_a_forked_helper_typesets_the_same_pixels() -> None:
    """The worker shares the parsing with a forked helper: same masks as one process alone."""
    from sorgui.session import formulas

    texts = {
        f"f{k}": expression_formula(" + ".join(f"{k + j}*x**{j}*y" for j in range(1, 12)), "f =") for k in range(3)
    }
    texts["v"] = vector_formula(("3/5", "-sqrt(2)", "(t**2 - 1)/(t**2 + 1)"))
    style = Style(width=260, size=10.5)
    formulas._BOXES.clear()
    alone = render_formulas(texts, style, processes=1)
    formulas._BOXES.clear()
    shared = render_formulas(texts, style, processes=2)
    for key, formula in alone.items():
        assert formula.lines == shared[key].lines and len(formula.masks) == len(shared[key].masks) > 0
        assert all(np.array_equal(a, b) for a, b in zip(formula.masks, shared[key].masks))
    assert len(alone["f0"].lines) > 1  # wrapped: pieces set side by side on one baseline
    assert alone["v"].code("Maple") == "[3/5, -sqrt(2), (t^2 - 1)/(t^2 + 1)]"
    assert "x**2*y" in alone["f0"].code("Python") and "x^2*y" in alone["f0"].code("Maple")


def test_the_pane_shows_the_catalogues_formulas_and_plain_text_reads_none(monkeypatch) -> None:
    """The pane's formulas are those of the export catalogue with a key (a vector with rows one
    per entry), the same keys untypeset as ready to typeset; the untypeset ones read no string."""
    from sorgui.engine import analyze

    analysis = analyze(example_text("torus"))
    keys = []
    for formula in catalogue(analysis):
        if formula.key:
            keys += [f"{formula.key}.{suffix}" for suffix, _label in formula.rows] or [formula.key]
    exact = pane_formulas(analysis)
    assert exact["polynomial"].pieces[0].startswith("f = ") and exact["canal.0.spine"].vector
    assert exact["parametrization.0.x"].source == analysis.parametrizations[0].coordinates[:1]

    def unread(text: str) -> None:
        raise AssertionError(f"read {text!r}")

    monkeypatch.setattr("sorgui.export.formulas.read_expression", unread)
    monkeypatch.setattr("sorgui.session.formulas.read_expression", unread)
    plain = pane_formulas(analysis, plain=True)
    assert list(plain) == list(exact) == keys
    assert all(formula.plain == exact[key].plain for key, formula in plain.items())


def test_view_region_frames_the_bounded_part() -> None:
    torus = polynomial_terms("(x^2 + y^2 + z^2 + 3)^2 - 16*(x^2 + y^2)")
    array = dense.from_terms({tuple(e): float(c) for e, c in torus}, 4)
    line = dense.restriction_to_line(array, np.zeros(3), np.array([1.0, 0.0, 0.0]))
    assert sorted(np.round(real_roots(line), 9)) == [-3.0, -1.0, 1.0, 3.0]
    region = view_region(torus, np.zeros(3), np.array([0.0, 0.0, 1.0]))
    assert region.center == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    assert 3.0 < region.radius < 4.5


def test_job_returns_plain_picklable_data() -> None:
    final = run_job(JobRequest(example_text("cylinder"), resolution=40))
    assert isinstance(final, Finished)
    result = final.result
    blob = pickle.loads(pickle.dumps(result))
    assert blob.analysis.recognition.symmetry == "cylinder_of_revolution"
    assert not blob.scene.surface.is_empty and not blob.scene.axis_segment.is_empty
    assert all(f.masks for f in blob.formulas.values())
    assert [name for name, _ in blob.timings][:2] == ["scene", "formulas"]


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
