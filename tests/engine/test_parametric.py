"""The analysis of a parametrization (docs/math.md §13): the same answers as for its equation,
with the map's own results; a bicubic patch and a perturbed surface of revolution are none, a
surface of revolution printed with 10 digits is nearly one."""

from __future__ import annotations

import json
from fractions import Fraction

import numpy as np
import pytest

from sorgui.engine import analyze
from sorgui.engine.results import Analysis
from sorgui.samples import bicubic_patch, map_text, quaternion_rotation, revolved_patch, rotation

ISSUE = "x = (1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s^2"
RADIUS = {0: 2, 1: 1, 2: Fraction(1, 3), 3: -1, 4: Fraction(1, 5)}
HEIGHT = {0: 1, 1: -1, 2: 1, 3: Fraction(1, 2), 4: Fraction(-1, 7)}
"""A profile of degree 4: with the rotation in ``t`` the map has bidegree (4, 2)."""


def test_the_issue_example_is_a_surface_of_revolution_with_the_keys_of_an_equation() -> None:
    analysis = analyze(ISSUE, timeout=120)
    data = analysis.to_json()
    equation = analyze(data["polynomial"], timeout=120).to_json()
    assert data["input_kind"] == "parametrization" and equation["input_kind"] == "equation"
    assert set(equation) <= set(data)
    assert data["is_sor"] and data["symmetry"] == "revolution"
    assert data["axis"]["direction"] == ["0", "0", "1"] and data["axis"]["point"] == ["0", "0", "0"]
    assert data["polynomial"] == equation["polynomial"]
    assert data["rationality"]["table_row"] == equation["rationality"]["table_row"]
    assert data["canal"]["is_canal"] is True
    record = data["parametric"]
    assert record["components"] == ["(1-t^2)/(1+t^2)*(2+s)", "2*t/(1+t^2)*(2+s)", "s^2"]
    assert record["parameters"] == ["s", "t"]
    assert record["profile_check"] is True and record["implicit_method"] == "profile curve"
    assert record["profile_curve"] is not None
    assert record["proper"] is True and record["fibre"] == 1
    given = data["parametrizations"][0]
    assert given["method"] == "the given parametrization" and given["proper"] is True
    assert [p["method"] for p in equation["parametrizations"]] == ["rotated profile"]
    assert [p["method"] for p in data["parametrizations"]] == ["the given parametrization"]
    note = "the rotated profile's map is the given map at (s, t) = (-t - 2, -1/s): listed once"
    assert note in data["rationality"]["notes"]
    assert Analysis.from_json(json.loads(json.dumps(data))) == analysis


TILTED = map_text(revolved_patch(RADIUS, HEIGHT, quaternion_rotation((1, 2, -2, 4)), (1, Fraction(-1, 2), 3)))
"""The profile of :data:`RADIUS` and :data:`HEIGHT` turned about a tilted rational axis (``|a|² ≠ 1``)."""


