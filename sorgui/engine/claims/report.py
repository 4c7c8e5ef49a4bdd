"""The whole report checked against its own polynomial: :func:`check_report` (docs/math.md §14).

The equation is read again by the parser, as if it had been typed; the report's polynomial and
field must be its. The factors multiply to ``f`` (up to a constant) and the square-free part is
their product; each factor's recognition is checked against the factor. Then the recognition
(:mod:`.recognition`), the rationality and the parameterizations (:mod:`.maps`), the cone or
cylinder (:mod:`.maps`), the canal surface (:mod:`.canal`) and, for rounded input, the nearest
exact surface, whose own analysis is checked as a report of its own. What is claimed about the
real points must at least agree with itself (a kind and its dimension). A parametrization's
report is checked against its map first (:mod:`.parametric`), then, when it knows its implicit
equation, against that equation as an equation's report.
"""

from __future__ import annotations

import math

from ..algebra.linalg import cross, is_zero, sub
from ..algebra.modular import Point
from ..algebra.polys import field_name
from ..errors import AnalysisError, ClaimError
from ..recognition.symmetry import SOR_KINDS, recognize_symmetry
from ..results import Analysis, Approximation, Factor
from .canal import check_canal
from .formulas import Surface, read_polynomial, vector
from .identities import Identities, proportional
from .maps import check_conical, check_parametrization, check_rationality
from .parametric import check_parametric
from .recognition import check_recognition

DIMENSIONS = {"empty": -1, "points": 0, "curve": 1, "surface": 2, "undecided": None}
"""The dimension of each kind of real locus."""


def check_report(analysis: Analysis) -> None:
    """Raise :class:`ClaimError` for the first claim of ``analysis`` that its polynomial does not
    bear out (the field named as in the JSON, e.g. ``axis.point``)."""
    ids = Identities()
    _check_analysis(analysis, "", ids)
    ids.run()


def _check_analysis(analysis: Analysis, where: str, ids: Identities) -> None:
    _check_real_locus(analysis, where)
    _check_unfinished(analysis, where)
    if analysis.approximate is not None:
        _check_approximation(analysis.approximate, f"{where}approximate")
        _check_nearest(analysis.approximate, f"{where}approximate", ids)
        if analysis.input_kind == "equation":
            _check_nearness(analysis.input, analysis.approximate, where)
    if analysis.input_kind == "parametrization":
        found = check_parametric(analysis, where, ids)
        if found is not None:
            _check_surface(analysis, found, where, ids)
        return
    if analysis.parametric is not None:
        raise ClaimError(f"{where}parametric", "is given for an equation")
    f = read_polynomial(analysis.input, f"{where}input")
    K = f.ring.domain
    if analysis.field != field_name(K):
        raise ClaimError(
            f"{where}field", f"is {analysis.field}, but the equation's coefficients lie in {field_name(K)}"
        )
    if read_polynomial(analysis.recognition.polynomial, f"{where}polynomial") != f:
        raise ClaimError(f"{where}polynomial", "is not the polynomial of the report's equation")
    surface = Surface.of(f)
    ids.need(*surface.radicands)
    _check_surface(analysis, surface, where, ids)


def _check_surface(analysis: Analysis, surface: Surface, where: str, ids: Identities) -> None:
    """Every claim of ``analysis`` that its polynomial ``surface`` decides."""
    rec = analysis.recognition
    check_recognition(rec, surface, where, ids)
    _check_factors(analysis, surface, where, ids)
    if analysis.rationality is not None:
        if rec.profile is None and analysis.rationality.table_row is not None:
            raise ClaimError(f"{where}rationality", "is given for a surface without a profile")
        multiplicity = analysis.factors[0].multiplicity if len(analysis.factors) == 1 else 1
        check_rationality(analysis.rationality, rec.profile, multiplicity, f"{where}rationality", ids)
    for i, param in enumerate(analysis.parametrizations):
        check_parametrization(param, surface, f"{where}parametrizations[{i}]", ids)
    if analysis.canal is not None:
        check_canal(analysis.canal, surface, rec.is_sor, f"{where}canal", ids)
    if analysis.conical is not None:
        check_conical(analysis.conical, surface, f"{where}conical", ids)


