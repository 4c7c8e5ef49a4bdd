"""Benchmark: a whole ``sorgui analyze --recognition-only`` process on a small equation.

Measures the wall time and the CPU time (user + system of the process and of every process it
started, :func:`benchmarks.report.process_times`), the best of ``--repeats`` runs, and the times
of the imports alone. The CPU time is the figure to compare on a busy machine: the wall time
includes waiting for the processor. The full analysis of the torus (:data:`FULL`) is measured
too, as a whole process, with its ratio to ``python -c "import sympy"`` in the same run (issue
34's goal: 0.6).
Run ``python -m benchmarks.startup [--repeats N] [--write]`` from the repository root.
"""

from __future__ import annotations

import sys

from benchmarks.recognition import surface
from benchmarks.report import process_times, run
from sorgui.engine.algebra.polys import poly_str

CASES = [
    ("paraboloid, degree 2", "x^2 + y^2 - z"),
    ("paper Example 1, degree 3", "y^2 + z^2 = x^3 + 3x^2 - 2x"),
    ("torus, degree 4", "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)"),
    ("(x^2+y^2+z^2-1)^5 + x, degree 10", "(x^2 + y^2 + z^2 - 1)^5 + x"),
    ("a cubic, neither of revolution nor canal, degree 3", "x^3 + y^2 z - x y z + 1"),
    ("a surface of revolution in general position, degree 10 (286 terms)", poly_str(surface(10))),
]
FULL = ("torus, degree 4, the full analysis", "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)")
NEITHER = ("Steiner's Roman surface, degree 4, the full analysis (no sympy)", "x^2y^2 + x^2z^2 + xyz + y^2z^2")
IMPORTS = [
    ("sympy", "import sympy"),
    ("numpy", "import numpy"),
    ("sorgui.engine", "import sorgui.engine"),
    ("sorgui.cli", "import sorgui.cli"),
]


def python_times(args: list[str], repeats: int) -> tuple[float, float]:
    """The best wall time and the best CPU time of ``python args`` over ``repeats`` runs (its
    analysis process and Singular included, :func:`benchmarks.report.process_times`)."""
    wall, cpu, _ = process_times([sys.executable, *args], repeats, min)
    return wall, cpu


def table(repeats: int) -> str:
    rows = ["| whole process | wall (s) | CPU (s) |", "|---|---|---|"]
    for name, text in CASES:
        wall, cpu = python_times(["-m", "sorgui.cli", "analyze", "--recognition-only", text], repeats)
        rows.append(f"| `sorgui analyze --recognition-only`: {name} | {wall:.2f} | {cpu:.2f} |")
    full = python_times(["-m", "sorgui.cli", "analyze", FULL[1]], repeats)
    rows.append(f"| `sorgui analyze`: {FULL[0]} | {full[0]:.2f} | {full[1]:.2f} |")
    neither = python_times(["-m", "sorgui.cli", "analyze", NEITHER[1]], repeats)
    rows.append(f"| `sorgui analyze`: {NEITHER[0]} | {neither[0]:.2f} | {neither[1]:.2f} |")
    measured = {}
    for _name, statement in IMPORTS:
        wall, cpu = python_times(["-c", statement], repeats)
        measured[statement] = (wall, cpu)
        rows.append(f'| `python -c "{statement}"` | {wall:.2f} | {cpu:.2f} |')
    sympy_wall, _ = measured["import sympy"]
    rows += [
        "",
        f"Full analysis ÷ `import sympy`, wall time: the torus {full[0] / sympy_wall:.2f}, Steiner's "
        f"surface {neither[0] / sympy_wall:.2f}. (The CPU column counts every process of the run: "
        "sorgui's, its analysis process and Singular.)",
    ]
    print("\n".join(rows), flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("startup", __doc__.splitlines()[0], table)
