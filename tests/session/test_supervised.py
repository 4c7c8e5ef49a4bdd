"""The analysis process of the command line: what it streams, what its parent makes of it."""

from __future__ import annotations

import errno
import os

import pytest

from sorgui.session.messages import AnalysisKnown, Failed, Finished, Message, Parsed, StageDone, StageStarted
from sorgui.session.supervised import (
    AnalysisRequest,
    StageLog,
    analyze_supervised,
    run_request,
)


def test_the_streamed_messages_rebuild_an_unfinished_analysis() -> None:
    """Everything the process sends before it is killed gives the same answer as the engine's own
    time limit: the stages done, the rest unfinished."""
    sent: list[Message] = []
    request = AnalysisRequest("(x^2+y^2+z^2+21)^2-100(x^2+y^2)", timeout=60)
    final = run_request(request, sent.append)
    assert isinstance(final, Finished)
    kinds = [type(m) for m in sent]
    assert kinds[:2] == [StageStarted, StageDone] and Parsed in kinds and AnalysisKnown in kinds
    cut = kinds.index(StageStarted, kinds.index(AnalysisKnown))  # killed while the stage after the verdict ran
    log = StageLog(request.recognition_only)
    for message in sent[: cut + 1]:
        assert not log.take(message)
    outcome = log.outcome("the analysis did not finish within the time limit of 60 s")
    assert isinstance(outcome, Finished)
    analysis = outcome.result
    assert analysis.is_sor and analysis.unfinished
    assert analysis.unfinished[0] == sent[cut].stage  # type: ignore[union-attr]
    assert {name for name, _ in analysis.timings} == {m.stage for m in sent[:cut] if isinstance(m, StageDone)}


def test_killed_before_the_equation_was_read_is_a_failure() -> None:
    log = StageLog(recognition_only=False)
    log.take(StageStarted("engine"))
    assert log.outcome("the analysis did not finish within the time limit of 1 s") == Failed(
        "the analysis did not finish within the time limit of 1 s (while reading the equation)"
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
