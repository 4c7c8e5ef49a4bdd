"""A parametrization's report checked against its map (docs/math.md §13, §14).

The map is the report's truth: its input is read again by the parametrization reader, as if
typed, and the engine's own exact decision from the map (:mod:`..parametric.detect`: the
symmetry algebra of the normal lines, the apex and the cylinder directions, milliseconds) is
computed again. The report's exact map must be the parsed one (the same rational functions,
tested at random points when it is not printed alike), its field and degree the parsed map's;
its symmetry, apex and directions those of the map; the profile curve ``F(h, ρ)`` must vanish
on ``(h, ρ) = (a·(P − c), |P − c|²)`` about the map's axis, by the route the symmetry allows.

When the implicit equation is known, the report's polynomial ``f`` must vanish on the map
(``f(P(s, t)) = 0`` at random points), be ``F(a·(p − c), |p − c|²)`` up to a constant when the
profile curve gave it, and, over ``QQ``, be irreducible (flint factors it in milliseconds): a
multiple of the image's equation vanishes on the map too. The rest of the report is then
checked against ``f`` as an equation's (:mod:`.report`). When it is not known (``""``), nothing
may claim what only ``f`` decides: the recognition is checked against the map's symmetry, the
cone or cylinder against the map's apex and directions, and every verified parameterization
must be the map itself.

Properness is not derived again (Singular's fibres): only its claims must agree with each
other, the number of points of the fibre and ``proper``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from sympy.polys.domains.domain import Domain

from ..algebra import linalg
from ..algebra.linalg import sub
from ..algebra.modular import Point
from ..algebra.polys import XYZ, Poly, field_name, is_rational_field, poly_ring, to_expr, to_flint, total_degree
from ..conical.detect import Conicity
from ..errors import AnalysisError, ClaimError, ParseError
from ..parametric.detect import conicity, parametric_symmetry
from ..parametric.implicit import implicit_route
from ..parametric.maps import RationalMap, fraction_text
from ..parametric_parsing import parse_parametrization
from ..recognition.symmetry import Symmetry
from ..results import UNDECIDED, Analysis, Canal, Conical, Recognition
from ..stage_results import GIVEN_MAP, ParametricInput, Parametrization
from .formulas import Surface, formula, nonzero, read_polynomial, values, vector
from .identities import Identities, proportional
from .maps import check_parametrization_form
from .recognition import check_basis, check_symmetry, undecided

NEEDS_EQUATION = "is given, but the implicit equation is not known: there is nothing to check it against"


class MapTruth:
    """The parsed map of a report's input and what the engine decides from it."""

    def __init__(self, analysis: Analysis, where: str) -> None:
        try:
            parsed = parse_parametrization(analysis.input)
        except ParseError as exc:
            raise ClaimError(f"{where}input", f"is not a parametrization sorgui reads: {exc.message}") from None
        self.map: RationalMap = parsed.map
        self.K: Domain = parsed.field
        self.radicands = parsed.radicands
        self.texts = tuple(fraction_text(self.map.ring, n, d) for n, d in self.map.fractions())
        """``P`` as exact strings in ``s, t`` (the engine's printer)."""
        try:
            self.symmetry: Symmetry = parametric_symmetry(self.map)
            self.cones: Conicity = conicity(self.map)
        except AnalysisError as exc:
            raise ClaimError(f"{where}parametric.symmetry", f"cannot be: {exc.message}") from None

    def on_map(self, point: Point) -> list[int]:
        """``P(s, t)`` at the point (its residues of ``s`` and ``t``)."""
        return values(point, self.texts)

    def profile(self, point: Point, xyz: Sequence[int]) -> tuple[int, int]:
        """``(h, ρ) = (a·(p − c), |p − c|²)`` at ``p = xyz`` about the map's axis."""
        c, a = self.axis()
        p = point.prime
        offset = [(v - point.value(ci)) % p for v, ci in zip(xyz, c)]
        h = sum(o * point.value(ai) for o, ai in zip(offset, a)) % p
        return h, sum(o * o for o in offset) % p

    def axis(self) -> tuple[list[Any], list[Any]]:
        sym = self.symmetry
        assert sym.axis_point is not None and sym.axis_direction is not None  # a unique axis
        return [to_expr(self.K, v) for v in sym.axis_point], [to_expr(self.K, v) for v in sym.axis_direction]


