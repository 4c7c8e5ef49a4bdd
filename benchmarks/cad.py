"""Benchmark: the STEP file of each kind of part sorgui writes, sewn and checked (issues 19, 31).

Run as ``python -m benchmarks.cad [--repeats N] [--write]``. The analyses and scenes are
computed beforehand (not timed). The first export in a fresh process also imports Open CASCADE;
that import is timed on its own, in a new interpreter. For each case the table gives the route,
faces and solids, the deviation measured against the tolerance aimed at, the median time of a
STEP file built from nothing (the model: faces, cut, sewing, checks, coverage; and the writer),
and of STEP, IGES and BRep written together (one model shared by the three). ``--write`` puts
the table into ``docs/benchmarks.md``.
"""

from __future__ import annotations

import os
import platform
import subprocess
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path

import sorgui.cad
from benchmarks.recognition import surface
from benchmarks.report import median_time, run
from sorgui.cad import cad_model
from sorgui.engine import analyze
from sorgui.engine.algebra.polys import poly_str
from sorgui.examples import example_text
from sorgui.export.files import export_file
from sorgui.render import ClipBox
from sorgui.samples import printed_exact, rational_sor
from sorgui.session.scene_data import build_scene

SUFFIXES = (".step", ".iges", ".brep")


def rounded_quartic() -> str:
    """A quartic surface of revolution on a rational axis in general position, 10 digits."""
    profile = {(0, 0): Fraction(-2), (2, 0): Fraction(1), (0, 1): Fraction(1), (4, 0): Fraction(-1, 3)}
    return printed_exact(rational_sor((1, 2, -1, 3), (Fraction(1, 3), Fraction(0), Fraction(1)), profile), 10)


def cases() -> dict[str, tuple[str, ClipBox | None]]:
    return {
        "torus": (example_text("torus"), None),
        "paper-example-1": (example_text("paper-example-1"), None),
        "paper-example-1, box -2:4,-4:2,-3:3": (example_text("paper-example-1"), ClipBox((-2, 4, -4, 2, -3, 3))),
        "degree 6, general position": (poly_str(surface(6)), None),
        "degree 8, general position": (poly_str(surface(8)), None),
        "degree 12, general position": (poly_str(surface(12)), None),
        "elliptic cylinder 9(2x-y)^2+4(2x+4y-5z-3)^2-180": ("9*(2*x-y)^2+4*(2*x+4*y-5*z-3)^2-180", None),
        "pipe about the twisted cubic": (example_text("pipe-twisted-cubic"), None),
        "rounded quartic SOR (10 digits)": (rounded_quartic(), None),
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
    load = os.getloadavg()[0]
    rows = [
        "| surface | route: faces (solids) | deviation / tolerance | `.step` median s (size) | "
        "`.step` + `.iges` + `.brep` median s |",
        "| --- | --- | --- | --- | --- |",
    ]
    with tempfile.TemporaryDirectory() as folder:
        for name, (text, box) in cases().items():
            start = time.perf_counter()
            analysis = analyze(text)
            scene = build_scene(analysis, box=box)
            prepared = time.perf_counter() - start
            path = Path(folder) / "part.step"

            def step(a=analysis, s=scene, p=path) -> None:
                sorgui.cad._BUILT.clear()
                export_file(a, p, scene=s)

            def three(a=analysis, s=scene) -> None:
                sorgui.cad._BUILT.clear()
                for suffix in SUFFIXES:
                    export_file(a, Path(folder) / f"part{suffix}", scene=s)

            seconds, _ = median_time(step, repeats)
            together, _ = median_time(three, repeats)
            model = cad_model(analysis, scene)
            solids = f" ({model.solids})" if model.solids else ""
            fit = "exact" if model.deviation is None else f"{model.deviation:.2e} / {model.tolerance:.2e}"
            rows.append(
                f"| {name} (analysis + scene {prepared:.2f} s) | {model.route}: {model.faces}{solids} | {fit} | "
                f"{seconds:.3f} ({path.stat().st_size / 1024:,.0f} KiB) | {together:.3f} |"
            )
    machine = f"{platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} cores"
    text = "\n".join(rows) + (
        f"\n\nImporting Open CASCADE and the CAD modules in a new process: {import_seconds():.2f} s (once per "
        f"process; the window pays it in its export process). Median of {repeats} runs, {machine}, load average "
        f"{load:.1f} at the start (a shared machine); command: `python -m benchmarks.cad --repeats 3 --write`."
    )
    print(text)
    return text


if __name__ == "__main__":
    run("cad", __doc__.splitlines()[0], table)
