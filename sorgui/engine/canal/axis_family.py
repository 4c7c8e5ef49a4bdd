"""The canal family of a surface of revolution whose spine is its axis (docs/math.md §9.2).

Every surface of revolution is the envelope of the spheres centred on its axis that touch it along
its parallels: the normals along a parallel meet the axis in one point, the sphere about it through
the parallel is tangent there. In the axis frame ``p = c + s·a + r·u`` (``n = |a|²``, ``k = |u|²``)
the parallel of the profile point ``(s, w = r²)`` lies on the sphere about ``c + σ·a`` of squared
radius ``ρ = n·(s − σ)² + k·w``, and the sphere touches the surface there when this does not change
to first order along the profile. With a proper parameterization ``(φ(t), ψ(t))`` of ``P²`` over
``QQ`` (the rationality stage's) that gives the rational family

    σ = φ + k·ψ′/(2n·φ′),   ρ = k²·ψ′²/(4n·φ′²) + k·ψ,   m(t) = c + σ(t)·a,

whose characteristic circles are the parallels (centre ``c + φ·a``, radius² ``k·ψ``, plane normal
``m′(t)``). Its SMAT curve is the axis and ``G(m_k, ρ) = 0``, ``G`` the resultant in ``t`` of the
two coordinates (the curve dual to ``P²`` in the ``(h, ρ)`` plane, where these spheres are lines).
Everything is computed in reduced flint fractions (:mod:`..algebra.fractions`) and checked:
the sphere through each parallel, its tangency, and every SMAT equation on ``(m(t), ρ(t))``.
"""

from __future__ import annotations

import sympy
from flint import fmpq, fmpq_mpoly
from sympy.polys.domains import QQ

from ..algebra.fractions import RationalFunction, evaluate, factored, from_expr
from ..algebra.linalg import Vector, dot
from ..algebra.rationals import context, flint_str, primitive
from ..recognition.profile import ProfileCurve
from ..results import Triple
from ..stage_results import CanalFamily

T = sympy.Symbol("t")
SMAT = ("m1", "m2", "m3", "r")
MAX_DEGREE = 24
"""The SMAT curve's equation is computed for families ``σ(t)``, ``ρ(t)`` up to this degree (the
resultant's size grows with the product of the degrees)."""

NOTE = (
    "the spine is the axis: the spheres centred on it that touch the surface along its parallels, "
    "from the parameterization of P²"
)


def axis_family(profile: ProfileCurve, phi: sympy.Expr, psi: sympy.Expr) -> CanalFamily | None:
    """The family of spheres centred on the axis from a proper parameterization ``(φ, ψ)`` of
    ``P²`` over ``QQ`` (sympy rational functions of ``t``); ``None`` when ``φ`` is constant (a
    plane across the axis: no sphere touches it along a parallel) or the family is too large."""
    frame = profile.frame
    if not all(QQ.of_type(c) for v in (frame.point, frame.direction, frame.normal) for c in v):
        return None
    c, a, u = (_rationals(v) for v in (frame.point, frame.direction, frame.normal))
    n, k = _rational(dot(frame.direction, frame.direction)), _rational(dot(frame.normal, frame.normal))
    ring = context(("t",))
    along, radial = from_expr(phi, [T], ring), from_expr(psi, [T], ring)
    d_along, d_radial = along.derivative(0), radial.derivative(0)
    if d_along.is_zero():
        return None
    offset = d_radial * (k / (2 * n)) / d_along
    sigma = along + offset
    rho = offset * offset * n + radial * k
    if max(_degree(sigma), _degree(rho)) > MAX_DEGREE:
        return None
    m = tuple(sigma * a[i] + RationalFunction.constant(c[i], ring) for i in range(3))
    verified = _touches(sigma, rho, along, radial, n, k)
    equations, model, keep = _smat(c, a, sigma, rho)
    verified = verified and all(evaluate(_terms(g), (*m, rho)).is_zero() for g in equations)
    d_sigma = sigma.derivative(0)
    return CanalFamily(
        degree=1,
        smat_degree=int(model.total_degree()),
        genus=0,
        planar=True,
        on_line=True,
        pipe=rho.num.is_constant() and rho.den.is_constant(),
        equations=tuple(flint_str(g, SMAT) for g in equations),
        spine_equations=tuple(flint_str(g, SMAT) for g in equations[:2]),
        plane_model=flint_str(model, ("u", "v")),
        projection=(tuple(int(i == keep) for i in range(4)), (0, 0, 0, 1)),
        parametrization=_texts(m),
        radius_squared=_text(rho),
        field="QQ",
        verified=verified,
        circle_center=_texts(tuple(along * a[i] + RationalFunction.constant(c[i], ring) for i in range(3))),
        circle_radius_squared=_text(radial * k),
        circle_normal=_texts(tuple(d_sigma * a[i] for i in range(3))),
    )


