"""Benchmark: writing every export format of the paper's Example 1 and of a torus.

Run as ``python -m benchmarks.exports [--repeats N] [--write]``. The analyses and the scenes are
computed once beforehand (not timed); each format is then written ``N`` times into a temporary
folder with :func:`sorgui.export.files.export_analysis`, and the median wall time is reported
with the file's size. The formula formats include the exact missed-point test (a Gröbner basis
per parameter line, :mod:`sorgui.export.formulas`); Markdown, HTML and PNG render a picture off
screen. ``--write`` puts the table into ``docs/benchmarks.md``.
"""

from __future__ import annotations

import os
import platform
import tempfile
from pathlib import Path

from benchmarks.report import median_time, run
from sorgui.engine import analyze
from sorgui.examples import example_text
from sorgui.export.files import export_analysis
from sorgui.export.formats import FORMATS
from sorgui.session.scene_data import build_scene

SURFACES = ("paper-example-1", "torus")


def table(repeats: int) -> str:
    rows = [
        "| format | " + " | ".join(f"{name}: median s (size)" for name in SURFACES) + " |",
        "| --- |" + " --- |" * len(SURFACES),
    ]
    prepared = {name: analyze(example_text(name)) for name in SURFACES}
    scenes = {name: build_scene(analysis) for name, analysis in prepared.items()}
    with tempfile.TemporaryDirectory() as folder:
        cells: dict[str, list[str]] = {suffix: [] for suffix in FORMATS}
        for name in SURFACES:
            for suffix in FORMATS:
                path = Path(folder) / f"{name}{suffix}"
                seconds, _ = median_time(
                    lambda name=name, path=path: export_analysis(prepared[name], path, scene=scenes[name]), repeats
                )
                cells[suffix].append(f"{seconds:.3f} ({path.stat().st_size / 1024:,.0f} KiB)")
        rows += [f"| `{suffix}` | " + " | ".join(cells[suffix]) + " |" for suffix in FORMATS]
    machine = f"{platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} cores"
    text = "\n".join(rows) + (
        f"\n\nMedian of {repeats} runs, {machine}; command: `python -m benchmarks.exports --repeats 3 --write`."
    )
    print(text)
    return text


if __name__ == "__main__":
    run("exports", __doc__.splitlines()[0], table)
