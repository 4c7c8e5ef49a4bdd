"""The SMAT curve of a canal surface: its ideal, spine, degree, planarity and plane model
(docs/math.md §9).

The SMAT points ``(m₁, m₂, m₃, ρ)`` of canal lines (:mod:`.focal`) are algebraic points; a
polynomial ``P`` vanishes on the ``deg F`` conjugate points of one line exactly when
``P(m, ρ) ≡ 0 mod F``, which is ``deg F`` linear equations over ``QQ`` on its coefficients. The
null space for polynomials of degree ≤ k (k = 1, 2, … until the ideal is one-dimensional) gives
an ideal ``J_k`` whose zero set contains the SMAT curve; Singular's ``minAssGTZ`` splits it and
the components that carry the sampled points are the SMAT curve (two of them, the focal conics,
for a Dupin cyclide). The same Singular run gives the spine ideal (``ρ`` eliminated), the degrees
(points on a random hyperplane) and a plane model ``G(u, v)`` under a random projection, whose
genus is the genus of the SMAT (Singular ``genus`` through :mod:`sorgui.engine.singular.curves`).
"""

from __future__ import annotations

import random
import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from itertools import combinations
from math import lcm
from typing import cast

import sympy
from flint import fmpq, fmpq_poly, fmpz_mat
from sympy.polys.domains import QQ

from ..algebra.polys import Poly, poly_ring, poly_str, total_degree
from ..errors import AnalysisError
from ..singular.process import emit, parse_int, parse_list, poly_to_singular, run_script
from .focal import Pair, PairRing, SmatSample

SMAT_NAMES = ("m1", "m2", "m3", "r")
"""The SMAT coordinates: the centre ``m`` and ``r`` for the squared radius ``ρ``."""

PLANE_NAMES = ("u", "v")

MAX_DEGREE = {2: 24, 3: 8, 4: 6}
"""The largest degree of the interpolated SMAT equations, by the number of free coordinates
(a plane SMAT curve has one equation, whose degree can be high; docs/math.md §9)."""

MARGIN = 8
"""Extra sampled points beyond the number of unknown coefficients."""


@dataclass(frozen=True)
class SmatCurve:
    """One irreducible (over QQ) SMAT curve: a sphere family ``(m, ρ)`` of the canal surface.

    ``equations`` generate its prime ideal in ``QQ[m1, m2, m3, r]``; ``spine_equations`` those of
    the spine (``r`` eliminated). ``projection`` gives ``u, v`` as integer linear forms in
    ``(m1, m2, m3, r)``; ``plane_model`` is the image ``G(u, v) = 0``, birational to the curve
    when ``birational``; ``inverse`` gives ``(m1, m2, m3, r)`` as rational functions of ``(u, v)``
    on the curve (``None`` when not found).
    """

    equations: tuple[Poly, ...]
    spine_equations: tuple[Poly, ...]
    spine_degree: int
    smat_degree: int
    planar: bool
    on_line: bool
    constant_radius: str | None
    plane_model: Poly
    projection: tuple[tuple[int, ...], tuple[int, ...]]
    birational: bool
    inverse: tuple[sympy.Expr, ...] | None


def monomials(k: int, nvars: int = 4) -> list[tuple[int, ...]]:
    """All exponent vectors of total degree ≤ ``k`` in ``nvars`` variables, graded."""
    out: list[tuple[int, ...]] = []
    for d in range(k + 1):
        out += _exponents(d, nvars)
    return out


def _exponents(d: int, n: int) -> list[tuple[int, ...]]:
    if n == 1:
        return [(d,)]
    return [(i, *rest) for i in range(d, -1, -1) for rest in _exponents(d - i, n - 1)]