def check_parametric(analysis: Analysis, where: str, ids: Identities) -> Surface | None:
    """The claims of a parametrization's report about its map; the implicit equation as a
    :class:`Surface` over the map's field, ``None`` when the report does not know it (then every
    other claim has been checked here)."""
    truth = MapTruth(analysis, where)
    record = analysis.parametric
    if record is None:
        raise ClaimError(f"{where}parametric", "is missing for a parametrization")
    K = truth.K
    if analysis.field != field_name(K):
        raise ClaimError(f"{where}field", f"is {analysis.field}, but the map's coefficients lie in {field_name(K)}")
    ids.need(*truth.radicands)
    _check_record(record, truth, f"{where}parametric.", ids)
    for i, given in enumerate(analysis.parametrizations):
        if given.method == GIVEN_MAP and given.proper != record.proper:
            raise ClaimError(
                f"{where}parametrizations[{i}].proper",
                f"is {given.proper}, but the given map's is {record.proper} (parametric.proper)",
            )
    known = bool(analysis.recognition.polynomial)
    if known and record.implicit_method is None:
        raise ClaimError(f"{where}parametric.implicit_method", "is missing, but the report has an implicit equation")
    if not known and record.implicit_method is not None:
        raise ClaimError(
            f"{where}parametric.implicit_method", "says how the implicit equation was found: it is missing"
        )
    if not known:
        _check_without_equation(analysis, truth, where, ids)
        return None
    surface = _implicit_equation(analysis, record, truth, where, ids)
    if analysis.conical is not None and surface.degree > 1:  # a plane is neither, as an equation
        _check_map_conical(analysis.conical, truth, K, f"{where}conical", known=True)
    return surface


def _check_record(record: ParametricInput, truth: MapTruth, where: str, ids: Identities) -> None:
    """The map, its field and degree, its symmetry, apex, directions, profile curve and fibre."""
    K = truth.K
    if record.field != field_name(K):
        raise ClaimError(f"{where}field", f"is {record.field}, but the map's coefficients lie in {field_name(K)}")
    if record.degree != truth.map.degree:
        raise ClaimError(f"{where}degree", f"is {record.degree}, but the map has degree {truth.map.degree}")
    if len(set(record.map_parameters)) != 2:
        raise ClaimError(f"{where}map_parameters", "must be two different names")
    _check_same_map(record.map, record.map_parameters, truth, f"{where}map", ids)
    sym, cones = truth.symmetry, truth.cones
    if record.symmetry == UNDECIDED:
        decided = (record.symmetry_dimension, record.symmetry_basis, record.conical, record.apex, record.directions)
        if decided != (0, (), "none", None, ()) or record.profile_check is not None or record.implicit_method:
            raise ClaimError(f"{where}symmetry", "is undecided, but the report gives what it decides")
        return
    if record.symmetry != sym.kind or record.symmetry_dimension != sym.dimension:
        raise ClaimError(
            f"{where}symmetry",
            f"is {record.symmetry!r} of dimension {record.symmetry_dimension}, but the map's normal lines "
            f"have the symmetry algebra {sym.kind!r} of dimension {sym.dimension}",
        )
    check_basis(record.symmetry_basis, sym, K, f"{where}symmetry_basis")
    if record.conical != cones.kind:
        raise ClaimError(f"{where}conical", f"is {record.conical!r}, but the map's is {cones.kind!r}")
    _check_apex(record.apex, cones, K, f"{where}apex")
    claimed = [
        nonzero(vector(K, d, f"{where}directions[{i}]"), f"{where}directions[{i}]")
        for i, d in enumerate(record.directions)
    ]
    true = list(cones.directions)
    if (
        len(claimed) != len(true)
        or linalg.rank(claimed, 3, K) != len(true)
        or linalg.rank(true + claimed, 3, K) != len(true)
    ):
        raise ClaimError(f"{where}directions", "do not span the directions along which the map's image is a cylinder")
    one_axis = sym.axis_point is not None and sym.axis_direction is not None
    if record.profile_check is not (True if one_axis else None):
        raise ClaimError(f"{where}profile_check", "must be true about one axis and null without one")
    route = implicit_route(sym, cones)
    if record.implicit_method is not None and record.implicit_method != route:
        raise ClaimError(
            f"{where}implicit_method", f"is {record.implicit_method!r}, but a map of its symmetry has it by {route!r}"
        )
    if (record.profile_curve is not None) != (record.implicit_method == "profile curve"):
        raise ClaimError(f"{where}profile_curve", "must be given exactly when the implicit equation comes from it")
    if record.profile_curve is not None:
        _check_profile_curve(record.profile_curve, truth, f"{where}profile_curve", ids)
    if record.fibre is None:
        if record.proper is not None:
            raise ClaimError(f"{where}proper", "is claimed without the fibre that decides it")
    elif record.fibre < 1 or record.proper is not (record.fibre == 1) or record.proper_method is None:
        raise ClaimError(f"{where}proper", f"does not follow from a fibre of {record.fibre} points")


