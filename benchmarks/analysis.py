"""Benchmark: the full analysis (recognition + rationality + parameterizations) with real Singular.

Cases: the paper's Example 1/2 and surfaces of revolution of degree 4…12 in general position
(``(1 + s^(d-2))·w = g(s)``, whose ``P²`` is rational, so every stage runs). Run
``python -m benchmarks.analysis [--write]``; ``--write`` updates ``docs/benchmarks.md``.
"""

from __future__ import annotations

import random

from sympy.polys.domains import QQ

from benchmarks.report import median_time, run
from sorgui.engine.analysis import analyze, analyze_polynomial
from sorgui.examples import example_text
from sorgui.samples import move, quaternion_rotation, rational_vector, revolve

DEGREES = (4, 6, 8, 10, 12)


def tube(degree: int, seed: int = 2):
    """``(1 + s^(d-2))·w = g(s)`` with a random ``g`` of degree ``d``, in general position."""
    rng = random.Random(seed)
    profile = {(0, 1): 1, (degree - 2, 1): 1} | {(i, 0): rng.randint(-5, 5) for i in range(degree)}
    profile[(degree, 0)] = -1
    f = revolve(profile, rational_vector((QQ(1, 2), -1, 2)), rational_vector((2, -1, 3)), axis_distance=True)
    return move(f, quaternion_rotation((2, 1, -1, 1)), rational_vector((1, QQ(-1, 3), 0)))


def table(repeats: int) -> str:
    """The markdown table: total and per-stage times of each case."""
    rows = [
        "| case | degree | Table 1 row | parameterizations | total (s) | stages (s) |",
        "|---|---:|---:|---:|---:|---|",
    ]
    cases = [("paper Example 1/2", lambda: analyze(example_text("paper-example-1")))]
    cases += [(f"general position, degree {d}", (lambda d=d: analyze_polynomial(tube(d)))) for d in DEGREES]
    for name, analysis in cases:
        seconds, result = median_time(analysis, repeats)
        stages = ", ".join(f"{n} {s:.3f}" for n, s in result.timings)
        row = result.rationality.table_row if result.rationality else "-"
        rows.append(
            f"| {name} | {result.recognition.degree} | {row} | {len(result.parametrizations)} "
            f"| {seconds:.3f} | {stages} |"
        )
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("analysis", __doc__, table)
