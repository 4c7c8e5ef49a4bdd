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
``_`` makes a pattern; vectors are tuples, printed as lists. The parameter domain of a map and
the points it misses are stated by :mod:`sorgui.export.coverage`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING, Literal, TypeAlias

from sorgui.engine.results import Analysis, Approximation, Canal, Conical, Profile, Recognition
from sorgui.engine.stage_results import Parametrization, Rationality

if TYPE_CHECKING:
    import sympy

    from sorgui.export.coverage import Coverage

Value: TypeAlias = "sympy.Expr | tuple[sympy.Expr, ...]"
"""A formula's exact value (sympy is loaded when the first is read: the window lists formulas without it)."""

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
        from sorgui.engine.values import read_expression

        values = tuple(read_expression(text) for text in self.source)
        return values[0] if self.kind == "expression" else values

    @property
    def parameters(self) -> tuple[sympy.Symbol, ...]:
        import sympy

        return tuple(sympy.Symbol(p) for p in self.parameter_names)

    @property
    def is_vector(self) -> bool:
        return self.kind == "vector"

    @cached_property
    def coverage(self) -> Coverage | None:
        """The domain and missed points of a map (``None`` for the others), made when first asked for."""
        if self.domain is None:
            return None
        import sympy

        from sorgui.export.coverage import coverage

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
    cone or cylinder, then those of its canal sphere families; for rounded input, those of the
    nearest exact surface within its rounding (:func:`nearest_analysis_formulas`)."""
    return [f for f in catalogue(analysis) if f.name] + nearest_analysis_formulas(analysis)


NEAREST_PREFIX = "nearest"
"""The start of the files' names of the nearest exact surface's formulas (``nearestX1``)."""


def nearest_analysis_formulas(analysis: Analysis) -> list[Formula]:
    """For rounded input whose nearest exact surface ``g`` lies within the rounding, what the
    files print of ``g``'s own analysis: its profile, the rationality's curves and maps, and its
    parameterizations, named ``nearestP``, ``nearestX1`` and so on (the window shows them in the
    nearest surface's view, from its own analysis)."""
    approx = analysis.approximate
    nearest = approx.nearest if approx is not None else None
    if nearest is None or not nearest.within_rounding or nearest.analysis is None:
        return []
    exact = nearest.analysis
    formulas = _profile(exact.recognition.profile) if exact.recognition.profile is not None else []
    if exact.rationality is not None:
        formulas += _rationality(exact.rationality)
    formulas += _maps(exact)
    return [
        replace(
            f,
            key=f"approximate.nearest.analysis.{f.key}" if f.key else "",
            name=f"{NEAREST_PREFIX}{f.name[0].upper()}{f.name[1:]}",
            description=f"of the nearest exact surface g: {f.description}",
        )
        for f in formulas
        if f.name
    ]


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
    if len(analysis.factors) > 1 or any(factor.multiplicity > 1 for factor in analysis.factors):  # as the pane lists
        for index, factor in enumerate(analysis.factors):
            out.append(Formula("expression", (factor.polynomial,), f"factor.{index}"))
            out += [replace(f, name="") for f in _recognition(factor.recognition, f"factor.{index}.")]  # pane only
    if analysis.rationality is not None:
        out += _rationality(analysis.rationality)
    return out + _maps(analysis)


def _maps(analysis: Analysis) -> list[Formula]:
    """The parameterizations of ``X``: ``X1``, ``X2``, … (each says whether substitution verified
    it); the typed map's ``X1`` says how it was read (an angle ``u`` as ``t = tan(u/2)``), since
    a formula file has no report beside it."""
    maps = [_map(par, f"parametrization.{i}", f"X{i + 1}", "") for i, par in enumerate(analysis.parametrizations)]
    record = analysis.parametric
    if maps and record is not None and record.notes and analysis.input_kind == "parametrization":
        maps[0] = replace(maps[0], description=f"{maps[0].description}; {'; '.join(record.notes)}")
    return maps


def _map(par: Parametrization, key: str, name: str, how: str) -> Formula:
    """A parameterization of ``X`` (of the surface, or ``how`` = " by its lines"), its
    description ending in "NOT verified" when substitution did not verify it."""
    kind = "real" if par.real else "complex"
    proper = {True: "proper", False: "not proper", None: "properness not decided"}[par.proper]
    check = "" if par.verified else ", NOT verified"
    return Formula(
        "vector",
        par.coordinates,
        key,
        name,
        description=f"parameterization {name[1:]} of X{how}: {par.method} ({kind}, {proper}, over {par.field}{check})",
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
            Formula("decimal line", axis.point + axis.direction, f"{key}axis.decimal"),
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
        # Named (printed by the files) when within the rounding: the surface the input was meant to be.
        named = nearest.within_rounding
        where = "within the rounding of the input" if named else "beyond the rounding"
        out.append(
            Formula(
                "expression",
                (nearest.polynomial,),
                "approximate.nearest",
                "g" if named else "",
                "g =",
                f"the nearest exact surface g(x, y, z) = 0, {where}",
            )
        )
        if nearest.axis is not None:
            line = nearest.axis.point + nearest.axis.direction
            out.append(Formula("line", line, "approximate.nearest.axis"))
            out.append(Formula("decimal line", line, "approximate.nearest.axis.decimal"))
            if named:
                out += [
                    Formula("vector", nearest.axis.point, name="nearestAxisPoint", description="a point of g's axis"),
                    Formula(
                        "vector",
                        nearest.axis.direction,
                        name="nearestAxisDirection",
                        description="the direction of g's axis",
                    ),
                ]
    return out


def nearest_formulas(analysis: Analysis) -> list[Formula]:
    """The formulas the files print of rounded input: the nearest exact surface within the
    rounding and its axis."""
    return [f for f in _approximate(analysis.approximate) if f.name] if analysis.approximate is not None else []
