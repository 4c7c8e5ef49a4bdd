"""``sorgui analyze`` on rounded input (docs/math.md §8), as real processes: the ``approximate``
JSON object, the verdict in words, and ``--tolerance``."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest

from sorgui.samples import printed
from tests.engine.test_approximate import _turned_torus

SORGUI = [sys.executable, "-m", "sorgui.cli", "analyze"]


def sorgui(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*SORGUI, *args], capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def torus_text() -> str:
    return printed(_turned_torus()[0], 10)


def test_json_has_the_approximate_object_with_the_nearest_analysis(torus_text: str) -> None:
    out = sorgui("--json", torus_text)
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["is_sor"] is False
    ap = data["approximate"]
    assert set(ap) >= {
        "tolerance",
        "near_sor",
        "kind",
        "relative_distance",
        "singular_values",
        "axis",
        "nearest",
        "notes",
    }
    assert ap["near_sor"] is True and ap["kind"] == "revolution"
    assert ap["tolerance_source"] == "input" and 0 < ap["tolerance"] < 1e-9
    direction = ap["axis"]["direction"]
    assert abs(abs(direction[0]) - math.cos(0.7)) < 1e-8 and abs(abs(direction[1]) - math.sin(0.7)) < 1e-8
    nearest = ap["nearest"]
    assert set(nearest) >= {"polynomial", "axis", "max_deviation", "analysis"}
    assert nearest["analysis"]["is_sor"] is True
    assert nearest["analysis"]["rationality"]["table_row"] == 1
    assert nearest["max_deviation"] < 1e-7
    assert nearest["within_rounding"] is True and 0 <= nearest["largest_residual"] <= 1


def test_a_nearest_surface_outside_the_rounding_says_by_how_much() -> None:
    """Its relative distance can be below the tolerance with one coefficient beyond its own
    rounding: the report says which figure put it outside (and a report saved before the figure
    existed still reads)."""
    from sorgui.engine.results import NearestSurface
    from sorgui.export.text import outside_words

    near = NearestSurface("x**2 + y**2 - z**2", "revolution", None, None, None, 1.4e-4, 0.11, False)
    assert outside_words(near) == "a coefficient is off by more than its rounding"
    near = NearestSurface("x**2 + y**2 - z**2", "revolution", None, None, None, 1.4e-4, 0.11, False, None, 2.615)
    assert outside_words(near) == "one coefficient is off by 2.6 times its own rounding"


def test_recognition_only_keeps_the_approximation_without_the_nearest_analysis(torus_text: str) -> None:
    data = json.loads(sorgui("--json", "--recognition-only", torus_text).stdout)
    assert data["approximate"]["near_sor"] is True
    assert data["approximate"]["nearest"]["analysis"] is None


def test_the_text_report_says_it_in_words(torus_text: str) -> None:
    out = sorgui(torus_text)
    assert out.returncode == 0, out.stderr
    assert "surface of revolution: NO exactly, but NEARLY: within the rounding of the input" in out.stdout
    assert (
        "not exactly, but within" in out.stdout and "(relative) of a surface of revolution about the axis" in out.stdout
    )
    assert "the analysis of the nearest exact surface:" in out.stdout
    assert out.stdout.endswith("\n")


def test_a_given_tolerance_applies_to_exact_input() -> None:
    plain = json.loads(sorgui("--json", "--recognition-only", "x^2+y^2-z").stdout)
    assert plain["approximate"] is None
    given = json.loads(sorgui("--json", "--recognition-only", "--tolerance", "1e-8", "x^2+y^2-z").stdout)
    assert given["approximate"]["tolerance"] == 1e-8 and given["approximate"]["near_sor"] is True


def test_a_near_miss_says_how_far_it_is() -> None:
    out = sorgui("--recognition-only", "x^2 + 2.5y^2 + 3.7z^2 - 1")
    assert "not near a surface of revolution" in out.stdout
    assert "smallest singular value" in out.stdout


ROUNDED_ELLIPTIC_CYLINDER = (
    "0.0649354*z^2 + 0.205178*y*z + 0.1634*y^2 + 0.0426503*x*z + 0.0931828*x*y + 0.132775*x^2"
    " - 0.205178*z - 0.3268*y - 0.0931828*x - 0.8366"
)
"""An elliptic cylinder about a tilted line, printed with 6 digits: within the rounding of an
extrusion, not near a surface of revolution."""


def test_rounded_input_near_an_extrusion_says_so_in_the_report_and_the_banner() -> None:
    """The report said "within … of an extrusion with normal (…)" (its vector is the direction
    of the extrusion) and "(no kind of symmetry was tried, see below)" of the extrusion's own
    residual; the window's banner called that residual the distance to "the nearest
    rotation-invariant polynomial"."""
    from sorgui.engine import analyze
    from sorgui.gui.wording import verdict

    out = sorgui("--recognition-only", ROUNDED_ELLIPTIC_CYLINDER)
    assert "not near a surface of revolution; within" in out.stdout
    assert "of an extrusion along (0.0556" in out.stdout and "with normal" not in out.stdout
    assert "times the rounding (at most 1: within it)" in out.stdout and "no kind of symmetry" not in out.stdout
    title, detail, kind = verdict(analyze(ROUNDED_ELLIPTIC_CYLINDER, recognition_only=True))
    assert (title, kind) == ("Not a surface of revolution", "not")
    assert detail.startswith("not near one either, but within the rounding it is an extrusion")
    assert "along (0.0556" in detail and "rotation-invariant" not in detail
    title, detail, _ = verdict(analyze("x^2 + 2.5y^2 + 3.7z^2 - 1", recognition_only=True))
    assert "the nearest rotation-invariant polynomial is" in detail


@pytest.mark.parametrize("value", ["0", "-1e-3", "1.5", "nan", "inf", "tight"])
def test_a_bad_tolerance_is_one_line_and_exit_2(value: str) -> None:
    out = sorgui("--tolerance", value, "x^2+y^2-z")
    assert out.returncode == 2
    assert out.stderr.count("\n") == 1 and "tolerance" in out.stderr and "Traceback" not in out.stderr
    data = json.loads(sorgui("--json", "--tolerance", value, "x^2+y^2-z").stdout)
    assert "tolerance" in data["error"]["message"]
