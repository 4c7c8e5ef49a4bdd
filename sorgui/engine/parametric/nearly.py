"""Rounded coefficients: is a parametrization, within its rounding, one of a surface of
revolution, a cone or a cylinder? (docs/math.md §12)

A CAD system prints the map with decimals; a surface of revolution about an axis that is not
along a rational direction is then exactly none. The systems of :mod:`.detect` are solved in
floating point by least squares over sample points of the map instead of exactly:

* the normal lines ``(n̂ : P × n̂)`` of the samples (unit normals, the points centred and scaled to
  the size ``L`` of the sampled patch) give the rows of the 6-column system of the symmetry
  algebra; its right singular vectors of the smallest singular values are approximate motions,
  classified as in docs/math.md §8.2 (a rotation: an axis; so(3): a sphere's centre; a
  rotation and a translation: a cylinder of revolution; two translations and a rotation: a plane);
* the **deviation** is the distance of the normal lines to that axis (to the centre; for a plane
  the sine of the angle between the normals), the largest over the samples whose normals are
  not within 6° of the axis direction, relative to ``L``;
* a cone's apex ``c`` is the least-squares solution of ``(P − c)·n̂ = 0`` (the tangent planes
  pass through it), a cylinder's direction the unit ``a`` that minimises ``|n̂·a|``.

The tolerance is the input's: half a unit in the last place of its most precise decimal,
relative (``0.5·10^(1−k)`` for ``k`` significant digits), or ``--tolerance``. A kind is *near*
when its deviation is within :data:`NEAR_FACTOR` times the tolerance (the ``residual`` of the
:class:`~sorgui.engine.results.Approximation` is the deviation in that unit: at most 1 is near) (CAD printing rounds
every coefficient, and the normals amplify that by the conditioning of the map; a coefficient
moved by ``10⁻³`` or ``10⁻⁶`` stays far outside).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..results import ApproximateAxis, Approximation
from .maps import RationalMap

NEAR_FACTOR = 30.0
"""How many times the tolerance the relative deviation of a near kind may reach: the rounding of
a surface of revolution's map printed with 6, 10 or 15 digits leaves 0.5 to 1.5 times it, a
coefficient moved by ``10⁻⁶`` thousands of times."""
COARSEST = 0.1
"""A rounding coarser than this (``0.5``, ``3.0``: a gallery's exact numbers) says nothing: the
input is taken as exact."""
GRID = 24
"""Samples per parameter over :data:`SPAN`."""
SPAN = 2.0
"""The samples lie in ``[−SPAN, SPAN]²`` of the parameter plane."""
SINE_FLOOR = 0.1
"""Normals within this sine of the axis direction are left out of the distance to the axis."""

_DECIMAL = re.compile(
    r"(?<![A-Za-z0-9_.])([0-9]*)\.([0-9]*)(?:[eE][+-]?[0-9]+)?|(?<![A-Za-z0-9_.])([0-9]+)[eE][+-]?[0-9]+"
)


@dataclass(frozen=True)
class NearCone:
    """A cone's apex (or a cylinder's unit direction) within the rounding, with its deviation."""

    apex: tuple[float, float, float] | None
    direction: tuple[float, float, float] | None
    residual: float


def printed_tolerance(text: str) -> float | None:
    """The relative rounding of the most precise decimal of ``text`` (``None``: no decimal)."""
    digits = 0
    for match in _DECIMAL.finditer(text):
        whole, fraction, plain = match.group(1), match.group(2), match.group(3)
        written = (whole or "") + (fraction or "") if plain is None else plain
        digits = max(digits, len(written.lstrip("0")) or 1)
    return None if digits == 0 else 0.5 * 10.0 ** (1 - digits)


@dataclass(frozen=True)
class _Samples:
    """Points of the map (centred at ``middle``, scaled by ``size``) and their unit normals."""

    points: np.ndarray
    normals: np.ndarray
    middle: np.ndarray
    size: float


def _samples(surface: RationalMap) -> _Samples | None:
    grid = np.linspace(-SPAN, SPAN, GRID)
    s, t = (a.ravel() for a in np.meshgrid(grid, grid))
    ring = surface.ring
    Xs, Xt, Ws, Wt = surface.derivatives
    value = {}
    for key, p in (("W", surface.W), ("Ws", Ws), ("Wt", Wt)):
        value[key] = _evaluate(ring, p, s, t)
    X = np.array([_evaluate(ring, p, s, t) for p in surface.X])
    XS = np.array([_evaluate(ring, p, s, t) for p in Xs])
    XT = np.array([_evaluate(ring, p, s, t) for p in Xt])
    W, WS, WT = value["W"], value["Ws"], value["Wt"]
    with np.errstate(all="ignore"):
        P = X / W
        Ps = (XS * W - X * WS) / W**2
        Pt = (XT * W - X * WT) / W**2
        N = np.cross(Ps.T, Pt.T)
        length = np.linalg.norm(N, axis=1)
        points = P.T
    scale = np.median(np.linalg.norm(points, axis=1)[np.isfinite(length)]) if np.any(np.isfinite(length)) else 0.0
    keep = np.isfinite(length) & (length > 1e-12 * max(np.nanmax(length, initial=0.0), 1e-300))
    keep &= np.all(np.isfinite(points), axis=1) & (np.linalg.norm(points, axis=1) < 1e3 * (scale + 1.0))
    if keep.sum() < 12:
        return None
    points, normals = points[keep], N[keep] / length[keep, None]
    middle = points.mean(axis=0)
    size = float(np.sqrt(np.mean(np.sum((points - middle) ** 2, axis=1))))
    if not size > 0:
        return None
    return _Samples((points - middle) / size, normals, middle, size)


def _evaluate(ring: Any, p: Any, s: np.ndarray, t: np.ndarray) -> np.ndarray:
    total = np.zeros_like(s)
    for (i, j), c in ring.terms(p):
        total = total + _float(ring, c) * s**i * t**j
    return total


def _float(ring: Any, c: Any) -> float:
    return float(c) if ring.is_flint else float(ring.K.to_sympy(c).evalf(20))


def nearly(surface: RationalMap, tolerance: float, source: str) -> tuple[Approximation, NearCone | None]:
    """The approximation of the symmetry (an :class:`Approximation` as rounded equations get,
    ``source`` ``input`` or ``given``) and, when the surface is near no surface of revolution,
    a near cone or cylinder."""
    samples = _samples(surface)
    if samples is None:
        return Approximation(tolerance, source, False, None, None, None, (), notes=(_FEW,)), None
    Q, n = samples.points, samples.normals
    rows = np.hstack([n, np.cross(Q, n)])
    _u, singular, vt = np.linalg.svd(rows, full_matrices=False)
    relative = tuple(float(v / singular[0]) for v in singular)
    gate = min(1e-2, 1e4 * tolerance)
    small = int(sum(v <= gate for v in relative))
    found = _classify(samples, vt, small)
    notes = (
        "the deviation is the largest distance of the normal lines to the axis (to the centre), "
        "relative to the size of the sampled patch, over the parameters in "
        f"[{-SPAN:g}, {SPAN:g}]²",
        "no nearest exact surface is computed for a parametrization",
    )
    if found is None:
        best = _rotation(samples, vt[-1])
        deviation = None if best is None else _axis_deviation(samples, *best)
        approximation = Approximation(
            tolerance,
            source,
            False,
            None,
            deviation,
            None if deviation is None else deviation / (NEAR_FACTOR * tolerance),
            relative,
            notes=notes,
        )
        return approximation, _near_cone(samples, tolerance)
    kind, deviation, axis, center, normal = found
    near = deviation <= NEAR_FACTOR * tolerance
    approximation = Approximation(
        tolerance,
        source,
        near,
        kind,
        deviation,
        deviation / (NEAR_FACTOR * tolerance),
        relative,
        axis=axis,
        center=center,
        normal=normal,
        notes=notes,
    )
    return approximation, None if near else _near_cone(samples, tolerance)


_FEW = "too few sample points of the map are finite to solve the systems in floating point"


def _classify(
    samples: _Samples, vt: np.ndarray, small: int
) -> (
    tuple[str, float, ApproximateAxis | None, tuple[float, float, float] | None, tuple[float, float, float] | None]
    | None
):
    """The most symmetric kind the small singular values allow, with its deviation."""
    if small >= 3:
        motions = vt[-3:]
        rotations = motions[:, 3:]
        if np.linalg.matrix_rank(rotations, tol=0.1) == 3:  # so(3): b = c × a for each
            rows = np.vstack([_cross_matrix(a) for a in rotations])  # c × a = -[a]× c
            rhs = np.concatenate([-b for b in motions[:, :3]])
            c, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
            deviation = float(np.max(np.linalg.norm(np.cross(samples.points - c, samples.normals), axis=1)))
            return "sphere", deviation, None, _vector(samples.middle + samples.size * c), None
        mean = samples.normals * np.sign(samples.normals @ samples.normals[0])[:, None]
        normal = mean.mean(axis=0)
        normal /= np.linalg.norm(normal)
        deviation = float(np.max(np.linalg.norm(np.cross(samples.normals, normal), axis=1)))
        return "plane", deviation, None, None, _vector(normal)
    if small >= 1:
        candidates = vt[-2:] if small >= 2 else vt[-1:]
        best = None
        for v in candidates:
            rotation = _rotation(samples, v)
            if rotation is not None:
                deviation = _axis_deviation(samples, *rotation)
                if best is None or deviation < best[0]:
                    best = (deviation, rotation)
        if best is None:
            return None
        deviation, (point, direction) = best
        kind = "cylinder_of_revolution" if small >= 2 else "revolution"
        direction = direction if direction[int(np.argmax(np.abs(direction)))] > 0 else -direction
        foot = samples.middle + samples.size * point
        foot = foot - (foot @ direction) * direction  # the point of the axis nearest the origin
        axis = ApproximateAxis(_vector(foot), _vector(direction))
        return kind, deviation, axis, None, None
    return None


def _rotation(samples: _Samples, v: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The axis (point, unit direction) of the motion ``(b, a) = v``, its screw part removed;
    ``None`` for a translation."""
    b, a = v[:3], v[3:]
    if np.linalg.norm(a) < 0.1 * np.linalg.norm(v):
        return None
    b = b - (a @ b) / (a @ a) * a
    point = np.cross(a, b) / (a @ a)
    return point, a / np.linalg.norm(a)


