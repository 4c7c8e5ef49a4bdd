"""Benchmark: ``sorgui analyze --each-line --recognition-only --jobs 1`` against one Singular
process looping over the same equations with the paper's Algorithm II.

For each degree (10 and 20), 20 surfaces of revolution in general position (seeds 1…20 of
:func:`benchmarks.recognition.surface`) are written one per line. sorgui analyses the file as
one ``--each-line`` process with one worker; Singular runs one script that defines
Algorithm II (:data:`benchmarks.algorithm2_singular.ALGORITHM_II`) as a procedure and calls it
on each equation in turn, in one process, on one core. Both answers are checked (20 surfaces of
revolution each). Each figure is the median wall time over ``--repeats`` runs. Run
``python -m benchmarks.batch_singular [--repeats N] [--write]`` from the repository root.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

from benchmarks.algorithm2_singular import ALGORITHM_II, process_times
from benchmarks.recognition import surface
from benchmarks.report import run
from sorgui.engine.algebra.polys import poly_str
from sorgui.engine.singular.process import find_singular, poly_to_singular

DEGREES = (10, 20)
COUNT = 20


def singular_loop(polynomials: list[str]) -> str:
    """One Singular script: Algorithm II as the procedure ``algorithmII`` and a call per equation."""
    body = ALGORITHM_II.replace("ring r = 0, (x, y, z), dp;\n", "").replace("poly f = %(f)s;\n", "")
    body = body.replace("quit;\n", "")
    lines = ["ring r = 0, (x, y, z), dp;", "proc algorithmII(poly f)", "{", body, "}"]
    lines += [f"algorithmII({p});" for p in polynomials]
    return "\n".join(lines) + "\nquit;\n"


def table(repeats: int) -> str:
    rows = [
        "| degree | equations | sorgui --each-line (s) | Singular loop (s) | Singular ÷ sorgui |",
        "|---:|---:|---:|---:|---:|",
    ]
    singular = str(find_singular())
    with tempfile.TemporaryDirectory() as folder:
        for degree in DEGREES:
            surfaces = [surface(degree, seed) for seed in range(1, COUNT + 1)]
            lines = Path(folder, f"sor{degree}.txt")
            lines.write_text("".join(poly_str(f) + "\n" for f in surfaces), encoding="utf-8")
            script = Path(folder, f"sor{degree}.sing")
            script.write_text(singular_loop([poly_to_singular(f, ["x", "y", "z"]) for f in surfaces]), encoding="utf-8")
            ours = process_times(
                [
                    sys.executable,
                    "-m",
                    "sorgui.cli",
                    "analyze",
                    "--each-line",
                    "--recognition-only",
                    "--jobs",
                    "1",
                    "-f",
                    str(lines),
                ],
                repeats,
            )
            answers = [json.loads(line) for line in ours[2].splitlines()]
            assert len(answers) == COUNT and all(a["is_sor"] for a in answers)
            theirs = process_times([singular, "-q", "-t", "--no-rc", "--random=4711", str(script)], repeats)
            assert theirs[2].count("SOR yes") == COUNT, theirs[2][-500:]
            rows.append(f"| {degree} | {COUNT} | {ours[0]:.2f} | {theirs[0]:.2f} | {theirs[0] / ours[0]:.2f} |")
            print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("batch-singular", __doc__.splitlines()[0], table)
