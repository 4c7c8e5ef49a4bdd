"""The window's view of the session: it subscribes to the session's events and only renders.

:class:`SessionView` turns every event of :class:`~sorgui.session.model.Session` into updates of
the run panel, the results pane, the 3D viewport and the status line:

* a new run clears the results and the 3D view at once (no old verdict under a new equation);
* stages are shown as they start and finish, each result as it arrives (the verdict and the
  axis with their mesh while Singular still runs); rebuilding the results pane is coalesced to
  once per turn of the event loop;
* when the edited equation differs from the analysed one, the results are greyed, the 3D view's
  surface too, and the notice says they belong to the previous equation;
* an input error, a failed stage or a cancelled run is said at the top of the pane;
* for rounded input, the switch shows the equation as typed or the nearest exact surface.
"""

from __future__ import annotations

import html
from typing import TYPE_CHECKING

from PySide6.QtCore import QObject, QTimer, Signal
from PySide6.QtWidgets import QLabel

from sorgui.engine.errors import ParseError
from sorgui.engine.limits import equation_span, statement_span
from sorgui.gui.camera import CameraState
from sorgui.gui.editor import EquationEditor
from sorgui.gui.results import ResultsPane
from sorgui.gui.stages import RunPanel, seconds_text
from sorgui.gui.viewport import Viewport
from sorgui.gui.wording import INVALID_NOTICE, invalid_heading, no_surface_caption
from sorgui.session.job import JobResult
from sorgui.session.model import Run, Session, StageState

if TYPE_CHECKING:
    from sorgui.session.scene import SceneData

PANE_DELAY_MS = 120
"""Results arriving within this time rebuild the results pane once (each rebuild costs the GUI
thread tens of milliseconds for a pane full of formulas)."""

CAPTION_CHARACTERS = 90
"""The viewport's caption shows this much of the equation."""

STALE_NOTICE = (
    "<b>These results are for the previous equation.</b> The equation above has "
    "changed: press Analyze (Ctrl+Return) to analyse it."
)


def short(text: str, limit: int = CAPTION_CHARACTERS) -> str:
    """``text`` on one line, elided to ``limit`` characters."""
    flat = " ".join(text.split())
    return flat if len(flat) <= limit else flat[: limit - 1] + "…"


STARTING = (
    "Starting the analysis process (on the very first start it also builds the font cache of the "
    "formulas, once, which can take a while)"
)
"""What the pane says before the first stage of a run has started."""


