"""What the analysis worker process does: analyse, build the scene, typeset the formulas.

This module is the target of the worker process (started with the ``spawn`` method by
:mod:`sorgui.gui.worker`) and imports no Qt. :func:`serve` makes the process a process-group
leader, waits for one :class:`JobRequest`, and sends plain messages back through its pipe:

* ``("progress", stage)`` for every stage (the engine's, then ``"scene"`` and ``"formulas"``);
* exactly one final message: ``("finished", JobResult)``, ``("invalid", (message, position,
  end))`` for text that is not a polynomial, ``("failed", message)`` or ``("cancelled", None)``.

Engine errors come back as one-line messages, never as tracebacks.
"""

from __future__ import annotations

import os
import sys
import threading
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from multiprocessing.connection import Connection
from typing import Any

from sorgui.engine import Analysis, Cancelled, ParseError, SorguiError, analyze
from sorgui.gui.formulas import Formula, Style, analysis_formulas, render_formulas, render_line
from sorgui.gui.scene_data import DEFAULT_RESOLUTION, SceneData, build_scene

Message = tuple[str, Any]

WORKER_NICENESS = 5
"""The worker runs at a lower priority than the GUI, which then always gets the processor."""


@dataclass(frozen=True)
class JobRequest:
    """One job for the worker process.

    With ``analysis`` (an earlier result's JSON) the engine is skipped and only the scene is
    rebuilt, e.g. for a new ``radius`` of the drawn ball. ``style`` ``None`` skips the formulas.
    """

    text: str
    method: str = "symmetry"
    recognition_only: bool = False
    singular_timeout: float = 60.0
    analysis: dict[str, Any] | None = None
    radius: float | None = None
    resolution: int = DEFAULT_RESOLUTION
    style: Style | None = Style()


@dataclass(frozen=True, eq=False)
class JobResult:
    """The worker's answer: the analysis (as JSON), its scene, its formulas (or ``None``) and
    the worker's own stage timings (scene, formulas)."""

    analysis_json: dict[str, Any]
    scene: SceneData
    formulas: dict[str, Formula] | None
    timings: tuple[tuple[str, float], ...]

    @property
    def analysis(self) -> Analysis:
        return Analysis.from_json(self.analysis_json)


def run_job(
    request: JobRequest,
    cancel: threading.Event | Any | None = None,
    progress: Callable[[str], None] | None = None,
) -> Message:
    """Do ``request`` and return the final message (also usable without a process)."""
    report = progress or (lambda _stage: None)
    timings: list[tuple[str, float]] = []

    def check() -> None:
        if cancel is not None and cancel.is_set():
            raise Cancelled("the analysis was cancelled")

    def stage(name: str, work: Callable[[], Any]) -> Any:
        check()
        report(name)
        start = time.perf_counter()
        value = work()
        timings.append((name, time.perf_counter() - start))
        return value

    try:
        if request.analysis is not None:
            analysis = Analysis.from_json(request.analysis)
        else:
            analysis = analyze(
                request.text,
                method=request.method,
                recognition_only=request.recognition_only,
                singular_timeout=request.singular_timeout,
                cancel=cancel,
                progress=report,
            )
        scene = stage("scene", lambda: build_scene(analysis, request.radius, request.resolution))
        formulas = None
        if request.style is not None:
            style = request.style
            formulas = stage("formulas", lambda: render_formulas(analysis_formulas(analysis), style))
        check()
        return "finished", JobResult(analysis.to_json(), scene, formulas, tuple(timings))
    except Cancelled:
        return "cancelled", None
    except ParseError as exc:
        return "invalid", (exc.message, exc.position, exc.end)
    except SorguiError as exc:
        return "failed", exc.message
    except MemoryError:
        return "failed", "the analysis ran out of memory"
    except Exception as exc:  # a bug: keep the window alive, print the details for a report
        traceback.print_exc(file=sys.stderr)
        return "failed", f"internal error ({type(exc).__name__}: {exc})"


def serve(conn: Connection, cancel: Any) -> None:
    """The worker process: lead a process group at a lower priority, wait for one request,
    answer it, exit.

    Leading a group lets the GUI kill the worker and everything it started at once. The
    process starts before it is needed (a warm spare), so waiting here is the normal case;
    the pipe closing without a request means it is not needed any more.
    """
    if hasattr(os, "setpgrp"):
        os.setpgrp()
    if hasattr(os, "nice"):
        os.nice(WORKER_NICENESS)
    render_line("x", Style())  # load mathtext's fonts while nobody waits
    try:
        request = conn.recv()
    except (EOFError, OSError):
        return
    try:
        conn.send(run_job(request, cancel, progress=lambda stage: conn.send(("progress", stage))))
    except (BrokenPipeError, OSError):
        pass  # the GUI has gone away or superseded this job
    conn.close()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)  # skip the interpreter's teardown: it would compete with the GUI for the processor
