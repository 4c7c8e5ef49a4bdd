"""The canal answer of a torus from its symmetry and its profile (docs/math.md §9.1).

A surface of revolution is canal through its symmetry alone (the spheres centred on the axis
that touch it along its parallels). A torus, the only irreducible Dupin cyclide of revolution,
is canal in a second way too, as a pipe about its core circle. Both families follow from the
profile in the axis frame without the SMAT, Singular or a line test:

    P²(s, w) = λ·((A(s − s₀)² + B·w + k)² − 4R²·B·w),   A = |a|², B = |u|², k = R² − r²,

with ``c + s₀a`` the centre, ``R²`` the core circle's radius² and ``r²`` the tube's. The identity
is checked exactly; it *is* the certificate: the surface is the circle ``(d − R)² + ζ² = r²`` of
the meridian half-plane (``d`` the distance to the axis, ``ζ`` along it) swept about the axis,
which is the envelope of the spheres of radius² ``r²`` centred on the core circle.

Each family is a conic ``a₁X² + a₂Y² = c`` in disguise: the core circle in its plane, and for
the spheres centred on the axis at ``m₀ + τa`` with radius ``r(V + 1)``, the curve
``r²V² − Aτ² = R²``. A rational point of small height (searched) gives ``m(t), ρ(t)`` over
``QQ`` by the lines through it; otherwise the family is given by its SMAT equations alone.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import gcd, isqrt, lcm
from typing import Any

from flint import fmpq, fmpq_poly
from sympy.polys.domains import QQ

from ..algebra.linalg import Vector, cross, dot
from ..algebra.polys import Poly, compose, poly_ring, poly_str, primitive, total_degree
from ..recognition.profile import ProfileCurve
from ..results import Canal, CanalEvidence
from ..stage_results import CanalFamily

HEIGHT = 12
"""Rational points ``Y = p/q`` with ``q ≤ HEIGHT`` are tried on each family's conic."""

SPAN = 24
"""``|Y| ≤ SPAN`` on a hyperbola (the axis family's conic), where ``|Y|`` is not bounded."""

REACH = 1000
"""``|Y| ≤ REACH`` on an ellipse too: one whose ``|Y|`` reaches ``10⁷⁵`` is not searched to its end."""

CERTIFICATE = (
    "the profile in the axis frame is (|X − m₀|² + R² − r²)² − 4R²·d² up to a constant (d the "
    "distance to the axis), exactly: the circle (d − R)² + ζ² = r² of the meridian half-plane swept "
    "about the axis, the envelope of the spheres of radius² r² centred on the core circle"
)
"""What the ``profile`` certificate of a torus's pipe family proves."""


@dataclass(frozen=True)
class Torus:
    """A torus about the axis through ``center`` with ``direction``: core circle of radius²
    ``core`` in the plane through ``center`` perpendicular to the axis, tube radius² ``tube``."""

    center: tuple[Fraction, Fraction, Fraction]
    direction: tuple[Fraction, Fraction, Fraction]
    normal: tuple[Fraction, Fraction, Fraction]
    core: Fraction
    tube: Fraction


def torus_of(profile: ProfileCurve) -> Torus | None:
    """The torus of this profile, read off ``P²`` and checked exactly; ``None`` when the surface is
    not a real torus over ``QQ`` (another surface of revolution, a complex core or tube)."""
    P = profile.square
    if not P.ring.domain.is_QQ or total_degree(P) != 4 or P.degree(1) != 2:
        return None
    frame = profile.frame
    a, u = _fractions(frame.direction), _fractions(frame.normal)
    A, B = dot(a, a), dot(u, u)
    terms = {m: Fraction(int(QQ.numer(c)), int(QQ.denom(c))) for m, c in P.items()}
    top = terms.get((4, 0), Fraction(0))
    if not top:
        return None
    scale = top / A**2
    s0 = -terms.get((3, 0), Fraction(0)) / (4 * top)
    s, w = P.ring.gens
    Q = compose(P, [s + QQ(s0.numerator, s0.denominator), w])
    coefficient = {m: Fraction(int(QQ.numer(c)), int(QQ.denom(c))) / scale for m, c in Q.items()}
    k = coefficient.get((2, 0), Fraction(0)) / (2 * A)
    core = (2 * B * k - coefficient.get((0, 1), Fraction(0))) / (4 * B)
    expected = (_q(A) * s**2 + _q(B) * w + _q(k)) ** 2 - 4 * _q(core) * _q(B) * w
    if Q != expected * _q(scale):
        return None
    tube = core - k
    if core <= 0 or tube <= 0:
        return None
    c = _fractions(frame.point)
    x, y, z = (c[i] + s0 * a[i] for i in range(3))
    return Torus((x, y, z), a, u, core, tube)


