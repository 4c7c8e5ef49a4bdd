"""The coefficients of the nearest exact surface (docs/math.md §8.5, "The nearest exact surface"):
the exact values of the coefficients ``q_ij`` of ``g = Σ q_ij h^i ρ^j`` on one exact axis,
simplest first, and the factor that puts a set of them within the input's rounding.

* **Snapped:** each the simplest rational within three standard errors of the weighted
  least-squares fit, as it is and in unit heights along the axis; or the ratios to the
  best-determined one, times a scale (snapped, or one that makes ``g`` agree with ``f`` where
  ``f`` is largest).
* **Held:** the coefficients that snap to 0 held there (and a paraboloid's ratio of its terms
  ``h²`` and ``ρ``), and the other ratios snapped one at a time, each within the errors of the
  fit with the ratios snapped so far held.
* **As fitted.**
* **A torus's constant** derived from its other coefficients, and **the factor** of fewest bits
  with every coefficient of ``λ·g`` within the rounding: ``g`` and ``λ·g`` are one surface, and
  candidates are ranked by the bits of their primitive integer vector.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np
from flint import fmpq, fmpq_mpoly
from sympy.polys.domains import QQ

from . import dense
from .dense import FloatArray
from .directions import Direction, decimal_places, direction_parts, simplest_between, simplest_near
from .near_symmetry import Fit, Normalised, invariant_basis
from .precision import Rounding

if TYPE_CHECKING:
    from ..algebra.polys import Poly


@dataclass(frozen=True)
class Typed:
    """The typed polynomial over ``QQ`` in the forms the candidates are compared with: flint's,
    and its terms as floats (computed once per snap, not once per candidate)."""

    flint: fmpq_mpoly
    floats: dict[dense.Monomial, float]


WITHIN = 1.0 - 1e-13
"""The share of each coefficient's rounding a rescaled surface is fitted within: the residual
is measured in floats, a hair from where the exact interval ends."""

SNAPPED, HELD, FITTED = "snapped", "held", "fitted"
"""Where a set of coefficients comes from (:func:`coefficient_candidates`): snapped from the
free fit; snapped one ratio at a time from fits with some coefficients held
(:func:`_held_candidates`), within the rounding by construction, so a weak sign, tried after
every simpler set on every axis; as fitted."""
HELD_SPREADS = (3.0, 1.0, 0.3, 0.1)
"""Radii, in standard errors, within which the ratios of a fit with coefficients held are
snapped one at a time (widest first, until the set is within the rounding)."""


def coefficient_candidates(
    f: Normalised,
    local: Fit,
    matched_for: Callable[[list[Fraction]], list[Fraction]],
    norm2: Fraction | None,
    within_for: Callable[[list[Fraction]], Fraction | None],
) -> list[tuple[list[Fraction], str]]:
    """Exact coefficients of ``g`` in the original coordinates for the fit ``local``, simplest
    first (the fewest bits up to a common factor, :func:`shape_bits`; one of each shape), each
    with where it comes from (:data:`SNAPPED`, :data:`HELD`, :data:`FITTED`): each snapped on
    its own, as it is and in unit heights along the axis (:func:`_in_unit_heights`); the ratios
    to the best-determined one snapped, times that coefficient snapped and times the scales
    ``matched_for`` gives them (:func:`matched_scales` on the axis); as fitted; snapped one
    ratio at a time with the coefficients that snap to 0 held there, times the factor
    ``within_for`` gives them (:func:`within_scale`; :func:`_held_candidates`); the first
    without the terms a torus has not (:func:`_torus_shaped`); and each of these made a torus
    when it has a torus's terms (:func:`torus_completion`, ``norm2`` the squared length ``|a|²``
    of the axis direction, when rational)."""
    degrees = np.array([i + 2 * j for i, j in local.exponents])
    factor = f.scale / f.length**degrees
    values = local.coefficients * factor
    errors = standard_errors(f, local) * factor * 3.0 * max(1.0, local.residual)
    found = [[simplest_near(v, e) for v, e in zip(values, errors)]]
    if norm2 is not None and norm2 != 1:
        found.append(_in_unit_heights(local.exponents, values, errors, norm2))
    found += _ratio_candidates(values, errors, matched_for)
    shaped = None if norm2 is None else _torus_shaped(local.exponents, found[0])
    if shaped is not None:
        found.append(shaped)
    sources = [(candidate, SNAPPED) for candidate in found]
    sources.append(([Fraction(v).limit_denominator(10**15) for v in values], FITTED))
    held: dict[int, Fraction] = {k: q for k, q in enumerate(found[0]) if not q}
    pivot = None
    paraboloid = _paraboloid(local.exponents, values, errors, norm2)
    if paraboloid is not None:
        pivot, k, ratio = paraboloid
        held[k] = ratio
    if held and len(held) < len(values) - 1:
        sources += [
            (candidate, HELD) for candidate in _held_candidates(f, local, held, pivot, factor, within_for, norm2)
        ]
    ranked: list[tuple[int, list[Fraction], str]] = []
    for candidate, source in sources:
        ranked.append((shape_bits(candidate), candidate, source))
        torus = None if norm2 is None else torus_completion(local.exponents, candidate, norm2)
        if torus is not None:
            ranked.append((shape_bits(torus[1:]), torus, source))
    distinct: list[tuple[list[Fraction], str]] = []
    shapes: set[tuple[int, ...]] = set()
    for _, candidate, source in sorted(ranked, key=lambda item: item[0]):
        shape = primitive_shape(candidate)
        if shape not in shapes:  # the same surface scaled: its scale is found when it is checked
            shapes.add(shape)
            distinct.append((candidate, source))
    return distinct


def _torus_shaped(exponents: tuple[tuple[int, int], ...], snapped: list[Fraction]) -> list[Fraction] | None:
    """``snapped`` with the terms other than a torus's (:data:`TORUS_TERMS`) set to 0, when it
    has a torus's terms and others that are not 0 (``None`` otherwise). On an axis snapped near
    an irrational one (a CAD torus turned by a random rotation, 6 digits), the centre's small
    slip along the axis gave ``h`` a coefficient of 0.46 ± 0.1, snapped to 1/2: no torus was
    tried, and the nearest surface was a quartic of genus 1 (Table 1, row 4)."""
    terms = dict(zip(exponents, snapped))
    if exponents[:1] != ((0, 0),) or not all(terms.get(m) for m in TORUS_TERMS[1:]):
        return None
    if not any(q for m, q in terms.items() if m not in TORUS_TERMS):
        return None
    return [q if m in TORUS_TERMS else Fraction(0) for m, q in zip(exponents, snapped)]


def _in_unit_heights(
    exponents: tuple[tuple[int, int], ...], values: FloatArray, errors: FloatArray, norm2: Fraction
) -> list[Fraction]:
    """Each coefficient snapped on its own in unit heights along the axis: ``q_ij h^i`` is
    ``(q_ij |a|^i)(h/|a|)^i``, and for an even ``i`` the designed value is ``q_ij |a|^i``, rational
    (a torus's ``4R²`` in ``q₂₀ = 4R²/|a|²``: ``4096/111588530``, not the simplest rational
    ``3/81730`` near it). An odd ``i`` has an irrational ``|a|^i`` and is snapped as it is."""
    snapped = []
    for (i, _), v, e in zip(exponents, values, errors):
        unit = norm2 ** (i // 2) if i % 2 == 0 else Fraction(1)
        snapped.append(simplest_near(v * float(unit), e * float(unit)) / unit)
    return snapped


def _ratio_candidates(
    values: FloatArray, errors: FloatArray, matched_for: Callable[[list[Fraction]], list[Fraction]]
) -> list[list[Fraction]]:
    """The ratios of ``values`` to the best-determined one, each snapped within its errors,
    times that value snapped and times the scales ``matched_for`` gives them."""
    pivot = int(np.argmax(np.abs(values) / np.maximum(errors, 1e-300)))
    if values[pivot] == 0.0:
        return []
    ratios = values / values[pivot]
    ratio_errors = errors / abs(values[pivot]) + np.abs(ratios) * errors[pivot] / abs(values[pivot])
    snapped = [simplest_near(r, e) for r, e in zip(ratios, ratio_errors)]
    scale = simplest_near(values[pivot], errors[pivot])
    return [[scale * r for r in snapped]] + [[matched * r for r in snapped] for matched in matched_for(snapped)]


def _held_candidates(
    f: Normalised,
    local: Fit,
    held: dict[int, Fraction],
    start: int | None,
    factor: FloatArray,
    within_for: Callable[[list[Fraction]], Fraction | None],
    norm2: Fraction | None,
) -> list[list[Fraction]]:
    """Coefficients within the rounding for a fit whose structure is known: ``held`` gives the
    ratios of some coefficients to the one at ``start`` (to the best-determined of the others
    when ``start`` is ``None``): those that snap to 0 on their own (a cone's apex at the
    profile's centre makes the terms ``1`` and ``h`` vanish, a torus's centre the odd powers of
    ``h``) and a paraboloid's ``q₂₀ = −q₀₁/|a|²`` (:func:`_paraboloid`). The others, each
    snapped within three standard errors of the free fit, can miss the rounding together
    (docs/math.md §8.5). With those held, the other ratios are snapped one at a time, the
    best-determined first, each within ``k`` standard errors of the fit with every ratio
    snapped so far held (each held ratio sharpens the rest), for ``k`` in
    :data:`HELD_SPREADS`; the set, or its torus completion (:func:`torus_completion`, whose
    constant is derived, not snapped), is kept with the simplest scale that puts every
    coefficient within the rounding. ``factor`` turns the normalised fit's coefficients into
    those of ``f``'s coordinates."""
    basis = invariant_basis(local.candidate, f.degree, f.selected)[0] * f.weights[:, None]
    target = f.vector * f.weights
    for spread in HELD_SPREADS:
        ratios = dict(held)
        pivot = start
        while True:
            fitted = _ratio_fit(basis, target, ratios, pivot, factor)
            if fitted is None:
                return []
            pivot, values, errors = fitted
            free = [k for k in range(len(values)) if k != pivot and k not in ratios]
            if not free:
                break
            relative = errors / np.maximum(np.maximum(np.abs(values), errors), 1e-300)
            k = free[int(np.argmin(relative[free]))]
            ratios[k] = simplest_near(values[k], spread * errors[k])
        ratios[pivot] = Fraction(1)
        snapped = [ratios[k] for k in range(len(values))]
        torus = None if norm2 is None else torus_completion(local.exponents, snapped, norm2)
        for candidate in (snapped, torus) if torus is not None else (snapped,):
            scale = within_for(candidate)
            if scale is not None:
                return [[scale * r for r in candidate]]
    return []


