"""Child processes that can always be ended, whatever they are doing.

A Python signal handler runs only between bytecodes, so neither a time limit (``SIGALRM``) nor
a ``SIGTERM`` handler can stop work stuck inside one long C call (flint, sympy's compiled
parts). Every analysis therefore runs in a :class:`ChildProcess` — for ``sorgui analyze``, for
each line of ``--each-line`` and for the window alike — and its parent ends it from outside:

* the child leads a process group of its own (so the terminal's Ctrl+C reaches only the
  parent), dies with its parent (``PR_SET_PDEATHSIG``, even after ``kill -9``) and takes the
  default action for ``SIGTERM`` and ``SIGHUP`` (:func:`become_child`);
* it sends the messages of :mod:`sorgui.session.messages` through a pipe
  (:meth:`ChildProcess.messages`, :meth:`ChildProcess.receive`);
* :meth:`ChildProcess.kill` stops its group, then kills it and the process groups of all its
  descendants (Singular runs in a session of its own) with ``SIGKILL``
  (:func:`kill_process_tree`).

A child is started by a ``multiprocessing`` context (``spawn`` for the window, whose threads a
fork would not copy) or by :data:`FORK`: a plain ``os.fork()`` with two pipes, for the command
line's analysis processes, which need none of ``multiprocessing`` (whose import, 10 ms, was a
tenth of a whole recognition-only process). Light to import (the standard library only, no
``multiprocessing``), so that a process can be started before the engine is loaded.
"""

from __future__ import annotations

import fcntl
import os
import pickle
import select
import signal
import sys
import time
import traceback
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from sorgui.session.messages import Hangup, Message

if TYPE_CHECKING:
    import multiprocessing.context
    import multiprocessing.process
    from multiprocessing.connection import Connection

ENDING = frozenset({signal.SIGTERM, signal.SIGHUP, signal.SIGINT})
"""Blocked while a child is started, so that it never runs its parent's handlers of them."""


def quick_context() -> multiprocessing.context.BaseContext:
    """The context of a child started from a command line's process: ``fork`` (the child has the
    parent's modules already, no second import of the engine) while this process has one
    thread, else ``spawn``: a fork copies the locks other threads hold (Open CASCADE's, VTK's,
    a BLAS pool's) but not the threads, and the child can wait on them forever; an export child
    forked after Open CASCADE had started its threads never answered."""
    import multiprocessing

    if _threads() == 1:
        return multiprocessing.get_context("fork")
    return multiprocessing.get_context("spawn")


def _threads() -> int:
    """This process's threads, those of C libraries included (``/proc/self/task``; Python's own
    where there is no ``/proc``)."""
    try:
        return len(os.listdir("/proc/self/task"))
    except OSError:
        import threading

        return threading.active_count()


def become_child(*, niceness: int = 0) -> None:
    """What a child process does first: lead a process group, die with its parent, take the
    default action for the ending signals (no handler of the parent's, none that a C call would
    delay), and run ``niceness`` steps below its parent's priority."""
    from sorgui.engine.lifetime import die_with_parent

    if hasattr(os, "setpgrp"):
        os.setpgrp()
    die_with_parent(signal.SIGKILL)
    for signum in ENDING:
        signal.signal(signum, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, ENDING)
    if niceness and hasattr(os, "nice"):
        os.nice(niceness)


class Fork:
    """The way to start a child by ``os.fork()`` (:data:`FORK`): what :class:`ChildProcess` takes in
    place of a ``multiprocessing`` context, for a parent with one thread."""

    def __repr__(self) -> str:
        return "FORK"


FORK = Fork()