def _check_factors(analysis: Analysis, surface: Surface, where: str, ids: Identities) -> None:
    """The factors multiply to ``f`` and their product is the square-free part."""
    factors: list[tuple[Surface, int]] = []
    for i, factor in enumerate(analysis.factors):
        factors.append((_check_factor(factor, f"{where}factors[{i}]", ids), factor.multiplicity))
    squarefree = Surface.of(read_polynomial(analysis.squarefree, f"{where}squarefree"))
    ids.need(*squarefree.radicands)
    if not factors:
        if analysis.recognition.decided and "factors" not in analysis.unfinished:
            raise ClaimError(f"{where}factors", "are missing")
        if squarefree.polynomial != surface.polynomial:
            raise ClaimError(f"{where}squarefree", "is not the polynomial (its factors are not known)")
        return
    if any(e < 1 for _, e in factors):
        raise ClaimError(f"{where}factors", "hold a multiplicity below 1")

    def product(point: Point, xyz: list[int], square_free: bool) -> int:
        total = 1
        for g, e in factors:
            total = total * pow(g.at(point, xyz), 1 if square_free else e, point.prime) % point.prime
        return total

    def xyz(point: Point) -> list[int]:
        return [point.of(n) for n in ("x", "y", "z")]

    ids.add(
        f"{where}factors",
        "do not multiply to the polynomial",
        lambda P: proportional(lambda Q: product(Q, xyz(Q), False), lambda Q: surface.at(Q, xyz(Q)), P),
    )
    ids.add(
        f"{where}squarefree",
        "is not the product of the distinct factors",
        lambda P: proportional(lambda Q: squarefree.at(Q, xyz(Q)), lambda Q: product(Q, xyz(Q), True), P),
    )


def _check_factor(factor: Factor, where: str, ids: Identities) -> Surface:
    """The factor, and its recognition checked against the polynomial it names (the factor,
    or ``f`` itself up to a constant when ``f`` is irreducible)."""
    g = read_polynomial(factor.polynomial, f"{where}.polynomial")
    recognised = read_polynomial(factor.recognition.polynomial, f"{where}.recognition.polynomial")
    if recognised.ring != g.ring or g * recognised.LC != recognised * g.LC:
        raise ClaimError(f"{where}.recognition.polynomial", "is not the factor's polynomial")
    surface = Surface.of(g)
    ids.need(*surface.radicands)
    check_recognition(factor.recognition, Surface.of(recognised), f"{where}.recognition.", ids)
    return surface


def _check_real_locus(analysis: Analysis, where: str) -> None:
    """The real locus agrees with itself (a kind and its dimension) and with the real maps: a
    real parameterization, or ``X`` rational over ``R``, has a surface of real points."""
    locus = analysis.real_locus
    if locus is None:
        return
    if DIMENSIONS[locus.kind] != locus.dimension:
        raise ClaimError(f"{where}real_locus.dimension", f"is {locus.dimension}, but {locus.kind!r} has another")
    if locus.kind in ("surface", "undecided"):
        return
    real_maps = [i for i, p in enumerate(analysis.parametrizations) if p.real]
    if real_maps:
        raise ClaimError(
            f"{where}real_locus.kind",
            f"is {locus.kind!r}, but parametrizations[{real_maps[0]}] is real: X has a surface of real points",
        )
    if analysis.rationality is not None and analysis.rationality.real_rational:
        raise ClaimError(
            f"{where}real_locus.kind",
            f"is {locus.kind!r}, but X is claimed rational over R, which needs a surface of real points",
        )


def _check_unfinished(analysis: Analysis, where: str) -> None:
    """A stage the time limit cut short has no result: no Table 1 row, no parameterization."""
    unfinished = set(analysis.unfinished)
    rat = analysis.rationality
    if "rationality" in unfinished and rat is not None and rat.table_row is not None:
        raise ClaimError(f"{where}unfinished", "lists the rationality, but the report gives its Table 1 row")
    if "parametrizations" in unfinished and analysis.parametrizations:
        raise ClaimError(f"{where}unfinished", "lists the parameterizations, but the report gives some")


def _check_approximation(approx: Approximation, where: str) -> None:
    """The floating-point verdict on rounded input agrees with itself: "near" is a surface of
    revolution's kind within the rounding (its residual at most ``1 + NOISE_ALLOWANCE``, the
    float noise it may excuse), a nearest exact surface is only found for a near one, and the
    sizes are sizes."""
    from ..rounded.approximate import NOISE_ALLOWANCE  # numpy: only for rounded input

    within = approx.residual is None or approx.residual <= 1.0 + NOISE_ALLOWANCE
    if approx.near_sor and (approx.kind not in SOR_KINDS or not within):
        raise ClaimError(f"{where}.near_sor", "is claimed, but the kind or the residual says otherwise")
    if approx.nearest is not None and not approx.near_sor:
        raise ClaimError(f"{where}.nearest", "is given, but the input is not claimed near a surface of revolution")
    for name in ("tolerance", "relative_distance", "residual"):
        value = getattr(approx, name)
        if value is not None and not (math.isfinite(value) and value >= 0):
            raise ClaimError(f"{where}.{name}", "must be a finite number, at least 0")
    nearest = approx.nearest
    if nearest is not None and nearest.max_deviation is not None and not nearest.max_deviation >= 0:
        raise ClaimError(f"{where}.nearest.max_deviation", "must be at least 0")
    if approx.axis is not None and not any(approx.axis.direction):
        raise ClaimError(f"{where}.axis.direction", "must not be 0")


