"""The entry point of an analysis worker process, light to import.

The window names :func:`worker_main` as the target of each worker process. Importing this
module loads nothing of the engine, so the window can start its first worker process before it
has loaded sympy, Qt's widgets or VTK itself (the worker then imports in parallel with it); the
process imports :mod:`sorgui.session.job` when it runs.
"""

from __future__ import annotations

from typing import Any


def worker_main(conn: Any, cancel: Any) -> None:  # noqa: ANN401 (a Connection and an Event)
    """Run :func:`sorgui.session.job.serve` in this (new) process."""
    from sorgui.session.job import serve

    serve(conn, cancel)
