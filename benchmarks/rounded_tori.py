"""Benchmark: rounded tori in general position, a whole ``sorgui analyze`` process each.

The ring torus ``(|p − c|² + 3)² = 16·(distance to the axis)²`` (radii 2 and 1) about the axis
of the tests' generic rounded torus and about random axes (seeded), and a torus of radii 3.7 and
0.45, printed with 10 significant digits as a CAD system prints it. The answer includes the
whole exact analysis of the nearest exact surface (docs/math.md §8.5): its axis is rational with
coordinates of 20 digits and more, and a torus's profile is two circles (Table 1's row 1); a
surface that is not quite a torus has a ``P²`` whose conic may need a point from Legendre's
equation (docs/math.md §5, "A point of a conic"). Each row: the wall time of the process (median of
``--repeats``), whether the nearest surface is within the rounding, its rationality status and
Table 1 row. Run ``python -m benchmarks.rounded_tori [--repeats N] [--write]`` from the
repository root.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from benchmarks.report import process_times, run
from sorgui.engine.rounded import dense
from sorgui.samples import printed

SEEDS = tuple(range(1, 13)) + (42,)
"""Random axes; the torus of seed 42 took 2.6 s before its conic's point came from Legendre's equation."""
DIGITS = 10
TURNED = np.array([np.sin(0.4) * np.sin(0.7), -np.cos(0.4) * np.sin(0.7), np.cos(0.7)])
"""The axis of the generic rounded torus of the tests (``tests/engine/test_approximate.py``): the
third column of Rz(0.4)·Rx(0.7). It took 10.9 s, its nearest surface's rationality undecided."""


DECIMAL_RADII = (
    np.array([0.3, -0.5, 0.81]) / np.linalg.norm([0.3, -0.5, 0.81]),
    np.array([0.2, -0.1, 0.4]),
    (3.7, 0.45),
)
"""A torus of decimal radii about a rational axis: its constant ``(R² − r²)²``, snapped on its
own, was not a torus's (10.9 s, its nearest surface's rationality undecided)."""


def random_axis(seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A random unit direction and a point (the origin for even seeds)."""
    rng = np.random.default_rng(seed)
    direction = rng.normal(size=3)
    direction /= np.linalg.norm(direction)
    point = np.round(rng.uniform(-1, 1, size=3), 1) if seed % 2 else np.zeros(3)
    return direction, point


def rounded_torus(
    direction: np.ndarray,
    point: np.ndarray,
    radii: tuple[float, float] = (2.0, 1.0),
    factor: float = 1.0,
    digits: int = DIGITS,
) -> str:
    """The torus of ``radii`` (major, minor) about the line through ``point`` along the unit
    ``direction``, its equation times ``factor``, printed with ``digits`` significant digits."""
    return printed(factor * torus(direction, point, radii), digits)


def torus(direction: np.ndarray, point: np.ndarray, radii: tuple[float, float]) -> np.ndarray:
    """The coefficients, in floats, of the torus of ``radii`` (major, minor) about the line
    through ``point`` along the unit ``direction``."""
    one = dense.from_terms({(0, 0, 0): 1.0}, 4)
    rho = dense.squared_distance(point)
    h = dense.linear_form(direction, point)
    h2 = dense.times(dense.times(one, h), h)
    r1 = dense.times(one, rho)
    r2 = dense.times(r1, rho)
    big, k = radii[0] ** 2, radii[0] ** 2 - radii[1] ** 2
    # (ρ + k)² − 4R²·(ρ − h²) = ρ² + (2k − 4R²)ρ + 4R²h² + k²; radii 2, 1: ρ² − 10ρ + 16h² + 9
    result: np.ndarray = r2 + (2 * k - 4 * big) * r1 + 4 * big * h2 + k * k * one
    return result


def table(repeats: int) -> str:
    rows = [
        "| torus | whole process (s) | nearest surface within the rounding | its rationality | Table 1 row |",
        "|---|---:|---|---|---:|",
    ]
    cases = [("the tests' axis", rounded_torus(TURNED, np.zeros(3)))]
    cases += [(f"seed {seed}", rounded_torus(*random_axis(seed))) for seed in SEEDS]
    cases.append(("radii 3.7 and 0.45", rounded_torus(*DECIMAL_RADII)))
    with tempfile.TemporaryDirectory() as folder:
        for name, text in cases:
            path = Path(folder, "torus.txt")
            path.write_text(text + "\n", encoding="utf-8")
            wall, _, out = process_times(
                [sys.executable, "-m", "sorgui.cli", "analyze", "--json", "-f", str(path)], repeats
            )
            nearest = json.loads(out)["approximate"]["nearest"]
            rationality = nearest["analysis"]["rationality"] if nearest and nearest["analysis"] else None
            status = "no nearest surface" if rationality is None else rationality["status"]
            row = "-" if rationality is None or rationality["table_row"] is None else rationality["table_row"]
            within = "-" if nearest is None else ("yes" if nearest["within_rounding"] else "no")
            rows.append(f"| {name} | {wall:.2f} | {within} | {status} | {row} |")
            print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("rounded-tori", __doc__.splitlines()[0], table)
