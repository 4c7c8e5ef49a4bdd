"""Canal surfaces: the exact verdict, its certificate or witness, and the kinds (docs/math.md §9).

A canal surface is the envelope of a one-parameter family of spheres ``|X − m(t)|² = ρ(t)``.

* **Not canal** is proved by one witness line on which the focal-sheet condition fails exactly
  (:mod:`.focal`, tested on lines by :mod:`.lines`).
* **Canal** is proved by the envelope certificate of the recovered family (:mod:`.spine`):
  ``f | Res_t(S, ∂S/∂t)`` for a rational family over ``QQ``, otherwise ``f`` divides every
  generator of the ideal ``⟨SMAT, |X − m|² − ρ, 4×4 minors of [Jac; 2(X − m), 1]⟩ ∩ QQ[x, y, z]``
  of the envelope of the SMAT curve (tangency: ``(2(X − m), 1)`` is normal to the curve).
* Kinds: ``pipe`` (ρ constant), ``revolution`` (spine on a line), ``dupin`` (canal in two ways:
  both focal conics), ``developable`` (Gaussian curvature zero: cones and cylinders).

Coefficients in ``QQ(√…)`` go through the norm ``Π f^σ ∈ QQ[x, y, z]``: the shape operator of a
component does not change when other components are multiplied in.
"""

from __future__ import annotations

import threading
from collections.abc import Iterable
from dataclasses import replace
from math import lcm
from typing import cast

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx
from sympy.polys.domains import QQ

from ..algebra import numberfields
from ..algebra.linalg import cross, primitive_vector, solve_unique
from ..algebra.polys import (
    Poly,
    compose,
    derivative,
    from_flint,
    is_rational_field,
    poly_ring,
    poly_str,
    to_flint,
    total_degree,
)
from ..algebra.rationals import squarefree
from ..errors import AnalysisError, Cancelled, SingularError
from ..recognition.profile import ProfileCurve
from ..recognition.symmetry import SOR_EVIDENCE, Motion, satisfies_identity
from ..results import Canal, CanalEvidence, Triple
from ..singular import curves
from ..singular.process import emit, parse_int, poly_to_singular, run_script
from ..stage_results import CanalFamily, Parametrization
from .axis_family import NOTE as AXIS_NOTE
from .axis_family import axis_family
from .focal import DEVELOPABLE, DUPIN, UMBILIC
from .lines import (
    MAX_DEGREE,
    SEED,
    SOR_NOTE,
    CanalClock,
    Lines,
    NotCanal,
    assemble,
    factor_verdict,
    not_canal,
    undecided,
)
from .parametrization import (
    RationalFamily,
    family_resultant_certificate,
    family_strings,
    radical_parametrization,
    rational_parametrization,
    recover_family,
    verify_radical,
)
from .radical import RadicalFamily, radical_family, radical_surface
from .spine import MARGIN, SmatCurve, constant_radius, monomials, smat_curves
from .torus import CERTIFICATE as TORUS_CERTIFICATE
from .torus import torus_canal, torus_of

GENUS_DEGREE = 12
"""The genus of a SMAT plane model of higher degree is not computed (Singular's time)."""

FAMILY_DEGREE = 6
"""``m(t), ρ(t)`` are computed for SMAT plane models up to this degree (exact rational functions
of higher degree make the verification slow)."""

RADICAL_ROOTS = 2
"""The circles of a family in square roots are checked on ``f`` (and given as a parameterization)
for at most this many roots: each root doubles the size of the check (two roots take about
2 s at degree 24)."""


