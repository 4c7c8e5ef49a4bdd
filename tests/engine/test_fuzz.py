"""No analysis ends in an internal error: generated equations of the kinds users paste.

Every failure the engine means is a :class:`~sorgui.engine.errors.SorguiError` (a parse error,
an analysis that cannot proceed, Singular's trouble); anything else is a bug. The equations mix
what galleries and CAD systems print: decimals and exponents, square roots, products of
surfaces (reducible), surfaces of revolution about the coordinate axes and about other lines,
powers, blends of two surfaces.
"""

from __future__ import annotations

from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from sorgui.engine import ParseError, SorguiError, analyze

NUMBERS = st.one_of(
    st.integers(-9, 9).map(str),
    st.sampled_from(["0.5", "1.5", "3.0", "0.25", "1.5e-3", "2.000001", "-0.333333", "1e-2"]),
    st.sampled_from(["sqrt(2)", "sqrt(3)", "(1/2)", "(2/3)", "sqrt(2)/2"]),
)
ATOMS = st.sampled_from(
    ["x", "y", "z", "(x^2+y^2)", "(x²+y²)", "(x^2+y^2+z^2)", "(x-1)", "(y+2z)", "(x+y+z)", "(y^2+z^2)", "(x-sqrt(2)*y)"]
)


@st.composite
def terms(draw: st.DrawFn) -> str:
    return f"{draw(NUMBERS)}*{draw(ATOMS)}^{draw(st.integers(0, 2))}"


@st.composite
def sums(draw: st.DrawFn) -> str:
    return "(" + "+".join(draw(st.lists(terms(), min_size=1, max_size=4))) + ")"


@st.composite
def equations(draw: st.DrawFn) -> str:
    kind = draw(st.sampled_from(["sum", "product", "power", "blend", "revolution"]))
    if kind == "sum":
        return draw(sums())
    if kind == "product":
        return f"{draw(sums())}*{draw(sums())}"
    if kind == "power":
        return f"{draw(sums())}^{draw(st.integers(2, 3))}+{draw(NUMBERS)}"
    first, second = draw(sums()), draw(sums())
    if kind == "blend":
        return f"{first}^2+{second}^2-{first}^2*{second}^2-{draw(NUMBERS)}"
    radius = draw(st.sampled_from(["(x^2+y^2)", "(y^2+z^2)", "((x-1)^2+(y-2)^2)"]))
    along = {"(x^2+y^2)": "z", "(y^2+z^2)": "x", "((x-1)^2+(y-2)^2)": "z"}[radius]
    coefficients = draw(st.lists(NUMBERS, min_size=2, max_size=4))
    profile = "+".join(f"{c}*{radius}^{i % 2}*{along}^{i // 2}" for i, c in enumerate(coefficients))
    return f"{profile}+{radius}^2"


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(equations())
# found by this test in CI: a family in square roots whose circles need the root of 2i
@example("(0.5*(x^2+y^2)^1)^2+(0.5*(x^2+y^2)^1)^2-(0.5*(x^2+y^2)^1)^2*(0.5*(x^2+y^2)^1)^2--3")
# found by this test in CI: two near-translations and no rotation (a division by |a|² = 0)
@example("(1*x^2+1.5e-3*y^2)")
def test_no_analysis_ends_in_an_internal_error(text: str) -> None:
    try:
        result = analyze(text, timeout=30)
    except ParseError:
        return
    except SorguiError:
        return
    assert result.recognition.symmetry
    notes = [
        *(result.rationality.notes if result.rationality else ()),
        *(result.canal.notes if result.canal else ()),
        *(result.approximate.notes if result.approximate else ()),
    ]
    assert not any("Error" in note or "internal error" in note for note in notes), notes
