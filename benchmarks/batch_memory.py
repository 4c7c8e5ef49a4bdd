"""Benchmark: the memory of ``sorgui analyze --each-line`` over 10⁵ lines stays flat.

:data:`LINES` small equations (surfaces of revolution, other quadrics, a line that is not a
polynomial now and then, comments), one per line, are analysed by ``python -m sorgui.cli analyze
--each-line --recognition-only --jobs 2 -f FILE -o RESULTS.jsonl``. Every half second the
resident memory (``VmRSS`` in ``/proc``) of the sorgui process and of its worker processes is
read, with the size of the results file; the table gives both at a tenth, a quarter, half, three
quarters and the end of the run, and the run's lines per second. The results file is checked to
hold one object per equation line. Run ``python -m benchmarks.batch_memory [--write]`` from the
repository root (``--repeats`` is not used: one run of 10⁵ lines takes minutes).
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.report import ROOT, run
from sorgui.session.child import descendants

LINES = 100_000
SAMPLE_EVERY = 0.5


def library(count: int) -> tuple[str, int]:
    """The text of ``count`` lines and the number of them that hold an equation."""
    out, equations = [], 0
    for i in range(1, count + 1):
        if i % 1000 == 0:
            out.append(f"# part {i // 1000}")
            continue
        equations += 1
        if i % 97 == 0:
            out.append(f"x^2 + sin(y) - {i}")
        elif i % 3 == 0:
            out.append(f"x^2 + {i % 50 + 2}*y^2 + z^2 - {i}")
        else:
            out.append(f"(x - {i % 17})^2 + (y + {i % 13})^2 - {i % 11 + 1}*z")
    return "\n".join(out) + "\n", equations


def rss(pid: int) -> int:
    """The resident memory of ``pid`` in kB (0 once it is gone)."""
    try:
        for line in Path(f"/proc/{pid}/status").read_text(encoding="ascii").splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    except OSError:
        pass
    return 0


def table(_repeats: int) -> str:
    with tempfile.TemporaryDirectory() as folder:
        text, equations = library(LINES)
        source, results = Path(folder, "library.txt"), Path(folder, "results.jsonl")
        source.write_text(text, encoding="utf-8")
        command = [sys.executable, "-m", "sorgui.cli", "analyze", "--each-line", "--recognition-only", "--jobs", "2"]
        started = time.monotonic()
        proc = subprocess.Popen([*command, "-f", str(source), "-o", str(results)], cwd=ROOT, stderr=subprocess.PIPE)
        samples: list[tuple[float, int, int, int]] = []  # (seconds, file size, parent kB, workers kB)
        while proc.poll() is None:
            workers = sum(rss(pid) for pid, _group in descendants(proc.pid))
            size = results.stat().st_size if results.exists() else 0
            samples.append((time.monotonic() - started, size, rss(proc.pid), workers))
            time.sleep(SAMPLE_EVERY)
        elapsed = time.monotonic() - started
        _, err = proc.communicate()
        written = results.read_bytes().count(b"\n")
        assert written == equations, (written, equations, err[-500:])
    running = [s for s in samples if s[3] > 0]  # the workers end with the run
    final = running[-1][1]
    rows = [
        f"{LINES:,} lines ({equations:,} equations) in {elapsed:.0f} s ({equations / elapsed:,.0f} lines/s), "
        f"`--jobs 2`, results file {final / 2**20:,.0f} MB:",
        "",
        "| part of the run | sorgui process (MB) | worker processes (MB) |",
        "|---|---:|---:|",
    ]
    for share in (0.1, 0.25, 0.5, 0.75, 1.0):
        sample = next(s for s in running if s[1] >= share * final)
        rows.append(f"| {share:.0%} of the lines | {sample[2] / 1024:.1f} | {sample[3] / 1024:.1f} |")
    largest = max(s[2] for s in running), max(s[3] for s in running)
    rows.append(f"| largest | {largest[0] / 1024:.1f} | {largest[1] / 1024:.1f} |")
    print("\n".join(rows), flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("batch-memory", __doc__.splitlines()[0], table)
