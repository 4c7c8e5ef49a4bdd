"""A parametrization's report checked against its map (sorgui.engine.claims.parametric, docs/math.md
§14): every genuine report passes, with and without its implicit equation, exact and rounded; every
claim about the map, or about the implicit equation, changed to a lie is refused naming its field
(real analyses, real Singular)."""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import pytest

from sorgui.engine import analyze
from sorgui.engine.claims.report import check_report
from sorgui.engine.errors import ClaimError
from sorgui.engine.results import Analysis
from sorgui.samples import bicubic_patch, map_text, revolved_patch, rotation

from .test_claims import refused_naming, tampered

ISSUE = "x = (1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s^2"
CUT_SHORT = (
    "x = (1-t^2)/(1+t^2)*(2+s^7+3*s^20-s^27)/(1+s^2+s^30), y = 2*t/(1+t^2)*(2+s^7+3*s^20-s^27)/(1+s^2+s^30),"
    " z = (s^29+s^3-5*s)/(1+s^2+s^30)"
)
"""A surface of revolution whose profile curve takes seconds to implicitize (degree 60)."""
PRINTED = map_text(
    revolved_patch({0: 2, 1: 1, 2: -1}, {0: 1, 2: 1}, rotation(np.array([0.9, 0.3, -0.2, 0.4])).tolist(), digits=10)
)
"""A surface of revolution turned by a rotation and printed with 10 digits: nearly one."""

MAPS: dict[str, tuple[str, dict[str, Any]]] = {
    "surface of revolution": (ISSUE, {}),
    "cone": ("x = s*(1-t^2)/(1+t^2) + 1, y = 3*s*2*t/(1+t^2) + 2, z = 3 + 2*s", {}),
    "paraboloid in u, v": ("x = u; y = v; z = u^2 + v^2", {}),
    "sphere": ("x = 2*s/(1+s^2+t^2), y = 2*t/(1+s^2+t^2), z = (1-s^2-t^2)/(1+s^2+t^2)", {}),
    "plane": ("x = s + t, y = s - t, z = 2*s + 1", {}),
    "cylinder over a cubic": ("(s^2, s^3, t)", {}),
    "cone over Q(sqrt 2), equation over QQ": (
        "x = sqrt(2)*(1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s",
        {},
    ),
    "rounded, exactly of revolution": ("x = 0.5*(1-t^2)/(1+t^2)*(2+s), y = 0.5*2*t/(1+t^2)*(2+s), z = 1.25*s^2", {}),
    "rounded, equation by Singular's elimination": ("x = 1.5e-1*s + t, y = s - t, z = s*t^2 + 2.5*s^3", {}),
    "rounded, nearly of revolution (no equation)": (PRINTED, {"recognition_only": True}),
    "bicubic patch (no equation)": (map_text(bicubic_patch(seed=3)), {"recognition_only": True, "timeout": 3}),
    "patch over Q(sqrt 2) (no equation: elimination is over QQ)": (
        "x = s + sqrt(2)*t^2, y = t + s^3, z = s*t^2 + t",
        {},
    ),
    "cut short in the implicit equation (no equation)": (CUT_SHORT, {"recognition_only": True, "timeout": 1}),
}


@pytest.fixture(scope="module")
def reports() -> dict[str, Analysis]:
    """Each map's analysis as a report reads it back (through its JSON)."""
    out = {}
    for name, (text, options) in MAPS.items():
        analysis = analyze(text, **{"timeout": 60, **options})
        out[name] = Analysis.from_json(json.loads(json.dumps(analysis.to_json())))
    return out


def test_the_reports_are_the_cases_they_are_named_for(reports: dict[str, Analysis]) -> None:
    known = {name for name, a in reports.items() if a.recognition.polynomial}
    assert known == {name for name in MAPS if "no equation" not in name}
    assert all(a.input_kind == "parametrization" for a in reports.values())
    assert reports["cone over Q(sqrt 2), equation over QQ"].field == "QQ(sqrt(2))"
    assert "sqrt" not in reports["cone over Q(sqrt 2), equation over QQ"].recognition.polynomial
    assert reports["rounded, exactly of revolution"].approximate is not None
    eliminated = reports["rounded, equation by Singular's elimination"].parametric
    assert eliminated is not None and eliminated.implicit_method == "elimination"
    nearly = reports["rounded, nearly of revolution (no equation)"].approximate
    assert nearly is not None and nearly.near_sor
    cut = reports["cut short in the implicit equation (no equation)"]
    assert "implicit equation" in cut.unfinished and cut.recognition.axis is not None


@pytest.mark.parametrize("name", list(MAPS))
def test_every_genuine_report_passes(reports: dict[str, Analysis], name: str) -> None:
    check_report(reports[name])


