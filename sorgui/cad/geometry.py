"""What a CAD file holds for an analysis, worked out without Open CASCADE (docs/math.md §11).

A surface of revolution ``X`` becomes, in order of preference:

* an **analytic** surface (:class:`Analytic`: plane, sphere, cylinder, cone, torus) when its
  exact profile has that form (the squared profile ``P²(x, w)``, ``w = y²``, in the orthonormal
  axis frame, compared coefficient by coefficient);
* the **exact** rational profile (:func:`exact_profile`): the meridian section ``σ = 0`` of a
  verified real parameterization, ``c + φ(t)·a + ρ(t)·u``, cut on the projective ``t``-line at its
  poles, where it crosses the axis and where it leaves the drawn ball, each arc written in the
  Bernstein basis of its homogeneous segment (:func:`bernstein`) — a rational Bézier arc whose
  weights are the denominator's Bernstein coefficients, subdivided until they share one sign;
* otherwise a **fitted** profile: the arcs of the real profile in the half-plane ``y ≥ 0``
  (:mod:`.meridian`), fitted with B-splines within a stated tolerance (:mod:`.fitted`).

Everything here is ``float64`` geometry from the engine's exact strings (read with the one safe
reader, :mod:`sorgui.engine.values`); the Bernstein coefficients are computed with 40 digits
and rounded once.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import mpmath
import numpy as np
import sympy

from sorgui.engine.results import Analysis, Factor, Profile, Recognition
from sorgui.engine.stage_results import Parametrization
from sorgui.engine.values import ExpressionError, Terms, float_vector, polynomial_terms, read_expression
from sorgui.numerics import real_roots
from sorgui.render import ClipSphere
from sorgui.render.geometry import foot_on_line
from sorgui.render.sampling import first_order_distance

DIGITS = 40
"""Working precision (decimal digits) of the Bernstein conversion; the result is rounded once."""

MAX_DEGREE = 25
"""The largest B-spline degree Open CASCADE builds (``Geom_BSplineCurve::MaxDegree``)."""


class CadGeometryError(ValueError):
    """What the analysis gives cannot be written as CAD geometry (said in one sentence)."""


@dataclass(frozen=True)
class Frame:
    """The orthonormal axis frame: ``point`` on the axis, unit ``direction`` along it and a unit
    ``normal`` spanning the meridian half-plane ``y ≥ 0`` with it."""

    point: np.ndarray
    direction: np.ndarray
    normal: np.ndarray

    def to_plane(self, xyz: np.ndarray) -> np.ndarray:
        """``(x, y)`` coordinates in the meridian plane of 3D points ``(n, 3)``."""
        d = np.asarray(xyz) - self.point
        return np.column_stack([d @ self.direction, d @ self.normal])

    def to_space(self, xy: np.ndarray) -> np.ndarray:
        """3D points of meridian coordinates ``(n, 2)``."""
        xy = np.asarray(xy)
        points: np.ndarray = self.point + xy[:, :1] * self.direction + xy[:, 1:] * self.normal
        return points


@dataclass(frozen=True)
class Analytic:
    """An analytic surface of Open CASCADE's kinds, placed at ``origin`` with axis ``direction``.

    ``kind`` is ``"plane"`` (``origin`` its point nearest the ball's centre, ``direction`` its
    normal, ``extent`` the radius of the disk inside the ball), ``"sphere"`` (``radius``),
    ``"cylinder"`` (``radius``, ``extent`` the axial range about ``origin``), ``"cone"`` (apex
    ``origin``, ``semi_angle``, ``extent`` the range of the signed distance from the apex along
    a generatrix) or ``"torus"`` (``radius`` the major and ``minor_radius`` the minor one).
    """

    kind: str
    origin: np.ndarray
    direction: np.ndarray
    radius: float = 0.0
    minor_radius: float = 0.0
    semi_angle: float = 0.0
    extent: tuple[float, float] = (0.0, 0.0)


@dataclass(frozen=True)
class RationalCurve:
    """A rational B-spline made of Bézier arcs of one ``degree`` joined end to end: ``poles``
    ``(k·degree + 1, 3)`` and positive ``weights``; knots ``0, 1, …, k``, inner ones of
    multiplicity ``degree``."""

    degree: int
    poles: np.ndarray
    weights: np.ndarray

    @property
    def arcs(self) -> int:
        return (len(self.poles) - 1) // self.degree

    def bezier_arcs(self) -> list[RationalCurve]:
        """Each arc on its own, its weights balanced: ``w_i·c^i`` with ``c = (w₀/w_n)^(1/n)`` is
        the same curve reparameterized, with equal end weights (the arcs of one B-spline share
        one weight scale, which can leave some a thousand times lighter than others)."""
        n = self.degree
        out = []
        for k in range(self.arcs):
            weights = self.weights[k * n : (k + 1) * n + 1]
            c = (weights[0] / weights[-1]) ** (1.0 / n)
            balanced = weights * c ** np.arange(n + 1)
            out.append(RationalCurve(n, self.poles[k * n : (k + 1) * n + 1], balanced / balanced.max()))
        return out

    def points(self, per_arc: int = 16) -> np.ndarray:
        """Points along the curve (de Casteljau on each arc), for checks and coverage."""
        out = []
        for k in range(self.arcs):
            P = self.poles[k * self.degree : (k + 1) * self.degree + 1]
            W = self.weights[k * self.degree : (k + 1) * self.degree + 1]
            for lam in np.linspace(0.0, 1.0, per_arc, endpoint=k == self.arcs - 1):
                basis = np.array(
                    [
                        math.comb(self.degree, i) * (1 - lam) ** (self.degree - i) * lam**i
                        for i in range(self.degree + 1)
                    ]
                )
                h = basis * W
                out.append(h @ P / h.sum())
        return np.array(out)


# --- the frame and the analytic kinds ---------------------------------------------------------


def axis_frame(profile: Profile) -> Frame:
    """The orthonormal frame of the profile's ``K``-rational frame ``(c, a, u)`` (rounded once)."""
    a, u = float_vector(profile.frame_direction), float_vector(profile.frame_normal)
    return Frame(float_vector(profile.frame_point), a / np.linalg.norm(a), u / np.linalg.norm(u))