FIGURES_AGREE = 1e-3
"""The relative difference allowed between a nearest surface's figures as claimed and as
computed again: the same float computations on the same numbers agree to the last bits on one
machine, and another machine's libraries may move the deviation's Newton steps by far less than
this; a surface pasted in from another report is off by orders of magnitude."""


def _check_nearness(text: str, approx: Approximation, where: str) -> None:
    """What the report says of its nearest exact surface ``g`` against the typed ``f`` (the
    distance of their coefficients, the largest residual in units of the rounding, the deviation
    of their zero sets, whether ``g`` is within the rounding), computed again under the rounding
    the report names (the input's digits, or the tolerance given): a report with another
    surface's ``g`` pasted in claimed it within the rounding of the typed one."""
    nearest = approx.nearest
    if nearest is None:
        return
    from ..rounded.approximate import nearest_figures, rounding_of  # numpy: only for rounded input

    f = read_polynomial(text, f"{where}input")
    where = f"{where}approximate"
    given = approx.tolerance if approx.tolerance_source == "given" else None
    try:
        rounding, _ = rounding_of(f, text, given)
    except AnalysisError as exc:
        raise ClaimError(f"{where}.tolerance", f"cannot be: {exc.message}") from None
    if rounding is None:
        raise ClaimError(f"{where}.nearest", "is given for an input without decimals or a tolerance")
    g = read_polynomial(nearest.polynomial, f"{where}.nearest.polynomial")
    try:
        found = nearest_figures(f, g, rounding)
    except AnalysisError as exc:
        raise ClaimError(f"{where}.nearest.polynomial", f"cannot be: {exc.message}") from None
    claimed = (
        ("relative_distance", nearest.relative_distance, found.relative_distance),
        ("largest_residual", nearest.largest_residual, found.largest_residual),
        ("max_deviation", nearest.max_deviation, found.max_deviation),
    )
    for name, said, computed in claimed:
        if said is None and name == "largest_residual":
            continue  # reports written before it was kept
        if not _agree(said, computed):
            raise ClaimError(f"{where}.nearest.{name}", f"is {said}, but the nearest surface's is {computed}")
    if nearest.within_rounding != found.within_rounding:
        raise ClaimError(
            f"{where}.nearest.within_rounding",
            f"is {str(nearest.within_rounding).lower()}, but the nearest surface is "
            + ("within" if found.within_rounding else "outside")
            + " the input's rounding",
        )


def _agree(said: float | None, computed: float | None) -> bool:
    if said is None or computed is None:
        return said is computed
    return abs(said - computed) <= FIGURES_AGREE * max(abs(said), abs(computed)) or said == computed


def _check_nearest(approx: Approximation, where: str, ids: Identities) -> None:
    """The nearest exact surface: its own analysis as a report, or else its symmetry and axis."""
    nearest = approx.nearest
    if nearest is None:
        return
    g = read_polynomial(nearest.polynomial, f"{where}.nearest.polynomial")
    K = g.ring.domain
    if nearest.analysis is not None:
        if read_polynomial(nearest.analysis.input, f"{where}.nearest.analysis.input") != g:
            raise ClaimError(f"{where}.nearest.analysis.input", "is not the nearest surface's polynomial")
        _check_analysis(nearest.analysis, f"{where}.nearest.analysis.", ids)
    try:
        sym = recognize_symmetry(g)
    except AnalysisError as exc:
        raise ClaimError(f"{where}.nearest.kind", f"cannot be: {exc.message}") from None
    if nearest.kind != sym.kind:
        raise ClaimError(f"{where}.nearest.kind", f"is {nearest.kind!r}, but the nearest surface is {sym.kind!r}")
    if nearest.axis is not None:
        if sym.axis_point is None or sym.axis_direction is None:
            raise ClaimError(f"{where}.nearest.axis", "is given, but the nearest surface has no single axis")
        point = vector(K, nearest.axis.point, f"{where}.nearest.axis.point")
        direction = vector(K, nearest.axis.direction, f"{where}.nearest.axis.direction")
        if is_zero(direction) or not is_zero(cross(direction, sym.axis_direction)):
            raise ClaimError(f"{where}.nearest.axis.direction", "is not the direction of the nearest surface's axis")
        if not is_zero(cross(sub(point, sym.axis_point), sym.axis_direction)):
            raise ClaimError(f"{where}.nearest.axis.point", "is not a point of the nearest surface's axis")
    if nearest.center is not None and (sym.center is None or vector(K, nearest.center, "") != tuple(sym.center)):
        raise ClaimError(f"{where}.nearest.center", "is not the centre of the nearest surface")
    if nearest.normal is not None and (
        sym.normal is None or not is_zero(cross(vector(K, nearest.normal, f"{where}.nearest.normal"), sym.normal))
    ):
        raise ClaimError(f"{where}.nearest.normal", "is not the normal of the nearest surface")