def _paraboloid(
    exponents: tuple[tuple[int, int], ...], values: FloatArray, errors: FloatArray, norm2: Fraction | None
) -> tuple[int, int, Fraction] | None:
    """For a quadric about an axis of rational ``|a|²`` whose fitted coefficients (``errors``
    the radii they are snapped within) are a paraboloid's, ``q₂₀|a|² + q₀₁ = 0`` (no term in
    the squared distance along the axis, ``ρ − h²/|a|²`` the squared distance to it): the
    index of ``q₀₁``, that of ``q₂₀`` and the ratio ``−1/|a|²`` of the two."""
    if norm2 is None or max(i + 2 * j for i, j in exponents) != 2 or (2, 0) not in exponents or (0, 1) not in exponents:
        return None
    h2, rho = exponents.index((2, 0)), exponents.index((0, 1))
    along = values[h2] * float(norm2) + values[rho]
    if not values[rho] or abs(along) > errors[h2] * float(norm2) + errors[rho]:
        return None
    return rho, h2, -1 / norm2


def _ratio_fit(
    basis: FloatArray, target: FloatArray, ratios: dict[int, Fraction], pivot: int | None, factor: FloatArray
) -> tuple[int, FloatArray, FloatArray] | None:
    """The least-squares fit of ``target`` (``f``, weighted) on the weighted local invariant
    ``basis`` with the coefficients at ``ratios`` held at those multiples of the one at
    ``pivot`` (the best-determined of the others when ``pivot`` is ``None``): the pivot, every
    coefficient's ratio to it in ``f``'s coordinates and the standard errors of the ratios (to
    first order, from the covariance of the fit). ``None`` when the fit is degenerate."""
    count = basis.shape[1]
    if pivot is None:
        free = [k for k in range(count) if k not in ratios]
        solved = _least_squares(basis[:, free], target)
        if solved is None:
            return None
        values, covariance = solved
        pivot = free[int(np.argmax(np.abs(values) / np.sqrt(np.maximum(np.diag(covariance), 1e-300))))]
    free = [k for k in range(count) if k != pivot and k not in ratios]
    held = basis[:, pivot].copy()
    for k, r in ratios.items():
        held += float(r) * factor[pivot] / factor[k] * basis[:, k]
    solved = _least_squares(np.column_stack([held, *(basis[:, k] for k in free)]), target)
    if solved is None or solved[0][0] == 0.0:
        return None
    solution, covariance = solved
    c = solution[0]
    values, errors = np.ones(count), np.zeros(count)
    for k, r in ratios.items():
        values[k] = float(r)
    for column, k in enumerate(free, start=1):
        scale = factor[k] / (factor[pivot] * c)
        values[k] = solution[column] * scale
        gradient = np.zeros(len(solution))  # of the ratio c_k·scale in (c, c_k): to first order
        gradient[column], gradient[0] = scale, -values[k] / c
        errors[k] = math.sqrt(max(float(gradient @ covariance @ gradient), 0.0))
    return pivot, values, errors


