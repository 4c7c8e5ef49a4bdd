"""``sorgui analyze --each-line --scheduler ADDRESS`` on a real Dask cluster of this machine: a
scheduler and two worker processes, started as the README says (``dask scheduler``,
``dask worker``)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.test_cli_batch import SORGUI, rows_of

pytest.importorskip("distributed")

DASK = [sys.executable, "-m", "distributed.cli.dask_scheduler"]
WORKER = [sys.executable, "-m", "distributed.cli.dask_worker"]


def dask_script(scheduler_file: Path, code: str) -> Any:
    """The JSON that ``code`` prints, run as a client of the cluster (``c`` its Client)."""
    client = f"c = Client(scheduler_file={str(scheduler_file)!r})"
    script = f"import json, os\nfrom distributed import Client\n{client}\n{code}"
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, check=True)
    return json.loads(done.stdout)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, Path]]:
    """A scheduler and two single-threaded workers; yields the scheduler's address and its file."""
    folder = tmp_path_factory.mktemp("dask")
    scheduler_file = folder / "scheduler.json"
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL, "cwd": folder}
    processes = [
        subprocess.Popen(
            [*DASK, "--scheduler-file", str(scheduler_file), "--host", "127.0.0.1", "--port", "0", "--no-dashboard"],
            **quiet,
        )
    ]
    try:
        deadline = time.monotonic() + 120
        while not scheduler_file.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        for _ in range(2):
            processes.append(
                subprocess.Popen(
                    [*WORKER, "--scheduler-file", str(scheduler_file), "--nthreads", "1", "--no-dashboard"],
                    **quiet,
                )
            )
        assert dask_script(scheduler_file, "c.wait_for_workers(2, timeout=120)\nprint(json.dumps(1))") == 1
        address = json.loads(scheduler_file.read_text())["address"]
        yield address, scheduler_file
    finally:
        for proc in reversed(processes):
            proc.send_signal(signal.SIGTERM)
        for proc in processes:
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()


def lines_of_a_library(count: int) -> str:
    """Surfaces of revolution on tilted axes, quadrics, planes and bad lines."""
    out = []
    for i in range(1, count + 1):
        if i % 23 == 0:
            out.append(f"x^2 + tan(z) - {i}")
        elif i % 4 == 0:
            out.append(f"((x - {i})^2 + (y - 2z)^2 + (2y + z)^2/5 + {i})^2 - 16((x - {i})^2 + (y - 2z)^2)")
        elif i % 4 == 1:
            out.append(f"x^2 + {i}y^2 + 3z^2 - {i}")
        else:
            out.append(f"(x + y - {i})^2 + (x - y + z)^2 - {i}z")
    return "\n".join(out) + "\n"


def test_two_hundred_lines_on_the_cluster_are_those_of_jobs_2(cluster: tuple[str, Path], tmp_path: Path) -> None:
    address, _ = cluster
    lines = tmp_path / "lines.txt"
    lines.write_text(lines_of_a_library(200), encoding="utf-8")
    batch = [*SORGUI, "--each-line", "--recognition-only", "-f", str(lines)]
    local = subprocess.run([*batch, "--jobs", "2"], capture_output=True, text=True, timeout=300)
    assert local.returncode == 2 and len(local.stdout.splitlines()) == 200
    on_cluster = subprocess.run([*batch, "--scheduler", address], capture_output=True, text=True, timeout=300)
    assert on_cluster.returncode == 2, on_cluster.stderr
    assert rows_of(on_cluster.stdout) == rows_of(local.stdout)
    assert sum("error" in json.loads(line) for line in on_cluster.stdout.splitlines()) == 8

    from_environment = subprocess.run(
        batch[:-2] + ["-f", str(lines)],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "DASK_SCHEDULER_ADDRESS": address},
    )
    assert rows_of(from_environment.stdout) == rows_of(local.stdout)