def analytic_surfaces(analysis: Analysis, ball: ClipSphere) -> list[Analytic] | None:
    """The analytic surfaces ``X`` is made of, if it is (``None`` otherwise): parallel planes and
    concentric spheres from the recognition, a cylinder, cone or torus from the exact squared
    profile ``P²(x, w)``; those that miss the ball are left out."""
    rec = analysis.recognition
    centre = np.asarray(ball.center)
    if rec.symmetry == "plane" and rec.normal is not None:
        return _planes(analysis.squarefree, rec.normal, centre, ball.radius)
    if rec.symmetry == "sphere" and rec.center is not None:
        return _spheres(analysis.squarefree, rec.center, centre, ball.radius)
    if len(analysis.factors) > 1:
        return _union(analysis.factors, centre, ball.radius)
    return _of_profile(rec, centre, ball.radius)


def _union(factors: Sequence[Factor], centre: np.ndarray, radius: float) -> list[Analytic] | None:
    """The analytic surfaces of a reducible ``X`` when each factor is one (a cylinder and a plane,
    two cones: their fitted profile strayed at the curves where they cross), those that miss
    the ball left out; ``None`` when a factor is not analytic."""
    specs: list[Analytic] = []
    for factor in factors:
        rec = factor.recognition
        try:
            if rec.symmetry == "plane" and rec.normal is not None:
                specs += _planes(factor.polynomial, rec.normal, centre, radius)
            elif rec.symmetry == "sphere" and rec.center is not None:
                specs += _spheres(factor.polynomial, rec.center, centre, radius)
            else:
                found = _of_profile(rec, centre, radius)
                if found is None:
                    return None
                specs += found
        except CadGeometryError:
            continue  # this factor misses the ball
    return specs


def _of_profile(rec: Recognition, centre: np.ndarray, radius: float) -> list[Analytic] | None:
    """A cylinder, cone or torus from the exact squared profile ``P²(x, w)`` of ``rec``."""
    if rec.profile is None or rec.axis is None:
        return None
    frame = axis_frame(rec.profile)
    x, w = sympy.symbols("x y")
    try:
        square = sympy.Poly(read_expression(rec.profile.square), x, w)
    except (ExpressionError, sympy.PolynomialError):
        return None
    spec = None
    if square.total_degree() <= 2 and square.degree(w) == 1 and not square.coeff_monomial(x * w):
        spec = _quadric(square, frame, centre, radius)  # P² = q(x) + c·w: a quadric (x·w is a cubic)
    elif square.total_degree() == 4:
        spec = _torus(square, frame)
    return None if spec is None else [spec]


