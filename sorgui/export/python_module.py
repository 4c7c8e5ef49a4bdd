"""The Python export: a module that evaluates the parameterizations with NumPy and checks them.

The written module needs only ``numpy`` and ``sympy``. It holds

* ``F``, ``P2`` and the other results as exact sympy expressions, built from sympy's own
  exact syntax (``S(3)/5``, ``sqrt(S(2))``), so nothing is rounded;
* one function per parameterization, ``X1(s, t)``, ``X2(s, t)``, … (and ``P2param(t)`` of the profile),
  vectorised over NumPy arrays (broadcast like ``s + t``), returning the arrays ``x, y, z``;
  its docstring states the parameter domain and the points it misses;
* ``check()``, which substitutes every exact parameterization into ``F`` (or ``P2K``) and
  asserts that the result cancels to zero (``P2param`` into ``P2K``); the spine ``canal1M(t)``
  of a canal sphere family goes into its spine's equations ``canal1Spine``, and ``(m(t), ρ(t))``
  into its SMAT curve's ``canal1SMAT`` (docs/math.md §9), not into ``F``.

The code is printed by sympy's printers (``NumPyPrinter`` for the functions, ``sstr`` with
``sympy_integers`` for the exact expressions).
The check clears denominators and compares polynomials, which takes a fraction of a second where
sympy's ``cancel`` of the substituted fraction takes many.
"""

from __future__ import annotations

import sympy
from sympy.printing.numpy import NumPyPrinter

from sorgui.engine.results import Analysis
from sorgui.export.cas import summary_lines
from sorgui.export.formulas import CANAL_PREFIX, NEAREST_PREFIX, Formula, analysis_formulas
from sorgui.export.quoting import hash_comment, one_line, python_literal

_NUMPY = NumPyPrinter({"fully_qualified_modules": True})


def exact_code(value: sympy.Expr | tuple[sympy.Expr, ...]) -> str:
    """Python source for ``value`` that rebuilds it exactly with ``from sympy import *`` names."""
    if isinstance(value, tuple):
        return "(" + ", ".join(exact_code(v) for v in value) + ("," if len(value) == 1 else "") + ")"
    code: str = sympy.sstr(value, sympy_integers=True)
    return code


def _numpy_code(expr: sympy.Expr) -> str:
    code: str = _NUMPY.doprint(expr)
    return code


def _function(formula: Formula) -> list[str]:
    if not all(str(p).isidentifier() for p in formula.parameters):
        raise ValueError(f"the parameters of {formula.name} are not names: {formula.parameters}")
    args = ", ".join(str(p) for p in formula.parameters)
    outputs = {"P2param": "s, w"}.get(
        formula.name,
        "x, y, z" if formula.name.startswith(("X", "C", CANAL_PREFIX)) else f"its {len(formula.value)} coordinates",
    )
    assert formula.coverage is not None
    text = [
        f"{formula.description[0].upper() + formula.description[1:]}.",
        "",
        f"Vectorised over NumPy arrays ({args} broadcast together); returns the arrays {outputs}.",
        "Where a denominator vanishes the values are inf or nan.",
        "",
        *formula.coverage.lines(),
    ]
    doc = [f"    {python_literal(chr(10).join(one_line(line) for line in text) + chr(10))}"]
    body = [f"    {p} = numpy.asarray({p})" for p in formula.parameters]
    zero = " + ".join(f"0 * {p}" for p in formula.parameters)
    body.append(f"    zero = {zero}")
    body.append('    with numpy.errstate(divide="ignore", invalid="ignore"):')
    body.append("        return (")
    body += [f"            zero + ({_numpy_code(c)})," for c in formula.value]
    body.append("        )")
    return [f"def {formula.name}({args}):", *doc, *body, "", ""]


_VANISHES = '''def _vanishes(equation, variables, coordinates, parameters):
    """Whether equation(coordinates) is zero: with the common denominator D of the coordinates
    (c_i = A_i / D) and d the degree of the equation, sum k * A^e * D^(d - |e|) over its terms."""
    fractions = [[Poly(e, *parameters, extension=True) for e in together(c).as_numer_denom()] for c in coordinates]
    denominator = fractions[0][1]
    for _, d in fractions[1:]:
        denominator = denominator.lcm(d)
    scaled = [n * denominator.exquo(d) for n, d in fractions]
    terms = Poly(equation, *variables, extension=True).terms()
    degree = max(sum(monomial) for monomial, _ in terms)
    total = Poly(0, *parameters, extension=True)
    for monomial, coefficient in terms:
        term = Poly(coefficient, *parameters, extension=True) * denominator ** (degree - sum(monomial))
        for power, value in zip(monomial, scaled):
            term = term * value ** power
        total = total + term
    return total.is_zero'''