def analyze_canal(
    f: Poly,
    *,
    is_sor: bool | None = None,
    full: bool = True,
    timeout: float = 60.0,
    cancel: threading.Event | None = None,
    profile: ProfileCurve | None = None,
    square: tuple[sympy.Expr, sympy.Expr] | None = None,
) -> Canal:
    """The canal verdict of ``f = 0`` with certificate or witness, kinds, families and
    parameterizations (genus, ``m(t)``, ``ρ(t)`` and surface parameterizations only when
    ``full``). ``is_sor`` (from the symmetry algebra) decides the ``revolution`` kind of a
    reducible surface, is cross-checked otherwise, and certifies a surface of revolution.
    A torus's answer is read off its ``profile`` (:mod:`.torus`): no line test, no SMAT. A
    surface of revolution whose ``P²`` has the proper parameterization ``square = (φ(t), ψ(t))``
    over ``QQ`` gets its family centred on the axis (:mod:`.axis_family`) when no other family
    has the axis as its spine."""
    torus = torus_of(profile) if is_sor and profile is not None else None
    if torus is not None:
        return torus_canal(torus, CanalEvidence("profile+rotation", _statement(["profile", "rotation"]), True))
    found = _analyze_canal(f, is_sor=is_sor, full=full, timeout=timeout, cancel=cancel)
    if not (is_sor and full and found.is_canal and profile is not None and square is not None):
        return found
    if any(family.on_line for family in found.families):
        return found
    family = axis_family(profile, *square)
    if family is None:
        return found
    notes = tuple(note for note in found.notes if note != SOR_NOTE)
    return replace(found, families=(family, *found.families), notes=(AXIS_NOTE, *notes))


def _analyze_canal(
    f: Poly, *, is_sor: bool | None, full: bool, timeout: float, cancel: threading.Event | None
) -> Canal:
    """The canal verdict of a surface that is not a torus."""
    clock = CanalClock(cancel)
    rational = is_rational_field(f.ring.domain)
    # a power (an ellipsoid to the 16th) is analysed by its square-free part's degree
    if total_degree(f) > MAX_DEGREE and not (rational and squarefree(to_flint(f)).total_degree() <= MAX_DEGREE):
        if is_sor:
            return Canal(
                True,
                "canal: a surface of revolution",
                ("revolution",),
                certificate=SOR_EVIDENCE,
                notes=(f"degree above {MAX_DEGREE}: only the symmetry algebra's answer is given",),
            )
        return Canal(None, f"not analysed: degree above {MAX_DEGREE}")
    if is_sor and not rational:
        # The norm holds the conjugate surfaces too, about other axes: no surface of revolution,
        # and its SMAT is what Singular would be asked for. The symmetry algebra answers.
        return Canal(
            True,
            "canal: a surface of revolution",
            ("revolution",),
            certificate=SOR_EVIDENCE,
            notes=(
                "coefficients outside QQ: the symmetry algebra's answer; the SMAT of the norm (the "
                "surface with its conjugates, about other axes) is not computed",
            ),
        )
    g = _rational_squarefree(f)
    _, factors = g.factor()
    parts = [
        _analyze_factor(h, clock, full, is_sor if len(factors) == 1 else None, timeout, cancel) for h, _ in factors
    ]
    notes = (
        ()
        if is_rational_field(f.ring.domain)
        else ("coefficients outside QQ: analysed through the norm of f over QQ (all conjugate surfaces)",)
    )
    return assemble(parts, is_sor, clock, notes)


def _rational_squarefree(f: Poly) -> fmpq_mpoly:
    """The square-free part over ``QQ`` of ``f`` (of its norm when ``K ≠ QQ``), as flint."""
    return squarefree(to_flint(f) if is_rational_field(f.ring.domain) else _norm(f))


