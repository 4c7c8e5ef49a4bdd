"""The recognition-only analysis of an equation over ``QQ``, and the full analysis of a surface
that is neither of revolution, a cone, a cylinder nor canal on its lines, on python-flint alone.

A whole ``sorgui analyze --recognition-only`` process on a small equation is mostly imports:
sympy's alone takes longer than the whole analysis (docs/benchmarks.md). Over ``QQ`` the
recognition needs none of sympy: the parser evaluates into flint's ``QQ[x, y, z]``
(:func:`.parsing.parse_rational`), the symmetry algebra ``L`` of (★) is flint's linear algebra
(:func:`.recognition.symmetry.rational_symmetry`), the profile ``p̃(s, r) = f(c + s·a + r·u)`` and the exact
frame test are flint compositions (docs/math.md §3), the factors are flint's, and the canal
answer of a surface of revolution is its symmetry algebra's (:func:`.recognition.symmetry.revolution_canal`);
that of another surface is "not canal" when a line refutes it (:mod:`.canal.lines`).

:func:`recognition_only_analysis` gives exactly the :class:`~.report.Analysis` of the general
pipeline (a test compares the two), and declines (``None``) what needs sympy: square roots in
the input, decimals (the rounded-input stage, docs/math.md §8), a surface that passes the canal
test on its lines (its spine is computed with Singular and sympy), and an axis direction with a
large ``|a|²`` (:data:`MAX_NORM`). :func:`full_analysis` does the same for the full analysis of a
surface whose full answer is the recognition's with "not a cone or a cylinder" (one exact linear
system, :func:`conical_kind`) and "not canal" (a witness line): the published cubics and quartics
that are not surfaces of revolution, in a fifth of a second as a whole process instead of half.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, overload

from flint import fmpq, fmpq_mat, fmpq_mpoly, fmpz_mpoly

from .algebra.linalg import Vector, cross, dot, perpendicular, primitive_vector
from .algebra.rationals import (
    RATIONALS,
    context,
    factor,
    flint_str,
    irreducible,
    primitive,
    rational_str,
    rational_surd,
    terms,
    terms_str,
)
from .errors import AnalysisError
from .expanded import Reading
from .parsing import has_decimals, read_rational
from .recognition.symmetry import (
    CYLINDER,
    REVOLUTION,
    SPHERE,
    Symmetry,
    rational_symmetry,
    revolution_canal,
)
from .results import Analysis, Axis, Canal, Conical, Factor, Profile, Recognition, Triple
from .timelimit import printed_skeleton

if TYPE_CHECKING:
    from .stages import StageClock

XYZ = ("x", "y", "z")
XY = ("x", "y")
Monomial = tuple[int, int]
MAX_NORM = 2**30
"""The rational path writes ``|a| = k·√d`` with ``d`` square-free, as sympy does when it finds the
square factors of ``|a|²``; sympy looks for them by trial division up to ``2¹⁵`` only, so larger
``|a|²`` (which might have a square factor beyond it) are left to the general pipeline."""
FULL_DEGREE = 12
"""The full analysis on flint alone is for surfaces up to this degree; one of higher degree keeps
the general pipeline (tests/test_cli_stuck.py ends one of degree 45 inside its factorization)."""
Surd = tuple[fmpq, int]
"""``(q, d)``: the number ``q·√d`` (``d`` square-free; ``d = 1`` for a rational)."""


def recognition_only_analysis(text: str, clock: StageClock) -> Analysis | None:
    """The recognition-only analysis of ``text`` over ``QQ`` (stages parse, recognition, factors,
    canal, run on ``clock``), or ``None`` when it needs sympy. Raises :class:`ParseError` for
    bad input, as the general pipeline does.

    ``clock`` is told the equation's skeleton once it is read (:meth:`StageClock.read`) and the
    recognition once it is done: a time limit met later reports them."""
    return _analysis(text, clock, full=False)


def full_analysis(text: str, clock: StageClock) -> Analysis | None:
    """The full analysis of ``text`` over ``QQ`` when it needs neither sympy nor Singular: a
    surface that is not of revolution (no real locus, rationality or parameterizations), not a
    cone or a cylinder (one exact linear system in flint, :func:`conical_kind`) and not canal by
    a line of the canal test (:mod:`.canal.lines`). ``None`` otherwise: the general pipeline
    answers. Stages parse, recognition, factors, conical, canal."""
    return _analysis(text, clock, full=True)


def _analysis(text: str, clock: StageClock, *, full: bool) -> Analysis | None:
    if has_decimals(text):
        return None
    with clock.stage("parse"):
        reading = read_rational(text)
        if reading is None or (full and reading.polynomial.total_degree() > FULL_DEGREE):
            return None  # the general pipeline: not read, printed and recognised twice
        g = reading.polynomial
        printed = flint_str(g, XYZ) if reading.printed is None else reading.printed
        start = printed_skeleton(printed, int(g.total_degree()), "QQ", text=text, method="symmetry")
    clock.read(start)
    with clock.stage("recognition"):
        found = recognize_rational(g, printed, reading.multiple, reading.whole)
    if found is None or (full and found[0].is_sor):
        return None
    recognized, square = found
    clock.recognized(recognized)
    with clock.stage("factors"):
        factors = _factor_reports(reading, recognized, square)
    if factors is None:
        return None
    reports, distinct = factors
    squarefree = distinct[0]
    for h in distinct[1:]:
        squarefree *= h
    # An irreducible g's square-free part is its one factor, already printed.
    squarefree_text = reports[0].polynomial if len(distinct) == 1 else flint_str(squarefree, XYZ)
    conical = None
    if full:
        with clock.stage("conical"):
            if conical_kind(g) != "none":
                return None
            conical = Conical("none")
    with clock.stage("canal"):
        if recognized.is_sor:
            canal: Canal | None = revolution_canal(recognized.degree)
        else:
            from .canal.lines import verdict_without_smat  # a surface of revolution's answer needs no line

            canal = verdict_without_smat(g, clock.cancel)
    if canal is None:
        return None
    clock.check()
    return Analysis(
        input=text,
        field="QQ",
        method="symmetry",
        recognition=recognized,
        factors=reports,
        squarefree=squarefree_text,
        rationality=None,
        parametrizations=(),
        timings=tuple(clock.timings),
        canal=canal,
        conical=conical,
    )


def conical_kind(g: fmpq_mpoly) -> str:
    """``cylinder``, ``cone`` or ``none`` for ``g`` of degree at least 2, as
    :func:`.conical.detect.detect` decides it (docs/math.md §10), in flint: the columns of ``M``
    are the coefficient vectors of ``∇g``; a cylinder when ``M`` has rank below 3, a cone when
    ``M c = X·∇g − d·g`` has a solution."""
    gradient = [g.derivative(i) for i in range(3)]
    x, y, z = g.context().gens()
    euler = x * gradient[0] + y * gradient[1] + z * gradient[2] - g * int(g.total_degree())
    columns = [dict(zip(map(tuple, d.monoms()), d.coeffs())) for d in gradient]
    rhs = dict(zip(map(tuple, euler.monoms()), euler.coeffs()))
    monomials = sorted(set(rhs).union(*columns))
    zero = fmpq(0)
    rows = [[column.get(m, zero) for column in columns] + [rhs.get(m, zero)] for m in monomials]
    augmented = fmpq_mat(len(rows), 4, [c for row in rows for c in row])
    M = fmpq_mat(len(rows), 3, [c for row in rows for c in row[:3]])
    if M.rank() < 3:
        return "cylinder"
    return "none" if augmented.rank() == 4 else "cone"


def recognize_rational(
    g: fmpq_mpoly,
    printed: str | None = None,
    multiple: Mapping[tuple[int, ...], int] | None = None,
    whole: fmpz_mpoly | None = None,
) -> tuple[Recognition, fmpq_mpoly | None] | None:
    """The :class:`Recognition` of ``g ∈ QQ[x, y, z]`` by the symmetry method and, for a surface
    with a unique axis, its ``P²(s, w)``; ``None`` when the axis direction's ``|a|²`` reaches
    :data:`MAX_NORM`. ``printed``: ``flint_str(g)`` when the caller has it; ``multiple``: the
    integer coefficients of a multiple of ``g`` when it has them (:attr:`.expanded.Reading.multiple`),
    ``whole`` that multiple over ``ZZ`` (:attr:`.expanded.Reading.whole`)."""
    symmetry = rational_symmetry(g, multiple, whole)
    profile = square = None
    if symmetry.kind in (REVOLUTION, CYLINDER):
        point, direction = symmetry.axis_point, symmetry.axis_direction
        assert point is not None and direction is not None  # a unique axis: both are set
        if dot(direction, direction) >= MAX_NORM:
            return None
        profile, square = _profile(g, point, direction)
    return Recognition(
        polynomial=flint_str(g, XYZ) if printed is None else printed,
        degree=int(g.total_degree()),
        is_sor=symmetry.is_sor,
        symmetry=symmetry.kind,
        symmetry_dimension=symmetry.dimension,
        symmetry_basis=tuple(tuple(map(rational_str, m.a + m.b)) for m in symmetry.basis),
        axis=_axis(symmetry),
        center=_triple(symmetry.center),
        normal=_triple(symmetry.normal),
        direction=_triple(symmetry.direction),
        profile=profile,
        radius_squared=_radius_squared(g, symmetry),
    ), square


def _radius_squared(g: fmpq_mpoly, symmetry: Symmetry) -> str | None:
    """``r² = −g(c)/a`` of a sphere of degree 2 (``a`` the coefficient of ``x²``)."""
    if symmetry.kind != SPHERE or g.total_degree() != 2 or symmetry.center is None:
        return None
    return str(-g(*symmetry.center) / g[2, 0, 0])


def _factor_reports(
    reading: Reading, whole: Recognition, square: fmpq_mpoly | None
) -> tuple[tuple[Factor, ...], list[fmpq_mpoly]] | None:
    """The irreducible factors of ``g`` (``reading``'s polynomial), each recognised, and the
    distinct ones (``None`` when a factor needs sympy). An irreducible ``g`` keeps ``whole`` as
    its factor's recognition.

    A surface with a unique axis factors as its ``P²`` does (docs/math.md §4: every factor of
    ``f`` over ``QQ`` is invariant under the rotations about the axis, so a polynomial in ``s``
    and ``w``), and ``P²`` has two variables and half the degree in ``w``: when it is
    irreducible and square-free, so is ``g``, without factoring ``g`` itself; its one factor is
    then ``g``'s primitive form, which the reader may have made and printed already."""
    g = reading.polynomial
    if square is not None and irreducible(square):
        h = primitive(g) if reading.primitive is None else reading.primitive
        printed = reading.primitive_printed
        if printed is None:
            printed = whole.polynomial if h == g else flint_str(h, XYZ)  # g printed once when it is primitive
        return (Factor(printed, 1, whole),), [h]
    factors = factor(g)
    distinct = [h for h, _ in factors]
    if len(factors) == 1 and factors[0][1] == 1:
        h = factors[0][0]
        text = whole.polynomial if h == g else flint_str(h, XYZ)
        return (Factor(text, 1, whole),), distinct
    reports = []
    for h, e in factors:
        found = recognize_rational(h)
        if found is None:
            return None
        reports.append(Factor(flint_str(h, XYZ), e, found[0]))
    return tuple(reports), distinct


@overload
def _triple(v: Vector) -> Triple: ...


@overload
def _triple(v: Vector | None) -> Triple | None: ...


def _triple(v: Vector | None) -> Triple | None:
    if v is None:
        return None
    x, y, z = v
    return rational_str(x), rational_str(y), rational_str(z)


def _axis(symmetry: Symmetry) -> Axis | None:
    """The axis report: point, direction and Plücker coordinates ``(v : p × v)``."""
    if symmetry.axis_point is None:
        return None
    point, direction = symmetry.axis_point, symmetry.axis_direction
    assert direction is not None  # set with the point
    plucker = primitive_vector(tuple(direction) + cross(point, direction), RATIONALS)
    return Axis(
        point=_triple(point),
        direction=_triple(direction),
        plucker=_triple(plucker[:3]) + _triple(plucker[3:]),
    )


def _profile(g: fmpq_mpoly, point: Vector, direction: Vector) -> tuple[Profile, fmpq_mpoly]:
    """The profile in the frame ``(c, a, u)`` of :func:`.recognition.profile.axis_frame` and its
    ``P²(s, w)``; the presented ``p(x, y)`` lies over ``QQ(|a|)``.

    ``P²`` comes from a coordinate slice of ``f`` (:func:`_slice_square`, docs/math.md §3.1), and
    ``p̃(s, r) = P²(s, r²)``. The paper's exact test ``f(c + s·a + r₁·u + r₂·w) = P²(s, r₁² +
    |a|²·r₂²)`` is not computed again: the rotation about this axis satisfies (★) identically
    (checked exactly in flint by :func:`.recognition.symmetry.rational_symmetry_algebra`), so ``f``
    is constant on every circle about the axis, which is that identity (docs/math.md §3.1)."""
    c, a, u = point, direction, perpendicular(direction, RATIONALS)
    square = primitive(_slice_square(g, c, a, dot(u, u)))
    rational = square.inflate([1, 2])
    orthonormal = _orthonormal(rational, dot(a, a), dot(u, u))
    texts = {m: _surd_text(c) for m, c in orthonormal.items()}  # printed once for p and for P²
    return Profile(
        polynomial=terms_str(XY, texts.items(), _given),
        square=terms_str(XY, {(i, j // 2): t for (i, j), t in texts.items()}.items(), _given),
        rational=flint_str(rational, ("s", "r")),
        rational_square=flint_str(square, ("s", "w")),
        frame_point=_triple(c),
        frame_direction=_triple(a),
        frame_normal=_triple(u),
        even=True,
        verified=True,
    ), square


def _slice_square(g: fmpq_mpoly, c: Vector, a: Vector, norm_u: fmpq) -> fmpq_mpoly:
    """``P²(s, w)`` of ``g``, a surface of revolution about the line ``c + t·a``, in the frame
    ``(c, a, u)`` with ``|u|² = norm_u``, from ``g`` on the coordinate plane ``x_k = γ``.

    The slice has two variables where ``p̃ = g(c + s·a + r·u)`` composes all of ``g``'s terms
    (a fifth of the time at degree 20). In the slice's coordinates ``q, w`` about the axis point
    ``c' = c + τ·a`` of that plane, ``g = K(q², w)``, and ``P²(s, w) = K(n·|u|²·w −
    |a|²·a_k²·(s − τ)², |a|²·(s − τ))`` (docs/math.md §3.1). Raises :class:`AnalysisError`
    when the slice is not even in ``q``: ``g`` is then not of revolution about this axis."""
    moving = [i for i in range(3) if a[i]]
    if len(moving) > 1:  # the plane x_k = 0 meets the axis at one point, c + τ·a
        k = moving[-1]
        tau, gamma = -c[k] / a[k], fmpq(0)
    else:  # the axis runs along e_j: the plane x_k = c_k holds it
        k = (moving[0] + 1) % 3
        tau, gamma = fmpq(0), c[k]
    i, j = (m for m in range(3) if m != k)
    n = a[i] ** 2 + a[j] ** 2
    slice_ring = context(("q", "w"))
    q, w = slice_ring.gens()
    along = {i: (a[i] * w - a[j] * q) / n, j: (a[j] * w + a[i] * q) / n}
    arguments = [c[m] + tau * a[m] + along[m] if m != k else slice_ring.from_dict({}) for m in range(3)]
    slice_qw = g.subs({k: gamma}).compose(*arguments, ctx=slice_ring)
    halved = slice_qw.deflate([2, 1])
    if halved.inflate([2, 1]) != slice_qw:
        raise AnalysisError("the axis found does not pass the exact profile test (internal error)")
    s, w = context(("s", "w")).gens()
    norm_a = dot(a, a)
    return halved.compose(n * norm_u * w - norm_a * a[k] ** 2 * (s - tau) ** 2, norm_a * (s - tau))


def _orthonormal(p: fmpq_mpoly, norm_a: fmpq, norm_u: fmpq) -> dict[Monomial, Surd]:
    """``p(x, y) = p̃(x/|a|, y/|u|)`` in the canonical scale of :func:`.recognition.profile.orthonormal_profile`,
    as terms with coefficients ``q·√d`` (:data:`Surd`).

    ``y`` occurs squared only, so ``|u|`` needs no root; ``1/|a|^i = |a|^(i mod 2)/|a|²^⌈i/2⌉``
    with ``|a| = k·√d`` (``d`` square-free), so every coefficient is a rational or a rational
    times ``√d``. Scaled by the top coefficient in ``y``: when all are rational, to integers with
    content 1 and that coefficient positive; otherwise that coefficient is 1.
    """
    k, d = rational_surd(norm_a)
    s_degree, r_degree = (int(e) for e in p.degrees())
    over_a = [1 / norm_a**e for e in range((s_degree + 1) // 2 + 1)]
    over_u = [1 / norm_u**e for e in range(r_degree // 2 + 1)]
    coefficients: dict[Monomial, Surd] = {}
    for (i, j), q in terms(p):
        value = q * over_a[(i + 1) // 2] * over_u[j // 2]
        coefficients[(i, j)] = (value * k, d) if i % 2 else (value, 1)
    top_monomial = max(coefficients, key=lambda m: (m[1], m[0]))
    scaled = {m: _divide(c, coefficients[top_monomial]) for m, c in coefficients.items()}
    if all(root == 1 for _, root in scaled.values()):
        rational = primitive(context(("x", "y")).from_dict({m: q for m, (q, _) in scaled.items()}))
        if rational[top_monomial] < 0:
            rational = -rational
        return {(i, j): (q, 1) for (i, j), q in terms(rational)}
    return scaled


def _divide(c: Surd, top: Surd) -> Surd:
    """``(q·√d) / (t·√e)`` for ``d, e ∈ {1, d₀}``: a rational or a rational times ``√d₀``."""
    (q, d), (t, e) = c, top
    if e == 1:
        return q / t, d
    return (q / t, 1) if d == e else (q / (t * e), e)


def _surd_text(c: Surd) -> tuple[bool, str]:
    """The sign and the magnitude of ``q·√d`` as sympy prints it (``2*sqrt(3)/3``), from the
    numerator and denominator of ``q`` as Python integers (flint's text of ``q`` costs twice as
    much)."""
    q, d = c
    numerator, denominator = int(q.p), int(q.q)
    negative = numerator < 0
    magnitude = str(-numerator if negative else numerator)
    if d != 1:
        magnitude = f"sqrt({d})" if magnitude == "1" else f"{magnitude}*sqrt({d})"
    return negative, magnitude if denominator == 1 else f"{magnitude}/{denominator}"


def _given(text: tuple[bool, str]) -> tuple[bool, str]:
    """A coefficient already printed (:func:`_surd_text`), for :func:`.algebra.rationals.terms_str`."""
    return text