def monomial_values(arith: PairRing, point: Sequence[Pair], exps: Sequence[tuple[int, ...]]) -> list[Pair]:
    """``M^α·W^(k − |α|)`` for the monomials ``α`` of ``exps`` (``k`` their largest degree) at
    the homogeneous SMAT point ``(M₁, M₂, M₃, Mρ; W)``: the monomials times ``W^k``."""
    coords, weight = point[:4], point[4]
    k = max(sum(e) for e in exps)
    cache: dict[tuple[int, ...], Pair] = {(0, 0, 0, 0): Pair(fmpq_poly(1), fmpq_poly(0))}
    powers = [Pair(fmpq_poly(1), fmpq_poly(0))]
    for _ in range(k):
        powers.append(arith.mul(powers[-1], weight))
    return [arith.mul(_monomial(arith, coords, e, cache), powers[k - sum(e)]) for e in exps]


def _monomial(arith: PairRing, point: Sequence[Pair], e: tuple[int, ...], cache: dict[tuple[int, ...], Pair]) -> Pair:
    if e in cache:
        return cache[e]
    i = next(j for j, k in enumerate(e) if k)
    lower = tuple(k - (j == i) for j, k in enumerate(e))
    value = arith.mul(_monomial(arith, point, lower, cache), point[i])
    cache[e] = value
    return value


def vanishing(sample: SmatSample, exps: Sequence[tuple[int, ...]]) -> list[list[int]]:
    """Integer coefficient vectors (over ``exps``) of the polynomials in ``(m, ρ)`` that vanish at
    every sampled point: an exact null space over ``QQ``."""
    rows: list[list[fmpq]] = []
    for test, arith in zip(sample.tests, sample.rings):
        assert test.smat is not None
        values = monomial_values(arith, test.smat, exps)
        n = test.F.degree()
        for part in ("u", "v"):
            columns = [_padded(getattr(v, part), n) for v in values]
            if part == "v" and not any(any(c) for c in columns):
                continue
            rows += [[col[i] for col in columns] for i in range(n)]
    return nullspace(rows, len(exps))


def _padded(p: fmpq_poly, n: int) -> list[fmpq]:
    coeffs = [fmpq(c) for c in p.coeffs()]
    return coeffs + [fmpq(0)] * (n - len(coeffs))


