"""Shared by the benchmarks: timing and writing a table into ``docs/benchmarks.md``."""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable
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


def write_section(name: str, table: str) -> None:
    """Replace the text between ``<!-- name:start -->`` and ``<!-- name:end -->`` in the doc."""
    doc = DOC.read_text(encoding="utf-8")
    start_mark, end_mark = f"<!-- {name}:start -->", f"<!-- {name}:end -->"
    start, end = doc.index(start_mark) + len(start_mark), doc.index(end_mark)
    DOC.write_text(doc[:start] + "\n" + table + "\n" + doc[end:], encoding="utf-8")


def run(section: str, description: str, table: Callable[[int], str]) -> None:
    """The command line of a benchmark: ``[--repeats N] [--write]``; print (and record) its table."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--write", action="store_true", help="update docs/benchmarks.md")
    args = parser.parse_args()
    result = table(args.repeats)
    if args.write:
        write_section(section, result)
