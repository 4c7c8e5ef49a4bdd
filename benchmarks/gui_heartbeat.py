"""Benchmark: does the window stay responsive while sorgui analyses? (goal: no gap > 100 ms)

A real main window (real Qt, real VTK render window; under Xvfb with Mesa's software OpenGL in
CI) analyses a few surfaces while a 10 ms ``QTimer`` heartbeat runs on the GUI thread. For each
surface the table gives the longest interval between two heartbeats, from pasting the text
until the results and the mesh are on screen (and 300 ms more, so that the first frame of the
new mesh is counted), the 99th percentile, and how many intervals exceeded 100 ms.

Run: ``xvfb-run -a -s "-screen 0 1920x1080x24" python -m benchmarks.gui_heartbeat [--write]``
"""

from __future__ import annotations

import argparse
import random
import statistics
import tempfile
import time

HEARTBEAT_MS = 10
GOAL_MS = 100.0
AFTER_MS = 300
"""Keep measuring this long after the result is shown (the mesh's first frame)."""


def sor_in_general_position(degree: int) -> str:
    """A surface of revolution of the given degree on a tilted rational axis (dense in x, y, z)."""
    from benchmarks.recognition import surface
    from sorgui.engine.polys import poly_str

    return poly_str(surface(degree, seed=degree))


def dense_surface(degree: int) -> str:
    """A dense polynomial in general position (every monomial up to ``degree``)."""
    rng = random.Random(5)
    return "+".join(
        f"{rng.choice([-1, 1]) * rng.randint(1, 99)}*x^{i}*y^{j}*z^{k}"
        for i in range(degree + 1)
        for j in range(degree + 1 - i)
        for k in range(degree + 1 - i - j)
    )


def cases() -> list[tuple[str, str]]:
    from sorgui.examples import example_text

    return [
        ("paper Example 1 (degree 6)", example_text("paper-example-1")),
        ("torus (degree 4)", example_text("torus")),
        ("SOR in general position, degree 12", sor_in_general_position(12)),
        ("dense surface, degree 40 (not a SOR)", dense_surface(40)),
    ]


def measure(window, text: str, timeout_s: float = 300.0) -> dict[str, float]:  # noqa: ANN001
    """Paste ``text``, analyse it, and record the heartbeat until it is shown."""
    from PySide6.QtCore import QCoreApplication, QTimer

    beats: list[float] = []
    outcome: list[str] = []
    heartbeat = QTimer()
    heartbeat.setInterval(HEARTBEAT_MS)
    heartbeat.timeout.connect(lambda: beats.append(time.perf_counter()))
    window.result_shown.connect(lambda _result: outcome.append("shown"))
    window.worker.failed.connect(lambda message: outcome.append("failed: " + message))
    heartbeat.start()
    beats.append(time.perf_counter())
    start = time.perf_counter()
    window.set_equation(text)
    window.analyze()
    deadline = start + timeout_s
    while not outcome and time.perf_counter() < deadline:
        QCoreApplication.processEvents()
        time.sleep(0.001)
    shown = time.perf_counter()
    while time.perf_counter() < shown + AFTER_MS / 1000:
        QCoreApplication.processEvents()
        time.sleep(0.001)
    heartbeat.stop()
    window.result_shown.disconnect()
    window.worker.failed.disconnect()
    if outcome[:1] != ["shown"]:
        raise RuntimeError(f"the analysis did not finish: {outcome or 'timeout'}")
    gaps = [1000 * (b - a) for a, b in zip(beats, beats[1:])]
    return {
        "seconds": shown - start,
        "longest": max(gaps),
        "p99": statistics.quantiles(gaps, n=100)[98],
        "over": sum(g > GOAL_MS for g in gaps),
        "beats": len(gaps),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--warmup", type=float, default=4.0, help="seconds for the warm worker to start")
    parser.add_argument("--write", action="store_true", help="update docs/benchmarks.md")
    args = parser.parse_args()

    from PySide6.QtCore import QCoreApplication, QSettings

    with tempfile.TemporaryDirectory() as folder:
        QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, folder)
        from sorgui.gui.app import create_application
        from sorgui.gui.main_window import MainWindow

        app = create_application([])
        window = MainWindow()
        window.resize(1400, 860)
        window.show()
        rows = [
            "| surface | characters | shown after (s) | longest gap (ms) | 99th pct (ms) | gaps > 100 ms |",
            "|---|---:|---:|---:|---:|---:|",
        ]
        print(f"software OpenGL: {window.viewport.software_rendering()}; heartbeat {HEARTBEAT_MS} ms", flush=True)
        for name, text in cases():
            until = time.perf_counter() + args.warmup  # the warm worker process gets ready
            while time.perf_counter() < until:
                QCoreApplication.processEvents()
                time.sleep(0.005)
            m = measure(window, text)
            rows.append(
                f"| {name} | {len(text):,} | {m['seconds']:.2f} | {m['longest']:.0f} | {m['p99']:.0f} "
                f"| {m['over']} of {m['beats']} |"
            )
            print(rows[-1], flush=True)
        window.close()
        app.processEvents()
    print()
    print("\n".join(rows))
    if args.write:
        from benchmarks.report import write_section

        write_section("gui", "\n".join(rows))


if __name__ == "__main__":  # the worker processes are spawned: they import this module
    main()
