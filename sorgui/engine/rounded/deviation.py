"""How far apart two zero sets are, inside the ball the viewport shows (docs/math.md §8).

The ball is the viewport's: centred on the axis (or the centre), with a radius taken from the
real points of the surface on a star of lines through that centre (the 13 axes and diagonals
of a cube and an axis frame), far points of unbounded branches dropped. Points of each zero set
are sampled on random lines through the ball (the real roots of the restriction, found by a DFT
and companion matrices) and moved onto the other zero set by Newton steps along the gradient;
the deviation is the largest distance moved, both ways (a sampled Hausdorff distance).
"""

from __future__ import annotations

import math
from itertools import product

import numpy as np

from sorgui.numerics import real_roots

from . import dense
from .dense import FloatArray

MIN_RADIUS = 1.0
"""The smallest ball drawn for a surface of unit size or more (:func:`natural_length`)."""
SMALLEST_RADIUS = 1.0e-6
"""The smallest ball drawn for a small part: one measured in metres (a torus 4 cm across,
``R = 0.03``) was drawn a speck in a ball of radius 2, and one of 0.4 mm not at all, when every
ball's radius was at least :data:`MIN_RADIUS`."""
MAX_RADIUS = 1.0e4
"""The largest ball drawn for an unbounded surface (its far branches dropped, :func:`view_ball`),
unless the part itself is larger (:data:`PART_SIZES`)."""
PART_SIZES = 4.0
"""An unbounded part of size ``L`` (:func:`size_about`) larger than :data:`MAX_RADIUS` is drawn in
a ball of radius up to this many times ``L``: a cylinder of radius 20,000 had the ball of radius
10,000 about its axis, which held none of it, and no file was written."""
NO_POINTS_RADIUS = 2.0
"""The ball's radius when no line through the centre meets the surface away from it (a cone
about its apex, a plane through the centre)."""
MARGIN = 1.25
SPREAD = 3.0
LINES = 160
NEWTON_STEPS = 6
CONVERGED = 1e-9


def probe_directions(axis: FloatArray | None) -> list[FloatArray]:
    """The 13 directions of a cube's axes and diagonals, plus an axis frame if there is one."""
    directions = [np.array(d, dtype=float) for d in product((-1, 0, 1), repeat=3)]
    directions = [d / np.linalg.norm(d) for d in directions if next((x for x in d if x), 0) > 0]
    if axis is not None:
        a = axis / np.linalg.norm(axis)
        e = np.zeros(3)
        e[int(np.argmin(np.abs(a)))] = 1.0
        u = np.cross(a, e)
        u /= np.linalg.norm(u)
        w = np.cross(a, u)
        directions += [a, u, w, (u + w) / np.sqrt(2), (u - w) / np.sqrt(2)]
    return directions


MERIDIAN_LINES = 48
"""Lines through the centre in one plane through the axis (every 3.75°): a surface of revolution
is the same in every such plane, so they see every part of it that a ball about the centre can
hold, the small far ones too (a torus high up the axis of a product of three)."""

SPHERE_LINES = 96
"""Lines through the centre in directions spread over the sphere, for a surface without an axis."""


def extent_directions(axis: FloatArray | None) -> list[FloatArray]:
    """The directions the view ball probes: :func:`probe_directions`, and a meridian star about
    the axis (or directions spread over the sphere without one)."""
    directions = probe_directions(axis)
    if axis is not None:
        a = axis / np.linalg.norm(axis)
        u = directions[-4]  # the frame's u ⟂ a (probe_directions)
        angles = np.pi * np.arange(MERIDIAN_LINES) / MERIDIAN_LINES
        directions += [np.cos(t) * a + np.sin(t) * u for t in angles]
    else:
        k = np.arange(SPHERE_LINES) + 0.5  # a Fibonacci lattice on the half sphere z > 0
        z = k / SPHERE_LINES
        phi = np.pi * (1 + 5**0.5) * k
        r = np.sqrt(1 - z * z)
        directions += list(np.column_stack([r * np.cos(phi), r * np.sin(phi), z]))
    return directions


def is_bounded(array: FloatArray, directions: list[FloatArray]) -> bool:
    """Whether the top-degree form of ``f`` keeps one strict sign on ``directions``: then (as
    far as they tell) ``f = 0`` has no real points at infinity and its real part is bounded."""
    degree = array.shape[0] - 1
    i, j, k = np.indices(array.shape)
    top = np.where(i + j + k == degree, array, 0.0)
    values = dense.evaluate(top, np.array(directions))
    largest = float(np.abs(values).max(initial=0.0))
    return largest > 0 and bool(np.all(values > 1e-9 * largest) or np.all(values < -1e-9 * largest))


