"""Benchmark: the whole-process full analysis of published surfaces, as users paste them.

The surfaces are in ``benchmarks/published-surfaces.txt`` (name, source, equation; degrees 2 to
12: surfaces of revolution and others from the SURFER gallery, POV-Ray, MathWorld, textbooks).
Each is analysed by ``python -m sorgui.cli analyze --json EQUATION`` in a new process (the
default full analysis: recognition, real locus, rationality with Singular, parameterizations,
canal surfaces), timed as a whole (wall time, median over ``--repeats``). The table gives the
stage that took longest inside the process and checks the goals of issue 16: degree ≤ 8 under
1 s, degree ≤ 12 under 3 s. Run ``python -m benchmarks.published [--repeats N] [--write]``.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

from benchmarks.report import ROOT, run

SURFACES = Path(__file__).resolve().parent / "published-surfaces.txt"
TIMEOUT = 120.0


def surfaces() -> list[tuple[str, str, str]]:
    """``(name, source, equation)`` of every entry of :data:`SURFACES`."""
    found = []
    for line in SURFACES.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.lstrip().startswith("#"):
            name, source, equation = (part.strip() for part in line.split("|", 2))
            found.append((name, source, equation))
    return found


def whole_process(equation: str, repeats: int) -> tuple[float, dict]:
    """The median wall time of ``sorgui analyze --json`` on ``equation``, and its report."""
    walls, report = [], {}
    for _ in range(repeats):
        start = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-m", "sorgui.cli", "analyze", "--json", "--timeout", str(TIMEOUT), "--", equation],
            capture_output=True,
            text=True,
            cwd=ROOT,
        )
        walls.append(time.perf_counter() - start)
        report = json.loads(done.stdout) if done.stdout.strip() else {"error": done.stderr.strip()}
    return statistics.median(walls), report


def table(repeats: int) -> str:
    rows = [
        "| surface | degree | SOR | whole process (s) | longest stage (s) | goal |",
        "|---|---:|:---:|---:|---|:---:|",
    ]
    met = {8: [0, 0], 12: [0, 0]}
    for name, _source, equation in surfaces():
        seconds, report = whole_process(equation, repeats)
        if "error" in report:
            rows.append(f"| {name} | – | – | {seconds:.2f} | error: {report['error']} | – |")
            continue
        degree = report["degree"]
        timings = report.get("timings", {})
        stage, longest = max(timings.items(), key=lambda item: item[1]) if timings else ("–", 0.0)
        limit = 1.0 if degree <= 8 else 3.0
        ok = seconds < limit and not report.get("unfinished")
        bucket = met[8 if degree <= 8 else 12]
        bucket[0] += ok
        bucket[1] += 1
        unfinished = f", unfinished: {', '.join(report['unfinished'])}" if report.get("unfinished") else ""
        rows.append(
            f"| {name} | {degree} | {'yes' if report['is_sor'] else 'no'} | {seconds:.2f} "
            f"| {stage} {longest:.2f}{unfinished} | {'✓' if ok else '✗'} |"
        )
        print(rows[-1], flush=True)
    rows.append("")
    rows.append(
        f"Within the goal: degree ≤ 8 under 1 s: {met[8][0]} of {met[8][1]}; "
        f"degree 9–12 under 3 s: {met[12][0]} of {met[12][1]}."
    )
    return "\n".join(rows)


if __name__ == "__main__":
    run("published", __doc__.splitlines()[0], table)