def _norm(f: Poly) -> fmpq_mpoly:
    """``Res_θ(f(x, y, z, θ), m(θ))``: the product of the conjugates of ``f`` over ``QQ`` (up to a
    constant). For ``K = QQ(√d₁, …)`` it is taken in the radical basis, one square root at a time
    (:func:`sorgui.engine.algebra.numberfields.norm`), much faster than the resultant in the primitive element."""
    K = f.ring.domain
    ctx3 = fmpq_mpoly_ctx.get(tuple(f"v{i}" for i in range(3)), "lex")
    if numberfields.supports(K):
        N = numberfields.norm(numberfields.to_flint(f), numberfields.radical_basis(K).radicands)
        return ctx3.from_dict({m[:3]: c for m, c in N.to_dict().items()})
    ctx = fmpq_mpoly_ctx.get(("x", "y", "z", "a"), "lex")
    terms: dict[tuple[int, int, int, int], object] = {}
    for monom, c in f.items():
        coords = [QQ.convert(q) for q in c.to_list()]
        n = len(coords) - 1
        for i, q in enumerate(coords):
            if q:
                terms[(*monom, n - i)] = q
    F = ctx.from_dict({m: _fmpq(q) for m, q in terms.items()})
    mod = [QQ.convert(q) for q in K.mod.to_list()]
    M = ctx.from_dict({(0, 0, 0, len(mod) - 1 - i): _fmpq(q) for i, q in enumerate(mod) if q})
    N = F.resultant(M, "a")
    return ctx3.from_dict({m[:3]: c for m, c in zip(N.monoms(), N.coeffs())})


def _fmpq(q: object) -> fmpq:
    return fmpq(int(QQ.numer(q)), int(QQ.denom(q)))


def _analyze_factor(
    h: fmpq_mpoly,
    clock: CanalClock,
    full: bool,
    is_sor: bool | None,
    timeout: float,
    cancel: threading.Event | None,
) -> Canal:
    """The verdict for one irreducible factor over ``QQ``."""
    verdict, lines = factor_verdict(h, clock, is_sor)
    if verdict is not None:
        return verdict
    assert lines is not None  # factor_verdict returns its lines whenever it leaves the verdict open
    poly = from_flint(h, poly_ring(("x", "y", "z"), QQ))
    try:
        branch = lines.canal[0].branch
        if branch == UMBILIC:
            return _umbilic(poly, lines)
        if is_sor and branch != DUPIN and total_degree(poly) > 2:  # higher degrees: factor_verdict
            kinds = {"revolution"} | ({branch} & {DUPIN, DEVELOPABLE})
            if constant_radius(lines.sample(len(monomials(1)) + MARGIN)):
                kinds.add("pipe")
            return Canal(
                True,
                "canal: a surface of revolution",
                tuple(sorted(kinds)),
                certificate=SOR_EVIDENCE,
                lines_tested=lines.tried,
                notes=(SOR_NOTE,),
            )
        with clock.stage("canal spine"):
            smat, _ = smat_curves(lines.sample, seed=SEED, timeout=timeout, cancel=cancel)
    except NotCanal as witness:
        return not_canal(witness.test, lines.tried)
    except (SingularError, AnalysisError) as error:
        if isinstance(error, Cancelled):
            raise
        return undecided(lines, error)
    return _canal(poly, smat, branch, lines, clock, full, timeout, cancel)


def _umbilic(poly: Poly, lines: Lines) -> Canal:
    """Every point umbilic on the lines: a sphere, checked exactly from the coefficients."""
    x, y, z = poly.ring.gens
    quadratic = (
        total_degree(poly) == 2
        and all(poly.coeff(m) == 0 for m in (x * y, x * z, y * z))
        and poly.coeff(x**2) == poly.coeff(y**2) == poly.coeff(z**2)
    )
    if not quadratic:
        return Canal(None, "undecided: totally umbilic on the lines but not a sphere", lines_tested=lines.tried)
    return Canal(
        True,
        "canal: a sphere (a constant family of spheres)",
        ("pipe", "revolution"),
        certificate=CanalEvidence("symmetry", "x², y², z² have equal coefficients and no mixed terms: a sphere", True),
        lines_tested=lines.tried,
    )


