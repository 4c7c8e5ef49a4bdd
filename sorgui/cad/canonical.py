"""The canonical form of a part: each recognised B-spline face on its native surface
(docs/math.md §12).

Every face that :mod:`.recognition` found within the tolerance of a plane, sphere, cylinder,
cone, torus, surface of revolution or extrusion, and whose file surface is not that already,
is rebuilt on the native surface from the same wires (``BRepBuilderAPI_MakeFace``): its edges
stay the ones its neighbours share, and gain a curve on the new surface (``ShapeFix_Face``
projects them). The new surface is turned (``UReverse``) when its normal points the other way
from the old one's, so the part keeps its outside. The part is then mended as a whole
(``ShapeFix_Shape``: edge tolerances, same parameters) and checked with ``BRepCheck_Analyzer``.
A face whose new form is not valid on its own keeps its old surface, and the report says so.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepLib import BRepLib
from OCP.BRepTools import BRepTools, BRepTools_ReShape, BRepTools_WireExplorer
from OCP.Geom import Geom_Curve, Geom_Surface
from OCP.Geom2d import Geom2d_BSplineCurve, Geom2d_Curve
from OCP.Geom2dAPI import Geom2dAPI_PointsToBSpline
from OCP.GeomAbs import GeomAbs_Shape
from OCP.GeomAdaptor import GeomAdaptor_Curve
from OCP.GeomLProp import GeomLProp_SLProps
from OCP.gp import gp_Pnt, gp_Pnt2d, gp_Vec2d
from OCP.OCP.collections import Array1_double, Array1_gp_Pnt2d, Array1_int
from OCP.ShapeAnalysis import ShapeAnalysis_Surface
from OCP.ShapeFix import ShapeFix_Shape
from OCP.TopAbs import TopAbs_Orientation, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Shape, TopoDS_Wire

from .failures import OCCT_ERRORS
from .native import edges_of
from .reading import Part, faces_of
from .recognition import Recognised

KEPT_SHOWN = 3
"""The recognised faces kept as read whose reasons the summary names (the rest are counted)."""


@dataclass(frozen=True)
class Canonical:
    """The rewritten part, the faces replaced and those kept (with the reason), and whether the
    whole part is valid under ``BRepCheck_Analyzer``."""

    shape: TopoDS_Shape
    replaced: tuple[int, ...]
    kept: tuple[tuple[int, str], ...]
    valid: bool
    file_note: str = ""
    """What the file written holds beyond the canonical part, in words (a STEP file written
    again with B-spline faces, :data:`.writers.BSPLINE_NOTE`)."""

    def summary(self) -> str:
        """What the file holds, in one line."""
        n = len(self.replaced)
        words = f"{n} face{'s' if n != 1 else ''} on native surfaces"
        if self.kept:
            why = "; ".join(f"face {number}: {reason}" for number, reason in self.kept[:KEPT_SHOWN])
            more = f"; {len(self.kept) - KEPT_SHOWN} more" if len(self.kept) > KEPT_SHOWN else ""
            plural = "s" if len(self.kept) != 1 else ""
            words += f", {len(self.kept)} recognised face{plural} kept as read ({why}{more})"
        words += "; valid (BRepCheck)" if self.valid else "; NOT valid under BRepCheck"
        return f"{words} ({self.file_note})" if self.file_note else words


def canonical_part(part: Part, recognised: Sequence[Recognised]) -> Canonical:
    """``part`` with every recognised face that has a native surface rebuilt on it."""
    copy = BRepBuilderAPI_Copy(part.shape, True, False).Shape()
    faces = faces_of(copy)
    reshape = BRepTools_ReShape()
    replaced, kept = [], []
    for face, found in zip(faces, recognised):
        if found.surface is None:
            continue
        number, tolerance = found.report.face, found.report.tolerance
        try:
            trial = TopoDS.Face(BRepBuilderAPI_Copy(face, True, False).Shape())
            new = rebuilt(trial, found.surface, tolerance) and rebuilt(face, found.surface, tolerance)
        except OCCT_ERRORS as exc:
            kept.append((number, f"Open CASCADE could not rebuild it ({str(exc).strip() or type(exc).__name__})"))
            continue
        if new is None:
            kept.append((number, "its face on the native surface is not valid within the tolerance"))
            continue
        reshape.Replace(face, new)
        replaced.append(number)
    shape = reshape.Apply(copy)
    if not BRepCheck_Analyzer(shape).IsValid():
        fix = ShapeFix_Shape(shape)
        try:
            fix.Perform()
            shape = fix.Shape()
        except OCCT_ERRORS:
            pass  # a face Open CASCADE cannot evaluate: the part is written unmended, said not valid
    return Canonical(shape, tuple(replaced), tuple(kept), BRepCheck_Analyzer(shape).IsValid())


def rebuilt(face: TopoDS_Face, surface: Geom_Surface, within: float) -> TopoDS_Face | None:
    """``face`` on ``surface``, bounded by its own edges, oriented as it was (``None`` if the
    result is not a valid face, or an edge is farther than ``within`` from the new surface).
    Every edge gets its curve on the new surface by projection (:func:`_projected`), the curves of
    each wire are chained end to end (:func:`_chain`), and the edges' tolerances are made to
    cover their distance to the new surface (``BRepLib``). The edges are changed in place (they
    are the neighbours' too): a trial on a copy of the face first tells whether it will do."""
    forward = TopoDS.Face(face.Oriented(TopAbs_Orientation.TopAbs_FORWARD))
    if _opposite(forward, surface):
        surface = surface.UReversed()
    builder = BRep_Builder()
    new = TopoDS_Face()
    tolerance = max(BRep_Tool.Tolerance_s(face), TOLERANCE)
    builder.MakeFace(new, surface, TopLoc_Location(), tolerance)
    for wire in _wires(forward):
        uses = _traversals(wire, forward, surface, tolerance)
        if uses is None or not _chain(uses, surface, _turning(wire, forward)):
            return None
        _store(uses, new, builder, tolerance)
        builder.Add(new, wire)
    edges = edges_of(forward)
    before = [BRep_Tool.Tolerance_s(e) for e in edges]
    BRepLib.SameParameter_s(new, tolerance, True)
    if any(BRep_Tool.Tolerance_s(e) > max(within, tolerance, old) for e, old in zip(edges, before)):
        return None
    if not BRepCheck_Analyzer(new).IsValid():
        return None
    return TopoDS.Face(new.Oriented(face.Orientation()))


TOLERANCE = 1e-7
"""The least tolerance of a rebuilt face and its edges (Open CASCADE's ``Precision::Confusion``)."""


def _wires(face: TopoDS_Face) -> list[TopoDS_Wire]:
    found = []
    explorer = TopExp_Explorer(face, TopAbs_WIRE)
    while explorer.More():
        found.append(TopoDS.Wire(explorer.Current()))
        explorer.Next()
    return found


@dataclass
class _Use:
    """One traversal of an edge in a wire: its curve on the new surface, its range, and whether
    it is traversed backwards."""

    edge: TopoDS_Edge
    curve: Geom2d_Curve | None
    first: float
    last: float
    reversed: bool
    degenerate: bool

    def start(self) -> np.ndarray:
        assert self.curve is not None
        return _uv(self.curve.Value(self.last if self.reversed else self.first))

    def end(self) -> np.ndarray:
        assert self.curve is not None
        return _uv(self.curve.Value(self.first if self.reversed else self.last))


def _uv(p: gp_Pnt2d) -> np.ndarray:
    return np.array([p.X(), p.Y()])


def _traversals(wire: TopoDS_Wire, face: TopoDS_Face, surface: Geom_Surface, tolerance: float) -> list[_Use] | None:
    """The edges of ``wire`` in the order the old face runs them, each projected onto
    ``surface`` (``None`` when a projection fails)."""
    uses = []
    explorer = BRepTools_WireExplorer(wire, face)
    while explorer.More():
        edge = explorer.Current()
        first, last = BRep_Tool.Range_s(edge, face)
        backwards = edge.Orientation() == TopAbs_Orientation.TopAbs_REVERSED
        curve = None
        if not BRep_Tool.Degenerated_s(edge):
            located = _curve3d(edge)
            if located is None:
                return None
            curve = _projected(located, first, last, surface, tolerance)
            if curve is None:
                return None
        uses.append(_Use(edge, curve, first, last, backwards, BRep_Tool.Degenerated_s(edge)))
        explorer.Next()
    return uses


PCURVE_POINTS = (17, 33, 65, 129, 257)
"""Points an edge is sampled at for its curve on the new surface, more until it is close enough."""


def _projected(
    curve: Geom_Curve, first: float, last: float, surface: Geom_Surface, tolerance: float
) -> Geom2d_Curve | None:
    """The curve in ``surface``'s ``(u, v)`` of the 3D ``curve`` over ``[first, last]``, with the
    same parameter: points projected in order (``ShapeAnalysis_Surface``, each from the one
    before), unwrapped across a periodic seam, a point at a singularity (a pole, an apex) given
    its neighbour's ``u``, interpolated (``Geom2dAPI_Interpolate``) on each span where the 3D
    curve is ``C²`` (a converted circle's parameter has corners at its knots), the spans joined,
    and checked halfway between the points; ``None`` when no sampling brings it within a tenth
    of ``tolerance``."""
    onto = ShapeAnalysis_Surface(surface)
    periods = [
        surface.UPeriod() if surface.IsUPeriodic() else None,
        surface.VPeriod() if surface.IsVPeriodic() else None,
    ]
    breaks = _smooth_spans(curve, first, last)
    for count in PCURVE_POINTS:
        per_span = max(5, count // (len(breaks) - 1))
        ts = np.unique(np.concatenate([np.linspace(a, b, per_span) for a, b in zip(breaks, breaks[1:])]))
        points = [curve.Value(float(t)) for t in ts]
        uv = _feet(onto, points, 1e-3 * tolerance)
        for k, period in enumerate(periods):
            if period is not None:
                uv[:, k] = np.unwrap(uv[:, k], period=period)
        singular = np.array([onto.IsDegenerated(p, tolerance) for p in points])
        if singular.all():
            return None
        if singular.any():
            good = np.nonzero(~singular)[0]
            for bad in np.nonzero(singular)[0]:
                uv[bad, 0] = uv[good[np.argmin(np.abs(good - bad))], 0]
        joined = _joined(uv, ts, breaks)
        if joined is None:
            continue
        halfway = 0.5 * (ts[:-1] + ts[1:])
        error = max(surface.Value(*_uv_of(joined, t)).Distance(curve.Value(float(t))) for t in halfway)
        if error <= 0.1 * tolerance:
            return joined
    return None


def _smooth_spans(curve: Geom_Curve, first: float, last: float) -> list[float]:
    """The parameters in ``[first, last]`` between which ``curve`` is ``C²``, ends included."""
    adaptor = GeomAdaptor_Curve(curve, first, last)
    count = adaptor.NbIntervals(GeomAbs_Shape.GeomAbs_C2)
    bounds = Array1_double(1, count + 1)
    adaptor.Intervals(bounds, GeomAbs_Shape.GeomAbs_C2)
    inner = [bounds.Value(k) for k in range(2, count + 1) if first < bounds.Value(k) < last]
    return [first, *inner, last]


def _feet(onto: ShapeAnalysis_Surface, points: list[gp_Pnt], precision: float) -> np.ndarray:
    """The ``(u, v)`` of each point, each projection starting from the one before."""
    uv, previous = [], None
    for p in points:
        previous = onto.ValueOfUV(p, precision) if previous is None else onto.NextValueOfUV(previous, p, precision)
        uv.append((previous.X(), previous.Y()))
    return np.array(uv)


def _joined(uv: np.ndarray, ts: np.ndarray, breaks: list[float]) -> Geom2d_Curve | None:
    """The cubics through the points ``uv`` at ``ts`` on each span between ``breaks``, joined
    into one B-spline: the spans' poles in a row (a joint's pole once) and their knots, a joint
    of multiplicity ``degree`` (``C⁰`` there, each span exactly as it was)."""
    pieces = []
    for a, b in zip(breaks, breaks[1:]):
        chosen = (ts >= a) & (ts <= b)
        piece = _interpolated(uv[chosen], ts[chosen])
        if piece is None:
            return None
        pieces.append(piece)
    if len(pieces) == 1:
        return pieces[0]
    degree = max(piece.Degree() for piece in pieces)
    for piece in pieces:
        piece.IncreaseDegree(degree)
    poles: list[gp_Pnt2d] = []
    knots: list[float] = []
    mults: list[int] = []
    for number, piece in enumerate(pieces):
        own = [piece.Pole(k) for k in range(1, piece.NbPoles() + 1)]
        poles += own if number == 0 else own[1:]
        for k in range(1, piece.NbKnots() + 1):
            knot, mult = piece.Knot(k), piece.Multiplicity(k)
            if k == 1 and number > 0:
                mults[-1] = degree
                continue
            knots.append(knot)
            mults.append(mult)
    array = Array1_gp_Pnt2d(1, len(poles))
    for k, pole in enumerate(poles, start=1):
        array.SetValue(k, pole)
    knot_array, mult_array = Array1_double(1, len(knots)), Array1_int(1, len(mults))
    for k, (knot, mult) in enumerate(zip(knots, mults), start=1):
        knot_array.SetValue(k, knot)
        mult_array.SetValue(k, mult)
    return Geom2d_BSplineCurve(array, knot_array, mult_array, degree)


def _uv_of(curve: Geom2d_Curve, t: float) -> tuple[float, float]:
    p = curve.Value(float(t))
    return p.X(), p.Y()


def _interpolated(uv: np.ndarray, ts: np.ndarray) -> Geom2d_BSplineCurve | None:
    """The B-spline of degree at most 8 nearest the points ``uv`` at the parameters ``ts``
    (``Geom2dAPI_PointsToBSpline``, through the end points, within ``1e-11`` of the others),
    over the parameters ``ts`` run."""
    points, parameters = Array1_gp_Pnt2d(1, len(uv)), Array1_double(1, len(ts))
    for k, ((u, v), t) in enumerate(zip(uv, ts), start=1):
        points.SetValue(k, gp_Pnt2d(float(u), float(v)))
        parameters.SetValue(k, float(t))
    scale = max(1.0, float(np.abs(uv).max()))
    try:
        approximation = Geom2dAPI_PointsToBSpline(points, parameters, 3, 8, GeomAbs_Shape.GeomAbs_C2, 1e-11 * scale)
    except OCCT_ERRORS:
        return None
    if not approximation.IsDone():
        return None
    curve = approximation.Curve()
    start, span = float(ts[0]), float(ts[-1] - ts[0])
    knots = Array1_double(1, curve.NbKnots())
    for k in range(1, curve.NbKnots() + 1):
        knots.SetValue(k, start + span * curve.Knot(k))
    curve.SetKnots(knots)  # the approximation runs over [0, 1]: back to the edge's parameter
    return curve


def _curve3d(edge: TopoDS_Edge) -> Geom_Curve | None:
    """The edge's 3D curve with its placement applied (a copy when it has one)."""
    return BRep_Tool.Curve_s(edge, 0.0, 0.0)


def _chain(uses: list[_Use], surface: Geom_Surface, turning: float) -> bool:
    """Make a wire's curves meet end to end, turning the way the old wire turned (the sign of
    ``turning``, its signed area): each curve is shifted by whole periods of a closed surface to
    start where the one before ends (a projection picks any period); the second run along a seam
    lies one period from the first, on the side that closes the wire the right way round; each
    degenerate edge (a pole, an apex) is the straight segment between its neighbours. ``False``
    when no choice closes the wire."""
    periods = np.array(
        [surface.UPeriod() if surface.IsUPeriodic() else 0.0, surface.VPeriod() if surface.IsVPeriodic() else 0.0]
    )
    steps = [np.array(v) * periods for v in ((1, 0), (-1, 0), (0, 1), (0, -1)) if np.any(np.array(v) * periods)]
    seams = [k for k, use in enumerate(uses) if not use.degenerate and _first_twin(uses, k) is not None]
    projected = [use.curve for use in uses]
    scale = max(float(np.abs(periods).max(initial=0.0)), 1.0)
    for choice in itertools.product(steps or [np.zeros(2)], repeat=len(seams)):
        for use, curve in zip(uses, projected):
            use.curve = curve
        placed = dict(zip(seams, choice))
        previous = None
        for k, use in enumerate(uses):
            if use.degenerate:
                continue
            twin = _first_twin(uses, k)
            if twin is not None:
                _place(use, twin, placed[k])
            elif previous is not None:
                _shift(use, previous.end(), periods)
            previous = use
        for k, use in enumerate(uses):
            if use.degenerate:
                before, after = _neighbour(uses, k, -1), _neighbour(uses, k, 1)
                if before is None or after is None:
                    return False
                use.curve = _segment(before.end(), after.start(), use.first, use.last, use.reversed)
        gaps = [np.linalg.norm(uses[k - 1].end() - use.start()) for k, use in enumerate(uses)]
        if max(gaps) <= 1e-7 * scale and _area(uses) * turning > 0:
            return True
    return False


def _first_twin(uses: list[_Use], k: int) -> _Use | None:
    """The earlier run along the same (seam) edge as run ``k``, if there is one."""
    for use in uses[:k]:
        if use.edge.IsSame(uses[k].edge) and not use.degenerate:
            return use
    return None


def _place(use: _Use, twin: _Use, step: np.ndarray) -> None:
    """Put the second run along a seam one period (``step``) from the first."""
    assert use.curve is not None and twin.curve is not None
    here = _uv(use.curve.Value(use.first))
    there = _uv(twin.curve.Value(twin.first)) + step
    move = there - here
    use.curve = use.curve.Translated(gp_Vec2d(float(move[0]), float(move[1])))


def _area(uses: list[_Use], count: int = 16) -> float:
    """The signed area the runs enclose in ``(u, v)`` (positive: counter-clockwise)."""
    points = []
    for use in uses:
        assert use.curve is not None
        ts = np.linspace(use.first, use.last, count)
        points += [_uv(use.curve.Value(float(t))) for t in (ts[::-1] if use.reversed else ts)]
    xy = np.array(points)
    return 0.5 * float(np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1]))