def _line_roots(polynomial: str, point: Sequence[str], direction: Sequence[str]) -> list[float]:
    """The real roots ``t`` of ``g(point + t·direction)``, exactly substituted (the square-free
    ``g`` of a union of parallel planes or of concentric spheres is a polynomial in one
    variable along such a line)."""
    t = sympy.Symbol("t")
    x, y, z = sympy.symbols("x y z")
    p = [read_expression(c) for c in point]
    d = [read_expression(c) for c in direction]
    line = {x: p[0] + t * d[0], y: p[1] + t * d[1], z: p[2] + t * d[2]}
    h = sympy.Poly(sympy.expand(read_expression(polynomial).subs(line, simultaneous=True)), t)
    if h.degree() < 1:
        return []
    return sorted(float(r.evalf(30)) for r in h.real_roots(multiple=True))


def _planes(polynomial: str, normal: Sequence[str], centre: np.ndarray, radius: float) -> list[Analytic]:
    """The planes ``n·p = t·|n|²`` at the real roots ``t`` of ``g(t·n)``, as their points nearest
    the ball's centre and their disks inside the ball (``z²`` is the plane ``z = 0``, from its
    square-free part)."""
    n = float_vector(normal)
    unit = n / np.linalg.norm(n)
    planes = []
    for t in _line_roots(polynomial, ("0", "0", "0"), normal):
        distance = float(unit @ centre) - t * float(np.linalg.norm(n))
        if abs(distance) < radius:
            foot = centre - distance * unit
            planes.append(Analytic("plane", foot, unit, extent=(0.0, math.sqrt(radius**2 - distance**2))))
    if not planes:
        raise CadGeometryError("the planes do not meet the drawn region")
    return planes


def _spheres(polynomial: str, center: Sequence[str], centre: np.ndarray, radius: float) -> list[Analytic]:
    """The spheres about ``center`` whose radii are the positive real roots of ``g(center + t·e₁)``
    (even in ``t``) and that meet the ball in more than a point: inside it, or the ball's own
    sphere (a sphere of radius 2 in the ball of radius 2 about its centre was refused, as if it
    had no point there, while a ball about a centre off by 4e-16 gave the whole sphere)."""
    middle = float_vector(center)
    reach = float(np.linalg.norm(middle - centre))
    radii = sorted({r for r in _line_roots(polynomial, center, ("1", "0", "0")) if r > 0})
    spheres = [
        Analytic("sphere", middle, np.array([0.0, 0.0, 1.0]), radius=r)
        for r in radii
        if abs(reach - r) < radius or _same_sphere(reach, r, radius)
    ]
    if not spheres:
        raise CadGeometryError("the sphere has no real points in the drawn region")
    return spheres


def _same_sphere(reach: float, r: float, radius: float) -> bool:
    """Whether the sphere of radius ``r`` whose centre is ``reach`` from the ball's is the ball's
    own sphere, within :data:`SAME_SPHERE` of its radius."""
    return reach <= SAME_SPHERE * radius and abs(r - radius) <= SAME_SPHERE * radius


SAME_SPHERE = 1e-12
"""The relative distance of centres and of radii within which a sphere is the ball's own."""


def _number(value: sympy.Expr) -> float:
    return float(sympy.re(value.evalf(30)))


