"""Benchmark: the slowest full analyses of degree ≤ 12, as whole processes.

The constructed tails: the surfaces of revolution whose ``P²`` is the rational sextic of
Singular's ``paraPlaneCurve`` example, as ``F(h, ρ) = 0`` and as ``y² + z² = `` the sextic, about
three axes (degree 12), the envelope of spheres on a line with a varying radius
(``tests/data/sphere-envelope.txt``, degree 6), a surface of revolution of degree 12 in
general position and a sphere whose radius² is a 5000-digit integer. Then every surface of the
test corpus (``tests/data/cases.json``, ``tests/data/canal-examples.txt``,
``benchmarks/published-surfaces.txt``) whose degree is at most 12, of which the five slowest
are listed. Each is ``python -m sorgui.cli analyze --json --timeout 120 -f FILE`` in a new
process (the full analysis), wall time, the best of ``--repeats`` for the constructed ones and
one run for the corpus. Run ``python -m benchmarks.tails [--repeats N] [--write]`` from the
repository root.
"""

from __future__ import annotations

import json
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.published import surfaces
from benchmarks.report import ROOT, run
from sorgui.engine.algebra.polys import poly_str
from sorgui.samples import PARAPLANECURVE_SEXTIC, general_position, rational_vector, revolve

DATA = ROOT / "tests" / "data"
SEXTIC = PARAPLANECURVE_SEXTIC
AXES = (((0, 0, 0), (1, 0, 0)), ((1, -2, 3), (2, 1, 2)), ((0, 0, 0), (1, 1, 1)))
GOAL = 10.0
HUGE = "".join(random.Random(1).choice("123456789") for _ in range(5000))
"""A 5000-digit constant, not a square: sympy tests the cofactor of each square root's radicand
for primality (48 s in pure Python, before sorgui handed that test to flint)."""


def constructed() -> list[tuple[str, str]]:
    cases = []
    for point, direction in AXES:
        for distance in (False, True):
            f = revolve(SEXTIC, rational_vector(point), rational_vector(direction), axis_distance=distance)
            form = "y² + z² = the sextic" if distance else "F(h, ρ) = 0"
            cases.append((f"paraPlaneCurve's sextic, {form}, axis {point} + t·{direction}", poly_str(f)))
    cases.append(("spheres on a line, radius 1 + t² (sphere-envelope.txt)", (DATA / "sphere-envelope.txt").read_text()))
    cases.append(("a surface of revolution of degree 12 in general position", poly_str(general_position(12, 5))))
    cases.append(("a sphere whose radius² is a 5000-digit integer (hostile input)", f"x^2 + y^2 + z^2 - {HUGE}"))
    return cases


def corpus() -> list[tuple[str, str]]:
    cases = [(name, equation) for name, _source, equation in surfaces()]
    cases += [(case["name"], case["input"]) for case in json.loads((DATA / "cases.json").read_text(encoding="utf-8"))]
    name = None
    for line in (DATA / "canal-examples.txt").read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if line.startswith("## "):
            name = line[3:].split("|")[0].strip()
        elif line and not line.startswith("#") and name:
            cases.append((name, line))
            name = None
    return cases


def whole(text: str, folder: str) -> tuple[float, dict]:
    path = Path(folder, "equation.txt")
    path.write_text(text, encoding="utf-8")
    start = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "sorgui.cli", "analyze", "--json", "--timeout", "120", "-f", str(path)],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    wall = time.perf_counter() - start
    try:
        return wall, json.loads(done.stdout)
    except ValueError:
        return wall, {}


def slowest(report: dict) -> str:
    timings = report.get("timings") or {}
    if not timings:
        return "–"
    stage = max(timings, key=timings.get)
    return f"{stage} {timings[stage]:.2f}"


def table(repeats: int) -> str:
    rows = [
        "| surface | degree | whole process (s) | slowest stage (s) | unfinished |",
        "|---|---:|---:|---|---|",
    ]
    with tempfile.TemporaryDirectory() as folder:
        for name, text in constructed():
            runs = [whole(text, folder) for _ in range(repeats)]
            wall, report = min(runs, key=lambda r: r[0])
            rows.append(
                f"| {name} | {report.get('degree', '?')} | {wall:.2f} | {slowest(report)} "
                f"| {', '.join(report.get('unfinished', [])) or '–'} |"
            )
            print(rows[-1], flush=True)
        measured = []
        for name, text in corpus():
            wall, report = whole(text, folder)
            if report.get("degree", 99) <= 12:
                measured.append((wall, name, report))
    measured.sort(key=lambda m: m[0], reverse=True)
    over = sum(1 for wall, _, _ in measured if wall > GOAL)
    rows += [
        "",
        f"The test corpus: {len(measured)} surfaces of degree ≤ 12, {over} over {GOAL:.0f} s; the five slowest:",
        "",
        "| surface | degree | whole process (s) | slowest stage (s) |",
        "|---|---:|---:|---|",
    ]
    for wall, name, report in measured[:5]:
        rows.append(f"| {name} | {report.get('degree')} | {wall:.2f} | {slowest(report)} |")
    print("\n".join(rows[-8:]), flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("tails", __doc__.splitlines()[0], table)
