"""The real profile of a surface of revolution in a meridian half-disk, as arcs to fit (docs/math.md §11).

The 3D view traces the profile ``p(x, y) = 0`` in a plane through the axis (a contour of a grid,
``sorgui.render.profile_curve``); that trace is pieced together here into the arcs a CAD part
needs, in the orthonormal frame of :class:`MeridianCurve` (``x`` along the axis, ``y ≥ 0``):

* the polylines are cut to the half-plane ``y ≥ 0`` and at their corners (a node or a cusp, where
  the tracing turns into another branch), every point moved onto ``p = 0`` by Newton's method;
* a piece traced twice is kept once;
* an end near the ball's boundary is moved onto the boundary's intersection with the profile (a
  root of ``p(m + R·cos θ, R·sin θ)``), an end near the axis onto a root of ``p(x, 0)``;
* the other ends are joined: two that continue one another, across a gap the tracing left; ends
  meeting at a singular point of the profile (``∇p = 0``, found by Newton's method on ``∇p``)
  all end there, so that the faces turned from them share that circle.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import mpmath
import numpy as np
import sympy

from sorgui.engine.results import Profile
from sorgui.engine.values import ExpressionError, Terms, polynomial_terms, read_expression
from sorgui.render import ClipSphere

from .geometry import Frame, polyline_distance
from .plane_curve import PlaneCurve

SHIFT_BITS = 8
"""The shift of a meridian curve's origin is a multiple of ``2⁻⁸``: exact, and small to write."""

CORNER = math.radians(25)
"""A turn of the traced polyline sharper than this is a singular point of the profile (a node or
a cusp, where the tracing turns into another branch): the branch is cut there."""

CLOSED = 0.25
"""Two free ends closer than this many tracing steps already meet: joined without a trace."""
REACH = 3.0
"""Ends closer than this many tracing steps are joined, or moved onto the ball or the axis."""

BOUNDARY_SAMPLES = 8192
"""Samples of the ball's half circle at which the profile's sign changes are looked for."""


DIGITS = 60
"""Digits with which the profile's exact coefficients are shifted, before rounding them once."""


@dataclass(frozen=True)
class MeridianCurve:
    """The profile ``p(x, y) = 0`` in an orthonormal ``frame`` whose point is moved along the
    axis next to the ball's centre, as a :class:`~.plane_curve.PlaneCurve` scaled by the ball's
    radius. The shift is done with :data:`DIGITS` digits on the exact ``p``: rounding the
    coefficients of ``p`` about a far origin moves a degree-12 profile by 1e-3 and leaves
    Newton's method stuck in that noise; about the drawn region it moves it by 1e-13."""

    curve: PlaneCurve
    frame: Frame


def meridian_curve(profile: Profile, frame: Frame, ball: ClipSphere) -> MeridianCurve:
    """The profile about the foot of the ball's centre on the axis (see :class:`MeridianCurve`)."""
    x, y = sympy.symbols("x y")
    foot = float(frame.to_plane(np.array([ball.center]))[0, 0])
    shift = sympy.Rational(round(foot * 2**SHIFT_BITS), 2**SHIFT_BITS)
    try:
        exact = sympy.Poly(read_expression(profile.polynomial), x, y)
        terms = _shifted(exact, shift)
    except (ExpressionError, sympy.PolynomialError, TypeError, ValueError):
        terms, shift = polynomial_terms(profile.polynomial, ("x", "y")), sympy.Integer(0)
    point = frame.point + float(shift) * frame.direction
    return MeridianCurve(PlaneCurve.from_terms(terms, ball.radius), Frame(point, frame.direction, frame.normal))


def _shifted(poly: sympy.Poly, shift: sympy.Rational) -> Terms:
    """The terms of ``p(x + shift, y)`` (Taylor's shift with :data:`DIGITS` digits, rounded once)."""
    with mpmath.workdps(DIGITS):
        s = mpmath.mpf(shift.p) / shift.q
        moved: dict[tuple[int, int], mpmath.mpf] = {}
        for (i, j), c in poly.terms():
            value = mpmath.mpf(str(sympy.N(c, DIGITS)))
            for k in range(i + 1):
                moved[(k, j)] = moved.get((k, j), mpmath.mpf(0)) + value * math.comb(i, k) * s ** (i - k)
        return [(m, float(v)) for m, v in moved.items() if v != 0]


