"""The one catalogue of an analysis' formulas: what the files print and the window typesets.

:func:`catalogue` lists every formula of an analysis once, in the engine's exact strings: its
key in the results pane, its name in the files, what it is (an expression, a vector, a line),
the label the pane puts before it and the sentence the files write about it. Building it reads
no formula, so the window can list the formulas at once; the exact sympy value of a formula
(read with :mod:`sorgui.engine.values`, never evaluated) and the coverage of a map are made
when first asked for. Every formula file (LaTeX, Maple, Mathematica, Python) prints the same
list, :func:`analysis_formulas`: the equation ``f``, the axis, the profile ``p`` and ``P²``,
the parameterization of ``P²``, the tubular surface ``T``, the map ``τ``, every
parameterization of ``X`` and the canal sphere families; the window typesets the formulas
with a key (:mod:`sorgui.session.formulas`).

Names are letters and digits only (``axisPoint``, not ``axis_point``), because in Mathematica
``_`` makes a pattern; vectors are tuples, printed as lists.

For every rational map, :class:`Coverage` states over which parameter domain it is defined and
which points it misses (docs/math.md, "Parameterizations"):

* **excluded parameter values**: the zeros of the denominators, as the irreducible factors
  of their product, with whether each has real zeros (decided exactly for factors in one
  parameter; stated as a curve ``g = 0`` of the parameter plane otherwise);
* **points reached only in a limit**: for each parameter ``p → ∞`` (the other one free), the
  limit of the map — a curve or a point of ``X`` that no finite value of ``p`` gives on that
  parameter line, such as the meridian at angle π of a rotation ``s ↦ ((1-s²)/(1+s²),
  2s/(1+s²))`` or the circle swept by the point at infinity of the profile — or the statement
  that the points run off to infinity (nothing affine is missed there).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any, Literal, TypeAlias

import sympy

from sorgui.engine.results import (
    Analysis,
    Approximation,
    Canal,
    Conical,
    Parametrization,
    Profile,
    Rationality,
    Recognition,
)
from sorgui.engine.values import read_expression

Value: TypeAlias = sympy.Expr | tuple[sympy.Expr, ...]


@dataclass(frozen=True)
class Excluded:
    """One irreducible factor ``g`` of the denominators: the map is undefined where ``g = 0``.

    ``real_zeros`` is ``True``/``False`` when decided exactly (``g`` in one parameter), ``None``
    for a curve in two parameters; ``roots`` are then its exact roots: the real ones for a real
    parameterization, all of them for a complex one.
    """

    factor: sympy.Expr
    real_zeros: bool | None
    roots: tuple[sympy.Expr, ...] = ()


@dataclass(frozen=True)
class Limit:
    """What the map tends to as ``parameter → ∞`` with the other parameters free.

    ``point`` is the limit (expressions in the remaining parameters), or ``None`` when some
    coordinate tends to infinity there (points at infinity: nothing affine is missed).
    ``check`` is an exact test at one sample value ``v`` of the other parameter: ``(v, missed)``
    with ``missed`` true when no parameter value at all, complex ones included, maps to the
    limit point there (a Gröbner basis of ``N_i - P_i·D_i = 0, u·D - 1 = 0`` is ``[1]``);
    ``None`` when the map is too large for the test or the limit is a curve of two parameters.
    """

    parameter: sympy.Symbol
    point: tuple[sympy.Expr, ...] | None
    check: tuple[sympy.Expr, bool] | None = None


@dataclass(frozen=True)
class Coverage:
    """The parameter domain of a rational map and the points it misses (module docstring)."""

    parameters: tuple[sympy.Symbol, ...]
    real: bool
    excluded: tuple[Excluded, ...]
    limits: tuple[Limit, ...]

    def lines(self, style: CoverageStyle | None = None) -> list[str]:
        """The coverage in words, one statement per line, with formulas printed by ``style``."""
        st = style or CoverageStyle()
        names = ", ".join(st.expr(p) for p in self.parameters)
        space = (st.real if self.real else st.complex) + st.power(len(self.parameters))
        out = [f"parameter domain: {st.math(f'({names}) {st.element} {space}')}"]
        if not self.excluded:
            out.append("no denominator: defined for every parameter value")
        for item in self.excluded:
            out.append(f"undefined where {st.math(st.expr(item.factor) + ' = 0')}: {_zeros_text(item, self.real, st)}")
        for limit in self.limits:
            tends = st.math(f"{st.expr(limit.parameter)} {st.to} {st.infinity}")
            if limit.point is None:
                out.append(f"as {tends} the points run off to infinity: no affine point is missed there")
                continue
            point = st.math("(" + ", ".join(st.expr(c) for c in limit.point) + ")")
            rest = [p for p in self.parameters if p != limit.parameter]
            moving = [p for p in rest if any(c.has(p) for c in limit.point)]
            what = f"the curve {point} over {', '.join(st.expr(p) for p in moving)}" if moving else f"the point {point}"
            fixed = f" with {', '.join(st.expr(p) for p in rest)} fixed" if rest else ""
            out.append(f"reached only as {tends}, by no finite {st.expr(limit.parameter)}{fixed}: {what}")
            if limit.check is not None and moving:
                value, missed = limit.check
                at = st.math(f"{st.expr(moving[0])} = {st.expr(value)}")
                out.append(
                    f"  checked exactly at {at}: "
                    + (
                        "no parameter value, complex ones included, gives that point: it is missed"
                        if missed
                        else "some other parameter value gives that point: it is not missed there"
                    )
                )
        return out


@dataclass(frozen=True)
class CoverageStyle:
    """How :meth:`Coverage.lines` prints formulas: sympy's syntax by default; the LaTeX, Maple
    and Mathematica writers pass their printers (``math`` wraps a formula, e.g. in ``$…$``)."""

    expr: Callable[[Any], str] = sympy.sstr
    math: Callable[[str], str] = str
    real: str = "R"
    complex: str = "C"
    element: str = "in"
    to: str = "->"
    infinity: str = "oo"
    power: Callable[[int], str] = field(default=lambda n: "" if n == 1 else f"^{n}")


def _zeros_text(item: Excluded, real: bool, st: CoverageStyle) -> str:
    if item.real_zeros is None:
        return "the real points of this curve of parameter values" if real else "a curve of parameter values"
    if real and not item.real_zeros:
        return "no real zeros"
    if not item.roots:
        return "it has real zeros"
    return ("the real zeros " if real else "the zeros ") + ", ".join(st.math(st.expr(r)) for r in item.roots)


def coverage(
    coordinates: tuple[sympy.Expr, ...], parameters: tuple[sympy.Symbol, ...], real: bool, limits: bool = True
) -> Coverage:
    """The domain and missed points of the rational map ``parameters ↦ coordinates``
    (``limits=False`` for a map of space such as ``τ``, where only the domain matters)."""
    fractions = [sympy.fraction(sympy.cancel(sympy.together(c))) for c in coordinates]
    factors: list[sympy.Expr] = []
    for _numerator, denominator in fractions:
        if not denominator.has(*parameters):
            continue
        for factor, _multiplicity in sympy.factor_list(denominator, *parameters)[1]:
            monic = sympy.Poly(factor, *parameters).monic().as_expr()
            if not any(sympy.expand(monic - known) == 0 for known in factors):
                factors.append(monic)
    excluded = tuple(_excluded(g, parameters, real) for g in factors)
    if not limits:
        return Coverage(parameters, real, excluded, ())
    return Coverage(
        parameters, real, excluded, tuple(_checked(_limit(fractions, p), fractions, parameters) for p in parameters)
    )


def _excluded(factor: sympy.Expr, parameters: tuple[sympy.Symbol, ...], real: bool) -> Excluded:
    used = [p for p in parameters if factor.has(p)]
    if len(used) != 1:
        return Excluded(factor, None)
    poly = sympy.Poly(factor, used[0])
    roots = sympy.roots(poly)
    if sum(roots.values()) != poly.degree():  # no closed form: count the real roots instead
        if not (poly.domain.is_QQ or poly.domain.is_ZZ):
            return Excluded(factor, None)
        return Excluded(factor, poly.count_roots() > 0)
    real_roots = [r for r in roots if r.is_real]
    shown = real_roots if real else list(roots)
    return Excluded(factor, bool(real_roots), tuple(sorted(shown, key=sympy.default_sort_key)))


def _limit(fractions: list[tuple[sympy.Expr, sympy.Expr]], parameter: sympy.Symbol) -> Limit:
    """The limit as ``parameter → ∞`` of each ``numerator/denominator`` (generic other parameters)."""
    point = []
    for numerator, denominator in fractions:
        top = sympy.Poly(numerator, parameter)
        bottom = sympy.Poly(denominator, parameter)
        if top.degree() > bottom.degree():
            return Limit(parameter, None)
        leading = top.coeff_monomial(parameter ** bottom.degree()) if top.degree() == bottom.degree() else 0
        point.append(sympy.cancel(leading / bottom.LC()))
    return Limit(parameter, tuple(point))


CHECK_MAX_DEGREE = 6
"""The exact missed-point test runs for maps of total degree at most this (it takes ~0.05 s at 5)."""

SAMPLE_VALUES = (sympy.Rational(7, 3), sympy.Rational(-5, 11), sympy.Rational(13, 2))
"""Sample values of the free parameter for that test (the first where the limit is defined)."""


def _checked(
    limit: Limit, fractions: list[tuple[sympy.Expr, sympy.Expr]], parameters: tuple[sympy.Symbol, ...]
) -> Limit:
    """``limit`` with its exact missed-point test (see :class:`Limit`), when it is affordable."""
    rest = [p for p in parameters if p != limit.parameter]
    if limit.point is None or len(rest) != 1:
        return limit
    degree = max(sympy.Poly(e, *parameters).total_degree() for pair in fractions for e in pair)
    if degree > CHECK_MAX_DEGREE:
        return limit
    other = rest[0]
    for value in SAMPLE_VALUES:
        if any(sympy.fraction(sympy.together(c))[1].subs(other, value) == 0 for c in limit.point):
            continue
        target = [sympy.cancel(c.subs(other, value)) for c in limit.point]
        u = sympy.Dummy("u")
        denominator = sympy.prod([d for _n, d in fractions])
        equations = [sympy.expand(n - pc * d) for (n, d), pc in zip(fractions, target)]
        basis = sympy.groebner([*equations, sympy.expand(u * denominator - 1)], u, *parameters, order="grevlex")
        return Limit(limit.parameter, limit.point, (value, list(basis.exprs) == [1]))
    return limit


Kind: TypeAlias = Literal["expression", "vector", "line", "decimal line", "approximate line"]
"""What the source strings of a formula are: one expression, the entries of a vector, or a line
``c + t·a`` (the entries of ``c``, then those of ``a``): exact, exact but shown in decimals, or
known only in floats (:attr:`Formula.numbers`, no source strings)."""

XYZ_ROWS = (("x", "x ="), ("y", "y ="), ("z", "z ="))
"""The pane's rows of a map to space: one per coordinate."""


