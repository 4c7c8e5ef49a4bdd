"""One batch, from the command line's options to its last output line and its summary.

The input is read a line at a time (:mod:`.lines`); each line to analyse goes to a runner —
this machine's worker processes (:class:`.pool.Pool`, ``--jobs``) or a Dask cluster
(:class:`.cluster.Cluster`, ``--scheduler``) — and the answers are written in input order
(:func:`in_order`) to standard output or to the results file (:mod:`.results_file`), while
the progress is drawn and counted (:mod:`.progress`). At most :data:`WINDOW` lines are between
the oldest line still without its object and the newest one started, so the memory of a batch
does not grow with its length, nor behind one slow line.
"""

from __future__ import annotations

import argparse
import json
import os
import stat
import sys
from collections.abc import Callable, Generator, Iterable, Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, BinaryIO, Protocol

from .answers import FAILED, NOT_A_POLYNOMIAL, Answer, Options, answer_of, batch_status, options_of, refused
from .errors import BatchError
from .lines import Line, LineReader, count_lines
from .progress import Progress
from .results_file import ResultsFile

WINDOW = 256
"""Lines started at most beyond the oldest one whose object is not yet written."""
SCHEDULER_VARIABLE = "DASK_SCHEDULER_ADDRESS"
"""The environment variable Dask's clients read the scheduler's address from."""


class Runner(Protocol):
    """Where lines are analysed: each started line's answer comes back once, by its index."""

    capacity: int
    """How many lines may be running at once."""

    def busy(self) -> int:
        """How many lines are running."""
        ...

    def start(self, index: int, line: Line) -> Answer | None:
        """Start analysing ``line``; its answer at once when it cannot be started."""
        ...

    def answers(self) -> Sequence[tuple[int, Reply]]:
        """The replies that came, waiting a little (at most a second) for one."""
        ...

    def close(self) -> None:
        """End every analysis still running."""
        ...


if TYPE_CHECKING:
    from sorgui.session.messages import FinalMessage
    from sorgui.session.supervised import AnalysisRequest

    Reply = Answer | FinalMessage
    """What a runner gives back for a line: its answer, or the final message of its analysis, made
    into the answer only after the next lines are started (the worker computes meanwhile)."""


def in_order(
    lines: Iterable[Line], runner: Runner, options: Options, window: int = WINDOW
) -> Generator[tuple[Line, Answer], None, None]:
    """Each line with its answer (analysed with ``options``), in input order; a refused line is
    answered at once. The runner is kept full: after each wait the next lines are started before
    the answers are made and written, so that this process's part of a line overlaps the
    workers' analyses."""
    waiting: dict[int, tuple[Line, Reply]] = {}
    started: dict[int, Line] = {}
    pending = iter(lines)
    first = index = 0
    more = True

    def refill() -> None:
        nonlocal index, more
        while more and runner.busy() < runner.capacity and index - first < window:
            line = next(pending, None)
            if line is None:
                more = False
                return
            answer = refused(line, options) if line.refusal is not None else runner.start(index, line)
            if answer is None:
                started[index] = line
            else:
                waiting[index] = (line, answer)
            index += 1

    while True:
        refill()
        while first in waiting:
            line, reply = waiting.pop(first)
            first += 1
            yield line, reply if isinstance(reply, Answer) else answer_of(line, reply, options)
            refill()
        if not runner.busy():
            if not more:
                return
            continue
        for i, reply in runner.answers():
            waiting[i] = (started.pop(i), reply)
        refill()