def _canal(
    poly: Poly,
    smat: list[SmatCurve],
    branch: str,
    lines: Lines,
    clock: CanalClock,
    full: bool,
    timeout: float,
    cancel: threading.Event | None,
) -> Canal:
    families: list[CanalFamily] = []
    rational: list[RationalFamily | None] = []
    notes: list[str] = []
    with clock.stage("canal genus"):
        genera = []
        for curve in smat:
            genera.append(_genus(curve, timeout, cancel, notes) if full else None)
    radicals: list[RadicalFamily | None] = []
    with clock.stage("canal family"):
        for curve, genus in zip(smat, genera):
            family = None
            if genus == 0 and curve.inverse is not None and total_degree(curve.plane_model) > FAMILY_DEGREE:
                notes.append(f"the SMAT curve's plane model has degree above {FAMILY_DEGREE}: m(t), ρ(t) not computed")
            elif genus == 0 and curve.inverse is not None:
                try:
                    plane = curves.parametrize(curve.plane_model, timeout=timeout, cancel=cancel, known_genus_zero=True)
                    family = recover_family(curve, plane)
                except (SingularError, AnalysisError) as error:
                    if isinstance(error, Cancelled):
                        raise
                    notes.append(f"no rational m(t), ρ(t): {error.message}")
            radical = radical_family(curve) if family is None and full else None
            rational.append(family)
            radicals.append(radical)
            families.append(_family_report(curve, genus, family, radical))
    with clock.stage("canal certificate"):
        certificate = _certificate(poly, smat, rational, timeout, cancel, notes)
    parametrizations: list[Parametrization] = []
    with clock.stage("canal parametrization"):
        for family in rational:
            if family is not None and family.verified:
                parametrizations.append(_radical(poly, family))
                found = rational_parametrization(poly, family)
                if found is not None:
                    parametrizations.append(_rational(found))
        for radical in radicals:
            if radical is not None and len(radical.roots) <= RADICAL_ROOTS:
                try:
                    parametrizations.append(_radical_surface(poly, radical))
                except AnalysisError as error:
                    notes.append(f"the circles of a family in square roots were not parameterized: {error.message}")
            elif radical is not None:
                notes.append(
                    f"the circles of a family in {len(radical.roots)} square roots were not "
                    f"parameterized (more than {RADICAL_ROOTS} roots)"
                )
    kinds = set()
    if any(c.constant_radius is not None for c in smat):
        kinds.add("pipe")
    if any(c.on_line for c in smat):
        kinds.add("revolution")
    if branch == DUPIN:
        kinds.add("dupin")
    if branch == DEVELOPABLE:
        kinds.add("developable")
    if branch == DUPIN and len(smat) == 1:
        notes.append("the two focal conics are conjugate over QQ: one family of equations holds both")
    if not full:
        notes.append("recognition only: no genus, m(t), ρ(t) or parameterization computed")
    elif not any(f is not None for f in rational):
        notes.append(
            "no rational parameterization of the surface: the SMAT curve is not rational"
            if any(g not in (0, None) for g in genera)
            else "no parameterization of the surface was computed"
        )
    verdict = certificate is not None and certificate.verified
    status = (
        "canal"
        if verdict
        else f"undecided: the canal condition holds on {len(lines.canal)} lines, but the envelope certificate failed"
    )
    return Canal(
        verdict if verdict else None,
        status,
        tuple(sorted(kinds)),
        tuple(families),
        certificate,
        parametrizations=tuple(parametrizations),
        lines_tested=lines.tried,
        notes=tuple(notes),
    )


def _genus(curve: SmatCurve, timeout: float, cancel: threading.Event | None, notes: list[str]) -> int | None:
    if total_degree(curve.plane_model) <= 2 and curve.birational and _irreducible_conic(curve.plane_model):
        return 0
    if not curve.birational:
        notes.append("the plane model of the SMAT curve is not birational to it: genus not computed")
        return None
    if total_degree(curve.plane_model) > GENUS_DEGREE:
        notes.append(f"the plane model of the SMAT curve has degree above {GENUS_DEGREE}: genus not computed")
        return None
    try:
        return curves.genus(curve.plane_model, timeout=timeout, cancel=cancel)
    except (SingularError, AnalysisError) as error:
        if isinstance(error, Cancelled):
            raise
        notes.append(f"genus of the SMAT curve not computed: {error.message}")
        return None


