"""What a batch says on standard error: its progress while it runs, and one summary line at the
end, when standard error is a terminal (the summary also when the lines go to a results file,
standard output then being silent, and when an analysis failed: a limit on processes fails every
line alike, and the error objects alone were easy to miss).

The progress line is redrawn at most :data:`REDRAW_EVERY` seconds apart: the lines done (of the
file's lines, when the input is a file), the lines analysed per second, and the time left at
that rate. The summary counts every output object as exactly one kind (:data:`.answers.KINDS`),
those kept from the results file by ``--resume`` included.
"""

from __future__ import annotations

import sys
import time
from typing import TextIO

from .answers import ERROR, KINDS, NEARLY, NOT_SURFACE_OF_REVOLUTION, SURFACE_OF_REVOLUTION, UNFINISHED

REDRAW_EVERY = 0.2
"""Seconds between two redraws of the progress line."""


class Progress:
    """The progress line (``stream`` a terminal) and the counts of the summary."""

    def __init__(self, stream: TextIO | None, total: int | None, *, shared: bool = False) -> None:
        self._stream = stream
        self._shared = shared  # the output lines go to the same terminal
        self._total = total
        self._started = time.monotonic()
        self._drawn = 0.0
        self._width = 0
        self.counts = dict.fromkeys(KINDS, 0)
        self.analysed = 0
        self.kept = 0
        self.line = 0
        self._from = 0  # the line before this run's first one (after the kept lines)
        self.first_failure: tuple[int, str] | None = None

    def keep(self, kinds: dict[str, int]) -> None:
        """Count the lines kept from the results file (``--resume``)."""
        for kind, n in kinds.items():
            self.counts[kind] += n
            self.kept += n

    def done(self, number: int, kind: str, failure: str | None = None) -> None:
        """Line ``number`` has its output object, of ``kind``; ``failure``: why its analysis failed."""
        if failure is not None and self.first_failure is None:
            self.first_failure = (number, failure)
        self.counts[kind] += 1
        self.analysed += 1
        if self.analysed == 1:
            self._from = number - 1
        self.line = number
        now = time.monotonic()
        if self._stream is not None and now - self._drawn >= REDRAW_EVERY:
            self._drawn = now
            self._draw(self._text(now))

    def _text(self, now: float) -> str:
        elapsed = max(now - self._started, 1e-9)
        rate = self.analysed / elapsed
        if self._total is None:
            return f"{self.line:,} lines · {rate:,.1f} lines/s"
        left = max(self._total - self.line, 0)
        line_rate = (self.line - self._from) / elapsed
        eta = f" · {_duration(left / line_rate)} left" if line_rate > 0 and left else ""
        return f"{self.line:,}/{self._total:,} lines · {rate:,.1f} lines/s{eta}"

    def before_output(self) -> None:
        """Erase the progress line before an output line is written to the same terminal (it was
        left in front of that line, and what was copied from the terminal was not JSON Lines);
        it is drawn again after the line."""
        if self._shared and self._stream is not None and self._width:
            try:
                self._stream.write("\r" + " " * self._width + "\r")
                self._stream.flush()
            except (OSError, ValueError):
                self._stream = None
            self._width = 0
            self._drawn = 0.0

    def _draw(self, text: str) -> None:
        assert self._stream is not None
        padding = " " * max(self._width - len(text), 0)
        self._width = len(text)
        try:
            self._stream.write(f"\r{text}{padding}")
            self._stream.flush()
        except (OSError, ValueError):
            self._stream = None  # the terminal went away: the batch goes on

    def summary(self, unread: str | None = None) -> str:
        """The summary line: the kinds counted, the time taken, and why reading stopped, if it did."""
        counts = self.counts
        total = sum(counts.values())
        sors = counts[SURFACE_OF_REVOLUTION]
        parts = [
            f"{sors:,} surface{'s' if sors != 1 else ''} of revolution",
            f"{counts[NOT_SURFACE_OF_REVOLUTION] + counts[NEARLY]:,} not"
            + (f" ({counts[NEARLY]:,} of them nearly: rounded input within its rounding)" if counts[NEARLY] else ""),
            f"{counts[ERROR]:,} error{'s' if counts[ERROR] != 1 else ''}",
            f"{counts[UNFINISHED]:,} unfinished",
        ]
        kept = f" ({self.kept:,} kept from before)" if self.kept else ""
        elapsed = _duration(time.monotonic() - self._started)
        stopped = f"; stopped reading: {unread}" if unread else ""
        failed = ""
        if self.first_failure is not None:
            failed = f"; the first failure, line {self.first_failure[0]}: {self.first_failure[1]}"
        return f"{total:,} line{'s' if total != 1 else ''}{kept}: {', '.join(parts)}; {elapsed}{failed}{stopped}"

    def close(self, summary: str) -> None:
        """Clear the progress line and write the summary line."""
        try:
            if self._stream is not None and self._width:
                self._stream.write("\r" + " " * self._width + "\r")
            sys.stderr.write(f"sorgui: {summary}\n")
            sys.stderr.flush()
        except (OSError, ValueError):
            pass  # stderr is closed: the exit status still says how it went


def _duration(seconds: float) -> str:
    """``4.2 s``, ``12 min``, ``3.5 h``."""
    if seconds < 60:
        return f"{seconds:.1f} s"
    if seconds < 3600:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"