"""The exact check of the written module (source): Poly arithmetic, no rational simplification."""


def _exact_name(formula: Formula, maps: list[Formula]) -> str:
    """``F`` for the equation, ``X1_EXACT`` beside the function ``X1``, else the formula's name."""
    if formula.name == "f":
        return "F"
    return formula.name + "_EXACT" if formula in maps else formula.name


def _canal_checks(formulas: list[Formula]) -> list[str]:
    """Lines of ``check()`` for each canal spine ``canal{i}M``: every spine equation vanishes at
    ``m(t)``, and every SMAT equation at ``(m(t), ρ(t))`` when ``canal{i}Rho`` is known."""
    names = {f.name for f in formulas}
    lines = []
    for spine in (f.name for f in formulas if f.name.startswith(CANAL_PREFIX) and f.name.endswith("M")):
        family = spine[:-1]
        lines += [
            f"    assert all(_vanishes(e, (m1, m2, m3), {spine}_EXACT, (t,)) for e in {family}Spine), {spine!r}",
            f"    checked.append({spine!r})",
        ]
        if f"{family}Rho" in names:
            lines += [
                f"    assert all(_vanishes(e, (m1, m2, m3, r), {spine}_EXACT + ({family}Rho,), (t,))",
                f"               for e in {family}SMAT), {family + 'Rho'!r}",
                f"    checked.append({family + 'Rho'!r})",
            ]
    return lines


def _check_target(formula: Formula) -> tuple[str, str]:
    """A map and the equation ``check()`` substitutes it into (``""``: none): ``P2K`` for the
    parameterization of ``P²``, the surface ``F`` for a map of ``X`` or of a canal surface; for
    rounded input, the nearest exact surface ``g``'s (``nearestX1`` into ``g``)."""
    name = formula.name
    nearest = name.startswith(NEAREST_PREFIX)
    own = name[len(NEAREST_PREFIX) :] if nearest else name
    if own == "P2param":
        return name, name.replace("P2param", "P2K")
    if own.startswith(("X", "C")) and own[1:].isdigit() and len(formula.value) == 3:
        return name, "g" if nearest else "F"
    return name, ""


def python_module(analysis: Analysis) -> str:
    """The source of the Python module for ``analysis`` (module docstring)."""
    formulas = analysis_formulas(analysis)
    maps = [f for f in formulas if f.coverage is not None and f.name not in ("tau", NEAREST_PREFIX + "Tau")]
    head = summary_lines(analysis)
    docstring = [
        head[0] + ".",
        "",
        *head[1:],
        "",
        "Written by sorgui. The parameterizations are NumPy functions; the results are exact sympy",
        "expressions; check() verifies by exact substitution that each parameterization lies on the surface.",
    ]
    lines = [
        python_literal("\n".join(one_line(line) for line in docstring) + "\n"),
        "",
        "import numpy",
        "from sympy import I, Poly, S, Symbol, sqrt, together  # noqa: F401 (I, sqrt: in the formulas)",
        "",
        'x, y, z, s, t, w, u, v = (Symbol(name) for name in ("x", "y", "z", "s", "t", "w", "u", "v"))',
        'm1, m2, m3, r = (Symbol(name) for name in ("m1", "m2", "m3", "r"))',
        "",
    ]
    for formula in formulas:
        lines.append(hash_comment(formula.description))
        lines.append(f"{_exact_name(formula, maps)} = {exact_code(formula.value)}")
    lines += [
        "",
        "PARAMETERS = {",
        *[f"    {f.name!r}: ({', '.join(map(str, f.parameters))},)," for f in maps],
        "}",
        '"""The parameters of each parameterization, in order."""',
        "",
        "",
    ]
    for formula in maps:
        lines += _function(formula)
    defined = {_exact_name(formula, maps) for formula in formulas}
    targets = {name: target for name, target in map(_check_target, maps) if target}
    lines += [
        *_VANISHES.splitlines(),
        "",
        "",
        "def check():",
        '    """Substitute every exact parameterization into its equation; assert the result is zero."""',
        "    checked = []",
    ]
    for name, target in targets.items():
        if target not in defined:  # a map whose implicit equation was not found
            lines.append(f"    # {name}: not checked, the equation {target} it lies on is not known")
            continue
        variables = "(s, w)" if target.endswith("P2K") else "(x, y, z)"
        lines += [
            f"    assert _vanishes({target}, {variables}, {name}_EXACT, PARAMETERS[{name!r}]), {name!r}",
            f"    checked.append({name!r})",
        ]
    lines += _canal_checks(formulas)
    lines += [
        "    return checked",
        "",
        "",
        'if __name__ == "__main__":',
        '    print("verified:", ", ".join(check()) or "nothing to check")',
    ]
    return "\n".join(lines) + "\n"
