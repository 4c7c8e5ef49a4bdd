"""Benchmark: STEP, IGES and BRep export of a torus, of the paper's Example 1 and of a degree-12
surface of revolution in general position (issue 19).

Run as ``python -m benchmarks.cad [--repeats N] [--write]``. The analyses and scenes are
computed beforehand (not timed). The first export in a fresh process also imports Open CASCADE;
that import is timed on its own, in a new interpreter, and the table gives the median of
``N`` exports after it. Each row says which route the file took (analytic, exact rational
profile, fitted profile), its number of faces and, for a fitted profile, the deviation measured
against the tolerance aimed at. ``--write`` puts the table into
``docs/benchmarks.md``.
"""

from __future__ import annotations

import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.recognition import surface
from benchmarks.report import median_time, run
from sorgui.cad import cad_model
from sorgui.engine import analyze
from sorgui.engine.algebra.polys import poly_str
from sorgui.examples import example_text
from sorgui.export.files import export_analysis
from sorgui.session.scene_data import build_scene

SUFFIXES = (".step", ".iges", ".brep")


def surfaces() -> dict[str, str]:
    return {
        "torus": example_text("torus"),
        "paper-example-1": example_text("paper-example-1"),
        "degree 12, general position": poly_str(surface(12)),
    }


def import_seconds() -> float:
    """``import OCP`` plus the modules a CAD export loads, in a new interpreter."""
    code = (
        "import time; t = time.perf_counter(); import sorgui.cad.model, sorgui.cad.writers; "
        "print(time.perf_counter() - t)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(out.stdout.strip())


def table(repeats: int) -> str:
    head = "| surface | route (faces) | deviation / tolerance | "
    rows = [head + " | ".join(f"`{s}` median s (size)" for s in SUFFIXES) + " |"]
    rows.append("| --- | --- | --- |" + " --- |" * len(SUFFIXES))
    with tempfile.TemporaryDirectory() as folder:
        for name, text in surfaces().items():
            start = time.perf_counter()
            analysis = analyze(text)
            scene = build_scene(analysis)
            prepared = time.perf_counter() - start
            model = cad_model(analysis, scene)
            cells = []
            for suffix in SUFFIXES:
                path = Path(folder) / f"part{suffix}"
                seconds, _ = median_time(
                    lambda a=analysis, path=path, s=scene: export_analysis(a, path, scene=s), repeats
                )
                cells.append(f"{seconds:.3f} ({path.stat().st_size / 1024:,.0f} KiB)")
            fit = "exact" if model.deviation is None else f"{model.deviation:.2e} / {model.tolerance:.2e}"
            rows.append(
                f"| {name} (analysis + scene {prepared:.2f} s) | {model.route} ({model.faces}) | {fit} | "
                + " | ".join(cells)
                + " |"
            )
    machine = f"{platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} cores"
    text = "\n".join(rows) + (
        f"\n\nImporting Open CASCADE and the CAD modules in a new process: {import_seconds():.2f} s (once per process; "
        f"the window pays it in its export process). Median of {repeats} runs, {machine}; command: "
        "`python -m benchmarks.cad --repeats 3 --write`."
    )
    print(text)
    return text


if __name__ == "__main__":
    run("cad", __doc__.splitlines()[0], table)
