"""The window's typesetting process, from the GUI thread: ask for formulas, receive their pictures.

:class:`Typesetter` starts :func:`sorgui.session.typesetting.serve` in a process of its own
(``spawn``, below the worker in priority, dying with the window) and keeps it for the window's life. The results
pane calls :meth:`Typesetter.request` with every formula it still shows as text, the rows on
screen first; a request replaces the one before. A timer takes the answers off the pipe (a few
per turn of the event loop, so that showing them never holds the loop up) and
:attr:`Typesetter.typeset` hands them on. Answers are kept by pieces and style, so a formula
typeset once is shown at once ever after (a new run, a rebuilt page, the zoom stepped back). A
process that died is started again at the next request.
"""

from __future__ import annotations

import multiprocessing
import time
from collections import OrderedDict
from collections.abc import Sequence

from PySide6.QtCore import QObject, QTimer, Signal

from sorgui.session.child import ChildProcess
from sorgui.session.messages import Hangup
from sorgui.session.process import typesetter_main
from sorgui.session.typesetting import Request, Style, Typeset

POLL_INTERVAL_MS = 25
"""How often the GUI thread looks at the pipe while answers are awaited."""

TURN_BUDGET_S = 0.012
"""Answers are taken off the pipe for at most this long per turn of the event loop."""

KEPT = 4000
"""Answers kept in memory (the oldest are dropped first)."""

PROCESS_NAME = "sorgui-typesetting"


class Typesetter(QObject):
    """The typesetting process and the answers it gave. :attr:`typeset` carries a list of
    :class:`~sorgui.session.typesetting.Typeset`."""

    typeset = Signal(object)

    def __init__(self, parent: QObject | None = None, start: bool = True) -> None:
        super().__init__(parent)
        self._context = multiprocessing.get_context("spawn")
        self._child: ChildProcess | None = None
        self._known: OrderedDict[tuple[tuple[str, ...], Style], Typeset] = OrderedDict()
        self._waiting: set[tuple[tuple[str, ...], Style]] = set()
        self._timer = QTimer(self)
        self._timer.setInterval(POLL_INTERVAL_MS)
        self._timer.timeout.connect(self._poll)
        self._closed = False
        if start:
            self._start()

    # --- public API ---

    def known(self, pieces: tuple[str, ...], style: Style) -> Typeset | None:
        """The answer for ``pieces`` in ``style``, if it came already."""
        return self._known.get((pieces, style))

    def request(self, formulas: Sequence[tuple[str, ...]], style: Style) -> None:
        """Typeset ``formulas`` (their LaTeX pieces) in this order, replacing the last request;
        those already known are not asked for again."""
        wanted = tuple(dict.fromkeys(p for p in formulas if p and (p, style) not in self._known))
        self._waiting = {(p, style) for p in wanted}
        if not wanted or self._closed:
            return
        child = self._child if self._child is not None and self._child.is_alive() else self._start()
        try:
            child.send(Request(style, wanted))
        except OSError:
            self._child = None
            return
        self._timer.start()

    @property
    def busy(self) -> bool:
        """Whether formulas asked for are still to come."""
        return bool(self._waiting)

    @property
    def pid(self) -> int | None:
        return self._child.pid if self._child is not None else None

    def shutdown(self, wait: float = 0.5) -> None:
        """End the process at once (the window is closing), waiting at most ``wait`` seconds
        for the kernel to release it; nothing is typeset after that."""
        self._closed = True
        self._timer.stop()
        self._waiting = set()
        if self._child is not None:
            self._child.close(wait=wait)
            self._child = None

    # --- helpers ---

    def _start(self) -> ChildProcess:
        if self._child is not None:
            self._child.close(wait=0.0)
        self._child = ChildProcess(self._context, typesetter_main, name=PROCESS_NAME)
        return self._child

    def _poll(self) -> None:
        child = self._child
        if child is None:
            self._timer.stop()
            return
        answers: list[Typeset] = []
        until = time.monotonic() + TURN_BUDGET_S
        while time.monotonic() < until:
            message = child.receive(0.0)
            if message is None:
                break
            if isinstance(message, Hangup):
                self._child = None
                self._waiting = set()
                break
            if isinstance(message, Typeset):
                key = (message.pieces, message.style)
                self._known[key] = message
                self._known.move_to_end(key)
                if len(self._known) > KEPT:
                    self._known.popitem(last=False)
                self._waiting.discard(key)
                answers.append(message)
        if answers:
            self.typeset.emit(answers)
        if not self._waiting:
            self._timer.stop()