def _least_squares(columns: FloatArray, target: FloatArray) -> tuple[FloatArray, FloatArray] | None:
    """The least-squares solution of ``columns · c ≈ target`` (columns scaled to unit length
    for the solve) and the covariance of ``c`` for unit errors in ``target`` (the weighted
    system of §8.3, whose errors are in units of the rounding); ``None`` when the columns are
    dependent."""
    norms = np.linalg.norm(columns, axis=0)
    if not norms.all():
        return None
    u, s, vt = np.linalg.svd(columns / norms, full_matrices=False)
    if s[-1] <= s[0] * 1e-13:
        return None
    solution: FloatArray = (vt.T @ ((u.T @ target) / s)) / norms
    covariance: FloatArray = ((vt.T / s**2) @ vt) / np.outer(norms, norms)
    return solution, covariance


TORUS_TERMS = ((0, 0), (2, 0), (0, 1), (0, 2))
"""The terms ``h^i ρ^j`` of a torus about its centre: ``(ρ + k)² − 4R²(ρ − h²/|a|²)``."""


def torus_completion(
    exponents: tuple[tuple[int, int], ...], coefficients: list[Fraction], norm2: Fraction
) -> list[Fraction] | None:
    """The coefficients with the constant that makes ``g`` a torus (or a cyclide of that form),
    when ``g`` has the terms of one (docs/math.md §8.5): ``q₀₀ = (q₀₁ + q₂₀·|a|²)² / (4 q₀₂)``.
    Every term is snapped on its own, and a CAD torus's constant ``(R² − r²)²`` lies within the
    rounding of simpler numbers that are not a torus (P of genus 1 instead of two circles);
    derived, it costs no bits. ``None`` unless the first term is the constant and the
    others present are exactly the torus's."""
    terms = dict(zip(exponents, coefficients))
    if exponents[:1] != ((0, 0),) or any(q for m, q in terms.items() if m not in TORUS_TERMS):
        return None
    q20, q01, q02 = (terms.get(m, Fraction(0)) for m in TORUS_TERMS[1:])
    if not q02 or not q20:
        return None
    return [(q01 + q20 * norm2) ** 2 / (4 * q02), *coefficients[1:]]