@pytest.mark.parametrize(
    ("given", "names", "dropped"),
    [
        ("x = (1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s^2", ("s", "t"), "rotated profile"),
        (
            "x = 2*u/(1+u^2)*(3+(1-v^2)/(1+v^2)), y = (1-u^2)/(1+u^2)*(3+(1-v^2)/(1+v^2)), z = 2*v/(1+v^2)",
            ("u", "v"),
            "rotated profile",
        ),
        (TILTED, ("s", "t"), "via tubular surface (real)"),
        ("x = (1-t^2)/(1+t^2)*(sqrt(2)+s), y = 2*t/(1+t^2)*(sqrt(2)+s), z = s^2", ("s", "t"), "rotated profile"),
    ],
)
def test_a_map_the_typed_one_is_after_a_change_of_parameters_is_not_listed(
    monkeypatch, given: str, names: tuple[str, str], dropped: str
) -> None:
    """A map that is the typed map after Möbius maps of its parameters (and a swap of them) is
    left out with a note (docs/math.md §6), over ``QQ`` and over ``QQ(√2)``; the note's change is
    checked by substituting it into the typed map: it gives the map left out (made again with the
    comparison turned off)."""
    import sympy

    from sorgui.engine.revolution import rationality

    analysis = analyze(given, timeout=120)
    assert [p.method for p in analysis.parametrizations] == ["the given parametrization"]
    name = "the rotated profile's map" if dropped == "rotated profile" else "the map through T"
    start = f"{name} is the given map at ({', '.join(names)}) = ("
    note = next(n for n in analysis.rationality.notes if n.startswith(start))
    monkeypatch.setattr(rationality, "_given_again", lambda *_: [])
    every = analyze(given, timeout=120)
    (left_out,) = [p for p in every.parametrizations if p.method == dropped]
    s, t = sympy.symbols("s t")
    local = {"s": s, "t": t, "sqrt": sympy.sqrt}
    images = [sympy.sympify(e, locals=local) for e in note.removeprefix(start).split("): listed once")[0].split(", ")]
    typed = [
        sympy.sympify(c, locals={**local, names[0]: s, names[1]: t}) for c in analysis.parametrizations[0].coordinates
    ]
    made = [sympy.sympify(c, locals=local) for c in left_out.coordinates]
    moved = [c.subs({s: images[0], t: images[1]}, simultaneous=True) for c in typed]
    assert all(sympy.cancel(a - b) == 0 for a, b in zip(moved, made))


def test_a_typed_map_is_proper_as_the_proper_map_left_out_for_it() -> None:
    """Singular counts fibres over ``QQ`` only, so it leaves a map over ``QQ(√2)`` undecided; the
    rotated profile's map, proper as the map through ``T`` is, is that map after bijections of
    the parameters and is left out for it: so the typed map is proper (docs/math.md §6, "The
    typed map"), and its report passes the claims' checks. Over ``QQ`` Singular's generic fibre
    says the same."""
    from sorgui.engine.claims.report import check_report
    from sorgui.engine.parametric.pipeline import PROPER_AS_LEFT_OUT

    over_root = analyze("x = (1-t^2)/(1+t^2)*(sqrt(2)+s), y = 2*t/(1+t^2)*(sqrt(2)+s), z = s^2", timeout=120)
    record = over_root.parametric
    assert record is not None and over_root.rationality is not None and over_root.rationality.given_map_proper
    assert (record.proper, record.fibre, record.proper_method) == (True, 1, PROPER_AS_LEFT_OUT)
    assert [p.proper for p in over_root.parametrizations] == [True]
    check_report(Analysis.from_json(json.loads(json.dumps(over_root.to_json()))))
    over_q = analyze("x = (1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s^2", timeout=120)
    assert over_q.rationality is not None and over_q.rationality.given_map_proper
    assert over_q.parametric is not None and over_q.parametric.proper is True
    assert over_q.parametric.proper_method == "the generic fibre (Singular, over QQ(s0, t0))"


def test_a_bidegree_4_2_surface_of_revolution_on_a_rational_axis() -> None:
    R = quaternion_rotation((1, 2, -2, 4))
    text = map_text(revolved_patch(RADIUS, HEIGHT, R, (1, Fraction(-1, 2), 3)))
    analysis = analyze(text, timeout=120)
    assert analysis.is_sor and analysis.recognition.symmetry == "revolution"
    direction = [str(Fraction(R[i][2])) for i in range(3)]
    axis = analysis.recognition.axis
    assert axis is not None
    k = next(i for i in range(3) if direction[i] != "0")
    scale = Fraction(axis.direction[k]) / Fraction(direction[k])
    assert [Fraction(c) for c in axis.direction] == [scale * Fraction(c) for c in direction]
    rationality = analysis.rationality
    assert rationality is not None and rationality.table_row in (1, 3, 4)  # X_C is rational
    # P² is parameterized by the map's own curve: paraPlaneCurve gave none of it in 60 s
    assert rationality.status == "decided" and rationality.square_parametrization is not None
    assert dict(analysis.timings)["rationality"] < 30