def _quadric(square: sympy.Poly, frame: Frame, centre: np.ndarray, radius: float) -> Analytic | None:
    """``P² = α·x² + β·x + γ + δ·w``: a cylinder (``α = β = 0``) or a cone (``α·δ < 0`` and a
    double root in ``x``); other quadrics of revolution are left to the exact profile."""
    x, w = square.gens
    alpha, beta, gamma = (square.coeff_monomial(m) for m in (x**2, x, 1))
    delta = square.coeff_monomial(w)
    height = float((centre - frame.point) @ frame.direction)
    off = off_axis(centre, frame.point, frame.direction)
    if alpha == 0 and beta == 0:
        r2 = _number(-gamma / delta)
        if r2 <= 0:
            return None
        gap = math.sqrt(r2) - off  # the cylinder's nearest approach to the ball's centre, across the axis
        if gap * gap >= radius**2:
            raise CadGeometryError("the cylinder does not meet the drawn ball")
        half = math.sqrt(radius**2 - gap * gap)
        return Analytic(
            "cylinder",
            frame.point + height * frame.direction,
            frame.direction,
            radius=math.sqrt(r2),
            extent=(-half, half),
        )
    if sympy.simplify(beta**2 - 4 * alpha * gamma) != 0 or _number(alpha / delta) >= 0:
        return None
    apex_x = _number(-beta / (2 * alpha))
    angle = math.atan(math.sqrt(_number(-alpha / delta)))
    offset = apex_x - height
    b, c = offset * math.cos(angle), offset**2 - radius**2
    if b * b - c <= 0:
        raise CadGeometryError("the cone does not meet the drawn ball")
    root = math.sqrt(b * b - c)
    extent = (-b - root, -b + root)
    if off > ON_AXIS * radius:  # a ball off the axis: every generatrix's stretch in it, cut to it later
        reach = math.hypot(offset, off) + radius
        extent = (-reach, reach)
    apex = frame.point + apex_x * frame.direction
    return Analytic("cone", apex, frame.direction, semi_angle=angle, extent=extent)


ON_AXIS = 1e-9
"""How far from the axis, relative to the ball's radius, the ball's centre may be and be on it."""


def off_axis(centre: np.ndarray, point: np.ndarray, direction: np.ndarray) -> float:
    """The distance of ``centre`` from the line through ``point`` along ``direction``."""
    return float(np.linalg.norm(centre - foot_on_line(centre, point, direction)))


def _torus(square: sympy.Poly, frame: Frame) -> Analytic | None:
    """``P² = (x'² + w + R² - r²)² - 4R²·w`` with ``x' = x - x₀`` and ``R, r > 0``: a ring torus
    (``R > r``), a horn torus (``R = r``) or a spindle torus (``R < r``, its tube circle crossing
    the axis: one turn of that circle is the outer and the inner part, each once)."""
    x, w = square.gens
    lead = square.coeff_monomial(w**2)
    if lead == 0:
        return None
    p = sympy.Poly(sympy.expand(square.as_expr() / lead), x, w)
    x0 = -p.coeff_monomial(x**3) / 4
    shifted = sympy.Poly(sympy.expand(p.as_expr().subs(x, x + x0)), x, w)
    A, B = shifted.coeff_monomial(x**2), shifted.coeff_monomial(w)
    R2, r2 = (A - B) / 4, (A - B) / 4 - A / 2
    model = sympy.expand((x**2 + w + R2 - r2) ** 2 - 4 * R2 * w)
    if sympy.expand(shifted.as_expr() - model) != 0:
        return None
    big, small = _number(R2), _number(r2)
    if not (big > 0 and small > 0):
        return None
    return Analytic(
        "torus",
        frame.point + _number(x0) * frame.direction,
        frame.direction,
        radius=math.sqrt(big),
        minor_radius=math.sqrt(small),
    )


# --- the exact profile ------------------------------------------------------------------------

Form = list[mpmath.mpf]
"""A binary form of degree ``n`` in ``(T, W)``: ``c[i]`` is the coefficient of ``T^i·W^(n-i)``."""


@dataclass(frozen=True)
class Section:
    """A rational curve ``(N₁, N₂, N₃)/D`` of ``t`` as binary forms of one degree."""

    numerators: tuple[Form, Form, Form]
    denominator: Form

    @property
    def degree(self) -> int:
        return len(self.denominator) - 1

    def at(self, t: np.ndarray) -> np.ndarray:
        """Points at parameters ``t`` (floats; ``inf`` not allowed)."""
        den = _values(self.denominator, t)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.column_stack([_values(n, t) / den for n in self.numerators])


def _values(form: Form, t: np.ndarray) -> np.ndarray:
    return np.polyval(np.array([float(c) for c in reversed(form)]), t)


def meridian_section(param: Parametrization, held: int = 0) -> Section:
    """The curve of a parameterization where its parameter ``held`` is 0, as forms in the other:
    ``σ = 0`` of one swept about the axis (docs/math.md §6); a typed map may turn about the axis
    along either parameter."""
    names = [sympy.Symbol(name) for name in param.parameters]
    s, t = names[held], names[1 - held]
    polys = [sympy.Poly(e, t) for e in over_one_denominator([read_expression(c).subs(s, 0) for c in param.coordinates])]
    n = max(p.degree() for p in polys)
    forms = [binary_form(p, n) for p in polys]
    return Section((forms[0], forms[1], forms[2]), forms[3])


