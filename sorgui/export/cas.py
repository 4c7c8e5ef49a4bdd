"""Formula files for other tools: a LaTeX document, a Maple worksheet and a Mathematica file.

All three print the same :func:`~sorgui.export.formulas.analysis_formulas` with sympy's own
printers (``latex``, ``maple_code``, ``mathematica_code``), so that the files read back into
exactly the expressions the engine found: the Maple lines are ``name := maple_code(value);``,
the Mathematica lines ``name = mathematica_code(value);`` (vectors as lists ``{a, b, c}``), which
``sympy.parsing.mathematica.parse_mathematica`` reads back. Each map is followed by its
parameter domain and the points it misses (:class:`~sorgui.export.coverage.Coverage`).
The LaTeX document needs only ``amsmath`` and ``amssymb``; long sums are broken over lines.
"""

from __future__ import annotations

import re
from collections.abc import Callable

import sympy
from sympy.printing.maple import maple_code
from sympy.printing.mathematica import mathematica_code

from sorgui.engine.results import Analysis, Approximation
from sorgui.engine.vocabulary import UNDECIDED_NEARNESS, kind_noun
from sorgui.export.coverage import CoverageStyle
from sorgui.export.formulas import Formula, analysis_formulas
from sorgui.export.quoting import hash_comment, mathematica_comment, one_line
from sorgui.export.text import TABLE_1, approximation_lines, within_words

LATEX_LINE = 100
"""Characters of LaTeX source per displayed line before a long sum is broken."""

_TEX_SPECIAL = {
    "\\": r"\textbackslash{}",
    "&": r"\&",
    "%": r"\%",
    "$": r"\$",
    "#": r"\#",
    "_": r"\_",
    "{": r"\{",
    "}": r"\}",
    "~": r"\textasciitilde{}",
    "^": r"\textasciicircum{}",
}
_GREEK = "alpha beta gamma delta varepsilon zeta eta theta lambda mu nu xi pi rho sigma varphi chi psi"
_TEX_UNICODE = {
    "τ": r"$\tau$",
    "·": r"$\cdot$",
    "×": r"$\times$",
    "²": r"$^2$",
    "³": r"$^3$",
    "→": r"$\to$",
    "≤": r"$\le$",
    "≥": r"$\ge$",
    "−": "-",
    "√": r"$\surd$",
    "̂": "",
    "±": r"$\pm$",
    "∞": r"$\infty$",
    "ℂ": r"$\mathbb{C}$",
    "ℝ": r"$\mathbb{R}$",
    "ℚ": r"$\mathbb{Q}$",
    "–": "--",
    "—": "---",
    "★": r"$\bigstar$",
    "…": r"\ldots{}",
    "≡": r"$\equiv$",
    "≈": r"$\approx$",
    "≠": r"$\neq$",
    "∈": r"$\in$",
    "∂": r"$\partial$",
    "∇": r"$\nabla$",
    "↦": r"$\mapsto$",
    "⟂": r"$\perp$",
    "⊥": r"$\perp$",
    "‖": r"$\|$",
    "°": r"$^\circ$",
    "′": r"$'$",
    "Σ": r"$\Sigma$",
    "Π": r"$\Pi$",
    "Δ": r"$\Delta$",
    **{g: f"$\\{name}$" for g, name in zip("αβγδεζηθλμνξπρσφχψ", _GREEK.split())},
    **{s: f"$_{d}$" for s, d in zip("₀₁₂₃₄₅₆₇₈₉", "0123456789")},
    **{s: f"$^{d}$" for s, d in zip("⁰¹⁴⁵⁶⁷⁸⁹", "01456789")},
    "⁻": r"$^-$",
    "ᵏ": "$^k$",
    "ᵢ": "$_i$",
    "ₖ": "$_k$",
}


def verdict(analysis: Analysis) -> str:
    """One line: whether ``X`` is a surface of revolution (:attr:`Analysis.verdict`)."""
    return {
        "undecided": "undecided whether it is a surface of revolution "
        "(the recognition did not finish within the time limit)",
        "sor": "a surface of revolution",
        "near": f"nearly a surface of revolution (not exactly: within {within_words(analysis)})",
        "not": "not a surface of revolution",
        "not exactly": f"not exactly a surface of revolution ({UNDECIDED_NEARNESS})",
    }[analysis.verdict]


