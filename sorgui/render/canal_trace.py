"""The spine and characteristic circles of a sphere family with no rational ``m(t)`` (a SMAT
curve of positive genus), traced numerically for the 3D view (docs/math.md §9).

The SMAT curve is the real curve ``F(m1, m2, m3, r) = 0`` of the family's equations
(:class:`~sorgui.render.canal_touch.SmatFamily`). Its points are found from points of the
surface (the sphere touching the surface there, :func:`~sorgui.render.canal_touch.touching_spheres`)
and each component is followed from such a point by predictor–corrector continuation: a step
along the tangent (the kernel of the Jacobian), then Newton's method back onto the curve in the
plane normal to the tangent. A component ends where it closes up, leaves the ball of radius
``bound`` or meets a singular point. The characteristic circle of a point ``(m, ρ)`` with
tangent ``(m′, ρ′)`` lies in the plane ``(X − m)·m′ + ρ′/2 = 0``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from sorgui.render.canal_scene import CIRCLE_POINTS, CanalScene, SmatFamily, Terms4
from sorgui.render.canal_touch import (
    characteristic_circle,
    gradient4,
    smat_tangent,
    touching_spheres,
    value4,
)

STEPS = 4000
"""The most continuation steps per direction from one start."""

NEWTON = 8
"""Newton iterations of one correction."""


def smat_scene(
    families: Sequence[SmatFamily],
    points: np.ndarray,
    normals: np.ndarray,
    *,
    bound: float,
    step: float,
    circles: int = 12,
    circle_points: int = CIRCLE_POINTS,
    starts: int = 40,
) -> CanalScene:
    """The spines (polylines of ``m``) and ``circles`` characteristic circles of ``families``,
    started from the spheres touching the surface at up to ``starts`` of ``points`` (with their
    unit ``normals``); ``step`` is the continuation step (length units)."""
    spines: list[np.ndarray] = []
    rings: list[np.ndarray] = []
    picked: np.ndarray | list[int] = (
        np.linspace(0, len(points) - 1, min(starts, len(points))).astype(int) if len(points) else []
    )
    for family in families:
        traced: list[np.ndarray] = []
        for i in picked:
            for touch in touching_spheres((family,), points[i], 1e-6 * bound, normal=normals[i]):
                start = np.append(touch.center, touch.radius**2)
                if any(np.min(np.linalg.norm(curve[:, :3] - start[:3], axis=1)) < 2 * step for curve in traced):
                    continue
                curve = _trace(family.equations, start, bound, step)
                if curve is not None and len(curve) > 2:
                    traced.append(curve)
        spines += [curve[:, :3] for curve in traced]
        rings += _circles(family.equations, traced, circles, circle_points)
    return CanalScene(tuple(spines), tuple(rings))


def _jacobian(equations: Sequence[Terms4], y: np.ndarray) -> np.ndarray:
    return np.array([gradient4(g, y) for g in equations])


def _values(equations: Sequence[Terms4], y: np.ndarray) -> np.ndarray:
    return np.array([value4(g, y) for g in equations])


def _correct(equations: Sequence[Terms4], guess: np.ndarray, tangent: np.ndarray) -> np.ndarray | None:
    """Newton's method from ``guess`` onto the curve, within the hyperplane through ``guess``
    normal to ``tangent``; ``None`` if it does not converge."""
    y = guess.copy()
    scale = 1.0 + float(np.abs(guess).max())
    for _ in range(NEWTON):
        residual = np.append(_values(equations, y), tangent @ (y - guess))
        if np.abs(residual).max() < 1e-11 * scale**2:
            return y
        system = np.vstack([_jacobian(equations, y), tangent])
        y = y - np.linalg.lstsq(system, residual, rcond=None)[0]
        if not np.all(np.isfinite(y)):
            return None
    residual = _values(equations, y)
    return y if np.abs(residual).max() < 1e-8 * scale**2 else None


def _trace(equations: Sequence[Terms4], start: np.ndarray, bound: float, step: float) -> np.ndarray | None:
    """The component through ``start`` as points ``(m1, m2, m3, r)``: both ways from ``start``
    until it closes up or ends (the ball's edge, a singular point)."""
    halves = []
    for sign in (1.0, -1.0):
        tangent = smat_tangent(equations, start)
        if tangent is None:
            return None
        tangent = sign * tangent
        y, points = start, []
        for count in range(STEPS):
            guess = y + step * tangent
            corrected = _correct(equations, guess, tangent)
            if corrected is None or np.linalg.norm(corrected[:3]) > bound:
                break
            new = smat_tangent(equations, corrected)
            if new is None:
                break
            tangent = new if new @ tangent > 0 else -new
            y = corrected
            points.append(y)
            if count > 4 and np.linalg.norm(y[:3] - start[:3]) < step:
                return np.array([start, *points, start])  # a closed component
        halves.append(points)
    return np.array([*reversed(halves[1]), start, *halves[0]])


def _circles(equations: Sequence[Terms4], curves: Sequence[np.ndarray], count: int, points: int) -> list[np.ndarray]:
    """``count`` characteristic circles at points spread along ``curves`` by arc length."""
    lengths = [np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(c[:, :3], axis=0), axis=1))]) for c in curves]
    total = sum(float(s[-1]) for s in lengths)
    if total <= 0:
        return []
    out = []
    for target in (np.arange(count) + 0.5) * total / count:
        for curve, arc in zip(curves, lengths):
            if target <= arc[-1]:
                y = curve[int(np.searchsorted(arc, target).clip(0, len(curve) - 1))]
                found = characteristic_circle(equations, y, points)
                if found is not None:
                    out.append(found[0])
                break
            target -= arc[-1]
    return out
