"""Benchmark: typesetting the results pane (goal: under 300 ms for the torus's results).

Each run starts a fresh process that gets ready as the window's warm spare worker does
(:func:`sorgui.session.job.serve`: mathtext's fonts and glyphs loaded while nobody waits), then
runs the job of one example as the window asks for it (formulas typeset, no scene) and adds up
its "formulas" stages: what the window's stage list shows as typesetting. The table gives the
median over the runs, the number of formulas and the pieces typeset, and the analysis' own time
for comparison.

Run: ``python -m benchmarks.typesetting [--repeats N] [--write]``
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time

from benchmarks.report import run

CASES = ("torus", "paper-example-1", "cone", "paper-cubic")
"""Examples of ``sorgui.examples`` (the torus is the goal's case)."""


def child(name: str) -> None:
    """One run in this process: warm up as a spare worker, run the job, print the figures."""
    from sorgui.examples import example_text
    from sorgui.session.job import JobRequest, run_job, warm_up

    warm_up()
    messages: list[tuple[str, object]] = []
    start = time.perf_counter()
    kind, result = run_job(
        JobRequest(example_text(name), scene=False),
        send=lambda k, p: messages.append((k, p)),
        processes=min(2, os.cpu_count() or 1),
    )
    total = time.perf_counter() - start
    assert kind == "finished", (kind, result)
    typesetting = sum(seconds for stage, seconds in result.timings if stage == "formulas")
    formulas = next(p for k, p in reversed(messages) if k == "formulas")
    print(
        json.dumps(
            {
                "typesetting": typesetting,
                "job": total,
                "formulas": len(formulas),
                "lines": sum(len(f.lines) for f in formulas.values()),
            }
        )
    )


def measure(name: str) -> dict[str, float]:
    out = subprocess.run(
        [sys.executable, "-m", "benchmarks.typesetting", "--child", name],
        capture_output=True,
        text=True,
        check=True,
        timeout=600,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def table(repeats: int) -> str:
    rows = ["| example | formulas | typeset lines | typesetting (s) | whole job (s) |", "|---|---:|---:|---:|---:|"]
    for name in CASES:
        runs = [measure(name) for _ in range(repeats)]
        rows.append(
            f"| {name} | {runs[0]['formulas']} | {runs[0]['lines']} "
            f"| {statistics.median(r['typesetting'] for r in runs):.3f} "
            f"| {statistics.median(r['job'] for r in runs):.2f} |"
        )
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--child":
        child(sys.argv[2])
    else:
        run("typesetting", __doc__.splitlines()[0], table)