@dataclass(frozen=True)
class Formula:
    """One formula of an analysis, as the engine's exact strings ``source``.

    ``key`` names it in the results pane and ``name`` in the files (``""``: not there);
    ``label`` is the LaTeX the pane writes before it, ``description`` the files' sentence.
    ``rows`` show a vector in the pane one entry per row: ``(suffix, label)``, keyed
    ``f"{key}.{suffix}"``. A map whose coverage the files state has a ``domain``:
    ``"parameters"`` (the parameter domain and the missed points) or ``"space"`` (a map of
    space such as τ: the domain only); ``real`` says whether it is real (``None``: real when no
    entry has ``I``). An approximate line is known only in floats: ``numbers`` (the point, then
    the direction), with ``tolerance`` the rounding of the input (smaller entries are 0).
    """

    kind: Kind
    source: tuple[str, ...]
    key: str = ""
    name: str = ""
    label: str = ""
    description: str = ""
    rows: tuple[tuple[str, str], ...] = ()
    parameter_names: tuple[str, ...] = ()
    domain: Literal["parameters", "space"] | None = None
    real: bool | None = None
    numbers: tuple[float, ...] = ()
    tolerance: float | None = None

    @cached_property
    def value(self) -> Value:
        """The exact value, read from :attr:`source` when first asked for (a tuple for a vector)."""
        values = tuple(read_expression(text) for text in self.source)
        return values[0] if self.kind == "expression" else values

    @property
    def parameters(self) -> tuple[sympy.Symbol, ...]:
        return tuple(sympy.Symbol(p) for p in self.parameter_names)

    @property
    def is_vector(self) -> bool:
        return self.kind == "vector"

    @cached_property
    def coverage(self) -> Coverage | None:
        """The domain and missed points of a map (``None`` for the others), made when first asked for."""
        if self.domain is None:
            return None
        value = self.value
        assert isinstance(value, tuple)
        real = not any(c.has(sympy.I) for c in value) if self.real is None else self.real
        return coverage(value, self.parameters, real, limits=self.domain == "parameters")


