"""A report's canal surface checked against its polynomial (docs/math.md §9, §14).

For a sphere family with a rational spine ``m(t)`` and squared radius ``ρ(t)`` (or one in
square roots): ``(m, ρ)`` lies on the SMAT equations, ``m`` on the spine's and ``(u, v)`` on
the plane model; a pipe has a constant radius. The characteristic circle (centre ``c(t)``,
squared radius ``R²(t)``, normal ``n(t)``) is the circle where the sphere ``|X − m|² = ρ``
meets its neighbour: ``n ∥ m'``, ``c − m ∥ m'``, ``2(c − m)·m' = −ρ'``, ``|c − m|² + R² = ρ``;
and it lies on ``f`` (a random point of it substituted). The parameterizations by circles
are checked as every parameterization (:mod:`.maps`), and a witness line's restriction is ``f``
on that line. A family given only by its SMAT equations (a spine of positive genus without
square roots) is drawn from them and not derived again.
"""

from __future__ import annotations

from ..algebra.modular import Point, Redraw
from ..errors import ClaimError
from ..results import Canal, CanalEvidence
from ..stage_results import CanalFamily
from .formulas import Surface, formula, values
from .identities import Identities
from .maps import check_parametrization

SMAT = ("m1", "m2", "m3", "r")


KINDS = ("developable", "dupin", "pipe", "revolution")
"""The kinds of canal surface a report may name (:func:`.canal.verdict.analyze_canal`)."""


def check_canal(canal: Canal, surface: Surface, is_sor: bool, where: str, ids: Identities) -> None:
    """The families, the parameterizations by circles and the witness of ``canal``."""
    if canal.is_canal is not True and (canal.kinds or canal.families or canal.parametrizations):
        raise ClaimError(f"{where}.is_canal", "is not true, but sphere families or kinds are given")
    unknown = sorted(set(canal.kinds) - set(KINDS))
    if unknown:
        raise ClaimError(f"{where}.kinds", f"holds {unknown[0]!r}, which is none of {', '.join(KINDS)}")
    if "revolution" in canal.kinds and not is_sor:
        raise ClaimError(f"{where}.kinds", "holds 'revolution' for a surface that is not one of revolution")
    if canal.is_canal is True and is_sor and "revolution" not in canal.kinds:
        raise ClaimError(f"{where}.kinds", "lacks 'revolution' for a surface of revolution")
    if any(family.pipe for family in canal.families) and "pipe" not in canal.kinds:
        raise ClaimError(f"{where}.kinds", "lacks 'pipe', but a sphere family has a constant radius")
    ids.need(*surface.radicands)
    for i, family in enumerate(canal.families):
        check_family(family, surface, f"{where}.families[{i}]", ids)
    for i, param in enumerate(canal.parametrizations):
        check_parametrization(param, surface, f"{where}.parametrizations[{i}]", ids)
    if canal.witness is not None:
        check_witness(canal.witness, surface, f"{where}.witness", ids)


def check_family(family: CanalFamily, surface: Surface, where: str, ids: Identities) -> None:
    """One sphere family: its spine and radius on its equations, its characteristic circles on ``f``."""
    if family.parametrization is not None and family.radius_squared is not None:
        spine, radius = family.parametrization, family.radius_squared
        _on_equations(family, spine, radius, family.parameter, where, ids)
        t = family.parameter

        def moving(point: Point) -> bool:
            other = point.fresh()
            return values(point, [*spine, radius]) != values(other, [*spine, radius])

        ids.add(f"{where}.parametrization", "is constant", moving, [*spine, radius])
        if family.pipe:
            ids.add(
                f"{where}.pipe",
                "is claimed, but the radius varies",
                lambda P: values(P, [radius]) == values(P.fresh(), [radius]),
                [radius],
            )
        if None not in (family.circle_center, family.circle_radius_squared, family.circle_normal):
            _check_circles(family, t, surface, where, ids)
    elif family.radical_spine is not None and family.radical_radius_squared is not None:
        _on_equations(family, family.radical_spine, family.radical_radius_squared, "t", where, ids, "radical_spine")
        if family.radius_squared is not None:  # a pipe's constant radius beside its spine in roots
            radius, radical = family.radius_squared, family.radical_radius_squared
            ids.add(
                f"{where}.radius_squared",
                "is not the family's squared radius",
                lambda P: values(P, [radius]) == values(P, [radical]),
                [radius, radical],
            )