def _irreducible_conic(G: Poly) -> bool:
    """A line, or a conic whose 3×3 symmetric matrix is regular (irreducible over C)."""
    if total_degree(G) == 1:
        return True
    u, v = G.ring.gens
    a, b, c = G.coeff(u**2), G.coeff(u * v), G.coeff(v**2)
    d, e, k = G.coeff(u), G.coeff(v), G.coeff(1)
    return cast(bool, sympy.Matrix([[2 * a, b, d], [b, 2 * c, e], [d, e, 2 * k]]).det() != 0)


def _family_report(
    curve: SmatCurve,
    genus: int | None,
    family: RationalFamily | None,
    radical: RadicalFamily | None = None,
) -> CanalFamily:
    radius = curve.constant_radius
    par = center = normal = radius2 = field_name = None
    verified = False
    if family is not None:
        par, radius = family_strings(family)
        center = _triple(family.center)
        normal = _triple(family.normal)
        radius2 = str(family.radius_squared)
        field_name = "QQ" if family.over_qq else "QQ(" + ", ".join(str(g) for g in family.generators) + ")"
        verified = family.verified
    return CanalFamily(
        degree=curve.spine_degree,
        smat_degree=curve.smat_degree,
        genus=genus,
        planar=curve.planar,
        on_line=curve.on_line,
        pipe=curve.constant_radius is not None,
        equations=tuple(poly_str(g) for g in curve.equations),
        spine_equations=tuple(poly_str(g) for g in curve.spine_equations),
        plane_model=poly_str(curve.plane_model),
        projection=curve.projection,
        parametrization=par,
        radius_squared=radius,
        field=field_name,
        verified=verified,
        circle_center=center,
        circle_radius_squared=radius2,
        circle_normal=normal,
        radical_spine=None if radical is None else _triple(radical.radicals(c) for c in radical.m),
        radical_radius_squared=None if radical is None else str(radical.radicals(radical.rho)),
        radical_parameter=None if radical is None else radical.parameter,
    )


def _triple(values: Iterable[object]) -> Triple:
    """The three coordinates of a point as the strings sympy reads back."""
    x, y, z = (str(v) for v in values)
    return x, y, z


def _certificate(
    poly: Poly,
    smat: list[SmatCurve],
    rational: list[RationalFamily | None],
    timeout: float,
    cancel: threading.Event | None,
    notes: list[str],
) -> CanalEvidence | None:
    """The envelope certificate of every family (both focal conics of a Dupin cyclide)."""
    methods = []
    for curve, family in zip(smat, rational):
        if curve.on_line and _invariant_about_spine(poly, curve):
            methods.append("rotation")
            continue
        if family is not None and family.over_qq and family.verified and family_resultant_certificate(poly, family):
            methods.append("resultant")
            continue
        try:
            method = envelope_certificate(poly, curve, timeout=timeout, cancel=cancel)
        except SingularError as error:
            if isinstance(error, Cancelled):
                raise
            notes.append(f"envelope certificate not computed: {error.message}")
            return None
        if method is None:
            return CanalEvidence("elimination", "f does not divide the envelope ideal of the SMAT curve", False)
        methods.append(method)
    if len(set(methods)) == 1:
        statement = CERTIFICATES[methods[0]]
        if len(smat) > 1:
            statement += f", for each of the {len(smat)} families"
        return CanalEvidence(methods[0], statement, True)
    return CanalEvidence("+".join(methods), _statement(methods), True)


def _statement(methods: list[str]) -> str:
    """What the certificates of the families prove, family by family."""
    return "; ".join(f"family {number}: {CERTIFICATES[m]}" for number, m in enumerate(methods, 1))


CERTIFICATES = {
    "rotation": (
        "the spine is a line and f is invariant under the rotations about it (the identity "
        "∇f·(a × (p − c)) ≡ 0): X is a surface of revolution, and its parallels are characteristic circles"
    ),
    "profile": TORUS_CERTIFICATE,
    "resultant": "f divides Res_t(S, ∂S/∂t) for S = |X − m(t)|² − ρ(t) (denominators cleared)",
    "incidence": (
        "f lies in the incidence ideal E of the SMAT curve (SMAT, |X − m|² = ρ, tangency), "
        "a complete intersection of dimension 2 whose points over a line are finitely many: "
        "the envelope lies in X and is a surface, so it is X"
    ),
    "elimination": (
        "f divides every generator of the envelope ideal of the SMAT curve "
        "(SMAT, |X − m|² = ρ, tangency; m and ρ eliminated)"
    ),
}
"""What each envelope certificate proves (docs/math.md §9)."""


