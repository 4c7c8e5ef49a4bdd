"""Plain-Python events: the session announces changes, views subscribe (napari's model/``_qt``
split). No Qt here, so the session runs the same under the window, the command line and tests.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

Callback = Callable[..., Any]


class EventEmitter:
    """One kind of event: ``connect`` a callback, ``emit`` calls every callback in order."""

    def __init__(self, name: str) -> None:
        self.name = name
        self._callbacks: list[Callback] = []

    def connect(self, callback: Callback) -> Callback:
        """Call ``callback`` on every :meth:`emit` (once, however often it is connected)."""
        if callback not in self._callbacks:
            self._callbacks.append(callback)
        return callback

    def disconnect(self, callback: Callback | None = None) -> None:
        """Stop calling ``callback`` (every callback, if ``None``)."""
        if callback is None:
            self._callbacks.clear()
        elif callback in self._callbacks:
            self._callbacks.remove(callback)

    def emit(self, *args: Any) -> None:
        for callback in list(self._callbacks):
            callback(*args)

    def __len__(self) -> int:
        return len(self._callbacks)

    def __repr__(self) -> str:
        return f"<EventEmitter {self.name}: {len(self._callbacks)} callbacks>"


class SessionEvents:
    """The events of a :class:`~sorgui.session.model.Session`, with their arguments:

    * ``equation_changed(text)``: the equation being edited changed;
    * ``stale_changed(stale)``: whether the shown results belong to another equation;
    * ``run_started(run)``: a new analysis started (everything of the old one is gone);
    * ``state_changed(stage, state)``: a stage became pending, running, done, failed, …;
    * ``stage_done(stage, seconds)``: a stage finished, with its time;
    * ``analysis_changed(analysis)``: more results are known (typed engine objects);
    * ``scene_changed(scene)`` and ``nearest_scene_changed(scene)``: a new 3D scene;
    * ``components_changed(components)``: the typed components of a blend, recognised;
    * ``run_finished(run)``: the run ended (``run.outcome`` says how);
    * ``view_changed(view)``: the user switched between the typed and the nearest surface;
    * ``refreshed(what, result)``: the scene (``what`` is ``"scene"``) of the finished run was redone
      (``result`` the updated :class:`~sorgui.session.job.JobResult`, ``None`` if that failed).
    """

    NAMES = (
        "equation_changed",
        "stale_changed",
        "run_started",
        "state_changed",
        "stage_done",
        "analysis_changed",
        "scene_changed",
        "nearest_scene_changed",
        "components_changed",
        "run_finished",
        "view_changed",
        "refreshed",
    )

    def __init__(self) -> None:
        for name in self.NAMES:
            setattr(self, name, EventEmitter(name))

    def __getattr__(self, name: str) -> EventEmitter:  # for type checkers: every name is an emitter
        raise AttributeError(name)

    def disconnect_all(self) -> None:
        """Forget every subscriber (a view closing)."""
        for name in self.NAMES:
            getattr(self, name).disconnect()