def summary_lines(analysis: Analysis) -> list[str]:
    """The verdict, symmetry, field and Table 1 row in plain words (the files' header)."""
    rec = analysis.recognition
    lines = [
        f"sorgui: {verdict(analysis)}",
        f"symmetry: {kind_noun(rec.symmetry)}"
        + (f" (dim L = {rec.symmetry_dimension})" if rec.decided else "")
        + f"; field K = {analysis.field}",
    ]
    rat = analysis.rationality
    if rat is not None and rat.table_row is not None:
        row = TABLE_1[rat.table_row - 1]
        lines.append(f"Table 1, row {rat.table_row}: genus(P) {row[0]}, genus(P^2) {row[1]}, X_C {row[2]}, X {row[3]}")
    canal = analysis.canal
    if canal is not None:
        answer = {True: "yes", False: "no", None: "undecided"}[canal.is_canal]
        kinds = f" ({', '.join(canal.kinds)})" if canal.kinds else ""
        count = len(canal.families)
        lines.append(f"canal surface: {answer}{kinds}; {count} sphere {'family' if count == 1 else 'families'} found")
    lines += [line.strip() for line in approximation_lines(analysis, nested=False)]
    return lines


def approximate_line(approx: Approximation) -> str:
    """The verdict on a rounded input in one line."""
    kind = f" ({kind_noun(approx.kind)})" if approx.kind else ""
    if approx.tolerance is None:  # numbers beyond floating point (1e400): nearness not decided
        return f"nearness to a surface of revolution not decided: {'; '.join(approx.notes) or 'no tolerance'}"
    residual = "" if approx.residual is None else f"; residual {approx.residual:.3g} roundings"
    return (
        f"{'near' if approx.near_sor else 'not near'} a surface of revolution{kind} within the relative "
        f"tolerance {approx.tolerance:g} ({approx.tolerance_source}){residual}"
    )


LATEX_NAMES = {
    "P2": "P^2",
    "P2K": r"\tilde{p}^2",
    "P2param": r"\mathrm{P2param}",
    "tau": r"\tau",
    "axisPoint": r"\mathrm{axisPoint}",
    "axisDirection": r"\mathrm{axisDirection}",
    "center": r"\mathrm{center}",
    "normal": r"\mathrm{normal}",
    "direction": r"\mathrm{direction}",
    "radiusSquared": "r^{2}",
}
"""How the formulas' names are typeset (``X1`` becomes ``X_{1}`` by sympy's rule)."""


CANAL_LATEX = {
    "Spine": r"\mathrm{spine}_{%s}",
    "SMAT": r"\mathrm{SMAT}_{%s}",
    "M": "m_{%s}",
    "Rho": "r^{2}_{%s}(t)",
    "C": "c_{%s}",
    "R2": "R^{2}_{%s}(t)",
    "N": "n_{%s}(t)",
}
"""How the canal formulas ``canal{i}…`` of family ``i`` are typeset (docs/math.md §9 names)."""

_CANAL_NAME = re.compile(r"canal(\d+)(Spine|SMAT|M|Rho|C|R2|N)")


def latex_name(name: str) -> str:
    """The LaTeX of a formula's name."""
    canal = _CANAL_NAME.fullmatch(name)
    if canal is not None:
        return CANAL_LATEX[canal.group(2)] % canal.group(1)
    return LATEX_NAMES.get(name) or sympy.latex(sympy.Symbol(name))


_SUBSCRIPTED = re.compile(r"(.*_\{[^{}]*)\}(\([^()]*\))?")


def component_name(name: str, i: int) -> str:
    r"""The LaTeX name of component ``i`` of the vector ``name``: ``X_{i}``, and a name that has a
    subscript already gets ``i`` in it (``\mathrm{SMAT}_{1}`` becomes ``\mathrm{SMAT}_{1,2}``: a
    second subscript is an error in LaTeX)."""
    subscripted = _SUBSCRIPTED.fullmatch(name)
    if subscripted is None:
        return f"{name}_{{{i}}}"
    return f"{subscripted.group(1)},{i}}}{subscripted.group(2) or ''}"


def tex_text(text: str) -> str:
    """``text`` escaped for LaTeX's text mode (special characters and the Unicode sorgui uses)."""
    out = []
    for char in one_line(text):
        if char in _TEX_SPECIAL:
            out.append(_TEX_SPECIAL[char])
        elif char in _TEX_UNICODE:
            out.append(_TEX_UNICODE[char])
        elif ord(char) < 128:
            out.append(char)
        else:
            out.append(f"[U+{ord(char):04X}]")
    return "".join(out)


def _signed_terms(expr: sympy.Expr) -> list[str]:
    """The terms of a sum as LaTeX, each after the first with its sign in front."""
    pieces = []
    for i, term in enumerate(expr.as_ordered_terms()):
        if i == 0:
            pieces.append(sympy.latex(term))
        elif term.could_extract_minus_sign():
            pieces.append("- " + sympy.latex(-term))
        else:
            pieces.append("+ " + sympy.latex(term))
    return pieces