def catalogue(analysis: Analysis) -> list[Formula]:
    """Every formula of ``analysis`` in reading order: the surface's, the cone's or cylinder's,
    the canal sphere families', and those of rounded input."""
    out = _surface(analysis)
    if analysis.conical is not None:
        out += _conical(analysis.conical)
    if analysis.canal is not None:
        out += _canal(analysis.canal)
    if analysis.approximate is not None:
        out += _approximate(analysis.approximate)
    return out


def analysis_formulas(analysis: Analysis) -> list[Formula]:
    """The formulas the files print, in reading order: those of the surface of revolution, of a
    cone or cylinder, then those of its canal sphere families."""
    return [f for f in catalogue(analysis) if f.name]


def surface_formulas(analysis: Analysis) -> list[Formula]:
    """The equation and the results of the surface-of-revolution analysis that the files print."""
    return [f for f in _surface(analysis) if f.name]


def _surface(analysis: Analysis) -> list[Formula]:
    """The equation, the axis or centre, the profile, the factors, the rationality and the parameterizations."""
    rec = analysis.recognition
    out = []
    if rec.polynomial:  # a parametrization's implicit equation may not be known
        out.append(Formula("expression", (rec.polynomial,), "polynomial", "f", "f =", "the equation f(x, y, z) = 0"))
    out += _recognition(rec, "")
    if rec.profile is not None:
        out += _profile(rec.profile)
    if len(analysis.factors) > 1:
        for index, factor in enumerate(analysis.factors):
            out.append(Formula("expression", (factor.polynomial,), f"factor.{index}"))
            out += [replace(f, name="") for f in _recognition(factor.recognition, f"factor.{index}.")]  # pane only
    if analysis.rationality is not None:
        out += _rationality(analysis.rationality)
    out += [
        _map(par, f"parametrization.{index}", f"X{index + 1}", "")
        for index, par in enumerate(analysis.parametrizations)
    ]
    return out