def _turning(wire: TopoDS_Wire, face: TopoDS_Face) -> float:
    """The signed area of ``wire`` in the old face's own ``(u, v)``."""
    uses = []
    explorer = BRepTools_WireExplorer(wire, face)
    while explorer.More():
        edge = explorer.Current()
        first, last = BRep_Tool.Range_s(edge, face)
        curve = BRep_Tool.CurveOnSurface_s(edge, face, 0.0, 0.0)
        backwards = edge.Orientation() == TopAbs_Orientation.TopAbs_REVERSED
        uses.append(_Use(edge, curve, first, last, backwards, BRep_Tool.Degenerated_s(edge)))
        explorer.Next()
    return _area(uses) if uses and all(u.curve is not None for u in uses) else 0.0


def _neighbour(uses: list[_Use], k: int, step: int) -> _Use | None:
    """The nearest traversal before (``step`` −1) or after (+1) ``k`` that is not degenerate."""
    for offset in range(1, len(uses)):
        other = uses[(k + step * offset) % len(uses)]
        if not other.degenerate:
            return other
    return None


def _store(uses: list[_Use], face: TopoDS_Face, builder: BRep_Builder, tolerance: float) -> None:
    """Give each edge its curve on ``face`` (both curves for a seam, the one the face runs
    forwards first)."""
    for use in uses:
        if use.curve is None:
            continue
        twins = [u for u in uses if u.edge.IsSame(use.edge) and u.curve is not None]
        if len(twins) == 2:
            ahead = twins[0] if not twins[0].reversed else twins[1]
            behind = twins[1] if ahead is twins[0] else twins[0]
            builder.UpdateEdge(use.edge, ahead.curve, behind.curve, face, tolerance)
        else:
            builder.UpdateEdge(use.edge, use.curve, face, tolerance)
        builder.Range(use.edge, face, use.first, use.last)


