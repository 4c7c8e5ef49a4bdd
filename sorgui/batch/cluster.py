"""``--each-line --scheduler ADDRESS``: the lines analysed on a Dask distributed cluster.

The client (:class:`Cluster`, a :class:`.run.Runner`) submits one task per line to the
scheduler at ``ADDRESS`` (``tcp://host:8786``; also read from ``DASK_SCHEDULER_ADDRESS``), a
bounded number at a time, and :mod:`.run` writes the answers in input order. Each task runs
:func:`analyse_on_worker` on a worker: the same analysis as ``--jobs``, in a killable process of
the worker's own (one per worker thread, kept from line to line) under the time limit of one
analysis, so a line's object is the same text whichever way it was made. A worker that dies
(killed, out of memory) loses no line: the scheduler gives its tasks to another worker, and an
answer is taken once per line. A line whose task ended the workers that ran it, again and
again, gets an error object. Dask is an extra (``pip install 'sorgui[cluster]'``), needed by the
client and on every worker, beside sorgui itself.
"""

from __future__ import annotations

import secrets
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

from .answers import FAILED, Answer, answer_of, error_answer, options_of
from .errors import BatchError
from .lines import Line
from .pool import LINES_PER_WORKER

if TYPE_CHECKING:
    from sorgui.session.supervised import AnalysisRequest, Supervised

INSTALL_HINT = "--scheduler needs Dask's distributed scheduler: pip install 'sorgui[cluster]'"
CONNECT_TIMEOUT = 10.0
"""Seconds to wait for the scheduler to answer when the batch starts."""
REFRESH_EVERY = 5.0
"""Seconds between two looks at how many worker threads the cluster has (workers come and go)."""


def _connect(distributed: Any, address: str) -> Any:  # noqa: ANN401 - the distributed module, a Client
    """A Dask client of the scheduler at ``address``, or :class:`.BatchError` in one line within
    :data:`CONNECT_TIMEOUT` and a second: Dask's own timeout does not cover a server that accepts
    the connection and never answers (a web server: the batch waited forever), and a server that
    answers with something else than Dask's messages raised from deep in its decoder."""
    found: list[Any] = []
    failed: list[BaseException] = []

    def connect() -> None:
        try:
            found.append(distributed.Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False))
        except BaseException as exc:  # noqa: BLE001 - any failure is said in one line
            failed.append(exc)

    thread = threading.Thread(target=connect, name="sorgui-dask-connect", daemon=True)
    thread.start()
    thread.join(CONNECT_TIMEOUT + 1.0)
    if found:
        return found[0]
    if not failed:
        why = f"no answer in {CONNECT_TIMEOUT:g} s"
    elif isinstance(failed[0], (OSError, TimeoutError, ValueError)):
        why = str(failed[0])
    else:
        detail = " ".join(f"{type(failed[0]).__name__}: {failed[0]}".split())[:120]
        why = f"the server there does not answer as a Dask scheduler does ({detail})"
    raise BatchError(f"cannot reach the Dask scheduler at {address}: {why}", status=1)


