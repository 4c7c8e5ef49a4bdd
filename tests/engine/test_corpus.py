"""The public corpus (tests/data/cases.json) through the CLI's JSON; every key a case states is checked."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
import sympy

from sorgui.cli import main

from ..conftest import corpus_cases

CASES = corpus_cases()
RATIONALITY_KEYS = (
    "profile_reducible",
    "genus_profile",
    "genus_profile_square",
    "table_row",
    "complex_rational",
    "real_roots_of_h",
    "real_rational",
)


def exact(values: list[str]) -> list[sympy.Expr]:
    """Engine strings back to exact numbers (the JSON promises sympy can read them)."""
    return [sympy.nsimplify(sympy.S(v)) for v in values]


def run_json(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, dict]:
    status = main(["analyze", "--json", *args])
    return status, json.loads(capsys.readouterr().out)


def assert_same_axis(found: dict, expected: dict) -> None:
    p, d = sympy.Matrix(exact(found["point"])), sympy.Matrix(exact(found["direction"]))
    q, e = sympy.Matrix(exact(expected["point"])), sympy.Matrix(exact(expected["direction"]))
    assert d.cross(e) == sympy.zeros(3, 1)
    assert (p - q).cross(e) == sympy.zeros(3, 1)


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_corpus_case(case: dict, capsys: pytest.CaptureFixture[str]) -> None:
    status, data = run_json(capsys, case["input"])
    expect = case["expect"]
    if expect.get("error"):
        assert status == 2
        assert data["error"]["message"]
        assert isinstance(data["error"]["position"], int)
        return
    assert status == 0
    assert data["is_sor"] == expect["is_sor"]
    assert data["symmetry"] == expect["symmetry"]
    if "axis" in expect:
        assert_same_axis(data["axis"], expect["axis"])
    if "center" in expect:
        assert exact(data["center"]) == exact(expect["center"])
    rationality = data["rationality"] or {}
    for key in RATIONALITY_KEYS:
        if key in expect:
            assert rationality[key] == expect[key], key
    for par in data["parametrizations"]:
        assert par["verified"] is True


@pytest.mark.parametrize("case", [c for c in CASES if not c["expect"].get("error")], ids=lambda c: c["name"])
def test_both_methods_agree_on_the_corpus(case: dict, capsys: pytest.CaptureFixture[str]) -> None:
    _, by_symmetry = run_json(capsys, "--recognition-only", "--method", "symmetry", case["input"])
    _, by_paper = run_json(capsys, "--recognition-only", "--method", "paper", case["input"])
    for key in ("is_sor", "symmetry", "symmetry_dimension", "axis", "center", "normal", "profile"):
        assert by_symmetry[key] == by_paper[key], key


def test_json_has_the_documented_keys(capsys: pytest.CaptureFixture[str]) -> None:
    _, data = run_json(capsys, "y^2 - 2xz")
    for key in (
        "input",
        "polynomial",
        "field",
        "degree",
        "factors",
        "is_sor",
        "symmetry",
        "symmetry_dimension",
        "axis",
        "center",
        "normal",
        "profile",
        "timings",
        "rationality",
        "parametrizations",
    ):
        assert key in data
    assert set(data["axis"]) == {"point", "direction", "plucker"}
    assert {"polynomial", "square"} <= set(data["profile"])
    assert data["field"] == "QQ" and data["degree"] == 2


def test_console_script_reports_bad_input_without_traceback(tmp_path) -> None:
    bad = subprocess.run(
        [sys.executable, "-m", "sorgui.cli", "analyze", "x^2 + sin(y)"], capture_output=True, text=True, timeout=60
    )
    assert bad.returncode == 2
    assert bad.stderr.count("\n") == 1 and "Traceback" not in bad.stderr
    assert "sin" in bad.stderr
    path = tmp_path / "eq.txt"
    path.write_text("x^2 + y^2 + z^2 - 1\n", encoding="utf-8")
    good = subprocess.run(
        [sys.executable, "-m", "sorgui.cli", "analyze", "--json", "-f", str(path)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert good.returncode == 0 and json.loads(good.stdout)["symmetry"] == "sphere"


def test_standard_input_and_missing_file(capsys: pytest.CaptureFixture[str], monkeypatch, tmp_path) -> None:
    import io

    monkeypatch.setattr(sys, "stdin", io.StringIO("x^2 + y^2 - 1"))
    status, data = run_json(capsys, "-")
    assert status == 0 and data["symmetry"] == "cylinder_of_revolution"
    status, data = run_json(capsys, "-f", str(tmp_path / "missing.txt"))
    assert status == 2 and "cannot read" in data["error"]["message"]


def test_non_sor_exits_zero(capsys: pytest.CaptureFixture[str]) -> None:
    status, data = run_json(capsys, "x^2 + 2y^2 + 3z^2 - 1")
    assert status == 0 and data["is_sor"] is False and data["axis"] is None