def _map(par: Parametrization, key: str, name: str, how: str) -> Formula:
    """A verified parameterization of ``X`` (of the surface, or ``how`` = " by its lines")."""
    kind = "real" if par.real else "complex"
    proper = {True: "proper", False: "not proper", None: "properness not decided"}[par.proper]
    return Formula(
        "vector",
        par.coordinates,
        key,
        name,
        description=f"parameterization {name[1:]} of X{how}: {par.method} ({kind}, {proper}, over {par.field})",
        rows=XYZ_ROWS,
        parameter_names=par.parameters,
        domain="parameters",
        real=par.real,
    )


def _recognition(rec: Recognition, key: str) -> list[Formula]:
    """The axis, centre, normal, direction and radius² of ``rec``, keyed from ``key``."""
    out = []
    if rec.axis is not None:
        axis = rec.axis
        out += [
            Formula("vector", axis.point, f"{key}axis.point", "axisPoint", description="a point of the axis"),
            Formula(
                "vector",
                axis.direction,
                f"{key}axis.direction",
                "axisDirection",
                description="the direction of the axis",
            ),
            Formula("vector", axis.plucker, f"{key}axis.plucker"),
            Formula("line", axis.point + axis.direction, f"{key}axis.line"),
        ]
    vectors = (
        ("center", rec.center, "the centre of the sphere"),
        ("normal", rec.normal, "the normal of the plane"),
        ("direction", rec.direction, "the direction of the extrusion"),
    )
    for name, value, text in vectors:
        if value is not None:
            out.append(Formula("vector", value, key + name, name, description=text))
    if rec.radius_squared is not None:
        text = "the square of the sphere's radius"
        out.append(Formula("expression", (rec.radius_squared,), f"{key}radius_squared", "radiusSquared", "r^2 =", text))
    return out