def matched_scales(g: fmpq_mpoly, typed: Typed, rounding: Rounding) -> list[Fraction]:
    """Scales ``λ`` that make ``λ·g`` agree with ``f`` where ``f`` is largest: at each of the
    three largest coefficients of ``f``, the simplest rational within its rounding divided by
    ``g``'s coefficient there (a CAD system that divides by its largest coefficient prints an
    exact ``1.000000000``)."""
    g_terms = dict(zip(map(dense.monomial, g.monoms()), g.coeffs()))
    f_terms = typed.floats
    shared = sorted((m for m in f_terms if m in g_terms), key=lambda m: -abs(f_terms[m]))
    scales: list[Fraction] = []
    for m in shared[:3]:
        value = simplest_near(f_terms[m], rounding.bound(m))
        scale = value / Fraction(int(g_terms[m].p), int(g_terms[m].q))
        if scale and scale not in scales:
            scales.append(scale)
    return scales


def within_scale(g: fmpq_mpoly | Poly, typed: Typed, rounding: Rounding) -> Fraction | None:
    """The factor ``μ`` that makes ``μ·g`` the monic form of ``g`` times the simplest ``λ``
    (the fewest bits, a decimal when one is simplest) with every coefficient within its
    rounding of ``f``'s, or ``None`` when there is no such ``λ`` (docs/math.md §8.5). ``f`` may be
    a simple surface times a printed factor (``0.94515``), and the scale snapped from one
    coefficient of the fit (the simplest rational within its standard errors, ``1189/1258``)
    misses the rounding of ``f``'s largest coefficients by a millionth. Over ``QQ(√d)`` (an axis
    in a quadratic field) ``g`` is made monic at its first rational coefficient, so that ``μ`` is
    rational, and the others are taken to 30 digits."""
    terms = _exact_terms(g)
    first = next((value for _, value, rational in terms if rational), None)
    if first is None:
        return None
    lo: Fraction | None = None
    hi: Fraction | None = None
    for m, n in ((m, value / first) for m, value, _ in terms):
        value, bound = Fraction(typed.floats.get(m, 0.0)), Fraction(rounding.bound(m) * WITHIN)
        low, high = sorted(((value - bound) / n, (value + bound) / n))
        lo = low if lo is None else max(lo, low)
        hi = high if hi is None else min(hi, high)
        if lo > hi:
            return None
    if lo is None or hi is None or lo <= 0 <= hi:
        return None
    return min((simplest_between(lo, hi), _shortest_decimal(lo, hi)), key=lambda v: bits([v])) / first


