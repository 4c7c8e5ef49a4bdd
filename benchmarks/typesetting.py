"""Benchmark: the results pane's formulas, as text at once and typeset beside (issue 30).

Each run is a fresh process. It analyses one example, then times, as the window does them:
the Unicode text of every formula of the pane (:func:`sorgui.session.formulas.pane_formulas`,
what the GUI thread pays before every row is readable; sympy is not used), and, after warming
mathtext up as the window's typesetting process does (:func:`sorgui.session.typesetting.serve`),
the typesetting of all of them (what that process spends off the critical path). The table gives
the median over the runs, the number of formulas and of typeset lines.

Run: ``python -m benchmarks.typesetting [--repeats N] [--write]``
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time

from benchmarks.report import run

CASES = ("torus", "paper-example-1", "cone", "paper-cubic", "rounded torus")
"""Examples of ``sorgui.examples``, and the 10-digit rounded torus of ``benchmarks.window``."""


def child(name: str) -> None:
    """One run in this process: analyse, print the text of every formula, typeset them."""
    from sorgui.engine import analyze
    from sorgui.examples import example_text
    from sorgui.session.formulas import pane_formulas
    from sorgui.session.typesetting import WARM_UP, Style, render_line, typeset

    if name == "rounded torus":
        from benchmarks.window import turned_torus

        text = turned_torus()
    else:
        text = example_text(name)
    analysis = analyze(text)
    start = time.perf_counter()
    formulas = pane_formulas(analysis)
    nearest = analysis.approximate.nearest.analysis if analysis.approximate and analysis.approximate.nearest else None
    if nearest is not None:
        formulas = {**formulas, **{f"nearest.{k}": f for k, f in pane_formulas(nearest, "decimal").items()}}
    text_seconds = time.perf_counter() - start
    style = Style()
    render_line(WARM_UP, style)
    start = time.perf_counter()
    answers = [typeset(f.pieces, style) for f in formulas.values() if f.pieces]
    typeset_seconds = time.perf_counter() - start
    print(
        json.dumps(
            {
                "text": text_seconds,
                "typesetting": typeset_seconds,
                "formulas": len(formulas),
                "lines": sum(len(a.lines) for a in answers),
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
    rows = [
        "| example | formulas | text of all, GUI thread (ms) | typeset lines | typesetting, its own process (s) |",
        "|---|---:|---:|---:|---:|",
    ]
    for name in CASES:
        runs = [measure(name) for _ in range(repeats)]
        rows.append(
            f"| {name} | {runs[0]['formulas']} | {1000 * statistics.median(r['text'] for r in runs):.1f} "
            f"| {runs[0]['lines']} | {statistics.median(r['typesetting'] for r in runs):.3f} |"
        )
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--child":
        child(sys.argv[2])
    else:
        run("typesetting", __doc__.splitlines()[0], table)