class ChildProcess:
    """A process running ``target(conn, *args)``, its end of a duplex pipe being ``conn``."""

    def __init__(
        self,
        context: Fork | multiprocessing.context.ForkContext | multiprocessing.context.SpawnContext,
        target: Callable[..., None],
        args: tuple[Any, ...] = (),
        name: str = "sorgui-analysis",
    ) -> None:
        self.conn: _Pipe | Connection[Any, Any]
        self.process: _ForkedProcess | multiprocessing.process.BaseProcess
        child_conn: _Pipe | Connection[Any, Any]
        if isinstance(context, Fork):
            self.conn, child_conn = _pipe_pair()
            self.process = _ForkedProcess(target, (child_conn, *args), own=self.conn)
        else:
            self.conn, child_conn = context.Pipe(duplex=True)
            self.process = context.Process(target=target, args=(child_conn, *args), name=name, daemon=True)
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, ENDING)
        try:
            self.process.start()
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, previous)
        child_conn.close()
        self.ended = False

    @property
    def pid(self) -> int | None:
        return self.process.pid

    def is_alive(self) -> bool:
        return self.process.is_alive()

    def send(self, request: object) -> None:
        self.conn.send(request)

    def messages(self) -> list[Message]:
        """The messages waiting in the pipe, without blocking; :class:`Hangup` once the child
        has hung up."""
        out: list[Message] = []
        try:
            while not self.ended and self.conn.poll():
                out.append(self.conn.recv())
        except (EOFError, OSError):
            out.append(Hangup())
        return out

    def receive(self, timeout: float) -> Message | None:
        """The next message, waiting at most ``timeout`` seconds (``None``: nothing came)."""
        try:
            if self.conn.poll(max(timeout, 0.0)):
                message: Message = self.conn.recv()
                return message
        except (EOFError, OSError):
            return Hangup()
        return None

    def kill(self) -> None:
        """End the child and everything it started, at once (:func:`kill_process_tree`)."""
        if self.process.is_alive() and self.pid is not None:
            kill_process_tree(self.pid)
        self.ended = True

    def reap(self) -> bool:
        """Release the process once it has exited; ``True`` when it is gone."""
        if self.process.is_alive():
            return False
        self.conn.close()
        self.process.join(0)
        return True

    def close(self, wait: float = 1.0) -> None:
        """Kill the child and release it, waiting at most ``wait`` seconds for the kernel."""
        self.kill()
        self.process.join(wait)
        self.conn.close()

    def exit_description(self) -> str:
        """How the process ended, in words (``signal 9``, ``exit status 1``)."""
        self.process.join(0.05)
        code = self.process.exitcode
        return f"signal {-code}" if code is not None and code < 0 else f"exit status {code}"


def wait_for_any(children: Sequence[ChildProcess], timeout: float) -> None:
    """Wait at most ``timeout`` seconds for a message (or the end) of one of ``children``."""
    if any(isinstance(child.conn, _Pipe) and child.conn.pending() for child in children):
        return
    if children:
        select.select([child.conn.fileno() for child in children], [], [], max(timeout, 0.0))
    else:
        time.sleep(max(timeout, 0.0))


class _Pipe:
    """One end of a duplex channel between a parent and a child made by :data:`FORK`: a pipe each
    way, each message a pickle after its length (8 bytes), as ``multiprocessing``'s connections
    send them, with the part of their interface that :class:`ChildProcess` uses.

    Both ends may send at once (a batch's next line goes to a worker while the worker writes its
    answer, each larger than a pipe's buffer): while its message does not fit, an end reads what
    the other sends into its inbox, so neither waits for the other to read."""

    def __init__(self, read: int, write: int) -> None:
        self._read, self._write = read, write
        self._inbox = bytearray()
        self._ended = False
        os.set_blocking(write, False)

    def fileno(self) -> int:
        return self._read

    def pending(self) -> bool:
        """Whether something was read ahead into the inbox (a file descriptor's readiness does not
        show it)."""
        return bool(self._inbox)

    def send(self, obj: object) -> None:
        data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
        view = memoryview(len(data).to_bytes(8, "big") + data)
        while view:
            try:
                view = view[os.write(self._write, view) :]
                continue
            except BlockingIOError:
                pass
            readable, _, _ = select.select([] if self._ended else [self._read], [self._write], [])
            if readable:
                self._read_ahead()

    def _read_ahead(self) -> None:
        chunk = os.read(self._read, 1 << 20)
        if chunk:
            self._inbox += chunk
        else:
            self._ended = True

    def recv(self) -> Any:  # noqa: ANN401 - whatever was sent
        size = int.from_bytes(self._exactly(8), "big")
        return pickle.loads(self._exactly(size))

    def _exactly(self, size: int) -> bytes:
        while len(self._inbox) < size:
            if self._ended:
                raise EOFError("the other end of the pipe closed")
            self._read_ahead()
        data = bytes(self._inbox[:size])
        del self._inbox[:size]
        return data

    def poll(self, timeout: float = 0.0) -> bool:
        """Whether a message (or the end of the channel) is waiting, waiting at most ``timeout`` s."""
        if self._inbox or self._ended:
            return True
        return bool(select.select([self._read], [], [], max(timeout, 0.0))[0])

    def close(self) -> None:
        for fd in (self._read, self._write):
            if fd >= 0:
                try:
                    os.close(fd)
                except OSError:
                    pass
        self._read = self._write = -1


PIPE_SIZE = 1 << 20
"""Bytes asked of the kernel for each pipe's buffer (Linux's ``F_SETPIPE_SZ``; 1 MB is the
limit an unprivileged process has by default): an answer of a few hundred kB is then written at
once, and its sender goes on without waiting for the reader, busy with the line before."""


def _pipe_pair() -> tuple[_Pipe, _Pipe]:
    """The parent's end and the child's end of a new duplex channel."""
    down_read, down_write = os.pipe()
    up_read, up_write = os.pipe()
    for fd in (down_write, up_write):
        try:
            fcntl.fcntl(fd, fcntl.F_SETPIPE_SZ, PIPE_SIZE)  # Linux only
        except (AttributeError, OSError):
            pass  # the default buffer: a sender may wait longer for its reader, nothing else
    return _Pipe(up_read, down_write), _Pipe(down_read, up_write)


