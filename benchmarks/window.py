"""Benchmark: the window keeps up with the engine (goal of issue 30), measured beside the command line.

For each equation of :func:`cases` (the paper's Example 1, the torus, a tube, the sphere, a
10-digit rounded torus on a rotated axis, a rounded degree-12 surface, the exact degree-12
product of three coaxial tori, a quadric cone), in the same run:

* **CLI**: the whole process ``sorgui analyze --json -f FILE``, wall time (median of the runs);
* **from Analyze**: one window (real Qt, real VTK render window; Xvfb and Mesa's software
  OpenGL here) analyses it while a 10 ms heartbeat runs on the GUI thread: when the verdict was
  on screen (the banner says more than "Analysing…"), when everything was shown (the run ended,
  its last results on the page and its last scene drawn), when the formulas on screen and all
  formulas were typeset, the longest gap between two heartbeats and how many exceeded 100 ms;
* **from start**: a fresh ``python`` process opens the window on the equation file as
  ``sorgui FILE`` does (empty settings): seconds from starting it until everything was shown.

Goals: the verdict within 0.3 s of Analyze, no gap over 100 ms, and everything shown (from
Analyze and from start) within 1.5 × the CLI's time + 1 s. The machine's load average is printed
beside the figures (the machine is shared: wall times grow with it).

Run: ``xvfb-run -a -s "-screen 0 1920x1080x24" python -m benchmarks.window [--repeats N] [--write]``
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path
from typing import Any

HEARTBEAT_MS = 10
GAP_GOAL_MS = 100.0
VERDICT_GOAL_S = 0.3
AFTER_MS = 300
"""The heartbeat runs on this long after everything is shown (the first frame of the last mesh)."""


def turned_torus(digits: int = 10) -> str:
    """The torus (R = 3, r = 1) about a line turned by 0.7 rad about z through (0.3, -1.2, 0.5),
    printed as a CAD system prints it, ``digits`` significant digits."""
    import numpy as np

    from sorgui.engine.rounded import dense
    from sorgui.samples import printed

    direction = np.array([math.cos(0.7), math.sin(0.7), 0.0])
    point = np.array([0.3, -1.2, 0.5])
    one = dense.from_terms({(0, 0, 0): 1.0}, 4)
    h, rho = dense.linear_form(direction, point), dense.squared_distance(point)
    r1 = dense.times(one, rho)
    return printed(dense.times(r1, rho) - 20 * r1 + 36 * dense.times(dense.times(one, h), h) + 64 * one, digits)


TORI_HEIGHTS = (-6, 0, 6)
"""The heights of the three coaxial tori (R = 3, r = 1) along their axis: the outer ones are far
enough from the middle one that a ball found on a few lines through the centre missed them."""

TURNED_TORI_HEIGHTS = (-3, 0, 3)
"""Those of the rounded degree-12 surface (closer: its nearest exact surface is found from 14 digits)."""


def _times(a: dict[tuple[int, int], Fraction], b: dict[tuple[int, int], Fraction]) -> dict[tuple[int, int], Fraction]:
    out: dict[tuple[int, int], Fraction] = {}
    for (i, j), c in a.items():
        for (k, m), d in b.items():
            out[(i + k, j + m)] = out.get((i + k, j + m), Fraction(0)) + c * d
    return {e: c for e, c in out.items() if c}


def tori_profile(heights: tuple[int, ...] = TORI_HEIGHTS) -> dict[tuple[int, int], Fraction]:
    """``Π_c T_c − 1000`` in ``h`` (along the axis) and ``ρ`` (squared distance from a point of
    it): ``T_c = (ρ − 2ch + c² + 8)² − 36(ρ − h²)``, the torus at height ``c``."""
    product = {(0, 0): Fraction(1)}
    for c in heights:
        base = {(0, 1): Fraction(1), (1, 0): Fraction(-2 * c), (0, 0): Fraction(c * c + 8)}
        torus = _times(base, base)
        torus[(0, 1)] = torus.get((0, 1), Fraction(0)) - 36
        torus[(2, 0)] = torus.get((2, 0), Fraction(0)) + 36
        product = _times(product, torus)
    product[(0, 0)] = product.get((0, 0), Fraction(0)) - 1000
    return product


def three_tori() -> str:
    """The exact degree-12 product of three coaxial tori about the z-axis, minus 1000."""
    factors = [f"((x^2+y^2+(z-{c})^2+8)^2-36(x^2+y^2))" for c in TORI_HEIGHTS]
    return "*".join(factors).replace("(z-0)", "z").replace("(z--", "(z+") + "-1000"


def rounded_degree_12(digits: int = 14) -> str:
    """The three coaxial tori turned onto a rational axis, printed with ``digits`` digits."""
    from sorgui.samples import printed_exact, rational_sor

    point = (Fraction(1, 3), Fraction(-2), Fraction(5, 7))
    return printed_exact(rational_sor((1, 2, -1, 3), point, tori_profile(TURNED_TORI_HEIGHTS)), digits)


def cases() -> list[tuple[str, str]]:
    from sorgui.examples import example_text

    return [
        ("paper Example 1", example_text("paper-example-1")),
        ("torus", example_text("torus")),
        ("tube (x²+y²+z²+21)²−100(x²+y²)", "(x^2+y^2+z^2+21)^2-100(x^2+y^2)"),
        ("sphere", example_text("sphere")),
        ("rounded torus, rotated axis, 10 digits", turned_torus()),
        ("rounded degree 12 (three tori, turned), 14 digits", rounded_degree_12()),
        ("three coaxial tori, exact, degree 12", three_tori()),
        ("quadric cone", example_text("cone")),
    ]


# --- the command line ---------------------------------------------------------------------


def cli_seconds(path: Path) -> float:
    """Wall time of the whole process ``sorgui analyze --json -f path``."""
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "sorgui.cli", "analyze", "--json", "-f", str(path)],
        check=True,
        capture_output=True,
        timeout=600,
    )
    return time.perf_counter() - start


# --- the window ---------------------------------------------------------------------------


def verdict_shown(window: Any) -> bool:
    """Whether the results pane shows a verdict of the current run (not "Analysing…")."""
    run = window.session.run
    return run is not None and run.analysis is not None and "Analysing" not in window.results.banner.text()


def all_shown(window: Any, done: list[str]) -> bool:
    """Whether the run has ended and its last results and scene are on screen."""
    return bool(done) and not window.viewport._render_timer.isActive() and not window.view._pane_timer.isActive()


def typeset_state(window: Any) -> tuple[bool, bool]:
    """``(the formulas on screen are typeset, all are)`` (those mathtext can typeset)."""
    results = window.results
    style = results.formula_style()
    page = results.widget()
    seen = results.viewport().rect().translated(0, results.verticalScrollBar().value())
    visible, everything = True, True
    from PySide6.QtCore import QRect

    for view in results.views.values():
        if not view.formula.pieces or view.typeset_style == style:
            continue
        everything = False
        if QRect(view.mapTo(page, view.rect().topLeft()), view.size()).intersects(seen):
            visible = False
    return visible, everything


def measure(window: Any, text: str, timeout_s: float = 300.0) -> dict[str, float]:
    """Paste ``text``, press Analyze, and time the window until it has shown everything."""
    from PySide6.QtCore import QCoreApplication, QTimer

    beats: list[float] = []
    marks: dict[str, float] = {}
    done: list[str] = []
    heartbeat = QTimer()
    heartbeat.setInterval(HEARTBEAT_MS)

    def beat() -> None:
        now = time.perf_counter()
        beats.append(now)
        if "verdict" not in marks and verdict_shown(window):
            marks["verdict"] = now
        if "shown" not in marks and all_shown(window, done):
            marks["shown"] = now
        if "shown" in marks:
            visible, everything = typeset_state(window)
            if visible and "visible typeset" not in marks:
                marks["visible typeset"] = now
            if everything and "all typeset" not in marks:
                marks["all typeset"] = now

    heartbeat.timeout.connect(beat)
    window.result_shown.connect(lambda _result: done.append("shown"))
    window.worker.failed.connect(lambda message: done.append("failed: " + message))
    heartbeat.start()
    window.set_equation(text)
    beats.append(time.perf_counter())
    start = time.perf_counter()
    window.analyze()
    deadline = start + timeout_s
    while "all typeset" not in marks and time.perf_counter() < deadline:
        QCoreApplication.processEvents()
        time.sleep(0.001)
        if "shown" in marks and time.perf_counter() > marks["shown"] + 60:
            break
    shown = marks.get("shown", time.perf_counter())
    until = shown + AFTER_MS / 1000
    while time.perf_counter() < until:
        QCoreApplication.processEvents()
        time.sleep(0.001)
    heartbeat.stop()
    window.result_shown.disconnect()
    window.worker.failed.disconnect()
    if done[:1] != ["shown"]:
        raise RuntimeError(f"the analysis did not finish: {done or 'timeout'}")
    gaps = [1000 * (b - a) for a, b in zip(beats, beats[1:]) if a <= until]
    return {
        **{name: value - start for name, value in marks.items()},
        "longest": max(gaps),
        "over": sum(g > GAP_GOAL_MS for g in gaps),
        "beats": len(gaps),
    }


def launch(path: str) -> None:
    """The child process of :func:`launch_seconds`: open the window on ``path`` as ``sorgui FILE``
    does and print (as JSON) the ``time.time()`` when everything was shown."""
    from PySide6.QtCore import QCoreApplication, QSettings

    folder = tempfile.mkdtemp()
    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, folder)
    from sorgui.gui.app import create_application, open_main_window

    app = create_application([])
    window = open_main_window(path)
    done: list[str] = []
    window.result_shown.connect(lambda _result: done.append("shown"))
    times: dict[str, float] = {}
    deadline = time.time() + 300
    while time.time() < deadline and "shown" not in times:
        QCoreApplication.processEvents()
        if "verdict" not in times and verdict_shown(window):
            times["verdict"] = time.time()
        if all_shown(window, done):
            times["shown"] = time.time()
        time.sleep(0.002)
    print(json.dumps(times), flush=True)
    window.setWindowModified(False)
    window.close()
    app.processEvents()


def launch_seconds(path: Path) -> dict[str, float]:
    """Seconds from starting a fresh interpreter on the window with ``path`` to its verdict and
    to everything shown."""
    start = time.time()
    out = subprocess.run(
        [sys.executable, "-m", "benchmarks.window", "--launch", str(path)],
        capture_output=True,
        text=True,
        check=True,
        timeout=600,
    )
    times = json.loads(out.stdout.strip().splitlines()[-1])
    return {name: value - start for name, value in times.items()}


def load() -> str:
    one, five, _fifteen = os.getloadavg()
    return f"{one:.1f} (5 min: {five:.1f})"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="runs of each measurement (median)")
    parser.add_argument("--warmup", type=float, default=3.0, help="seconds for the warm worker to start")
    parser.add_argument("--write", action="store_true", help="update docs/benchmarks.md")
    parser.add_argument("--only", help="the cases whose name contains this")
    parser.add_argument("--launch", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.launch:
        launch(args.launch)
        return
    from benchmarks.report import compile_sorgui

    compile_sorgui()  # the window processes run bytecode, as an installed sorgui does
    from PySide6.QtCore import QCoreApplication, QSettings

    chosen = [(n, t) for n, t in cases() if not args.only or args.only in n]
    before = load()
    with tempfile.TemporaryDirectory() as folder:
        files = []
        for index, (_name, text) in enumerate(chosen):
            path = Path(folder) / f"case{index}.txt"
            path.write_text(text + "\n", encoding="utf-8")
            files.append(path)
        cli = [statistics.median(cli_seconds(p) for _ in range(args.repeats)) for p in files]
        starts = [
            statistics.median(launch_seconds(p).get("shown", math.nan) for _ in range(args.repeats)) for p in files
        ]
        QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, folder)
        from sorgui.gui.app import create_application
        from sorgui.gui.main_window import MainWindow

        app = create_application([])
        window = MainWindow()
        window.resize(1400, 860)
        window.show()
        window.viewport.start_rendering()
        rows = [
            "| surface | CLI (s) | goal (s) | verdict (s) | shown from Analyze (s) | shown from start (s) "
            "| visible typeset (s) | all typeset (s) | longest gap (ms) | gaps > 100 ms |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for (name, text), seconds, started in zip(chosen, cli, starts):
            runs = []
            for _ in range(args.repeats):
                until = time.perf_counter() + args.warmup
                while time.perf_counter() < until:
                    QCoreApplication.processEvents()
                    time.sleep(0.005)
                runs.append(measure(window, text))

            def median(key: str, runs: list[dict[str, float]] = runs) -> float:
                return statistics.median(r.get(key, math.nan) for r in runs)

            goal = 1.5 * seconds + 1.0
            rows.append(
                f"| {name} | {seconds:.2f} | {goal:.2f} | {median('verdict'):.2f} | {median('shown'):.2f} "
                f"| {started:.2f} | {median('visible typeset'):.2f} | {median('all typeset'):.2f} "
                f"| {max(r['longest'] for r in runs):.0f} | {sum(r['over'] for r in runs)} of "
                f"{sum(r['beats'] for r in runs)} |"
            )
            print(rows[-1], flush=True)
        window.setWindowModified(False)
        window.close()
        app.processEvents()
    after = load()
    note = (
        f"Median of {args.repeats} runs each; longest gap and gaps over 100 ms over all runs. Load average "
        f'{before} before, {after} after; {os.cpu_count()} CPUs. Command: `xvfb-run -a -s "-screen 0 '
        f'1920x1080x24" python -m benchmarks.window --repeats {args.repeats} --write`.'
    )
    print()
    print("\n".join(rows))
    print(note)
    if args.write:
        from benchmarks.report import write_section

        write_section("window", "\n".join(rows) + "\n\n" + note)


if __name__ == "__main__":  # the worker processes are spawned: they import this module
    main()