def _shift(use: _Use, target: np.ndarray, periods: np.ndarray) -> None:
    """Move ``use``'s curve by whole periods so that it starts nearest ``target``."""
    assert use.curve is not None
    offset = target - use.start()
    steps = np.where(periods > 0, np.round(offset / np.where(periods > 0, periods, 1.0)), 0.0)
    if np.any(steps):
        move = steps * periods
        use.curve = use.curve.Translated(gp_Vec2d(float(move[0]), float(move[1])))


def _segment(start: np.ndarray, end: np.ndarray, first: float, last: float, backwards: bool) -> Geom2d_Curve:
    """The straight segment from ``start`` to ``end`` over the range ``[first, last]`` (run from
    ``last`` to ``first`` when the edge is traversed backwards)."""
    a, b = (end, start) if backwards else (start, end)
    poles = Array1_gp_Pnt2d(1, 2)
    poles.SetValue(1, gp_Pnt2d(float(a[0]), float(a[1])))
    poles.SetValue(2, gp_Pnt2d(float(b[0]), float(b[1])))
    knots, mults = Array1_double(1, 2), Array1_int(1, 2)
    for k, knot in enumerate((first, last), start=1):
        knots.SetValue(k, knot)
        mults.SetValue(k, 2)
    return Geom2d_BSplineCurve(poles, knots, mults, 1)


