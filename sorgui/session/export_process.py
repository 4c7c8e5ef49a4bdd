"""Writing files of an analysis in a child process that can always be ended, under a deadline.

Every export of ``sorgui analyze -o``, ``sorgui open REPORT -o`` and the window's File → Export
runs here, as an analysis does (:mod:`sorgui.session.child`): an export can take long inside
one C call (Open CASCADE cutting a shape, a fit, a mesh), where neither a time limit nor a
signal handler of Python is heard, so the parent kills the child at the deadline or on a
signal, and removes what the child had half written (:func:`sorgui.export.atomic.remove_leftovers`;
an old file is left as it was).

The child (:func:`export_child`) answers each :class:`ExportRequest` with one message per file,
:class:`FileWritten` or :class:`FileFailed`, then :class:`ExportsDone`; a report named by path
is read (and its claims checked, :func:`sorgui.export.reports.read_report`) in the child, so a
crafted report that is slow to check is bounded by the same deadline. The scene that meshes,
pictures and CAD files need is built once in the child unless the caller sends its own (the
window's drawn one).

Light to import (the standard library and the session's messages): the window and the command
line start the child before the export modules are loaded.
"""

from __future__ import annotations

import sys
import time
import traceback
from collections.abc import Iterator
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sorgui.session.child import ChildProcess, become_child, quick_context
from sorgui.session.messages import Hangup

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

    from sorgui.engine.results import Analysis


@dataclass(frozen=True)
class ExportTarget:
    """One file to write: its path and the format (``None``: its suffix names it)."""

    path: str
    fmt: str | None = None


@dataclass(frozen=True)
class ExportRequest:
    """The files to write from ``analysis``, or from the saved report ``report`` (read in the
    child), with the options of ``-o``: the units and fitting tolerance of CAD files and the
    region (``radius`` of the drawn ball, a ball ``center`` with it, or a box ``bounds``), and
    ``cap``: CAD files hold the solid ``f ≤ 0`` inside the region.
    ``scene`` (a ``SceneData``) and ``picture`` (PNG bytes) are the window's own, used instead
    of building them."""

    targets: tuple[ExportTarget, ...]
    analysis: Analysis | None = None
    report: str | None = None
    report_line: int | None = None
    """In a results file of ``--each-line`` named by ``report``: the result of this input line."""
    units: str = "mm"
    tolerance: float | None = None
    radius: float | None = None
    center: tuple[float, float, float] | None = None
    bounds: tuple[float, float, float, float, float, float] | None = None
    scene: Any = None
    picture: bytes | None = None
    cap: bool = False


@dataclass(frozen=True)
class FileWritten:
    """``path`` is written; ``holds`` says what a CAD file holds (``""`` for other formats)."""

    path: str
    holds: str = ""


@dataclass(frozen=True)
class FileFailed:
    """``path`` was not written (an old file is left as it was): the reason in one line."""

    path: str
    message: str


@dataclass(frozen=True)
class ReportRefused:
    """The report could not be read or its claims do not hold: nothing was written."""

    message: str


@dataclass(frozen=True)
class ExportsDone:
    """Every file of the request has had its answer."""


ExportMessage = FileWritten | FileFailed | ReportRefused | ExportsDone


def export_child(conn: Connection) -> None:
    """The export process: answer every :class:`ExportRequest` that arrives, file by file,
    until the pipe closes."""
    become_child()
    while True:
        try:
            request = conn.recv()
        except (EOFError, OSError):
            return
        try:
            for message in run_exports(request):
                conn.send(message)
        except (BrokenPipeError, OSError):
            return


def run_exports(request: ExportRequest) -> Iterator[ExportMessage]:
    """Write the files of ``request`` one after the other, saying how each went."""
    analysis = request.analysis
    if analysis is None:
        from sorgui.export.reports import ReportError, read_report

        assert request.report is not None
        try:
            analysis = read_report(request.report, request.report_line)
        except ReportError as exc:
            yield ReportRefused(exc.message)
            yield ExportsDone()
            return
    scene, scene_error = request.scene, None
    if scene is not None and any(_needs_scene(t) for t in request.targets):
        from sorgui.session.scene_data import at_full_resolution

        scene = at_full_resolution(scene)
    if scene is None and any(_needs_scene(t) for t in request.targets):
        try:
            scene = _scene(analysis, request)
        except (ValueError, ArithmeticError) as exc:  # a region the mesh cannot be sampled in
            scene_error = f"the surface cannot be drawn in that region: {exc}"
    for target in request.targets:
        if scene is None and scene_error is not None and _needs_scene(target):
            yield FileFailed(target.path, f"cannot write {target.path}: {scene_error}")
            continue
        yield _write(analysis, target, request, scene)
    yield ExportsDone()


def _needs_scene(target: ExportTarget) -> bool:
    """Meshes, pictures and CAD files need the scene; Markdown and HTML reports show its picture."""
    from sorgui.export.formats import format_of

    try:
        form = format_of(target.path, target.fmt)
    except ValueError:
        return False
    return form.needs_scene or form.suffix in (".md", ".html")


def _scene(analysis: Analysis, request: ExportRequest) -> Any:  # noqa: ANN401 - a SceneData
    """The scene of ``analysis`` in the request's region (the drawn ball by default), with rounded
    input's approximate axis, as the window draws it."""
    from sorgui.render import ClipBox, ClipSphere
    from sorgui.session.scene_data import approximate_axis, build_scene

    ball = ClipSphere(request.center, request.radius) if request.center is not None and request.radius else None
    box = ClipBox(request.bounds) if request.bounds else None
    scene = build_scene(analysis, radius=request.radius if ball is None else None, region=ball, box=box)
    return replace(scene, approximate_axis=approximate_axis(analysis, scene.region))


