"""The sphere of a canal surface's family that touches the surface at a picked point, and its
characteristic circle (docs/math.md §9): the canal analogue of the circle of latitude.

A point ``p`` of the envelope lies on the characteristic circle ``c(t)``, ``R²(t)`` (in the
plane with normal ``n(t)``) of the sphere ``|X − m(t)|² = ρ(t)`` that touches the surface
there. The parameter ``t`` is found numerically: the distance from ``p`` to the circle of
parameter ``t`` is minimised over ``t = tan φ`` (a coarse scan, then finer scans about the
best value). Everything here is ``float64`` numpy data read once from the engine's exact
strings (:func:`family_curves`, in the worker), so the GUI thread only evaluates polynomials.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sorgui.engine.report import Canal
from sorgui.render.canal_scene import Function, circle, evaluate, rational_function

SCAN = 2000
"""Samples of ``φ`` in the coarse scan over the whole real line of ``t``."""


@dataclass(frozen=True, eq=False)
class FamilyCurves:
    """One rational sphere family as float coefficient arrays: the centre ``m(t)``, the squared
    radius ``ρ(t)``, and the characteristic circle's centre ``c(t)``, ``R²(t)`` and plane normal."""

    center: tuple[Function, Function, Function]
    radius_squared: Function
    circle_center: tuple[Function, Function, Function]
    circle_radius_squared: Function
    circle_normal: tuple[Function, Function, Function]


@dataclass(frozen=True, eq=False)
class Touch:
    """The sphere of family ``family`` (parameter ``t``) touching the surface at the picked point:
    its centre and radius, its characteristic circle (a closed polyline) and the distance from
    the point to that circle (small when the point is on the surface)."""

    family: int
    t: float
    center: np.ndarray
    radius: float
    circle: np.ndarray
    distance: float


def family_curves(canal: Canal) -> tuple[FamilyCurves, ...]:
    """The float curves of every family of ``canal`` that has ``m(t)``, ``ρ(t)`` and circles."""
    out = []
    for family in canal.families:
        if (family.parametrization is None or family.radius_squared is None or family.circle_center is None
                or family.circle_radius_squared is None or family.circle_normal is None):
            continue
        out.append(FamilyCurves(
            tuple(rational_function(c) for c in family.parametrization),  # type: ignore[arg-type]
            rational_function(family.radius_squared),
            tuple(rational_function(c) for c in family.circle_center),  # type: ignore[arg-type]
            rational_function(family.circle_radius_squared),
            tuple(rational_function(c) for c in family.circle_normal),  # type: ignore[arg-type]
        ))
    return tuple(out)


def touching_spheres(families: tuple[FamilyCurves, ...], point: np.ndarray, tolerance: float,
                     circle_points: int = 96) -> list[Touch]:
    """For each family, the sphere whose characteristic circle passes within ``tolerance`` of
    ``point`` (none for a family whose circles all miss it)."""
    point = np.asarray(point, dtype=np.float64)
    out = []
    for index, family in enumerate(families):
        t, distance = _nearest_circle(family, point)
        if not np.isfinite(distance) or distance > tolerance:
            continue
        center = _vector(family.center, np.array([t]))[0]
        rho = float(evaluate(family.radius_squared, np.array([t]))[0])
        ring = _circle(family, t, circle_points)
        if ring is None or not (np.all(np.isfinite(center)) and rho > 0):
            continue
        out.append(Touch(index, t, center, float(np.sqrt(rho)), ring, distance))
    return out


def _vector(fns: tuple[Function, Function, Function], t: np.ndarray) -> np.ndarray:
    return np.column_stack([evaluate(fn, t) for fn in fns])


def _circle_distance(family: FamilyCurves, point: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The distance from ``point`` to the characteristic circle of each parameter in ``t``."""
    c = _vector(family.circle_center, t)
    n = _vector(family.circle_normal, t)
    r2 = evaluate(family.circle_radius_squared, t)
    with np.errstate(all="ignore"):
        n = n / np.linalg.norm(n, axis=1, keepdims=True)
        d = point - c
        h = np.sum(d * n, axis=1)
        radial = np.linalg.norm(d - h[:, None] * n, axis=1)
        distance = np.sqrt(h * h + (radial - np.sqrt(r2)) ** 2)
    return np.where(np.isfinite(distance) & (r2 > 0), distance, np.inf)


def _nearest_circle(family: FamilyCurves, point: np.ndarray) -> tuple[float, float]:
    """``(t, distance)`` of the circle nearest ``point``: a scan of ``φ``, then three refinements."""
    phi = np.linspace(-np.pi / 2, np.pi / 2, SCAN + 2)[1:-1]
    step = phi[1] - phi[0]
    for _round in range(4):
        distance = _circle_distance(family, point, np.tan(phi))
        best = int(np.argmin(distance))
        centre = phi[best]
        phi = np.clip(np.linspace(centre - 2 * step, centre + 2 * step, 81), -np.pi / 2 + 1e-9, np.pi / 2 - 1e-9)
        step = phi[1] - phi[0]
    return float(np.tan(centre)), float(distance[best])


def _circle(family: FamilyCurves, t: float, points: int) -> np.ndarray | None:
    ts = np.array([t])
    return circle(_vector(family.circle_center, ts)[0], _vector(family.circle_normal, ts)[0],
                  float(evaluate(family.circle_radius_squared, ts)[0]), points)