def run_each_line(args: argparse.Namespace, emit: Callable[[str], None], limit: int) -> int:
    """``sorgui analyze --each-line``: the options of ``args`` (``-f FILE`` or ``-``, ``-o``,
    ``--resume``, ``--jobs``, ``--scheduler`` and the analysis options); ``emit`` writes a line
    to standard output; ``limit`` is the characters of one equation. Returns the exit status;
    raises :class:`BatchError` for options or files that cannot be used."""
    if args.file is not None and args.expression is not None:
        raise BatchError("give either an expression or -f FILE, not both")
    if args.file is None and args.expression != "-":
        raise BatchError("--each-line reads -f FILE or '-' (standard input)")
    if len(args.output) > 1:
        raise BatchError("--each-line writes one results file: give -o once")
    if args.output and Path(args.output[0]).suffix.lower() == ".json":
        raise BatchError(
            f"--each-line writes JSON Lines, one object per line, not one report: name the results file "
            f"{Path(args.output[0]).with_suffix('.jsonl').name} ('sorgui open' reads a .json report)"
        )
    if args.resume and not args.output:
        raise BatchError("--resume continues a results file: give it with -o RESULTS.jsonl")
    scheduler = args.scheduler or (os.environ.get(SCHEDULER_VARIABLE) if args.jobs is None else None)
    if args.scheduler and args.jobs is not None:
        raise BatchError("--jobs and --scheduler exclude each other: the cluster's workers run the lines")
    source = str(args.file) if args.file is not None else "standard input"
    stream = _open_input(args.file)
    try:
        inputs = _regular_status(stream)
        options = options_of(_requests(args)(""))
        results = ResultsFile(args.output[0], args.resume, inputs, options) if args.output else None
        try:
            show = sys.stderr if sys.stderr.isatty() else None
            total = count_lines(stream) if show is not None and inputs else None
            progress = Progress(show, total, shared=show is not None and sys.stdout.isatty())
            reader = LineReader(stream, limit)
            status = _run(reader, results, emit, progress, _runner(args, scheduler), options)
        except BaseException as exc:
            if results is not None and not isinstance(exc, Exception):  # Ctrl+C or an ending signal
                print(
                    f"sorgui: {results.path} holds {results.lines():,} line{'s' if results.lines() != 1 else ''}; "
                    "the same command with --resume goes on from there",
                    file=sys.stderr,
                )
            raise
        finally:
            if results is not None:
                results.close()
        if results is not None:
            progress.keep(results.kept)
            status = batch_status((status, *results.kept_statuses))
        if reader.stopped:
            print(f"sorgui: stopped reading {source}: {reader.stopped}", file=sys.stderr)
            status = status or NOT_A_POLYNOMIAL
        if show is not None or results is not None or status == FAILED:
            progress.close(progress.summary())
        return status
    finally:
        if stream is not sys.stdin.buffer:
            stream.close()


def _run(
    reader: LineReader,
    results: ResultsFile | None,
    emit: Callable[[str], None],
    progress: Progress,
    runner: Runner,
    options: Options,
) -> int:
    """Analyse the lines ``reader`` gives that ``results`` does not keep; the exit status."""
    statuses: set[int] = set()
    answers = in_order(_fresh(reader, results), runner, options)
    try:
        for line, answer in answers:
            if results is not None:
                results.write(answer)
            else:
                progress.before_output()
                emit(answer.text)
            statuses.add(answer.status)
            failure = json.loads(answer.text)["error"]["message"] if answer.status == FAILED else None
            progress.done(line.number, answer.kind, failure)
    except OSError as exc:
        raise BatchError(
            f"cannot write {results.path if results else 'the output'}: {exc.strerror or exc}", 1
        ) from None
    finally:
        answers.close()
        runner.close()  # Ctrl+C, a signal, a closed pipe, or done: the workers go too
    return batch_status(statuses)


def _fresh(lines: Iterable[Line], results: ResultsFile | None) -> Iterator[Line]:
    """The lines that the results file does not already hold (``--resume``)."""
    for line in lines:
        if results is None or not results.keeps(line):
            yield line
    if results is not None:
        results.finish_reading()


def _requests(args: argparse.Namespace) -> Callable[[str], AnalysisRequest]:
    """The analysis request of a line's text, with the options of ``args`` (the stages of the
    engine's flint-only path, a few milliseconds, not reported)."""
    from sorgui.session.supervised import AnalysisRequest

    def request(text: str) -> AnalysisRequest:
        return AnalysisRequest(
            text,
            method=args.method,
            recognition_only=args.recognition_only,
            tolerance=args.tolerance,
            timeout=args.timeout,
            quick_stages=False,
        )

    return request


def _runner(args: argparse.Namespace, scheduler: str | None) -> Runner:
    """The worker processes of this machine, or the Dask cluster at ``scheduler``."""
    request = _requests(args)
    if scheduler:
        from .cluster import Cluster

        return Cluster(scheduler, request)
    from .pool import Pool, worker_count

    jobs, lowered = worker_count(args.jobs or 1)
    if lowered:
        print(f"sorgui: {lowered}", file=sys.stderr, flush=True)
    return Pool(jobs, request)


def _open_input(path: Path | None) -> BinaryIO:
    if path is None:
        return sys.stdin.buffer
    try:
        return open(path, "rb")  # noqa: SIM115 - closed by run_each_line
    except OSError as exc:
        raise BatchError(f"cannot read {path}: {exc.strerror or exc}") from None


def _regular_status(stream: BinaryIO) -> list[os.stat_result]:
    """The input's status when it is a regular file (not to be overwritten, and countable)."""
    try:
        status = os.fstat(stream.fileno())
    except (OSError, ValueError, AttributeError):
        return []
    return [status] if stat.S_ISREG(status.st_mode) else []