def test_a_random_bicubic_patch_is_not_a_surface_of_revolution() -> None:
    analysis = analyze(map_text(bicubic_patch(seed=3)), timeout=8)
    assert not analysis.is_sor and analysis.recognition.symmetry == "none"
    assert analysis.recognition.symmetry_dimension == 0
    assert analysis.conical is not None and analysis.conical.kind == "none"
    assert analysis.input_kind == "parametrization"
    assert analysis.parametric is not None and analysis.parametric.symmetry == "none"
    assert analysis.parametrizations[0].method == "the given parametrization"


def test_a_surface_of_revolution_plus_a_small_term_is_not_one() -> None:
    text = map_text(revolved_patch(RADIUS, HEIGHT, extra="1/1000*s*t"))
    analysis = analyze(text, timeout=60, recognition_only=True)
    assert not analysis.is_sor and analysis.recognition.symmetry == "none"
    assert analysis.approximate is None  # exact input: the exact answer only


def _printed(digits: int, extra: str = "") -> str:
    R = rotation(np.array([0.9, 0.3, -0.2, 0.4]))
    return map_text(revolved_patch(RADIUS, HEIGHT, R.tolist(), (0.3, -1.2, 0.5), digits=digits, extra=extra))


def test_a_surface_of_revolution_printed_with_10_digits_is_nearly_one() -> None:
    analysis = analyze(_printed(10), timeout=60, recognition_only=True)
    assert not analysis.is_sor
    approx = analysis.approximate
    assert approx is not None and approx.near_sor and approx.kind == "revolution"
    assert approx.tolerance == pytest.approx(5e-10)
    assert approx.residual is not None and approx.residual <= 1
    axis = rotation(np.array([0.9, 0.3, -0.2, 0.4]))[:, 2]
    assert approx.axis is not None
    assert abs(abs(np.dot(approx.axis.direction, axis)) - 1) < 1e-8
    offset = np.array(approx.axis.point) - np.array([0.3, -1.2, 0.5])
    assert np.linalg.norm(np.cross(offset, axis)) < 1e-7


def test_a_perturbed_surface_of_revolution_printed_with_10_digits_is_not_nearly_one() -> None:
    analysis = analyze(_printed(10, extra="1/1000*s*t"), timeout=60, recognition_only=True)
    approx = analysis.approximate
    assert approx is not None and not approx.near_sor
    assert approx.relative_distance is not None and approx.relative_distance > 1e-5


def test_a_time_limit_keeps_the_parametrization() -> None:
    analysis = analyze(map_text(bicubic_patch(seed=5)), timeout=1.5)
    assert analysis.input_kind == "parametrization" and analysis.parametric is not None
    assert analysis.recognition.symmetry == "none"  # the decision takes milliseconds


@pytest.mark.parametrize(
    "text",
    [
        "x = 2.000*s/(1+s^2+t^2), y = 2.040*t/(1+s^2+t^2), z = 1.010*(s^2+t^2-1)/(1+s^2+t^2)",
        "x = 2.0*s/(1+s^2+t^2), y = 3.0*t/(1+s^2+t^2), z = 4.0*(s^2+t^2-1)/(1+s^2+t^2)",
    ],
)
def test_a_rounded_map_near_no_symmetry_says_so_once(text: str) -> None:
    """Two ellipsoids, not of revolution: the report said "not near" and then "residual 0.718
    times the rounding (at most 1: within it)", or "nearness not decided" with no reason; it now
    says why no kind was tried."""
    from sorgui.export.text import plain_text

    analysis = analyze(text, recognition_only=True)
    assert analysis.approximate is not None and not analysis.approximate.near_sor
    report = plain_text(analysis)
    assert "not near a surface of revolution" in report
    assert "within it" not in report and "not decided" not in report
    assert "not near any continuous symmetry: the smallest singular value" in report


def test_a_map_over_a_number_field_prints_without_denominator_one() -> None:
    """Its components printed as ``(t)/(1)``: the denominator, an element of QQ(√2), was compared
    with the integer 1."""
    analysis = analyze("(sqrt(2)*s, t, s*t)")
    assert analysis.parametric is not None and analysis.parametric.map == ("sqrt(2)*s", "t", "s*t")