def _on_equations(
    family: CanalFamily,
    spine: tuple[str, str, str],
    radius: str,
    parameter: str,
    where: str,
    ids: Identities,
    name: str = "parametrization",
) -> None:
    texts = [*spine, radius]
    projection = family.projection

    def on_smat(point: Point) -> bool:
        p = point.prime
        coordinates = values(point, texts)
        named = dict(zip(SMAT, coordinates))
        if any(values(point, [e], **named)[0] for e in family.equations):
            return False
        if any(values(point, [e], **{k: named[k] for k in SMAT[:3]})[0] for e in family.spine_equations):
            return False
        if len(projection) == 2 and all(len(row) == 4 for row in projection):
            u, v = (sum(c * x for c, x in zip(row, coordinates)) % p for row in projection)
            return values(point, [family.plane_model], u=u, v=v)[0] == 0
        return True

    ids.add(
        f"{where}.{name}",
        "does not lie on the family's SMAT equations",
        on_smat,
        [*texts, *family.equations, *family.spine_equations, family.plane_model],
    )


def _check_circles(family: CanalFamily, t: str, surface: Surface, where: str, ids: Identities) -> None:
    assert family.parametrization and family.radius_squared and family.circle_center and family.circle_normal
    assert family.circle_radius_squared is not None
    m = [formula(c) for c in family.parametrization]
    rho = formula(family.radius_squared)
    centre, normal = list(family.circle_center), list(family.circle_normal)
    radius_squared = family.circle_radius_squared

    def characteristic(point: Point) -> bool:
        p = point.prime
        jets = [point.jet(c, t) for c in m]
        mv, dm = [v for v, _ in jets], [d for _, d in jets]
        drho = point.jet(rho, t)[1]
        c = values(point, centre)
        n = values(point, normal)
        rv, r2 = point.value(rho), values(point, [radius_squared])[0]
        offset = [(ci - mi) % p for ci, mi in zip(c, mv)]
        return (
            _parallel(n, dm, p)
            and _parallel(offset, dm, p)
            and (2 * _dot(offset, dm) + drho) % p == 0
            and (_dot(offset, offset) + r2 - rv) % p == 0
        )

    def on_surface(point: Point) -> bool:
        p = point.prime
        c = values(point, centre)
        n = values(point, normal)
        r2 = values(point, [radius_squared])[0]
        helper = [1, 0, 0] if n[1] or n[2] else [0, 1, 0]
        e1 = _cross(n, helper, p)
        e2 = _cross(n, e1, p)
        length1, length_n = _dot(e1, e1) % p, _dot(n, n) % p
        if length1 == 0 or length_n == 0:
            raise Redraw("the circle's frame is degenerate at the point")
        if r2 == 0:
            return surface.at(point, c) == 0  # a circle of radius 0: its centre
        # A point α·e1 + β·e2 from the centre: α²·|e1|² + β²·|n|²·|e1|² = r² (|e2|² = |n|²·|e1|²).
        # β is drawn and α is a root: a conic over F_p has points whatever p, and about every
        # second β serves. (Roots of r²/|e1|² and r²/(|e1|²·|n|²) at once may exist for no point
        # at all modulo p: a torus's circles about the axis (2, -2, 1) need √5.)
        beta = point.of(f"circle beta {where}")
        alpha_squared = (r2 - beta * beta * length1 * length_n) * pow(length1, -1, p) % p
        alpha = point.root(("circle", where, "alpha"), alpha_squared)
        xyz = [(ci + alpha * a + beta * b) % p for ci, a, b in zip(c, e1, e2)]
        return surface.at(point, xyz) == 0

    texts = [*family.parametrization, family.radius_squared, *centre, *normal, radius_squared]
    ids.add(f"{where}.circle_center", "is not the family's characteristic circle", characteristic, texts)
    ids.add(f"{where}.circle_center", "is a circle that does not lie on the surface", on_surface, texts)


def check_witness(witness: CanalEvidence, surface: Surface, where: str, ids: Identities) -> None:
    """A witness line's restriction is ``f(point + τ·direction)`` up to a constant."""
    if witness.point is None or witness.direction is None or witness.restriction is None:
        return
    point_texts, direction_texts, restriction = witness.point, witness.direction, witness.restriction

    def line(point: Point) -> int:
        p = point.prime
        tau = point.of("tau")
        c, a = values(point, point_texts), values(point, direction_texts)
        return surface.at(point, [(ci + tau * ai) % p for ci, ai in zip(c, a)])

    ids.proportional_to(
        f"{where}.restriction", "is not f on the witness line", restriction, line, [*point_texts, *direction_texts]
    )


def _dot(u: list[int], v: list[int]) -> int:
    return sum(a * b for a, b in zip(u, v))


def _cross(u: list[int], v: list[int], p: int) -> list[int]:
    return [(u[1] * v[2] - u[2] * v[1]) % p, (u[2] * v[0] - u[0] * v[2]) % p, (u[0] * v[1] - u[1] * v[0]) % p]


def _parallel(u: list[int], v: list[int], p: int) -> bool:
    return not any(_cross(u, v, p))