def scaled_surface(g: fmpq_mpoly | Poly, factor: Fraction) -> fmpq_mpoly | Poly:
    """``factor·g``, over ``QQ`` or ``QQ(√d)``."""
    if isinstance(g, fmpq_mpoly):
        return g * fmpq(factor.numerator, factor.denominator)
    K = g.ring.domain
    return g * K.convert(QQ(factor.numerator, factor.denominator))


def _exact_terms(g: fmpq_mpoly | Poly) -> list[tuple[dense.Monomial, Fraction, bool]]:
    """The terms of ``g`` with their coefficients as rationals and whether they are exact: over
    ``QQ(√d)`` (whose elements are ``b·√d + a``, the list ``[b, a]``) an irrational one is taken
    to 30 digits."""
    if isinstance(g, fmpq_mpoly):
        return [(dense.monomial(m), Fraction(int(c.p), int(c.q)), True) for m, c in zip(g.monoms(), g.coeffs())]
    K = g.ring.domain
    d = int(-K.mod.to_list()[-1])
    root = Fraction(math.isqrt(d * 10**60), 10**30)
    terms = []
    for m, c in g.items():
        parts = [Fraction(int(v.numerator), int(v.denominator)) for v in c.to_list()]
        b, a = ([Fraction(0)] * (2 - len(parts)) + parts)[-2:]
        terms.append((dense.monomial(m), a + b * root, b == 0))
    return terms


