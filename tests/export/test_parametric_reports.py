"""A parametrization's report (docs/math.md §13, §14): read back as it was written, also without an
implicit equation; a crafted one is refused in one line naming the field."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from sorgui.engine import analyze
from sorgui.export.files import export_file
from sorgui.export.reports import ReportError, read_report
from sorgui.samples import bicubic_patch, map_text

CONE = "x = s*(1-t^2)/(1+t^2) + 1, y = 3*s*2*t/(1+t^2) + 2, z = 3 + 2*s"


@pytest.fixture(scope="module")
def reports(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("reports")
    out = {}
    for name, text, seconds in (("cone", CONE, 60.0), ("patch", map_text(bicubic_patch(seed=3)), 3.0)):
        path = folder / f"{name}.json"
        export_file(analyze(text, timeout=seconds, recognition_only=True), path)
        out[name] = path
    return out


def test_reports_read_back(reports: dict[str, Path]) -> None:
    cone = read_report(reports["cone"])
    assert cone.input_kind == "parametrization" and cone.conical is not None and cone.conical.apex == ("1", "2", "3")
    patch = read_report(reports["patch"])
    assert patch.parametric is not None and patch.recognition.polynomial == ""  # not known: no elimination


@pytest.mark.parametrize(
    "change, words",
    [
        (lambda d: d["parametric"].__setitem__("components", ["s", "t", "s*t"]), "does not hold the components"),
        (lambda d: d.__setitem__("input_kind", "equation"), "an equation's report with a parametrization's fields"),
        (lambda d: d.__setitem__("input_kind", "script"), "input_kind is not one of sorgui's values"),
        (lambda d: d["parametric"].__setitem__("symmetry", "<b>"), "parametric.symmetry is not one of"),
        (lambda d: d["parametric"].__setitem__("map", ["__import__('os')", "t", "s"]), "parametric.map is not"),
        (lambda d: d["parametric"].__setitem__("map_parameters", ["os", "t"]), "not a parameter name"),
        (lambda d: d.__setitem__("input", "x = s, y = t"), "not an equation sorgui reads"),
        (lambda d: d.__setitem__("parametric", None), "parametric is missing"),
        (lambda d: d["parametric"].__setitem__("map", ["s", "t", "s*t"]), "its parametric.map is not the map"),
        (lambda d: d.__setitem__("symmetry", "revolution"), "its symmetry is 'revolution'"),
    ],
)
def test_a_crafted_report_is_refused(reports: dict[str, Path], tmp_path: Path, change: Any, words: str) -> None:
    message = refusal(reports["patch"], tmp_path, change)
    assert words in message and "\n" not in message


def refusal(report: Path, tmp_path: Path, change: Any) -> str:  # noqa: ANN401
    """The one-line message with which ``report``, changed by ``change``, is refused."""
    data = json.loads(report.read_text(encoding="utf-8"))
    change(data)
    path = tmp_path / "crafted.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(ReportError) as info:
        read_report(path)
    return info.value.message


@pytest.mark.parametrize(
    "change, words",
    [
        (lambda d: d["parametric"].__setitem__("apex", ["1", "2", "4"]), "its parametric.apex is not the apex"),
        (lambda d: d["conical"].__setitem__("apex", ["1", "2", "4"]), "its conical.apex is not the apex"),
        (lambda d: d.__setitem__("polynomial", "x**2 + y**2 - z**2"), "its polynomial does not vanish on the map"),
    ],
)
def test_a_report_that_lies_about_its_map_is_refused(
    reports: dict[str, Path], tmp_path: Path, change: Any, words: str
) -> None:
    """Claims that validate but that the map does not bear out (sorgui.engine.claims.parametric)."""
    message = refusal(reports["cone"], tmp_path, change)
    assert "is refused" in message and words in message and "\n" not in message, message


def test_an_approximate_axis_is_printed_as_a_unit_vector() -> None:
    """A torus map whose axis is tilted by 1.7° within a tolerance of 0.033: the report printed
    the axis ``(0, 0, 0.999550219)`` (the tilt dropped as rounding, the rest kept), no unit
    vector; the window's sentence the same."""
    import re

    from sorgui.export.text import text_report
    from sorgui.gui.wording import near_words

    analysis = analyze(
        "x = (50.0000 + 12.5000*cos(v))*cos(u), y = (50.0000 + 12.5000*cos(v))*sin(u), z = 12.5000*sin(v) + 1.5*cos(u)",
        recognition_only=True,
    )
    approximate = analysis.approximate
    assert approximate is not None and approximate.axis is not None and approximate.near_sor
    assert abs(approximate.axis.direction[0]) > 0.02  # the tilt, within the tolerance
    for text in (text_report(analysis), near_words(approximate)):
        found = re.search(r"t·\(([^)]*)\)", text)
        assert found is not None, text
        assert sum(float(c) ** 2 for c in found.group(1).split(",")) == pytest.approx(1, abs=1e-8), text
