"""Benchmark: the full analysis (recognition + rationality + parameterizations) with real Singular.

Cases: the paper's Example 1/2 and surfaces of revolution of degree 4…12 in general position
(``tube``: ``(1 + x^(d-2))·(y² + z²) = g(x)``, whose ``P²`` is rational, so every stage runs). Run
``python benchmarks/analysis.py [--write]``; ``--write`` updates ``docs/benchmarks.md``.
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
import time
from pathlib import Path

from sympy.polys.domains import QQ

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from sorgui.engine.analysis import analyze, analyze_polynomial  # noqa: E402
from sorgui.examples import example_text  # noqa: E402
from tests.engine.helpers import move, quaternion_rotation, rational_vector, revolve  # noqa: E402

DEGREES = (4, 6, 8, 10, 12)
MARK_START = "<!-- analysis:start -->"
MARK_END = "<!-- analysis:end -->"


def tube(degree: int, seed: int = 2):
    """``(1 + s^(d-2))·w = g(s)`` with a random ``g`` of degree ``d``, in general position."""
    rng = random.Random(seed)
    profile = {(0, 1): 1, (degree - 2, 1): 1} | {(i, 0): rng.randint(-5, 5) for i in range(degree)}
    profile[(degree, 0)] = -1
    f = revolve(profile, rational_vector((QQ(1, 2), -1, 2)), rational_vector((2, -1, 3)))
    return move(f, quaternion_rotation((2, 1, -1, 1)), rational_vector((1, QQ(-1, 3), 0)))


def timed(run, repeats: int):
    """Median wall time and the last result of ``run()``."""
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def table(repeats: int) -> str:
    rows = ["| case | degree | Table 1 row | parameterizations | total (s) | stages (s) |",
            "|---|---:|---:|---:|---:|---|"]
    cases = [("paper Example 1/2", lambda: analyze(example_text("paper-example-1")))]
    cases += [(f"general position, degree {d}", (lambda d=d: analyze_polynomial(tube(d)))) for d in DEGREES]
    for name, run in cases:
        seconds, result = timed(run, repeats)
        stages = ", ".join(f"{n} {s:.3f}" for n, s in result.timings)
        row = result.rationality.table_row if result.rationality else "-"
        rows.append(f"| {name} | {result.recognition.degree} | {row} | {len(result.parametrizations)} "
                    f"| {seconds:.3f} | {stages} |")
        print(rows[-1], flush=True)
    return "\n".join(rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--write", action="store_true", help="update docs/benchmarks.md")
    args = parser.parse_args()
    result = table(args.repeats)
    if args.write:
        path = ROOT / "docs" / "benchmarks.md"
        doc = path.read_text(encoding="utf-8")
        start, end = doc.index(MARK_START) + len(MARK_START), doc.index(MARK_END)
        path.write_text(doc[:start] + "\n" + result + "\n" + doc[end:], encoding="utf-8")


if __name__ == "__main__":
    main()
