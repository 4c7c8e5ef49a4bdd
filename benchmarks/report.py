"""Shared by the benchmarks: timing and writing a table into ``docs/benchmarks.md``."""

from __future__ import annotations

import argparse
import compileall
import ctypes
import os
import resource
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TypeVar

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "benchmarks.md"
T = TypeVar("T")


def wall_times(run: Callable[[], T], repeats: int) -> tuple[list[float], T]:
    """The wall times of ``repeats`` calls of ``run()``, and its last result."""
    times: list[float] = []
    result = None
    for _ in range(repeats):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return times, result  # type: ignore[return-value]


def median_time(run: Callable[[], T], repeats: int) -> tuple[float, T]:
    """The median wall time of ``run()`` over ``repeats`` calls, and its last result."""
    times, result = wall_times(run, repeats)
    return statistics.median(times), result


PR_SET_CHILD_SUBREAPER = 36
"""Linux's ``prctl`` option by which orphaned descendants are re-parented to this process."""


def process_times(
    args: Sequence[str], repeats: int, statistic: Callable[[list[float]], float] = statistics.median
) -> tuple[float, float, str]:
    """The wall time and the CPU time of the process ``args`` (``statistic`` of ``repeats``
    runs, the median by default), and the standard output of its last run.

    The CPU time is user + system of the process and of every process it started, those it
    left running included: sorgui kills its analysis process (and that process's Singular)
    once the answer is in and does not wait for it, so ``getrusage`` of the children alone
    would not count the analysis. This process becomes their subreaper (Linux), and they are
    counted once they are reaped. The wall time ends when the process itself exits."""
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
    walls, cpus, out = [], [], ""
    for _ in range(repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        done = subprocess.run(list(args), capture_output=True, text=True, cwd=ROOT, check=True)
        walls.append(time.perf_counter() - start)
        _reap_orphans()
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
        out = done.stdout
    return statistic(walls), statistic(cpus), out


def _reap_orphans(patience: float = 10.0) -> None:
    """Wait for the descendants re-parented to this process (killed ones end at once)."""
    deadline = time.monotonic() + patience
    while time.monotonic() < deadline:
        try:
            pid, _status = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            time.sleep(0.005)
    print(f"benchmark: a process left by {sys.argv[0]} still runs after {patience} s", file=sys.stderr)


def write_section(name: str, table: str) -> None:
    """Replace the text between ``<!-- name:start -->`` and ``<!-- name:end -->`` in the doc."""
    doc = DOC.read_text(encoding="utf-8")
    start_mark, end_mark = f"<!-- {name}:start -->", f"<!-- {name}:end -->"
    start, end = doc.index(start_mark) + len(start_mark), doc.index(end_mark)
    DOC.write_text(doc[:start] + "\n" + table + "\n" + doc[end:], encoding="utf-8")


def compile_sorgui() -> None:
    """Compile sorgui's modules to bytecode, as ``pip install`` does, so that the processes a
    benchmark starts run what an installed sorgui runs. Without it, a checkout under
    ``PYTHONDONTWRITEBYTECODE=1`` (set on some machines) compiles every module of sorgui from
    source in each process: about 0.1 s more for a full analysis."""
    compileall.compile_dir(ROOT / "sorgui", quiet=1)


def run(section: str, description: str, table: Callable[[int], str]) -> None:
    """The command line of a benchmark: ``[--repeats N] [--write]``; print (and record) its table."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--write", action="store_true", help="update docs/benchmarks.md")
    args = parser.parse_args()
    compile_sorgui()
    result = table(args.repeats)
    if args.write:
        write_section(section, result)