@dataclass(frozen=True)
class Arc:
    """Ordered points on ``p = 0`` in the half-plane ``y ≥ 0`` (meridian coordinates); a
    ``closed`` arc is a loop whose last point is not repeated."""

    points: np.ndarray
    closed: bool = False


def profile_arcs(polylines: Sequence[np.ndarray], curve: MeridianCurve, ball: ClipSphere) -> list[Arc]:
    """The arcs of the real profile inside ``ball`` from the traced polylines (3D points)."""
    pieces = _pieces(polylines, curve)
    if not pieces:
        return []
    step = float(np.percentile(np.concatenate([_lengths(p) for p in pieces]), 95))
    pieces = [part for piece in pieces for part in _faithful(piece, curve.curve)]
    pieces = _once(pieces, step / 20)
    centre = np.array([float(curve.frame.to_plane(np.array([ball.center]))[0, 0]), 0.0])
    boundary = _boundary_points(curve.curve, centre, ball.radius)
    targets = [*boundary, *_axis_points(curve.curve, centre, ball.radius)]
    pieces = [_to_targets(p, targets, REACH * step) for p in pieces]
    graph = _Graph(curve.curve, step, centre, ball.radius, boundary, pieces)
    graph.join()
    graph.extend()
    graph.join()
    arcs = _chains(graph.pieces, graph.links)
    axis = _axis_points(curve.curve, centre, ball.radius)
    return _at_axis(arcs, axis, step, step / 4)


def _at_axis(arcs: list[Arc], axis: list[np.ndarray], reach: float, near: float) -> list[Arc]:
    """The arcs cut where they touch the axis (a profile tangent to it there, as ``y = x²``:
    the faces turned from the two sides meet at that pole), what is then traced twice kept once."""
    pieces: list[np.ndarray] = []
    loops = [a for a in arcs if a.closed]
    for arc in arcs:
        if arc.closed:
            continue
        points = arc.points
        for target in axis:
            distance = np.linalg.norm(points[1:-1] - target, axis=1)
            if len(distance) and distance.min() <= reach:
                i = int(np.argmin(distance)) + 1
                head, tail = points[: i + 1].copy(), points[i:].copy()
                head[-1], tail[0] = target, target
                pieces.append(head)
                points = tail
        pieces.append(points)
    return loops + [Arc(p) for p in _once(pieces, near) if len(p) >= 2]


def _pieces(polylines: Sequence[np.ndarray], curve: MeridianCurve) -> list[np.ndarray]:
    """The polylines cut to ``y ≥ 0`` and at their corners, moved onto the profile."""
    out = []
    for line in polylines:
        xy = curve.frame.to_plane(line)
        for run in _runs_above_axis(xy):
            out += [part for part in _smooth_parts(curve.curve.onto(run)) if len(part) >= 2]
    return out


def _lengths(points: np.ndarray) -> np.ndarray:
    return np.asarray(np.linalg.norm(np.diff(points, axis=0), axis=1))


def _smooth_parts(xy: np.ndarray) -> list[np.ndarray]:
    """The polyline without repeated points (Newton's method gathers them at a singular point),
    cut at its corners."""
    steps = _lengths(xy)
    keep = np.concatenate([[True], steps > 1e-9 * max(1.0, float(np.abs(xy).max()))])
    xy = xy[keep]
    if len(xy) < 3:
        return [xy]
    seg = np.diff(xy, axis=0)
    cos = np.einsum("ij,ij->i", seg[:-1], seg[1:]) / (
        np.linalg.norm(seg[:-1], axis=1) * np.linalg.norm(seg[1:], axis=1)
    )
    corners = np.nonzero(cos < math.cos(CORNER))[0] + 1
    return [xy[a : b + 1] for a, b in zip([0, *corners], [*corners, len(xy) - 1])]


def _runs_above_axis(xy: np.ndarray) -> list[np.ndarray]:
    """The runs of a polyline with ``y ≥ 0``, each crossing of ``y = 0`` interpolated onto it."""
    runs: list[np.ndarray] = []
    current: list[np.ndarray] = []
    for k, point in enumerate(xy):
        if point[1] >= 0:
            if not current and k > 0 and xy[k - 1][1] < 0:
                current.append(_crossing(xy[k - 1], point))
            current.append(point)
        elif current:
            current.append(_crossing(current[-1], point))
            runs.append(np.array(current))
            current = []
    if current:
        runs.append(np.array(current))
    return runs


