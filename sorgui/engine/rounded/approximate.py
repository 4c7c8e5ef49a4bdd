"""Rounded input: is ``f``, up to the rounding of its printed digits, a surface of revolution?
(docs/math.md §8)

:func:`approximate_symmetry` runs the three float steps of :mod:`.near_symmetry` (singular
values of (★), the approximate Killing fields, the weighted nearest invariant polynomial with a
Gauss–Newton axis) for the kinds the small singular values allow, most symmetric first, and
accepts the first whose residual is within the rounding. For a near surface of revolution it
then snaps to the simplest exact surface (:mod:`.snapping`) and measures how far its zero set
is from ``f``'s (:mod:`.deviation`). ``is_sor`` keeps its exact meaning; this module only adds
the :class:`~sorgui.engine.results.Approximation` beside it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import numpy as np
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from ..algebra.linalg import Vector, cross, primitive_vector
from ..algebra.polys import Poly, poly_str, to_str
from ..errors import AnalysisError
from ..recognition.recognize import axis_report
from ..recognition.symmetry import (
    CYLINDER,
    EXTRUSION,
    PLANE,
    REVOLUTION,
    SOR_KINDS,
    SPHERE,
    recognize_symmetry,
)
from ..results import ApproximateAxis, Approximation, NearestSurface, Triple
from ..syntax import square_roots
from ..vocabulary import kind_noun
from . import dense
from .dense import FloatArray
from .deviation import axis_centre, max_deviation
from .directions import Quadratic, decimal_places, perpendicular, rational_sqrt, three
from .near_symmetry import (
    Candidate,
    Fit,
    Normalised,
    candidates,
    fit,
    killing_system,
    normalise,
    plain_distance,
    refine,
)
from .precision import FLOAT_FLOOR, TIE, Rounding, given_rounding, input_rounding
from .snapping import ExactSurface, snap, snap_again

MAX_SPAN = 1e100
"""Coefficients whose sizes differ by more than this are not compared in floating point."""

COARSEST = 0.1
"""A rounding read off the printed digits coarser than this (relative) says nothing about the
intended surface: decimals such as ``0.5`` or ``3.0`` (a gallery's exact numbers) are taken as
exact, and nearness is only decided with ``--tolerance``. A digit's rounding is read a hair
wide (:data:`.precision.TIE`): one digit is this coarse, not coarser."""

GATE = 1e4
"""A kind is tried when its singular values are below ``GATE·τ`` (and :data:`GATE_CAP`), ``τ`` the rounding
of the coefficients (★) reads (:func:`gradient_tolerance`) if larger than the input's: a cheap filter;
the weighted residual decides."""

GATE_CAP = 5e-2
"""The gate's cap: singular values above it are no near symmetry, whatever the rounding. A
spheroid of semi-axes 63.5 and 25.4 printed with ``%.4f`` (quadratic coefficients such as
``0.0003``, one digit) has its rotation's at 0.013, and with a cap of 10⁻² it was "not near"
(a fit about the unrefined axis, 4.3 roundings off; refined, 0.19)."""

NOISE_ALLOWANCE = 1.0
"""A fit is within the rounding when its residual is at most ``1 + min(noise, NOISE_ALLOWANCE)``:
floating point's own error in the fit (``noise``, in units of the rounding) excuses at most one
more rounding. An ill-conditioned fit (an axis far from the part) has a noise of thousands of
roundings, and ``x²+y²`` times a cubic was called near a surface of revolution 119 roundings
away, at a relative distance of 0.98."""


@dataclass(frozen=True)
class NearResult:
    """The approximation, and the exact surface it snapped to with the axis frame that keeps
    its profile simple (for the caller to analyse)."""

    approximation: Approximation
    nearest: Poly | None
    frame: tuple[Vector, Vector, Vector] | None = None


def rounding_of(f: Poly, text: str | None, tolerance: float | None) -> tuple[Rounding | None, tuple[str, ...]]:
    """The rounding in force: given by ``tolerance``, else read off the digits of ``text``
    (``None`` for exact input without a tolerance), with a note when a given tolerance is finer
    than the digits printed."""
    coefficients = dense.float_coefficients(f)
    printed = None if text is None else input_rounding(text, coefficients)
    if tolerance is None:
        return printed, _finer_than_floats(printed)
    if not (math.isfinite(tolerance) and 0.0 < tolerance < 1.0):
        raise AnalysisError(f"the tolerance must be a number between 0 and 1, not {tolerance}")
    notes: tuple[str, ...] = ()
    if printed is not None and tolerance < printed.tolerance:
        notes = (
            f"the tolerance {tolerance:.2g} is below the precision of the input's digits "
            f"({printed.tolerance:.2g} relative): a rounded surface may be missed",
        )
    return given_rounding(tolerance, coefficients), notes


FLOAT_DIGITS = 15
"""Significant digits a double holds for sure: a rounding read off more digits is floored at
:data:`~.precision.FLOAT_FLOOR` of the largest coefficient."""


def _finer_than_floats(printed: Rounding | None) -> tuple[str, ...]:
    """A note when the input prints more digits than the computation's floating point holds:
    "within the rounding" then means within its floor, not within the last digit printed."""
    if printed is None or printed.digits is None or printed.digits <= FLOAT_DIGITS:
        return ()
    return (
        f"the input prints {printed.digits} significant digits, more than floating point holds: "
        f"'within the rounding' means within {FLOAT_FLOOR:.0e} of the largest coefficient, "
        "not within the last digit printed",
    )


BALANCE_FROM = 30
"""A rounded ``f`` whose largest coefficient is beyond ``10^±30`` is analysed as ``10^k·f`` (the
same surface, its decimals shifted), its largest coefficient near 1: the squares and sums of
squares of the float computations underflowed for coefficients of ``1e-200`` and stopped the
analysis."""


def approximate_symmetry(
    f: Poly, rounding: Rounding, *, snap_exact: bool = True, notes: tuple[str, ...] = (), sphere: bool = False
) -> NearResult:
    """The :class:`Approximation` of ``f`` under ``rounding`` (docs/math.md §8), computed for
    ``10^k·f`` and its rounding ``10^k·e`` when ``f``'s coefficients are far from 1
    (:data:`BALANCE_FROM`); the nearest exact surface is then scaled back by ``10^-k``, so that
    it is compared with ``f`` as typed. Relative distances and zero sets do not depend on ``k``.
    ``sphere``: ``f`` is exactly a sphere, and its designed sphere (§8.5, "Spheres") is the
    nearest exact surface when it is another one."""
    k = _balancing_power(f)
    if not k:
        return _approximate_symmetry(f, rounding, snap_exact=snap_exact, notes=notes, sphere=sphere)
    scale, scaled = _balanced(rounding, k)
    near = _approximate_symmetry(f * scale, scaled, snap_exact=snap_exact, notes=notes, sphere=sphere)
    if near.nearest is None or near.approximation.nearest is None:
        return near
    g = near.nearest * (1 / scale)
    nearest = replace(near.approximation.nearest, polynomial=poly_str(g))
    return NearResult(replace(near.approximation, nearest=nearest), g, near.frame)


def _balancing_power(f: Poly) -> int:
    """``k`` with ``10^k·f``'s largest coefficient near 1, or 0 when it is within
    ``10^±BALANCE_FROM`` already (ordinary input is analysed as typed)."""
    largest = max((abs(c) for c in dense.float_coefficients(f).values()), default=0.0)
    if not math.isfinite(largest) or largest == 0:
        return 0
    exponent = math.floor(math.log10(largest))
    return -exponent if abs(exponent) > BALANCE_FROM else 0


def _balanced(rounding: Rounding, k: int) -> tuple[Any, Rounding]:
    """The factor ``10^k`` and the rounding of ``10^k·f`` (:data:`BALANCE_FROM`)."""
    scale = QQ(10) ** k if k > 0 else QQ(1, 10 ** (-k))
    scaled = replace(
        rounding,
        bounds={m: b * 10.0**k for m, b in rounding.bounds.items()},
        default=rounding.default * 10.0**k,
    )
    return scale, scaled


def _approximate_symmetry(
    f: Poly, rounding: Rounding, *, snap_exact: bool = True, notes: tuple[str, ...] = (), sphere: bool = False
) -> NearResult:
    """:func:`approximate_symmetry` for coefficients of ordinary size."""
    coefficients = dense.float_coefficients(f)
    sizes = [abs(c) for c in coefficients.values() if c]
    finite = all(math.isfinite(c) for c in coefficients.values()) and math.isfinite(rounding.tolerance)
    if not finite or max(sizes) > MAX_SPAN * min(sizes):
        note = (
            f"the coefficients span more than {math.log10(MAX_SPAN):.0f} orders of magnitude: beyond "
            "what floating point can compare, so nearness was not decided"
            if finite
            else "the input's numbers lie beyond the range of floating point (about 1e308): nearness was not decided"
        )
        tolerance = rounding.tolerance if math.isfinite(rounding.tolerance) else None
        return NearResult(
            Approximation(tolerance, rounding.source, False, None, None, None, (), notes=(*notes, note)), None
        )
    if rounding.source == "input" and rounding.tolerance > COARSEST * TIE:
        note = (
            f"the input's decimals have at most {rounding.digits} significant digits, a rounding of "
            f"{rounding.tolerance:.2g} (relative): too coarse to tell which surface was meant, so its numbers "
            "are taken as exact; give --tolerance to ask whether it is near a surface of revolution"
        )
        return NearResult(
            Approximation(rounding.tolerance, rounding.source, False, None, None, None, (), notes=(*notes, note)), None
        )
    normalised = normalise(coefficients, rounding)
    sigma, vectors = killing_system(normalised)
    collected = list(notes)
    accepted, best = _search(normalised, sigma, vectors, rounding.tolerance)
    near = accepted is not None and accepted.candidate.kind in SOR_KINDS
    shown = accepted or best
    exact: ExactSurface | None = None
    nearest: NearestSurface | None = None
    if near and sphere:
        assert accepted is not None  # near: an accepted fit
        exact = snap(normalised, accepted, f, rounding)
        radius = None if exact is None else _designed_radius(exact, f)
        if radius is None:
            exact = None  # the typed sphere is its own designed sphere, or none was found
        else:
            assert exact is not None and exact.point is not None  # a designed radius: a sphere about a point
            centre = ", ".join(_decimal_text(Fraction(v)) for v in exact.point)
            collected.append(
                f"exactly a sphere as typed; the sphere of radius {_decimal_text(radius)} about ({centre}), the "
                "nearest exact surface, is within the rounding too (decimals, as a CAD system designs them)"
            )
    elif near and snap_exact:
        assert accepted is not None  # near: an accepted fit
        exact = snap(normalised, accepted, f, rounding)
        nearest = None if exact is None else _nearest_surface(exact, normalised, f)
        if nearest is None or not nearest.within_rounding:
            again = snap_again(normalised, accepted, f, rounding)
            found = None if again is None else _nearest_surface(again, normalised, f)
            if found is not None and found.within_rounding:
                exact, nearest = again, found
        if exact is None:
            collected.append(
                "no exact surface with rational axis and coefficients was found within the "
                "rounding; the axis above is approximate"
            )
    if near and snap_exact and rounding.read_from is not None:  # "nearly", not an exact surface
        collected.append(
            f"the rounding is read off one number, {rounding.read_from} ({rounding.digits} significant digits), and "
            "every other number to as many digits; if they carry more (a printer that drops trailing zeros "
            "prints 58 for 58.00000), give --tolerance for the digits they were printed with"
        )
    distance = None if shown is None else plain_distance(normalised, shown.candidate)
    if accepted is None:
        collected.append(_far_note(sigma, best, rounding, distance))
    if nearest is None and exact is not None:
        nearest = _nearest_surface(exact, normalised, f)
    approximation = Approximation(
        tolerance=rounding.tolerance,
        tolerance_source=rounding.source,
        near_sor=near,
        kind=None if accepted is None else accepted.candidate.kind,
        relative_distance=distance,
        residual=None if shown is None else shown.residual,
        singular_values=tuple(float(s) for s in sigma),
        axis=_axis(accepted, normalised) if accepted is not None else None,
        center=_center(accepted, normalised) if accepted is not None else None,
        normal=_normal(accepted) if accepted is not None else None,
        nearest=nearest,
        notes=tuple(collected),
    )
    if exact is None:
        return NearResult(approximation, None)
    frame = None
    snapped = exact.direction
    if exact.point is not None and snapped is not None:
        K = exact.polynomial.ring.domain
        point, direction = _in_field(exact.point, K), _in_field(snapped, K)
        if isinstance(snapped[0], Quadratic):  # any u ⟂ a over QQ(√d): a × e_k
            k = min(range(3), key=lambda i: abs(float(snapped[i])))
            normal = cross(direction, tuple(K.one if i == k else K.zero for i in range(3)))
        else:
            normal = _in_field(perpendicular(snapped), K)
        frame = (point, direction, normal)
    return NearResult(approximation, exact.polynomial, frame)


def _decimal_text(v: Fraction) -> str:
    """A decimal ``d/10ᵏ`` as it is printed (``150.25``), exactly."""
    places = decimal_places(v) or 0
    n = int(v * 10**places)
    digits = str(abs(n)).rjust(places + 1, "0")
    return ("-" if n < 0 else "") + (f"{digits[:-places]}.{digits[-places:]}" if places else digits)


def _designed_radius(exact: ExactSurface, f: Poly) -> Fraction | None:
    """The radius of ``exact`` when it is a sphere other than ``f`` whose centre and radius are
    decimals, as a CAD system designs them (§8.5, "Spheres"), else ``None``: a sphere snapped to
    other rationals within the rounding is no simpler an answer than the typed one."""
    g = exact.polynomial
    if exact.point is None or g * f.LC == f * g.LC:
        return None
    centre = [Fraction(v) for v in exact.point]
    lam, constant = (Fraction(int(c.numerator), int(c.denominator)) for c in (g.LC, g.coeff(1)))
    squared = sum((c * c for c in centre), Fraction(0)) - constant / lam  # g = λ(|p − c|² − r²)
    radius = rational_sqrt(squared) if squared > 0 else None
    if radius is None or any(decimal_places(v) is None for v in (*centre, radius)):
        return None
    return radius


def _in_field(vector: Sequence[Fraction | Quadratic], K: Domain) -> Vector:
    """Snapped coordinates (rationals, or ``a + b√d``) as elements of ``K``."""
    out = []
    for v in vector:
        if isinstance(v, Quadratic):
            a, b = (K.convert(QQ(q.numerator, q.denominator)) for q in (v.a, v.b))
            out.append(a + b * square_roots(K, (v.d,))[v.d])
        else:
            out.append(K.convert(QQ(v.numerator, v.denominator)))
    return tuple(out)


def _search(f: Normalised, sigma: FloatArray, vectors: FloatArray, tolerance: float) -> tuple[Fit | None, Fit | None]:
    """The first kind (most symmetric first) whose refined fit is within the rounding, and the
    best fit seen (for saying how far a miss is)."""
    gate = min(GATE_CAP, GATE * max(tolerance, gradient_tolerance(f)))
    best: Fit | None = None
    for count in (3, 2, 1):
        if sigma[6 - count] > gate and not (count == 1 and best is None):
            continue
        for candidate in _starts(vectors, count, sigma, gate):
            result = refine(f, candidate) if sigma[6 - count] <= gate else fit(f, candidate)
            if best is None or result.residual < best.residual:
                best = result
            if result.residual <= 1.0 + min(result.noise, NOISE_ALLOWANCE):
                return result, best
    return None, best


def gradient_tolerance(f: Normalised) -> float:
    """The relative rounding of the coefficients that (★) reads: all but the constant term,
    which no derivative sees. A large constant (a part far from the origin, printed with a fixed
    number of places) makes the input's tolerance far smaller than the rounding of ``∇f``, and
    a cylinder printed with ``%.6f`` about a point 10 units away had the singular value of its
    second symmetry over a gate drawn from the constant's digits."""
    varying = f.array[f.selected][1:], f.bounds[f.selected][1:]
    size = float(np.linalg.norm(varying[0]))
    return float(np.linalg.norm(varying[1])) / size if size > 0.0 else math.inf


def _starts(vectors: FloatArray, count: int, sigma: FloatArray, gate: float) -> list[Candidate]:
    """The candidates of ``count`` symmetries to refine. One rotation, when the two smallest
    singular values are both small (a near-sphere: any two rotations nearly keep ``f``), is
    started from four directions of the plane of their vectors: the singular vectors of a
    degenerate pair are any orthonormal basis of it, and Gauss–Newton does not leave a saddle
    between two axes (``x² + 1.000001y² + 0.999999z²`` is near a surface about y and about z)."""
    if count != 1 or sigma[-2] > gate:
        return candidates(vectors, count)
    first, second = vectors[-1], vectors[-2]
    turns = [k * math.pi / 4 for k in range(4)]
    return [c for t in turns for c in candidates(np.array([math.cos(t) * first + math.sin(t) * second]), 1)]


def _far_note(sigma: FloatArray, best: Fit | None, rounding: Rounding, distance: float | None) -> str:
    smallest = f"the smallest singular value of (★) is {sigma[-1]:.2g} against a tolerance of {rounding.tolerance:.2g}"
    if best is None:
        return f"not near any continuous symmetry: {smallest}"
    kind = kind_noun(best.candidate.kind)
    weighed = ""
    if distance is not None and distance <= rounding.tolerance:  # near overall, far for a coefficient's own rounding
        weighed = (
            " of the coefficients it changes, each weighed by its own rounding (the relative distance weighs all alike)"
        )
    return (
        f"not within the rounding of {kind}: the nearest one about the best axis is "
        f"{distance:.2g} away (relative), {best.residual:.3g} times the rounding{weighed}; {smallest}"
    )


def _axis(result: Fit, f: Normalised) -> ApproximateAxis | None:
    c = result.candidate
    if c.kind not in (REVOLUTION, CYLINDER):
        return None
    assert c.direction is not None and c.point is not None  # an axis: direction and point
    direction = c.direction / np.linalg.norm(c.direction)
    point = c.point * f.length
    point = point - (point @ direction) * direction
    return ApproximateAxis(three(float(v) for v in point), three(float(v) for v in direction))


def _center(result: Fit, f: Normalised) -> tuple[float, float, float] | None:
    c = result.candidate
    if c.kind != SPHERE:
        return None
    assert c.point is not None  # a sphere's candidate has its centre
    return three(float(v) * f.length for v in c.point)


def _normal(result: Fit) -> tuple[float, float, float] | None:
    c = result.candidate
    if c.kind not in (PLANE, EXTRUSION):
        return None
    assert c.direction is not None  # a plane's normal, an extrusion's direction
    return three(float(v) for v in c.direction / np.linalg.norm(c.direction))


FAR_ZERO_SET = 0.05
"""A snapped surface whose zero set lies farther than this from ``f``'s (in the units of the
normalised ``f``, whose points are of size 1) is not within the rounding, whatever its
coefficients: a paraboloid printed with fixed decimals had coefficients within the rounding of
an ellipsoid centred 6·10⁸ away, 2.6·10⁴ from it where that ellipsoid is drawn."""


def _nearest_surface(exact: ExactSurface, f: Normalised, original: Poly) -> NearestSurface:
    """The report of the snapped surface, with the deviation of its zero set from ``f``'s; within
    the rounding when its coefficients are and its zero set is not :data:`FAR_ZERO_SET` away."""
    sym = exact.symmetry
    K = exact.polynomial.ring.domain

    def triple(v: Vector | None) -> Triple | None:
        return None if v is None else three(to_str(K, c) for c in v)

    def floats(v: Vector) -> FloatArray:  # QQ or QQ(√d)
        return np.array([float(K.to_sympy(c)) for c in v])

    g = dense.scaled(dense.from_terms(dense.float_coefficients(exact.polynomial), f.degree), f.length) / f.scale
    axis = None
    center = np.zeros(3)
    direction = None
    if sym.axis_point is not None:
        assert sym.axis_direction is not None  # a unique axis has a point and a direction
        if exact.point is not None and exact.direction is not None:
            axis = axis_report(_in_field(exact.point, K), primitive_vector(sym.axis_direction, K), K)
        else:
            axis = axis_report(sym.axis_point, sym.axis_direction, K)
        center = floats(sym.axis_point) / f.length
        direction = floats(sym.axis_direction)
    elif sym.center is not None:
        center = floats(sym.center) / f.length
    deviation = max_deviation(f.array, g, center, direction)
    if deviation is None and direction is not None:  # the part may be small and far from that point
        deviation = max_deviation(f.array, g, axis_centre(g, center, direction), direction)
    near_zero_set = deviation is None or deviation <= FAR_ZERO_SET
    return NearestSurface(
        polynomial=poly_str(exact.polynomial),
        kind=sym.kind,
        axis=axis,
        center=triple(sym.center),
        normal=triple(sym.normal),
        relative_distance=exact.relative_distance,
        max_deviation=None if deviation is None else deviation * f.length,
        within_rounding=exact.largest <= 1.0 and near_zero_set,
        largest_residual=exact.largest,
    )


def nearest_figures(f: Poly, g: Poly, rounding: Rounding) -> NearestSurface:
    """The report of ``g`` as the nearest exact surface of the rounded ``f`` under ``rounding``,
    its figures (the largest residual in units of the rounding, the relative distance, the
    deviation of the zero sets, within the rounding or not) computed again as the analysis
    computes them (:func:`.snapping.check_surface`, :func:`_nearest_surface`): a saved report's
    claims about its nearest surface are checked against these (docs/math.md §14).

    ``f`` and ``g`` are balanced as :func:`approximate_symmetry` balances them. The difference
    is exact when both are over ``QQ``, else taken in floats, as the analysis takes it."""
    k = _balancing_power(f)
    if k:
        scale, rounding = _balanced(rounding, k)
        f, g = f * scale, g * scale
    coefficients = dense.float_coefficients(f)
    if g.ring == f.ring:
        difference = dense.float_coefficients(f - g)
    else:
        others = dense.float_coefficients(g)
        difference = {m: coefficients.get(m, 0.0) - others.get(m, 0.0) for m in set(coefficients) | set(others)}
    ratios = [abs(r) / rounding.bound(m) for m, r in difference.items()]
    residual = math.sqrt(sum(v * v for v in ratios) / math.comb(rounding.degree + 3, 3))
    distance = math.hypot(*difference.values()) / math.hypot(*coefficients.values())
    symmetry = recognize_symmetry(g)
    exact = ExactSurface(g, symmetry, residual, max(ratios, default=0.0), distance, None, None)
    return _nearest_surface(exact, normalise(coefficients, rounding), f)
