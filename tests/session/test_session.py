"""The Qt-free session: stages as they arrive, typed results, the never-stale rule, cancel.

Real analyses (the exact engine and Singular) run in this process through the session's
:class:`~sorgui.session.InlineRunner`; the state machine's rarer paths (a failed stage, an
unplanned stage) are fed the worker's own messages.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from sorgui.engine.results import Analysis
from sorgui.engine.stage_results import BEING_COMPUTED
from sorgui.examples import example_text
from sorgui.session import Session, StageState
from sorgui.session.components import component_texts
from sorgui.session.job import JobRequest
from sorgui.session.messages import AnalysisKnown, Failed, JobCancelled, StageStarted

TORUS = example_text("torus")


def record(session: Session) -> list[tuple[str, tuple]]:
    """Every event of ``session``, in order, with its arguments."""
    log: list[tuple[str, tuple]] = []
    for name in session.events.NAMES:
        getattr(session.events, name).connect(lambda *args, n=name: log.append((n, args)))
    return log


def states(session: Session) -> dict[str, StageState]:
    return {stage.name: stage.state for stage in session.run.stage_list()}


def test_results_arrive_stage_by_stage_as_typed_objects() -> None:
    session = Session()
    log = record(session)
    run = session.analyze(TORUS, resolution=40)
    assert run.outcome == "finished"
    names = [name for name, _ in log]
    first = names.index("analysis_changed")
    early = log[first][1][0]
    assert isinstance(early, Analysis)
    assert early.is_sor and early.recognition.axis.direction == ("0", "0", "1")
    assert early.rationality is None, "the verdict is published before Singular runs"
    assert ("state_changed", ("rationality", StageState.RUNNING)) in log[first:]
    assert names.index("scene_changed") < log.index(("state_changed", ("rationality", StageState.RUNNING)))
    assert isinstance(run.analysis, Analysis) and run.analysis.rationality.table_row == 1
    assert run.analysis.parametrizations and run.scene.patch is not None
    done = {name: StageState.DONE for name in states(session)}
    assert states(session) == {**done, "components": StageState.SKIPPED}, "a surface of revolution needs no components"
    assert all(stage.seconds > 0 for stage in run.stage_list() if stage.state is StageState.DONE)
    assert run.progress == (len(run.stages), len(run.stages))
    assert "formulas" not in run.stages, "the worker does not typeset: the window has them typeset on the side"
    assert names[-1] == "run_finished"


@pytest.mark.parametrize("text", ["x^2 + y^2 + z^2 - 4", "y^2 - x^3 - x^2"])
def test_the_scenes_patch_is_the_first_map_the_files_take(text: str) -> None:
    """The window's patch is made of :func:`~sorgui.engine.patches.patch_maps`'s first map, as
    the patch files are: the sphere's own map once it comes (its stereographic projection is known
    first, from the recognition), the map of a cylinder over a curve by its lines."""
    from sorgui.engine.patches import patch_maps
    from sorgui.session.scene_data import with_patch

    session = Session()
    run = session.analyze(text, resolution=30)
    assert run.outcome == "finished"
    first = patch_maps(run.analysis)[0]
    assert first.method != "stereographic projection of the sphere"
    assert run.scene.patch is not None
    expected = with_patch(replace(run.scene, patch=None), run.analysis).patch
    assert expected is not None
    np.testing.assert_array_equal(run.scene.patch.points, expected.points)  # nan where the other's is


def test_the_stage_list_is_planned_once_and_no_stage_runs_again_after_it_is_done() -> None:
    """The rows a run shows do not change in number while it runs, and a stage that is done
    never shows as running again; the curves of the 3D view (drawn again as the patch and the
    canal spines become known) wait between their runs and are done when the run is."""
    session = Session()
    counts: list[int] = []
    history: dict[str, list[StageState]] = {}

    def seen(name: str, state: StageState) -> None:
        counts.append(len(session.run.stages))
        history.setdefault(name, []).append(state)

    session.events.state_changed.connect(seen)
    run = session.analyze(TORUS, resolution=30)
    assert run.outcome == "finished" and len(set(counts)) == 1, counts
    assert "approximate" not in run.stages and "nearest" not in run.stages, "no decimals in the torus"
    for name, states_seen in history.items():
        if StageState.DONE in states_seen:
            assert StageState.RUNNING not in states_seen[states_seen.index(StageState.DONE) :], (name, states_seen)
    assert history["curves"][-2:] == [StageState.PENDING, StageState.DONE], history["curves"]
    rounded = session.analyze("x^2 + y^2 - 1.5*z", resolution=30)
    assert rounded.outcome == "finished" and {"approximate", "nearest"} <= set(rounded.stages)


def test_a_surface_that_is_not_one_of_revolution_skips_the_rationality() -> None:
    session = Session()
    run = session.analyze(example_text("ellipsoid"), resolution=30)
    assert run.outcome == "finished" and not run.analysis.is_sor
    assert states(session)["rationality"] is StageState.SKIPPED
    assert states(session)["parametrizations"] is StageState.SKIPPED
    assert states(session)["recognition"] is StageState.DONE


def test_a_changed_equation_makes_the_results_stale_and_a_new_run_drops_them() -> None:
    session = Session()
    log = record(session)
    session.analyze(TORUS, resolution=30)
    assert not session.stale
    session.set_equation(TORUS + " + 1")
    assert session.stale and ("stale_changed", (True,)) in log
    assert session.run.text == TORUS, "the shown results still name their own equation"
    seen: list[object] = []
    session.events.run_started.connect(lambda run: seen.append((run.analysis, run.scene, session.stale)))
    session.analyze(resolution=30)
    assert seen == [(None, None, False)], "nothing of the old run survives the start of the new one"
    assert ("stale_changed", (False,)) in log
    session.set_equation(session.run.text)
    assert not session.stale


def test_cancel_keeps_what_is_done_and_marks_the_rest_cancelled() -> None:
    session = Session()
    session.events.analysis_changed.connect(lambda analysis: session.cancel())
    run = session.analyze(TORUS, resolution=30)
    assert run.outcome == "cancelled"
    assert run.analysis is not None and run.analysis.is_sor, "the verdict stays"
    stages = states(session)
    assert stages["recognition"] is StageState.DONE
    assert stages["rationality"] is StageState.CANCELLED
    assert stages["parametrizations"] is StageState.CANCELLED


def test_a_map_whose_equation_was_not_found_marks_that_stage() -> None:
    """The implicit equation's stage ends "not found" (✗), not done, when the engine found none
    (here: Singular's elimination runs over QQ only); a cancelled run's equation still "being
    computed" is "not computed" once the run has ended."""
    session = Session()
    run = session.analyze("(s, t, sqrt(2)*s^3*t + t^5 + s)", resolution=20)
    assert run.outcome == "finished"
    assert run.analysis.parametric.implicit_status.startswith("not found")
    stage = run.stages["implicit equation"]
    assert stage.state is StageState.FAILED and stage.note == "not found"
    assert states(session)["recognition"] is not StageState.FAILED

    session = Session(ScriptedRunner())
    session.analyze("(s, t, s^3*t + t^5 + s)")
    session.handle(StageStarted("parametric"))
    known = run.analysis.parametric
    early = replace(run.analysis, parametric=replace(known, implicit_status=BEING_COMPUTED), timings=())
    session.handle(AnalysisKnown(early))
    session.handle(StageStarted("implicit equation"))
    session.handle(JobCancelled())
    assert session.run.analysis.parametric.implicit_status == "not computed: the analysis was cancelled"
    assert states(session)["implicit equation"] is StageState.CANCELLED


def test_input_errors_end_the_run_with_a_position() -> None:
    session = Session()
    run = session.analyze("x^2 +* y")
    assert run.outcome == "invalid" and run.analysis is None
    message, position, end = run.error
    assert position == 5 and end > position and message == run.message  # at the "*"
    assert states(session)["parse"] is StageState.FAILED
    assert states(session)["recognition"] is StageState.SKIPPED


class ScriptedRunner:
    """A runner that only records requests: the test feeds the worker's messages itself."""

    def __init__(self) -> None:
        self.requests: list[JobRequest] = []
        self.cancelled = 0

    def start(self, request: JobRequest) -> None:
        self.requests.append(request)

    def cancel(self) -> None:
        self.cancelled += 1


def test_a_failed_stage_is_marked_and_the_rest_is_not_run() -> None:
    runner = ScriptedRunner()
    session = Session(runner)
    session.analyze("x^2 + y^2 - z")
    for stage in ("parse", "recognition", "factors", "rationality"):
        session.handle(StageStarted(stage))
    assert states(session)["factors"] is StageState.DONE
    session.handle(Failed("Singular: out of memory"))
    run = session.run
    assert run.outcome == "failed" and run.message == "Singular: out of memory"
    assert run.failed_stage().name == "rationality"
    assert states(session)["parametrizations"] is StageState.SKIPPED


def test_an_unplanned_engine_stage_is_inserted_where_it_starts() -> None:
    session = Session(ScriptedRunner())
    session.analyze("x^2 + y^2 - 1.0000001*z^2")
    assert "approximate" in session.run.stages, "planned for decimals"
    for stage in ("parse", "recognition", "canal spine"):
        session.handle(StageStarted(stage))
    names = [stage.name for stage in session.run.stage_list()]
    assert names.index("canal spine") == names.index("recognition") + 1
    assert states(session)["recognition"] is StageState.DONE
    assert states(session)["canal spine"] is StageState.RUNNING


def test_messages_after_the_end_and_requests_of_the_nearest_view() -> None:
    runner = ScriptedRunner()
    session = Session(runner)
    session.analyze("x^2 + y^2 - z")
    session.handle(JobCancelled())
    session.handle(AnalysisKnown("late"))  # a retired job's message: ignored
    assert session.run.analysis is None
    with pytest.raises(ValueError):
        session.set_view("nearest")
    with pytest.raises(ValueError):
        session.set_view("sideways")
    assert session.remesh(2.0) is False, "nothing finished to re-mesh"


def test_remesh_rebuilds_only_the_scene_of_the_finished_run() -> None:
    session = Session()
    log = record(session)
    run = session.analyze(example_text("sphere"), resolution=30)
    old = run.scene
    assert session.remesh(2 * old.region.radius, 30)
    refreshed = [args for name, args in log if name == "refreshed"]
    assert len(refreshed) == 1 and refreshed[0][0] == "scene"
    assert run.scene is not old and run.scene.region.radius == pytest.approx(2 * old.region.radius)
    assert refreshed[0][1].scene is run.scene
    assert run.outcome == "finished" and states(session)["rationality"] is not StageState.RUNNING


def test_a_blend_is_explained_by_its_typed_components() -> None:
    session = Session()
    run = session.analyze(example_text("non-coaxial-blend"), resolution=30)
    assert run.outcome == "finished" and not run.analysis.is_sor and len(run.analysis.factors) == 1
    kinds = [(c.text, c.recognition.symmetry) for c in run.components]
    assert kinds == [("x^2 + y^2 + (z - 1)^2 - 4", "sphere"), ("(x - z)^2/2 + y^2 - 1", "cylinder_of_revolution")]
    assert run.components[0].recognition.center == ("0", "0", "1")
    assert run.components[1].recognition.axis.direction == ("1", "0", "1")
    assert len(run.scene.factor_axes.polylines()) == 2
    assert Session().analyze(TORUS, resolution=30).components == ()
    assert component_texts("x^2 + 2y^2 + 3z^2 - 1") == (), "a monomial's variables are no surfaces"
    assert component_texts("2(x+1)(y-2) - 3") == ("x+1", "y-2")


def test_a_sphere_s_meridian_is_drawn_with_its_first_scene() -> None:
    """The profile a quadric sphere is read about (the axis along z through its centre) is known
    with the recognition, so the first scene draws it."""
    run = Session().analyze("x^2 + y^2 + z^2 - 2", resolution=30)
    assert run.outcome == "finished" and not run.scene.profile_curve.is_empty
    assert run.analysis.rationality.table_row == 3
