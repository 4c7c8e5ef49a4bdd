"""The sphere of a canal surface's family that touches the surface at a picked point, and its
characteristic circle (docs/math.md §9): the canal analogue of the circle of latitude.

A point ``p`` of the envelope lies on the characteristic circle ``c(t)``, ``R²(t)`` (in the
plane with normal ``n(t)``) of the sphere ``|X − m(t)|² = ρ(t)`` that touches the surface
there. For a rational family the parameter ``t`` is found numerically: the distance from ``p``
to the circle of parameter ``t`` is minimised over ``t = tan φ`` (a coarse scan, then finer
scans about the best value). A family with no ``m(t)`` (a spine of positive genus) is known by
the equations of its SMAT curve in ``m1, m2, m3, r``: the touching sphere's centre lies on the
normal line ``p + s·n`` at distance ``|s|``, so ``(p + s·n, s²)`` is a common real root of
those equations restricted to the line; the circle's plane has the normal ``m′`` and passes
through ``p`` (``(X − m)·m′ + ρ′/2 = 0``, with ``(m′, ρ′)`` the SMAT curve's tangent). Everything
here is ``float64`` numpy data read once from the engine's exact strings
(:func:`sorgui.session.canal_data.family_curves`, in the worker), so the GUI thread only
evaluates polynomials.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sorgui.numerics import real_roots
from sorgui.render.canal_scene import FamilyCurves, Function, SmatFamily, Terms4, circle, evaluate_angle

SCAN = 2000
"""Samples of ``φ`` in the coarse scan over the whole real line of ``t``."""

REFINEMENTS = 10
"""Refinements of the scan, each twenty times finer: down to the precision of a double."""


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


def touching_spheres(
    families: tuple[FamilyCurves | SmatFamily, ...],
    point: np.ndarray,
    tolerance: float,
    circle_points: int = 96,
    normal: np.ndarray | None = None,
) -> list[Touch]:
    """For each family, the sphere whose characteristic circle passes within ``tolerance`` of
    ``point`` (none for a family whose circles all miss it). A :class:`SmatFamily` needs the
    surface's unit ``normal`` at ``point``."""
    point = np.asarray(point, dtype=np.float64)
    out = []
    for index, family in enumerate(families):
        if isinstance(family, SmatFamily):
            if normal is not None and np.any(normal):
                out += [
                    t
                    for t in _smat_touches(index, family, point, np.asarray(normal, dtype=np.float64), circle_points)
                    if t.distance <= tolerance
                ]
            continue
        phi, distance = _nearest_circle(family, point)
        if not np.isfinite(distance) or distance > tolerance:
            continue
        angle = np.array([phi])
        center = _vector(family.center, angle)[0]
        rho = float(evaluate_angle(family.radius_squared, angle)[0])
        ring = _circle(family, phi, circle_points)
        if ring is None or not (np.all(np.isfinite(center)) and rho > 0):
            continue
        out.append(Touch(index, float(np.tan(phi)), center, float(np.sqrt(rho)), ring, distance))
    return out


def _vector(fns: tuple[Function, Function, Function], phi: np.ndarray) -> np.ndarray:
    """The vector function at the angles ``phi`` (``t = tan φ``)."""
    return np.column_stack([evaluate_angle(fn, phi) for fn in fns])


