"""Parametrizations on the command line, as a user types them (docs/math.md §13): an expression,
a file of three lines, ``--each-line``, the exports and the saved report read back; bad maps are
one line and exit 2."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from sorgui.export.reports import read_report

SORGUI = [sys.executable, "-m", "sorgui.cli"]
ISSUE = "x = (1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s^2"


def sorgui(*args: str, timeout: float = 180) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*SORGUI, *args], capture_output=True, text=True, timeout=timeout)


def test_the_issue_example_is_analysed(tmp_path: Path) -> None:
    out = sorgui("analyze", ISSUE)
    assert out.returncode == 0, out.stderr
    assert "parametrization in s, t (over QQ, degree 4):" in out.stdout
    assert "surface of revolution: YES" in out.stdout
    assert "cross-check ∂(h, ρ)/∂(s, t) ≡ 0 about the axis: yes" in out.stdout
    assert "the given map is proper" in out.stdout
    report = tmp_path / "sor.json"
    text = tmp_path / "sor.txt"
    written = sorgui("analyze", "--json", ISSUE, "-o", str(report), "-o", str(text))
    data = json.loads(written.stdout)
    assert data["input_kind"] == "parametrization" and data["is_sor"] is True
    assert data["parametric"]["components"][2] == "s^2"
    analysis = read_report(report)  # validated like any report from elsewhere
    assert analysis.parametric is not None and analysis.parametric.proper is True
    assert "parametrization in s, t" in text.read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("text", "parameters"),
    [
        (
            r"\mathbf{r}(u,v) = \left( \frac{1-u^2}{1+u^2}(2+v), \frac{2u}{1+u^2}(2+v), v^2 \right)",
            "u, v",
        ),
        ("P := (s,t) -> [(1-s^2)/(1+s^2)*(2+t), 2*s/(1+s^2)*(2+t), t^2];", "s, t"),
    ],
)
def test_a_map_pasted_from_latex_or_maple_is_analysed(text: str, parameters: str) -> None:
    """A LaTeX vector label and a Maple function were refused as 'not 1 component'; the map is
    a surface of revolution about the z-axis."""
    out = sorgui("analyze", text)
    assert out.returncode == 0, out.stderr
    assert f"parametrization in {parameters} (over QQ, degree 4):" in out.stdout
    assert "surface of revolution: YES" in out.stdout


def test_a_file_of_three_lines(tmp_path: Path) -> None:
    path = tmp_path / "cone.sor"
    path.write_text("x = s*(1-t^2)/(1+t^2) + 1\ny = 3*s*2*t/(1+t^2) + 2\nz = 3 + 2*s\n", encoding="utf-8")
    data = json.loads(sorgui("analyze", "--json", "-f", str(path)).stdout)
    assert data["input_kind"] == "parametrization"
    assert data["is_sor"] is False and data["conical"]["kind"] == "cone"
    assert data["conical"]["apex"] == ["1", "2", "3"]
    assert data["polynomial"] == "36*x**2 + 4*y**2 - 9*z**2 - 72*x - 16*y + 54*z - 29"


def test_each_line_mixes_equations_and_parametrizations(tmp_path: Path) -> None:
    path = tmp_path / "lines.txt"
    path.write_text(
        "x = u; y = v; z = u^2 + v^2  # a paraboloid\nx^2 + y^2 - z\nx = s, y = s^2, z = s^3\n", encoding="utf-8"
    )
    out = sorgui("analyze", "--each-line", "-f", str(path))
    lines = [json.loads(line) for line in out.stdout.splitlines()]
    assert [line["line"] for line in lines] == [1, 2, 3]
    assert lines[0]["input_kind"] == "parametrization" and lines[0]["symmetry"] == "revolution"
    assert lines[1]["input_kind"] == "equation" and lines[1]["polynomial"] == lines[0]["polynomial"]
    assert "image is a curve" in lines[2]["error"]["message"]
    assert out.returncode == 2


@pytest.mark.parametrize(
    "text, words",
    [
        ("x = s, y = s^2, z = s^3", "the image is a curve"),
        ("x = s, y = t, z = 2", "the component z is constant"),
        ("x = s, y = t, z = cos(t)", "t is written both inside cos or sin and outside them"),
        ("x = s, y = t, z = exp(t)", "'exp' is not allowed"),
        ("x = s, y = t, z = s*t*u", "3 parameters"),
        ("x = s/(t-t), y = t, z = s", "the denominator is identically zero"),
    ],
)
def test_bad_maps_are_one_line_and_exit_2(text: str, words: str) -> None:
    out = sorgui("analyze", text)
    assert out.returncode == 2
    assert out.stderr.count("\n") == 1 and words in out.stderr and "Traceback" not in out.stderr
    data = json.loads(sorgui("analyze", "--json", text).stdout)
    assert words in data["error"]["message"] and isinstance(data["error"]["position"], int)


def test_a_flat_rounded_map_writes_standard_json_that_reads_back(tmp_path: Path) -> None:
    """A paraboloid ``z = 0.01·(s² + t²)`` turned by a rotation printed to 12 digits: over the
    sampled patch every normal lies along the axis, so its distance from the map is not measured.
    It was written as ``Infinity``, which no JSON reader (sorgui's own included) accepts."""
    rows = (
        ("0.781639173907", "-0.482929284214", "0.394739798174"),
        ("0.550117230704", "0.832030133775", "-0.0713924994179"),
        ("-0.293957878439", "0.272956338888", "0.916015066887"),
    )
    text = "(" + ", ".join(f"{a}*s + {b}*t + {c}*0.01*(s^2+t^2)" for a, b, c in rows) + ")"
    report = tmp_path / "map.json"
    done = sorgui("analyze", "--json", "-o", str(report), text)
    assert done.returncode == 0, done.stderr

    def refuse(constant: str) -> None:
        raise AssertionError(f"not standard JSON: {constant}")

    data = json.loads(done.stdout, parse_constant=refuse)
    near = data["approximate"]
    assert near["relative_distance"] is None and near["near_sor"] is False
    assert any("not measured" in note for note in near["notes"])
    assert read_report(report).approximate is not None  # sorgui reads its own file back