def _crossing(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    lam = p[1] / (p[1] - q[1])
    return np.array([p[0] + lam * (q[0] - p[0]), 0.0])


def _once(pieces: list[np.ndarray], near: float) -> list[np.ndarray]:
    """The pieces without the runs of segments that an earlier (longer) piece already passes
    within ``near`` of (at the segment's middle): the tracing can run along a branch twice."""
    kept: list[np.ndarray] = []
    for piece in sorted(pieces, key=lambda p: -float(_lengths(p).sum())):
        middles = (piece[:-1] + piece[1:]) / 2
        covered = np.zeros(len(middles), dtype=bool)
        for other in kept:
            covered |= polyline_distance(middles, other) <= near
        fresh = np.flatnonzero(~covered)
        for run in np.split(fresh, np.flatnonzero(np.diff(fresh) > 1) + 1):
            if len(run):
                kept.append(piece[run[0] : run[-1] + 2])
    return kept


def _boundary_points(poly: PlaneCurve, centre: np.ndarray, radius: float) -> list[np.ndarray]:
    """Where the profile crosses the ball's half circle ``centre + R·(cos θ, sin θ)``, ``θ ∈ (0, π)``:
    the sign changes of ``p`` along it, refined by bisection."""

    def at(theta: np.ndarray) -> np.ndarray:
        return centre + radius * np.column_stack([np.cos(theta), np.sin(theta)])

    theta = np.linspace(0.0, math.pi, BOUNDARY_SAMPLES)
    values = poly.value_and_gradient(at(theta))[0]
    found = []
    for k in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0):
        low, high = float(theta[k]), float(theta[k + 1])
        sign_low = np.sign(values[k])
        for _ in range(60):
            middle = (low + high) / 2
            value = poly.value_and_gradient(at(np.array([low, middle])))[0]
            if np.sign(value[1]) == sign_low:
                low = middle
            else:
                high = middle
        found.append(at(np.array([(low + high) / 2]))[0])
    return found


def _axis_points(poly: PlaneCurve, centre: np.ndarray, radius: float) -> list[np.ndarray]:
    """Where the profile meets the axis inside the ball: the real roots of ``p(x, 0)``. A root
    of multiplicity ``k`` comes out of the eigenvalues as ``k`` roots about it; the mean of such
    a cluster is the root (to rounding), so clusters are merged before Newton's method polishes
    the simple ones."""
    column = poly.coefficients[:, 0]
    nonzero = np.flatnonzero(column)
    if len(nonzero) == 0 or nonzero[-1] == 0:
        return []
    roots = np.roots(column[: nonzero[-1] + 1][::-1]) * poly.length
    found: list[list[complex]] = []
    for root in sorted(roots, key=lambda r: r.real):
        if found and abs(root - np.mean(found[-1])) <= 1e-3 * radius:
            found[-1].append(root)
        else:
            found.append([root])
    points = []
    for cluster in found:
        middle = complex(np.mean(cluster))
        if abs(middle.imag) > 1e-9 * radius:
            continue
        point = np.array([[middle.real, 0.0]])
        if len(cluster) == 1:
            point = poly.onto(point, steps=20)
        if abs(point[0, 0] - centre[0]) <= radius * (1 + 1e-9):
            points.append(point[0])
    return points


def _to_targets(piece: np.ndarray, targets: Sequence[np.ndarray], reach: float) -> np.ndarray:
    """``piece`` with each end that lies within ``reach`` of a boundary or axis point moved onto
    it (the nearest)."""
    if not targets:
        return piece
    points = np.array(targets)
    out = piece.copy()
    for index in (0, -1):
        distance = np.linalg.norm(points - out[index], axis=1)
        k = int(np.argmin(distance))
        if distance[k] <= reach:
            out[index] = points[k]
    return _distinct_ends(out)


def _distinct_ends(piece: np.ndarray) -> np.ndarray:
    """``piece`` without inner points that coincide with (or lie beyond) a moved end."""
    if len(piece) <= 2:
        return piece
    keep = np.ones(len(piece), dtype=bool)
    tiny = 1e-9 * max(1.0, float(np.abs(piece).max()))
    for end, neighbour in ((0, 1), (-1, -2)):
        if np.linalg.norm(piece[end] - piece[neighbour]) <= tiny:
            keep[neighbour] = False
    return piece[keep] if keep.sum() >= 2 else piece[[0, -1]]