class Cluster:
    """Lines submitted to a Dask scheduler as tasks, at most :attr:`capacity` at a time."""

    def __init__(self, address: str, request: Any) -> None:  # noqa: ANN401 - a Callable[[str], AnalysisRequest]
        try:
            import logging

            import distributed
        except ImportError:
            raise BatchError(INSTALL_HINT) from None
        logging.getLogger("distributed").setLevel(logging.ERROR)  # the one-line errors are sorgui's
        self._dask: Any = distributed
        self.client: Any = _connect(distributed, address)
        self.address = address
        self.request = request
        self.running: dict[Any, tuple[int, Line]] = {}
        self._token = secrets.token_hex(6)
        self._looked = 0.0
        self.capacity = 2
        self._refresh()

    def _refresh(self) -> None:
        """:attr:`capacity`: twice the cluster's worker threads (a queued task for each), at least 2."""
        now = time.monotonic()
        if now - self._looked < REFRESH_EVERY:
            return
        self._looked = now
        try:
            workers = self.client.scheduler_info()["workers"].values()
            threads = sum(int(w.get("nthreads", 1)) for w in workers)
        except (OSError, KeyError, TimeoutError):
            return
        self.capacity = max(2, 2 * threads)

    def busy(self) -> int:
        return len(self.running)

    def start(self, index: int, line: Line) -> Answer | None:
        future = self.client.submit(
            analyse_on_worker,
            line,
            self.request(line.equation),
            key=f"sorgui-line-{self._token}-{line.number}",
            pure=False,
        )
        self.running[future] = (index, line)
        return None

    def answers(self) -> list[tuple[int, Answer]]:
        """The answers of the tasks that ended (waiting at most a second for one)."""
        try:
            self._dask.wait(list(self.running), timeout=1.0, return_when="FIRST_COMPLETED")
        except Exception:  # noqa: BLE001, S110 - a timeout or cancelled tasks: their status says which
            pass
        self._refresh()
        found = []
        for future, (index, line) in list(self.running.items()):
            if not future.done():
                continue
            del self.running[future]
            found.append((index, self._answer(future, line)))
            future.release()
        return found

    def _answer(self, future: Any, line: Line) -> Answer:  # noqa: ANN401 - a distributed.Future
        if future.status == "finished":
            answer: Answer = future.result()
            return answer
        if future.cancelled():
            raise BatchError(
                f"the Dask scheduler at {self.address} dropped line {line.number}'s task (was it restarted?); "
                "the lines written so far are kept: run again with --resume",
                status=1,
            )
        exception = future.exception()
        if isinstance(exception, self._dask.KilledWorker):
            message = "the analysis ended every Dask worker that ran it (out of memory?)"
        else:
            message = f"the Dask task failed ({type(exception).__name__}: {exception})"
        return error_answer(line, message, FAILED, options_of(self.request(line.equation)))

    def close(self) -> None:
        try:
            if self.running:
                self.client.cancel(list(self.running))
            self.client.close(timeout=5)
        except Exception:  # noqa: BLE001, S110 - the scheduler is gone: nothing left to close
            pass
        self.running = {}


# --- on a worker -----------------------------------------------------------------------------

_local = threading.local()
_warmed = threading.Lock()
_warm: list[bool] = []


def analyse_on_worker(line: Line, request: AnalysisRequest) -> Answer:
    """A Dask task: the answer for ``line``, analysed in this worker thread's analysis process (started
    once, after the engine is warmed up in the worker, and replaced when it was killed or died)."""
    import multiprocessing

    from sorgui.session.supervised import Supervised

    worker: Supervised | None = getattr(_local, "worker", None)
    if worker is None:
        with _warmed:
            if not _warm:
                from .pool import warm_up

                warm_up()
                _warm.append(True)
        try:
            with _children_allowed():
                worker = Supervised(multiprocessing.get_context("fork"))
        except OSError as exc:
            reason = f"the analysis process could not be started: {exc.strerror or exc}"
            return error_answer(line, reason, FAILED, options_of(request))
        _local.worker = worker
    message = worker.run(request)
    _local.served = getattr(_local, "served", 0) + 1
    if worker.child.ended or not worker.child.is_alive() or _local.served >= LINES_PER_WORKER:
        worker.close()
        _local.worker, _local.served = None, 0
    return answer_of(line, message, options_of(request))


@contextmanager
def _children_allowed() -> Iterator[None]:
    """Let this process start a child although it is daemonic: a Dask worker runs as a daemonic
    ``multiprocessing`` process of its nanny, which ``multiprocessing`` forbids children so that
    none outlives it. The analysis process dies with its parent all the same
    (:func:`~sorgui.session.child.become_child`), which is what that rule protects."""
    import multiprocessing

    config = multiprocessing.current_process()._config  # type: ignore[attr-defined]
    daemonic = config.get("daemon", False)
    config["daemon"] = False
    try:
        yield
    finally:
        config["daemon"] = daemonic
