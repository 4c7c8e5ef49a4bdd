"""Rounded coefficients: is a parametrization, within its rounding, one of a surface of
revolution, a cone or a cylinder? (docs/math.md §13)

A CAD system prints the map with decimals; a surface of revolution about an axis that is not
along a rational direction is then exactly none. The systems of :mod:`.detect` are solved in
floating point by least squares over sample points of the map instead of exactly, by the line
complex of sampled normals that CAD faces are read with (:mod:`sorgui.engine.rounded.line_complex`):

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
when its deviation is within :func:`~sorgui.engine.results.map_near_limit` (30 times the
tolerance, at most 0.05; the ``residual`` of the :class:`~sorgui.engine.results.Approximation` is
the deviation in that unit: at most 1 is near) (CAD printing rounds
every coefficient, and the normals amplify that by the conditioning of the map; a coefficient
moved by ``10⁻³`` or ``10⁻⁶`` stays far outside).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..recognition.symmetry import CYLINDER, PLANE, REVOLUTION, SPHERE
from ..results import ApproximateAxis, Approximation, map_near_limit
from ..rounded.line_complex import (
    Samples,
    axis_of,
    cone_apex,
    motions,
    normal_lines,
    normal_miss,
    rotation_axis,
    translation_direction,
)
from .maps import RationalMap

COARSEST = 0.1
"""A rounding coarser than this (``0.5``, ``3.0``: a gallery's exact numbers) says nothing: the
input is taken as exact."""
GRID = 24
"""Samples per parameter over :data:`SPAN`."""
SPAN = 2.0
"""The samples lie in ``[−SPAN, SPAN]²`` of the parameter plane."""
FLOAT_FLOOR = 4e-15
"""The finest relative rounding a printed map is read at: its points and normals are sampled in
double precision (a torus's map printed with 17 digits was 7.9 times outside a rounding of
``5·10⁻¹⁷``), as an equation's coefficients are (docs/math.md §8.1)."""
SINE_FLOOR = 0.1
"""Normals within this sine of the axis direction are left out of the distance to the axis."""

_DECIMAL = re.compile(
    r"(?<![A-Za-z0-9_.])([0-9]*)\.([0-9]*)(?:(?:[eEdD]|\*\^)[-+−]?[0-9]+)?"
    r"|(?<![A-Za-z0-9_.])([0-9]+)(?:[eEdD]|\*\^)[-+−]?[0-9]+"
)


@dataclass(frozen=True)
class NearCone:
    """A cone's apex (or a cylinder's unit direction) within the rounding, with its deviation."""

    apex: tuple[float, float, float] | None
    direction: tuple[float, float, float] | None
    residual: float


def printed_tolerance(text: str) -> float | None:
    """The relative rounding of the decimals of ``text`` (``None``: no decimal), at least
    :data:`FLOAT_FLOOR`. Printed with significant digits (``%g``: no fraction ends in ``0``), the
    rounding of the most precise one, ``0.5·10^(1−k)`` for ``k`` digits: short exact numbers
    (``1.5``) stand beside the rounded ones. Printed with fixed decimals (``%.6f``: some fraction
    ends in ``0``), each literal's own last place counts, relative to its size or to 1, and the
    coarsest is taken: ``0.071392`` is as rounded as ``0.781639``, and the ``100.125000`` of a
    translation had made it ``5·10⁻⁹`` (the rotation's entries are off by ``5·10⁻⁷``)."""
    literals = [
        ((m.group(1) or "") + (m.group(2) or "") if m.group(3) is None else m.group(3), m)
        for m in _DECIMAL.finditer(text)
    ]
    if not literals:
        return None
    fixed = [m for _, m in literals if m.group(3) is None and m.group(0) == f"{m.group(1)}.{m.group(2)}"]
    if any(m.group(2).endswith("0") for m in fixed):
        coarsest = max(0.5 * 10.0 ** -len(m.group(2)) / max(1.0, abs(float(m.group(0) + "0"))) for m in fixed)
        return max(coarsest, FLOAT_FLOOR)
    digits = max(len(written.lstrip("0")) or 1 for written, _ in literals)
    return max(0.5 * 10.0 ** (1 - digits), FLOAT_FLOOR)


def _samples(surface: RationalMap) -> Samples | None:
    """The map's points and unit normals on the :data:`GRID` × :data:`GRID` parameter grid
    (poles and points far beyond the rest left out); ``None`` when too few are finite."""
    grid = np.linspace(-SPAN, SPAN, GRID)
    s, t = (a.ravel() for a in np.meshgrid(grid, grid))
    ring = surface.ring
    Xs, Xt, Ws, Wt = surface.derivatives
    X, XS, XT = (np.array([_evaluate(ring, p, s, t) for p in vector]) for vector in (surface.X, Xs, Xt))
    W, WS, WT = (_evaluate(ring, p, s, t) for p in (surface.W, Ws, Wt))
    with np.errstate(all="ignore"):
        points = (X / W).T
        normals = np.cross(((XS * W - X * WS) / W**2).T, ((XT * W - X * WT) / W**2).T)
        length = np.linalg.norm(normals, axis=1)
        distance = np.linalg.norm(points, axis=1)
    finite = np.isfinite(length) & np.all(np.isfinite(points), axis=1)
    if finite.sum() < 12:
        return None
    keep = finite & (length > 1e-12 * float(np.max(length[finite])))
    keep &= distance < 1e3 * (float(np.median(distance[finite])) + 1.0)
    if keep.sum() < 12:
        return None
    return Samples(points[keep], normals[keep] / length[keep, None])


def _evaluate(ring: Any, p: Any, s: np.ndarray, t: np.ndarray) -> np.ndarray:
    total = np.zeros_like(s)
    for (i, j), c in ring.terms(p):
        total = total + _float(ring, c) * s**i * t**j
    return total


def _float(ring: Any, c: Any) -> float:
    return float(c) if ring.is_flint else float(ring.K.to_sympy(c).evalf(20))


NOTES = (
    "the deviation is the largest distance of the normal lines to the axis (to the centre), "
    f"relative to the size of the sampled patch, over the parameters in [{-SPAN:g}, {SPAN:g}]²",
    "no nearest exact surface is computed for a parametrization",
)


def nearly(surface: RationalMap, tolerance: float, source: str) -> tuple[Approximation, NearCone | None]:
    """The approximation of the symmetry (an :class:`Approximation` as rounded equations get,
    ``source`` ``input`` or ``given``) and, when the surface is near no surface of revolution,
    a near cone or cylinder."""
    samples = _samples(surface)
    if samples is None:
        return Approximation(tolerance, source, False, None, None, None, (), notes=(_FEW,)), None
    relative, _vectors = normal_lines(samples)
    gate = min(1e-2, 1e4 * tolerance)
    small = int(sum(v <= gate for v in relative))
    singular = tuple(float(v) for v in relative)
    found = _nearest_kind(samples, small)
    if found is None:
        axis = rotation_axis(samples)
        deviation = None if axis is None else _axis_deviation(samples, axis)
        along = deviation is not None and not math.isfinite(deviation)
        deviation = None if along else deviation
        residual = None if deviation is None else deviation / map_near_limit(tolerance)
        why = (
            f"not near any continuous symmetry: the smallest singular value of (★) is {singular[-1]:.4g}, "
            f"above {gate:.4g}, so no kind is tried"
            if small == 0
            else f"{small} singular value(s) of (★) are at most {gate:.4g}, but no kind of symmetry could be "
            "measured on the sampled patch"
        )
        far = (
            why
            + ("" if deviation is None else " (the residual is that of the best rotation axis)")
            + (
                f"; the sampled normals all lie along the best rotation axis (within {SINE_FLOOR:g}), "
                "so their distance from it is not measured"
                if along
                else ""
            )
        )
        approximation = Approximation(
            tolerance, source, False, None, deviation, residual, singular, notes=(far, *NOTES)
        )
        return approximation, _near_cone(samples, tolerance)
    kind, deviation, axis, center, normal = found
    near = deviation <= map_near_limit(tolerance)
    approximation = Approximation(
        tolerance,
        source,
        near,
        kind,
        deviation,
        deviation / map_near_limit(tolerance),
        singular,
        axis=axis,
        center=center,
        normal=normal,
        notes=NOTES,
    )
    return approximation, None if near else _near_cone(samples, tolerance)


_FEW = "too few sample points of the map are finite to solve the systems in floating point"
Found = tuple[str, float, ApproximateAxis | None, tuple[float, float, float] | None, tuple[float, float, float] | None]


def _nearest_kind(samples: Samples, small: int) -> Found | None:
    """The most symmetric kind the ``small`` singular values allow (the candidates of
    :func:`~sorgui.engine.rounded.line_complex.motions`), with its relative deviation."""
    p, n, size = samples.points, samples.normals, samples.size
    for count in (3, 2, 1):
        if small < count:
            continue
        best: Found | None = None
        for candidate in motions(samples, count):
            if candidate.kind == SPHERE and candidate.point is not None:
                c = candidate.point
                deviation = float(np.max(np.linalg.norm(np.cross(p - c, n), axis=1))) / size
                found: Found = (SPHERE, deviation, None, _vector(c), None)
            elif candidate.kind == PLANE and candidate.direction is not None:
                d = candidate.direction / np.linalg.norm(candidate.direction)
                found = (PLANE, float(np.max(np.linalg.norm(np.cross(n, d), axis=1))), None, None, _vector(d))
            elif candidate.kind in (REVOLUTION, CYLINDER) and candidate.point is not None:
                assert candidate.direction is not None
                axis = axis_of(candidate.point, candidate.direction, np.zeros(3))
                found = (candidate.kind, _axis_deviation(samples, axis), axis, None, None)
            else:
                continue
            if not math.isfinite(found[1]):  # no normal far enough from the axis to measure it
                continue
            if best is None or found[1] < best[1]:
                best = found
        if best is not None:
            return best
    return None


def _axis_deviation(samples: Samples, axis: ApproximateAxis) -> float:
    """The largest distance of the normal lines to the axis (:func:`normal_miss`), relative to
    the samples' size, over the normals at least :data:`SINE_FLOOR` away from its direction
    (a normal nearly along the axis meets it anywhere within the rounding)."""
    sine = np.linalg.norm(np.cross(samples.normals, np.array(axis.direction)), axis=1)
    keep = sine >= SINE_FLOOR
    if not np.any(keep):
        return math.inf
    return float(np.max(normal_miss(samples, axis)[keep])) / samples.size


def _near_cone(samples: Samples, tolerance: float) -> NearCone | None:
    """A cone whose tangent planes pass within the rounding of one apex, else a cylinder whose
    normals are within it of perpendicular to one direction, else ``None``."""
    n, p, size = samples.normals, samples.points, samples.size
    singular = np.linalg.svd(n, compute_uv=False)
    if singular[-1] <= map_near_limit(tolerance) * singular[0]:
        a = translation_direction(samples)
        a = a if a[int(np.argmax(np.abs(a)))] > 0 else -a
        deviation = float(np.max(np.abs(n @ a)))
        return NearCone(None, _vector(a), deviation) if deviation <= map_near_limit(tolerance) else None
    apex = cone_apex(samples)
    deviation = float(np.max(np.abs(np.sum((p - apex) * n, axis=1)))) / size
    return NearCone(_vector(apex), None, deviation) if deviation <= map_near_limit(tolerance) else None


def _vector(v: np.ndarray) -> tuple[float, float, float]:
    return float(v[0]), float(v[1]), float(v[2])
