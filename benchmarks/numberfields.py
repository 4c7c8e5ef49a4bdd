"""Benchmark: full analyses of published surfaces over ``K = QQ(√…)`` and a large power over ``QQ``.

Cases: Barth's decic (degree 10, with the golden ratio ``(1+sqrt(5))/2``), Sarti's dodecic
(degree 12, with ``sqrt(5)``), the paraboloid ``x²+y²+√2x+√3y+√5z+√7`` (a field of degree 16)
and ``(x+2y+3z+4+5x²+y²)^30``. Each runs the whole ``analyze`` of the command line. Run
``python -m benchmarks.numberfields [--repeats N] [--write]``; ``--write`` updates
``docs/benchmarks.md``.
"""

from __future__ import annotations

from benchmarks.report import median_time, run
from sorgui.engine.analysis import analyze

PHI = "((1+sqrt(5))/2)"

BARTH = (
    f"8*(x^2-{PHI}^4*y^2)*(y^2-{PHI}^4*z^2)*(z^2-{PHI}^4*x^2)"
    "*(x^4+y^4+z^4-2*x^2*y^2-2*x^2*z^2-2*y^2*z^2)"
    f"+(3+5*{PHI})*(x^2+y^2+z^2-1)^2*(x^2+y^2+z^2-(2-{PHI}))^2"
)
"""Barth's decic with ``w = 1`` (W. Barth, 1996: 345 nodes)."""


def _sarti() -> str:
    """Sarti's dodecic with ``w = 1`` (A. Sarti, 2001: 600 nodes), in the invariants
    ``l₁ = x⁴+y⁴+z⁴+1``, ``l₂ = x²y²+z²``, ``l₃ = x²z²+y²``, ``l₄ = x²+y²z²``, ``l₅ = xyz``."""
    l1, l2, l3, l4, l5 = "(x^4+y^4+z^4+1)", "(x^2*y^2+z^2)", "(x^2*z^2+y^2)", "(x^2+y^2*z^2)", "(x*y*z)"
    pairs = [(l2, l3), (l3, l4), (l4, l2)]
    minus = "+".join(f"{a}^2*{b}-{a}*{b}^2" for a, b in pairs)
    plus = "+".join(f"{a}^2*{b}+{a}*{b}^2" for a, b in pairs)
    s = f"({l2}+{l3}+{l4})"
    return (
        f"243*(33*sqrt(5)*({minus})+19*({plus})+10*({l2}^3+{l3}^3+{l4}^3)"
        f"-14*{l1}*({l2}*{l3}+{l2}*{l4}+{l3}*{l4})+2*{l1}^2*{s}-6*{l1}*({l2}^2+{l3}^2+{l4}^2)"
        f"-352*{l5}^2*{s}+336*{l5}^2*{l1}+48*{l2}*{l3}*{l4})-22*(x^2+y^2+z^2+1)^6"
    )


SARTI = _sarti()

CASES = (
    ("Barth's decic", BARTH),
    ("Sarti's dodecic", SARTI),
    ("paraboloid, 4 square roots", "x^2+y^2+sqrt(2)x+sqrt(3)y+sqrt(5)z+sqrt(7)"),
    ("paraboloid, 3 square roots", "x^2+y^2+sqrt(2)x+sqrt(3)y+sqrt(5)z+7"),
    ("(x+2y+3z+4+5x²+y²)^30", "(x+2y+3z+4+5x^2+y^2)^30"),
)


def table(repeats: int) -> str:
    """The markdown table: total and per-stage times of each case."""
    rows = [
        "| case | degree | field | surface of revolution | factors | total (s) | stages (s) |",
        "|---|---:|---|---|---:|---:|---|",
    ]
    for name, text in CASES:
        seconds, result = median_time(lambda text=text: analyze(text), repeats)
        stages = ", ".join(f"{n} {s:.3f}" for n, s in result.timings)
        rows.append(
            f"| {name} | {result.recognition.degree} | {result.field} | "
            f"{'yes' if result.recognition.is_sor else 'no'} | {len(result.factors)} | {seconds:.3f} | {stages} |"
        )
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("numberfields", __doc__, table)
