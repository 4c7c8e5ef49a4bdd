"""What the analysis worker process does: analyse, build the scene, and send every result the
moment it is known.

This module is the target of the worker process (started with the ``spawn`` method by
:mod:`sorgui.gui.worker`) and imports no Qt. :func:`serve` makes the process a process-group
leader, waits for one :class:`JobRequest`, and sends the messages of :mod:`sorgui.session.messages`:

* :class:`StageStarted` and :class:`StageDone` as each stage starts and ends (the engine's
  stages, and the worker's own: ``"scene"``, the first mesh; ``"curves"``, what the view draws
  besides it as the analysis learns it, which may run several times; ``"nearest scene"``;
  ``"components"``);
* :class:`Parsed` once the equation is read and :class:`Analysed` once the engine is done (the
  window's time limit then no longer applies; both are for the worker's supervision,
  :mod:`sorgui.gui.worker`, which kills a job stuck past its limit);
* :class:`AnalysisKnown`: the results known so far, first after the factors (verdict, axis,
  profile), then after each later stage, then complete;
* :class:`SceneKnown` (first without the parameterization patch) and, for rounded input,
  :class:`NearestSceneKnown`; :class:`ComponentsKnown`: for a *no*, the typed components of a
  blend, each recognised (:mod:`sorgui.session.components`);
* exactly one final message: :class:`Finished` with a :class:`JobResult` (without the scenes,
  already sent), :class:`Invalid` for text that is not a polynomial, :class:`Failed` or
  :class:`JobCancelled`.

The formulas are not typeset here: the window shows them as text at once and has them typeset
by a process of its own (:mod:`sorgui.session.typesetting`), so typesetting never delays the
engine. Engine errors come back as one-line messages, never as tracebacks.
"""

from __future__ import annotations

import gc
import importlib
import os
import sys
import threading
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from multiprocessing.connection import Connection
from typing import Any

from sorgui.engine import Analysis, Cancelled, ParseError, SorguiError, analyze
from sorgui.session.child import become_child
from sorgui.session.messages import (
    Analysed,
    AnalysisKnown,
    ComponentsKnown,
    Failed,
    FinalMessage,
    Finished,
    Invalid,
    JobCancelled,
    Message,
    NearestSceneKnown,
    Parsed,
    SceneKnown,
    StageDone,
    StageStarted,
)

Send = Callable[[Message], None]

WORKER_NICENESS = 1
"""The worker runs just below the window: the GUI thread wins the processor when both want it,
yet other programs' work (a build, a CAD job) does not starve the worker. At 10 a machine busy
with two such jobs gave it a tenth of its share, and the window took 5-9 times the command
line's time for the same equation (docs/benchmarks.md)."""


@dataclass(frozen=True)
class JobRequest:
    """One job for the worker process.

    With ``analysis`` (an earlier result) the engine is skipped: only the scene is built (e.g.
    for a new ``radius`` of the drawn ball, or a saved report). ``box`` (``(xmin, xmax, ymin,
    ymax, zmin, zmax)``) cuts the scene's mesh, and the CAD faces written of it, to that box,
    drawn in the ball about it.
    """

    text: str
    method: str = "symmetry"
    recognition_only: bool = False
    singular_timeout: float = 60.0
    tolerance: float | None = None
    analysis: Analysis | None = None
    radius: float | None = None
    resolution: int | None = None
    box: tuple[float, float, float, float, float, float] | None = None


@dataclass(frozen=True, eq=False)
class JobResult:
    """The worker's complete answer: the analysis, its scene, the nearest exact surface's scene
    (rounded input) and the worker's own stage timings (scene, curves)."""

    analysis: Analysis
    scene: Any
    timings: tuple[tuple[str, float], ...]
    nearest_scene: Any = None