def latex_display(lhs: str, expr: sympy.Expr) -> list[str]:
    """``lhs = expr`` displayed, a long sum (or the long numerator of a quotient) over lines."""
    whole = sympy.latex(expr)
    if len(whole) <= LATEX_LINE:
        return [r"\[", f"{lhs} = {whole}", r"\]"]
    numerator, denominator = sympy.fraction(sympy.together(expr))
    if not isinstance(numerator, sympy.Add):
        return [r"\[", f"{lhs} = {whole}", r"\]"]
    prefix = f"{lhs} = " + ("" if denominator == 1 else r"\frac{1}{" + sympy.latex(denominator) + r"}\bigl(")
    lines, current = [], prefix
    for piece in _signed_terms(numerator):
        if len(current) + len(piece) > LATEX_LINE and current != prefix:
            lines.append(current + r" \\")
            current = "\\quad " + piece
        else:
            current += " " + piece
    lines.append(current + ("" if denominator == 1 else r"\bigr)"))
    return [r"\begin{multline*}", *lines, r"\end{multline*}"]


def _tex_math(text: str) -> str:
    return f"${text}$"


LATEX_STYLE = CoverageStyle(
    expr=sympy.latex,
    math=_tex_math,
    real=r"\mathbb{R}",
    complex=r"\mathbb{C}",
    element=r"\in",
    to=r"\to",
    infinity=r"\infty",
    power=lambda n: "" if n == 1 else f"^{{{n}}}",
)


def _latex_formula(formula: Formula) -> list[str]:
    lines = [r"\paragraph{" + tex_text(formula.description[0].upper() + formula.description[1:]) + "}"]
    if not formula.is_vector:
        lines += latex_display(latex_name(formula.name), formula.value)
    elif formula.parameters and formula.name.startswith("X"):
        args = ", ".join(sympy.latex(p) for p in formula.parameters)
        for coordinate, value in zip("xyz", formula.value):
            lines += latex_display(f"{coordinate}({args})", value)
    else:
        args = "(" + ", ".join(sympy.latex(p) for p in formula.parameters) + ")" if formula.parameters else ""
        name = latex_name(formula.name) + args
        row = r"\left(" + ", ".join(sympy.latex(c) for c in formula.value) + r"\right)"
        if len(row) <= LATEX_LINE:
            lines += [r"\[", f"{name} = {row}", r"\]"]
        else:
            for i, value in enumerate(formula.value, 1):
                lines += latex_display(component_name(name, i), value)
    if formula.coverage is not None:
        lines.append(r"\begin{itemize}")
        lines += [r"\item " + _tex_words(line) for line in formula.coverage.lines(LATEX_STYLE)]
        lines.append(r"\end{itemize}")
    return lines


def _tex_words(line: str) -> str:
    """A coverage line: escape the words between the ``$…$`` formulas, keep the formulas."""
    parts = line.split("$")
    return "".join(tex_text(part) if i % 2 == 0 else f"${part}$" for i, part in enumerate(parts))


def latex_document(analysis: Analysis) -> str:
    """A complete LaTeX document (``pdflatex`` compiles it) with every result as a formula."""
    head = summary_lines(analysis)
    lines = [
        r"\documentclass[11pt]{article}",
        r"\usepackage[T1]{fontenc}",
        r"\usepackage{amsmath}",
        r"\usepackage{amssymb}",
        r"\allowdisplaybreaks",
        r"\begin{document}",
        r"\section*{" + tex_text(head[0]) + "}",
        *[tex_text(line) + r"\par" for line in head[1:]],
    ]
    for formula in analysis_formulas(analysis):
        lines += _latex_formula(formula)
    lines.append(r"\end{document}")
    return "\n".join(lines) + "\n"


def _code_file(
    printer: Callable[[object], str], assign: str, comment: Callable[[str], str], style: CoverageStyle
) -> Callable[[Analysis], str]:
    """A writer of ``name assign value;`` lines with comments, for a computer algebra system."""

    def write(analysis: Analysis) -> str:
        lines = [comment(line) for line in summary_lines(analysis)]
        for formula in analysis_formulas(analysis):
            value = list(formula.value) if formula.is_vector else formula.value
            lines.append(comment(formula.description))
            if formula.coverage is not None:
                lines += [comment("  " + line) for line in formula.coverage.lines(style)]
            lines.append(f"{formula.name}{assign}{printer(value)};")
        return "\n".join(lines) + "\n"

    return write


maple_file = _code_file(maple_code, " := ", hash_comment, CoverageStyle(expr=maple_code, infinity="infinity"))
"""The Maple file: ``name := value;`` with ``#`` comments; vectors are Maple lists."""

mathematica_file = _code_file(
    mathematica_code, " = ", mathematica_comment, CoverageStyle(expr=mathematica_code, infinity="Infinity")
)
"""The Mathematica file: ``name = value;`` with ``(* *)`` comments; vectors are lists."""