TORUS_FIXED_POINT = (
    "(1.500000 + 0.781639*((30+10*(1-u^2)/(1+u^2))*(1-v^2)/(1+v^2)) + -0.482929*((30+10*(1-u^2)/(1+u"
    "^2))*2*v/(1+v^2)) + 0.394740*(10*2*u/(1+u^2)), -2.250000 + 0.550117*((30+10*(1-u^2)/(1+u^2))*(1"
    "-v^2)/(1+v^2)) + 0.832030*((30+10*(1-u^2)/(1+u^2))*2*v/(1+v^2)) + -0.071392*(10*2*u/(1+u^2)), 1"
    "00.125000 + -0.293958*((30+10*(1-u^2)/(1+u^2))*(1-v^2)/(1+v^2)) + 0.272956*((30+10*(1-u^2)/(1+u"
    "^2))*2*v/(1+v^2)) + 0.916015*(10*2*u/(1+u^2)))"
    ""
)
"""A torus (radii 30 and 10) turned by a float rotation and moved to ``(1.5, −2.25, 100.125)``, its
map printed with fixed decimals (``%.6f``)."""

TORUS_ALL_DIGITS = (
    "(1.5 + 0.78163917390702498*((30+10*(1-u^2)/(1+u^2))*(1-v^2)/(1+v^2)) + -0.48292928421421222*((30+10*"
    "(1-u^2)/(1+u^2))*2*v/(1+v^2)) + 0.39473979817379978*(10*2*u/(1+u^2)), -2.25 + 0.55011723070435836*(("
    "30+10*(1-u^2)/(1+u^2))*(1-v^2)/(1+v^2)) + 0.83203013377463464*((30+10*(1-u^2)/(1+u^2))*2*v/(1+v^2)) "
    "+ -0.071392499417875871*(10*2*u/(1+u^2)), 100.125 + -0.29395787843858057*((30+10*(1-u^2)/(1+u^2))*(1"
    "-v^2)/(1+v^2)) + 0.27295633888831433*((30+10*(1-u^2)/(1+u^2))*2*v/(1+v^2)) + 0.91601506688731726*(10"
    "*2*u/(1+u^2)))"
)
"""The same torus with the rotation's entries printed with 17 significant digits (``%.17g``)."""


def test_a_map_printed_with_fixed_decimals_is_judged_by_its_coarsest_literal() -> None:
    """Its translation ``100.125000`` has 9 significant digits, and the tolerance was read off
    it (``5·10⁻⁹``), a hundred times finer than the rotation's ``0.071392``: the torus was "not
    near" (1.46 times outside). Each literal's own last place now counts, relative to its size
    or to 1; an entry moved by ``10⁻³`` stays far outside."""
    approx = analyze(TORUS_FIXED_POINT, timeout=60, recognition_only=True).approximate
    assert approx is not None and approx.tolerance == pytest.approx(5e-7)
    assert approx.near_sor and approx.kind == "revolution"
    missed = analyze(TORUS_FIXED_POINT.replace("0.781639", "0.782639"), timeout=60, recognition_only=True)
    assert missed.approximate is not None and not missed.approximate.near_sor
    assert missed.approximate.residual is not None and missed.approximate.residual > 10


def test_a_map_printed_with_every_digit_of_a_double_is_read_at_floating_point_precision() -> None:
    """With 17 digits the tolerance was ``5·10⁻¹⁷``, below the double precision its normals are
    sampled in, and the torus was 7.9 times outside it; it is now read at ``4·10⁻¹⁵``, and an
    entry moved by ``10⁻¹²`` stays outside."""
    approx = analyze(TORUS_ALL_DIGITS, timeout=60, recognition_only=True).approximate
    assert approx is not None and approx.tolerance == pytest.approx(4e-15)
    assert approx.near_sor and approx.kind == "revolution"
    moved = TORUS_ALL_DIGITS.replace("0.78163917390702498", "0.78163917390802498")
    missed = analyze(moved, timeout=60, recognition_only=True).approximate
    assert missed is not None and not missed.near_sor