@dataclass
class _Presenter:
    """Turns each analysis the engine publishes into messages: the scene once the recognition
    is known, then what it lacks of each later analysis (the patch, the rounded-input extras,
    the canal surface's curves, the cone's apex), and the nearest exact surface's scene."""

    request: JobRequest
    send: Send
    check: Callable[[], None]
    timings: list[tuple[str, float]] = field(default_factory=list)
    scene: Any = None
    nearest_scene: Any = None
    _patch_map: Any = None
    """The map whose patch the scene has (:func:`~sorgui.engine.patches.patch_maps`'s first)."""
    _approximated: bool = False
    _canal: tuple[Any, ...] = ()
    _conical: bool = False
    _without_equation: bool = False
    """The scene was drawn before a parametrization's implicit equation was known (its patch)."""
    _apex_seen: bool = False
    """The cone's apex (or a cone's within the rounding) was known when the scene was drawn, or
    the scene was drawn again to hold it (:meth:`_misses_apex`)."""
    _components: tuple[Any, ...] | None = None
    """The typed components of a *no*, once found (:meth:`_explain`)."""

    def stage(self, name: str, work: Callable[[], Any]) -> Any:
        self.check()
        self.send(StageStarted(name))
        start = time.perf_counter()
        value = work()
        seconds = time.perf_counter() - start
        self.timings.append((name, seconds))
        self.send(StageDone(name, seconds))
        return value

    def present(self, analysis: Analysis) -> None:
        from sorgui.session import scene_data

        self.send(AnalysisKnown(analysis))
        request = self.request
        if self.scene is not None and self._without_equation and analysis.squarefree:
            self._forget_scene()  # a parametrization's implicit equation has come: the surface replaces the patch
        if self.scene is not None and self._misses_apex(analysis):
            self._forget_scene()  # drawn before the cone's apex was known, in a ball without it: drawn again
            self.nearest_scene = None
        if self.scene is None and self._awaits_rounding(analysis):
            return  # rounded input is drawn about its approximate axis, once that is known
        if self.scene is None:
            self._without_equation = not analysis.squarefree
            self._apex_seen = self._apex_seen or analysis.conical is not None
            self.scene = self.stage("scene", lambda: scene_data.build_scene_of(analysis, request))
            self.send(SceneKnown(self.scene))
            self._explain(analysis)
        extras = self._extras(analysis)
        if extras is not None:
            self.scene = self.stage("curves", lambda: extras(self.scene))
            self.send(SceneKnown(self.scene))
        nearest = _nearest(analysis) if self._approximated and self.nearest_scene is None else None
        if nearest is not None:
            target: Analysis = nearest

            def draw_nearest() -> Any:
                return scene_data.build_scene(
                    target, region=self.scene.region, resolution=request.resolution, box=self.scene.box
                )

            self.nearest_scene = self.stage("nearest scene", draw_nearest)
            self.send(NearestSceneKnown(self.nearest_scene))

    def _awaits_rounding(self, analysis: Analysis) -> bool:
        """Whether ``analysis`` is rounded input's exact verdict, its rounding still to come."""
        from sorgui.engine.parsing import has_decimals

        request = self.request
        rounded = request.tolerance is not None or has_decimals(request.text)
        typed = analysis.input_kind != "parametrization"  # a map's scene does not wait for a rounding
        return rounded and typed and request.analysis is None and analysis.approximate is None

    def _forget_scene(self) -> None:
        """Drop the scene and what was added to it: the next analysis draws it again, whole."""
        self.scene, self._patch_map, self._approximated, self._conical, self._canal = (None, None, False, False, ())

    def _misses_apex(self, analysis: Analysis) -> bool:
        """Whether the scene, drawn before the cone stage, is in a ball that leaves out the apex
        that ``analysis`` now gives (:func:`~sorgui.session.scene_data.with_apex`): asked once,
        when the cone stage's answer first comes; never for a ball or a box of the user's."""
        from sorgui.session import scene_data

        if self._apex_seen or analysis.conical is None:
            return False
        self._apex_seen = True
        if self.request.radius is not None or self.request.box is not None:
            return False
        region = self.scene.region
        return bool(scene_data.with_apex(region, analysis.conical, None) != region)

    def _explain(self, analysis: Analysis) -> None:
        """For a *no* on irreducible input: the typed components of a blend and their axes
        (found once, drawn again in a scene drawn again)."""
        from sorgui.session import scene_data
        from sorgui.session.components import typed_components

        if (
            analysis.is_sor
            or len(analysis.factors) > 1
            or self.request.analysis is not None
            or analysis.input_kind == "parametrization"  # a map has no typed components
        ):
            return
        if self._components is None:
            self._components = tuple(self.stage("components", lambda: typed_components(self.request.text)))
            if self._components:
                self.send(ComponentsKnown(self._components))
        if self._components:
            recognitions = [c.recognition for c in self._components]
            self.scene = scene_data.with_component_axes(self.scene, recognitions)
            self.send(SceneKnown(self.scene))

    def _extras(self, analysis: Analysis) -> Callable[[Any], Any] | None:
        """What the scene still lacks of ``analysis``: the patch, the rounded-input extras, the
        canal surface's spines and circles, the apex and base curve of a cone or a cylinder."""
        from sorgui.engine.patches import patch_maps
        from sorgui.session import scene_data

        steps: list[Callable[[Any], Any]] = []
        maps = patch_maps(analysis)
        if maps and maps[0] != self._patch_map:  # a sphere's projection comes first, X's own map later
            self._patch_map = maps[0]
            steps.append(lambda scene: scene_data.with_patch(scene, analysis))
        if not self._approximated and analysis.approximate is not None:
            self._approximated = True
            steps.append(lambda scene: scene_data.with_approximation(scene, analysis))
        conical = analysis.conical
        if not self._conical and conical is not None and conical.kind in ("cone", "cylinder"):
            self._conical = True
            steps.append(lambda scene: scene_data.with_conical(scene, analysis))
        canal = analysis.canal
        if canal is not None and canal.is_canal and canal.families:
            drawn = tuple((f.parametrization, f.circle_center) for f in canal.families)
            # a family of positive (or unknown) genus gets no m(t): its SMAT equations serve for picking
            ready = any(p for p, _c in drawn) or all(f.genus != 0 for f in canal.families)
            if drawn != self._canal and ready:
                self._canal = drawn
                steps.append(lambda scene: scene_data.with_canal(scene, analysis))
        if not steps:
            return None

        def apply(scene: Any) -> Any:
            for step in steps:
                scene = step(scene)
            return scene

        return apply