def _profile(profile: Profile) -> list[Formula]:
    """The profile ``p``, ``P²``, its K-rational forms and the axis frame they live in."""
    frame = ", ".join(f"({', '.join(v)})" for v in (profile.frame_point, profile.frame_direction, profile.frame_normal))
    return [
        Formula(
            "expression",
            (profile.polynomial,),
            "profile.polynomial",
            "p",
            "p(x, y) =",
            "the profile p(x, y) = 0 (x along the axis, y the distance to it)",
        ),
        Formula(
            "expression",
            (profile.square,),
            "profile.square",
            "P2",
            "P^2(x, y) =",
            "the curve P2 = 0 (the profile p with y^2 replaced by y)",
        ),
        Formula(
            "expression",
            (profile.rational_square,),
            name="P2K",
            description="the curve P2K(s, w) = 0: the K-rational profile in the points c + s*a + r*u "
            f"with w = r^2, for (c, a, u) = {frame}",
        ),
        Formula("expression", (profile.rational,), "profile.rational", label=r"\tilde{p}(s, r) ="),
        Formula("vector", profile.frame_point, "profile.frame_point", label="c ="),
        Formula("vector", profile.frame_direction, "profile.frame_direction", label="a ="),
        Formula("vector", profile.frame_normal, "profile.frame_normal", label="u ="),
    ]


def _rationality(rat: Rationality) -> list[Formula]:
    """The parameterization of ``P²``, the tubular surface ``T``, ``h`` and the map ``τ``."""
    out = []
    if rat.square_parametrization:
        out.append(
            Formula(
                "vector",
                rat.square_parametrization,
                "rationality.square_parametrization",
                "P2param",
                description="a parameterization t -> (s(t), w(t)) of the curve P2K = 0",
                rows=(("0", r"\varphi ="), ("1", r"\rho =")),
                parameter_names=("t",),
                domain="parameters",
            )
        )
    if rat.tubular_surface:
        text = "the tubular surface T(x, y, z) = 0 (in the axis frame of the profile)"
        out.append(Formula("expression", (rat.tubular_surface,), "rationality.tubular_surface", "T", "T:", text))
    if rat.h:
        out.append(Formula("expression", (rat.h,), "rationality.h", label="h ="))
    if rat.tau:
        out.append(
            Formula(
                "vector",
                rat.tau,
                "rationality.tau",
                "tau",
                description="the map tau from T to X (in the axis frame of the profile)",
                rows=tuple((c, rf"\tau_{c} =") for c in "xyz"),
                parameter_names=("x", "y", "z"),
                domain="space",
                real=True,
            )
        )
    return out


def _conical(conical: Conical) -> list[Formula]:
    """The apex or direction of a cone or cylinder, its base curve and its parameterizations."""
    out = []
    if conical.apex is not None:
        text = "the apex of the cone (every line through it lies on X)"
        out.append(Formula("vector", conical.apex, "conical.apex", "coneApex", "c =", text))
    if conical.direction is not None:
        text = "the direction of the cylinder (every line along it through a point of X lies on X)"
        out.append(Formula("vector", conical.direction, "conical.direction", "cylinderDirection", "a =", text))
    base = conical.base_curve
    if base is not None:
        u, v = base.variables
        where = f"in the chart {base.chart}" if base.chart is not None else f"{u}·U + {v}·W across the direction"
        text = f"the base curve g({u}, {v}) = 0, {where}"
        out.append(Formula("expression", (base.polynomial,), "conical.base", "baseCurve", f"g({u}, {v}) =", text))
        for name, label in (("frame_u", "U"), ("frame_w", "W")):
            value = getattr(base, name)
            if value is not None:
                text = f"the vector {label} of the base curve's plane"
                out.append(Formula("vector", value, f"conical.base.{name}", f"baseCurve{label}", f"{label} =", text))
    for index, part in enumerate(conical.components, 1):
        u, v = part.variables
        genus = f"genus {part.genus}" if part.genus is not None else "genus undecided"
        text = f"component {index} of the reducible base curve (degree {part.degree}, {genus})"
        key, name = f"conical.component.{index}", f"baseCurveComponent{index}"
        out.append(Formula("expression", (part.polynomial,), key, name, f"g_{index}({u}, {v}) =", text))
    for index, par in enumerate(conical.parametrizations):
        out.append(_map(par, f"conical.parametrization.{index}", f"C{index + 1}", " by its lines"))
    return out


CANAL_PREFIX = "canal"
"""Every canal formula's name starts with this and the family's number: ``canal1Spine``, ``canal1M``."""


