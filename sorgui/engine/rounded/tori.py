"""The nearest exact torus of a rounded quartic of revolution (docs/math.md §8.5, "Tori").

A torus is fixed by its centre ``C``, its axis direction ``a`` and its radii ``R`` (of the
circle of centres) and ``r`` (of the tube). With ``q = p − C``, ``ρ = |q|²``, ``h = a·q``,
``k = R² − r²`` and ``S = 4R²``:

    g = (ρ + k)² − S·(ρ − h²/|a|²) = ρ² + (2k − S)·ρ + (S/|a|²)·h² + k²,

rational when ``C``, ``a``, ``R²`` and ``r²`` are. The profile's snapping (:mod:`.snapping`)
fits the coefficients of ``g`` on one exact axis; a CAD torus on a turned axis has an
irrational direction, and on a rational one near it the fit's radii slip by a few of their
standard errors (a 6-digit torus of ``R = 32``, ``r = 8`` in mm had ``4R²`` at
``4095.990 ± 0.003``): no torus was tried within the rounding. Here the radii are found from
every coefficient with the centre held, snapped, and the axis fitted again for them:

1. the centre is the profile's, snapped as a cone's apex is (:func:`.cones.snapped_points`);
2. with the centre held, ``f ≈ λρ² + qᵀMq + c₀`` is linear in ``λ``, the six entries of ``M``
   and ``c₀``: a weighted least-squares fit over every coefficient (weights: the rounding);
3. ``M/λ = (2k − S)·I + S·ââᵀ``: the odd eigenvalue is ``2k``, the pair ``2k − S``; ``R`` and
   ``r`` are snapped to decimals (coarsest first), and with them held ``(λ, â)`` are fitted
   again (:func:`.cones.refit_direction`); ``â`` is snapped in each family of directions, a
   quadratic field's first (:func:`.cones.first_shapes`);
4. ``g`` is scaled by the simplest factor that puts every coefficient within the rounding and
   checked exactly, as a cone is (:func:`.cones.first_direction`).

The simplest torus that passes, by the bits of its coefficients, centre and axis, is the answer.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np

from .cones import (
    Build,
    Check,
    Model,
    S,
    Shape,
    Tries,
    form_design,
    form_entries,
    nearest_about,
    refit_direction,
    snapped_points,
)
from .dense import FloatArray, Monomial
from .directions import angles_of, decimal_near, unit_at
from .near_symmetry import lawson
from .precision import Rounding

if TYPE_CHECKING:
    from .coefficients import Typed
    from .near_symmetry import Normalised

RADIUS_RADII = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
"""Radii, relative to each of the torus's radii, within which it is snapped to the decimal of
fewest places, coarsest first."""


def nearest_torus(
    f: Normalised,
    typed: Typed,
    rounding: Rounding,
    centre: FloatArray,
    build: Build,
    check: Check[S],
) -> tuple[list[Fraction], S] | None:
    """The simplest torus with every coefficient within the rounding of the quartic ``f`` (its
    ``q_ij`` on :data:`.coefficients.TORUS_TERMS`, and the surface), or ``None``. ``centre`` is
    the profile's centre in ``f``'s coordinates. ``build`` makes ``g`` and ``check`` checks it
    against the typed surface (:func:`.snapping.check_surface`)."""
    if f.degree != 4 or not np.all(np.isfinite(centre)):
        return None
    monomials = [(i, j, d - i - j) for d in range(5) for i in range(d + 1) for j in range(d - i + 1)]
    weights = np.array([1.0 / rounding.bound(m) for m in monomials])
    target = np.array([typed.floats.get(m, 0.0) for m in monomials]) * weights
    scale = max(float(np.linalg.norm(centre)), f.length)

    def tries(design: FloatArray, solution: FloatArray) -> Tries | None:
        shape = _shape(solution)
        if shape is None:
            return None
        lam, R, r, unit = shape
        radii = dict.fromkeys((decimal_near(R, e * R), decimal_near(r, e * r)) for e in RADIUS_RADII)
        shapes = [
            Shape(pair, _torus_coefficients(*_shape_of(pair)), _torus_model(*map(float, _shape_of(pair))))
            for pair in radii
            if all(pair)
        ]
        return shapes, _largest_smallest(design, target, lam, unit)

    def design_at(C: FloatArray) -> FloatArray:
        design: FloatArray = _design(monomials, C) * weights[:, None]
        return design

    return nearest_about(snapped_points(centre, scale), design_at, target, tries, typed, rounding, build, check)


def _shape_of(radii: tuple[Fraction, Fraction]) -> tuple[Fraction, Fraction]:
    """``(k, S) = (R² − r², 4R²)`` of the radii ``(R, r)``."""
    R, r = radii
    return R * R - r * r, 4 * R * R


def _torus_coefficients(k: Fraction, S4: Fraction) -> Callable[[Fraction], list[Fraction]]:
    """A torus's ``q_ij`` on :data:`.coefficients.TORUS_TERMS` (``1, h², ρ, ρ²``) for a direction
    of ``|a|²``: ``k², S/|a|², 2k − S, 1``."""
    return lambda norm2: [k * k, S4 / norm2, 2 * k - S4, Fraction(1)]


def _torus_model(k: float, S4: float) -> Model:
    """The unknowns of :func:`_design` for ``(λ, â)``, the radii held: ``λ``, the entries of
    ``λ((2k − S)I + Sââᵀ)`` and ``λk²``."""

    def unknowns(scale: float, n: FloatArray) -> FloatArray:
        M = scale * ((2 * k - S4) * np.eye(3) + S4 * np.outer(n, n))
        return np.concatenate([[scale], form_entries(M), [scale * k * k]])

    return unknowns


def _largest_smallest(
    design: FloatArray, target: FloatArray, lam: float, unit: FloatArray
) -> Callable[[Model], FloatArray]:
    """The axis refitted for a torus's model: by least squares (:func:`.cones.refit_direction`),
    then the direction near it that makes the largest weighted residual smallest, with the
    scale (:func:`.near_symmetry.lawson`): every coefficient within its rounding is a bound on
    the largest. The least-squares axis of a 6-digit torus was 1.6e-7 from the one it was
    printed from, and only a torus scaled by ``2481838/2481837`` was within the rounding about
    the directions near it."""

    def refit(model: Model) -> FloatArray:
        fitted = refit_direction(design, target, model, lam, unit)
        column = design @ model(1.0, fitted)
        scale = float(column @ target) / float(column @ column)

        def residual(params: FloatArray) -> FloatArray:
            change, theta, phi = params
            return design @ model(scale * (1.0 + change), unit_at(theta, phi)) - target

        start = np.array([0.0, *angles_of(fitted)])
        _, theta, phi = lawson(residual, start)
        return unit_at(theta, phi)

    return refit


def _shape(solution: FloatArray) -> tuple[float, float, float, FloatArray] | None:
    """``(λ, R, r, â)`` of the fit ``λρ² + qᵀMq + c₀``: ``M/λ = (2k − S)I + Sââᵀ``, its odd
    eigenvalue ``2k`` with the eigenvector ``â``, the pair ``2k − S``; ``None`` unless it is a
    real torus (``S > 0``, ``r² > 0``)."""
    lam = float(solution[0])
    if lam == 0.0:
        return None
    M = solution[1:7] / lam
    values, vectors = np.linalg.eigh(np.array([[M[0], M[3], M[4]], [M[3], M[1], M[5]], [M[4], M[5], M[2]]]))
    gaps = [abs(values[1] - values[2]), abs(values[0] - values[2]), abs(values[0] - values[1])]
    odd = int(np.argmin(gaps))  # the eigenvalue not in the nearest pair
    pair = float(np.mean([values[i] for i in range(3) if i != odd]))
    k, S4 = float(values[odd]) / 2, float(values[odd]) - pair
    if S4 <= 0 or S4 / 4 - k <= 0:
        return None
    return lam, float(np.sqrt(S4 / 4)), float(np.sqrt(S4 / 4 - k)), vectors[:, odd]


def _design(monomials: list[Monomial], C: FloatArray) -> FloatArray:
    """The coefficients of ``λρ² + qᵀMq + c₀`` (``q = p − C``) at ``monomials`` as linear forms
    in ``λ``, the entries of ``M`` (:func:`.cones.form_design`) and ``c₀``."""
    rho: dict[Monomial, float] = {(2, 0, 0): 1.0, (0, 2, 0): 1.0, (0, 0, 2): 1.0, (0, 0, 0): float(C @ C)}
    for i, m in enumerate(((1, 0, 0), (0, 1, 0), (0, 0, 1))):
        rho[m] = -2.0 * C[i]
    squared: dict[Monomial, float] = {}
    for m1, v1 in rho.items():
        for m2, v2 in rho.items():
            m = (m1[0] + m2[0], m1[1] + m2[1], m1[2] + m2[2])
            squared[m] = squared.get(m, 0.0) + v1 * v2
    constant = np.array([1.0 if not any(m) else 0.0 for m in monomials])
    quartic = np.array([squared.get(m, 0.0) for m in monomials])
    return np.column_stack([quartic, form_design(monomials, C), constant])
