"""Report files read back: JSON into equal result objects, Markdown and HTML with formulas and picture."""

from __future__ import annotations

import base64
import dataclasses
import json

import pytest

from sorgui.engine.results import Analysis, Approximation, report_json
from sorgui.export.files import export_analysis
from sorgui.export.formats import format_of
from sorgui.export.reports import ReportError, html_report, markdown_report, read_report

PNG = b"\x89PNG\r\n\x1a\n" + b"\x00" * 16
"""Stands for a picture (the reports only embed or copy the bytes)."""


@pytest.mark.parametrize("name", ["paper-example-1", "torus", "paper-cubic"])
def test_json_reloads_into_equal_result_objects(analyses, tmp_path, name: str) -> None:
    path = export_analysis(analyses[name], tmp_path / "report.json")
    assert read_report(path) == analyses[name]
    assert json.loads(path.read_text(encoding="utf-8")) == report_json(analyses[name])  # with its version


def test_approximate_results_are_kept_and_reported(analyses, tmp_path) -> None:
    approx = Approximation(
        tolerance=1e-6,
        tolerance_source="input",
        near_sor=True,
        kind="revolution",
        relative_distance=2e-7,
        residual=0.4,
        singular_values=(1.0, 0.5, 1e-8),
    )
    analysis = dataclasses.replace(analyses["torus"], approximate=approx)
    path = export_analysis(analysis, tmp_path / "rounded.json")
    assert read_report(path) == analysis
    text = markdown_report(analysis)
    assert "## Rounded input" in text and "exactly a surface of revolution, and within the tolerance" in text


def test_unknown_results_are_listed_not_lost(analyses) -> None:
    class Later(Analysis):
        def to_json(self):  # noqa: ANN202 - a result type added after this exporter
            return {**super().to_json(), "later": {"spine": "line", "radius": "1"}}

    analysis = Later(**{f.name: getattr(analyses["torus"], f.name) for f in dataclasses.fields(Analysis)})
    text = markdown_report(analysis)
    assert "## Further results" in text and '"spine": "line"' in text


def test_markdown_has_latex_formulas_and_the_picture_beside_it(analyses, tmp_path) -> None:
    path = export_analysis(analyses["torus"], tmp_path / "torus.md", picture=PNG)
    text = path.read_text(encoding="utf-8")
    assert text.startswith("# sorgui: a surface of revolution")
    assert "![The surface and its axis](torus.png)" in text
    assert (tmp_path / "torus.png").read_bytes() == PNG
    assert "$X_{1}(s, t) = " in text or "$$\nX_{1}(s, t) = " in text
    assert r"- parameter domain: $(s, t) \in \mathbb{R}^{2}$" in text
    assert "Table 1, row 1" in text


def test_html_is_one_file_with_the_picture_inside(analyses) -> None:
    text = html_report(analyses["paper-example-1"], PNG)
    assert text.startswith("<!DOCTYPE html>") and text.rstrip().endswith("</html>")
    assert 'src="data:image/png;base64,' + base64.b64encode(PNG).decode() + '"' in text
    assert '<span class="math">$(s, t) \\in \\mathbb{R}^{2}$</span>' in text
    assert "<script" not in text  # nothing fetched from elsewhere


def test_reports_without_a_picture(analyses, tmp_path) -> None:
    path = export_analysis(analyses["cone"], tmp_path / "cone.md")
    assert "![" not in path.read_text(encoding="utf-8")
    assert not (tmp_path / "cone.png").exists()


def test_bad_reports_are_refused_with_one_line(tmp_path) -> None:
    cases = {
        "missing.json": None,
        "text.json": "x^2 + y^2",
        "error.json": '{"error": {"message": "bad"}}',
        "other.json": '{"input": "x"}',
    }
    for name, content in cases.items():
        if content is not None:
            (tmp_path / name).write_text(content, encoding="utf-8")
        with pytest.raises(ReportError) as info:
            read_report(tmp_path / name)
        assert name in info.value.message and "\n" not in info.value.message


def test_format_names() -> None:
    assert format_of("a.STL").suffix == ".stl"
    assert format_of("a.dat", "patch.ply").suffix == ".ply"
    assert format_of("a", "md").kind == "report"
    with pytest.raises(ValueError, match="unknown export format"):
        format_of("a.docx")


def test_a_nearest_surface_outside_the_rounding_is_not_presented_as_the_part() -> None:
    """``x² + 1.000001y² + 0.999999z² − 2.5`` snaps to ``x² + y² + 871605/871606·z² − 5/2``, which
    lies outside the rounding of the input: the report says that no simple exact surface was found
    within it, and does not go on with that surface's analysis (it is in the JSON)."""
    import dataclasses

    from sorgui.engine import analyze
    from sorgui.export.text import plain_text

    analysis = analyze("x^2 + 1.000001y^2 + 0.999999z^2 - 2.5")
    approx = analysis.approximate
    assert approx is not None and approx.nearest is not None and not approx.nearest.within_rounding
    text = plain_text(analysis)
    assert "no simple exact surface was found within the rounding" in text
    assert "the analysis of the nearest exact surface" not in text
    inside = dataclasses.replace(
        analysis,
        approximate=dataclasses.replace(approx, nearest=dataclasses.replace(approx.nearest, within_rounding=True)),
    )
    assert "the analysis of the nearest exact surface" in plain_text(inside)