def _opposite(face: TopoDS_Face, surface: Geom_Surface) -> bool:
    """Whether ``surface``'s normal points against the face's surface's at the middle of the face."""
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    old = GeomLProp_SLProps(BRep_Tool.Surface_s(face), 0.5 * (u0 + u1), 0.5 * (v0 + v1), 1, 1e-12)
    if not old.IsNormalDefined():
        return False
    point = old.Value()
    uv = ShapeAnalysis_Surface(surface).ValueOfUV(point, 1e-9)
    new = GeomLProp_SLProps(surface, uv.X(), uv.Y(), 1, 1e-12)
    if not new.IsNormalDefined():
        return False
    a, b = old.Normal(), new.Normal()
    return bool(np.dot([a.X(), a.Y(), a.Z()], [b.X(), b.Y(), b.Z()]) < 0)


def canonical_file(part: Part, recognised: Sequence[Recognised], name: str, suffix: str) -> tuple[bytes, Canonical]:
    """The bytes of the CAD file ``name`` (format ``suffix``) of the canonical part, and the part."""
    from sorgui import __version__

    from .writers import CadHeader, write_cad

    canonical = canonical_part(part, recognised)
    description = (f"the canonical form of {part.path.name}", canonical.summary())
    data, note = write_cad(suffix, canonical.shape, CadHeader("", description, __version__, name))
    return data, replace(canonical, file_note=note)
