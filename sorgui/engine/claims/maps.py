"""A report's maps checked against its polynomial: the parameterizations of ``X`` (of a surface
of revolution, of a canal surface by its circles, of a cone or a cylinder by its lines), the
rationality facts of Table 1 with the parameterization of ``P²``, the tubular surface ``T`` and
the map ``τ``, and the apex, direction and base curve of a cone or a cylinder (docs/math.md
§5, §6, §10, §14).

A parameterization marked verified must lie on ``f`` (substituted at random points) and be a
map of rank 2 (a 2×2 minor of its Jacobian nonzero): a point of ``X`` or a curve on it is no
parameterization. ``(φ(t), ψ(t))`` must lie on ``P²`` and not be constant; ``T`` is
``y² + z² − h(x)``; ``τ = (φ(x), d(x)·y/q(x), d(x)·z/q(x))`` with ``d²h/q² = ψ``, so that
``τ(T) ⊂ X``; the real roots of ``h`` are counted again, exactly, and the row of Table 1 and the
verdicts follow from the genera as the paper's table says. A cone's ``f(c + X)`` is homogeneous,
a cylinder's ``f`` invariant along its direction, and the base curve is the top-degree form in
its chart, or the section by its plane.
"""

from __future__ import annotations

import sympy

from ..algebra.linalg import cross, dot, is_zero
from ..algebra.modular import Point
from ..algebra.polys import to_expr
from ..errors import ClaimError
from ..results import Conical, Profile
from ..stage_results import Parametrization, Rationality
from .formulas import Surface, formula, nonzero, values, vector
from .identities import Identities, proportional


def check_parametrization(param: Parametrization, surface: Surface, where: str, ids: Identities) -> None:
    """A verified map lies on ``f`` and has rank 2; a real one has no ``I`` (an unverified one
    is shown as such and not checked)."""
    check_parametrization_form(param, where)
    if not param.verified:
        return
    ids.need(*surface.radicands)
    coordinates = [formula(c) for c in param.coordinates]

    def on_surface(point: Point) -> bool:
        return surface.at(point, values(point, param.coordinates)) == 0

    def rank_two(point: Point) -> bool:
        p = point.prime
        m = [[point.jet(c, n)[1] for n in param.parameters] for c in coordinates]
        return any((m[i][0] * m[j][1] - m[i][1] * m[j][0]) % p for i, j in ((0, 1), (0, 2), (1, 2)))

    ids.add(where, "does not lie on the surface (f(X(s, t)) is not 0)", on_surface, param.coordinates)
    ids.add(where, "is not a map onto a surface (its Jacobian has rank below 2)", rank_two, param.coordinates)


def check_parametrization_form(param: Parametrization, where: str) -> None:
    """A real map has no ``I``; its two parameters are different names."""
    if param.real and any(_complex(formula(c)) for c in param.coordinates):
        raise ClaimError(f"{where}.real", "is claimed, but the coordinates hold I")
    if not param.real and not any(formula(c).has(sympy.I) for c in param.coordinates):
        raise ClaimError(f"{where}.real", "is false (a complex map), but the coordinates hold no I")
    if len(set(param.parameters)) != 2:
        raise ClaimError(f"{where}.parameters", "must be two different names")


def _complex(expr: sympy.Expr) -> bool:
    """Whether ``expr`` holds ``I`` other than beside the square root of a polynomial (``I·√(1 − t²)``
    is real where ``t² > 1``: the circles of a canal surface)."""
    radical = any(a.exp.is_Rational and a.exp.q == 2 and a.base.free_symbols for a in expr.atoms(sympy.Pow))
    return bool(expr.has(sympy.I)) and not radical