def _check_same_map(claimed: Sequence[str], names: Sequence[str], truth: MapTruth, where: str, ids: Identities) -> None:
    """``claimed`` in the two parameters ``names`` is the parsed map (positionally: ``names[0]``
    is the first parameter): printed alike, or equal at random points."""
    if tuple(claimed) == tuple(fraction_text(truth.map.ring, n, d, names) for n, d in truth.map.fractions()):
        return

    def equal(point: Point) -> bool:
        s, t = point.of("s"), point.of("t")
        return values(point, claimed, **{names[0]: s, names[1]: t}) == truth.on_map(point)

    ids.add(where, "is not the map of the report's input", equal, [*claimed, *truth.texts])


def _check_apex(claimed: tuple[str, str, str] | None, cones: Conicity, K: Domain, where: str) -> None:
    """The apex of a cone, up to the directions of a cylinder (planes through a line)."""
    if cones.apex is None:
        if claimed is not None:
            raise ClaimError(where, "is given, but the map's image is no cone")
        return
    if claimed is None:
        raise ClaimError(where, "is missing")
    offset = sub(vector(K, claimed, where), cones.apex)
    if linalg.rank([*cones.directions, offset], 3, K) != len(cones.directions):
        raise ClaimError(where, "is not the apex of the map's image (det(P − c, P_s, P_t) is not 0)")


def _check_profile_curve(text: str, truth: MapTruth, where: str, ids: Identities) -> None:
    """``F(h, ρ)`` is not zero and vanishes on ``(h, ρ)`` of the map."""
    if formula(text) == 0:
        raise ClaimError(where, "is zero")

    def vanishes(point: Point) -> bool:
        h, rho = truth.profile(point, truth.on_map(point))
        return values(point, [text], h=h, rho=rho)[0] == 0

    ids.add(where, "does not vanish on the map's profile curve (h, ρ)", vanishes, [text, *truth.texts])


def _implicit_equation(
    analysis: Analysis, record: ParametricInput, truth: MapTruth, where: str, ids: Identities
) -> Surface:
    """The report's implicit equation: on the map, from its profile curve, irreducible over ``QQ``."""
    at = f"{where}polynomial"
    f = _over(read_polynomial(analysis.recognition.polynomial, at), truth.K, at)
    if total_degree(f) < 1:
        raise ClaimError(at, "is a constant, not the equation of the map's image")
    surface = Surface.of(f)
    ids.need(*surface.radicands)

    def on_surface(point: Point) -> bool:
        return surface.at(point, truth.on_map(point)) == 0

    first = Identities()  # before the claims about f: a wrong f is named as such
    first.need(*surface.radicands, *truth.radicands)
    first.add(at, "does not vanish on the map (f(P(s, t)) is not 0)", on_surface, truth.texts)
    first.run()
    if is_rational_field(truth.K):
        _, factors = to_flint(f).factor()
        if len(factors) != 1 or factors[0][1] != 1:
            raise ClaimError(at, "is a product, but the image of a map is irreducible: it is not its equation")
    curve = record.profile_curve
    if curve is not None:

        def xyz(point: Point) -> list[int]:
            return [point.of(n) for n in XYZ]

        def composed(point: Point) -> int:
            h, rho = truth.profile(point, xyz(point))
            return values(point, [curve], h=h, rho=rho)[0]

        ids.add(
            f"{where}parametric.profile_curve",
            "is not the profile curve of the report's polynomial (f ∝ F(a·(p − c), |p − c|²))",
            lambda P: proportional(composed, lambda Q: surface.at(Q, xyz(Q)), P),
            [curve],
        )
    return surface