class SessionView(QObject):
    """Renders one :class:`Session` into the window's widgets.

    :attr:`shown` is emitted with the run's :class:`~sorgui.session.job.JobResult` once a run
    has finished and its results and scene are on screen (and after a re-mesh).
    """

    shown = Signal(object)

    def __init__(
        self,
        session: Session,
        editor: EquationEditor,
        panel: RunPanel,
        results: ResultsPane,
        viewport: Viewport,
        status: QLabel,
    ) -> None:
        super().__init__(results)
        self.session = session
        self.editor, self.panel, self.results, self.viewport, self.status = editor, panel, results, viewport, status
        self.restore_camera: tuple[str, CameraState | None] | None = None
        """The last session's camera and the equation it looked at: restored when the first
        scene shown is of that same equation."""
        self._fresh_scene = True
        self._pane_timer = QTimer(self)
        self._pane_timer.setSingleShot(True)
        self._pane_timer.setInterval(PANE_DELAY_MS)
        self._dirty = False
        self._shown: tuple[object, bool] | None = None
        self._shown_pending = False
        """Whether the page shown names stages still to come."""
        """The analysis the results pane shows, and whether it is the nearest surface's."""
        self._pane_timer.timeout.connect(self.refresh_pane)
        events = session.events
        events.run_started.connect(self._on_run_start_change)
        events.state_changed.connect(self._on_stage_change)
        events.analysis_changed.connect(self._on_results_change)
        events.components_changed.connect(self._on_results_change)
        events.scene_changed.connect(self._on_scene_change)
        events.nearest_scene_changed.connect(self._on_nearest_scene_change)
        events.run_finished.connect(self._on_run_finish_change)
        events.stale_changed.connect(self._on_stale_change)
        events.view_changed.connect(self._on_view_change)
        events.refreshed.connect(self._on_refresh_change)
        panel.view_requested.connect(self._show_requested_view)

    def close(self) -> None:
        """Stop listening (the window is closing)."""
        self._pane_timer.stop()
        self.session.events.disconnect_all()

    # --- rendering ---

    def refresh_pane(self) -> None:
        """Rebuild the results pane from the session's current run and view."""
        self._pane_timer.stop()
        self._dirty = False
        self._shown = None
        run = self.session.run
        if run is None:
            return
        if run.outcome == "invalid":
            self.results.show_message(invalid_heading(run.message or ""), run.message or "", "error")
        elif run.analysis is None:
            if run.running:
                running = next((s.title for s in run.stage_list() if s.state is StageState.RUNNING), STARTING)
                self.results.show_message(
                    "Analysing…", f"{running}. The verdict appears as soon as it is known.", "info"
                )
            elif run.outcome == "cancelled":
                self.results.show_message("Cancelled", "The analysis was stopped before the verdict was known.", "info")
            else:
                self.results.show_message("The analysis failed", run.message or "", "error")
        else:
            nearest_analysis = self.session.nearest_analysis if self.session.view == "nearest" else None
            nearest = nearest_analysis is not None
            analysis = nearest_analysis if nearest_analysis is not None else run.analysis
            found = run.analysis.approximate.nearest if run.analysis.approximate is not None else None
            pending = {s.name for s in run.stage_list() if s.state in (StageState.PENDING, StageState.RUNNING)}
            done = (
                () if run.report else tuple((s.name, s.seconds) for s in run.stage_list() if s.state is StageState.DONE)
            )
            self.results.show_analysis(
                analysis,
                done,
                pending=pending,
                unfinished={s.name for s in run.unfinished()} if not nearest else set(),
                stopped={s.name for s in run.stage_list() if s.state in (StageState.CANCELLED, StageState.UNFINISHED)},
                limit=run.limit,
                nearest=nearest,
                beyond=nearest and found is not None and not found.within_rounding,
                components=() if nearest else run.components,
                wall=None if run.running or run.report else run.elapsed(),
            )
            self._shown = (analysis, nearest)
            self._shown_pending = bool(pending)
        self.results.set_stale(self.session.stale)
        self.panel.set_nearest_available(self.session.nearest_analysis is not None, self.session.view)

    def _schedule_pane(self) -> None:
        self._dirty = True
        if not self._pane_timer.isActive():
            self._pane_timer.start()

    def _caption(self, run: Run, nearest: bool = False) -> str:
        if nearest:
            return "The nearest exact surface of revolution of: " + short(run.text)
        analysis = run.analysis
        if analysis is not None and analysis.input_kind == "parametrization":
            start, end = statement_span(run.text)
            return "P: " + short(run.text[start:end])
        start, end = equation_span(run.text)  # without a label ('f :=') or a final ';'
        equation = short(run.text[start:end])
        return equation if "=" in equation else "f = " + equation

    def _update_notice(self) -> None:
        run = self.session.run
        if self.session.stale:
            self.panel.set_notice("stale", STALE_NOTICE)
        elif run is not None and run.report and run.outcome in (None, "finished"):
            self.panel.set_notice(
                "report",
                "<b>Shown as saved in the report, not analysed again.</b> "
                "Press Analyze (Ctrl+Return) to analyse the equation anew.",
            )
        elif run is not None and run.limited:
            names = ", ".join(stage.title for stage in run.unfinished())
            self.panel.set_notice(
                "limit",
                f"<b>Stopped at the time limit of {run.limit:g} s.</b> Not finished: {html.escape(names)}; "
                "their results are undecided, what was finished is shown (Analysis → Time Limit… allows more).",
            )
        elif run is None or run.running or run.outcome == "finished":
            self.panel.set_notice(None)
        elif run.outcome == "invalid":
            self.panel.set_notice("error", INVALID_NOTICE)
        elif run.outcome == "failed":
            failed = run.failed_stage()
            where = f" in the stage “{failed.title}”" if failed is not None else ""
            kept = " The results of the stages before it are shown." if run.analysis is not None else ""
            self.panel.set_notice("error", f"<b>The analysis failed{where}:</b> {run.message}.{kept}")
        else:
            done = sum(1 for stage in run.stage_list() if stage.state is StageState.DONE)
            if run.analysis is not None:
                kept = "what was done is shown"
            elif done:
                plural = "s" if done > 1 else ""
                kept = f"{done} stage{plural} finished before the verdict was known, so no result is shown"
            else:
                kept = "nothing was finished"
            self.panel.set_notice(
                "cancelled",
                f"<b>Cancelled</b> after {seconds_text(run.elapsed())}: {kept}; the rest is marked cancelled.",
            )

    # --- handlers ---

    def _on_run_start_change(self, run: Run) -> None:
        """A new run: its stages at once. The same equation analysed again keeps its results on
        screen until the new ones replace them; another equation's are cleared at once."""
        shown = self._shown[0] if self._shown is not None else None
        again = not self._shown_nearest() and getattr(shown, "input", None) == run.text
        self._fresh_scene = not again
        self.panel.show_run(run)
        self._update_notice()
        if again:
            self._shown = None  # the new run's first verdict replaces the pane at once
            self.viewport.caption.setText("Analysing again: " + short(run.text))
        else:
            self.refresh_pane()
            self.viewport.clear(caption="Analysing: " + short(run.text))
        self.status.setText("Drawing the saved report…" if run.report else "Starting…")

    def _shown_nearest(self) -> bool:
        return self._shown is not None and self._shown[1]

    def _on_stage_change(self, name: str, state: StageState) -> None:
        run = self.session.run
        if run is None:
            return
        self.panel.show_run(run)
        if state is StageState.RUNNING and run.running:
            self.status.setText(run.stages[name].title + "…")

    def _on_results_change(self, _value: object) -> None:
        run = self.session.run
        if self._shown is None and run is not None and run.analysis is not None:
            self.refresh_pane()  # the run's first verdict: shown at once, never coalesced
        else:
            self._schedule_pane()

    def _on_scene_change(self, scene: SceneData) -> None:
        run = self.session.run
        if run is None or self.session.view != "typed":
            return
        self._show_scene(scene, self._caption(run))

    def _on_nearest_scene_change(self, scene: SceneData) -> None:
        run = self.session.run
        if run is not None and self.session.view == "nearest":
            self._show_scene(scene, self._caption(run, nearest=True))

    def _show_scene(self, scene: SceneData, caption: str) -> None:
        if self._dirty and not self.viewport.rendering:
            self.refresh_pane()  # the results first: drawing must first create the render window
        fresh, camera = self._fresh_scene, None
        if fresh and self.restore_camera is not None:
            equation, state = self.restore_camera
            run = self.session.run
            camera = state if run is not None and run.text == equation else None
            self.restore_camera = None
        self._fresh_scene = False
        shown = self.viewport.scene
        # a new ball or box (View → Cut to a Box, the ball radius) is framed afresh, as a new surface
        moved = shown is not None and (shown.region != scene.region or shown.box != scene.box)
        self.viewport.show_scene(scene, reset_camera=(fresh or moved) and camera is None, caption=caption)
        if camera is not None:
            self.viewport.restore_camera(camera)
        if self.session.stale:
            self.viewport.set_stale(True, "Previous equation (out of date): " + caption)

    def _on_run_finish_change(self, run: Run) -> None:
        # A page that says a stage is still coming ("being decided") is rebuilt at the end, even
        # when no new result came: a stage that did not run (a sphere has no rationality) is over.
        if self._dirty or run.outcome != "finished" or self._shown_pending:
            self.refresh_pane()
        self.panel.show_run(run)
        self._update_notice()
        if run.outcome == "finished":
            analysis = run.analysis
            assert analysis is not None  # a finished run has its whole analysis
            verdict = {
                "sor": "surface of revolution",
                "near": "nearly a surface of revolution",
                "not": "not a surface of revolution",
                "not exactly": "not exactly a surface of revolution (nearness within the rounding undecided)",
                "undecided": "undecided whether it is a surface of revolution",
            }[analysis.verdict]
            summary = run.scene.summary() if run.scene is not None else ""
            notes = " ".join(run.scene.notes) if run.scene is not None else ""
            if run.report:
                self.status.setText(f"Report shown as saved, not analysed again: {verdict}; {summary}".strip())
            elif run.limited:
                so_far = f"{verdict}; some later stages undecided" if analysis.recognition.decided else verdict
                stopped = f"Stopped at the time limit of {run.limit:g} s after {run.elapsed():.2f} s"
                self.status.setText(f"{stopped}: {so_far}; {summary}".strip())
            else:
                self.status.setText(f"Done in {run.elapsed():.2f} s: {verdict}; {summary}. {notes}".strip())
            if run.result is not None:
                self.shown.emit(run.result)
        elif run.outcome == "invalid":
            assert run.error is not None  # an invalid text's error, set with the outcome
            message, position, end = run.error
            assert position is not None  # every invalid text's error comes from a ParseError
            self.editor.show_error(ParseError(message, position, end))
            self.status.setText("Fix the equation to analyse it")
            self.viewport.clear(caption=no_surface_caption(message))
        elif run.outcome == "failed":
            self.status.setText("Failed: " + (run.message or ""))
            if run.scene is None:
                self.viewport.clear(caption="No surface: the analysis failed")
        else:
            self.status.setText("Cancelled")
            if run.scene is None:
                self.viewport.clear(caption="Cancelled before the surface was drawn: " + short(run.text))

    def _on_stale_change(self, stale: bool) -> None:
        run = self.session.run
        self.results.set_stale(stale)
        self._update_notice()
        if run is not None and self.viewport.scene is not None:
            caption = self._caption(run, self.session.view == "nearest")
            self.viewport.set_stale(stale, ("Previous equation (out of date): " if stale else "") + caption)

    def _show_requested_view(self, view: str) -> None:
        if self.session.nearest_analysis is not None or view == "typed":
            self.session.set_view(view)

    def _on_view_change(self, view: str) -> None:
        run = self.session.run
        self.refresh_pane()
        if run is None:
            return
        scene = run.nearest_scene if view == "nearest" else run.scene
        if scene is not None:
            self.viewport.show_scene(scene, reset_camera=False, caption=self._caption(run, view == "nearest"))
            if self.session.stale:
                self.viewport.set_stale(True)

    def _on_refresh_change(self, what: str, result: JobResult | None) -> None:
        if result is None:
            self.status.setText("Could not redo the mesh")
            return
        assert result.scene is not None  # a redrawing sends its scene before it finishes
        notes = " ".join(result.scene.notes)  # why nothing is drawn in the ball asked for
        self.status.setText(f"Re-meshed: {result.scene.summary()}. {notes}".strip())
        self.shown.emit(result)