def _shortest_decimal(lo: Fraction, hi: Fraction) -> Fraction:
    """The decimal with the fewest digits in ``[lo, hi]`` (``0 < lo`` or ``hi < 0``): a printed
    factor reads as one (``0.9451502``, not ``606759779/641971867``)."""
    if hi < 0:
        return -_shortest_decimal(-hi, -lo)
    power = 10 ** max(0, -math.floor(math.log10(hi - lo)))
    while True:
        n = math.ceil(lo * power)
        if n <= hi * power:
            return Fraction(n, power)
        power *= 10


def bits(values: list[Fraction]) -> int:
    return sum(v.numerator.bit_length() + v.denominator.bit_length() for v in values)


def direction_bits(a: Direction, c: Sequence[Fraction]) -> int:
    """The bits of the axis through ``c`` along ``a``: :func:`axis_bits` on a rational direction,
    else those of the point and of both parts of each coordinate of a quadratic one."""
    rational = [v for v in a if isinstance(v, Fraction)]
    return axis_bits(rational, c) if len(rational) == len(a) else bits([*c, *direction_parts(a)])


def axis_bits(a: Sequence[Fraction], c: Sequence[Fraction]) -> int:
    """The bits of the axis along ``a`` through ``c``: of ``a``, and of ``|a|²·c`` counted as a
    CAD system's numbers (:func:`decimal_bits`). For the foot of the origin, ``|a|²·c = |a|²·c₀
    − (a·c₀)·a`` holds the designer's decimals of a designed point ``c₀`` (docs/math.md §8.5); a
    centre or an apex is counted alike. Counted on ``c`` by :func:`bits`, the foot ``(4753/2250,
    …)`` of the axis along ``(11, 10, 2)`` through ``(3.1, −2.4, 5.05)`` cost more than a point
    ``(526/249, …)`` a ten-thousandth off that axis, also within a 6-digit rounding, which was
    the answer."""
    primitive = primitive_shape(list(a))  # |a|² of the direction's own integers, whatever its length
    norm2 = sum(v * v for v in primitive)
    return sum(decimal_bits(norm2 * v) for v in c) + bits(list(a))


def decimal_bits(v: Fraction) -> int:
    """The bits of ``v`` as a CAD system prints it: a decimal ``d/10ᵏ`` costs the bits of its
    digits ``d`` and of ``k`` (``4.964``: 13 + 2, against 18 for ``690/139`` beside it), or its
    :func:`bits` when fewer (``1/8``); any other rational its :func:`bits`."""
    places = decimal_places(v)
    if places is None:
        return bits([v])
    digits: int = abs(v.numerator) * 10**places // v.denominator
    return min(bits([v]), digits.bit_length() + places.bit_length())


def primitive_shape(values: list[Fraction]) -> tuple[int, ...]:
    """The primitive integer vector proportional to ``values`` (its first non-zero entry
    positive): the coefficients of one surface ``g = 0`` up to the factor of ``g``."""
    common = math.lcm(*(v.denominator for v in values))
    integers = [v.numerator * (common // v.denominator) for v in values]
    content = math.gcd(*integers) or 1
    sign = -1 if next((n for n in integers if n), 0) < 0 else 1
    return tuple(sign * n // content for n in integers)


def shape_bits(values: list[Fraction]) -> int:
    """The bits of the surface's coefficients up to a factor, those of :func:`_shape`: ``g`` and
    ``0.94515·g`` are one surface, as simple as each other (docs/math.md §8.5)."""
    return sum(n.bit_length() + 1 for n in primitive_shape(values))


def standard_errors(f: Normalised, local: Fit) -> FloatArray:
    """Standard errors of the fitted coefficients, in units of the rounding bounds."""
    weighted = invariant_basis(local.candidate, f.degree, f.selected)[0] * f.weights[:, None]
    norms = np.linalg.norm(weighted, axis=0)
    norms[norms == 0.0] = 1.0
    _, s, vt = np.linalg.svd(weighted / norms, full_matrices=False)
    s = np.maximum(s, s[0] * 1e-15)
    covariance = (vt.T / s**2) @ vt
    errors: FloatArray = np.sqrt(np.abs(np.diag(covariance))) / norms
    return errors
