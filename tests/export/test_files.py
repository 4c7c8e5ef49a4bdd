"""Every export format through export_analysis and the command line, and the exact reader of engine strings."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import sympy

from sorgui.cli import main
from sorgui.engine import analyze
from sorgui.engine.results import Analysis
from sorgui.engine.values import read_expression
from sorgui.export.files import export_analysis
from sorgui.export.formats import FORMATS
from sorgui.export.formulas import analysis_formulas

x, y, s, t = sympy.symbols("x y s t")


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("-x**2 + y**2", -(x**2) + y**2),
        ("-2**2", sympy.Integer(-4)),
        ("2**-1*x", x / 2),
        ("x**2**3", x**8),
        ("(1 - s**2)/(s**2 + 1)", (1 - s**2) / (s**2 + 1)),
        ("-sqrt(2)/2 + I*t", -sympy.sqrt(2) / 2 + sympy.I * t),
    ],
)
def test_engine_strings_are_read_exactly(text: str, expected: sympy.Expr) -> None:
    assert sympy.simplify(read_expression(text) - expected) == 0


def test_formulas_are_the_exact_results() -> None:
    result = analyze("y^2 - 2xz")
    formulas = {f.name: f.value for f in analysis_formulas(result)}
    assert sympy.expand(formulas["p"] - (-(x**2) + y**2)) == 0 or sympy.expand(formulas["p"] - (x**2 - y**2)) == 0
    assert list(formulas["axisDirection"]) == [1, 0, 1]
    assert {"f", "P2", "T", "X1"} <= set(formulas)


@pytest.mark.parametrize("suffix", sorted(s for s, f in FORMATS.items() if not f.needs_scene))
def test_every_format_is_written(analyses, tmp_path, suffix: str) -> None:
    result = analyses["paper-example-1"]
    path = export_analysis(result, tmp_path / f"example{suffix}")
    text = path.read_text(encoding="utf-8")
    assert text.endswith("\n") and len(text) > 100
    if suffix == ".json":
        assert Analysis.from_json(json.loads(text)) == result
    if suffix == ".tex":
        assert text.startswith(r"\documentclass") and r"\end{document}" in text and "row 4" in text
        assert r"\usepackage{amssymb}" in text
    if suffix == ".mpl":
        assert "f := " in text and "T := " in text
    if suffix == ".m":
        assert "f = " in text and "(*" in text and "*)" in text


def test_unknown_format_is_refused(tmp_path) -> None:
    with pytest.raises(ValueError, match="unknown export format"):
        export_analysis(analyze("x^2 + y^2 - 1"), tmp_path / "out.docx")


def test_command_line_output_option(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    tex, mma = tmp_path / "cone.tex", tmp_path / "cone.m"
    assert main(["analyze", "-o", str(tex), "--output", str(mma), "y^2 - 2xz"]) == 0
    assert tex.exists() and mma.exists()
    capsys.readouterr()
    assert main(["analyze", "--json", "-o", str(tmp_path / "x.doc"), "y^2 - 2xz"]) == 2
    assert "unknown export format" in json.loads(capsys.readouterr().out)["error"]["message"]


def test_command_line_meshes_pictures_and_format_option(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    import pyvista

    outputs = [tmp_path / n for n in ("torus.stl", "torus.patch.obj", "torus.html", "torus.md", "torus.png")]
    arguments = [a for path in outputs for a in ("-o", str(path))]
    assert main(["analyze", *arguments, "(x^2 + y^2 + z^2 + 8)^2 - 36(x^2 + y^2)"]) == 0
    assert pyvista.read(outputs[0]).n_cells > 1000 and pyvista.read(outputs[1]).n_cells > 100
    assert 'src="data:image/png;base64,' in outputs[2].read_text(encoding="utf-8")
    assert (tmp_path / "torus.png").read_bytes().startswith(b"\x89PNG")
    assert main(["analyze", "--format", "py", "-o", str(tmp_path / "torus.txt"), "x^2 + y^2 - z^2 - 1"]) == 0
    assert "def X1(s, t):" in (tmp_path / "torus.txt").read_text(encoding="utf-8")
    capsys.readouterr()
    assert main(["analyze", "--format", "docx", "-o", str(tmp_path / "a.txt"), "x^2 + y^2 - 1"]) == 2
    assert "unknown export format" in capsys.readouterr().err


def test_open_refuses_what_is_not_a_report(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "equation.json"
    bad.write_text("x^2 + y^2 - 1", encoding="utf-8")
    assert main(["open", str(bad)]) == 2
    assert capsys.readouterr().err.strip().splitlines() == [
        f"sorgui: {bad} is not a JSON report: Expecting value: line 1 column 1 (char 0)"
    ]


def test_open_points_a_cad_part_to_analyze(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    """``sorgui open part.step`` said "is not a JSON report: Expecting value: line 1 column 1"."""
    part = tmp_path / "part.step"
    part.write_text("ISO-10303-21;\n", encoding="ascii")
    assert main(["open", str(part)]) == 2
    assert capsys.readouterr().err.strip() == (
        f"sorgui: {part} is a CAD part, not a report: 'sorgui analyze {part}' reads its surfaces "
        f"('sorgui {part}' shows them in the window)"
    )


def test_open_hands_a_valid_report_to_the_window(analyses, tmp_path, monkeypatch) -> None:
    import sorgui.gui.app

    opened: list[tuple[str, object, object]] = []
    monkeypatch.setattr(
        sorgui.gui.app, "run_gui", lambda path=None, report=None, line=None: opened.append((path, report, line)) or 0
    )
    report = export_analysis(analyses["torus"], tmp_path / "torus.sorgui.json")
    assert main(["open", str(report)]) == 0
    [(path, read, line)] = opened
    assert path == str(report) and read.recognition.polynomial == analyses["torus"].recognition.polynomial  # read once
    assert line is None  # a report, not a line of a batch's results file


def test_the_picture_of_rounded_input_shows_its_approximate_axis(tmp_path) -> None:
    """As the window draws it, in its orange: rounded input has no exact axis of its own, and its
    report's picture ("the surface and its axis") had none."""
    import numpy as np
    import pyvista

    data = Path(__file__).parents[1] / "data" / "rounded-torus-6-digits.txt"
    rounded, exact = tmp_path / "rounded.png", tmp_path / "exact.png"
    assert main(["analyze", "-f", str(data), "-o", str(rounded)]) == 0
    assert main(["analyze", "(x^2 + y^2 + z^2 + 8)^2 - 36(x^2 + y^2)", "-o", str(exact)]) == 0

    def orange_pixels(path: Path) -> int:
        image = pyvista.read(path)
        rgb = np.asarray(image.point_data.active_scalars)[:, :3].astype(int)
        return int(np.sum(np.all(np.abs(rgb - (239, 108, 0)) <= 24, axis=1)))

    assert orange_pixels(rounded) > 200
    assert orange_pixels(exact) == 0


def test_the_picture_shows_the_axes_of_a_products_factors(tmp_path) -> None:
    """As the window draws them (the picture had none); faint where the surface hides them."""
    import numpy as np
    import pyvista

    product = tmp_path / "product.png"
    assert main(["analyze", "(x^2+y^2-1)*(y^2+z^2-1)", "-o", str(product)]) == 0
    rgb = np.asarray(pyvista.read(product).point_data.active_scalars)[:, :3].astype(int)
    assert int(np.sum(np.all(np.abs(rgb - (0x45, 0x5A, 0x64)) <= 4, axis=1))) > 100  # FACTOR_AXES_COLOR