class _ForkedProcess:
    """A child made by ``os.fork()`` running ``target(*args)``, with the part of
    ``multiprocessing.Process``'s interface that :class:`ChildProcess` uses (``start``,
    ``is_alive``, ``join``, ``pid``, ``exitcode``: minus the signal for a killed one). The child
    closes the parent's end of its channel and reads standard input from ``/dev/null``, as
    ``multiprocessing``'s children do, and leaves with ``os._exit`` (no teardown: the exit
    status 1 and a traceback on standard error if ``target`` raised)."""

    def __init__(self, target: Callable[..., None], args: tuple[Any, ...], own: _Pipe) -> None:
        self._target, self._args, self._own = target, args, own
        self.pid: int | None = None
        self.exitcode: int | None = None

    def start(self) -> None:
        _flush_standard_streams()  # what is buffered is written once, not by the child too
        pid = os.fork()
        if pid:
            self.pid = pid
            return
        code = 1
        try:
            self._own.close()
            try:
                sys.stdin.close()
                sys.stdin = open(os.devnull, encoding="utf-8")  # noqa: SIM115 - for the process
            except (OSError, ValueError):
                pass
            self._target(*self._args)
            code = 0
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 1
        except BaseException:  # noqa: BLE001 - the child reports and ends, whatever happened
            traceback.print_exc()
        finally:
            _flush_standard_streams()
            os._exit(code)

    def is_alive(self) -> bool:
        return self.pid is not None and self._reap(os.WNOHANG) is None

    def join(self, timeout: float | None = None) -> None:
        """Wait at most ``timeout`` seconds (``None``: as long as it takes) for the child to end:
        on its process descriptor where the kernel has them (Linux 5.3), else a few times a
        millisecond."""
        if self._reap(os.WNOHANG) is not None or self.pid is None:
            return
        if timeout is None:
            self._reap(0)
            return
        try:
            descriptor = os.pidfd_open(self.pid)
        except (AttributeError, OSError):
            deadline = time.monotonic() + timeout
            while self._reap(os.WNOHANG) is None and time.monotonic() < deadline:
                time.sleep(0.001)
            return
        try:
            select.select([descriptor], [], [], max(timeout, 0.0))
        finally:
            os.close(descriptor)
        self._reap(os.WNOHANG)

    def _reap(self, options: int) -> int | None:
        """The exit code once the child has ended (``-signal`` for a killed one), else ``None``."""
        if self.exitcode is None and self.pid is not None:
            try:
                pid, status = os.waitpid(self.pid, options)
            except ChildProcessError:
                self.exitcode = -signal.SIGKILL  # reaped elsewhere; it is gone
                return self.exitcode
            if pid:
                self.exitcode = -os.WTERMSIG(status) if os.WIFSIGNALED(status) else os.WEXITSTATUS(status)
        return self.exitcode


def _flush_standard_streams() -> None:
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass


def descendants(pid: int) -> list[tuple[int, int]]:
    """``(pid, pgid)`` of every descendant of ``pid``, read from ``/proc`` (empty elsewhere).

    Every process's ``stat`` is read, with plain system calls: the end of each ``sorgui
    analyze`` waits for this, and a desktop runs hundreds of processes."""
    parents: dict[int, list[tuple[int, int]]] = {}
    try:
        names = os.listdir("/proc")
    except OSError:
        return []
    for name in names:
        if not name.isdigit():
            continue
        try:
            fd = os.open(f"/proc/{name}/stat", os.O_RDONLY)
        except OSError:
            continue
        try:
            stat = os.read(fd, 4096)
        except OSError:
            continue
        finally:
            os.close(fd)
        fields = stat.rsplit(b")", 1)[1].split()  # after "pid (comm)": state ppid pgrp ...
        parents.setdefault(int(fields[1]), []).append((int(name), int(fields[2])))
    found, stack = [], [pid]
    while stack:
        for child in parents.get(stack.pop(), []):
            found.append(child)
            stack.append(child[0])
    return found


def kill_process_tree(pid: int) -> None:
    """Kill the process ``pid``, its process group and the groups of all its descendants.

    The group is stopped first, so that nothing new is started between listing and killing.
    """
    _signal_group(pid, signal.SIGSTOP)
    groups = {pgid for _pid, pgid in descendants(pid)} | {pid}
    groups.discard(os.getpgrp())  # a child that has not yet left our group: never kill ourselves
    for group in groups:
        _signal_group(group, signal.SIGKILL)
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def _signal_group(pgid: int, signum: int) -> None:
    try:
        os.killpg(pgid, signum)
    except (ProcessLookupError, PermissionError):
        pass
