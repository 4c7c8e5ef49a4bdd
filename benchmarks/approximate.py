"""Benchmark: rounded input (docs/math.md §8).

For each degree, a random surface of revolution about an axis turned by a random unit
quaternion in floats (an irrational rotation) is printed with 10 significant digits, as a CAD
system prints it. Timed inside the process, median of the repeats:

* **recognition** — the approximate recognition with axis refinement: the rounding bounds
  from the digits, the float system (★), the weighted fit and the Gauss–Newton axis;
* **snapped** — the same plus the snapping to the nearest exact surface and the deviation of
  the zero sets;
* **whole report** — ``analyze`` of the printed text: exact recognition, the approximate stage
  and the whole exact analysis of the nearest exact surface (Singular included).

Run ``python -m benchmarks.approximate [--repeats N] [--write]`` from the repository root.
"""

from __future__ import annotations

import numpy as np

from benchmarks.report import median_time, run
from sorgui.engine.analysis import analyze
from sorgui.engine.parsing import parse_polynomial
from sorgui.engine.rounded.approximate import approximate_symmetry, rounding_of
from sorgui.samples import printed, random_sor

DEGREES = (4, 6, 8, 10, 12, 16, 20)
WHOLE_REPORT = (4, 6)
DIGITS = 10


def rounded_surface(degree: int, seed: int = 3) -> str:
    """A printed rounded surface of revolution of the given degree."""
    array, _, _ = random_sor(np.random.default_rng(seed + degree), degree)
    return printed(array, DIGITS)


def approximate(text: str, snap: bool):
    """The approximate recognition, checked: the benchmark only counts correct answers."""
    f = parse_polynomial(text).polynomial
    rounding, _ = rounding_of(f, text, None)
    result = approximate_symmetry(f, rounding, snap_exact=snap).approximation
    assert result.near_sor and result.kind == "revolution"
    assert not snap or result.nearest is not None
    return result


def whole_report(text: str):
    analysis = analyze(text)
    assert analysis.approximate.near_sor and analysis.approximate.nearest.analysis is not None
    return analysis


def table(repeats: int) -> str:
    """The markdown table of median times per degree."""
    rows = ["| degree | terms | recognition (s) | snapped (s) | whole report (s) |", "|---:|---:|---:|---:|---:|"]
    for degree in DEGREES:
        text = rounded_surface(degree)
        recognition = median_time(lambda text=text: approximate(text, False), repeats)[0]
        snapped = median_time(lambda text=text: approximate(text, True), repeats)[0]
        report = (
            f"{median_time(lambda text=text: whole_report(text), repeats)[0]:.3f}" if degree in WHOLE_REPORT else "-"
        )
        terms = len(parse_polynomial(text).polynomial)
        rows.append(f"| {degree} | {terms} | {recognition:.3f} | {snapped:.3f} | {report} |")
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("approximate", __doc__, table)