End = tuple[int, int]
"""A piece's end: ``(piece, 0)`` its first point, ``(piece, -1)`` its last."""

Links = dict[End, tuple[End, np.ndarray]]
"""Each joined end, the end it is joined to and the points between them (from the first to the
second; none where they meet)."""


TRACE_STEPS = 4000
"""The most steps a trace along the profile takes."""


@dataclass
class _Trace:
    """Points traced along the profile from an end, and why the tracing stopped: ``"boundary"``,
    ``"axis"`` (its last point is on them), ``"end"`` (it came to the end ``hit`` of a piece),
    ``"node"`` (to a singular point inside the piece ``hit[0]``, at its vertex ``hit[1]``),
    ``"singular"`` (its last point is a singular point) or ``"lost"``."""

    points: list[np.ndarray]
    reason: str
    hit: End | None = None


class _Graph:
    """The pieces of the traced profile and the links that join their ends into arcs."""

    def __init__(
        self,
        poly: PlaneCurve,
        step: float,
        centre: np.ndarray,
        radius: float,
        boundary: list[np.ndarray],
        pieces: list[np.ndarray],
    ) -> None:
        self.poly, self.step, self.centre, self.radius = poly, step, centre, radius
        self.boundary = np.array(boundary).reshape(-1, 2)
        self.pieces = pieces
        self.links: Links = {}

    def free(self) -> list[End]:
        """The ends neither on the ball's boundary, nor on the axis, nor joined."""
        out = []
        for k, piece in enumerate(self.pieces):
            for index in (0, -1):
                q = piece[index]
                on_ball = abs(float(np.linalg.norm(q - self.centre)) - self.radius) <= 1e-9 * self.radius
                if not on_ball and q[1] > 1e-12 * self.radius and (k, index) not in self.links:
                    out.append((k, index))
        return out

    def join(self) -> None:
        """Join the free ends that lie together: through the singular point where they meet at one
        (continuing branches paired, the others ending there), along the profile otherwise."""
        reach = REACH * self.step
        pieces = self.pieces
        for cluster in _clusters(self.free(), pieces, reach):
            singular = _singular_point(self.poly, np.mean([pieces[k][i] for k, i in cluster], axis=0), reach)
            if singular is None:
                for a, b in _pairs(cluster, pieces, reach, smooth=False):
                    if np.linalg.norm(pieces[a[0]][a[1]] - pieces[b[0]][b[1]]) <= CLOSED * self.step:
                        # the ends already meet (a loop traced whole): a trace from one to the other
                        # went round the loop again, and the part was the solid turned twice
                        _link(self.links, a, b, np.zeros((0, 2)))
                        continue
                    trace = self.trace(pieces[a[0]][a[1]], _tangent(pieces[a[0]], a[1]), target=b)
                    between = trace.points[:-1] if trace.reason == "end" else []
                    _link(self.links, a, b, np.array(between).reshape(-1, 2))
                continue
            for a, b in _pairs(cluster, pieces, reach, smooth=True):
                _link(self.links, a, b, singular[None, :])
            for end in cluster:
                if end not in self.links:
                    pieces[end[0]] = _extended(pieces[end[0]], end[1], singular)

    def extend(self) -> None:
        """Trace every free end on along the profile, until the ball's boundary, the axis, a
        singular point or another piece: the tracing of the 3D view can stop short of them, or
        join two branches that pass close to each other across a grid cell."""
        tried: set[End] = set()
        while True:
            ends = [e for e in self.free() if e not in tried]
            if not ends:
                return
            end = ends[0]
            tried.add(end)
            piece = self.pieces[end[0]]
            trace = self.trace(piece[end[1]], _tangent(piece, end[1]))
            if trace.reason == "lost" or not trace.points:
                continue
            if trace.reason == "node" and trace.hit is not None:
                self._split(trace.hit[0], trace.hit[1], trace.points[-1])
            if trace.reason == "end" and trace.hit is not None and trace.hit not in self.links:
                self.pieces[end[0]] = _extended_by(self.pieces[end[0]], end[1], trace.points[:-1])
                _link(self.links, end, trace.hit, np.zeros((0, 2)))
                continue
            self.pieces[end[0]] = _extended_by(self.pieces[end[0]], end[1], trace.points)

    def _split(self, k: int, index: int, point: np.ndarray) -> None:
        """Cut piece ``k`` at its vertex ``index``, moved onto ``point`` (a node on it)."""
        piece = self.pieces[k]
        head, tail = piece[: index + 1].copy(), piece[index:].copy()
        head[-1], tail[0] = point, point
        self.pieces[k] = head
        self.pieces.append(tail)
        new = len(self.pieces) - 1
        if (k, -1) in self.links:
            partner, between = self.links.pop((k, -1))
            _link(self.links, (new, -1), partner, between)

    def trace(self, start: np.ndarray, direction: np.ndarray, target: End | None = None) -> _Trace:
        """Points of ``p = 0`` from ``start`` on in ``direction``: a tangent step, Newton's method
        back onto the curve, the step halved where the curve turns or the normal jumps (to another
        branch), until a reason to stop (:class:`_Trace`); with ``target``, only that end stops it."""
        step, poly = self.step, self.poly
        index = _Index(self.pieces, step)
        h, q, travelled = step / 4, start, 0.0
        normal = _direction(poly, q)
        points: list[np.ndarray] = []
        cos = math.cos(math.radians(30))
        for _ in range(TRACE_STEPS):
            tangent = np.array([-normal[1], normal[0]])
            tangent = tangent * (1.0 if tangent @ direction >= 0 else -1.0)
            trial = poly.onto((q + h * tangent)[None, :], steps=6)[0]
            move = trial - q
            moved = float(np.linalg.norm(move))
            turned = _direction(poly, trial)
            if not (0.25 * h <= moved <= 1.5 * h and move @ direction >= cos * moved and turned @ normal >= cos):
                h /= 2
                if h >= 1e-5 * step:
                    continue
                singular = _singular_point(poly, q, REACH * step)
                if singular is None:
                    return _Trace(points, "lost")
                return _Trace([*points, singular], "singular")
            stop = self._stopped(q, trial, travelled + moved, index, target)
            if stop is not None:
                stop.points = [*points, *stop.points]
                return stop
            points.append(trial)
            direction, normal, q, travelled = move / moved, turned, trial, travelled + moved
            h = min(1.5 * h, step / 4)
        return _Trace(points, "lost")

    def _stopped(
        self, q: np.ndarray, trial: np.ndarray, travelled: float, index: _Index, target: End | None
    ) -> _Trace | None:
        """Why a trace stops at its step from ``q`` to ``trial``, if it does."""
        if trial[1] <= 0:
            lam = q[1] / (q[1] - trial[1])
            foot = self.poly.onto(np.array([[q[0] + lam * (trial[0] - q[0]), 0.0]]), steps=20)[0]
            return _Trace([foot], "axis")
        if np.linalg.norm(trial - self.centre) >= self.radius:
            near = np.linalg.norm(self.boundary - trial, axis=1) if len(self.boundary) else np.zeros(0)
            if len(near) and near.min() <= 2 * self.step:
                return _Trace([self.boundary[int(np.argmin(near))]], "boundary")
            return _Trace([], "boundary")
        if travelled <= 1.5 * self.step:
            return None
        hit = index.near(trial, self.step / 3)
        if hit is None:
            return None
        k, i = hit
        ends = {(k, 0): 0, (k, -1): len(self.pieces[k]) - 1}
        for end, position in ends.items():
            if abs(i - position) <= 2 and (target is None or end == target):
                piece = self.pieces[k]
                if len(piece) > 3:  # the trace came alongside the end: the piece starts where it came
                    self.pieces[k] = piece[i:] if position == 0 else piece[: i + 1]
                return _Trace([self.pieces[k][end[1]]], "end", end)
        if target is not None:
            return None
        singular = _singular_point(self.poly, self.pieces[k][i], REACH * self.step)
        if singular is None or not 0 < i < len(self.pieces[k]) - 1:
            return _Trace([], "lost")
        nearest = int(np.argmin(np.linalg.norm(self.pieces[k] - singular, axis=1)))
        if not 0 < nearest < len(self.pieces[k]) - 1:
            return _Trace([], "lost")
        return _Trace([singular], "node", (k, nearest))


