"""Child processes started by os.fork() (session.child.FORK): their channel and their end."""

from __future__ import annotations

import os
import signal
import time
from typing import Any

from sorgui.session.child import FORK, ChildProcess, wait_for_any

BIG = "x" * 3_000_000
"""Larger than a pipe's buffer, even one of 1 MB."""


def _echo_twice(conn: Any) -> None:  # noqa: ANN401 - the child's end of the channel
    """Send a big message before reading the one the parent sends meanwhile, then echo it."""
    conn.send(BIG)
    conn.send(len(conn.recv()))


def test_both_ends_send_more_than_a_pipe_holds_at_once() -> None:
    """The parent and the child each send 3 MB before reading: neither waits for the other."""
    child = ChildProcess(FORK, _echo_twice)
    try:
        child.send(BIG + "y")
        wait_for_any([child], 10)
        assert child.receive(10) == BIG
        assert child.receive(10) == len(BIG) + 1
    finally:
        child.close()


def _sleep(conn: Any) -> None:  # noqa: ANN401
    conn.send("ready")
    time.sleep(60)


def test_a_killed_child_reports_its_signal_and_hangs_up() -> None:
    child = ChildProcess(FORK, _sleep)
    assert child.receive(10) == "ready"
    os.kill(child.pid or 0, signal.SIGKILL)
    deadline = time.monotonic() + 10
    while child.is_alive() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert not child.is_alive()
    assert child.exit_description() == f"signal {signal.SIGKILL.value}"
    assert type(child.receive(1)).__name__ == "Hangup"
    child.close()


def _fail(conn: Any) -> None:  # noqa: ANN401
    raise RuntimeError("a bug in the child")


def test_a_child_that_raises_ends_with_status_1() -> None:
    child = ChildProcess(FORK, _fail)
    child.process.join(10)
    assert child.exit_description() == "exit status 1"
    child.close()