def _write(analysis: Analysis, target: ExportTarget, request: ExportRequest, scene: Any) -> ExportMessage:  # noqa: ANN401
    """One file, and how it went in one line (every failure caught: the next file is written)."""
    from sorgui.engine.errors import SorguiError
    from sorgui.export.files import export_file

    path = target.path
    try:
        written, holds = export_file(
            analysis,
            path,
            target.fmt,
            scene=scene,
            units=request.units,
            tolerance=request.tolerance,
            picture=request.picture,
            cap=request.cap,
        )
        return FileWritten(str(written), holds)
    except OSError as exc:
        return FileFailed(path, f"cannot write {path}: {exc.strerror or exc}")
    except (ValueError, SorguiError) as exc:
        return FileFailed(path, f"cannot write {path}: {exc}")
    except MemoryError:
        return FileFailed(path, f"cannot write {path}: it ran out of memory")
    except Exception as exc:  # noqa: BLE001 - a bug still ends in one line; the details go to stderr
        traceback.print_exc(file=sys.stderr)
        return FileFailed(path, f"cannot write {path}: internal error ({type(exc).__name__}: {exc}); please report it")


KILL_WAIT = 0.5
"""Seconds a killed export process is waited for before its half-written files are removed."""


@dataclass
class ExportProcess:
    """One :class:`ChildProcess` running :func:`export_child`, given one request at a time, with
    the deadline (``time.monotonic()``) of the request it is working on."""

    context: Any
    limit: float | None = None
    """The user's time limit in seconds, named when a file is not written by the deadline."""
    child: ChildProcess | None = None
    request: ExportRequest | None = None
    deadline: float = float("inf")
    answered: set[str] = field(default_factory=set)

    @property
    def busy(self) -> bool:
        return self.request is not None

    def give(self, request: ExportRequest, deadline: float | None = None) -> None:
        """Send ``request`` (starting the child if there is none); it is to be done by ``deadline``."""
        if self.child is None or not self.child.is_alive():
            self.child = ChildProcess(self.context, export_child, name="sorgui-export")
        self.request, self.answered = request, set()
        self.deadline = float("inf") if deadline is None else deadline
        self.child.send(request)

    def collect(self, timeout: float = 0.0) -> list[ExportMessage]:
        """The messages that have come (waiting at most ``timeout`` seconds for the first). At the
        deadline, or when the child died, the child is killed, its half-written files removed, and
        every file not yet answered gets its :class:`FileFailed`, followed by :class:`ExportsDone`."""
        assert self.child is not None and self.request is not None
        wait = min(timeout, max(self.deadline - time.monotonic(), 0.0))
        first = self.child.receive(wait)
        out: list[ExportMessage] = []
        for message in ([first] if first is not None else []) + self.child.messages():
            if isinstance(message, Hangup):
                return out + self._end(f"the export process died ({self.child.exit_description()})")
            assert isinstance(message, (FileWritten, FileFailed, ReportRefused, ExportsDone))
            out.append(message)
            if isinstance(message, (FileWritten, FileFailed)):
                self.answered.add(message.path)
            if isinstance(message, ExportsDone):
                self.request = None
                return out
        if time.monotonic() >= self.deadline:
            limit = "" if self.limit is None else f" of {self.limit:g} s"
            return out + self._end(f"not written within the time limit{limit}")
        return out

    def _end(self, reason: str) -> list[ExportMessage]:
        """Kill the child; the files it had not answered failed for ``reason``."""
        from sorgui.export.atomic import remove_leftovers

        assert self.child is not None and self.request is not None
        pid = self.child.pid
        self.child.close(wait=KILL_WAIT)  # dead, so that nothing it writes comes after the clean-up
        self.child = None
        request, self.request = self.request, None
        folders = {Path(t.path).parent for t in request.targets}
        for folder in folders:
            remove_leftovers(folder, pid)
        return [
            *(
                FileFailed(t.path, f"cannot write {t.path}: {reason}" + _kept(Path(t.path)))
                for t in request.targets
                if t.path not in self.answered
            ),
            ExportsDone(),
        ]

    def cancel(self) -> list[ExportMessage]:
        """Stop the current request at once (the window's quit)."""
        if self.request is None or self.child is None:
            return []
        return self._end("cancelled")

    def close(self) -> None:
        """Kill the child (and remove what it had half written)."""
        if self.request is not None:
            self.cancel()
        if self.child is not None:
            self.child.close(wait=0.0)
            self.child = None


def export_supervised(
    request: ExportRequest, deadline: float | None, limit: float | None = None
) -> list[ExportMessage]:
    """Write the files of ``request`` in a child (forked when it can be) by ``deadline`` (the user's time limit
    being ``limit`` seconds) and return its messages (:class:`ExportsDone` last). A signal that
    reaches this process unwinds through here and kills the child at once; a process limit
    that keeps it from starting fails every file in one line each."""
    worker = ExportProcess(quick_context(), limit)
    try:
        worker.give(request, deadline)
    except OSError as exc:  # a limit on processes (ulimit -u) or on memory
        reason = f"the export process could not be started: {exc.strerror or exc}"
        return [*(FileFailed(t.path, f"cannot write {t.path}: {reason}") for t in request.targets), ExportsDone()]
    messages: list[ExportMessage] = []
    try:
        while not messages or not isinstance(messages[-1], ExportsDone):
            messages += worker.collect(timeout=0.5)
        return messages
    finally:
        worker.close()


def _kept(path: Path) -> str:
    """What became of the file an export did not write: its old one stays, if there was one (a new
    file's refusal said "an old file is left as it was" too)."""
    return " (the old file is left as it was)" if path.exists() else " (no file was written)"
