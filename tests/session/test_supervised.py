"""The analysis process of the command line: what it streams, what its parent makes of it."""

from __future__ import annotations

import errno
import os

import pytest

from sorgui.engine.results import Analysis
from sorgui.session.messages import AnalysisKnown, Failed, Finished, Message, Parsed, StageDone, StageStarted
from sorgui.session.supervised import (
    AnalysisRequest,
    StageLog,
    analyze_supervised,
    run_request,
)

TORUS = "(x^2+y^2+z^2+21)^2-100(x^2+y^2)"


def _ended_after(request: AnalysisRequest, heard: list[Message]) -> Analysis:
    """What the parent makes of a process ended once it had sent ``heard`` (not its final message)."""
    log = StageLog(request.recognition_only)
    for message in heard:
        assert not log.take(message)
    outcome = log.outcome("the analysis did not finish within the time limit of 60 s")
    assert isinstance(outcome, Finished)
    return outcome.result


def test_the_streamed_messages_rebuild_an_unfinished_analysis() -> None:
    """Everything the process sends before it is killed gives the same answer as the engine's own
    time limit: the stages done, the rest unfinished."""
    sent: list[Message] = []
    request = AnalysisRequest(TORUS, timeout=60)
    final = run_request(request, sent.append)
    assert isinstance(final, Finished)
    kinds = [type(m) for m in sent]
    assert kinds[:2] == [StageStarted, StageDone] and Parsed in kinds and AnalysisKnown in kinds
    cut = kinds.index(StageStarted, kinds.index(AnalysisKnown))  # killed while the stage after the verdict ran
    analysis = _ended_after(request, sent[: cut + 1])
    assert analysis.is_sor and analysis.unfinished
    assert analysis.unfinished[0] == sent[cut].stage  # type: ignore[union-attr]
    assert {name for name, _ in analysis.timings} == {m.stage for m in sent[:cut] if isinstance(m, StageDone)}


def test_ended_in_the_factors_of_the_flint_path_names_them() -> None:
    """A recognition-only analysis runs on flint alone (:mod:`sorgui.engine.rational_path`) and
    streams its stages, its reading and its recognition as the general pipeline does: a process
    ended in its factors stage (as inside one long flint factorization) reports that stage
    unfinished and keeps the verdict and the axis (it said "while reading the equation")."""
    sent: list[Message] = []
    request = AnalysisRequest(TORUS, recognition_only=True, timeout=60)
    final = run_request(request, sent.append)
    assert isinstance(final, Finished)
    cut = sent.index(StageStarted("factors"))
    analysis = _ended_after(request, sent[: cut + 1])
    assert analysis.is_sor and analysis.recognition.axis == final.result.recognition.axis
    assert analysis.unfinished == ("factors", "canal") and not analysis.factors
    assert [name for name, _ in analysis.timings] == ["parse", "recognition"]


def test_a_stage_run_again_after_the_flint_path_declined_is_timed_once() -> None:
    """The full analysis of a torus: flint reads and recognises it, then leaves it to the general
    pipeline (Table 1 needs sympy and Singular), which reads and recognises it again; each of the
    two stages is timed once, in the place of its last run, by the engine and the parent alike."""
    sent: list[Message] = []
    final = run_request(AnalysisRequest(TORUS, timeout=60), sent.append)
    assert isinstance(final, Finished)
    assert [m.stage for m in sent if isinstance(m, StageDone)].count("parse") == 2
    names = [name for name, _ in final.result.timings]
    assert names[:4] == ["engine", "parse", "recognition", "factors"] and len(set(names)) == len(names)
    log = StageLog(recognition_only=False)
    for message in sent:
        log.take(message)
    assert [name for name, _ in log.timings] == names


def test_killed_before_the_equation_was_read_is_a_failure() -> None:
    """The failure names what was running: the engine's loading, or the reading."""
    for stage, doing in (("engine", "loading the engine"), ("parse", "reading the equation")):
        log = StageLog(recognition_only=False)
        log.take(StageStarted(stage))
        assert log.outcome("the analysis did not finish within the time limit of 1 s") == Failed(
            f"the analysis did not finish within the time limit of 1 s (while {doing})"
        )


def test_no_process_can_be_started(monkeypatch: pytest.MonkeyPatch) -> None:
    """A limit on processes (``ulimit -u``) is said in one line, not as a traceback."""

    def refuse() -> int:
        raise BlockingIOError(errno.EAGAIN, "Resource temporarily unavailable")

    monkeypatch.setattr(os, "fork", refuse)
    assert analyze_supervised(AnalysisRequest("x^2 + y^2 - z", timeout=10)) == Failed(
        "the analysis process could not be started: Resource temporarily unavailable"
    )


def test_a_short_limit_keeps_most_of_itself_for_the_engine() -> None:
    """``--timeout 1`` left the engine 0.3 s, most of it Python's start: the margins of a short
    limit shrink with it, the kill still before the limit."""
    from sorgui.session.supervised import ANSWER_MARGIN, GRACE, margins

    assert margins(60.0) == (ANSWER_MARGIN, GRACE)
    for limit in (0.2, 0.5, 1.0, 2.0):
        answer, grace = margins(limit)
        assert answer <= 0.3 * limit + 1e-12 and 0 < grace < answer
