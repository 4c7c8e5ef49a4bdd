"""The strings of a report read for its checks: formulas, numbers and vectors of ``K``, and
polynomials evaluated modulo a prime (:mod:`..algebra.modular`).

A report's exact strings are read by the engine's reader of machine-written formulas
(:mod:`..expressions`) in :data:`REPORT_SYNTAX`: sorgui's own variable names, ``sqrt``, ``I``,
and ``cos``/``sin`` of the angle of a canal surface's circles. Nothing is evaluated as code.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import sympy
from flint import fmpq_mpoly
from sympy.polys.domains.domain import Domain

from ..algebra.linalg import Vector
from ..algebra.modular import Point
from ..algebra.polys import Poly, is_rational_field, to_flint
from ..errors import ClaimError, ExpressionError, ParseError
from ..expressions import Syntax, read
from ..parsing import parse_polynomial

NAMES = ("x", "y", "z", "s", "t", "w", "r", "u", "v", "m1", "m2", "m3", "theta", "tau", "a", "h", "rho")
"""The variables of sorgui's results: space, the parameters of maps and profiles, the SMAT
coordinates of canal surfaces, the parameter of a witness line, the ring parameter of
Singular's fields, and the height and squared distance of a parametrization's profile curve."""

REPORT_SYNTAX = Syntax(
    powers=("**", "^"),
    decimals=False,
    rational_exponents=True,
    functions={"sqrt": sympy.sqrt, "sin": sympy.sin, "cos": sympy.cos},
    constants={"I": sympy.I},
    names={name: sympy.Symbol(name) for name in NAMES},
)
"""The syntax of every exact string sorgui writes into a report."""


@lru_cache(maxsize=8192)
def formula(text: str) -> sympy.Expr:
    """The report string ``text`` as a sympy expression (:class:`ExpressionError` otherwise)."""
    return read(text, REPORT_SYNTAX)


def number(K: Domain, text: str, where: str) -> Any:  # noqa: ANN401 - an element of K
    """The report's number ``text`` as an element of ``K`` (refused when it is not one: a complex
    number, a square root outside ``K``, a variable)."""
    try:
        value = formula(text)
        if value.free_symbols:
            raise ExpressionError("it holds a variable")
        return K.from_sympy(value)
    except (ExpressionError, sympy.CoercionFailed, sympy.polys.polyerrors.CoercionFailed, ValueError) as exc:
        raise ClaimError(where, f"is not a number of the field {K}: {text!r} ({exc})") from None


def vector(K: Domain, texts: Sequence[str], where: str) -> Vector:
    """Three numbers of ``K``."""
    return tuple(number(K, text, f"{where}[{i}]") for i, text in enumerate(texts))


def nonzero(v: Vector, where: str) -> Vector:
    if not any(v):
        raise ClaimError(where, "is the zero vector")
    return v


@dataclass(frozen=True)
class Surface:
    """A polynomial ``g ∈ K[x, y, z]`` ready to be evaluated modulo a prime: ``g`` in flint, the
    square roots of ``K`` being extra variables (:func:`..algebra.numberfields.to_flint`)."""

    polynomial: Poly
    flint: fmpq_mpoly
    radicands: tuple[int, ...]

    @classmethod
    def of(cls, g: Poly) -> Surface:
        K = g.ring.domain
        if is_rational_field(K):
            return cls(g, to_flint(g), ())
        from ..algebra import numberfields

        return cls(g, numberfields.to_flint(g), numberfields.radical_basis(K).radicands)

    @property
    def degree(self) -> int:
        return max((sum(m) for m in self.polynomial.itermonoms()), default=0)

    def at(self, point: Point, xyz: Sequence[int]) -> int:
        """``g(xyz)`` modulo the point's prime (``xyz`` residues)."""
        from flint import fmpq

        roots = [point.embedding.sqrt_rational(d) for d in self.radicands]
        return point.embedding.rational(self.flint(*[fmpq(v) for v in (*xyz, *roots)]))

    def top_form(self) -> Surface:
        """The form of highest degree ``g_d`` (the cone's base curve, docs/math.md §10)."""
        d = self.degree
        g = self.polynomial
        top = g.ring.from_dict({m: c for m, c in g.items() if sum(m) == d})
        return Surface.of(top)


def read_polynomial(text: str, where: str) -> Poly:
    """A polynomial of the report read by the parser of typed input (bounded as typed input is)."""
    try:
        return parse_polynomial(text).polynomial
    except ParseError as exc:
        raise ClaimError(where, f"is not a polynomial sorgui reads: {exc.message}") from None


def values(point: Point, texts: Sequence[str], **names: int) -> list[int]:
    """The report's formulas ``texts`` at ``point``, with the variables ``names`` set to the given
    residues (the other variables keep the point's own)."""
    here = point.with_values(names) if names else point
    return [here.value(formula(text)) for text in texts]
