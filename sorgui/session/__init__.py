"""The application model without Qt: the equation, the running analysis and its stages, the
typed results as they arrive, and plain-Python events for views (``docs`` of
:mod:`sorgui.session.model`).

Importing this package loads neither Qt nor VTK nor pyvista (a test checks it): the 3D scene
(:mod:`sorgui.session.scene_data`) is built in the worker process, which imports it itself.
"""

from sorgui.session.events import EventEmitter, SessionEvents
from sorgui.session.job import JobRequest, JobResult
from sorgui.session.model import STAGES, InlineRunner, Run, Runner, Session, Stage, StageState

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
