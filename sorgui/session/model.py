"""The application model: one equation, one analysis run, the state of each of its stages.

A :class:`Session` owns the equation being edited and the current :class:`Run` (the analysis of
one text: its stages, its typed results as they arrive, how it ended). It starts jobs through a
:class:`Runner` (the window's process worker, or :class:`InlineRunner` here, without Qt), takes
the worker's messages in :meth:`Session.handle`, and announces every change through
:class:`~sorgui.session.events.SessionEvents`. Views subscribe and only render.

Two rules make the window trustworthy: a new run drops everything of the previous one at once
(no old verdict under a new equation), and the moment the edited equation differs from the
analysed one the session is *stale* (``stale_changed(True)``), so views mark the results as
belonging to the previous equation.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from enum import Enum
from typing import TYPE_CHECKING, Any, Protocol

from sorgui.engine.results import Analysis
from sorgui.engine.stage_results import BEING_COMPUTED
from sorgui.engine.vocabulary import no_surface_words
from sorgui.session.components import Component
from sorgui.session.events import SessionEvents
from sorgui.session.job import JobRequest, JobResult, run_job
from sorgui.session.messages import (
    SUPERVISION,
    AnalysisKnown,
    ComponentsKnown,
    Failed,
    FinalMessage,
    Finished,
    Hangup,
    Invalid,
    JobCancelled,
    Message,
    NearestSceneKnown,
    SceneKnown,
    StageDone,
    StageStarted,
)

if TYPE_CHECKING:
    from sorgui.session.scene import SceneData

STAGES = (
    "engine",
    "parse",
    "parametric",
    "properness",
    "implicit equation",
    "recognition",
    "factors",
    "approximate",
    "scene",
    "real locus",
    "rationality",
    "parametrizations",
    "conical",
    "canal",
    "nearest",
    "curves",
    "nearest scene",
    "components",
)
"""Every stage a run may have, in the order they usually start. A run plans the ones its input
can need (:func:`planned_stages`) and marks those the analysis turns out not to need as
skipped, so the number of stages shown never changes while it runs."""

REVOLUTION_ONLY = ("real locus", "rationality", "parametrizations")
"""Stages that run only for a surface of revolution."""

NOT_REVOLUTION_ONLY = ("components",)
"""Stages that run only when the answer is no (the typed components of a blend)."""

ROUNDED_ONLY = ("approximate", "nearest", "nearest scene")
"""Stages that run only for rounded (decimal) input or a given tolerance."""

PARAMETRIC_ONLY = ("parametric", "properness", "implicit equation")
"""Stages that run only for a parametrization (docs/math.md §13)."""

WORKER_STAGES = ("scene", "curves", "nearest scene", "components")
"""Stages of the worker itself (they run beside the engine's)."""

REPEATED = ("curves",)
"""Worker stages that run again as the analysis learns more (their times add up): between two
runs such a stage waits (pending, with its time so far), and it is done when the run is."""

STAGE_TITLES = {
    "engine": "Loading the exact engine (sympy)",
    "parse": "Reading the equation",
    "parametric": "Normal lines, apex and directions of the map",
    "properness": "Whether the map is proper (Singular)",
    "implicit equation": "Implicit equation of the map",
    "recognition": "Symmetry algebra, axis and profile",
    "factors": "Factors over K",
    "approximate": "Nearest surface of revolution (rounded input)",
    "nearest": "Exact analysis of the nearest surface",
    "real locus": "Real points",
    "conical": "Cone or cylinder over a curve",
    "canal": "Canal surface (envelope of spheres)",
    "canal test": "Canal surface test",
    "canal spine": "Spine curve",
    "canal genus": "Genus of the spine",
    "canal family": "Family of spheres",
    "canal certificate": "Canal certificate",
    "canal parametrization": "Canal parameterization",
    "scene": "Mesh of the surface",
    "curves": "Curves and patch in the 3D view",
    "nearest scene": "Mesh of the nearest surface",
    "rationality": "Table 1 row and genera (Singular)",
    "parametrizations": "Parameterizations",
    "components": "Typed components (explaining the no)",
}


class StageState(str, Enum):
    """Where a stage of a run is."""

    PENDING = "pending"
    RUNNING = "running"
    DONE = "done"
    FAILED = "failed"
    CANCELLED = "cancelled"
    SKIPPED = "skipped"
    """Not needed for this input (e.g. no rationality for a surface that is not one of revolution)."""
    UNFINISHED = "unfinished"
    """Cut short, or never reached, by the time limit (its result is undecided)."""


@dataclass
class Stage:
    """One stage of a run: its state, the seconds it took (summed over repeats) and, while it
    runs, when it started (``time.monotonic``)."""

    name: str
    state: StageState = StageState.PENDING
    seconds: float = 0.0
    started: float | None = None
    note: str | None = None
    """What the stage found when that is the news, e.g. "not found" (a failed stage)."""

    @property
    def title(self) -> str:
        return STAGE_TITLES.get(self.name, self.name)

    def elapsed(self, now: float | None = None) -> float:
        """Seconds so far: the recorded time, plus the running time if it runs."""
        if self.state is StageState.RUNNING and self.started is not None:
            return self.seconds + ((now if now is not None else time.monotonic()) - self.started)
        return self.seconds


@dataclass
class Run:
    """The analysis of one text: its stages and the results known so far.

    ``outcome`` is ``None`` while it runs, then ``"finished"``, ``"invalid"`` (not a
    polynomial: ``error`` is ``(message, position, end)``), ``"failed"`` (``message``) or
    ``"cancelled"``.
    """

    text: str
    request: JobRequest
    stages: dict[str, Stage] = field(default_factory=dict)
    analysis: Analysis | None = None
    scene: SceneData | None = None
    nearest_scene: SceneData | None = None
    components: tuple[Component, ...] = ()
    outcome: str | None = None
    message: str | None = None
    error: tuple[str, int | None, int | None] | None = None
    result: JobResult | None = None
    started: float = field(default_factory=time.monotonic)
    ended: float | None = None

    def __post_init__(self) -> None:
        if not self.stages:
            self.stages = {name: Stage(name) for name in planned_stages(self.request)}

    @property
    def running(self) -> bool:
        return self.outcome is None

    @property
    def progress(self) -> tuple[int, int]:
        """``(finished stages, all stages)``, skipped ones counted as finished."""
        over = (StageState.DONE, StageState.SKIPPED, StageState.FAILED, StageState.CANCELLED, StageState.UNFINISHED)
        return sum(s.state in over for s in self.stages.values()), len(self.stages)

    def stage_list(self) -> list[Stage]:
        return list(self.stages.values())

    def failed_stage(self) -> Stage | None:
        return next((s for s in self.stages.values() if s.state is StageState.FAILED), None)

    def elapsed(self) -> float:
        return (self.ended if self.ended is not None else time.monotonic()) - self.started

    @property
    def report(self) -> bool:
        """Whether the run shows a saved report (its analysis given, only the scene made)."""
        return self.request.analysis is not None

    @property
    def limit(self) -> float:
        """The run's time limit in seconds (the window's Analysis → Time Limit…)."""
        return self.request.singular_timeout

    @property
    def limited(self) -> bool:
        """Whether the run ended at its time limit with stages not finished."""
        return self.outcome == "finished" and self.analysis is not None and bool(self.analysis.unfinished)

    def unfinished(self) -> list[Stage]:
        return [s for s in self.stages.values() if s.state is StageState.UNFINISHED]


def _settled(analysis: Analysis, outcome: str) -> Analysis:
    """``analysis`` as it stands once its run ended: a map's implicit equation still "being
    computed" when the run was cancelled or failed is not computed."""
    record = analysis.parametric
    if record is None or record.implicit_status != BEING_COMPUTED:
        return analysis
    status = f"not computed: the analysis was {'cancelled' if outcome == 'cancelled' else 'stopped'}"
    return replace(analysis, parametric=replace(record, implicit_status=status))


def result_unfinished(message: Finished) -> bool:
    """Whether a finished job's analysis was cut short by its time limit."""
    return bool(getattr(message.result.analysis, "unfinished", ()))


def planned_stages(request: JobRequest) -> tuple[str, ...]:
    """The stages a run of ``request`` may need: the rounded-input ones only for decimals or a
    given tolerance, the analysis' stages only when it is computed (not for a saved report)."""
    from sorgui.engine.parsing import has_decimals, is_parametrization

    rounded = request.tolerance is not None or has_decimals(request.text)
    parametric = is_parametrization(request.text)
    names = [n for n in STAGES if (rounded or n not in ROUNDED_ONLY) and (parametric or n not in PARAMETRIC_ONLY)]
    if parametric:  # no nearest exact surface for a map (docs/math.md §13)
        names = [n for n in names if n not in ("nearest", "nearest scene")]
    if request.analysis is not None:  # a saved report: only the worker's own stages run
        names = [n for n in names if n in WORKER_STAGES]
    return tuple(names)


class Runner(Protocol):
    """Runs one job at a time and hands every message to the session's :meth:`Session.handle`;
    starting a job supersedes the running one (whose messages are then never delivered)."""

    def start(self, request: JobRequest) -> None: ...

    def cancel(self) -> None: ...


class InlineRunner:
    """Runs a job to its end in the calling thread (the command line, tests): :meth:`start`
    returns when the run is over. :meth:`cancel` may be called from a session callback."""

    def __init__(self, deliver: Callable[[Message], None]) -> None:
        import threading

        self._deliver = deliver
        self._cancel = threading.Event()

    def start(self, request: JobRequest) -> None:
        self._cancel.clear()
        self._deliver(run_job(request, self._cancel, send=self._deliver))

    def cancel(self) -> None:
        self._cancel.set()


VIEWS = ("typed", "nearest")
"""What the results and the 3D view show: the equation as typed, or for rounded input the
nearest exact surface of revolution (``Analysis.approximate.nearest``)."""


class Session:
    """The equation being edited, the current run, and the events views subscribe to."""

    def __init__(self, runner: Runner | None = None) -> None:
        self.events = SessionEvents()
        self.runner: Runner = runner if runner is not None else InlineRunner(self.handle)
        self.equation = ""
        self.run: Run | None = None
        self.view = "typed"
        self._stale = False
        self._refresh: str | None = None
        """``"scene"`` while a job only redoes the scene of the current run."""

    # --- the equation ---

    @property
    def stale(self) -> bool:
        """Whether the shown results belong to another equation than the one being edited."""
        return self._stale

    def set_equation(self, text: str) -> None:
        """The edited equation is now ``text`` (results of another text become stale)."""
        if text == self.equation:
            return
        self.equation = text
        self.events.equation_changed.emit(text)
        self._update_stale()

    def _update_stale(self) -> None:
        stale = self.run is not None and self.run.text != self.equation
        if stale != self._stale:
            self._stale = stale
            self.events.stale_changed.emit(stale)

    # --- runs ---

    def analyze(self, text: str | None = None, **options: Any) -> Run:
        """Start the analysis of ``text`` (default: the edited equation); ``options`` are fields
        of :class:`JobRequest` (``resolution``, ``method``, …). Any previous run is
        superseded and everything it showed is dropped at once."""
        if text is not None:
            self.set_equation(text)
        request = JobRequest(self.equation, **options)
        self._refresh = None
        self.run = Run(self.equation, request)
        self.view = "typed"
        self._update_stale()
        self.events.run_started.emit(self.run)
        self.runner.start(request)
        return self.run

    def remesh(
        self,
        radius: float | None = None,
        resolution: int | None = None,
        box: tuple[float, float, float, float, float, float] | None = None,
    ) -> bool:
        """Rebuild the current run's scene in a ball of ``radius``, or cut to ``box`` in the ball
        about it (no new analysis)."""
        changes: dict[str, Any] = {"radius": radius, "box": box}
        if resolution is not None:
            changes["resolution"] = resolution
        return self._redo("scene", changes)

    @property
    def can_redo(self) -> bool:
        """Whether the current run's scene can be made again: it has ended (finished,
        or cancelled or stopped after its mesh was drawn) and nothing is being redone."""
        run = self.run
        if run is None or run.running or run.analysis is None or self._refresh is not None:
            return False
        return run.outcome == "finished" or run.scene is not None

    def _redo(self, what: str, changes: dict[str, Any]) -> bool:
        """Redo the scene of the current run (``False`` when :attr:`can_redo` is not)."""
        run = self.run
        if run is None or not self.can_redo:
            return False
        self._refresh = what
        self.runner.start(replace(run.request, analysis=run.analysis, **changes))
        return True

    def cancel(self) -> None:
        """Ask the running job to stop; what is done stays, the rest becomes *cancelled*."""
        if self.run is not None and self.run.running:
            self.runner.cancel()

    def set_view(self, view: str) -> None:
        """Show the equation as typed (``"typed"``) or the nearest exact surface (``"nearest"``)."""
        if view not in VIEWS:
            raise ValueError(f"unknown view {view!r}; one of {VIEWS}")
        if view == "nearest" and self.nearest_analysis is None:
            raise ValueError("there is no nearest exact surface to show")
        if view != self.view:
            self.view = view
            self.events.view_changed.emit(view)

    @property
    def nearest_analysis(self) -> Analysis | None:
        """The exact analysis of the nearest exact surface of the current (rounded) input."""
        run = self.run
        if run is None or run.analysis is None or run.analysis.approximate is None:
            return None
        nearest = run.analysis.approximate.nearest
        return None if nearest is None else nearest.analysis

    # --- messages of the runner ---

    def handle(self, message: Message) -> None:
        """Take one message of the current job (:mod:`sorgui.session.messages`)."""
        run = self.run
        if run is None:
            return
        if self._refresh is not None:
            self._handle_refresh(run, message)
            return
        if not run.running or isinstance(message, SUPERVISION):
            return
        match message:
            case StageStarted(stage):
                self._start_stage(run, stage)
            case StageDone(stage, seconds):
                self._finish_stage(run, stage, seconds, add=True)
            case AnalysisKnown(analysis):
                run.analysis = analysis
                for name, seconds in () if run.report else analysis.timings:  # a report's stages ran elsewhere
                    self._finish_stage(run, name, seconds, add=False)
                self._skip_unneeded(run, analysis)
                self.events.analysis_changed.emit(analysis)
            case SceneKnown(scene):
                run.scene = scene
                self.events.scene_changed.emit(scene)
            case NearestSceneKnown(scene):
                run.nearest_scene = scene
                self.events.nearest_scene_changed.emit(scene)
            case ComponentsKnown(components):
                run.components = tuple(components)
                self.events.components_changed.emit(run.components)
            case Finished() | Invalid() | Failed() | JobCancelled() | Hangup():
                self._end(run, message)

    def _handle_refresh(self, run: Run, message: Message) -> None:
        match message:
            case SceneKnown(scene):
                run.scene = scene
                self.events.scene_changed.emit(scene)
            case Finished() | Invalid() | Failed() | JobCancelled():
                what, self._refresh = self._refresh, None
                redone = None
                if isinstance(message, Finished):  # a cancelled run redrawn keeps what it had, with the new mesh
                    if run.result is not None:
                        run.result = replace(run.result, scene=run.scene)
                    if run.result is None and run.analysis is not None:
                        redone = JobResult(run.analysis, run.scene, (), run.nearest_scene)
                    else:
                        redone = run.result
                self.events.refreshed.emit(what, redone)

    def _set_state(self, run: Run, stage: Stage, state: StageState) -> None:
        if stage.state is not state:
            stage.state = state
            self.events.state_changed.emit(stage.name, state)

    def _stage(self, run: Run, name: str) -> Stage:
        """The stage ``name``; an unplanned one is inserted after the last stage that started."""
        if name not in run.stages:
            names = list(run.stages)
            started = [i for i, n in enumerate(names) if run.stages[n].state is not StageState.PENDING]
            at = started[-1] + 1 if started else 0
            names.insert(at, name)
            old = run.stages
            run.stages = {n: old[n] if n in old else Stage(n) for n in names}
        return run.stages[name]

    def _skip_unneeded(self, run: Run, analysis: Analysis) -> None:
        """Once the verdict is known, the planned stages it does not need are skipped."""
        unneeded = NOT_REVOLUTION_ONLY if analysis.is_sor else REVOLUTION_ONLY
        if len(analysis.factors) > 1:
            unneeded = (*unneeded, *NOT_REVOLUTION_ONLY)
        for name in unneeded:
            stage = run.stages.get(name)
            if stage is not None and stage.state is StageState.PENDING:
                self._set_state(run, stage, StageState.SKIPPED)

    def _start_stage(self, run: Run, name: str) -> None:
        """``name`` runs. The engine runs one stage at a time: one of its stages starting ends the
        one before (whose end the engine does not always announce)."""
        now = time.monotonic()
        if name not in WORKER_STAGES:
            for other in run.stages.values():
                if other.state is StageState.RUNNING and other.name not in WORKER_STAGES and other.name != name:
                    other.seconds = now - (other.started or now)
                    other.started = None
                    self._set_state(run, other, StageState.DONE)
                    self.events.stage_done.emit(other.name, other.seconds)
        stage = self._stage(run, name)
        if stage.state is StageState.DONE:
            return  # announced again after it ended (its end came first): it stays done
        stage.started = now
        self._set_state(run, stage, StageState.RUNNING)

    def _finish_stage(self, run: Run, name: str, seconds: float, add: bool) -> None:
        """``name`` ended after ``seconds`` (``add``: one more run of it). A stage that may run
        again waits (pending) until the run ends; any other is done, and its time final."""
        stage = self._stage(run, name)
        if stage.state is StageState.DONE and name not in REPEATED:
            if not add and seconds != stage.seconds:  # the engine's own figure for it
                stage.seconds = seconds
            return
        stage.seconds = stage.seconds + seconds if add else seconds
        stage.started = None
        self._set_state(run, stage, StageState.PENDING if name in REPEATED else StageState.DONE)
        self.events.stage_done.emit(name, stage.seconds)

    def _end(self, run: Run, message: FinalMessage | Hangup) -> None:
        run.outcome = {Finished: "finished", Invalid: "invalid", JobCancelled: "cancelled"}.get(type(message), "failed")
        run.ended = time.monotonic()
        rest = StageState.CANCELLED if run.outcome == "cancelled" else StageState.SKIPPED
        running = {
            "finished": StageState.DONE,
            "invalid": StageState.FAILED,
            "failed": StageState.FAILED,
            "cancelled": StageState.CANCELLED,
        }[run.outcome]
        if isinstance(message, Finished) and result_unfinished(message):
            running = rest = StageState.UNFINISHED  # the time limit cut them short
        match message:
            case Finished(result):
                run.analysis = result.analysis
                scene = run.scene if run.scene is not None else result.scene
                run.scene = _with_real_points(scene, result.analysis)
                if run.scene is not scene and run.scene is not None:
                    self.events.scene_changed.emit(run.scene)  # its note, shown under the empty view
                run.nearest_scene = run.nearest_scene if run.nearest_scene is not None else result.nearest_scene
                run.result = replace(result, scene=run.scene, nearest_scene=run.nearest_scene)
            case Invalid(text, position, end):
                run.error = (text, position, end)
                run.message = text
            case Failed(text):
                run.message = text
            case JobCancelled():
                run.message = "cancelled"
            case _:
                run.message = "the analysis process hung up"
        if run.analysis is not None:
            run.analysis = _settled(run.analysis, run.outcome)
        now = time.monotonic()
        for stage in run.stages.values():
            if stage.state is StageState.RUNNING:
                if stage.started is not None and stage.name not in WORKER_STAGES:
                    stage.seconds += now - stage.started
                stage.started = None
                self._set_state(run, stage, running)
            elif stage.state is StageState.PENDING:
                waited = StageState.SKIPPED if stage.name in WORKER_STAGES else rest
                self._set_state(run, stage, StageState.DONE if stage.seconds > 0 else waited)
        implicit = run.stages.get("implicit equation")
        record = run.analysis.parametric if run.analysis is not None else None
        if implicit is not None and record is not None and record.implicit_status.startswith("not found"):
            implicit.note = "not found"
            self._set_state(run, implicit, StageState.FAILED)
        self.events.run_finished.emit(run)


def _with_real_points(scene: SceneData | None, analysis: Analysis) -> SceneData | None:
    """An empty scene whose note says what the real points are, once the real locus is known
    (the scene is drawn before it): ``x² + y² + z² + 1`` was told to give a region."""
    if scene is None or not scene.surface.is_empty:
        return scene
    words = no_surface_words(analysis.real_locus)
    return scene if words is None else replace(scene, notes=(f"{words[0].upper()}{words[1:]}.",))