def _axis_deviation(samples: _Samples, point: np.ndarray, direction: np.ndarray) -> float:
    """The largest distance of the normal lines to the axis (normals not along it), relative."""
    across = np.cross(samples.normals, direction)
    sine = np.linalg.norm(across, axis=1)
    keep = sine >= SINE_FLOOR
    if not np.any(keep):
        return math.inf
    distance = np.abs(np.sum((samples.points[keep] - point) * across[keep], axis=1)) / sine[keep]
    return float(np.max(distance))


def _near_cone(samples: _Samples, tolerance: float) -> NearCone | None:
    """A cone whose tangent planes pass within the rounding of one apex, else a cylinder whose
    normals are within it of perpendicular to one direction, else ``None``."""
    n, Q = samples.normals, samples.points
    _u, singular, vt = np.linalg.svd(n, full_matrices=False)
    if singular[-1] <= NEAR_FACTOR * tolerance * singular[0]:
        a = vt[-1] / np.linalg.norm(vt[-1])
        a = a if a[int(np.argmax(np.abs(a)))] > 0 else -a
        deviation = float(np.max(np.abs(n @ a)))
        if deviation <= NEAR_FACTOR * tolerance:
            return NearCone(None, _vector(a), deviation)
        return None
    c, *_ = np.linalg.lstsq(n, np.sum(n * Q, axis=1), rcond=None)
    deviation = float(np.max(np.abs(np.sum((Q - c) * n, axis=1))))
    if deviation <= NEAR_FACTOR * tolerance:
        return NearCone(_vector(samples.middle + samples.size * c), None, deviation)
    return None


def _cross_matrix(a: np.ndarray) -> np.ndarray:
    """``[a]×`` with ``[a]× c = a × c``."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _vector(v: np.ndarray) -> tuple[float, float, float]:
    return float(v[0]), float(v[1]), float(v[2])
