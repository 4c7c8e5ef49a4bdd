"""Scene data of a canal surface (docs/math.md §9): the spine curves and a few characteristic
circles as plain ``float64`` polylines, for the 3D view (no Qt, no VTK).

The families come as plain data (:class:`FamilyCurves`, :class:`SmatFamily`), read from the
engine's exact strings once, in the worker (:mod:`sorgui.session.canal_data`): ``m(t)`` and the
circles ``c(t)``, ``R²(t)``, ``m′(t)`` of a rational family as numerator and denominator
coefficient arrays, sampled at ``t = tan φ`` so that the whole rational curve is covered; points
outside the ball of radius ``bound`` are dropped (a polyline is split there).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sorgui.render.geometry import runs

Function = tuple[np.ndarray, np.ndarray]
"""A rational function of ``t``: numerator and denominator coefficients, highest degree first."""

Terms4 = tuple[tuple[tuple[int, int, int, int], float], ...]
"""A polynomial in ``m1, m2, m3, r`` as ``(exponents, coefficient)`` pairs."""


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
class SmatFamily:
    """A sphere family with no rational ``m(t)``: the equations of its SMAT curve in
    ``m1, m2, m3, r`` as float terms (exponents in that order)."""

    equations: tuple[Terms4, ...]


CIRCLE_POINTS = 256
"""Points of a drawn characteristic circle: its chords stay within the surface's own triangles
(a 64-point circle of radius 1 sagged 1.2e-3 inside its chords, more than a mesh of spacing
0.04 does, and was drawn dotted through the surface that hid it)."""


@dataclass(frozen=True)
class CanalScene:
    """Polylines ``(n, 3)``: the spines (one or more pieces per family) and closed circles."""

    spines: tuple[np.ndarray, ...]
    circles: tuple[np.ndarray, ...]


def canal_scene(
    families: Sequence[FamilyCurves | SmatFamily],
    *,
    bound: float = 20.0,
    samples: int = 400,
    circles: int = 12,
    circle_points: int = CIRCLE_POINTS,
) -> CanalScene:
    """The spines and ``circles`` characteristic circles of every rational family.

    Families without ``m(t)`` (a :class:`SmatFamily`, a spine of positive genus) contribute
    nothing here: they are traced from the surface (:mod:`sorgui.render.canal_trace`).
    """
    spines: list[np.ndarray] = []
    rings: list[np.ndarray] = []
    for family in families:
        if isinstance(family, FamilyCurves):
            spines += _split(_spine(family.center, samples), bound)
            rings += _circles(family, bound, circles, circle_points)
    return CanalScene(tuple(spines), tuple(rings))


def evaluate(fn: Function, t: np.ndarray) -> np.ndarray:
    """Values of a :data:`Function` at the parameters ``t`` (``inf``/``nan`` at poles)."""
    with np.errstate(all="ignore"):
        return np.polyval(fn[0], t) / np.polyval(fn[1], t)


def evaluate_angle(fn: Function, phi: np.ndarray) -> np.ndarray:
    """Values of a :data:`Function` at ``t = tan φ``, the numerator and denominator homogenized
    to one degree in ``(sin φ, cos φ)``: finite at ``φ = ±π/2`` (``t = ∞``) where the function
    has a limit, so a search over ``φ`` reaches the parameter's point at infinity too."""
    num, den = fn
    n = max(len(num), len(den)) - 1
    s, c = np.sin(phi), np.cos(phi)

    def homogeneous(coefficients: np.ndarray) -> np.ndarray:
        degree = len(coefficients) - 1
        return sum(
            (a * s ** (degree - i) * c ** (n - degree + i) for i, a in enumerate(coefficients)), np.zeros_like(phi)
        )

    with np.errstate(all="ignore"):
        values: np.ndarray = homogeneous(num) / homogeneous(den)
        return values


def _parameters(samples: int) -> np.ndarray:
    """``t = tan φ`` for ``φ`` evenly spaced in ``(−π/2, π/2)``: the whole real line."""
    phi = np.linspace(-np.pi / 2, np.pi / 2, samples + 2)[1:-1]
    return np.tan(phi)


def _spine(triple: Sequence[Function], samples: int) -> np.ndarray:
    """``samples`` points of the spine ``m(t)``, ``t = tan φ`` for ``φ`` evenly spaced in
    ``[−π/2, π/2]``, ends included (:func:`evaluate_angle`): a spine through its point at
    ``t = ∞`` (a torus's circle of centres, a Dupin cyclide's ellipse) was drawn with a gap there."""
    phi = np.linspace(-np.pi / 2, np.pi / 2, samples)
    return np.column_stack([evaluate_angle(fn, phi) for fn in triple])


def _vectors(triple: Sequence[Function], t: np.ndarray) -> np.ndarray:
    return np.column_stack([evaluate(fn, t) for fn in triple])


def _split(points: np.ndarray, bound: float) -> list[np.ndarray]:
    """The runs of finite points inside the ball of radius ``bound`` (at least two points each)."""
    inside = np.all(np.isfinite(points), axis=1) & (np.linalg.norm(np.nan_to_num(points), axis=1) <= bound)
    return runs(points, inside)


def _circles(family: FamilyCurves, bound: float, count: int, points: int) -> list[np.ndarray]:
    t = _parameters(count)
    centers = _vectors(family.circle_center, t)
    normals = _vectors(family.circle_normal, t)
    radius2 = evaluate(family.circle_radius_squared, t)
    out = []
    for c, n, r2 in zip(centers, normals, radius2):
        ring = circle(c, n, float(r2), points)
        if ring is not None and np.all(np.linalg.norm(ring, axis=1) <= bound):
            out.append(ring)
    return out


def circle(center: np.ndarray, normal: np.ndarray, radius_squared: float, points: int) -> np.ndarray | None:
    """The circle of the given centre, plane normal and squared radius as a closed polyline of
    ``points + 1`` points; ``None`` when it is not a real circle (or not finite)."""
    norm = float(np.linalg.norm(normal))
    if not (
        np.all(np.isfinite(center))
        and np.isfinite(radius_squared)
        and radius_squared > 0
        and np.isfinite(norm)
        and norm > 0
    ):
        return None
    n = normal / norm
    helper = np.eye(3)[int(np.argmin(np.abs(n)))]
    e1 = np.cross(n, helper)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    theta = np.linspace(0.0, 2 * np.pi, points + 1)
    ring: np.ndarray = center + np.sqrt(radius_squared) * (np.outer(np.cos(theta), e1) + np.outer(np.sin(theta), e2))
    return ring
