"""Benchmark: reading an equation, the parser's fast path against its general parser.

The surfaces of revolution in general position of :func:`benchmarks.recognition.surface`
(degrees 10 and 20) are printed the ways libraries print them: sorgui's own form
(``3/5*x**2*y``), sympy's ``str`` (``3*x**2*y/5``), Maple's (``3/5*x^2*y``), by hand with
implicit products (``3/5x^2y``), as ``lhs = rhs``, and with decimal coefficients (each printed
with ``%.17g``, as CAD output; another polynomial, read as exactly). Each text is read by the
general parser (tokens, syntax tree, checks, evaluation into flint: what every form but the
first took before the fast path read it) and by ``parsing.parse_rational`` (the fast path in
front of it), and the two polynomials are checked equal. The figures are the best of
``--repeats`` runs, in one process. The previous fast path (``algebra.rationals.expanded_terms``,
which read sorgui's and Maple's forms only) is timed where it reads the text. Run ``python -m
benchmarks.reading [--repeats N] [--write]`` from the repository root.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from benchmarks.recognition import surface
from benchmarks.report import run
from sorgui.engine import parsing, syntax
from sorgui.engine.algebra import rationals
from sorgui.engine.algebra.polys import poly_str

DEGREES = (10, 20)


def forms(f: Any) -> dict[str, str]:  # noqa: ANN401 - a sympy PolyElement
    """The printed forms of one polynomial (the last one rounded to 17 digits)."""
    text = poly_str(f)
    caret = text.replace("**", "^")
    first, rest = text.split(" ", 1)
    flipped = rest.replace(" + ", " # ").replace(" - ", " + ").replace(" # ", " - ")
    decimals = " + ".join(
        f"{float(c):.17g}*{'*'.join(f'{v}^{e}' for v, e in zip('xyz', m) if e)}" if any(m) else f"{float(c):.17g}"
        for m, c in f.items()
    ).replace("+ -", "- ")
    return {
        "sorgui (`3/5*x**2*y`)": text,
        "sympy str (`3*x**2*y/5`)": str(f.as_expr()),
        "Maple (`3/5*x^2*y`)": caret,
        "implicit (`3/5x^2y`)": caret.replace("*", ""),
        "`lhs = rhs`": f"{first} = {flipped.removeprefix('+ ').removeprefix('- ')}"
        if not flipped.startswith("- ")
        else f"{first} = -{flipped[2:]}",
        "decimals (`%.17g`)": decimals,
    }


def best(read: Callable[[], Any], repeats: int) -> tuple[float, Any]:
    """The best time of ``repeats`` calls of ``read`` and its result."""
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = read()
        times.append(time.perf_counter() - start)
    return min(times), result


def general(text: str) -> Any:  # noqa: ANN401 - a flint polynomial
    """The general parser alone, its cache of the last syntax tree emptied first."""
    syntax.parsed_tree.cache_clear()
    tree, evaluator, saw_variable = syntax.checked(text)
    return syntax.evaluate(text, evaluator, tree, syntax.FlintRationals(), saw_variable)


def previous(text: str) -> Any:  # noqa: ANN401 - a flint polynomial, or None where it did not read the text
    kept = rationals.expanded_terms(text, ("x", "y", "z"), max_digits=parsing.MAX_DIGITS, max_degree=60)
    return None if kept is None else rationals.context(("x", "y", "z")).from_dict(kept)


def table(repeats: int) -> str:
    rows = [
        "| degree | terms | printed as | general parser (ms) | fast path (ms) | general ÷ fast "
        "| previous fast path (ms) |",
        "|---:|---:|---|---:|---:|---:|---:|",
    ]
    for degree in DEGREES:
        f = surface(degree)
        for name, text in forms(f).items():
            slow, expected = best(lambda text=text: general(text), max(1, repeats // 3))
            fast, found = best(lambda text=text: parsing.parse_rational(text), repeats)
            assert found == expected, name
            before, old = best(lambda text=text: previous(text), repeats)
            old_cell = f"{before * 1e3:.2f}" if old is not None else "–"
            cells = f"{slow * 1e3:.1f} | {fast * 1e3:.2f} | {slow / fast:.0f} | {old_cell}"
            rows.append(f"| {degree} | {len(f)} | {name} | {cells} |")
            print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("reading", __doc__.splitlines()[0], table)
