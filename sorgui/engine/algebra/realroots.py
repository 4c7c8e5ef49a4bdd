"""Exact counting of the real roots of a univariate polynomial over ``K ⊂ R`` (docs/math.md §5).

The paper's Corollary needs the number of real roots of ``h = r̂·q̂``: the real surface is
rational iff it is unirational and ``h`` has at most two real roots. Algorithm: Sturm's
theorem on the square-free part over ``K``; the signs of elements of ``K`` come from arb balls
refined until they exclude 0 (rigorous, never plain floats).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import flint
import sympy
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain
from sympy.polys.rootisolation import dup_sturm
from sympy.polys.sqfreetools import dup_sqf_part

from ..errors import AnalysisError
from .polys import Poly, is_rational_field, to_expr


def count_real_roots(h: Poly) -> int:
    """The number of distinct real roots of a univariate ``h`` with coefficients in ``K ⊂ R``
    (for the Corollary of the paper: ``r̂·q̂`` has at most two real roots iff ``X`` is rational).

    Sturm's theorem on the square-free part over ``K``; the signs of the leading coefficients
    (elements of ``K``) come from arb balls refined until they exclude 0, so the answer is
    exact.
    """
    used = {i for m in h.itermonoms() for i, e in enumerate(m) if e}
    if len(used) > 1:
        raise ValueError("count_real_roots needs a univariate polynomial")
    if not h:
        raise ValueError("the zero polynomial has infinitely many roots")
    K = h.ring.domain
    i = used.pop() if used else 0
    degree = max(m[i] for m in h.itermonoms())
    dense = [K.zero] * (degree + 1)
    for m, c in h.items():
        dense[degree - m[i]] = c
    f = dense if K.is_Field else [K.get_field().convert(c, K) for c in dense]
    field = K if K.is_Field else K.get_field()
    chain = dup_sturm(dup_sqf_part(f, field), field)
    at_plus = [sign(field, p[0]) for p in chain]
    at_minus = [s * (-1) ** (len(p) - 1) for s, p in zip(at_plus, chain, strict=True)]
    return sign_changes(at_minus) - sign_changes(at_plus)


def sign_changes(signs: Sequence[int]) -> int:
    """The number of sign changes in a sequence of signs (zeros skipped), as in Sturm's theorem."""
    nonzero = [s for s in signs if s]
    return sum(1 for u, v in zip(nonzero, nonzero[1:]) if u != v)


def sign(K: Domain, c: Any) -> int:
    """The sign of ``c ∈ K``: exact over ``QQ``; over ``QQ(θ)``, ``c(θ)`` in ball arithmetic
    with rising precision until the ball excludes 0 (it does, as ``c ≠ 0``)."""
    if not c:
        return 0
    if is_rational_field(K):
        return 1 if c > 0 else -1
    coeffs = [flint.fmpq(int(QQ.numer(q)), int(QQ.denom(q))) for q in map(QQ.convert, c.to_list())]
    prec = 64
    while prec <= 1 << 16:
        with flint.ctx.workprec(prec):
            theta = _arb(K.ext.as_expr())
            value = flint.arb(0)
            for q in coeffs:
                value = value * theta + q
            if value > 0:
                return 1
            if value < 0:
                return -1
        prec *= 4
    raise AnalysisError(f"could not decide the sign of {to_expr(K, c)}")


def _arb(expr: sympy.Expr) -> flint.arb:
    """A ball containing the real radical expression ``expr`` (rationals, ``+``, ``*``, powers
    with integer or half-integer exponents), at the current working precision."""
    if expr.is_Rational:
        return flint.arb(flint.fmpq(int(expr.p), int(expr.q)))
    if expr.is_Add:
        return sum((_arb(e) for e in expr.args), flint.arb(0))
    if expr.is_Mul:
        value = flint.arb(1)
        for e in expr.args:
            value *= _arb(e)
        return value
    if expr.is_Pow and expr.exp.is_Rational and expr.exp.q in (1, 2):
        base = _arb(expr.base)
        if expr.exp.q == 2:
            if not base > 0:
                raise AnalysisError(f"{expr} is not a real number")
            base = base.sqrt()
        return base ** int(expr.exp.p)
    raise AnalysisError(f"cannot evaluate {expr} as a real algebraic number")