def nullspace(rows: list[list[fmpq]], ncols: int) -> list[list[int]]:
    """A basis of ``{c : rows·c = 0}`` over ``QQ`` with integer, content-free vectors."""
    if not rows:
        return [[int(i == j) for i in range(ncols)] for j in range(ncols)]
    integer_rows = []
    for row in rows:
        den = lcm(*(int(c.q) for c in row)) if row else 1
        integer_rows.append([int(c * den) for c in row])
    X, nullity = fmpz_mat(integer_rows).nullspace()
    out = []
    for j in range(nullity):
        vec = [int(X[i, j]) for i in range(ncols)]
        g = 0
        for c in vec:
            g = sympy.igcd(g, c)
        out.append([c // g for c in vec] if g else vec)
    return out


def to_poly(vec: Sequence[int], exps: Sequence[tuple[int, ...]], names: Sequence[str] = SMAT_NAMES) -> Poly:
    """The polynomial with coefficients ``vec`` over the monomials ``exps``."""
    R = poly_ring(tuple(names), QQ)
    return R.from_dict({e: QQ(c) for e, c in zip(exps, vec) if c})


def vanishes_on_sample(P: Poly, sample: SmatSample) -> bool:
    """Whether ``P(m, ρ) ≡ 0`` at every sampled point (all lines, both roots on the Dupin branch)."""
    for test, arith in zip(sample.tests, sample.rings):
        assert test.smat is not None
        if _value(P, test.smat, arith) != Pair(fmpq_poly(0), fmpq_poly(0)):
            return False
    return True


def _value(P: Poly, point: Sequence[Pair], arith: PairRing) -> Pair:
    exps = list(P.keys())
    values = monomial_values(arith, point, exps)
    return arith.linear([fmpq(int(QQ.numer(P[e])), int(QQ.denom(P[e]))) for e in exps], values)


# --- the ideal and its components -------------------------------------------------------------


def smat_curves(
    sample_for: Callable[[int], SmatSample],
    *,
    seed: int,
    timeout: float,
    cancel: threading.Event | None,
) -> tuple[list[SmatCurve], SmatSample]:
    """The SMAT curves through the sampled points. First the linear equations (the spine's
    plane or line, a constant radius); then, in the remaining free coordinates only, equations
    of degree k = 2, 3, … until their ideal is one-dimensional and its components carry the sample.

    ``sample_for(n)`` returns the SMAT points of enough canal lines for at least ``n`` points.
    """
    rnd = random.Random(seed)
    linear_exps = monomials(1)
    sample = sample_for(len(linear_exps) + MARGIN)
    linear = [to_poly(v, linear_exps) for v in vanishing(sample, linear_exps)]
    free = _free_coordinates(linear)
    if not free:
        raise AnalysisError("the sphere family is constant (the SMAT is a point)")
    if len(free) == 1:
        curves = _decompose(linear, sample, rnd, timeout=timeout, cancel=cancel)
        if curves:
            return curves, sample
        raise AnalysisError("the linear equations of the SMAT do not cut out a curve")
    top = MAX_DEGREE[len(free)]
    for k in range(2, top + 1):
        exps = [_embed(e, free) for e in monomials(k, len(free))]
        sample = sample_for(len(exps) + MARGIN)
        vectors = vanishing(sample, exps)
        if not vectors:
            continue
        generators = linear + [to_poly(v, exps) for v in vectors]
        curves = _decompose(generators, sample, rnd, timeout=timeout, cancel=cancel)
        if curves:
            return curves, sample
    raise AnalysisError(f"the SMAT curve has no equations of degree ≤ {top} that cut it out")


def constant_radius(sample: SmatSample) -> bool:
    """Whether ``ρ`` is constant on the sampled points (a pipe): a linear equation in ``r`` alone."""
    exps = monomials(1)
    return any(set(e for e, c in zip(exps, v) if c) == {(0, 0, 0, 1), (0, 0, 0, 0)} for v in vanishing(sample, exps))


def _free_coordinates(linear: list[Poly]) -> list[int]:
    """The coordinates left free by the linear equations (the non-pivot columns of their
    reduced echelon form)."""
    if not linear:
        return [0, 1, 2, 3]
    R = linear[0].ring
    rows = [[g.coeff(x) for x in R.gens] for g in linear]
    _, pivots = sympy.Matrix(rows).rref()
    return [i for i in range(4) if i not in pivots]


def _embed(e: tuple[int, ...], free: list[int]) -> tuple[int, ...]:
    out = [0, 0, 0, 0]
    for i, k in zip(free, e):
        out[i] = k
    return tuple(out)


PROJECTIONS = (
    ((1, 0, 0, 0), (0, 1, 0, 0)),
    ((1, 0, 0, 0), (0, 0, 1, 0)),
    ((0, 1, 0, 0), (0, 0, 1, 0)),
    ((0, 0, 1, 0), (0, 0, 0, 1)),
    ((1, 0, 0, 0), (0, 0, 0, 1)),
    ((0, 1, 0, 0), (0, 0, 0, 1)),
)
"""Coordinate projections tried first for the plane model (small coefficients); a random one
follows. The first in shape position (every coordinate a rational function of ``u, v`` on the
curve) is birational and is kept."""


def _decompose(
    generators: list[Poly],
    sample: SmatSample,
    rnd: random.Random,
    *,
    timeout: float,
    cancel: threading.Event | None,
) -> list[SmatCurve]:
    """Singular: the one-dimensional associated primes of the ideal, with spine data; keep the
    smallest set of components whose union carries every sampled point."""
    hyper = [rnd.randint(-9, 9) or 1 for _ in range(5)]
    plane = [rnd.randint(-9, 9) or 1 for _ in range(4)]
    projections = list(PROJECTIONS) + [
        (tuple(rnd.randint(-5, 5) or 1 for _ in range(4)), tuple(rnd.randint(-5, 5) or 1 for _ in range(4)))
    ]
    weights = ",".join(str(c) for pair in projections for row in pair for c in row)
    ideal = ",".join(poly_to_singular(g) for g in generators)
    lin = "+".join(f"({c})*{n}" for c, n in zip(hyper, SMAT_NAMES)) + f"+({hyper[4]})"
    lin3 = "+".join(f"({c})*{n}" for c, n in zip(plane, SMAT_NAMES[:3])) + f"+({plane[3]})"
    script = f"""LIB "primdec.lib";
ring sR = 0,(m1,m2,m3,r),dp; short = 0;
ideal J = {ideal};
int d = dim(std(J));
{emit("dim", "string(d)")}
intmat W[{2 * len(projections)}][4] = {weights};
ring sP = 0,(m1,m2,m3,r,u,v),dp; short = 0;
ring sV = (0,v),(m1,m2,m3,r,u),lp; short = 0;
ring s3 = 0,(m1,m2,m3),dp; short = 0;
setring sR;
int i; int c; int k; int j; int ok; int hit;
if (d == 1) {{
  list L = minAssGTZ(J);
  for (i = 1; i <= size(L); i++) {{
    ideal P = std(L[i]);
    if (dim(P) == 1) {{
      sorguiEmit("component", string(i));
      sorguiEmit("gens" + string(i), string(P));
      sorguiEmit("smatdeg" + string(i), string(vdim(std(P + ideal({lin})))));
      ideal Sp = eliminate(P, r);
      setring s3; ideal Sp3 = std(imap(sR, Sp));
      sorguiEmit("spine" + string(i), string(Sp3));
      sorguiEmit("spinedeg" + string(i), string(vdim(std(Sp3 + ideal({lin3})))));
      for (c = 1; c <= {len(projections)}; c++) {{
        setring sV; option(redSB);
        poly lu = 0; poly lv = 0;
        for (k = 1; k <= 4; k++) {{ lu = lu + W[2*c-1, k]*var(k); lv = lv + W[2*c, k]*var(k); }}
        ideal G = std(ideal(imap(sR, P)) + ideal(u - lu, v - lv));
        ok = 1;
        for (k = 1; k <= 4; k++) {{
          hit = 0;
          for (j = 1; j <= size(G); j++) {{ if (leadmonom(G[j]) == var(k)) {{ hit = 1; }} }}
          ok = ok * hit;
        }}
        if (ok || c == {len(projections)}) {{
          sorguiEmit("proj" + string(i), string(c));
          sorguiEmit("shape" + string(i), string(ok));
          sorguiEmit("basis" + string(i), string(G));
          setring sP;
          poly pu = 0; poly pv = 0;
          for (k = 1; k <= 4; k++) {{ pu = pu + W[2*c-1, k]*var(k); pv = pv + W[2*c, k]*var(k); }}
          ideal E = imap(sR, P), u - pu, v - pv;
          sorguiEmit("plane" + string(i), string(eliminate(E, m1*m2*m3*r)));
          break;
        }}
      }}
      setring sR;
    }}
  }}
}}
"""
    found = run_script(script, timeout=timeout, cancel=cancel)
    if parse_int(found["dim"][0]) != 1:
        return []
    R = poly_ring(SMAT_NAMES, QQ)
    symbols = {n: sympy.Symbol(n) for n in SMAT_NAMES + PLANE_NAMES}
    R3 = poly_ring(SMAT_NAMES[:3], QQ)
    RP = poly_ring(PLANE_NAMES, QQ)
    candidates = []
    for key in found.get("component", []):
        eqs = tuple(R.from_expr(e) for e in parse_list(found[f"gens{key}"][0], symbols) if e != 0)
        spine = tuple(R3.from_expr(e) for e in parse_list(found[f"spine{key}"][0], symbols) if e != 0)
        planes = [RP.from_expr(e) for e in parse_list(found[f"plane{key}"][0], symbols) if e != 0]
        projection = projections[parse_int(found[f"proj{key}"][0]) - 1]
        inverse = None
        if parse_int(found[f"shape{key}"][0]) == 1:
            inverse = _shape_inverse(parse_list(found[f"basis{key}"][0], symbols), symbols)
        candidates.append(
            _Candidate(
                eqs,
                spine,
                parse_int(found[f"smatdeg{key}"][0]),
                parse_int(found[f"spinedeg{key}"][0]),
                planes,
                projection,
                inverse,
            )
        )
    chosen = _covering(candidates, sample, rnd)
    return [_curve(c) for c in chosen]


@dataclass(frozen=True)
class _Candidate:
    equations: tuple[Poly, ...]
    spine: tuple[Poly, ...]
    smat_degree: int
    spine_degree: int
    planes: list[Poly]
    projection: tuple[tuple[int, ...], tuple[int, ...]]
    inverse: tuple[sympy.Expr, ...] | None


def _shape_inverse(basis: list[sympy.Expr], symbols: dict[str, sympy.Symbol]) -> tuple[sympy.Expr, ...] | None:
    """``(m1, m2, m3, r)`` as rational functions of ``(u, v)`` from a lexicographic basis in
    shape position over ``QQ(v)``: each coordinate ``x`` has a basis element ``c·x − h(u)``."""
    u, v = symbols["u"], symbols["v"]
    out = []
    for name in SMAT_NAMES:
        x = symbols[name]
        for e in basis:
            e = sympy.expand(e)
            if (e.free_symbols - {x, u, v}) or sympy.degree(e, x) != 1:
                continue
            lead = e.coeff(x)
            if u in lead.free_symbols:
                continue
            out.append(sympy.cancel(-(e - lead * x) / lead))
            break
        else:
            return None
    return tuple(out)


def _covering(candidates: list[_Candidate], sample: SmatSample, rnd: random.Random) -> list[_Candidate]:
    """The smallest set of components whose union vanishes on every sampled point (tested with
    the product of one random combination of each component's generators)."""
    combos = []
    for candidate in candidates:
        eqs = candidate.equations
        R = eqs[0].ring
        combos.append(sum((R(rnd.randint(1, 9)) * g for g in eqs), R.zero))
    for size in range(1, len(candidates) + 1):
        for subset in combinations(range(len(candidates)), size):
            product = combos[subset[0]]
            for j in subset[1:]:
                product *= combos[j]
            if vanishes_on_sample(product, sample):
                return [candidates[j] for j in subset]
    return []


def _curve(candidate: _Candidate) -> SmatCurve:
    eqs = candidate.equations
    R = eqs[0].ring
    linear_m = [g for g in candidate.spine if total_degree(g) <= 1]
    constant = None
    r = R.gens[3]
    for g in eqs:
        if all(m[:3] == (0, 0, 0) for m in g.keys()):
            if total_degree(g) == 1:
                constant = str(-g.coeff(1) / g.coeff(r))
            else:
                constant = f"a root of {poly_str(g)}"
    planes = candidate.planes
    G = planes[0] if len(planes) == 1 else _gcd_all(planes)
    return SmatCurve(
        equations=eqs,
        spine_equations=candidate.spine,
        spine_degree=candidate.spine_degree,
        smat_degree=candidate.smat_degree,
        planar=_linear_rank(linear_m) >= 1,
        on_line=_linear_rank(linear_m) >= 2,
        constant_radius=constant,
        plane_model=G,
        projection=candidate.projection,
        birational=candidate.inverse is not None or total_degree(G) == candidate.smat_degree,
        inverse=candidate.inverse,
    )


def _gcd_all(polys: list[Poly]) -> Poly:
    g = polys[0]
    for p in polys[1:]:
        g = g.gcd(p)
    return g


def _linear_rank(polys: list[Poly]) -> int:
    """The rank of the homogeneous linear parts of linear polynomials in ``m``."""
    if not polys:
        return 0
    R = polys[0].ring
    rows = [[g.coeff(x) for x in R.gens] for g in polys]
    return cast(int, sympy.Matrix(rows).rank())