def over_one_denominator(exprs: Sequence[sympy.Expr]) -> list[sympy.Expr]:
    """The numerators of rational functions over their least common denominator, and that
    denominator last: ``[N₁, …, Nₖ, D]`` with ``exprs[i] = Nᵢ/D``."""
    pairs = [sympy.fraction(sympy.together(e)) for e in exprs]
    den = sympy.Integer(1)
    for _, d in pairs:
        den = sympy.lcm(den, d)
    return [*(sympy.cancel(n * den / d) for n, d in pairs), den]


def real_number(value: sympy.Expr) -> mpmath.mpf:
    """An exact real coefficient with :data:`DIGITS` digits; a non-real one is refused."""
    number = sympy.N(value, DIGITS)
    if sympy.im(number) != 0:
        raise CadGeometryError("the parameterization is not real")
    with mpmath.workdps(DIGITS):
        return mpmath.mpf(sympy.re(number))


def binary_form(poly: sympy.Poly, n: int) -> Form:
    """The univariate ``poly`` as a binary form of degree ``n`` (coefficients of ``T^i·W^(n-i)``)."""
    coefficients = [mpmath.mpf(0)] * (n + 1)
    for (k,), c in poly.terms():
        coefficients[k] = real_number(c)
    return coefficients


def bernstein(form: Form, start: tuple[float, float], end: tuple[float, float]) -> Form:
    """The Bernstein coefficients of ``form`` on the segment ``μ·start + λ·end`` of the projective
    line (homogeneous points): ``form(μA + λB) = Σ b_k·C(n, k)·μ^(n-k)·λ^k``."""
    n = len(form) - 1
    with mpmath.workdps(DIGITS):
        powers_t = _powers(mpmath.mpf(start[0]), mpmath.mpf(end[0]), n)
        powers_w = _powers(mpmath.mpf(start[1]), mpmath.mpf(end[1]), n)
        total = [mpmath.mpf(0)] * (n + 1)
        for i, c in enumerate(form):
            if c == 0:
                continue
            for j, a in enumerate(powers_t[i]):
                for k, b in enumerate(powers_w[n - i]):
                    total[j + k] += c * a * b
        return [total[k] / math.comb(n, k) for k in range(n + 1)]


def _powers(p: mpmath.mpf, q: mpmath.mpf, n: int) -> list[Form]:
    """``(p·μ + q·λ)^i`` for ``i = 0 … n``, each as coefficients of ``μ^(i-k)·λ^k``."""
    out: list[Form] = [[mpmath.mpf(1)]]
    for _ in range(n):
        last = out[-1]
        out.append(
            [(last[k] * p if k < len(last) else 0) + (last[k - 1] * q if k > 0 else 0) for k in range(len(last) + 1)]
        )
    return out


def exact_profile(analysis: Analysis, frame: Frame, ball: ClipSphere, size: float) -> list[RationalCurve] | None:
    """The real profile in the half-plane ``y ≥ 0`` inside ``ball``, as exact rational arcs of the
    first verified real parameterization whose meridian section (where its first parameter is 0,
    else where its second is) lies on ``X`` in a plane through the axis; ``None`` when there is
    none (the profile is then fitted)."""
    terms = polynomial_terms(analysis.recognition.polynomial)
    for param, held in ((p, i) for p in analysis.parametrizations for i in (0, 1)):
        if not (param.real and param.verified):
            continue
        try:
            section = meridian_section(param, held)
        except (ExpressionError, CadGeometryError, sympy.PolynomialError):
            continue
        if not 0 < section.degree <= MAX_DEGREE:
            continue
        normal = _meridian_normal(section, terms, frame, size)
        if normal is None:
            continue
        try:
            arcs = _arcs(section, Frame(frame.point, frame.direction, normal), ball, size)
        except CadGeometryError:  # a weight vanishes on a drawn arc: the next map, else the fit
            continue
        return [_turned(arc, frame, normal) for arc in arcs]
    return None