def _touches(
    sigma: RationalFunction, rho: RationalFunction, along: RationalFunction, radial: RationalFunction, n: fmpq, k: fmpq
) -> bool:
    """The two identities in ``t``: the parallel of ``(φ, ψ)`` lies on the sphere
    (``n·(φ − σ)² + k·ψ = ρ``) and the sphere is tangent there (``2n·(φ − σ)·φ′ + k·ψ′ = 0``)."""
    gap = along - sigma
    on_sphere = gap * gap * n + radial * k - rho
    tangent = gap * along.derivative(0) * (2 * n) + radial.derivative(0) * k
    return on_sphere.is_zero() and tangent.is_zero()


def _smat(
    c: tuple[fmpq, ...], a: tuple[fmpq, ...], sigma: RationalFunction, rho: RationalFunction
) -> tuple[tuple[fmpq_mpoly, ...], fmpq_mpoly, int]:
    """The SMAT equations in ``m1, m2, m3, r`` (the axis, two linear forms, and ``G(m_k, r)``),
    ``G`` in ``u, v``, and ``k``: the coordinate with the largest ``|a_k|``, a coordinate on the
    axis. ``G`` is the product of the factors of ``Res_t(m_k(t) − u, ρ(t) − v)`` that vanish on
    the family (the resultant is a power of ``G`` when the family is not proper)."""
    keep = max(range(3), key=lambda i: (abs(a[i]), -i))
    M = context(SMAT)
    gens = M.gens()
    line = tuple(
        primitive(gens[j] * a[keep] - gens[keep] * a[j] - (c[j] * a[keep] - c[keep] * a[j]))
        for j in range(3)
        if j != keep
    )
    plane = context(("t", "u", "v"))
    _, u, v = plane.gens()

    def lift(p: fmpq_mpoly) -> fmpq_mpoly:
        return plane.from_dict({(int(m[0]), 0, 0): q for m, q in zip(p.monoms(), p.coeffs())})

    first = lift(sigma.num) * a[keep] + lift(sigma.den) * (c[keep] - u)
    second = lift(rho.num) - lift(rho.den) * v
    UV = context(("u", "v"))
    model = UV.from_dict({(0, 0): 1})
    coordinate = sigma * a[keep] + RationalFunction.constant(c[keep], sigma.ctx)
    for h, _ in first.resultant(second, "t").factor()[1]:
        factor = UV.from_dict({(int(m[1]), int(m[2])): q for m, q in zip(h.monoms(), h.coeffs())})
        if not factor.is_constant() and evaluate(_terms(factor), (coordinate, rho)).is_zero():
            model *= factor
    model = primitive(model)
    curve = primitive(model.compose(gens[keep], gens[3], ctx=M))
    return (*line, curve), model, keep


def _terms(g: fmpq_mpoly) -> list[tuple[tuple[int, ...], fmpq]]:
    return [(tuple(int(e) for e in m), q) for m, q in zip(g.monoms(), g.coeffs())]


def _degree(f: RationalFunction) -> int:
    return max(int(f.num.total_degree()), int(f.den.total_degree()))


def _text(f: RationalFunction) -> str:
    return str(factored(f, [T]))


def _texts(v: tuple[RationalFunction, ...]) -> Triple:
    x, y, z = (_text(f) for f in v)
    return x, y, z


def _rational(q: object) -> fmpq:
    return fmpq(int(QQ.numer(q)), int(QQ.denom(q)))


def _rationals(v: Vector) -> tuple[fmpq, ...]:
    return tuple(_rational(q) for q in v)
