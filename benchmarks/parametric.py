"""Benchmark: deciding a parametrization (docs/math.md §13), inside one process.

The maps: a surface of revolution of bidegree (4, 2) (a quartic profile turned by
``((1 − t²), 2t)/(1 + t²)``) moved by a rational rotation and a translation, exact and printed
with 10 digits; a random bicubic polynomial patch (``samples.bicubic_patch``). For each: reading
the text, the exact decision from the map (the symmetry algebra of the normal lines, the apex
and cylinder directions, the cross-check of the profile), the least-squares systems of rounded
input, the implicit equation when the decision gives one (a flint resultant), and the whole
``analyze(text, recognition_only=True)`` (which also recognises the implicit equation; no
Singular). Goal: each map decided in under 0.5 s. Each figure is the median over ``--repeats``
runs (after one warm-up run that loads sympy). Run ``python -m benchmarks.parametric
[--repeats N] [--write]`` from the repository root.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from benchmarks.report import median_time, run
from sorgui.engine import analyze
from sorgui.engine.parametric.detect import conicity, parametric_symmetry, profile_is_a_curve
from sorgui.engine.parametric.implicit import implicit_equation
from sorgui.engine.parametric.nearly import nearly, printed_tolerance
from sorgui.engine.parametric_parsing import parse_parametrization
from sorgui.samples import bicubic_patch, map_text, quaternion_rotation, revolved_patch, rotation

RADIUS = {0: 2, 1: 1, 2: Fraction(1, 3), 3: -1, 4: Fraction(1, 5)}
HEIGHT = {0: 1, 1: -1, 2: 1, 3: Fraction(1, 2), 4: Fraction(-1, 7)}


def maps() -> dict[str, str]:
    """The benchmark's maps by name."""
    exact = revolved_patch(RADIUS, HEIGHT, quaternion_rotation((1, 2, -2, 4)), (1, Fraction(-1, 2), 3))
    turned = rotation(np.array([0.9, 0.3, -0.2, 0.4])).tolist()
    printed = revolved_patch(RADIUS, HEIGHT, turned, (0.3, -1.2, 0.5), digits=10)
    return {
        "SOR, bidegree (4, 2), rational axis": map_text(exact),
        "SOR, bidegree (4, 2), printed with 10 digits": map_text(printed),
        "bicubic patch": map_text(bicubic_patch(seed=3)),
    }


def decide(text: str) -> str:
    """Read and decide (the least squares too for decimals); the kind the map has."""
    surface = parse_parametrization(text).map
    symmetry = parametric_symmetry(surface)
    conicity(surface)
    if symmetry.axis_point is not None:
        assert profile_is_a_curve(surface, symmetry.axis_point, symmetry.axis_direction)
    tolerance = printed_tolerance(text)
    if tolerance is not None and not symmetry.is_sor:
        approximation, _ = nearly(surface, tolerance, "input")
        return "nearly " + str(approximation.kind) if approximation.near_sor else symmetry.kind
    return symmetry.kind


def table(repeats: int) -> str:
    """The markdown table of the median times per map and step."""
    rows = [
        "| map | text | read (s) | decided (s) | implicit equation (s) | analyze, recognition only (s) | answer |",
        "|---|---:|---:|---:|---:|---:|---|",
    ]
    analyze(next(iter(maps().values())), recognition_only=True)  # load sympy and the engine once
    for name, text in maps().items():
        read, _ = median_time(lambda text=text: parse_parametrization(text), repeats)
        decided, answer = median_time(lambda text=text: decide(text), repeats)
        surface = parse_parametrization(text).map
        symmetry, cones = parametric_symmetry(surface), conicity(surface)
        implicit = "–"
        if symmetry.kind != "none" or cones.kind != "none":
            seconds, _ = median_time(
                lambda m=surface, s=symmetry, c=cones: implicit_equation(m, s, c, timeout=60), repeats
            )
            implicit = f"{seconds:.3f}"
        whole, _ = median_time(lambda text=text: analyze(text, recognition_only=True, timeout=60), repeats)
        rows.append(
            f"| {name} | {len(text)} chars | {read:.3f} | {decided:.3f} | {implicit} | {whole:.3f} | {answer} |"
        )
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("parametric", __doc__, table)