def _circle_distance(family: FamilyCurves, point: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """The distance from ``point`` to the characteristic circle of each parameter ``tan φ``."""
    c = _vector(family.circle_center, phi)
    n = _vector(family.circle_normal, phi)
    r2 = evaluate_angle(family.circle_radius_squared, phi)
    with np.errstate(all="ignore"):
        n = n / np.linalg.norm(n, axis=1, keepdims=True)
        d = point - c
        h = np.sum(d * n, axis=1)
        radial = np.linalg.norm(d - h[:, None] * n, axis=1)
        distance = np.sqrt(h * h + (radial - np.sqrt(r2)) ** 2)
    return np.where(np.isfinite(distance) & (r2 > 0), distance, np.inf)


def _nearest_circle(family: FamilyCurves, point: np.ndarray) -> tuple[float, float]:
    """``(φ, distance)`` of the circle nearest ``point`` (``t = tan φ``, the point at infinity
    ``φ = π/2`` included): a scan of ``φ``, then refinements down to the precision of a double
    (each narrows the step twentyfold)."""
    phi = np.linspace(-np.pi / 2, np.pi / 2, SCAN + 1)
    step = phi[1] - phi[0]
    for _round in range(REFINEMENTS):
        distance = _circle_distance(family, point, phi)
        best = int(np.argmin(distance))
        centre = phi[best]
        phi = np.linspace(centre - 2 * step, centre + 2 * step, 81)
        step = phi[1] - phi[0]
    return float(centre), float(distance[best])


def _circle(family: FamilyCurves, phi: float, points: int) -> np.ndarray | None:
    angle = np.array([phi])
    return circle(
        _vector(family.circle_center, angle)[0],
        _vector(family.circle_normal, angle)[0],
        float(evaluate_angle(family.circle_radius_squared, angle)[0]),
        points,
    )


def _evaluate4(terms: Terms4, points: np.ndarray) -> np.ndarray:
    """Values of a polynomial in ``m1, m2, m3, r`` at ``points`` (shape ``(k, 4)``, complex too)."""
    total = np.zeros(len(points), dtype=points.dtype)
    for exponents, c in terms:
        total = total + c * np.prod(points ** np.asarray(exponents), axis=1)
    return total


def value4(terms: Terms4, point: np.ndarray) -> float:
    """The value of a polynomial in ``m1, m2, m3, r`` at one point."""
    return float(_evaluate4(terms, np.asarray(point, dtype=np.float64)[None, :])[0])


def gradient4(terms: Terms4, point: np.ndarray) -> np.ndarray:
    """The gradient of a polynomial in ``m1, m2, m3, r`` at one point."""
    out = np.zeros(4)
    for exponents, c in terms:
        for axis, e in enumerate(exponents):
            if e:
                lowered = list(exponents)
                lowered[axis] -= 1
                out[axis] += c * e * float(np.prod(point ** np.asarray(lowered)))
    return out


def smat_tangent(equations: Sequence[Terms4], point: np.ndarray) -> np.ndarray | None:
    """The unit tangent ``(m′, ρ′)`` of a SMAT curve at ``point`` (the kernel of the Jacobian of
    its equations); ``None`` at a singular point."""
    _u, sigma, vt = np.linalg.svd(np.array([gradient4(g, point) for g in equations]))
    if len(sigma) < 3 or sigma[2] <= 1e-9 * max(sigma[0], 1.0):
        return None
    tangent: np.ndarray = vt[-1]
    return tangent


def characteristic_circle(
    equations: Sequence[Terms4], point: np.ndarray, points: int
) -> tuple[np.ndarray, np.ndarray, float] | None:
    """The characteristic circle of the sphere ``point = (m, ρ)`` of a SMAT curve: its polyline,
    centre and squared radius (in the plane ``(X − m)·m′ + ρ′/2 = 0``); ``None`` if not real."""
    tangent = smat_tangent(equations, point)
    if tangent is None:
        return None
    speed = float(tangent[:3] @ tangent[:3])
    if speed <= 1e-18:
        return None
    shift = -tangent[3] / (2 * speed)
    center = point[:3] + shift * tangent[:3]
    radius_squared = float(point[3] - shift * shift * speed)
    ring = circle(center, tangent[:3], radius_squared, points)
    return None if ring is None else (ring, center, radius_squared)


def _on_normal_line(terms: Terms4, point: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Coefficients (lowest degree first) of ``s ↦ P(point + s·normal, s²)``, by a DFT of its
    values at roots of unity."""
    degree = max((e[0] + e[1] + e[2] + 2 * e[3] for e, _c in terms), default=0)
    n = degree + 1
    s = np.exp(2j * np.pi * np.arange(n) / n)
    points = np.column_stack([point[None, :] + s[:, None] * normal[None, :], s * s])
    return (np.fft.fft(_evaluate4(terms, points)) / n).real


def _smat_touches(
    index: int, family: SmatFamily, point: np.ndarray, normal: np.ndarray, circle_points: int
) -> list[Touch]:
    """The spheres of ``family`` touching the surface at ``point``: the real ``s ≠ 0`` where every
    SMAT equation vanishes on ``(point + s·normal, s²)``."""
    normal = normal / np.linalg.norm(normal)
    lines = [_on_normal_line(g, point, normal) for g in family.equations]
    lines = [c for c in lines if np.abs(c).max(initial=0.0) > 0]
    if not lines:
        return []
    scales = [float(np.abs(c).max()) for c in lines]
    first = min(range(len(lines)), key=lambda i: np.count_nonzero(np.abs(lines[i]) > 1e-12 * scales[i]))
    out = []
    for s in real_roots(lines[first]):
        if abs(s) < 1e-9:
            continue
        if any(
            abs(np.polynomial.polynomial.polyval(s, c)) > 1e-6 * scale * max(1.0, abs(s)) ** (len(c) - 1)
            for c, scale in zip(lines, scales)
        ):
            continue
        center = point + s * normal
        found = characteristic_circle(family.equations, np.append(center, s * s), circle_points)
        if found is None:
            continue
        ring, ring_center, radius_squared = found
        tangent = smat_tangent(family.equations, np.append(center, s * s))
        assert tangent is not None  # characteristic_circle found it at the same point
        offset = point - ring_center
        height = float(offset @ tangent[:3]) / float(np.linalg.norm(tangent[:3]))
        radial = float(np.sqrt(max(offset @ offset - height * height, 0.0)))
        distance = float(np.hypot(height, radial - np.sqrt(radius_squared)))
        out.append(Touch(index, float(s), center, abs(float(s)), ring, distance))
    return out