def _nearest(analysis: Analysis) -> Analysis | None:
    """The exact analysis of the nearest exact surface of rounded input, if there is one."""
    approx = analysis.approximate
    if approx is None or approx.nearest is None:
        return None
    return approx.nearest.analysis


def run_job(
    request: JobRequest,
    cancel: threading.Event | Any | None = None,
    progress: Callable[[str], None] | None = None,
    send: Send | None = None,
) -> FinalMessage:
    """Do ``request`` and return the final message (also usable without a process).

    ``send`` receives every intermediate message; ``progress`` (an older, simpler hook) only
    the names of the stages as they start.
    """

    def deliver(message: Message) -> None:
        if send is not None:
            try:
                send(message)
            except OSError:  # the window has gone (closed, or ended by a signal): stop, quietly
                raise Cancelled("the window has gone") from None
        if isinstance(message, StageStarted) and progress is not None:
            progress(message.stage)

    def check() -> None:
        if cancel is not None and cancel.is_set():
            raise Cancelled("the analysis was cancelled")

    presenter = _Presenter(request, deliver, check)
    try:
        if request.analysis is not None:
            analysis = request.analysis
            if not isinstance(analysis, Analysis):
                raise TypeError(f"a job's analysis must be an Analysis, not {type(analysis).__name__}")
            presenter.present(analysis)
        else:
            analysis = analyze(
                request.text,
                method=request.method,
                recognition_only=request.recognition_only,
                singular_timeout=request.singular_timeout,
                timeout=request.singular_timeout,  # the window's limit bounds the whole analysis
                tolerance=request.tolerance,
                cancel=cancel,
                progress=lambda stage: deliver(StageStarted(stage)),
                partial=presenter.present,
                stage_done=lambda stage, seconds: deliver(StageDone(stage, seconds)),
                parsed=lambda start: deliver(Parsed(start)),
            )
            deliver(Analysed())  # the engine is done: its time limit is over
            canal = analysis.canal is not None and bool(analysis.canal.is_canal)
            cone = analysis.conical is not None and analysis.conical.kind == "cone"
            if (
                analysis.parametrizations
                or analysis.approximate is not None
                or analysis.rationality is not None
                or canal
                or cone
            ):
                presenter.present(analysis)  # the complete analysis: patch, rounded-input extras, canal, apex
            else:
                deliver(AnalysisKnown(analysis))
        check()
        if send is not None:  # the scenes went out as messages: not pickled twice
            return Finished(JobResult(analysis, None, tuple(presenter.timings)))
        return Finished(JobResult(analysis, presenter.scene, tuple(presenter.timings), presenter.nearest_scene))
    except Cancelled:
        return JobCancelled()
    except ParseError as exc:
        return Invalid(exc.message, exc.position, exc.end)
    except SorguiError as exc:
        return Failed(exc.message)
    except MemoryError:
        return Failed("the analysis ran out of memory")
    except Exception as exc:  # a bug: keep the window alive, print the details for a report
        traceback.print_exc(file=sys.stderr)
        return Failed(f"internal error ({type(exc).__name__}: {exc})")


def warm_up(waited_for: Callable[[], bool] = lambda: False) -> None:
    """What a spare worker process does while nobody waits: load the scene's modules (VTK and
    pyvista), then freeze the garbage collector's view of everything loaded so far (the
    collections during a job then walk only the job's own objects, not sympy's and VTK's).

    It stops as soon as ``waited_for()`` says a request has arrived (as at the window's start,
    when the first analysis is asked for at once): its verdict needs none of this, and the
    stages that do load what they need themselves.
    """
    steps: tuple[Callable[[], object], ...] = (
        lambda: importlib.import_module("sorgui.session.scene_data"),
        gc.collect,
        gc.freeze,
    )
    for step in steps:
        if waited_for():
            return
        step()


def serve(conn: Connection, cancel: Any, niceness: int = WORKER_NICENESS) -> None:
    """The worker process: lead a process group at a lower priority, wait for one request,
    answer it, exit.

    Leading a group lets the GUI kill the worker and everything it started at once. The
    process starts before it is needed (a warm spare), so waiting here is the normal case;
    the pipe closing without a request means it is not needed any more.
    """
    become_child(niceness=niceness)  # the window killed (even by kill -9): the worker goes too
    warm_up(waited_for=conn.poll)

    try:
        request = conn.recv()
    except (EOFError, OSError):
        return
    try:
        conn.send(run_job(request, cancel, send=conn.send))
    except (BrokenPipeError, OSError):
        pass  # the GUI has gone away or superseded this job
    conn.close()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)  # skip the interpreter's teardown: it would compete with the GUI for the processor