def torus_canal(torus: Torus, certificate: CanalEvidence) -> Canal:
    """The canal answer of a torus: a pipe about its core circle (family 1), a surface of
    revolution (family 2) and a Dupin cyclide, with ``m(t)``, ``ρ(t)`` and the circles of each
    family that is rational over ``QQ``; ``certificate`` states the two proofs."""
    return Canal(
        True,
        "canal",
        ("dupin", "pipe", "revolution"),
        (_pipe_family(torus), _axis_family(torus)),
        certificate,
        notes=(PARAMETRIZATION_NOTE,),
    )


PARAMETRIZATION_NOTE = (
    "the torus's parameterizations are those of the surface of revolution: they run along "
    "its parallels and its meridians, the characteristic circles of the two families"
)


def _pipe_family(torus: Torus) -> CanalFamily:
    """Spheres of radius² ``r²`` centred on ``m₀ + X·u + Y·(a × u)``, ``B X² + AB Y² = R²``;
    their characteristic circles are the meridians (centre ``m(t)``, normal ``m′(t)``)."""
    a, u = torus.direction, torus.normal
    v = cross(a, u)
    A, B = dot(a, a), dot(u, u)
    conic = _conic(B, A * B, torus.core)
    M = poly_ring(("m1", "m2", "m3", "r"), QQ)
    d = [M.gens[i] - _q(torus.center[i]) for i in range(3)]
    plane = primitive(sum((_q(a[i]) * d[i] for i in range(3)), M.zero))
    sphere = sum((d[i] ** 2 for i in range(3)), M.zero) - _q(torus.core)
    k = _largest(a)
    keep = (min(i for i in range(3) if i != k), max(i for i in range(3) if i != k))
    solved = M.gens[k] - plane * QQ.quo(QQ.one, plane.coeff(M.gens[k]))
    circle = primitive(compose(sphere, [solved if i == k else g for i, g in enumerate(M.gens)]))
    equations = (primitive(M.gens[3] - _q(torus.tube)), plane, circle)
    family = None
    if conic is not None:
        X, Y = conic
        m = tuple(_add(_const(c), _add(_scale(X, u[i]), _scale(Y, v[i]))) for i, c in enumerate(torus.center))
        rho = _const(torus.tube)
        family = _Family(m, rho, m, rho, tuple(_derivative(c) for c in m))
    return _report(
        equations,
        equations[1:],
        _rename(circle, keep),
        keep,
        family,
        degree=2,
        smat_degree=2,
        on_line=False,
        radius=_fraction_str(torus.tube),
    )


def _axis_family(torus: Torus) -> CanalFamily:
    """Spheres centred on ``P = m₀ + τa`` with ``ρ = r²(V + 1)²``, ``r²V² − Aτ² = R²``: ``r·V`` is
    the distance from ``P`` to the core circle. The sphere touches the tube along the parallel
    about ``m₀ − (τ/V)·a`` of radius ``R(1 + 1/V)`` (on the line from ``P`` through the core circle)."""
    a = torus.direction
    A = dot(a, a)
    conic = _conic(torus.tube, -A, torus.core)
    M = poly_ring(("m1", "m2", "m3", "r"), QQ)
    d = [M.gens[i] - _q(torus.center[i]) for i in range(3)]
    k = _largest(a)
    line = tuple(primitive(_q(a[k]) * d[j] - _q(a[j]) * d[k]) for j in range(3) if j != k)
    T2 = (d[k] * _q(1 / a[k])) ** 2 * _q(A)  # Aτ² on the axis, τ from the coordinate m_k
    r2, R2 = _q(torus.tube), _q(torus.core)
    model = primitive((M.gens[3] - r2 - R2 - T2) ** 2 - 4 * r2 * (T2 + R2))
    family = None
    if conic is not None:
        V, tau = conic
        m = tuple(_add(_const(c), _scale(tau, a[i])) for i, c in enumerate(torus.center))
        one = _add(V, _const(Fraction(1)))
        ratio = _div(one, V)
        centre = tuple(_add(_const(c), _scale(_div(tau, V), -a[i])) for i, c in enumerate(torus.center))
        family = _Family(
            m,
            _scale(_mul(one, one), torus.tube),
            centre,
            _scale(_mul(ratio, ratio), torus.core),
            tuple(_derivative(c) for c in m),
        )
    return _report(
        (*line, model),
        line,
        _rename(model, (k, 3)),
        (k, 3),
        family,
        degree=1,
        smat_degree=4,
        on_line=True,
        radius=None,
    )


