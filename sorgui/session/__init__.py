"""The application model without Qt: the equation, the running analysis and its stages, the
typed results as they arrive, and plain-Python events for views (``docs`` of
:mod:`sorgui.session.model`).

Importing this package loads neither Qt nor VTK nor pyvista (a test checks it): the 3D scene
(:mod:`sorgui.session.scene_data`) is built in the worker process, which imports it itself.
"""

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from sorgui.session.events import EventEmitter, SessionEvents
    from sorgui.session.job import JobRequest, JobResult
    from sorgui.session.model import (
        STAGES,
        InlineRunner,
        Run,
        Runner,
        Session,
        Stage,
        StageState,
    )

_HOMES = {
    "EventEmitter": "events",
    "SessionEvents": "events",
    "JobRequest": "job",
    "JobResult": "job",
    "STAGES": "model",
    "InlineRunner": "model",
    "Run": "model",
    "Runner": "model",
    "Session": "model",
    "Stage": "model",
    "StageState": "model",
}
"""Where each name lives: imported on first use, so that a worker process can be started
(:mod:`sorgui.session.process`) before the engine is loaded."""


def __getattr__(name: str) -> Any:  # noqa: ANN401 (PEP 562)
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(f"sorgui.session.{home}"), name)


__all__ = [
    "STAGES",
    "EventEmitter",
    "InlineRunner",
    "JobRequest",
    "JobResult",
    "Run",
    "Runner",
    "Session",
    "SessionEvents",
    "Stage",
    "StageState",
]