def _turned(curve: RationalCurve, frame: Frame, normal: np.ndarray) -> RationalCurve:
    """The curve turned about the axis from the half-plane of ``normal`` into the frame's own
    (the same surface of revolution; the traced profile it is compared with lies there)."""
    a = frame.direction
    cos, sin = float(normal @ frame.normal), float(np.cross(normal, frame.normal) @ a)
    rotation = (
        cos * np.eye(3)
        + sin * np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
        + (1 - cos) * np.outer(a, a)
    )
    return RationalCurve(curve.degree, frame.point + (curve.poles - frame.point) @ rotation.T, curve.weights)


def _meridian_normal(section: Section, terms: Terms, frame: Frame, size: float) -> np.ndarray | None:
    """The unit normal of the plane through the axis that holds the section, if it lies in one and
    on ``f = 0`` (checked at points: a report read from a file is not trusted to hold what the
    engine verified)."""
    points = section.at(np.tan(np.linspace(-1.5, 1.5, 41)))
    points = points[np.all(np.isfinite(points), axis=1)]
    if len(points) < 10:
        return None
    relative = points - frame.point
    radial = relative - np.outer(relative @ frame.direction, frame.direction)
    lengths = np.linalg.norm(radial, axis=1)
    if lengths.max() == 0:
        return None
    normal: np.ndarray = radial[np.argmax(lengths)] / lengths.max()
    side = np.cross(frame.direction, normal)
    if np.max(np.abs(radial @ side)) > 1e-9 * max(size, float(lengths.max())):
        return None
    if not np.all(surface_distance(terms, points) <= 1e-9 * size):
        return None
    return normal


def surface_distance(terms: Terms, points: np.ndarray) -> np.ndarray:
    """The first-order distance ``|f|/|∇f|`` of each point to ``f = 0`` (0 at a singular point on it)."""
    distance = first_order_distance(terms, points)
    out: np.ndarray = np.where(np.isnan(distance), 0.0, distance)
    return out