def view_ball(
    array: FloatArray, center: FloatArray, axis: FloatArray | None = None, *, whole: bool = False
) -> tuple[FloatArray, float]:
    """The ball that shows the real surface ``f = 0`` around ``center``: a bounded surface
    (:func:`is_bounded`) whole, from its real points on the lines of :func:`extent_directions`
    through ``center``; an unbounded one from its real points on the lines of
    :func:`probe_directions`, those farther than ``SPREAD`` times the median distance dropped
    (far branches). Centred on the middle of the points kept (along the axis, if any), radius
    ``MARGIN`` times the farthest, at least :func:`natural_length`, at most ``MAX_RADIUS`` (or
    ``PART_SIZES`` times the part's size, when that is larger); with
    ``whole`` (the drawn scene's ball) a bounded surface's is not capped (a sphere of radius 30,000
    was looked for in a ball of radius 10,000). The deviation of two zero sets keeps the cap: the
    candidates' balls decide which nearest surface is chosen."""
    directions = extent_directions(axis)
    bounded = is_bounded(array, directions)
    if not bounded:
        directions = probe_directions(axis)
    # each line in steps of the part's size: its restriction is read off values at that distance
    # (a sphere of radius 3e6 had, from values at distance 1, a leading coefficient of 1e-13 of
    # the largest, taken for noise, and no point at all)
    length = size_about(array, center) or 1.0
    steps = [length * d for d in directions]
    points = [center + t * step for step in steps for t in real_roots(dense.restriction_to_line(array, center, step))]
    pts = np.array(points).reshape(-1, 3)
    distances = np.linalg.norm(pts - center, axis=1)
    positive = distances[distances > 1e-9 * max(1.0, float(np.linalg.norm(center)))]
    if len(positive) == 0:
        return center, NO_POINTS_RADIUS
    far = distances.max() if bounded else SPREAD * float(np.median(positive))
    core = pts[distances <= min(distances.max(), far)]
    if axis is not None:
        a = axis / np.linalg.norm(axis)
        heights = (core - center) @ a
        middle = center + 0.5 * (heights.min() + heights.max()) * a
    else:
        middle = 0.5 * (core.min(axis=0) + core.max(axis=0))
    radius = MARGIN * float(np.linalg.norm(core - middle, axis=1).max())
    largest = math.inf if bounded and whole else max(MAX_RADIUS, PART_SIZES * length)  # a bounded part whole
    return middle, float(np.clip(radius, _clipped(length), largest))


TRANSLATION_NOISE = 1e-12
"""Coefficients of ``f`` about the ball's middle below this share of the largest are rounding
noise of the translation (:func:`natural_length`)."""


def natural_length(array: FloatArray, middle: FloatArray | None = None) -> float:
    """The length at which the lowest and highest homogeneous parts of ``f`` about ``middle``
    (the surface's own centre, exact; the origin if not given) weigh alike,
    ``(|f_low| / |f_high|)^(1/(high − low))``, between :data:`SMALLEST_RADIUS` and
    :data:`MIN_RADIUS`: the floor of the view ball's radius. A small part (``x² + y² − 2.5e-5``:
    0.005) gets a ball of its size wherever it is (a sphere of radius 0.005 about
    ``(0.3, 0.2, 0)`` had the floor 0.36 about the origin, and was drawn with 52 triangles); a
    cone about its apex, whose numerical roots near the apex are noise of about 10⁻⁵, keeps the
    floor of 1 (its parts are all of one degree; about the middle of those roots they were not,
    and a cubic cone was drawn in a ball 6e-6 across)."""
    return _clipped(size_about(array, middle) if middle is not None else part_size(array))


def _clipped(length: float | None) -> float:
    """A part's size as the floor of a view ball's radius (:func:`natural_length`)."""
    return MIN_RADIUS if length is None else float(np.clip(length, SMALLEST_RADIUS, MIN_RADIUS))


def size_about(array: FloatArray, middle: FloatArray) -> float | None:
    """:func:`part_size` of ``f`` about ``middle`` (of ``f`` itself when that has none; ``None``
    when neither has a finite one): the unclipped length of :func:`natural_length`."""
    moved = dense.translated(array, middle)
    largest = float(np.abs(moved).max(initial=0.0))
    moved[np.abs(moved) <= TRANSLATION_NOISE * largest] = 0.0  # a shift by 5e-16 made terms of 1e-46
    for length in (part_size(moved), part_size(array)):
        if length is not None and math.isfinite(length):
            return length
    return None


