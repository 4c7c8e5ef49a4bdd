"""The analysis process of the command line: what it streams, what its parent makes of it."""

from __future__ import annotations

import errno
import multiprocessing

import pytest

from sorgui.session.supervised import (
    AnalysisRequest,
    StageLog,
    analyze_supervised,
    run_request,
)


def test_the_streamed_messages_rebuild_an_unfinished_analysis() -> None:
    """Everything the process sends before it is killed gives the same answer as the engine's own
    time limit: the stages done, the rest unfinished."""
    sent: list[tuple[str, object]] = []
    request = AnalysisRequest("(x^2+y^2+z^2+21)^2-100(x^2+y^2)", timeout=60)
    final = run_request(request, lambda kind, payload: sent.append((kind, payload)))
    assert final[0] == "finished"
    kinds = [kind for kind, _ in sent]
    assert kinds[:2] == ["progress", "done"] and "parsed" in kinds and "analysis" in kinds
    cut = kinds.index("progress", kinds.index("analysis"))  # killed while the stage after the verdict ran
    log = StageLog(request.recognition_only)
    for message in sent[: cut + 1]:
        assert not log.take(message)
    kind, analysis = log.outcome("the analysis did not finish within the time limit of 60 s")
    assert kind == "finished" and analysis.is_sor and analysis.unfinished
    assert analysis.unfinished[0] == sent[cut][1]
    assert {name for name, _ in analysis.timings} == {payload[0] for kind, payload in sent[:cut] if kind == "done"}


def test_killed_before_the_equation_was_read_is_a_failure() -> None:
    log = StageLog(recognition_only=False)
    log.take(("progress", "engine"))
    assert log.outcome("the analysis did not finish within the time limit of 1 s") == (
        "failed",
        "the analysis did not finish within the time limit of 1 s (while reading the equation)",
    )


def test_no_process_can_be_started(monkeypatch: pytest.MonkeyPatch) -> None:
    """A limit on processes (``ulimit -u``) is said in one line, not as a traceback."""

    def refuse(self: object) -> None:
        raise BlockingIOError(errno.EAGAIN, "Resource temporarily unavailable")

    monkeypatch.setattr(multiprocessing.context.ForkProcess, "start", refuse)
    kind, message = analyze_supervised(AnalysisRequest("x^2 + y^2 - z", timeout=10))
    assert kind == "failed" and message == "the analysis process could not be started: Resource temporarily unavailable"