def canal_formulas(canal: Canal) -> list[Formula]:
    """The sphere families of a canal surface (docs/math.md §9) that the files print, for each
    family ``i`` with data: ``canal{i}Spine`` (the spine's equations in ``m1, m2, m3``),
    ``canal{i}SMAT`` (the SMAT curve's in ``m1, m2, m3, r``, ``r`` = ρ), ``canal{i}M`` (the spine
    ``m(t)``), ``canal{i}Rho`` (the squared radius ``r²(t)``), ``canal{i}C`` and ``canal{i}R2``
    (the characteristic circles' centre ``c(t)`` and squared radius ``R²(t)``)."""
    return [f for f in _canal(canal) if f.name]


def _canal(canal: Canal) -> list[Formula]:
    """Each sphere family's equations, spine ``m(t)``, squared radius ``r²(t)`` and characteristic circles."""
    out: list[Formula] = []
    for index, fam in enumerate(canal.families):
        i = index + 1
        name = f"{CANAL_PREFIX}{i}"
        radius = "constant" if fam.pipe else "varying"
        shape = "on a line" if fam.on_line else "planar" if fam.planar else "not planar"
        genus = "undecided" if fam.genus is None else fam.genus
        out += [
            Formula(
                "vector",
                fam.spine_equations,
                name=f"{name}Spine",
                description=f"the spine of sphere family {i} (centres m1, m2, m3; degree {fam.degree}, {shape}): "
                "these equations are zero",
            ),
            Formula(
                "vector",
                fam.equations,
                name=f"{name}SMAT",
                description=f"the SMAT curve of sphere family {i} (centre m1, m2, m3, squared radius r; "
                f"genus {genus}, radius {radius}): these equations are zero",
            ),
        ]
        spine = f"canal.{index}.spine"
        if fam.parametrization is not None:
            check = "verified" if fam.verified else "not verified"
            text = f"the spine t -> m(t) of sphere family {i} (over {fam.field}, {check})"
            out.append(
                Formula(
                    "vector",
                    fam.parametrization,
                    spine,
                    f"{name}M",
                    "m(t) =",
                    text,
                    parameter_names=("t",),
                    domain="parameters",
                )
            )
        elif fam.radical_spine is not None:
            text = (
                f"the spine t -> m(t) of sphere family {i} in square roots "
                f"(t = {fam.radical_parameter}; verified on the SMAT equations)"
            )
            out.append(Formula("vector", fam.radical_spine, spine, f"{name}M", "m(t) =", text, parameter_names=("t",)))
        rho = fam.radius_squared or fam.radical_radius_squared
        if rho is not None:
            text = f"the squared radius r^2(t) of the spheres of family {i} ({radius})"
            out.append(Formula("expression", (rho,), f"canal.{index}.radius", f"{name}Rho", r"r^2(t) =", text))
        if fam.circle_center is not None:
            out.append(
                Formula(
                    "vector",
                    fam.circle_center,
                    name=f"{name}C",
                    description=f"the centre t -> c(t) of the characteristic circles of family {i}",
                    parameter_names=("t",),
                    domain="parameters",
                )
            )
        if fam.circle_radius_squared is not None:
            text = f"the squared radius R2(t) of the characteristic circles of family {i}"
            out.append(Formula("expression", (fam.circle_radius_squared,), name=f"{name}R2", description=text))
        if fam.circle_normal is not None:
            text = f"the normal n(t) of the planes of the characteristic circles of family {i}"
            out.append(Formula("vector", fam.circle_normal, name=f"{name}N", description=text))
    return out


def _approximate(approx: Approximation) -> list[Formula]:
    """The approximate axis of rounded input, the nearest exact surface and its axis."""
    out = []
    if approx.axis is not None:
        numbers = (*approx.axis.point, *approx.axis.direction)
        out.append(Formula("approximate line", (), "approximate.axis", numbers=numbers, tolerance=approx.tolerance))
    nearest = approx.nearest
    if nearest is not None:
        out.append(Formula("expression", (nearest.polynomial,), "approximate.nearest", label="g ="))
        if nearest.axis is not None:
            line = nearest.axis.point + nearest.axis.direction
            out.append(Formula("line", line, "approximate.nearest.axis"))
            out.append(Formula("decimal line", line, "approximate.nearest.axis.decimal"))
    return out
