"""A CAD part analysed in a child process: ``sorgui analyze PART.step`` and File → Open of a part.

Reading a STEP file and recognising its faces are long calls into Open CASCADE, which a signal
handler cannot interrupt; they run in a :class:`~sorgui.session.child.ChildProcess`, killed at
the time limit, on a signal or when the window cancels. The child sends :class:`PartProgress`
after every face and one :class:`PartAnswer`: the report (:mod:`sorgui.cad.part_report`), the
bytes of every canonical CAD file asked for (the parent writes them, atomically, so that a
killed child leaves no half-written file), and the part's triangles when the window asks.
"""

from __future__ import annotations

import sys
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from sorgui.session.child import ChildProcess, become_child
from sorgui.session.messages import Hangup

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

    from sorgui.cad.part_report import PartReport
    from sorgui.cad.tessellation import PartMesh

PART_SUFFIXES = (".step", ".stp", ".iges", ".igs", ".brep")
"""The formats a part is read from and a canonical part written to (``sorgui.cad.CAD_SUFFIXES``)."""
REPORT_SUFFIXES = (".json", ".txt")
"""The formats of a part's report."""


@dataclass(frozen=True)
class PartRequest:
    """A part file, the tolerance (``None``: each face's own, at least ``1e-7``), the canonical
    CAD files wanted (by name: their suffix says the format) and whether to triangulate it."""

    path: str
    tolerance: float | None = None
    canonical: tuple[str, ...] = ()
    mesh: bool = False


@dataclass(frozen=True)
class PartProgress:
    """``done`` of ``total`` faces recognised."""

    done: int
    total: int


@dataclass(frozen=True)
class CanonicalFile:
    """A canonical CAD file to write: its name, its bytes and what it holds, in words."""

    path: str
    data: bytes
    holds: str
    valid: bool


@dataclass(frozen=True)
class PartAnswer:
    """The end of a part's analysis: the report (``None`` on failure), the canonical files, the
    triangles, or the ``error`` in one line (``bad_input``: the file is at fault, not sorgui)."""

    report: PartReport | None = None
    files: tuple[CanonicalFile, ...] = ()
    mesh: PartMesh | None = None
    error: str | None = None
    bad_input: bool = False


@dataclass
class PartLog:
    """What the parent knows of the running analysis: the faces done so far."""

    done: int = 0
    total: int | None = None
    answer: PartAnswer | None = field(default=None)


def run_part(request: PartRequest, progress: Callable[[int, int], None] | None = None) -> PartAnswer:
    """Read, recognise and rewrite the part in this process (Open CASCADE is imported here)."""
    try:
        from sorgui.cad.reading import PartError, read_part
    except ImportError:
        from sorgui.cad import INSTALL_HINT

        return PartAnswer(error=f"cannot read {request.path}: {INSTALL_HINT}", bad_input=True)
    from sorgui.cad.canonical import canonical_file
    from sorgui.cad.recognition import analyse_part

    try:
        part = read_part(request.path)
    except PartError as exc:
        return PartAnswer(error=str(exc), bad_input=True)
    report, found = analyse_part(part, request.tolerance, progress)
    files = []
    for name in request.canonical:
        suffix = "." + name.rsplit(".", 1)[-1].lower()
        data, canonical = canonical_file(part, found, name.rsplit("/", 1)[-1], suffix)
        files.append(CanonicalFile(name, data, canonical.summary(), canonical.valid))
    mesh = None
    if request.mesh:
        from sorgui.cad.tessellation import part_mesh

        mesh = part_mesh(part.shape, part.faces)
    return PartAnswer(report=report, files=tuple(files), mesh=mesh)


def part_child(conn: Connection) -> None:
    """The part process: answer every :class:`PartRequest` that arrives, with progress."""
    become_child()
    while True:
        try:
            request = conn.recv()
        except (EOFError, OSError):
            return
        try:
            conn.send(_answer(request, lambda done, total: conn.send(PartProgress(done, total))))
        except (BrokenPipeError, OSError):
            return


def _answer(request: PartRequest, progress: Callable[[int, int], None]) -> PartAnswer:
    try:
        return run_part(request, progress)
    except MemoryError:
        return PartAnswer(error=f"the analysis of {request.path} ran out of memory")
    except Exception as exc:  # noqa: BLE001 - a bug or an Open CASCADE fault still ends in one line
        traceback.print_exc(file=sys.stderr)
        return PartAnswer(error=f"internal error reading {request.path} ({type(exc).__name__}: {exc})")


class PartWorker:
    """One :class:`ChildProcess` running :func:`part_child`, with the request it works on."""

    def __init__(self, context: Any) -> None:  # noqa: ANN401 (a multiprocessing context)
        self.child = ChildProcess(context, part_child, name="sorgui-part")
        self.log = PartLog()
        self.request: PartRequest | None = None

    def give(self, request: PartRequest) -> None:
        self.request = request
        self.log = PartLog()
        self.child.send(request)

    def collect(self, timeout: float = 0.0) -> PartAnswer | None:
        """The answer if it has come (waiting at most ``timeout`` seconds for a first message);
        the process's death makes one."""
        first = self.child.receive(timeout)
        for message in ([first] if first is not None else []) + self.child.messages():
            if isinstance(message, Hangup):
                self.child.ended = True
                return PartAnswer(error=f"the part's analysis process died ({self.child.exit_description()})")
            if isinstance(message, PartProgress):
                self.log.done, self.log.total = message.done, message.total
            elif isinstance(message, PartAnswer):
                self.log.answer = message
                return message
        return None

    def close(self, wait: float = 1.0) -> None:
        self.child.close(wait)


def analyse_part_supervised(request: PartRequest, timeout: float, started: float | None = None) -> PartAnswer:
    """Analyse ``request`` in a forked child, killed ``timeout`` seconds after ``started``
    (``time.monotonic()``, by default now). A signal unwinds through here and kills the child."""
    import multiprocessing

    begun = time.monotonic() if started is None else started
    deadline = begun + timeout - 0.3
    try:
        worker = PartWorker(multiprocessing.get_context("fork"))
    except OSError as exc:
        return PartAnswer(error=f"the analysis process could not be started: {exc.strerror or exc}")
    try:
        worker.give(request)
        import sorgui.cad.part_report  # noqa: F401 - the answer's module, loaded while the child works

        while True:
            answer = worker.collect(timeout=max(0.0, min(0.5, deadline - time.monotonic())))
            if answer is not None:
                return answer
            if time.monotonic() >= deadline:
                worker.child.kill()
                done = worker.log.done
                faces = f" ({done} of {worker.log.total} faces recognised)" if worker.log.total else ""
                return PartAnswer(error=f"the analysis of {request.path} did not finish within {timeout:g} s{faces}")
    finally:
        worker.close(wait=0.0)
