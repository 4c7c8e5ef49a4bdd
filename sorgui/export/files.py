"""Writing an :class:`~sorgui.engine.report.Analysis` to files: JSON, text, LaTeX, Maple, Mathematica.

The format follows the file's suffix (:data:`FORMATS`). JSON is exactly ``sorgui analyze
--json``; the text file is the command line's report; the LaTeX, Maple and Mathematica files
hold the results as formulas (the equation, the axis, the profile and ``P²``, the tubular
surface and every parameterization), printed by sympy's printers from the engine's exact
strings (read back with :mod:`sorgui.export.exact`, never evaluated).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import sympy
from sympy.printing.maple import maple_code
from sympy.printing.mathematica import mathematica_code

from sorgui.engine.report import Analysis
from sorgui.export.exact import read_expression
from sorgui.export.text import TABLE_1, format_report

Formula = tuple[str, str, sympy.Expr]
"""(name used in code, description, exact expression)."""


def analysis_formulas(analysis: Analysis) -> list[Formula]:
    """The results of ``analysis`` as named exact expressions, in reading order."""
    rec = analysis.recognition
    out: list[Formula] = [("f", "the equation f(x, y, z) = 0", read_expression(rec.polynomial))]
    vectors = {
        "axis_point": ("a point of the axis", rec.axis.point if rec.axis else None),
        "axis_direction": ("the direction of the axis", rec.axis.direction if rec.axis else None),
        "center": ("the centre of the sphere", rec.center),
        "normal": ("the normal of the plane", rec.normal),
        "direction": ("the direction of the extrusion", rec.direction),
    }
    for name, (text, value) in vectors.items():
        if value is not None:
            out.append((name, text, sympy.Matrix([read_expression(v) for v in value]).T))
    if rec.profile is not None:
        out.append(("p", "the profile p(x, y) = 0 (x along the axis, y the distance)", read_expression(rec.profile.polynomial)))
        out.append(("P2", "the curve P² (p with y² replaced by y)", read_expression(rec.profile.square)))
    rat = analysis.rationality
    if rat is not None and rat.tubular_surface is not None:
        out.append(("T", "the tubular surface T = 0", read_expression(rat.tubular_surface)))
    for i, par in enumerate(analysis.parametrizations, 1):
        coords = sympy.Matrix([read_expression(c) for c in par.coordinates]).T
        out.append((f"X{i}", f"parameterization {i}: {par.method}, over {par.field}", coords))
    return out


def _latex(analysis: Analysis) -> str:
    """A LaTeX document with the verdict, the Table 1 row and every formula."""
    field = analysis.field.replace("QQ", r"\mathbb{Q}")
    symmetry = analysis.recognition.symmetry.replace("_", " ")
    lines = [
        r"\documentclass{article}",
        r"\usepackage{amsmath}",
        r"\allowdisplaybreaks",
        r"\begin{document}",
        r"\section*{sorgui: " + ("a surface of revolution" if analysis.is_sor else "not a surface of revolution") + "}",
        f"Symmetry: {symmetry}; field $K = {field}$.",
    ]
    rat = analysis.rationality
    if rat is not None and rat.table_row is not None:
        row = TABLE_1[rat.table_row - 1]
        lines.append(f"Table 1, row {rat.table_row}: genus$(P)$ {row[0]}, genus$(P^2)$ {row[1]}, "
                     f"$X_\\mathbb{{C}}$ {row[2]}, $X$ {row[3]}.")
    for _name, text, expr in analysis_formulas(analysis):
        lines += [f"\\paragraph{{{text[0].upper() + text[1:]}}}", r"\[", sympy.latex(expr), r"\]"]
    lines.append(r"\end{document}")
    return "\n".join(lines) + "\n"


def _code(printer: Callable[[sympy.Expr], str], assign: str, comment: tuple[str, str]) -> Callable[[Analysis], str]:
    """A writer of ``name assign value;`` lines with comments for a computer algebra system."""
    start, end = comment

    def write(analysis: Analysis) -> str:
        verdict = "a surface of revolution" if analysis.is_sor else "not a surface of revolution"
        lines = [f"{start} sorgui: {verdict}{end}"]
        for name, text, expr in analysis_formulas(analysis):
            lines += [f"{start} {text}{end}", f"{name}{assign}{printer(expr)};"]
        return "\n".join(lines) + "\n"

    return write


FORMATS: dict[str, Callable[[Analysis], str]] = {
    ".json": lambda analysis: json.dumps(analysis.to_json(), indent=1) + "\n",
    ".txt": lambda analysis: format_report(analysis) + "\n",
    ".tex": _latex,
    ".mpl": _code(maple_code, " := ", ("#", "")),
    ".m": _code(mathematica_code, " = ", ("(*", " *)")),
}
"""File suffix → writer."""


def export_analysis(analysis: Analysis, path: str | Path) -> Path:
    """Write ``analysis`` to ``path`` in the format its suffix names; raise ``ValueError`` for an
    unknown suffix and ``OSError`` when the file cannot be written."""
    path = Path(path)
    writer = FORMATS.get(path.suffix.lower())
    if writer is None:
        raise ValueError(f"unknown export format {path.suffix!r}; use one of {', '.join(FORMATS)}")
    path.write_text(writer(analysis), encoding="utf-8")
    return path
