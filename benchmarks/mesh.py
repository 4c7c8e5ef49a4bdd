"""Benchmark: the mesh of the paper's Example 1 (degree 6) on a 150³ grid.

Run as ``python benchmarks/mesh.py [--runs N] [--resolution R]``. Prints a markdown table with
the minimum and median wall time of each stage over several runs:

* sampling: ``f`` on the offset grid (nested Horner, ``sorgui.render.sampling``);
* contouring: ``vtkFlyingEdges3D``, mapping the points to world coordinates, numpy arrays;
* finishing: one Newton step per vertex, orientation by ``∇f`` and the normals;
* total: ``surface_mesh`` end to end (measured separately).

The goal is a total under 1 s on a 2-core machine. The polynomial is read from the shared
corpus and expanded with sympy: acceptable here, on a trusted constant, and never in ``sorgui/``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import sympy
from vtkmodules.vtkCommonCore import vtkSMPTools

from sorgui.render.geometry import ClipSphere
from sorgui.render.mesh import (
    enable_vtk_threads,
    finish_mesh,
    sample_surface,
    sampling_grid,
    surface_mesh,
    zero_level_triangles,
)

CASES = Path(__file__).resolve().parents[2] / "shared" / "corpus" / "cases.json"
CASE = "paper-example-1"
# The axis passes through (3/5, -4/5, 0) with direction (4, 3, 0). The surface is unbounded
# (the profile's P² is (-t³+t, (t+1)⁴+4)); this box around the axis point shows its waist.
BOUNDS = (0.6 - 8, 0.6 + 8, -0.8 - 8, -0.8 + 8, -8.0, 8.0)


def example_terms() -> list[tuple[tuple[int, int, int], float]]:
    """The expanded polynomial of the case as plain terms (sympy on a trusted constant)."""
    text = next(c["input"] for c in json.loads(CASES.read_text()) if c["name"] == CASE)
    x, y, z = sympy.symbols("x y z")
    poly = sympy.Poly(sympy.sympify(text.replace("^", "**")), x, y, z)
    return [(monomial, float(c)) for monomial, c in poly.terms()]


def timed(fn: Callable[[], object], runs: int) -> tuple[list[float], object]:
    """Wall times of ``runs`` calls of ``fn`` and the last result."""
    times, result = [], None
    for _ in range(runs):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return times, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--resolution", type=int, default=150)
    args = parser.parse_args()

    terms = example_terms()
    enable_vtk_threads()
    grid = sampling_grid(BOUNDS, args.resolution)
    surface_mesh(terms, BOUNDS, args.resolution)  # warm up: imports, BLAS and VTK threads

    sampling, values = timed(lambda: sample_surface(terms, grid), args.runs)
    contouring, (points, triangles) = timed(lambda: zero_level_triangles(values, grid), args.runs)
    finishing, _ = timed(lambda: finish_mesh(terms, points, triangles, grid), args.runs)
    total, mesh = timed(lambda: surface_mesh(terms, BOUNDS, args.resolution), args.runs)
    clip = ClipSphere((0.6, -0.8, 0.0), 7.0)
    clipped_total, clipped = timed(
        lambda: surface_mesh(terms, BOUNDS, args.resolution, clip=clip), args.runs
    )

    print(f"# Mesh benchmark: `{CASE}` (degree 6, {len(terms)} terms)\n")
    print(
        f"grid {grid.dims[0]}×{grid.dims[1]}×{grid.dims[2]} = {int(np.prod(grid.dims)):,} nodes, "
        f"spacing {grid.spacing:.4g}; {mesh.n_points:,} points, {mesh.n_faces:,} triangles; "
        f"{args.runs} runs; VTK SMP backend {vtkSMPTools().GetBackend()} "
        f"({vtkSMPTools().GetEstimatedNumberOfThreads()} threads), {os.cpu_count()} CPUs, "
        f"{platform.processor() or platform.machine()}\n"
    )
    print("| stage | min (ms) | median (ms) |")
    print("|---|---:|---:|")
    rows = [
        ("sampling (Horner on the tensor grid)", sampling),
        ("contouring (vtkFlyingEdges3D)", contouring),
        ("finishing (Newton step, orientation, normals)", finishing),
        ("**total** `surface_mesh`", total),
        (f"total with a clip sphere ({clipped.n_faces:,} triangles)", clipped_total),
    ]
    for name, times in rows:
        print(f"| {name} | {1000 * min(times):.1f} | {1000 * statistics.median(times):.1f} |")
    verdict = "met" if statistics.median(total) < 1.0 else "NOT met"
    print(f"\nGoal (< 1 s for the total): {verdict}.")


if __name__ == "__main__":
    main()
