"""Canal surfaces (docs/math.md §9): every example of tests/data/canal-examples.txt gets its verdict,
with a certificate or a witness line, the kinds, the spines and the verified families."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import sympy

from sorgui.engine.algebra import numberfields
from sorgui.engine.algebra.polys import Poly, to_flint
from sorgui.engine.analysis import analyze
from sorgui.engine.canal import verdict as canal_module
from sorgui.engine.canal.lines import LINES, SEED, Lines
from sorgui.engine.canal.spine import SmatCurve, smat_curves
from sorgui.engine.canal.verdict import (
    CERTIFICATE_LINE,
    _rational_squarefree,
    analyze_canal,
    envelope_certificate,
)
from sorgui.engine.parsing import parse_polynomial
from sorgui.engine.results import Analysis, Canal
from sorgui.export.text import plain_text

EXAMPLES = Path(__file__).resolve().parents[1] / "data" / "canal-examples.txt"


def examples() -> dict[str, str]:
    """``name → polynomial`` from the examples file (``## name | expectation`` then the polynomial)."""
    lines = EXAMPLES.read_text(encoding="utf-8").splitlines()
    return {line[3:].split(" |")[0]: lines[i + 1] for i, line in enumerate(lines) if line.startswith("## ")}


EXPECTED: dict[str, set[str] | None] = {
    "torus R=2 r=1": {"dupin", "pipe", "revolution"},
    "Dupin a,b,c,mu=5,4,3,4": {"dupin"},
    "hyperboloid x2+y2-z2-1": {"revolution"},
    "cone of revolution": {"developable", "revolution"},
    "cylinder": {"developable", "pipe", "revolution"},
    "triaxial ellipsoid": None,
    "elliptic cylinder": None,
    "elliptic paraboloid": None,
    "blend cyl R=2 / plane z=0, ball 1 (torus)": {"dupin", "pipe", "revolution"},
    "squashed torus": None,
    "Darboux cyclide": None,
    "pipe parabola": {"pipe"},
    "canal parabola r=(1+t)/2": set(),
    "SOR z-axis r=1+t^2/2": {"revolution"},
    "pipe twisted cubic": {"pipe"},
    "blend cyl R=2 / plane 3x+4z=0, ball 1": {"pipe"},
    "pipe parabola + z^6/1000": None,
    "Dupin + x/100": None,
}
"""The kinds of every canal example (``None``: not canal). The two degree-24 examples are below."""

SLOW = ("blend cylinders R=2 (axis y) & R=3 (axis x), ball 1 (genus-1 spine)", "two-cylinder blend + x^3")


def canal_of(name: str, full: bool = True) -> Canal:
    return analyze_canal(parse_polynomial(examples()[name]).polynomial, full=full)


def test_every_example_is_covered() -> None:
    assert set(examples()) == set(EXPECTED) | set(SLOW)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_verdict_and_kinds(name: str) -> None:
    canal = canal_of(name)
    expected = EXPECTED[name]
    if expected is None:
        assert canal.is_canal is False, canal.status
        assert canal.witness is not None and canal.witness.verified and canal.witness.method == "line"
        assert canal.families == () and canal.certificate is None
        return
    assert canal.is_canal is True, canal.status
    assert canal.certificate is not None and canal.certificate.verified
    assert set(canal.kinds) == expected
    assert canal.witness is None
    for family in canal.families:
        if family.genus == 0 and family.parametrization is not None:
            assert family.verified
    assert all(p.verified for p in canal.parametrizations)


def _substitute(equations: tuple[str, ...], values: dict[str, sympy.Expr]) -> list[sympy.Expr]:
    symbols = {n: sympy.Symbol(n) for n in ("m1", "m2", "m3", "r")}
    out = []
    for text in equations:
        expr = sympy.parse_expr(text, local_dict=symbols)  # engine output, not user input
        out.append(sympy.cancel(expr.subs({symbols[k]: v for k, v in values.items()})))
    return out


def test_dupin_cyclide_has_both_focal_conics() -> None:
    canal = canal_of("Dupin a,b,c,mu=5,4,3,4")
    assert len(canal.families) == 2
    spines = {frozenset(f.spine_equations) for f in canal.families}
    assert frozenset({"m3", "16*m1**2 + 25*m2**2 - 400"}) in spines
    assert frozenset({"m2", "16*m1**2 - 9*m3**2 - 144"}) in spines
    t = sympy.Symbol("t")
    # The ellipse (5 cos, 4 sin, 0) with r = 4 − 3 cos, rationally: cos = (1−t²)/(1+t²).
    c, s = (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)
    ellipse = next(f for f in canal.families if "m3" in f.spine_equations)
    assert _substitute(ellipse.equations, {"m1": 5 * c, "m2": 4 * s, "m3": 0, "r": (4 - 3 * c) ** 2}) == [0, 0, 0]
    assert all(f.genus == 0 and f.planar and not f.on_line and f.verified for f in canal.families)


def test_torus_spines_are_the_core_circle_and_the_axis() -> None:
    canal = canal_of("torus R=2 r=1")
    spines = {frozenset(f.spine_equations) for f in canal.families}
    assert spines == {frozenset({"m3", "m1**2 + m2**2 - 4"}), frozenset({"m1", "m2"})}
    circle = next(f for f in canal.families if f.pipe)
    assert circle.radius_squared == "1" and circle.degree == 2


def test_every_family_of_the_torus_blend_has_its_m_and_rho() -> None:
    """The second focal conic (the axis, ρ varying) has a plane model on which paraPlaneCurve
    fails; the conic route parameterizes it (docs/math.md §5)."""
    canal = canal_of("blend cyl R=2 / plane z=0, ball 1 (torus)")
    assert len(canal.families) == 2
    assert all(f.genus == 0 and f.verified and f.parametrization is not None for f in canal.families)
    assert not any("no rational m(t)" in note for note in canal.notes)


def test_a_certificate_by_two_methods_states_each() -> None:
    certificate = canal_of("torus R=2 r=1").certificate
    assert certificate.verified and set(certificate.method.split("+")) == {"resultant", "rotation"}
    first, second = certificate.statement.split("; family 2: ")
    assert first.startswith("family 1: ")
    assert {"Res_t" in first, "rotations" in first} == {True, False}
    assert ("Res_t" in second) != ("Res_t" in first)


def test_radical_parameterizations_take_square_factors_out_of_the_roots() -> None:
    """Where |e₁|², |e₂|², R² are squares of rational functions (the torus) no root is left;
    elsewhere (the twisted cubic) only square-free radicands stay under the root."""
    torus = canal_of("torus R=2 r=1")
    radicals = [p for p in torus.parametrizations if "radical" in p.method]
    assert radicals and all(p.verified and "sqrt" not in "".join(p.coordinates) for p in radicals)
    (radical,) = [p for p in canal_of("pipe twisted cubic").parametrizations if "radical" in p.method]
    t = sympy.Symbol("t")
    # the engine's own output (with sin, cos), read back here only, never in sorgui itself
    roots = set().union(*(sympy.sympify(c).atoms(sympy.Pow) for c in radical.coordinates))
    radicands = [sympy.expand(r.base) for r in roots if r.exp in (sympy.Rational(1, 2), sympy.Rational(-1, 2))]
    assert radicands and all(sympy.degree(sympy.gcd(r, sympy.diff(r, t)), t) == 0 for r in radicands)


def test_pipe_around_the_parabola() -> None:
    canal = canal_of("pipe parabola")
    (family,) = canal.families
    assert set(family.equations) == {"r - 1", "m3", "m1**2 - m2"}
    assert (family.degree, family.genus, family.planar, family.pipe) == (2, 0, True, True)
    assert canal.certificate.method == "resultant"
    radical, rational = canal.parametrizations
    assert radical.verified and radical.parameters == ("t", "theta")
    assert rational.verified and rational.real and rational.parameters == ("t", "s") and rational.field == "QQ"


def test_twisted_cubic_pipe_is_not_planar() -> None:
    (family,) = canal_of("pipe twisted cubic").families
    assert (family.degree, family.genus, family.planar, family.pipe) == (3, 0, False, True)
    t = sympy.Symbol("t")
    assert _substitute(family.equations, {"m1": t, "m2": t**2, "m3": t**3, "r": 1}) == [0] * len(family.equations)


def test_rolling_ball_blend_of_cylinder_and_oblique_plane() -> None:
    canal = canal_of("blend cyl R=2 / plane 3x+4z=0, ball 1")
    (family,) = canal.families
    assert set(family.equations) == {"r - 1", "3*m1 + 4*m3 - 5", "9*m2**2 + 16*m3**2 - 40*m3 - 56"}
    assert (family.degree, family.genus, family.planar, family.on_line) == (2, 0, True, False)
    assert family.circle_radius_squared == "1"


def test_varying_radius_is_not_a_pipe() -> None:
    (family,) = canal_of("canal parabola r=(1+t)/2").families
    assert not family.pipe and family.planar and family.genus == 0 and family.verified
    t = sympy.Symbol("t")
    assert _substitute(family.equations, {"m1": t, "m2": t**2, "m3": 0, "r": (1 + t) ** 2 / 4}) == [0, 0, 0]


@pytest.mark.parametrize("recognition_only", [False, True])
def test_a_power_of_high_degree_is_analysed_by_its_square_free_part(recognition_only: bool) -> None:
    """``q¹⁶`` has degree 32, above the canal test's limit of 30: its zero set is ``q``'s, which is
    answered (the flint path of recognition only, and the general pipeline)."""
    triaxial = analyze("(x^2 + 2y^2 + 3z^2 - 1)^16", recognition_only=recognition_only).canal
    assert triaxial is not None and triaxial.is_canal is False and "degree above" not in triaxial.status
    cone = analyze("(x^2 + y^2 - z^2)^16", recognition_only=recognition_only).canal
    assert cone is not None and cone.is_canal is True
    high = analyze("(x^31 + y^2 - z)^1", recognition_only=recognition_only).canal
    assert high is not None and "degree above 30" in high.status


def test_recognition_only_gives_the_verdict_without_the_families_parameterization() -> None:
    canal = canal_of("pipe parabola", full=False)
    assert canal.is_canal is True and canal.certificate.method == "incidence"
    assert canal.families[0].genus is None and canal.parametrizations == ()


@pytest.mark.parametrize("name", SLOW)
def test_two_cylinder_blend(name: str) -> None:
    canal = canal_of(name)
    if name.endswith("x^3"):
        assert canal.is_canal is False and canal.witness is not None
        return
    assert canal.is_canal is True and set(canal.kinds) == {"pipe"}
    (family,) = canal.families
    assert (family.degree, family.genus, family.planar, family.pipe) == (4, 1, False, True)
    assert family.parametrization is None
    assert family.radical_spine == ("t", "sqrt(t**2 + 7)", "sqrt((3 - t)*(t + 3))")
    assert (family.radical_radius_squared, family.radical_parameter) == ("1", "m1")
    (surface,) = canal.parametrizations
    assert surface.verified and "square roots" in surface.method and surface.parameters == ("t", "theta")
    assert canal.certificate.method == "incidence"
    assert any("not rational" in n for n in canal.notes)


def _pipe_parabola_and_its_smat() -> tuple[Poly, SmatCurve]:
    f = parse_polynomial(examples()["pipe parabola"]).polynomial
    lines = Lines(to_flint(f), SEED)
    for _ in range(LINES):
        lines.next()
    (curve,), _ = smat_curves(lines.sample, seed=SEED, timeout=60.0, cancel=None)
    return f, curve


@pytest.mark.parametrize("line", [CERTIFICATE_LINE, ("1", "0")])
def test_the_envelope_certificate_proves_only_envelopes(monkeypatch: pytest.MonkeyPatch, line: tuple[str, str]) -> None:
    """The incidence certificate, and the elimination it falls back to when the line proves
    nothing (here ``⟨1⟩``: no point over it): both accept the pipe and refuse another surface."""
    monkeypatch.setattr(canal_module, "CERTIFICATE_LINE", line)
    f, curve = _pipe_parabola_and_its_smat()
    method = "incidence" if line == CERTIFICATE_LINE else "elimination"
    assert envelope_certificate(f, curve, timeout=60.0, cancel=None) == method
    x = f.ring.gens[0]
    assert envelope_certificate(f + x, curve, timeout=60.0, cancel=None) is None


def test_json_round_trip_and_text_report() -> None:
    analysis = analyze(examples()["torus R=2 r=1"])
    data = json.loads(json.dumps(analysis.to_json()))
    canal = data["canal"]
    assert canal["is_canal"] is True and set(canal["kinds"]) == {"dupin", "pipe", "revolution"}
    assert canal["spine"] == canal["families"][0] and canal["radius_squared"] == canal["spine"]["radius_squared"]
    assert canal["certificate"]["verified"] and canal["witness"] is None
    assert Analysis.from_json(data) == analysis
    text = plain_text(analysis)
    assert "canal surface: YES" in text and "a Dupin cyclide" in text and "certificate (" in text


def test_text_report_of_a_near_miss() -> None:
    analysis = analyze(examples()["triaxial ellipsoid"], recognition_only=True)
    assert analysis.canal is not None and analysis.canal.is_canal is False
    text = plain_text(analysis)
    assert "canal surface: NO" in text and "witness line" in text


def test_coefficients_in_a_quadratic_field_go_through_the_norm() -> None:
    cylinder = analyze_canal(parse_polynomial("x^2 + y^2 - sqrt(2)").polynomial)
    assert cylinder.is_canal is True and set(cylinder.kinds) == {"developable", "pipe", "revolution"}
    assert cylinder.families[0].radius_squared == "a root of r**2 - 2"
    assert any("norm" in n for n in cylinder.notes)
    elliptic = analyze_canal(parse_polynomial("x^2 + sqrt(2)*y^2 - 1").polynomial)
    assert elliptic.is_canal is False and elliptic.witness is not None


def test_dupin_cyclide_has_real_rational_parameterizations() -> None:
    canal = canal_of("Dupin a,b,c,mu=5,4,3,4")
    rational = [p for p in canal.parametrizations if p.parameters == ("t", "s")]
    assert len(rational) == 2 and all(p.verified and p.real for p in rational)


def test_no_rational_parameterization_without_a_sum_of_two_squares() -> None:
    # |m′|² − r′² = 3/4 + 4t² is not a sum of two squares over QQ: only the radical form.
    canal = canal_of("canal parabola r=(1+t)/2")
    assert [p.parameters for p in canal.parametrizations] == [("t", "theta")]


def test_norm_in_the_radical_basis_matches_the_resultant(monkeypatch: pytest.MonkeyPatch) -> None:
    # Res_θ(f, m(θ)) and the flint norm one square root at a time give the same square-free part.
    f = parse_polynomial("x^2+y^2+sqrt(2)x+sqrt(3)y+sqrt(5)z+sqrt(6)").polynomial
    fast = _rational_squarefree(f)
    monkeypatch.setattr(numberfields, "supports", lambda K: False)
    assert _rational_squarefree(f) == fast


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_the_modular_screen_never_contradicts_the_exact_line_test(name: str) -> None:
    """A line the screen modulo a prime calls "not canal" is not canal over QQ; on non-canal
    examples of the general branch the screen finds such lines (it is what makes them fast)."""
    from sorgui.engine.canal import focal

    f = _rational_squarefree(parse_polynomial(examples()[name]).polynomial)
    D = focal.Derivatives(f)
    screened = 0
    lines = Lines(f, SEED)
    for _ in range(4):
        point = tuple(lines.rnd.randint(-7, 7) for _ in range(3))
        direction = tuple(lines.rnd.randint(-7, 7) or 1 for _ in range(3))
        try:
            fast = focal.line_test(D, point, direction)
        except focal.UnluckyLine:
            continue
        with pytest.MonkeyPatch.context() as patch:
            patch.setattr(focal, "_fails_modulo_prime", lambda *_: False)
            exact = focal.line_test(D, point, direction)
        assert fast.canal == exact.canal and fast.branch == exact.branch
        screened += fast.residue is None
    if EXPECTED[name] is not None:
        assert screened == 0
    elif name in ("squashed torus", "Darboux cyclide", "triaxial ellipsoid"):  # the general branch
        assert screened > 0
