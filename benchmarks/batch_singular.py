"""Benchmark: ``sorgui analyze --each-line --recognition-only --jobs 1`` against one Singular
process looping over the same equations with the paper's Algorithm II.

Three batches of surfaces of revolution in general position, one equation per line: 10 of
degree 10 and 10 of degree 20 (seeds 1…10 of :func:`benchmarks.recognition.surface`: random
profiles on one tilted axis, moved by one rational rotation), and 100 of degree 10 on random
rational axes (:func:`random_axis_surface`: a random profile about the line through a random
rational point along a random integer direction). sorgui analyses each file as one
``--each-line`` process with one worker; Singular runs one script that defines Algorithm II
(:data:`benchmarks.algorithm2_singular.ALGORITHM_II`) as a procedure and calls it on each
equation in turn, in one process, on one core. Both are whole processes (starting Python and
importing the engine included), run alternately in the same run; both answers are checked
(every line a surface of revolution). Each figure is the median wall time over ``--repeats``
runs, and the median CPU time (user + system of the process and of every process it started:
sorgui's worker, or Singular alone; :func:`benchmarks.report.process_times`), the better guide
on a busy machine. Run ``python -m
benchmarks.batch_singular [--repeats N] [--write]`` from the repository root.
"""

from __future__ import annotations

import json
import random
import sys
import tempfile
from pathlib import Path

from benchmarks.algorithm2_singular import ALGORITHM_II
from benchmarks.recognition import random_profile, surface
from benchmarks.report import process_times, run
from sorgui.engine.algebra.polys import Poly, poly_str
from sorgui.engine.singular.process import find_singular, poly_to_singular
from sorgui.samples import move, quaternion_rotation, rational_vector, revolve

BATCHES = (
    ("10 SORs of degree 10", 10, 10, False),
    ("100 SORs of degree 10, random rational axes", 10, 100, True),
    ("10 SORs of degree 20", 20, 10, False),
)
"""(name, degree, lines, random axes)."""


def random_axis_surface(degree: int, seed: int) -> Poly:
    """A SOR of ``degree`` in general position about a random rational axis: a random profile
    ``F(s, w)`` (as in :func:`benchmarks.recognition.surface`) about the line through a random
    rational point along a random integer direction, moved by the rational rotation of a random
    integer quaternion and a random rational shift (like a part placed in an assembly)."""
    rng = random.Random(1000 + seed)
    profile = random_profile(degree, rng)

    def rational() -> str:
        return f"{rng.randint(-9, 9)}/{rng.randint(1, 9)}"

    direction = (0, 0, 0)
    while direction == (0, 0, 0):
        direction = tuple(rng.randint(-9, 9) for _ in range(3))
    quaternion = [0, 0, 0, 0]
    while not any(quaternion):
        quaternion = [rng.randint(-3, 3) for _ in range(4)]
    f = revolve(profile, rational_vector([rational() for _ in range(3)]), rational_vector(direction))
    return move(f, quaternion_rotation(quaternion), rational_vector([rational() for _ in range(3)]))


def singular_loop(polynomials: list[str]) -> str:
    """One Singular script: Algorithm II as the procedure ``algorithmII`` and a call per equation."""
    body = ALGORITHM_II.replace("ring r = 0, (x, y, z), dp;\n", "").replace("poly f = %(f)s;\n", "")
    body = body.replace("quit;\n", "")
    lines = ["ring r = 0, (x, y, z), dp;", "proc algorithmII(poly f)", "{", body, "}"]
    lines += [f"algorithmII({p});" for p in polynomials]
    return "\n".join(lines) + "\nquit;\n"


def table(repeats: int) -> str:
    rows = [
        "| batch | terms per line | sorgui --each-line (s) | Singular loop (s) | Singular ÷ sorgui "
        "| sorgui CPU (s) | Singular CPU (s) | Singular ÷ sorgui, CPU |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    singular = str(find_singular())
    with tempfile.TemporaryDirectory() as folder:
        for index, (name, degree, count, random_axes) in enumerate(BATCHES):
            make = random_axis_surface if random_axes else surface
            surfaces = [make(degree, seed) for seed in range(1, count + 1)]
            lines = Path(folder, f"batch{index}.txt")
            lines.write_text("".join(poly_str(f) + "\n" for f in surfaces), encoding="utf-8")
            script = Path(folder, f"batch{index}.sing")
            script.write_text(singular_loop([poly_to_singular(f, ["x", "y", "z"]) for f in surfaces]), encoding="utf-8")
            sorgui = [sys.executable, "-m", "sorgui.cli", "analyze", "--each-line", "--recognition-only"]
            ours = process_times([*sorgui, "--jobs", "1", "-f", str(lines)], repeats)
            answers = [json.loads(line) for line in ours[2].splitlines()]
            assert len(answers) == count and all(a["is_sor"] for a in answers)
            theirs = process_times([singular, "-q", "-t", "--no-rc", "--random=4711", str(script)], repeats)
            assert theirs[2].count("SOR yes") == count, theirs[2][-500:]
            terms = round(sum(len(f) for f in surfaces) / count)
            rows.append(
                f"| {name} | {terms} | {ours[0]:.2f} | {theirs[0]:.2f} | {theirs[0] / ours[0]:.2f} "
                f"| {ours[1]:.2f} | {theirs[1]:.2f} | {theirs[1] / ours[1]:.2f} |"
            )
            print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("batch-singular", __doc__.splitlines()[0], table)