def _product(p: Form, q: Form) -> Form:
    out = [mpmath.mpf(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def _point(theta: float) -> tuple[float, float]:
    """The homogeneous point ``(sin θ/2, cos θ/2)`` of ``t = tan(θ/2)``: continuous in ``θ``."""
    return (math.sin(theta / 2), math.cos(theta / 2))


def _value(form: Form, theta: float) -> float:
    T, W = _point(theta)
    n = len(form) - 1
    return float(sum(c * T**i * W ** (n - i) for i, c in enumerate(form)))


def _angles(form: Form) -> list[float]:
    """The angles ``θ = 2·atan(t)`` of the real roots of ``form`` (``π`` for ``t = ∞``), found in
    ``t = ρ·s`` with ``ρ`` balancing its lowest and highest coefficients: the sphere's form of a
    hyperbola of waist 1000 (coefficients from 2 to 3.2·10¹³) lost its top one to the roots'
    noise floor, and with it the crossings at ``t = ±6088``; the arc then ran into a pole."""
    c = np.array([float(v) for v in form])
    top = float(np.abs(c).max(initial=0.0))
    if top == 0:
        return []
    if not math.isfinite(top):  # beyond floats: no root is read, as real_roots reads none
        return [math.pi] if abs(c[-1]) <= 1e-14 * top else []
    kept = np.nonzero(np.abs(c) > 1e-14 * top)[0]
    low, high = int(kept[0]), int(kept[-1])
    rho = (abs(c[low]) / abs(c[high])) ** (1.0 / (high - low)) if high > low else 1.0
    scaled = np.where(np.abs(c) > 1e-14 * top, c, 0.0) * rho ** np.arange(len(c))
    out = [2 * math.atan(float(s) * rho) for s in real_roots(scaled)]
    if high < len(c) - 1:
        out.append(math.pi)
    return out


@dataclass(frozen=True)
class _Span:
    start: float
    end: float
    cut_start: bool


def _arcs(section: Section, frame: Frame, ball: ClipSphere, size: float) -> list[RationalCurve]:
    """The arcs of ``section`` inside ``ball`` on the side ``y > 0``, and those on ``y < 0``
    mirrored across the axis unless they repeat an arc already kept (a profile symmetric about
    the axis, as an irreducible ``P`` is, is covered once)."""
    c, a = frame.point, frame.direction
    centre = c + float((np.asarray(ball.center) - c) @ a) * a
    N, D = section.numerators, section.denominator
    with mpmath.workdps(DIGITS):
        rho = [
            sum(((N[i][k] - mpmath.mpf(c[i]) * D[k]) * frame.normal[i] for i in range(3)), mpmath.mpf(0))
            for k in range(len(D))
        ]
        offsets = [[N[i][k] - mpmath.mpf(centre[i]) * D[k] for k in range(len(D))] for i in range(3)]
        inside = [sum(q) for q in zip(*(_product(o, o) for o in offsets))]
        radius2 = _product(D, D)
        ball_form = [q - mpmath.mpf(ball.radius) ** 2 * r for q, r in zip(inside, radius2)]
    cuts = sorted({round(t, 12) for form in (D, rho, ball_form) for t in _angles(form)})
    spans = _spans(cuts)
    inside_ball = [k for k, s in enumerate(spans) if _value(ball_form, (s.start + s.end) / 2) < 0]
    pieces = _pieces(spans, inside_ball)
    positive: list[RationalCurve] = []
    negative: list[RationalCurve] = []
    for piece in pieces:
        middle = (piece[0].start + piece[0].end) / 2
        curve = _curve(section, piece)
        (positive if _value(rho, middle) * _value(D, middle) > 0 else negative).append(curve)
    kept = list(positive)
    for curve in negative:
        mirrored = _mirrored(curve, frame)
        probe = mirrored.points(4)[1:-1]
        if not any(np.all(polyline_distance(probe, p.points(200)) < 1e-4 * size) for p in positive):
            kept.append(mirrored)
    return kept


def ball_arcs(section: Section, centre: np.ndarray, radius: float) -> list[RationalCurve]:
    """The arcs of ``section`` inside the ball about ``centre``: the projective ``t``-line cut at
    the poles (roots of ``D``) and where the curve crosses the sphere (``|N − m·D|² − R²·D²``),
    the spans inside kept and joined where no real cut parts them, each a rational B-spline."""
    N, D = section.numerators, section.denominator
    with mpmath.workdps(DIGITS):
        offsets = [[N[i][k] - mpmath.mpf(centre[i]) * D[k] for k in range(len(D))] for i in range(3)]
        inside = [sum(q) for q in zip(*(_product(o, o) for o in offsets))]
        ball_form = [q - mpmath.mpf(radius) ** 2 * r for q, r in zip(inside, _product(D, D))]
    cuts = sorted({round(t, 12) for form in (D, ball_form) for t in _angles(form)})
    spans = _spans(cuts)
    kept = [k for k, span in enumerate(spans) if _value(ball_form, (span.start + span.end) / 2) < 0]
    return [_curve(section, piece) for piece in _pieces(spans, kept)]


def polynomial_spans(numerators: tuple[Form, Form, Form]) -> list[np.ndarray]:
    """A polynomial map of the projective line (binary forms of one degree ``n``) over spans of at
    most ``π/4`` covering it: on each, the control points ``(n + 1, 3)`` of the Bézier curve it is
    (its Bernstein coefficients)."""
    out = []
    for span in _spans([]):
        A, B = _point(span.start), _point(span.end)
        with mpmath.workdps(DIGITS):
            coordinates = [bernstein(n, A, B) for n in numerators]
        out.append(np.array([[float(coordinates[i][k]) for i in range(3)] for k in range(len(coordinates[0]))]))
    return out


def polyline_distance(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    """The distance of each point to the polyline through ``polyline``'s vertices."""
    if len(polyline) == 1:
        return np.asarray(np.linalg.norm(points - polyline[0], axis=1))
    a, b = polyline[:-1], polyline[1:]
    edge = b - a
    length2 = np.maximum(np.einsum("ij,ij->i", edge, edge), 1e-300)
    out = np.empty(len(points))
    for k, q in enumerate(points):
        along = np.clip(np.einsum("ij,ij->i", q - a, edge) / length2, 0.0, 1.0)
        out[k] = np.min(np.linalg.norm(a + along[:, None] * edge - q, axis=1))
    return out


def _spans(cuts: list[float]) -> list[_Span]:
    """The projective line cut at ``cuts`` (angles in ``(-π, π]``), each span at most ``π/4`` long
    (extra cuts marked as such), in order, the last one wrapping round to the first cut."""
    ends = [(t, True) for t in cuts] or [(-math.pi, False)]
    spans: list[_Span] = []
    for k, (start, real_start) in enumerate(ends):
        end = ends[(k + 1) % len(ends)][0]
        if end <= start:
            end += 2 * math.pi
        pieces = max(1, math.ceil((end - start) / (math.pi / 4)))
        step = (end - start) / pieces
        spans += [_Span(start + j * step, start + (j + 1) * step, real_start and j == 0) for j in range(pieces)]
    return spans


def _pieces(spans: list[_Span], kept: list[int]) -> list[list[_Span]]:
    """The kept spans (indices into ``spans``) joined where no real cut separates them; a piece
    running through the last span into the first continues at angles lifted by ``2π``, so that
    its homogeneous points stay continuous. A piece all round the line (a closed curve, an
    ellipse) is cut in two: a closed curve's face would have two boundary edges in one place."""
    pieces: list[list[int]] = []
    for k in kept:
        if pieces and pieces[-1][-1] == k - 1 and not spans[k].cut_start:
            pieces[-1].append(k)
        else:
            pieces.append([k])
    out = [[spans[k] for k in piece] for piece in pieces]
    wraps = len(pieces) > 1 and pieces[0][0] == 0 and pieces[-1][-1] == len(spans) - 1 and not spans[0].cut_start
    if wraps:
        lifted = [_Span(s.start + 2 * math.pi, s.end + 2 * math.pi, s.cut_start) for s in out.pop(0)]
        out[-1] += lifted
    halves = []
    for piece in out:
        if len(piece) > 1 and piece[-1].end - piece[0].start >= 2 * math.pi - 1e-9:
            halves += [piece[: len(piece) // 2], piece[len(piece) // 2 :]]
        else:
            halves.append(piece)
    return halves


def _curve(section: Section, spans: list[_Span]) -> RationalCurve:
    """One rational B-spline through ``spans``: the Bernstein form of each, halved until the
    weights share one sign, each arc reparameterized to end weights 1 (``w_i·c^i/w₀`` with
    ``c = (w₀/w_n)^(1/n)``, the same arc). Every pole where arcs meet then weighs 1, the first
    and the last too: a closed profile whose end weights differed (1/9 and 1) was read back from
    STEP as a periodic curve with the first weight at both ends, its last arc off the surface."""
    arcs: list[tuple[np.ndarray, np.ndarray]] = []
    for span in spans:
        arcs += _bezier(section, span.start, span.end, depth=0)
    balanced = [_ends_one(w, section.degree) for _, w in arcs]
    poles = np.concatenate([arcs[0][0][:1]] + [p[1:] for p, _ in arcs])
    weights = np.concatenate([balanced[0][:1]] + [w[1:] for w in balanced])
    return RationalCurve(section.degree, poles, weights / weights.max())


def _ends_one(weights: np.ndarray, n: int) -> np.ndarray:
    """The weights of one arc of degree ``n`` reparameterized to ``1`` at both ends; those within
    a few units in the last place of 1 are 1 (an arc of a parabola is a polynomial one: all 1)."""
    out: np.ndarray
    if weights[0] == weights[-1]:
        out = weights / weights[0]
    else:
        out = weights * ((weights[0] / weights[-1]) ** (1.0 / n)) ** np.arange(n + 1) / weights[0]
    out[np.abs(out - 1.0) <= 4 * np.finfo(float).eps] = 1.0
    out[0] = out[-1] = 1.0
    return out


def _bezier(section: Section, start: float, end: float, depth: int) -> list[tuple[np.ndarray, np.ndarray]]:
    A, B = _point(start), _point(end)
    weights = bernstein(section.denominator, A, B)
    values = np.array([float(w) for w in weights])
    if not (np.all(values > 0) or np.all(values < 0)):
        if depth >= 12:
            raise CadGeometryError("the profile's denominator vanishes on a drawn arc")
        middle = (start + end) / 2
        return _bezier(section, start, middle, depth + 1) + _bezier(section, middle, end, depth + 1)
    with mpmath.workdps(DIGITS):
        coordinates = [bernstein(n, A, B) for n in section.numerators]
        poles = np.array([[float(coordinates[i][k] / weights[k]) for i in range(3)] for k in range(len(weights))])
    return [(poles, values)]


def _mirrored(curve: RationalCurve, frame: Frame) -> RationalCurve:
    """The curve reflected across the axis in its meridian plane (the same surface when turned)."""
    offsets = (curve.poles - frame.point) @ frame.normal
    return RationalCurve(curve.degree, curve.poles - 2 * np.outer(offsets, frame.normal), curve.weights)
