"""LaTeX, Maple and Mathematica files read back: compiled, compared, parsed."""

from __future__ import annotations

import shutil
import subprocess

import pytest
import sympy
from sympy.parsing.mathematica import parse_mathematica
from sympy.printing.maple import maple_code

from sorgui.export.cas import latex_document, maple_file, mathematica_file, tex_text
from sorgui.export.files import export_analysis
from sorgui.export.formulas import analysis_formulas

NAMES = ("paper-example-1", "torus", "cone", "paper-cubic")


def assignments(text: str, separator: str) -> dict[str, str]:
    """``name -> value`` of the lines ``name<separator>value;`` of a file (comments skipped)."""
    out = {}
    for line in text.splitlines():
        if separator in line and line.endswith(";") and not line.startswith(("#", "(*")):
            name, value = line[:-1].split(separator, 1)
            out[name] = value
    return out


@pytest.mark.parametrize("name", NAMES)
def test_mathematica_parses_back_into_the_same_expressions(analyses, name: str) -> None:
    analysis = analyses[name]
    text = mathematica_file(analysis)
    values = assignments(text, " = ")
    formulas = analysis_formulas(analysis)
    assert set(values) == {f.name for f in formulas}
    assert all("_" not in n for n in values)
    for formula in formulas:
        parsed = parse_mathematica(values[formula.name])
        if formula.is_vector:
            assert isinstance(parsed, sympy.Tuple) and len(parsed) == len(formula.value), formula.name
            pairs = zip(parsed, formula.value)
        else:
            pairs = [(parsed, formula.value)]
        for got, expected in pairs:
            assert sympy.simplify(got - expected) == 0, formula.name
    assert "(* parameter domain" in text.replace("(*   ", "(* ")


@pytest.mark.parametrize("name", NAMES)
def test_maple_lines_are_sympy_maple_code_of_the_results(analyses, name: str) -> None:
    analysis = analyses[name]
    text = maple_file(analysis)
    values = assignments(text, " := ")
    for formula in analysis_formulas(analysis):
        value = list(formula.value) if formula.is_vector else formula.value
        assert values[formula.name] == maple_code(value)
    assert "# sorgui: a surface of revolution" in text
    if analysis.parametrizations:
        assert "#   parameter domain: (s, t) in" in text and "undefined where" in text


def test_every_formula_file_states_domain_and_missed_points(analyses) -> None:
    torus = analyses["torus"]
    for text in (latex_document(torus), maple_file(torus), mathematica_file(torus)):
        assert "parameter domain" in text
        assert "no real zeros" in text
        assert "reached only as" in text and "it is missed" in text


def test_latex_text_is_escaped() -> None:
    assert tex_text("a_b & 50% τ·x²") == r"a\_b \& 50\% $\tau$$\cdot$x$^2$"


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex is not installed (.ci/run installs it)")
@pytest.mark.parametrize("name", NAMES)
def test_latex_document_compiles(analyses, name: str, tmp_path) -> None:
    path = export_analysis(analyses[name], tmp_path / f"{name}.tex")
    run = subprocess.run(
        ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", path.name],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
        stdin=subprocess.DEVNULL,
    )
    assert run.returncode == 0, run.stdout[-2000:]
    assert (tmp_path / f"{name}.pdf").stat().st_size > 10_000


@pytest.mark.parametrize("name", NAMES)
def test_the_equation_line_of_each_file_pastes_back_into_sorgui(analyses, name: str) -> None:
    """A user who copies the line ``f = …;`` (Mathematica), ``f := …;`` (Maple) or the LaTeX
    document's ``f = …`` (all its lines, with their line breaks and ``quad``) back into sorgui gets
    the same polynomial."""
    from sorgui.engine.parsing import parse_polynomial

    analysis = analyses[name]
    expected = parse_polynomial(analysis.recognition.polynomial).polynomial
    lines = [
        next(line for line in mathematica_file(analysis).splitlines() if line.startswith("f = ")),
        next(line for line in maple_file(analysis).splitlines() if line.startswith("f := ")),
        _latex_equation(latex_document(analysis)),
    ]
    for line in lines:
        assert parse_polynomial(line).polynomial == expected, line


def _latex_equation(document: str) -> str:
    """The lines of the equation ``f = …`` in a LaTeX document, as a user selects them."""
    start = document.index("f = ")
    return document[start : min(document.index(end, start) for end in ("\\end{", "\\]"))]


def test_the_parameterization_lines_paste_back_as_the_same_map(analyses) -> None:
    """Maple's ``X1 := [X, Y, Z];`` and Mathematica's ``X1 = {X, Y, Z};`` of the torus read back
    as the map the analysis found."""
    from sorgui.engine.parametric_parsing import parse_parametrization

    analysis = analyses["torus"]
    found = parse_parametrization("(" + ", ".join(analysis.parametrizations[0].coordinates) + ")").map
    maple = next(line for line in maple_file(analysis).splitlines() if line.startswith("X1 := ["))
    mathematica = next(line for line in mathematica_file(analysis).splitlines() if line.startswith("X1 = {"))
    for line in (maple, mathematica):
        parsed = parse_parametrization(line).map
        assert (parsed.X, parsed.W) == (found.X, found.W), line


def test_the_unicode_of_sorgui_s_words_is_typeset() -> None:
    """The notes' ★, ρ, ≡, subscripts and ellipses were printed as [U+2605] and the like."""
    text = tex_text("singular values of (★): ρ₀ ≡ 0 … ∂(h, ρ)/∂(s, t), 10⁻³")
    assert "U+" not in text and r"$\bigstar$" in text and r"$\rho$" in text
