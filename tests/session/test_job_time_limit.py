"""The window's analysis worker obeys one time limit for the whole analysis (its own limit)."""

from __future__ import annotations

import time
from pathlib import Path

from sorgui.session.job import JobRequest, run_job
from sorgui.session.messages import Finished

SLOW = (Path(__file__).resolve().parents[1] / "data" / "slow-singular.txt").read_text(encoding="utf-8")


def test_the_worker_reports_unfinished_stages_and_keeps_the_rest() -> None:
    start = time.monotonic()
    final = run_job(JobRequest(SLOW, singular_timeout=4, resolution=30))
    assert isinstance(final, Finished)
    result = final.result
    assert time.monotonic() - start < 4 + 20  # plus the scene of the surface, on a busy machine
    analysis = result.analysis
    assert analysis.is_sor and analysis.recognition.axis is not None
    assert analysis.unfinished == ("rationality", "parametrizations", "conical", "canal")
    assert analysis.rationality.status.startswith("undecided")


PARENT = """
import sys, multiprocessing
from sorgui.session.job import JobRequest, serve
from sorgui.session.messages import Finished

if __name__ == "__main__":
    context = multiprocessing.get_context("spawn")
    conn, child = context.Pipe()
    cancel = context.Event()
    worker = context.Process(target=serve, args=(child, cancel), daemon=True)
    worker.start()
    conn.send(JobRequest(open(sys.argv[1]).read(), singular_timeout=600, resolution=30))
    print(worker.pid, flush=True)
    while True:  # read the worker's messages, as the window does
        conn.recv()
"""


def test_the_worker_and_its_singular_die_with_the_window(tmp_path: Path) -> None:
    """kill -9 of the window's process (here a stand-in that starts the worker as the window
    does): the worker dies (PR_SET_PDEATHSIG), and so does the Singular it started."""
    import os
    import signal
    import subprocess
    import sys

    from tests.test_cli_signals import dead, singular_processes, wait_for

    script = tmp_path / "window.py"
    script.write_text(PARENT, encoding="utf-8")
    parent = subprocess.Popen(
        [sys.executable, str(script), str(Path(__file__).resolve().parents[1] / "data" / "slow-singular.txt")],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        worker = int(parent.stdout.readline())
        singular = wait_for(lambda: singular_processes(worker), 120)[0]
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait(30)
        wait_for(lambda: dead(worker) and dead(singular), 15)
    finally:
        if parent.poll() is None:
            parent.kill()
            parent.wait()
        parent.stdout.close()