def test_a_worker_killed_in_the_middle_loses_and_duplicates_no_line(cluster: tuple[str, Path], tmp_path: Path) -> None:
    address, scheduler_file = cluster
    lines = tmp_path / "lines.txt"
    lines.write_text(lines_of_a_library(200), encoding="utf-8")
    batch = [*SORGUI, "--each-line", "--recognition-only", "-f", str(lines)]
    local = subprocess.run([*batch, "--jobs", "2"], capture_output=True, text=True, timeout=300)
    pids = dask_script(scheduler_file, "print(json.dumps(list(c.run(os.getpid).values())))")
    results = tmp_path / "results.jsonl"
    proc = subprocess.Popen([*batch, "--scheduler", address, "-o", str(results)], stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while (not results.exists() or results.read_bytes().count(b"\n") < 30) and time.monotonic() < deadline:
        time.sleep(0.005)
    at_kill = results.read_bytes().count(b"\n")
    os.kill(pids[0], signal.SIGKILL)  # its nanny starts another; its lines go to the other worker
    _, err = proc.communicate(timeout=300)
    written = results.read_text(encoding="utf-8")
    assert proc.returncode == 2, err
    assert 30 <= at_kill < 200
    assert [json.loads(line)["line"] for line in written.splitlines()] == list(range(1, 201))
    assert rows_of(written) == rows_of(local.stdout)
    assert dask_script(scheduler_file, "c.wait_for_workers(2, timeout=120)\nprint(json.dumps(1))") == 1


def test_without_dask_one_line_says_what_to_install(tmp_path: Path) -> None:
    lines = tmp_path / "lines.txt"
    lines.write_text("x^2+y^2-z\n", encoding="utf-8")
    code = (
        "import sys\n"
        "sys.modules['distributed'] = None\n"
        "from sorgui.cli import main\n"
        f"sys.exit(main(['analyze', '--each-line', '--scheduler', 'tcp://127.0.0.1:1', '-f', {str(lines)!r}]))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 2 and out.stderr == "sorgui: --scheduler needs Dask's distributed scheduler: " + (
        "pip install 'sorgui[cluster]'\n"
    )


def test_a_scheduler_out_of_reach_is_one_line(tmp_path: Path) -> None:
    lines = tmp_path / "lines.txt"
    lines.write_text("x^2+y^2-z\n", encoding="utf-8")
    out = subprocess.run(
        [*SORGUI, "--each-line", "--scheduler", "tcp://127.0.0.1:9", "-f", str(lines)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 1 and out.stderr.startswith("sorgui: cannot reach the Dask scheduler at tcp://127.0.0.1:9")
    assert out.stderr.count("\n") == 1


@pytest.mark.parametrize("reply", [b"", b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n" * 4])
def test_a_server_that_is_not_a_scheduler_is_one_line_in_time(tmp_path: Path, reply: bytes) -> None:
    """A server that accepts the connection and never answers (a web server) held the batch
    forever; one that answers in HTTP ended it with a traceback from Dask's decoder."""
    import socket
    import threading

    server = socket.create_server(("127.0.0.1", 0))
    accepted: list[socket.socket] = []

    def serve() -> None:
        while True:
            try:
                connection, _ = server.accept()
            except OSError:
                return
            accepted.append(connection)
            if reply:
                connection.recv(100)
                connection.sendall(reply)

    threading.Thread(target=serve, daemon=True).start()
    lines = tmp_path / "lines.txt"
    lines.write_text("x^2+y^2-z\n", encoding="utf-8")
    address = f"tcp://127.0.0.1:{server.getsockname()[1]}"
    started = time.monotonic()
    try:
        out = subprocess.run(
            [*SORGUI, "--each-line", "--scheduler", address, "-f", str(lines)],
            capture_output=True,
            text=True,
            timeout=120,
        )
    finally:
        server.close()
        for connection in accepted:
            connection.close()
    assert out.returncode == 1 and out.stderr.startswith(f"sorgui: cannot reach the Dask scheduler at {address}: ")
    assert out.stderr.count("\n") == 1 and "Traceback" not in out.stderr
    assert time.monotonic() - started < 60