def _conic(a1: Fraction, a2: Fraction, c: Fraction) -> tuple[Rat, Rat] | None:
    """A rational parameterization ``(X(t), Y(t))`` of ``a₁X² + a₂Y² = c`` by the lines through a
    rational point of small height; ``None`` when none is found (the family then needs a square
    root, and is given by its equations)."""
    point = _rational_point(a1, a2, c)
    if point is None:
        return None
    X0, Y0 = point
    t = (fmpq_poly([0, 1]), fmpq_poly([1]))
    p, q = _fq(a1), _fq(a2)
    T = fmpq_poly([0, 1])
    if Y0 == 0:  # the lines X = X₀ + λ, Y = tλ
        lam = _norm(-2 * p * _fq(X0) + 0 * T, p + q * T * T)
        return _add(_const(X0), lam), _mul(t, lam)
    lam = _norm(-2 * (p * _fq(X0) * T + q * _fq(Y0)), p * T * T + q)  # X = X₀ + tλ, Y = Y₀ + λ
    return _add(_const(X0), _mul(t, lam)), _add(_const(Y0), lam)


def _rational_point(a1: Fraction, a2: Fraction, c: Fraction) -> tuple[Fraction, Fraction] | None:
    """A point ``(X, Y)`` of ``a₁X² + a₂Y² = c`` with ``Y = p/q``, ``q ≤ HEIGHT`` and ``|p| ≤ q·b``
    (``b`` bounds ``|Y|`` on an ellipse, up to :data:`REACH`; :data:`SPAN` otherwise), tried in order of height so the
    parameterization stays small: ``X = √(N·A₁)/(A₁q)`` with ``N = Cq² − A₂p²`` in integers."""
    scale = lcm(a1.denominator, a2.denominator, c.denominator)
    A1, A2, C = (int(x * scale) for x in (a1, a2, c))
    bound = min(isqrt(abs(C // A2)) + 2, REACH) if A2 * A1 > 0 else SPAN
    for q in range(1, HEIGHT + 1):
        for p in sorted(range(-bound * q, bound * q + 1), key=abs):
            N = (C * q * q - A2 * p * p) * A1
            root = isqrt(N) if N >= 0 else -1
            if root * root == N:
                return Fraction(root, A1 * q), Fraction(p, q)
    return None


@dataclass(frozen=True)
class _Family:
    """A family's ``m(t)``, ``ρ(t)`` and characteristic circles (centre, radius², normal) over ``QQ``."""

    m: tuple[Rat, ...]
    rho: Rat
    centre: tuple[Rat, ...]
    radius2: Rat
    normal: tuple[Rat, ...]


def _report(
    equations: tuple[Poly, ...],
    spine: tuple[Poly, ...],
    model: Poly,
    projection: tuple[int, int],
    family: _Family | None,
    *,
    degree: int,
    smat_degree: int,
    on_line: bool,
    radius: str | None,
) -> CanalFamily:
    """The report of a family: ``m(t)``, ``ρ(t)`` and the circles only when the family is over
    ``QQ`` and passes the substitution into every SMAT equation; a pipe's ``radius`` always."""
    first, second = (tuple(int(i == k) for i in range(4)) for k in projection)
    if family is not None and not all(_vanishes(g, (*family.m, family.rho)) for g in equations):
        family = None
    return CanalFamily(
        degree=degree,
        smat_degree=smat_degree,
        genus=0,
        planar=True,
        on_line=on_line,
        pipe=radius is not None,
        equations=tuple(poly_str(g) for g in equations),
        spine_equations=tuple(poly_str(g) for g in spine),
        plane_model=poly_str(model),
        projection=(first, second),
        parametrization=None if family is None else _texts(family.m),
        radius_squared=radius if family is None else _text(family.rho),
        field=None if family is None else "QQ",
        verified=family is not None,
        circle_center=None if family is None else _texts(family.centre),
        circle_radius_squared=None if family is None else _text(family.radius2),
        circle_normal=None if family is None else _texts(family.normal),
    )


def _vanishes(g: Poly, point: tuple[Rat, ...]) -> bool:
    """Whether ``g(m(t), ρ(t)) = 0`` identically (a SMAT equation on the family)."""
    total = _const(Fraction(0))
    for monom, c in g.items():
        term = _const(Fraction(int(QQ.numer(c)), int(QQ.denom(c))))
        for value, e in zip(point, monom):
            for _ in range(e):
                term = _mul(term, value)
        total = _add(total, term)
    return total[0].is_zero()


def _largest(a: tuple[Fraction, ...]) -> int:
    """The coordinate ``k`` with the largest ``|a_k|`` (the first on ties): projecting along it
    is birational on a circle perpendicular to ``a``, and ``m_k`` is a coordinate on the axis."""
    return max(range(3), key=lambda i: (abs(a[i]), -i))


def _rename(g: Poly, keep: tuple[int, int]) -> Poly:
    """A polynomial in the two kept SMAT coordinates, written in ``u, v``."""
    UV = poly_ring(("u", "v"), QQ)
    images = [UV.zero] * 4
    images[keep[0]], images[keep[1]] = UV.gens
    return primitive(compose(g, images))


# Rational functions of t over QQ, as (numerator, denominator) in python-flint: sympy's
# expressions would cost more than the whole rest of the torus's canal answer.
Rat = tuple[fmpq_poly, fmpq_poly]


def _norm(n: fmpq_poly, d: fmpq_poly) -> Rat:
    g = n.gcd(d)
    n, d = n // g, d // g
    lead = d[d.degree()]
    return n / lead, d / lead


def _const(x: Fraction) -> Rat:
    return fmpq_poly([_fq(x)]), fmpq_poly([1])


def _add(p: Rat, q: Rat) -> Rat:
    return _norm(p[0] * q[1] + q[0] * p[1], p[1] * q[1])


def _mul(p: Rat, q: Rat) -> Rat:
    return _norm(p[0] * q[0], p[1] * q[1])


def _div(p: Rat, q: Rat) -> Rat:
    return _norm(p[0] * q[1], p[1] * q[0])


def _scale(p: Rat, c: Fraction) -> Rat:
    return _norm(p[0] * _fq(c), p[1])


def _derivative(p: Rat) -> Rat:
    return _norm(p[0].derivative() * p[1] - p[0] * p[1].derivative(), p[1] * p[1])


def _text(p: Rat) -> str:
    """``p`` as sympy prints a factored rational function, e.g. ``-2*(t - 1)*(t + 1)/(t**2 + 1)``."""
    content_n, top = _factors(p[0])
    content_d, bottom = _factors(p[1])
    c = content_n / content_d
    numerator = "*".join(([str(abs(int(c.p)))] if abs(int(c.p)) != 1 or not top else []) + top)
    below = ([str(int(c.q))] if c.q != 1 else []) + bottom
    sign = "-" if c.p < 0 else ""
    if not below:
        return sign + numerator
    return f"{sign}{numerator}/" + (below[0] if len(below) == 1 else "(" + "*".join(below) + ")")


def _texts(v: tuple[Rat, ...]) -> tuple[str, str, str]:
    """The three coordinates of a point as :func:`_text` prints them."""
    x, y, z = (_text(c) for c in v)
    return x, y, z


def _factors(p: fmpq_poly) -> tuple[fmpq, list[str]]:
    """The content of ``p`` and its primitive integer factors as text (``(t**2 + 1)**2``)."""
    content, factors = p.factor()
    texts = []
    for g, e in factors:
        numbers = [int(x * g.denom()) for x in g.coeffs()]
        h = 0
        for x in numbers:
            h = gcd(h, x)
        integer = fmpq_poly([x // h for x in numbers])
        content *= (g[g.degree()] / integer[integer.degree()]) ** e
        body = _poly_text(integer)
        text = body if body == "t" else f"({body})"
        texts.append(text if e == 1 else f"{text}**{e}")
    return content, texts


def _poly_text(p: fmpq_poly) -> str:
    """An integer polynomial in ``t`` as sympy prints it (``3*t**2 - 2*t + 1``)."""
    text = ""
    for k in range(p.degree(), -1, -1):
        c = int(p[k])
        if not c:
            continue
        monomial = "" if k == 0 else "t" if k == 1 else f"t**{k}"
        body = str(abs(c)) if not monomial else monomial if abs(c) == 1 else f"{abs(c)}*{monomial}"
        text += ("-" if c < 0 else "") + body if not text else (" - " if c < 0 else " + ") + body
    return text


def _fq(x: Fraction) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def _fraction_str(x: Fraction) -> str:
    return str(x.numerator) if x.denominator == 1 else f"{x.numerator}/{x.denominator}"


def _fractions(v: Vector) -> tuple[Fraction, Fraction, Fraction]:
    x, y, z = (Fraction(int(QQ.numer(c)), int(QQ.denom(c))) for c in v)
    return x, y, z


def _q(x: Fraction | int) -> Any:
    """``x`` in sympy's ``QQ`` (whose elements have no type information)."""
    x = Fraction(x)
    return QQ(x.numerator, x.denominator)