def test_a_textbook_torus_in_cos_and_sin_is_the_torus() -> None:
    """``((50 + 12.5 cos v) cos u, (50 + 12.5 cos v) sin u, 12.5 sin v)`` was refused ("'cos' is
    not allowed"). Read in ``t = tan(u/2)`` and ``s = tan(v/2)`` (docs/math.md §13) it is the
    torus of radii 50 and 12.5, of Table 1's row 1, its map proper and listed as given."""
    analysis = analyze("x = (50 + 12.5*cos(v))*cos(u), y = (50 + 12.5*cos(v))*sin(u), z = 12.5*sin(v)", timeout=120)
    assert analysis.is_sor and analysis.input_kind == "parametrization"
    assert analysis.recognition.polynomial == (
        "16*x**4 + 32*x**2*y**2 + 32*x**2*z**2 + 16*y**4 + 32*y**2*z**2 + 16*z**4"
        " - 85000*x**2 - 85000*y**2 + 75000*z**2 + 87890625"
    )
    record = analysis.parametric
    assert record is not None and record.map_parameters == ("t", "s") and record.proper
    assert any("t = tan(u/2)" in note for note in record.notes)
    assert analysis.rationality.table_row == 1
    assert any(p.verified and p.real for p in analysis.parametrizations)


def test_a_rounded_turned_torus_in_cos_and_sin_is_nearly_of_revolution() -> None:
    """The same torus (radii 2 and 1) turned by 45° about y, with ``√2/2`` printed to 10 digits."""
    c = "0.7071067812"
    text = f"x = {c}*(2+cos(v))*cos(u) - {c}*sin(v), y = (2+cos(v))*sin(u), z = {c}*(2+cos(v))*cos(u) + {c}*sin(v)"
    analysis = analyze(text, timeout=120)
    assert not analysis.is_sor and analysis.approximate is not None and analysis.approximate.near_sor


def test_the_given_map_is_said_to_give_x_as_the_closure_of_its_image() -> None:
    """``(s² − t², 2st, s² + t²)`` reaches only ``z ≥ 0`` of the cone ``x² + y² = z²`` with real
    parameters: "X is its image" was false over the reals."""
    given = analyze("(s^2-t^2, 2*s*t, s^2+t^2)").parametrizations[0]
    assert given.method == "the given parametrization"
    assert "X is the closure of its image" in given.verification and "part of it" in given.verification


def test_a_rounded_map_s_nearness_is_said_in_its_own_unit() -> None:
    """A rounded torus's map is near a surface of revolution when its deviation is within 30
    times the tolerance: 1.8 times it was said to be "within the rounding of the input", with a
    "residual 0.0605 times the rounding" beside it."""
    from pathlib import Path

    from sorgui.export.text import plain_text

    text = (Path(__file__).parents[1] / "data" / "rounded-torus-map.txt").read_text(encoding="utf-8")
    report = plain_text(analyze(text, recognition_only=True))
    assert "NEARLY: within 30 times the rounding of the input" in report
    assert "times 30 times the tolerance, a map's limit of nearness (at most 1: within it)" in report


def test_a_map_printed_with_two_digits_is_near_nothing_it_is_not() -> None:
    """Printed with two significant digits (a tolerance of 0.05), 30 times the tolerance is above
    1, and the elliptic paraboloid ``(s, 2t, 3s² + 3t²)`` was "nearly a cylinder along (0, 0, 1)
    within the rounding (relative residual 0.86)": its normals lean up to 80° from the
    perpendicular to that direction. A map's limit of nearness is at most 0.05."""
    from sorgui.engine.results import MAP_NEAR_CEILING, map_near_limit
    from sorgui.export.text import plain_text

    assert map_near_limit(0.05) == MAP_NEAR_CEILING == 0.05 and map_near_limit(5e-7) == pytest.approx(1.5e-5)
    analysis = analyze("1.0*s, 2.0*t, 3.0*s^2 + 3.0*t^2", timeout=120)
    assert analysis.conical is not None and analysis.conical.kind == "none"
    assert analysis.conical.near_direction is None and analysis.conical.near_apex is None
    assert "nearly" not in plain_text(analysis)
