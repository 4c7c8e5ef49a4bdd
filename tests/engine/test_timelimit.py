"""One time limit for the whole analysis: unfinished stages are undecided, finished ones kept."""

from __future__ import annotations

import signal
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from sorgui.engine import Analysis, analyze
from sorgui.engine.errors import TimeLimitReached
from sorgui.engine.parsing import parse_polynomial
from sorgui.engine.results import UNDECIDED
from sorgui.engine.timelimit import skeleton, time_limit, unfinished_analysis

SLOW = (Path(__file__).resolve().parents[1] / "data" / "slow-singular.txt").read_text(encoding="utf-8")


def test_a_limit_met_in_singular_keeps_the_recognition() -> None:
    start = time.monotonic()
    result = analyze(SLOW, timeout=3)
    assert time.monotonic() - start < 3 + 3
    assert result.is_sor and result.recognition.axis is not None and result.factors
    assert result.unfinished == ("rationality", "parametrizations", "conical", "canal")  # the window's list too
    assert result.rationality is not None and result.rationality.status.startswith("undecided")
    assert "time limit of 3 s" in result.rationality.status
    assert Analysis.from_json(result.to_json()) == result


def test_a_limit_met_in_python_keeps_what_finished() -> None:
    """Factoring this power over QQ took 15 s in sympy; wherever the limit falls, the finished
    stages are kept and only the others are listed as unfinished."""
    start = time.monotonic()
    result = analyze("(x+2y+3z+4+5x^2+y^2)^30", timeout=2)
    assert time.monotonic() - start < 2 + 3
    done = {name for name, _ in result.timings}
    assert not done & set(result.unfinished)
    assert result.recognition.symmetry == ("none" if "recognition" in done else UNDECIDED)
    assert bool(result.factors) == ("factors" in done)


def test_a_limit_met_on_the_flint_path_is_reported_from_there(monkeypatch: pytest.MonkeyPatch) -> None:
    """A recognition-only analysis over ``QQ`` runs on flint alone (:mod:`~sorgui.engine.rational_path`).
    A limit met in its factors stage (held here in Python for 30 s) names that stage and keeps
    the verdict and the axis; the general pipeline does not start the analysis again (it did, and
    reported the recognition as unfinished after loading sympy and reading the equation anew)."""
    from sorgui.engine import rational_path

    factors = rational_path._factor_reports

    def held(*args: Any) -> Any:  # noqa: ANN401 - the arguments of the wrapped function
        time.sleep(30)
        return factors(*args)

    monkeypatch.setattr(rational_path, "_factor_reports", held)
    started: list[str] = []
    result = analyze("(x^2+y^2+z^2+21)^2-100(x^2+y^2)", recognition_only=True, timeout=1, progress=started.append)
    assert started == ["parse", "recognition", "factors"]
    assert result.is_sor and result.recognition.axis is not None and not result.factors
    assert [name for name, _ in result.timings] == ["parse", "recognition"]
    assert result.unfinished == ("factors", "canal")


def test_a_limit_met_while_reading_says_so(monkeypatch: pytest.MonkeyPatch) -> None:
    from sorgui.engine import rational_path

    def held(text: str) -> None:
        time.sleep(30)

    monkeypatch.setattr(rational_path, "read_rational", held)
    with pytest.raises(TimeLimitReached, match=r"time limit of 1 s \(while reading the equation\)"):
        analyze("x^2 + y^2 - z", recognition_only=True, timeout=1)


def test_nothing_finished_is_reported_undecided() -> None:
    f = parse_polynomial("x^2 + y^2 - z").polynomial
    start = skeleton(f, text="x^2+y^2-z", method="symmetry")
    result = unfinished_analysis(
        start,
        recognition=None,
        latest=None,
        timings=(("parse", 0.01),),
        current="recognition",
        message="too slow",
        recognition_only=False,
    )
    assert result.recognition.symmetry == UNDECIDED and not result.is_sor
    assert result.unfinished == (
        "recognition",
        "factors",
        "real locus",
        "rationality",
        "parametrizations",
        "conical",
        "canal",
    )
    assert result.rationality.status == "undecided: too slow"
    data = result.to_json()
    assert data["is_sor"] is None and data["symmetry"] == UNDECIDED  # neither yes nor no
    assert Analysis.from_json(data) == result
    from sorgui.export.text import plain_text

    report = plain_text(result)
    assert "surface of revolution: undecided" in report and "not finished within the time limit" in report
    from sorgui.export.cas import summary_lines
    from sorgui.export.reports import markdown_report

    for text in (markdown_report(result), "\n".join(summary_lines(result))):
        assert "undecided whether it is a surface of revolution" in text
        assert "not a surface of revolution" not in text and "dimension 0" not in text and "dim L" not in text


def test_the_alarm_is_restored_and_only_armed_in_the_main_thread() -> None:
    before = signal.getsignal(signal.SIGALRM)
    with pytest.raises(TimeLimitReached):
        with time_limit(0.2):
            time.sleep(5)
    assert signal.getsignal(signal.SIGALRM) == before
    assert signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0)
    seen: list[object] = []

    def other_thread() -> None:
        with time_limit(0.1):
            time.sleep(0.3)  # not interrupted: signals only reach the main thread
        seen.append(signal.getsignal(signal.SIGALRM))

    thread = threading.Thread(target=other_thread)
    thread.start()
    thread.join()
    assert seen == [before]


def test_a_map_stopped_before_its_implicit_equation_lists_it_unfinished() -> None:
    """A bicubic map stopped at 1 s, in its properness (Singular), listed ``properness``,
    ``factors`` and ``canal`` unfinished, and not its implicit equation, which its report said
    was not found within the limit (at 3 s it was listed)."""
    bicubic = (
        "x = u + 2*v^3 - u^2*v + 3*u^3*v^2, y = v - u^3 + 2*u*v^2 + u^2*v^3 - 1, z = u*v + u^3*v^3 - 2*v^2*u + 5*u^2"
    )
    result = analyze(bicubic, timeout=1)
    done = {name for name, _ in result.timings}
    assert result.input_kind == "parametrization" and "implicit equation" not in done
    assert "implicit equation" in result.unfinished
    assert "properness" in result.unfinished or "properness" in done


def _stopped_before_its_rounding() -> Analysis:
    """A rounded hyperboloid (no surface of revolution exactly) stopped after its factors, before
    the analysis of its rounding."""
    from dataclasses import replace

    full = analyze("1.0000001*x^2 + y^2 - z^2 - 1", recognition_only=True)
    latest = replace(full, approximate=None, timings=())
    return unfinished_analysis(
        latest,
        recognition=latest.recognition,
        latest=latest,
        timings=(("parse", 0.001), ("recognition", 0.001), ("factors", 0.001)),
        current=None,
        message="too slow",
        recognition_only=True,
    )


def test_rounded_input_stopped_before_its_rounding_is_not_a_plain_no() -> None:
    """Rounded input (a torus, in the QA run) stopped (its time limit, Esc) before the analysis of its
    rounding was a plain "NO" (red "Not a surface of revolution" in the window), where the
    whole analysis says "nearly": its exact *no* is said, and its nearness undecided."""
    from sorgui.export.cas import verdict
    from sorgui.export.text import plain_text

    result = _stopped_before_its_rounding()
    assert "approximate" in result.unfinished and result.verdict == "not exactly"
    assert "surface of revolution: NO exactly; its decimals are exact rationals of which it is not one" in (
        plain_text(result)
    )
    assert verdict(result).startswith("not exactly a surface of revolution (its decimals")
