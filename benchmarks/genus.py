"""Benchmark: full analyses of degree-12 surfaces of revolution in general position.

``genus(P²)`` (25) comes from Riemann–Hurwitz for ``P → P²`` once Singular has shown the profile
``P`` smooth modulo a prime; Singular's ``genus`` of ``P²`` took 18–36 s (66 s on a busy machine).
Run ``python -m benchmarks.genus [--repeats N] [--write]``; ``--write`` updates
``docs/benchmarks.md``.
"""

from __future__ import annotations

from benchmarks.report import median_time, run
from sorgui.engine.analysis import analyze_polynomial
from sorgui.samples import general_position

SEEDS = (5, 6, 7)


def table(repeats: int) -> str:
    """The markdown table: total and per-stage times of each case."""
    rows = ["| case | genus(P) | genus(P²) | Table 1 row | total (s) | stages (s) |", "|---|---:|---:|---:|---:|---|"]
    for seed in SEEDS:
        f = general_position(12, seed)
        seconds, result = median_time(lambda f=f: analyze_polynomial(f), repeats)
        rat = result.rationality
        stages = ", ".join(f"{n} {s:.3f}" for n, s in result.timings)
        rows.append(
            f"| degree 12, seed {seed} | {rat.genus_profile} | {rat.genus_profile_square} | {rat.table_row} "
            f"| {seconds:.3f} | {stages} |"
        )
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("genus", __doc__, table)