class _Index:
    """The vertices of the pieces in square cells of the tracing step, to find one near a point."""

    def __init__(self, pieces: list[np.ndarray], step: float) -> None:
        self.step = step
        self.pieces = pieces
        self.cells: dict[tuple[int, int], list[tuple[int, int]]] = {}
        for k, piece in enumerate(pieces):
            for i, (x, y) in enumerate(piece):
                self.cells.setdefault((int(x // step), int(y // step)), []).append((k, i))

    def near(self, point: np.ndarray, within: float) -> tuple[int, int] | None:
        """The nearest vertex within ``within`` of ``point`` (``(piece, index)``), if any."""
        cx, cy = int(point[0] // self.step), int(point[1] // self.step)
        best, found = within, None
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for k, i in self.cells.get((cx + dx, cy + dy), ()):
                    d = float(np.linalg.norm(self.pieces[k][i] - point))
                    if d <= best:
                        best, found = d, (k, i)
        return found


def _direction(poly: PlaneCurve, point: np.ndarray) -> np.ndarray:
    """The unit normal ``∇p/|∇p|`` at ``point`` (``0`` where ``∇p`` vanishes)."""
    gradient = poly.value_and_gradient(point[None, :])[1][0]
    length = float(np.linalg.norm(gradient))
    return gradient / length if length > 0 and math.isfinite(length) else np.zeros(2)


def _faithful(piece: np.ndarray, poly: PlaneCurve) -> list[np.ndarray]:
    """``piece`` cut where a segment leaves the profile (its middle farther from ``p = 0`` than a
    quarter of its length: a chord from one branch to another, across a grid cell)."""
    if len(piece) < 2:
        return []
    middles = (piece[:-1] + piece[1:]) / 2
    sag = np.linalg.norm(poly.onto(middles) - middles, axis=1)
    bad = np.flatnonzero(sag > 0.25 * _lengths(piece))
    cuts = [-1, *bad, len(piece) - 1]
    return [piece[a + 1 : b + 1] for a, b in zip(cuts[:-1], cuts[1:]) if b - a >= 2]


def _link(links: Links, a: End, b: End, between: np.ndarray) -> None:
    links[a] = (b, between)
    links[b] = (a, between[::-1])


def _extended_by(piece: np.ndarray, index: int, points: list[np.ndarray]) -> np.ndarray:
    """``piece`` continued beyond its end ``index`` by ``points`` (in the order traced)."""
    if not points:
        return piece
    more = np.array(points).reshape(-1, 2)
    return np.vstack([more[::-1], piece]) if index == 0 else np.vstack([piece, more])


def _clusters(ends: list[End], pieces: list[np.ndarray], reach: float) -> list[list[End]]:
    """The ends grouped by nearness (``reach``, transitively)."""
    groups: list[list[End]] = []
    for end in ends:
        q = pieces[end[0]][end[1]]
        near = [g for g in groups if any(np.linalg.norm(pieces[k][i] - q) <= reach for k, i in g)]
        merged = [end] + [e for g in near for e in g]
        groups = [g for g in groups if g not in near] + [merged]
    return [g for g in groups if len(g) >= 2]


def _tangent(piece: np.ndarray, index: int) -> np.ndarray:
    """The unit direction in which ``piece`` leaves through its end ``index``."""
    inner = piece[1] if index == 0 else piece[-2]
    direction: np.ndarray = piece[index] - inner
    length = float(np.linalg.norm(direction))
    return direction / length if length > 0 else direction


def _pairs(ends: list[End], pieces: list[np.ndarray], reach: float, smooth: bool) -> list[tuple[End, End]]:
    """Ends to join, nearest first, within ``reach``: each pointing at the other (or meeting it)
    and, if ``smooth``, the two leaving in opposite directions (the curve continues)."""
    scored = []
    for i, a in enumerate(ends):
        for b in ends[i + 1 :]:
            if a[0] == b[0] and len(pieces[a[0]]) < 4:
                continue
            pa, pb = pieces[a[0]][a[1]], pieces[b[0]][b[1]]
            gap = float(np.linalg.norm(pb - pa))
            ta, tb = _tangent(pieces[a[0]], a[1]), _tangent(pieces[b[0]], b[1])
            turn = float(-ta @ tb)
            aims = gap <= 1e-9 * reach or min(float(ta @ (pb - pa)), float(tb @ (pa - pb))) >= -0.5 * gap
            if gap <= reach and aims and (turn >= math.cos(CORNER) or not smooth):
                scored.append((gap - turn * 1e-9 * reach, a, b))
    taken: set[End] = set()
    out = []
    for _, a, b in sorted(scored):
        if a not in taken and b not in taken:
            taken |= {a, b}
            out.append((a, b))
    return out


def _extended(piece: np.ndarray, index: int, point: np.ndarray) -> np.ndarray:
    """``piece`` with ``point`` as its new end at ``index``."""
    if np.linalg.norm(piece[index] - point) <= 1e-12 * max(1.0, float(np.abs(point).max())):
        out = piece.copy()
        out[index] = point
        return out
    return np.vstack([point, piece]) if index == 0 else np.vstack([piece, point])


def _singular_point(poly: PlaneCurve, guess: np.ndarray, reach: float) -> np.ndarray | None:
    """The singular point of the profile next to ``guess`` (Newton's method on ``∇p = 0``, the
    Hessian by central differences), if it converges within ``reach`` onto ``p = 0``."""
    point = guess.copy()
    for _ in range(40):
        gradient = _gradient(poly, point)
        h = 1e-4 * reach
        hessian = np.column_stack(
            [(_gradient(poly, point + e) - _gradient(poly, point - e)) / (2 * h) for e in (h * np.eye(2))]
        )
        try:
            move = np.linalg.lstsq(hessian, -gradient, rcond=1e-12)[0]
        except np.linalg.LinAlgError:
            return None
        point = point + move
        if not np.all(np.isfinite(point)) or np.linalg.norm(point - guess) > reach:
            return None
        if np.linalg.norm(move) <= 1e-15 * max(1.0, float(np.abs(point).max())):
            break
    point[1] = max(point[1], 0.0)
    around = point + 0.1 * reach * np.column_stack([np.cos(np.arange(8)), np.sin(np.arange(8))])
    values = np.abs(poly.value_and_gradient(np.vstack([point, around]))[0])
    return point if values[0] <= 1e-6 * values[1:].max() else None


def _gradient(poly: PlaneCurve, point: np.ndarray) -> np.ndarray:
    gradient: np.ndarray = poly.value_and_gradient(point[None, :])[1][0]
    return gradient


def _chains(pieces: list[np.ndarray], links: Links) -> list[Arc]:
    """The pieces walked along their links into arcs (a walk that comes back is a loop)."""
    used = [False] * len(pieces)
    arcs = []
    starts = [k for k in range(len(pieces)) if (k, 0) not in links or (k, -1) not in links]
    for start in [*starts, *range(len(pieces))]:
        if used[start]:
            continue
        first = 0 if (start, 0) not in links else -1
        points, closed = _walk(pieces, links, start, first, used)
        arcs.append(Arc(points, closed))
    return arcs


def _walk(pieces: list[np.ndarray], links: Links, start: int, first: int, used: list[bool]) -> tuple[np.ndarray, bool]:
    """The points from piece ``start`` (entered at its end ``first``) on through the links."""
    parts: list[np.ndarray] = []
    k, entry = start, first
    while True:
        used[k] = True
        parts.append(pieces[k] if entry == 0 else pieces[k][::-1])
        leaving: End = (k, -1 if entry == 0 else 0)
        if leaving not in links:
            return _glued(parts), False
        (k, entry), between = links[leaving]
        parts.append(between)
        if used[k]:
            return _glued(parts), k == start


def _glued(parts: list[np.ndarray]) -> np.ndarray:
    """The parts end to end, without a point repeated where they meet."""
    points = np.vstack(parts)
    keep = np.concatenate([[True], _lengths(points) > 1e-12 * max(1.0, float(np.abs(points).max()))])
    glued: np.ndarray = points[keep]
    return glued


Distance = Callable[[np.ndarray], np.ndarray]
"""A distance of 3D points ``(n, 3)`` to the surface (or its profile), length units."""


def profile_distance(curve: MeridianCurve, floor: float = 0.0) -> Distance:
    """The distance of 3D points in the meridian plane to the profile: the first-order ``|p|/|∇p|``,
    or where smaller the way Newton's method moves the point onto ``p = 0`` (near a singular point
    of the profile, where ``∇p`` vanishes, the first-order distance is far too large). Newton's
    method is run only from points whose first-order distance is above ``floor``."""

    def distance(xyz: np.ndarray) -> np.ndarray:
        xy = curve.frame.to_plane(xyz)
        xy[:, 1] = np.abs(xy[:, 1])
        out = curve.curve.distance(xy)
        far = np.flatnonzero(~(out <= floor))
        moved = np.linalg.norm(curve.curve.onto(xy[far], steps=30) - xy[far], axis=1)
        out[far] = np.minimum(out[far], moved)
        return np.asarray(out)

    return distance
