"""Benchmark: ``sorgui analyze --each-line --jobs 2`` on 100 equations of degree ≤ 8.

The equations (``benchmarks/batch-100.txt``, written by ``--generate`` and kept in the
repository) are 20 classic surfaces as they are published (spheres, tori, cones, quadrics,
Steiner's Roman surface, Cayley's cubic, Goursat's and Kummer-like quartics, the heart surface,
Dupin cyclides, blends), 40 surfaces of revolution in general position (random profiles, random
rational axes, rotated and shifted) and 40 random polynomials of degree 2…8, which have no
symmetry. Every analysis is complete (recognition, rationality with Singular,
parameterizations). Run ``python -m benchmarks.batch [--repeats N] [--write]`` from the
repository root: it times the whole ``sorgui`` process (wall time).
"""

from __future__ import annotations

import json
import random
import subprocess
import sys
import time
from pathlib import Path

from sympy.polys.domains import QQ

from benchmarks.report import ROOT, run
from sorgui.engine.algebra.polys import poly_str
from sorgui.samples import move, quaternion_rotation, rational_vector, revolve

EQUATIONS = Path(__file__).resolve().parent / "batch-100.txt"
JOBS = 2

CLASSIC = [
    ("sphere", "x^2 + y^2 + z^2 - 1"),
    ("shifted sphere", "(x - 1/2)^2 + (y + 3)^2 + z^2 = 4"),
    ("torus", "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)"),
    ("spindle torus", "(x^2 + y^2 + z^2 + 1 - 4)^2 - 4(x^2 + y^2)"),
    ("cone", "x^2 + y^2 - z^2"),
    ("cylinder", "x^2 + y^2 - 1"),
    ("paraboloid", "z = x^2 + y^2"),
    ("hyperboloid of one sheet", "x^2 + y^2 - z^2 - 1"),
    ("hyperboloid of two sheets", "-x^2 - y^2 + z^2 - 1"),
    ("ellipsoid", "x^2/4 + y^2/9 + z^2 - 1"),
    ("oblate spheroid", "x^2 + y^2 + 4z^2 - 4"),
    ("Steiner's Roman surface", "x^2 y^2 + y^2 z^2 + z^2 x^2 - x y z"),
    ("Cayley's nodal cubic", "4(x^3 + y^3 + z^3 + 1) - (x + y + z + 1)^3"),
    ("Goursat quartic", "x^4 + y^4 + z^4 - (x^2 + y^2 + z^2) + 1/4"),
    ("tanglecube", "x^4 - 5x^2 + y^4 - 5y^2 + z^4 - 5z^2 + 11.8"),
    ("heart surface", "(x^2 + 9/4 y^2 + z^2 - 1)^3 - x^2 z^3 - 9/80 y^2 z^3"),
    ("Dupin cyclide (ring)", "(x^2 + y^2 + z^2 - 4 + 1)^2 - 4(2x - 1)^2 - 4*3 y^2"),
    ("paper Example 1", "y^2 + z^2 = x^3 + 3x^2 - 2x"),
    ("sphere-cylinder blend", "(x^2 + y^2 - 1)(x^2 + y^2 + z^2 - 4) - 1/10"),
    (
        "Kummer-like quartic",
        "(x^2 + y^2 + z^2 - 2)^2 - 3(1 - z - sqrt(2) x)(1 - z + sqrt(2) x)(1 + z + sqrt(2) y)(1 + z - sqrt(2) y)/3",
    ),
]


def surface_of_revolution(rng: random.Random) -> str:
    """``F(s, w) = 0`` with ``s`` along a random rational axis and ``w`` the squared distance,
    ``F`` random of degree ≤ 4 in ``(s, w)`` (so ``f`` has degree ≤ 8), moved rigidly."""
    degree = rng.randint(2, 4)
    profile = {
        (i, j): rng.randint(-6, 6)
        for i in range(degree + 1)
        for j in range(degree + 1 - i)
        if (i + 2 * j <= 8) and rng.random() < 0.6
    }
    profile[(0, 1)] = 1
    profile[(degree, 0)] = rng.choice((-1, 1))
    axis = rational_vector((rng.randint(1, 3), rng.randint(-3, 3), rng.randint(-3, 3)))
    point = rational_vector((QQ(rng.randint(-4, 4), 2), rng.randint(-2, 2), rng.randint(-2, 2)))
    f = revolve(profile, point, axis, axis_distance=True)
    q = [rng.randint(-2, 2) for _ in range(4)]
    if not any(q):
        q = [1, 0, 0, 0]
    return poly_str(move(f, quaternion_rotation(q), rational_vector((rng.randint(-2, 2), 0, QQ(1, 3)))))


def random_polynomial(rng: random.Random) -> str:
    """A sparse random polynomial of degree 2…8 in x, y, z with small integer coefficients."""
    degree = rng.randint(2, 8)
    terms = [
        f"{rng.randint(-9, 9)}*x^{a}*y^{b}*z^{c}"
        for a in range(degree + 1)
        for b in range(degree + 1 - a)
        for c in range(degree + 1 - a - b)
        if rng.random() < 0.25
    ]
    terms.append(f"x^{degree}")
    return " + ".join(terms)


def generate() -> None:
    """Write the 100 equations (deterministic: seed 2026)."""
    rng = random.Random(2026)
    lines = ["# 100 equations of degree <= 8 for benchmarks/batch.py (written by --generate)"]
    lines += [f"{text}  # {name}" for name, text in CLASSIC]
    lines += ["# surfaces of revolution in general position"] + [surface_of_revolution(rng) for _ in range(40)]
    lines += ["# random polynomials"] + [random_polynomial(rng) for _ in range(40)]
    EQUATIONS.write_text("\n".join(lines) + "\n", encoding="utf-8")


def table(repeats: int) -> str:
    rows = [
        "| equations | jobs | wall (s) | analysed | bad lines | surfaces of revolution |",
        "|---|---|---|---|---|---|",
    ]
    times, answers = [], []
    for _ in range(repeats):
        start = time.perf_counter()
        out = subprocess.run(
            [sys.executable, "-m", "sorgui.cli", "analyze", "--each-line", "--jobs", str(JOBS), "-f", str(EQUATIONS)],
            capture_output=True,
            text=True,
            cwd=ROOT,
            check=False,
        )
        times.append(time.perf_counter() - start)
        answers = [json.loads(line) for line in out.stdout.splitlines()]
    errors = sum("error" in a for a in answers)
    sors = sum(bool(a.get("is_sor")) for a in answers)
    rows.append(
        f"| {len(answers)} | {JOBS} | {min(times):.1f} (min of {repeats}) | {len(answers) - errors} "
        f"| {errors} | {sors} |"
    )
    print("\n".join(rows), flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    if "--generate" in sys.argv:
        generate()
    else:
        run("batch", __doc__.splitlines()[0], table)
