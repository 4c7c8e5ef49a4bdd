"""The canal sphere family in every formula file, read back: the spine, m(t), ρ(t) and the
characteristic circles of the canal surface around the parabola with radius (1 + t)/2
(tests/data/canal-examples.txt), found by the real engine."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import sympy
from sympy.parsing.mathematica import parse_mathematica
from sympy.printing.maple import maple_code

from sorgui.engine import analyze
from sorgui.engine.results import Analysis
from sorgui.export.cas import latex_document, maple_file, mathematica_file
from sorgui.export.files import export_analysis
from sorgui.export.formulas import canal_formulas
from sorgui.export.reports import html_report, markdown_report
from tests.export.test_cas import assignments
from tests.export.test_python_module import load

EXAMPLES = Path(__file__).resolve().parents[1] / "data" / "canal-examples.txt"
NAME = "canal parabola r=(1+t)/2"
t, m1, m2, m3, r = sympy.symbols("t m1 m2 m3 r")


def example(name: str) -> str:
    """The polynomial under the heading ``## name | …`` of the canal examples."""
    lines = EXAMPLES.read_text(encoding="utf-8").splitlines()
    heading = next(i for i, line in enumerate(lines) if line.startswith(f"## {name} |"))
    return lines[heading + 1]


@pytest.fixture(scope="module")
def canal_analysis() -> Analysis:
    return analyze(example(NAME))


def test_the_example_has_a_rational_family_with_varying_radius(canal_analysis) -> None:
    canal = canal_analysis.canal
    assert canal is not None and canal.is_canal and len(canal.families) == 1
    names = [f.name for f in canal_formulas(canal)]
    assert names == ["canal1Spine", "canal1SMAT", "canal1M", "canal1Rho", "canal1C", "canal1R2", "canal1N"]
    formulas = {f.name: f for f in canal_formulas(canal)}
    assert formulas["canal1Spine"].value == (m3, m1**2 - m2)
    assert formulas["canal1M"].value == (t, t**2, sympy.Integer(0))
    assert sympy.expand(formulas["canal1Rho"].value - (t + 1) ** 2 / 4) == 0


def test_mathematica_reads_back_every_canal_formula(canal_analysis) -> None:
    values = assignments(mathematica_file(canal_analysis), " = ")
    for formula in canal_formulas(canal_analysis.canal):
        parsed = parse_mathematica(values[formula.name])
        expected = formula.value if formula.is_vector else (formula.value,)
        got = tuple(parsed) if formula.is_vector else (parsed,)
        assert len(got) == len(expected), formula.name
        assert all(sympy.simplify(a - b) == 0 for a, b in zip(got, expected)), formula.name


def test_maple_lines_are_maple_code_of_the_canal_formulas(canal_analysis) -> None:
    text = maple_file(canal_analysis)
    values = assignments(text, " := ")
    for formula in canal_formulas(canal_analysis.canal):
        assert values[formula.name] == maple_code(list(formula.value) if formula.is_vector else formula.value)
    assert values["canal1M"] == "[t, t^2, 0]"
    assert "# canal surface: yes; 1 sphere family found" in text
    assert "#   no denominator: defined for every parameter value" in text


def test_python_module_evaluates_m_and_checks_it_on_the_spine(canal_analysis, tmp_path) -> None:
    path = export_analysis(canal_analysis, tmp_path / "canal_parabola.py")
    module = load(path, "exported_canal_parabola")
    assert module.check() == ["canal1M", "canal1Rho"]
    values = np.linspace(-2.0, 3.0, 11)
    x, y, z = module.canal1M(values)
    assert x.shape == y.shape == z.shape == (11,)
    assert np.array_equal(x, values) and np.allclose(y, values**2) and np.array_equal(z, np.zeros(11))
    cx, cy, cz = module.canal1C(values[:, None] + 0 * values[None, :])
    assert cx.shape == (11, 11) and np.all(np.isfinite(cx))
    assert "parameter domain" in module.canal1M.__doc__
    assert module.canal1Spine == (m3, m1**2 - m2)
    assert sympy.expand(module.canal1Rho - (t + 1) ** 2 / 4) == 0


@pytest.mark.parametrize(
    ("old", "new", "failing"),
    [
        ("canal1M_EXACT = (", "canal1M_EXACT = (S(1)/7 + ", "canal1M"),
        ("canal1Rho = ", "canal1Rho = S(1)/7 + ", "canal1Rho"),
    ],
)
def test_check_fails_for_a_wrong_spine_or_radius(canal_analysis, tmp_path, old: str, new: str, failing: str) -> None:
    path = export_analysis(canal_analysis, tmp_path / f"wrong_{failing}.py")
    text = path.read_text(encoding="utf-8")
    assert old in text
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    module = load(path, f"exported_wrong_{failing}")
    with pytest.raises(AssertionError, match=failing):
        module.check()


def test_reports_have_a_canal_section_in_words_and_formulas(canal_analysis) -> None:
    text = markdown_report(canal_analysis)
    canal = text[text.index("## Canal") :]
    assert "The surface is a canal surface (canal)." in canal
    assert "- spine of degree 2 (planar); SMAT curve of degree 2 and genus 0" in canal
    assert "- radius varying" in canal
    assert r"$m_{1}(t) = \left(t, t^{2}, 0\right)$" in canal
    assert r"$r^{2}_{1}(t) = \frac{\left(t + 1\right)^{2}}{4}$" in canal
    assert r"c_{1}(t) = " in canal and r"R^{2}_{1}(t) = " in canal
    assert "Certificate (resultant, checked): f divides Res_t" in canal
    assert "canal1" not in text and "## Further results" not in text
    page = html_report(canal_analysis)
    assert "<h2>Canal</h2>" in page and r"r^{2}_{1}(t)" in page


def test_latex_names_the_spine_and_radius(canal_analysis) -> None:
    text = latex_document(canal_analysis)
    assert r"m_{1}(t) = \left(t, t^{2}, 0\right)" in text
    assert r"r^{2}_{1}(t) = \frac{\left(t + 1\right)^{2}}{4}" in text
    assert r"\mathrm{spine}_{1} = \left(m_{3}, m_{1}^{2} - m_{2}\right)" in text


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex is not installed (.ci/run installs it)")
def test_latex_document_with_the_canal_family_compiles(canal_analysis, tmp_path) -> None:
    path = export_analysis(canal_analysis, tmp_path / "canal.tex")
    run = subprocess.run(
        ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", path.name],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
        stdin=subprocess.DEVNULL,
    )
    assert run.returncode == 0, run.stdout[-2000:]
    assert (tmp_path / "canal.pdf").stat().st_size > 10_000
