"""Benchmark: the real points of a surface of revolution (docs/math.md §3.4), stage "real locus".

Cases: the recognition benchmark's surfaces in general position (degree 4…30, settled by the
first look along lines), and surfaces whose real part is thin, far, empty, a curve or points
(settled by the exact steps: discriminant, Gröbner bases, Sturm–Tarski). Only the real-locus
stage is timed (the recognition is done once beforehand). Run from the repository root as
``python -m benchmarks.real_locus [--repeats N] [--write]``.
"""

from __future__ import annotations

from benchmarks.recognition import surface
from benchmarks.report import median_time, run
from sorgui.engine.algebra.polys import Poly, field_name
from sorgui.engine.parsing import parse_polynomial
from sorgui.engine.recognition.recognize import recognize
from sorgui.engine.revolution.real_locus import real_locus

DEGREES = (4, 8, 12, 16, 20, 25, 30)

SPECIAL = (
    ("thin spindle torus about z = 5", "(x^2+y^2+(z-5)^2+1/1000000-4/1000000)^2-4/1000000(x^2+y^2)"),
    ("torus of radii 1000 and 1", "(x^2+y^2+(z-5)^2+1000000-1)^2-4000000(x^2+y^2)"),
    ("empty torus", "(x^2+y^2+z^2+3)^2+16(x^2+y^2)"),
    ("a circle", "(x^2+y^2+z^2-5)^2+z^2"),
    ("two points", "x^2+y^2+(z^2-1)^2"),
    ("two circles and a point, degree 12", "((x^2+y^2-1)^2+z^2)*((x^2+y^2-4)^2+z^2)*(x^2+y^2+(z-3)^2)"),
    ("A² + B² = 0, degree 12", "(z^3-2z(x^2+y^2)+(x^2+y^2)^2-3)^2+(z^2(x^2+y^2)-(x^2+y^2)+1)^2"),
    ("a circle over QQ(√2, √3)", "(x^2+y^2-sqrt(2))^2+(z-sqrt(3))^2"),
)


def timed_row(name: str, f: Poly, repeats: int) -> str:
    """One table row: the median time of the real-locus stage of ``f`` and its answer."""
    _, symmetry, profile = recognize(f)
    seconds, locus = median_time(lambda: real_locus(f, symmetry, profile), repeats)
    counts = ", ".join(
        f"{k} {v}"
        for k, v in (("points", locus.points), ("circles", locus.circles), ("axis line", locus.axis_line))
        if v
    )
    return f"| {name} | {field_name(f.ring.domain)} | {locus.kind}{f' ({counts})' if counts else ''} | {seconds:.3f} |"


def table(repeats: int) -> str:
    """The markdown table: case, field, answer, median time of the stage."""
    rows = ["| case | field | real points | real locus (s) |", "|---|---|---|---:|"]
    cases = [(f"general position, degree {d}", surface(d)) for d in DEGREES]
    cases += [(name, parse_polynomial(text).polynomial) for name, text in SPECIAL]
    for name, f in cases:
        rows.append(timed_row(name, f, repeats))
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("real-locus", __doc__, table)