def check_rationality(
    rat: Rationality, profile: Profile | None, multiplicity: int, where: str, ids: Identities
) -> None:
    """Table 1's facts, the parameterization of ``P²``, ``T``, ``τ`` and the real roots of ``h``
    (of the square-free ``g`` with ``f = c·g^multiplicity``, whose profile is ``p̃`` to that power)."""
    from ..revolution.rationality import has_real_surface, table_row

    genus_p2 = rat.genus_profile_square
    if rat.table_row is not None:
        if genus_p2 is None or rat.profile_reducible is None:
            raise ClaimError(f"{where}.table_row", "is given without the genera that decide it")
        if not rat.profile_reducible and rat.genus_profile is None:
            raise ClaimError(f"{where}.genus_profile", "is missing for an irreducible profile")
        row = table_row(rat.profile_reducible, rat.genus_profile, genus_p2)
        if rat.table_row != row:
            raise ClaimError(f"{where}.table_row", f"is {rat.table_row}, but those genera are row {row} of Table 1")
        if rat.complex_rational is not (genus_p2 == 0):
            raise ClaimError(f"{where}.complex_rational", "does not follow from genus(P²) (Table 1)")
    if genus_p2 is not None and genus_p2 > 0 and (rat.unirational or rat.real_rational or rat.square_parametrization):
        raise ClaimError(where, "claims a rational real surface or a parameterization of P², of positive genus")
    if rat.real_rational and not rat.unirational:
        raise ClaimError(f"{where}.real_rational", "is claimed for a surface that is not unirational")
    if rat.absolute_factors and profile is not None:
        _check_absolute_factors(rat.absolute_factors, profile, multiplicity, f"{where}.absolute_factors", ids)
    if rat.square_parametrization is None:
        if rat.tubular_surface is not None or rat.tau is not None or rat.h is not None:
            raise ClaimError(f"{where}.tubular_surface", "is given without the parameterization of P² it comes from")
        return
    if profile is None:
        raise ClaimError(f"{where}.square_parametrization", "is given for a surface without a profile")
    if genus_p2 != 0:
        raise ClaimError(f"{where}.genus_profile_square", "must be 0: P² has a parameterization")
    phi, psi = rat.square_parametrization

    def on_square(point: Point) -> bool:
        s, w = values(point, [phi, psi])
        return values(point, [profile.rational_square], s=s, w=w)[0] == 0

    def moving(point: Point) -> bool:
        return values(point, [phi, psi]) != values(point.fresh(), [phi, psi])

    ids.add(f"{where}.square_parametrization", "does not lie on P²", on_square, [phi, psi, profile.rational_square])
    ids.add(f"{where}.square_parametrization", "is constant", moving, [phi, psi])
    if rat.tubular_surface is None or rat.h is None or rat.tau is None:
        raise ClaimError(f"{where}.tubular_surface", "is missing beside the parameterization of P²")
    h, tau = rat.h, rat.tau

    def tube(point: Point) -> int:
        y, z = point.of("y"), point.of("z")
        return (y * y + z * z - values(point, [h], t=point.of("x"))[0]) % point.prime

    def tau_maps_t_to_x(point: Point) -> bool:
        p = point.prime
        x, y, z = point.of("x"), point.of("y"), point.of("z")
        if y == 0 or z == 0:
            return True
        first, second, third = values(point, tau)
        along, _ = values(point, [phi, psi], t=x)
        ratio = second * pow(y, -1, p) % p
        h_x, psi_x = values(point, [h, psi], t=x)
        return (
            (first - along) % p == 0
            and (third * pow(z, -1, p) - ratio) % p == 0
            and (ratio * ratio * h_x - psi_x) % p == 0
        )

    ids.proportional_to(f"{where}.tubular_surface", "is not y² + z² − h(x)", rat.tubular_surface, tube, [h])
    ids.add(
        f"{where}.tau",
        "does not map T onto X (τ = (φ, d·y/q, d·z/q) with d²h/q² = ψ)",
        tau_maps_t_to_x,
        [*tau, phi, psi, h],
    )
    if rat.real_roots_of_h is not None:
        _check_real_roots(rat, h, where)
        if rat.unirational is not has_real_surface(formula(h), rat.real_roots_of_h):
            raise ClaimError(f"{where}.unirational", "does not follow from h (docs/math.md §5)")
        if rat.real_rational is not (bool(rat.unirational) and rat.real_roots_of_h <= 2):
            raise ClaimError(f"{where}.real_rational", "does not follow from the real roots of h (Table 1)")


def _check_absolute_factors(
    factors: tuple[str, ...], profile: Profile, multiplicity: int, where: str, ids: Identities
) -> None:
    """The absolute factors of ``p̃`` (each ``g  where m(a) = 0`` standing for its conjugates over
    ``QQ(a)``, perhaps ``(…)^k``) multiply to ``p̃`` up to a constant: the norm of each, the
    resultant in ``a`` with its minimal polynomial, is the product of its conjugates."""
    a = sympy.Symbol("a")
    product = sympy.Integer(1)
    for text in factors:
        body, power = text, 1
        if body.startswith("(") and ")^" in body:
            body, _, exponent = body[1:].rpartition(")^")
            power = int(exponent) if exponent.isdigit() else 0
        factor, _, minimal = body.partition("  where ")
        g = formula(factor)
        if minimal:
            g = sympy.resultant(g, formula(minimal.removesuffix(" = 0")), a)
        if power < 1 or g.has(a):
            raise ClaimError(where, f"holds a factor sorgui does not write: {text[:40]!r}")
        product *= g ** (power * multiplicity)

    def claimed(point: Point) -> int:
        return point.value(product)

    def profile_value(point: Point) -> int:
        return values(point, [profile.rational])[0]

    ids.add(
        where,
        "do not multiply to the profile p̃(s, r)",
        lambda P: proportional(claimed, profile_value, P),
        [profile.rational],
    )