SOR = "surface of revolution"
CUT = "cut short in the implicit equation (no equation)"
PATCH = "bicubic patch (no equation)"
ELIMINATED = "rounded, equation by Singular's elimination"
LIES = [
    (SOR, ("parametric", "map", 2), "s**3", "parametric.map"),
    (SOR, ("parametric", "map", 2), "s**2 + 0*t", None),  # the same map printed otherwise
    (SOR, ("parametric", "map_parameters"), ["t", "s"], "parametric.map"),
    (SOR, ("parametric", "degree"), 7, "parametric.degree"),
    (SOR, ("parametric", "field"), "QQ(sqrt(3))", "parametric.field"),
    (SOR, ("parametric", "symmetry"), "sphere", "parametric.symmetry"),
    (SOR, ("parametric", "symmetry_basis", 0), ["1", "0", "0", "0", "0", "0"], "parametric.symmetry_basis"),
    (SOR, ("parametric", "profile_check"), None, "parametric.profile_check"),
    (SOR, ("parametric", "profile_curve"), "h - rho", "parametric.profile_curve"),
    (SOR, ("parametric", "profile_curve"), "0", "parametric.profile_curve"),
    (SOR, ("parametric", "implicit_method"), "elimination", "parametric.implicit_method"),
    (SOR, ("parametric", "fibre"), 2, "parametric.proper"),
    (SOR, ("polynomial",), "x**2 + y**2 - z", "polynomial"),
    (SOR, ("parametrizations", 0, "coordinates", 0), "s", "parametrizations[0]"),
    (SOR, ("axis", "point"), ["1", "0", "0"], "axis.point"),
    (SOR, ("rationality", "table_row"), 3, "rationality.table_row"),
    ("cone", ("parametric", "apex"), ["1", "2", "4"], "parametric.apex"),
    ("cone", ("parametric", "conical"), "none", "parametric.conical"),
    ("cone", ("conical", "apex"), ["1", "2", "4"], "conical.apex"),
    ("cone", ("conical", "kind"), "none", "conical.kind"),
    ("cylinder over a cubic", ("parametric", "directions"), [["1", "0", "0"]], "parametric.directions"),
    ("cylinder over a cubic", ("parametric", "directions"), [], "parametric.directions"),
    ("cone over Q(sqrt 2), equation over QQ", ("parametric", "apex"), ["0", "0", "2"], "parametric.apex"),
    ("cone over Q(sqrt 2), equation over QQ", ("field",), "QQ", "field"),
    (ELIMINATED, ("parametric", "implicit_method"), "profile curve", "parametric.implicit_method"),
    (ELIMINATED, ("polynomial",), "x**3 - z", "polynomial"),
    (ELIMINATED, ("conical", "kind"), "cylinder", "conical"),
    (PATCH, ("symmetry",), "revolution", "symmetry"),
    (PATCH, ("parametrizations", 0, "coordinates", 1), "t + 1", "parametrizations[0]"),
    (PATCH, ("conical", "kind"), "cone", "conical.kind"),
    (PATCH, ("parametric", "implicit_method"), "elimination", "parametric.implicit_method"),
    (PATCH, ("squarefree",), "x", "squarefree"),
    (CUT, ("axis", "point"), ["1", "0", "0"], "axis.point"),
    (CUT, ("axis", "direction"), ["0", "1", "0"], "axis.direction"),
    (CUT, ("parametric", "symmetry"), "none", "parametric.symmetry"),
    (CUT, ("symmetry",), "sphere", "symmetry"),
    (PATCH, ("canal", "is_canal"), True, "canal.is_canal"),
]


@pytest.mark.parametrize(
    ("name", "path", "value", "named"), LIES, ids=[f"{n}:{'.'.join(map(str, p))}" for n, p, *_ in LIES]
)
def test_a_lie_is_refused_naming_its_field(
    reports: dict[str, Analysis],
    name: str,
    path: tuple[Any, ...],
    value: Any,  # noqa: ANN401
    named: str | None,
) -> None:
    refused_naming(tampered(reports[name], path, value), named)  # None: the truth in other words


@pytest.mark.parametrize("name", [SOR, ELIMINATED])
def test_a_multiple_of_the_implicit_equation_is_refused(reports: dict[str, Analysis], name: str) -> None:
    """``f·(x + 1)`` vanishes on the map too, but the image of a map is irreducible."""
    analysis = reports[name]
    with pytest.raises(ClaimError, match="^polynomial is a product"):
        check_report(tampered(analysis, ("polynomial",), f"({analysis.recognition.polynomial})*(x + 1)"))


def test_the_profile_curve_is_the_implicit_equations(reports: dict[str, Analysis]) -> None:
    """``F·(h + 1)`` vanishes on the map's ``(h, ρ)`` too, but ``f`` is not ``F(h, ρ)`` of it."""
    sor = reports[SOR]
    record = sor.parametric
    assert record is not None and record.profile_curve is not None
    with pytest.raises(ClaimError, match="^parametric.profile_curve is not the profile curve"):
        check_report(tampered(sor, ("parametric", "profile_curve"), f"({record.profile_curve})*(h + 1)"))


def test_without_the_equation_only_the_map_itself_parameterizes(reports: dict[str, Analysis]) -> None:
    """A report that does not know ``f`` cannot have another parameterization checked: a copy of
    the map in other names passes, the torus's does not; nor may it claim what ``f`` decides."""
    cut = reports[CUT].to_json()
    given = cut["parametrizations"][0]
    renamed = dict(given, parameters=["u", "v"], coordinates=[c.replace("s", "u") for c in given["coordinates"]])
    renamed["coordinates"] = [c.replace("t", "v") for c in renamed["coordinates"]]
    check_report(tampered(reports[CUT], ("parametrizations",), [given, renamed]))
    other = dict(given, coordinates=["s", "t", "s**2 + t**2"])
    with pytest.raises(ClaimError, match=r"^parametrizations\[1\] is not the map"):
        check_report(tampered(reports[CUT], ("parametrizations",), [given, other]))
    torus = analyze("(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)").to_json()
    with pytest.raises(ClaimError, match="^profile"):
        check_report(tampered(reports[CUT], ("profile",), torus["profile"]))
    with pytest.raises(ClaimError, match="^rationality"):
        check_report(tampered(reports[PATCH], ("rationality",), torus["rationality"]))


def test_a_properness_changed_in_the_record_alone_is_refused(reports: dict[str, Analysis]) -> None:
    """``parametric.proper = false`` with a fibre of 2 agrees with itself, and the report was
    opened saying the given map is not proper and, further down, that it is ("real, proper")."""
    lie = tampered(reports[SOR], ("parametric", "fibre"), 2)
    refused_naming(tampered(lie, ("parametric", "proper"), False), "parametrizations[0].proper")
