"""The entry points of the window's processes, light to import.

The window names :func:`worker_main` as the target of each analysis worker process and
:func:`typesetter_main` as that of its typesetting process. Importing this module loads nothing
of the engine, so the window can start its first worker process before it has loaded sympy,
Qt's widgets or VTK itself (the worker then imports in parallel with it); the process imports
:mod:`sorgui.session.job` (or :mod:`sorgui.session.typesetting`) when it runs.
"""

from __future__ import annotations

import multiprocessing.context
from typing import Any

STARTUP_NICENESS = 0
"""The window's first worker, which analyses the startup equation while the window loads its
modules, runs at the window's own priority: at 10 it got the processor only when the loading
window left it, and the first verdict came a second later."""


class CancelFlag:
    """The window's "stop" for one job: a byte of shared memory that the window sets and the
    engine reads between steps (``is_set``, as a ``threading.Event``). Unlike a
    ``multiprocessing.Event`` it holds no named semaphore, so a window that ends at once (a
    signal) leaves nothing behind for the resource tracker to complain about."""

    def __init__(self, context: multiprocessing.context.SpawnContext) -> None:
        self._value = context.RawValue("b", 0)

    def set(self) -> None:
        self._value.value = 1

    def is_set(self) -> bool:
        return bool(self._value.value)


def worker_main(conn: Any, cancel: CancelFlag, niceness: int | None = None) -> None:  # noqa: ANN401 (a Connection)
    """Run :func:`sorgui.session.job.serve` in this (new) process (at ``niceness``, else the
    worker's own)."""
    from sorgui.session.job import WORKER_NICENESS, serve

    serve(conn, cancel, WORKER_NICENESS if niceness is None else niceness)


TYPESETTER_NICENESS = 5
"""The typesetting process runs below the worker (niceness 1) and the window, which show the
formulas as text first. At 15 a machine busy with other programs' work typeset a rounded
torus's formulas in 27 s instead of 4 s (docs/benchmarks.md)."""


def typesetter_main(conn: Any) -> None:  # noqa: ANN401 (a Connection)
    """Run :func:`sorgui.session.typesetting.serve` in this (new) process."""
    from sorgui.session.child import become_child

    become_child(niceness=TYPESETTER_NICENESS)
    from sorgui.session.typesetting import serve

    serve(conn)