def _invariant_about_spine(f: Poly, curve: SmatCurve) -> bool:
    """Whether ``f`` is invariant under the rotations about the spine line (MATH.md §2, (★))."""
    rows = [[g.coeff(x) for x in g.ring.gens] for g in curve.spine_equations if total_degree(g) == 1]
    rhs = [-g.coeff(1) for g in curve.spine_equations if total_degree(g) == 1]
    direction = primitive_vector(cross(tuple(rows[0]), tuple(rows[1])), QQ)
    point = solve_unique([*rows[:2], list(direction)], [*rhs[:2], QQ.zero], QQ)
    if point is None:
        return False
    return satisfies_identity(f, Motion(a=direction, b=cross(point, direction)))


CERTIFICATE_LINE = ("3*x - 2*y + 5*z - 7", "x + 4*y - 3*z + 2")
"""The line of the incidence certificate (two planes): any line does that meets the envelope
in finitely many points of the incidence variety; another makes the certificate fall back to
the elimination."""


def envelope_certificate(
    f: Poly,
    curve: SmatCurve,
    *,
    timeout: float,
    cancel: threading.Event | None,
) -> str | None:
    """Singular: ``"incidence"`` or ``"elimination"`` when ``X`` is proved to lie in the envelope
    of the family (docs/math.md §9), ``None`` when it is not.

    The linear SMAT equations are solved first (``m, ρ`` affine in the free coordinates ``u``),
    so the tangency condition is the vanishing of the maximal minors of
    ``[∂(nonlinear equations)/∂u; (2(X − m), 1)·∂(m, ρ)/∂u]``, with fewer variables. These
    equations, with the sphere's, generate the incidence ideal ``E`` of (sphere, point of its
    characteristic circle). The *incidence* certificate needs no elimination: ``E`` has one
    generator more than there are ``u`` (so every component of ``V(E)`` has dimension ≥ 2),
    ``dim V(E) = 2``, ``f ∈ E``, and ``V(E)`` over :data:`CERTIFICATE_LINE` is finite and not
    empty. Otherwise ``f`` must divide every generator of ``E ∩ QQ[x, y, z]`` (*elimination*).
    """
    free, coords = _affine_coordinates(curve.equations)
    names = tuple(f"u{i}" for i in range(len(free)))
    S = poly_ring(names + ("x", "y", "z"), QQ)
    images = [S.from_dict({_lift_monom(m, len(names)): c for m, c in expr.items()}) for expr in coords]
    nonlinear = [g for g in (compose(h, images) for h in curve.equations if total_degree(h) > 1) if g]
    X = S.gens[len(names) :]
    sphere = sum(((X[i] - images[i]) ** 2 for i in range(3)), S.zero) - images[3]
    rows = [[derivative(g, j) for j in range(len(names))] for g in nonlinear]
    rows.append(
        [
            sum((2 * (X[i] - images[i]) * derivative(images[i], j) for i in range(3)), S.zero)
            + derivative(images[3], j)
            for j in range(len(names))
        ]
    )
    rows = [_integer_row(row) for row in rows]
    entries = ",".join(poly_to_singular(e) if e else "0" for row in rows for e in row)
    gens = ",".join([poly_to_singular(g) for g in nonlinear] + [poly_to_singular(sphere)])
    variables = "*".join(names)
    square = int(len(rows) == len(names))
    script = f"""ring sE = 0,({",".join(names)},x,y,z),dp; short = 0;
matrix M[{len(rows)}][{len(names)}] = {entries};
ideal E = {gens}, minor(M, {len(names)});
poly f = {poly_to_singular(f, ["x", "y", "z"])};
ideal G = std(E);
int ok = 0;
if ({square} && dim(G) == 2 && size(reduce(f, G)) == 0) {{
  ideal H = std(E + ideal({", ".join(CERTIFICATE_LINE)}));
  if (dim(H) == 0) {{ ok = 2; }}
}}
if (ok == 0) {{
  ideal El = eliminate(E, {variables});
  ok = (size(El) > 0) && (size(reduce(El, std(ideal(f)))) == 0);
}}
{emit("ok", "string(ok)")}
"""
    found = run_script(script, timeout=timeout, cancel=cancel)
    return {2: "incidence", 1: "elimination"}.get(parse_int(found["ok"][0]))


