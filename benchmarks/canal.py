"""Benchmark: the canal recognizer (docs/math.md §9) on the worked examples.

For each case: the time of the focal-sheet test alone (three lines, or up to the witness line),
of the exact verdict with its certificate (``full=False``: test, SMAT, certificate), and of the
whole canal analysis (``full=True``: also the genus, ``m(t)``, ``ρ(t)``, the radical and rational
parameterizations). Run ``python -m benchmarks.canal [--repeats N] [--write]``; ``--write``
updates docs/benchmarks.md.
"""

from __future__ import annotations

from pathlib import Path

from benchmarks.report import median_time, run
from sorgui.engine.algebra.polys import to_flint
from sorgui.engine.canal.lines import LINES, SEED, Lines, NotCanal
from sorgui.engine.canal.verdict import analyze_canal
from sorgui.engine.parsing import parse_polynomial

EXAMPLES = Path(__file__).resolve().parents[1] / "tests" / "data" / "canal-examples.txt"

CASES = (
    ("pipe twisted cubic", "pipe around the twisted cubic"),
    ("blend cyl R=2 / plane 3x+4z=0", "rolling-ball blend, cylinder and oblique plane"),
    ("blend cylinders R=2", "two-cylinder blend (genus-1 spine)"),
    ("two-cylinder blend + x^3", "two-cylinder blend + x³ (not canal)"),
)


def example(prefix: str) -> str:
    lines = EXAMPLES.read_text(encoding="utf-8").splitlines()
    return next(lines[i + 1] for i, line in enumerate(lines) if line.startswith("## " + prefix))


def line_test(f) -> str:  # noqa: ANN001 - a polynomial of the engine
    """The focal-sheet test on LINES lines (or up to the first witness line)."""
    lines = Lines(to_flint(f), SEED)
    try:
        for _ in range(LINES):
            lines.next()
    except NotCanal:
        return "not canal"
    return "canal condition holds"


def table(repeats: int) -> str:
    rows = [
        "| case | degree | test on lines (s) | verdict + certificate (s) | with spine, genus, m(t) (s) | answer |",
        "|---|---:|---:|---:|---:|---|",
    ]
    for prefix, label in CASES:
        f = parse_polynomial(example(prefix)).polynomial
        test, _ = median_time(lambda f=f: line_test(f), repeats)
        verdict, quick = median_time(lambda f=f: analyze_canal(f, full=False), repeats)
        whole, full = median_time(lambda f=f: analyze_canal(f, full=True), repeats)
        answer = {True: "canal", False: "not canal", None: "undecided"}[full.is_canal]
        if full.kinds:
            answer += " (" + ", ".join(full.kinds) + ")"
        if full.families:
            fam = full.families[0]
            answer += f"; spine degree {fam.degree}, genus {fam.genus}"
        if quick.certificate is not None:
            answer += f"; certificate {quick.certificate.method}"
        rows.append(
            f"| {label} | {f.ring and max(sum(m) for m in f.monoms())} | {test:.2f} | {verdict:.2f} "
            f"| {whole:.2f} | {answer} |"
        )
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("canal", __doc__.splitlines()[0], table)