def _check_real_roots(rat: Rationality, h: str, where: str) -> None:
    from ..revolution.rationality import count_real_roots_of

    expr = formula(h)
    if expr.has(sympy.I) or expr.free_symbols - {sympy.Symbol("t")}:
        raise ClaimError(f"{where}.h", "is not a real polynomial in t")
    generators = tuple(sorted({a for a in expr.atoms(sympy.Pow) if a.exp == sympy.Rational(1, 2)}, key=str))
    if expr.is_number:
        roots = 0
    else:
        roots = count_real_roots_of(expr, generators)
    if roots != rat.real_roots_of_h:
        raise ClaimError(f"{where}.real_roots_of_h", f"is {rat.real_roots_of_h}, but h has {roots} real roots")


def check_conical(conical: Conical, surface: Surface, where: str, ids: Identities) -> None:
    """The apex (``f(c + X)`` homogeneous), the direction (``f`` invariant along it), the base
    curve and the parameterizations of a cone or a cylinder."""
    K = surface.polynomial.ring.domain
    d = surface.degree
    ids.need(*surface.radicands)
    if conical.kind == "none":
        if conical.apex is not None or conical.direction is not None or conical.base_curve is not None:
            raise ClaimError(f"{where}.kind", "is none, but an apex, a direction or a base curve is given")
    if conical.kind == "cone" and conical.apex is None:
        raise ClaimError(f"{where}.apex", "is missing for a cone")
    if conical.kind == "cylinder" and conical.direction is None:
        raise ClaimError(f"{where}.direction", "is missing for a cylinder")
    if conical.apex is not None:
        apex = [to_expr(K, c) for c in vector(K, conical.apex, f"{where}.apex")]

        def homogeneous(point: Point) -> bool:
            p = point.prime
            c = [point.value(v) for v in apex]
            ray = [point.of(n) for n in ("x", "y", "z")]
            scale = point.of("t")
            near = surface.at(point, [(ci + xi) % p for ci, xi in zip(c, ray)])
            far = surface.at(point, [(ci + scale * xi) % p for ci, xi in zip(c, ray)])
            return (far - pow(scale, d, p) * near) % p == 0

        ids.add(f"{where}.apex", "is not the apex of a cone: f(c + X) is not homogeneous", homogeneous)
    if conical.direction is not None:
        a = [to_expr(K, c) for c in nonzero(vector(K, conical.direction, f"{where}.direction"), f"{where}.direction")]

        def invariant(point: Point) -> bool:
            p = point.prime
            xyz = [point.of(n) for n in ("x", "y", "z")]
            step = point.of("t")
            moved = [(v + step * point.value(c)) % p for v, c in zip(xyz, a)]
            return (surface.at(point, moved) - surface.at(point, xyz)) % p == 0

        ids.add(f"{where}.direction", "is not a direction along which the surface is invariant", invariant)
    if conical.base_curve is not None:
        _check_base_curve(conical, surface, f"{where}.base_curve", ids)
    for i, param in enumerate(conical.parametrizations):
        check_parametrization(param, surface, f"{where}.parametrizations[{i}]", ids)


def _check_base_curve(conical: Conical, surface: Surface, where: str, ids: Identities) -> None:
    base = conical.base_curve
    assert base is not None
    K = surface.polynomial.ring.domain
    first, second = base.variables
    if conical.kind == "cone" and base.chart is not None:
        chart = "xyz".index(base.chart.split("=")[0].strip())
        top = surface.top_form()
        free = [i for i in range(3) if i != chart]
        if sorted((first, second)) != sorted("xyz"[i] for i in free):
            raise ClaimError(f"{where}.variables", "are not the coordinates of its chart")

        def chart_value(point: Point) -> int:
            xyz = [1, 1, 1]
            for i in free:
                xyz[i] = point.of("xyz"[i])
            return top.at(point, xyz)

        ids.proportional_to(where, "is not the top-degree form of f in its chart", base.polynomial, chart_value)
        return
    if conical.kind == "cylinder" and None not in (base.frame_point, base.frame_u, base.frame_w):
        assert base.frame_point and base.frame_u and base.frame_w and conical.direction
        c = vector(K, base.frame_point, f"{where}.frame_point")
        u = nonzero(vector(K, base.frame_u, f"{where}.frame_u"), f"{where}.frame_u")
        w = nonzero(vector(K, base.frame_w, f"{where}.frame_w"), f"{where}.frame_w")
        a = vector(K, conical.direction, "conical.direction")
        if dot(u, a) or dot(w, a) or is_zero(cross(u, w)):
            raise ClaimError(where, "is not cut by a plane across the direction (frame_u, frame_w)")
        frame = [[to_expr(K, v) for v in vec] for vec in (c, u, w)]

        def section(point: Point) -> int:
            p = point.prime
            s, t = point.of(first), point.of(second)
            xyz = [
                (point.value(frame[0][i]) + s * point.value(frame[1][i]) + t * point.value(frame[2][i])) % p
                for i in range(3)
            ]
            return surface.at(point, xyz)

        ids.proportional_to(where, "is not the section of f by its plane", base.polynomial, section)
