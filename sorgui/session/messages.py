"""The messages an analysis process sends its parent, one class each.

Every analysis runs in a child process (:mod:`sorgui.session.child`): ``sorgui analyze`` and each
line of ``--each-line`` through :mod:`sorgui.session.supervised`, the window's jobs through
:mod:`sorgui.session.job`. The child streams what it knows the moment it knows it, and ends
with exactly one final message. The parent dispatches on the class (``match``), never on a
string; the messages are frozen dataclasses that pickle through the pipe.

Light to import (the standard library only): the window's worker reads them before the engine
is loaded.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

# --- intermediate messages ---


@dataclass(frozen=True)
class StageStarted:
    """A stage has started (the engine's stages, and the window worker's ``scene``, ``curves``,
    ``nearest scene`` and ``components``)."""

    stage: str


@dataclass(frozen=True)
class StageDone:
    """A stage has ended after ``seconds``."""

    stage: str
    seconds: float


@dataclass(frozen=True)
class Parsed:
    """The equation's skeleton once it is read (an ``Analysis`` with the input and the field):
    what a supervising parent reports when it ends the child before any result."""

    analysis: Any


@dataclass(frozen=True)
class Analysed:
    """The engine's part of a window's job is over: its time limit no longer applies."""


@dataclass(frozen=True)
class AnalysisKnown:
    """The results known so far (verdict and axis first, then the Table 1 row, then all)."""

    analysis: Any


@dataclass(frozen=True)
class SceneKnown:
    """The typed surface's scene (``SceneData``), first without the parameterization patch."""

    scene: Any


@dataclass(frozen=True)
class NearestSceneKnown:
    """The nearest exact surface's scene, for rounded input."""

    scene: Any


@dataclass(frozen=True)
class ComponentsKnown:
    """For a *no*: the typed components of a blend, each recognised."""

    components: tuple[Any, ...]


# --- final messages ---


@dataclass(frozen=True)
class Finished:
    """The answer: an ``Analysis`` (``sorgui analyze``) or a ``JobResult`` (the window)."""

    result: Any


@dataclass(frozen=True)
class Invalid:
    """The text is not a polynomial: the message, and where (``position`` to ``end``)."""

    message: str
    position: int | None = None
    end: int | None = None


@dataclass(frozen=True)
class Failed:
    """The analysis could not be done, in one line of words."""

    message: str


@dataclass(frozen=True)
class JobCancelled:
    """The job stopped because it was asked to."""


@dataclass(frozen=True)
class Hangup:
    """The child closed its end of the pipe (it exited or was killed): made by the parent."""


Message = (
    StageStarted
    | StageDone
    | Parsed
    | Analysed
    | AnalysisKnown
    | SceneKnown
    | NearestSceneKnown
    | ComponentsKnown
    | Finished
    | Invalid
    | Failed
    | JobCancelled
    | Hangup
)
FinalMessage = Finished | Invalid | Failed | JobCancelled

FINAL = (Finished, Invalid, Failed, JobCancelled)
SUPERVISION = (Parsed, Analysed)
"""For the supervising parent alone; views never see them."""
INTERMEDIATE = (StageDone, AnalysisKnown, SceneKnown, NearestSceneKnown, ComponentsKnown)
"""Results a window's job sends before its final message (stage starts aside)."""
