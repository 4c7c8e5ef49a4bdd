"""The designed sphere of a rounded quadric: its centre and radius as a CAD system printed them
(docs/math.md §8.5, "Spheres").

A sphere ``λ(|p − c|² − r²)`` printed with decimals is often exactly a sphere still, but of a
centre and radius with as many digits as the input: ``x² − 6.2x + y² + 4.8y + z² − 10.1z −
120.418`` (radius 12.7 about ``(3.1, −2.4, 5.05)``, 6 digits) is the sphere of ``r² =
322581/2000``, ``r = 12.70002``. Here the centre is snapped as a cone's apex is
(:func:`.cones.snapped_points`: decimals of fewest places first, coarsest first), and about each
centre the radius as a cylinder's is (:func:`.cylinders.snapped_radius`: the decimal of fewest
places, else ``r²`` the simplest rational), the radius fitted to the constant term; the first
sphere whose every coefficient is within the rounding, up to the simplest factor
(:func:`.coefficients.within_scale`), and that the exact recognizer confirms, is the answer.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction
from functools import partial
from typing import TYPE_CHECKING

import numpy as np
from flint import fmpq_mpoly

from .coefficients import Typed
from .cones import MAX_CHECKS, S, snapped_points
from .cylinders import snapped_radius

if TYPE_CHECKING:
    from ..algebra.linalg import Vector
    from .precision import Rounding

EXPONENTS = ((0, 0), (0, 1))
"""The terms ``1, ρ`` of a sphere about its centre, ``ρ = |p − c|²`` (:func:`.snapping.build`)."""

SphereBuild = Callable[["Vector", list[Fraction]], "fmpq_mpoly | None"]
"""``g = q₀₀ + q₀₁·|p − c|²`` about the centre ``c``."""


def nearest_sphere(
    typed: Typed, rounding: Rounding, build: SphereBuild, check: Callable[[Vector, fmpq_mpoly], S | None]
) -> tuple[list[Fraction], S] | None:
    """The designed sphere within the rounding of the typed quadric (its ``q₀₀, q₀₁`` on
    :data:`EXPONENTS`, and the surface), or ``None``: its centre and ``r²`` are read off the
    typed coefficients (``λ|p|² + b·p + k``: ``c = −b/2λ``, ``r² = |c|² − k/λ``), then snapped;
    ``check`` checks the sphere ``g`` about ``c`` against the typed surface
    (:func:`.snapping.check_surface`), called as ``check(c, g)``."""
    floats = typed.floats
    lam = floats.get((2, 0, 0), 0.0)
    if not lam or any(floats.get(m, 0.0) != lam for m in ((0, 2, 0), (0, 0, 2))):
        return None
    centre = np.array([-floats.get(m, 0.0) / (2 * lam) for m in ((1, 0, 0), (0, 1, 0), (0, 0, 1))])
    constant = floats.get((0, 0, 0), 0.0) / lam
    if float(centre @ centre) - constant <= 0:
        return None  # no real points: no radius to design
    scale = max(float(np.linalg.norm(centre)), math.sqrt(float(centre @ centre) - constant))
    checks = 0
    for point in dict.fromkeys(snapped_points(centre, scale)):
        about = np.array([float(v) for v in point])
        r2 = float(about @ about) - constant  # the radius that keeps the constant term
        if r2 <= 0:
            continue
        found, tried = snapped_radius(
            r2,
            Fraction(1),
            partial(build, point),
            typed,
            rounding,
            partial(check, point),
        )
        if found is not None:
            _, coefficients, surface = found
            return coefficients, surface
        checks += tried
        if checks >= MAX_CHECKS:
            return None
    return None