def part_size(array: FloatArray) -> float | None:
    """``(|f_low| / |f_high|)^(1/(high − low))``, unclipped (:func:`natural_length`); ``None``
    when ``f`` is zero or homogeneous (a cone about the origin has no size), or beyond floats."""
    i, j, k = np.indices(array.shape)
    degrees = (i + j + k).ravel()
    values = np.abs(array).ravel()
    largest = float(values.max(initial=0.0))
    if largest == 0 or not math.isfinite(largest):  # 1e400 is inf in floats: no size to read
        return None
    sizes = np.bincount(degrees, weights=(values / largest) ** 2)
    present = np.nonzero(sizes)[0]
    low, high = int(present.min()), int(present.max())
    if high == low:
        return None
    return float((np.sqrt(sizes[low]) / np.sqrt(sizes[high])) ** (1.0 / (high - low)))


def sample_zero_set(array: FloatArray, center: FloatArray, radius: float, seed: int = 0) -> FloatArray:
    """Real points of ``f = 0`` inside the ball, on ``LINES`` random lines through it."""
    rng = np.random.default_rng(seed)
    found = []
    for _ in range(LINES):
        start = center + radius * rng.uniform(-0.5, 0.5, 3)
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        for t in real_roots(dense.restriction_to_line(array, start, direction)):
            p = start + t * direction
            if np.linalg.norm(p - center) <= radius:
                found.append(p)
    return np.array(found).reshape(-1, 3)


def distance_to_zero_set(array: FloatArray, points: FloatArray) -> FloatArray:
    """How far Newton steps along the gradient move each point onto ``f = 0`` (points where the
    steps do not converge, next to a singular point, are left out)."""
    moved = points.copy()
    for _ in range(NEWTON_STEPS):
        values = dense.evaluate(array, moved)
        grads = dense.gradient(array, moved)
        norms = np.einsum("ij,ij->i", grads, grads)
        safe = norms > 0
        step = np.zeros_like(moved)
        step[safe] = (values[safe] / norms[safe])[:, None] * grads[safe]
        moved -= step
    converged = np.abs(dense.evaluate(array, moved)) <= CONVERGED * (1.0 + np.abs(dense.evaluate(array, points)))
    distances: FloatArray = np.linalg.norm(moved - points, axis=1)[converged]
    return distances


def max_deviation(first: FloatArray, second: FloatArray, center: FloatArray, axis: FloatArray | None) -> float | None:
    """The largest distance between the zero sets of two polynomials (dense arrays in the same
    coordinates) inside the view ball of ``second``; ``None`` when neither has real points there
    that Newton's steps move onto the other (every sample next to a singular point, say). When
    ``second`` has points there but ``first`` has none and no step from ``second``'s reaches it,
    the zero sets are far apart: the distance of ``second``'s points from ``first``'s in its own
    view ball (a small torus printed with 5 digits is a larger blob, and "-" was said)."""
    ball, radius = view_ball(second, center, axis)
    distances = [np.zeros(0)]
    clouds = []
    for source, target in ((second, first), (first, second)):
        points = sample_zero_set(source, ball, radius)
        clouds.append(points)
        if len(points):
            distances.append(distance_to_zero_set(target, points))
    moved = np.concatenate(distances)
    if moved.size:
        return float(moved.max())
    if len(clouds[0]):
        own = sample_zero_set(first, *view_ball(first, center, axis))
        return _cloud_distance(clouds[0], own) if len(own) else None
    return None


def axis_centre(array: FloatArray, point: FloatArray, direction: FloatArray) -> FloatArray:
    """The point of the axis through ``point`` along ``direction`` about which ``f`` lies: the mean
    of the roots of ``f`` on the axis (a torus's centre, a paraboloid's vertex, a cone's apex,
    whether the roots are real or not); ``point`` when ``f`` is constant along the axis (a
    cylinder). The recognizer's point of the axis may be far from a small part: the lines
    through it that look for the part missed a torus of radii 0.03 and 0.007 centred 2.8 away."""
    unit = direction / np.linalg.norm(direction)
    coefficients = dense.restriction_to_line(array, point, unit)
    significant = np.nonzero(np.abs(coefficients) > 1e-12 * np.abs(coefficients).max(initial=0.0))[0]
    if len(significant) == 0 or significant.max() == 0:
        return point
    d = int(significant.max())
    centre: FloatArray = point - float(coefficients[d - 1] / (d * coefficients[d])) * unit
    return centre


def _cloud_distance(first: FloatArray, second: FloatArray) -> float:
    """The largest distance from a point of either sample to the nearest point of the other (the
    Hausdorff distance of the samples): the zero sets' deviation where Newton's steps from one
    do not reach the other."""
    squares = (first**2).sum(axis=1)[:, None] + (second**2).sum(axis=1)[None, :] - 2.0 * first @ second.T
    gaps = np.sqrt(np.maximum(squares, 0.0))
    return float(max(gaps.min(axis=1).max(), gaps.min(axis=0).max()))