def _over(f: Poly, K: Domain, where: str) -> Poly:
    """``f`` in ``K[x, y, z]`` (its printed coefficients may lie in a subfield of the map's)."""
    if f.ring.domain == K:
        return f
    source = f.ring.domain
    try:
        return poly_ring(XYZ, K).from_dict({m: K.from_sympy(source.to_sympy(c)) for m, c in f.items()})
    except Exception:  # noqa: BLE001 - sympy's coercion errors are several classes
        raise ClaimError(where, f"has coefficients outside the map's field {field_name(K)}") from None


def _check_without_equation(analysis: Analysis, truth: MapTruth, where: str, ids: Identities) -> None:
    """A report whose implicit equation is not known: its recognition, factors, cone or cylinder
    and parameterizations against the map alone; nothing that only ``f`` decides."""
    K = truth.K
    _check_map_recognition(analysis.recognition, truth, K, where)
    if analysis.squarefree:
        raise ClaimError(f"{where}squarefree", "is given, but the implicit equation is not known")
    if len(analysis.factors) != 1 or analysis.factors[0].multiplicity != 1:
        raise ClaimError(f"{where}factors", "must be the one factor of the map's image, irreducible")
    factor = analysis.factors[0]
    if factor.polynomial:
        raise ClaimError(f"{where}factors[0].polynomial", "is given, but the implicit equation is not known")
    _check_map_recognition(factor.recognition, truth, K, f"{where}factors[0].recognition.")
    if analysis.rationality is not None:
        raise ClaimError(f"{where}rationality", NEEDS_EQUATION)
    _check_canal(analysis.canal, f"{where}canal")
    if analysis.conical is not None:
        _check_map_conical(analysis.conical, truth, K, f"{where}conical", known=False)
    for i, param in enumerate(analysis.parametrizations):
        _check_map_parameterization(param, truth, f"{where}parametrizations[{i}]", ids)


def _check_map_recognition(rec: Recognition, truth: MapTruth, K: Domain, where: str) -> None:
    if rec.polynomial or rec.degree != 0:
        raise ClaimError(f"{where}degree", "is given, but the implicit equation is not known")
    if undecided(rec, where):
        return
    check_symmetry(rec, truth.symmetry, K, where, "the map's normal lines'")
    if rec.profile is not None or rec.radius_squared is not None:
        raise ClaimError(f"{where}profile" if rec.profile else f"{where}radius_squared", NEEDS_EQUATION)


def _check_canal(canal: Canal | None, where: str) -> None:
    if canal is None:
        return
    decided = (canal.kinds, canal.families, canal.parametrizations, canal.certificate, canal.witness)
    if canal.is_canal is not None or decided != ((), (), (), None, None):
        raise ClaimError(f"{where}.is_canal", NEEDS_EQUATION)


def _check_map_conical(conical: Conical, truth: MapTruth, K: Domain, where: str, known: bool) -> None:
    """The kind, apex and direction against the map's; without ``f`` (not ``known``), no base
    curve and no lines, which need it."""
    cones = truth.cones
    if conical.kind != cones.kind:
        raise ClaimError(f"{where}.kind", f"is {conical.kind!r}, but the map's image is {cones.kind!r}")
    _check_apex(conical.apex, cones, K, f"{where}.apex")
    if conical.direction is None:
        if cones.directions:
            raise ClaimError(f"{where}.direction", "is missing for a cylinder")
    else:
        d = nonzero(vector(K, conical.direction, f"{where}.direction"), f"{where}.direction")
        if linalg.rank([*cones.directions, d], 3, K) != len(cones.directions):
            raise ClaimError(f"{where}.direction", "is not a direction along which the map's image is a cylinder")
    if not known and (conical.base_curve is not None or conical.components or conical.parametrizations):
        raise ClaimError(f"{where}.base_curve", NEEDS_EQUATION)


def _check_map_parameterization(param: Parametrization, truth: MapTruth, where: str, ids: Identities) -> None:
    """Without ``f``, a verified parameterization can only be the map itself."""
    check_parametrization_form(param, where)
    if not param.verified:
        return
    if param.field != field_name(truth.K):
        raise ClaimError(f"{where}.field", f"is {param.field}, but the map's is {field_name(truth.K)}")
    _check_same_map(param.coordinates, param.parameters, truth, where, ids)