def _affine_coordinates(equations: tuple[Poly, ...]) -> tuple[list[int], list[Poly]]:
    """The free SMAT coordinates left by the linear equations, and ``(m1, m2, m3, r)`` as affine
    polynomials in them (in a ring whose variables are the free coordinates, in order)."""
    R = equations[0].ring
    linear = [g for g in equations if total_degree(g) == 1]
    rows = [[g.coeff(x) for x in R.gens] + [g.coeff(1)] for g in linear]
    reduced, pivots = sympy.Matrix(rows).rref() if rows else (sympy.zeros(0, 5), ())
    free = [i for i in range(4) if i not in pivots]
    F = poly_ring(tuple(f"u{k}" for k in range(len(free))) or ("u0",), QQ)
    coords: list[Poly] = []
    for i in range(4):
        if i in free:
            coords.append(F.gens[free.index(i)])
            continue
        row = reduced.row(list(pivots).index(i))
        expr = F(QQ(-int(sympy.fraction(row[4])[0]), int(sympy.fraction(row[4])[1])))
        for k, j in enumerate(free):
            c = row[j]
            if c:
                expr -= F(QQ(int(sympy.fraction(c)[0]), int(sympy.fraction(c)[1]))) * F.gens[k]
        coords.append(expr)
    return free, coords


def _lift_monom(m: tuple[int, ...], n: int) -> tuple[int, ...]:
    return tuple(m[:n]) + (0,) * (n - len(m[:n])) + (0, 0, 0)


def _integer_row(row: list[Poly]) -> list[Poly]:
    """The row times the lcm of its denominators (one factor for the whole row keeps the minors)."""
    den = 1
    for e in row:
        for c in e.coeffs() if e else ():
            den = lcm(den, int(QQ.denom(c)))
    return [e * den for e in row]


def _radical(poly: Poly, family: RationalFamily) -> Parametrization:
    coords = radical_parametrization(family)
    verified = verify_radical(poly, family)
    return Parametrization(
        coordinates=_triple(coords),
        parameters=("t", "theta"),
        field="QQ" if family.over_qq else "QQ(" + ", ".join(str(g) for g in family.generators) + ")",
        real=all(g.is_real for g in family.generators),
        proper=None,
        method="canal: characteristic circles (radical)",
        verified=verified,
        verification="substituted into f: f(c + a·e₁ + b·e₂) ≡ 0 modulo the circle a²|e₁|² + b²|e₂|² = R²",
    )


def _radical_surface(poly: Poly, family: RadicalFamily) -> Parametrization:
    coords, verified = radical_surface(poly, family)
    return Parametrization(
        coordinates=_triple(coords),
        parameters=("t", "theta"),
        field="QQ",
        real=True,
        proper=None,
        method=f"canal: characteristic circles (radical, the spine in square roots, t = {family.parameter}; "
        "real where the radicands are not negative)",
        verified=verified,
        verification="substituted into f: f(c + a·e₁ + b·e₂) ≡ 0 modulo the roots' squares and the circle "
        "a²|e₁|² + b²|e₂|² = R²",
    )


def _rational(found: tuple[tuple[sympy.Expr, ...], bool]) -> Parametrization:
    coords, verified = found
    return Parametrization(
        coordinates=_triple(coords),
        parameters=("t", "s"),
        field="QQ",
        real=True,
        proper=None,
        method="canal: rational (unit normals on the characteristic circles, sum of two squares)",
        verified=verified,
    )