TURNED_CYLINDER_10_DIGITS = (
    "+1.000000000e+00*x^2 +7.500000000e-01*y^2 -8.660254038e-01*y*z +2.500000000e-01*z^2 "
    "+2.598076211e+00*y -1.500000000e+00*z -2.000000000e+00"
)
"""The cylinder of radius 2 about the z-axis turned by 30° about x and moved to (0, 0, 3)."""


def test_the_files_of_rounded_input_carry_the_nearest_exact_surface(tmp_path) -> None:
    """What was found is written, not only the verdict: the approximate axis and the nearest
    exact surface in every file's header, and ``g`` and its exact axis as formulas."""
    from sorgui.engine import analyze
    from sorgui.export.cas import latex_document, mathematica_file

    analysis = analyze(TURNED_CYLINDER_10_DIGITS)
    for text in (latex_document(analysis), mathematica_file(analysis), markdown_report(analysis)):
        assert "about the axis (0, -1.29903811, 0.75)" in text, text[:1500]
        assert "within the rounding" in text and "nearest exact surface" in text
    assert "nearestAxisDirection = {0, 1, 3^(1/2)};" in mathematica_file(analysis)
    assert "g = x^2 + (3/4)*y^2" in mathematica_file(analysis)
    assert "(revolution)" not in latex_document(analysis) and "cylinder_of_revolution" not in latex_document(analysis)


def test_the_headline_of_rounded_input_within_its_rounding_is_nearly_as_in_the_window() -> None:
    """Not exactly of revolution but within its rounding: every file says *nearly* first, as
    the window's banner does (the Markdown and HTML said "not a surface of revolution")."""
    from sorgui.engine import analyze
    from sorgui.export.reports import html_report
    from sorgui.export.text import text_report

    analysis = analyze(TURNED_CYLINDER_10_DIGITS)
    assert not analysis.is_sor and analysis.approximate is not None and analysis.approximate.near_sor
    assert markdown_report(analysis).startswith("# sorgui: nearly a surface of revolution (not exactly")
    html = html_report(analysis)
    assert "sorgui: nearly a surface of revolution" in html and "sorgui: not a surface of revolution" not in html
    assert "surface of revolution: NO exactly, but NEARLY: within the rounding" in text_report(analysis)


def test_an_exact_ellipsoid_nearly_a_sphere_is_not_called_exactly_a_sphere() -> None:
    from sorgui.engine import analyze
    from sorgui.export.text import text_report

    text = text_report(analyze("x^2 + 1.0001y^2 + z^2 - 1"))
    assert "exactly a surface of revolution; within the tolerance, nearly a sphere" in text
    assert "exactly a sphere" not in text


def test_a_residual_over_one_within_the_float_noise_is_not_said_to_be_at_most_one() -> None:
    """A cone printed with 17 digits is near a surface of revolution with a residual of 1.04
    roundings (floating point's own error in the fit excuses up to one more): the line said
    "(at most 1: within it)" beside 1.04."""
    from sorgui.engine import analyze
    from sorgui.export.text import text_report

    cone = (
        "(1)*x^2 + (-7)*x + (0.66000000000000014)*y^2 + (1.1777945491468365)*y*z + (-6.5945618440278562)*y"
        " + (-0.020000000000000073)*z^2 + (1.7522431864335473)*z + (1.9955476949651754)"
    )
    analysis = analyze(cone, recognition_only=True)
    assert analysis.approximate is not None and analysis.approximate.near_sor
    assert analysis.approximate.residual is not None and 1 < analysis.approximate.residual <= 2
    text = text_report(analysis)
    assert "(over 1, by less than floating point's own error in the fit: within it)" in text
    assert "at most 1: within it" not in text


def test_a_tolerance_given_is_named_in_the_headline() -> None:
    """With ``--tolerance`` the headline said "within the rounding of the input", whatever the
    digits: it names the tolerance given."""
    from sorgui.engine import analyze
    from sorgui.export.text import text_report

    given = text_report(analyze("x^2 + 1.0000001y^2 + 2z^2 - 1", recognition_only=True, tolerance=1e-6))
    assert "surface of revolution: NO exactly, but NEARLY: within the tolerance given (see below)" in given
    typed = text_report(analyze("x^2 + 1.0000001y^2 + 2z^2 - 1", recognition_only=True))
    assert "NEARLY: within the rounding of the input (see below)" in typed
