"""The window's analysis worker obeys one time limit for the whole analysis (its own limit)."""

from __future__ import annotations

import time
from pathlib import Path

from sorgui.session.job import JobRequest, run_job

SLOW = (Path(__file__).resolve().parents[1] / "data" / "slow-singular.txt").read_text(encoding="utf-8")


def test_the_worker_reports_unfinished_stages_and_keeps_the_rest() -> None:
    start = time.monotonic()
    kind, result = run_job(JobRequest(SLOW, singular_timeout=4, style=None, resolution=30))
    assert kind == "finished"
    assert time.monotonic() - start < 4 + 20  # plus the scene of the surface, on a busy machine
    analysis = result.analysis
    assert analysis.is_sor and analysis.recognition.axis is not None
    assert analysis.unfinished == ("rationality", "parametrizations")
    assert analysis.rationality.status.startswith("undecided")
