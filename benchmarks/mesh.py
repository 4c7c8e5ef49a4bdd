"""Benchmark: the mesh of the paper's Example 1 (degree 6) on a 150³ grid.

Run as ``python -m benchmarks.mesh [--runs N] [--resolution R] [--write]``. Prints a markdown table with
the minimum and median wall time of each stage over several runs:

* sampling: ``f`` on the offset grid (nested Horner, ``sorgui.render.sampling``);
* contouring: ``vtkFlyingEdges3D``, mapping the points to world coordinates, numpy arrays;
* finishing: one Newton step per vertex, orientation by ``∇f`` and the normals;
* total: ``surface_mesh`` end to end (measured separately).

The goal is a total under 1 s on a 2-core machine; ``--write`` puts the table into
``docs/benchmarks.md``.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics

import numpy as np
from vtkmodules.vtkCommonCore import vtkSMPTools

from benchmarks.report import wall_times, write_section
from sorgui.engine.parsing import parse_polynomial
from sorgui.examples import example_text
from sorgui.render.geometry import ClipSphere
from sorgui.render.mesh import (
    enable_vtk_threads,
    finish_mesh,
    sample_surface,
    sampling_grid,
    surface_mesh,
    zero_level_triangles,
)

CASE = "paper-example-1"
# The axis passes through (3/5, -4/5, 0) with direction (4, 3, 0). The surface is unbounded
# (the profile's P² is (-t³+t, (t+1)⁴+4)); this box around the axis point shows its waist.
BOUNDS = (0.6 - 8, 0.6 + 8, -0.8 - 8, -0.8 + 8, -8.0, 8.0)


def example_terms() -> list[tuple[tuple[int, int, int], float]]:
    """The polynomial of the example as plain float terms."""
    f = parse_polynomial(example_text(CASE)).polynomial
    return [(monomial, float(c)) for monomial, c in f.terms()]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--resolution", type=int, default=150)
    parser.add_argument("--write", action="store_true", help="update docs/benchmarks.md")
    args = parser.parse_args()

    terms = example_terms()
    enable_vtk_threads()
    grid = sampling_grid(BOUNDS, args.resolution)
    surface_mesh(terms, BOUNDS, args.resolution)  # warm up: imports, BLAS and VTK threads

    sampling, values = wall_times(lambda: sample_surface(terms, grid), args.runs)
    contouring, (points, triangles) = wall_times(lambda: zero_level_triangles(values, grid), args.runs)
    finishing, _ = wall_times(lambda: finish_mesh(terms, points, triangles, grid), args.runs)
    total, mesh = wall_times(lambda: surface_mesh(terms, BOUNDS, args.resolution), args.runs)
    clip = ClipSphere((0.6, -0.8, 0.0), 7.0)
    clipped_total, clipped = wall_times(lambda: surface_mesh(terms, BOUNDS, args.resolution, clip=clip), args.runs)

    lines = [
        f"`{CASE}` (degree 6, {len(terms)} terms): grid {grid.dims[0]}×{grid.dims[1]}×{grid.dims[2]} "
        f"= {int(np.prod(grid.dims)):,} nodes, "
        f"spacing {grid.spacing:.4g}; {mesh.n_points:,} points, {mesh.n_faces:,} triangles; "
        f"{args.runs} runs; VTK SMP backend {vtkSMPTools().GetBackend()} "
        f"({vtkSMPTools().GetEstimatedNumberOfThreads()} threads), {os.cpu_count()} CPUs, "
        f"{platform.processor() or platform.machine()}",
        "",
        "| stage | min (ms) | median (ms) |",
        "|---|---:|---:|",
    ]
    rows = [
        ("sampling (Horner on the tensor grid)", sampling),
        ("contouring (vtkFlyingEdges3D)", contouring),
        ("finishing (Newton step, orientation, normals)", finishing),
        ("**total** `surface_mesh`", total),
        (f"total with a clip sphere ({clipped.n_faces:,} triangles)", clipped_total),
    ]
    for name, times in rows:
        lines.append(f"| {name} | {1000 * min(times):.1f} | {1000 * statistics.median(times):.1f} |")
    verdict = "met" if statistics.median(total) < 1.0 else "NOT met"
    lines.append(f"\nGoal (< 1 s for the total): {verdict}.")
    print("\n".join(lines))
    if args.write:
        write_section("mesh", "\n".join(lines))


if __name__ == "__main__":
    main()
