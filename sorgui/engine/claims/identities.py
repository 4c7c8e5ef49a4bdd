"""The identities a report claims, tested at random points modulo random primes.

Each check of :mod:`.recognition`, :mod:`.maps` and :mod:`.canal` adds an :class:`Identity`: the
field it vouches for, what is wrong when it fails, a test of one :class:`~..algebra.modular.Point`
and the formulas it reads (their square roots decide the :class:`~..algebra.modular.Embedding`).
:meth:`Identities.run` tests each in :data:`~..algebra.modular.ROUNDS` rounds; a point where a
denominator vanishes or a square root is missing is drawn again. An identity that holds passes
every round; one that does not fails with probability at least ``1 - D/p`` in each
(docs/math.md §14).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

import sympy

from ..algebra.modular import ATTEMPTS, ROUNDS, Embedding, Point, Redraw, embedding, radicands_of
from ..errors import AnalysisError, ClaimError
from .formulas import formula, values


@dataclass(frozen=True)
class Identity:
    """A claim of the report as a test of one point: ``test`` is ``True`` where it holds."""

    where: str
    fails: str
    test: Callable[[Point], bool]
    attempts: int = ATTEMPTS


@dataclass
class Identities:
    """The identities of one report and the radicands their formulas hold."""

    items: list[Identity] = field(default_factory=list)
    radicands: set[sympy.Rational] = field(default_factory=set)
    complex_unit: bool = False

    def add(self, where: str, fails: str, test: Callable[[Point], bool], texts: Iterable[str] = ()) -> None:
        """Add the identity ``test`` about ``where``, reading the formulas ``texts``."""
        found = radicands_of(formula(text) for text in texts)
        self.radicands |= found.rationals
        self.complex_unit = self.complex_unit or found.complex_unit
        self.items.append(Identity(where, fails, test, ATTEMPTS << min(found.polynomial_factors, MAX_FACTORS)))

    def proportional_to(
        self, where: str, fails: str, claimed: str, truth: Callable[[Point], int], texts: Iterable[str] = ()
    ) -> None:
        """Add the identity that the report's formula ``claimed`` is ``truth`` up to a constant
        factor (the same curve or surface), reading ``claimed`` and ``texts``."""

        def value(point: Point) -> int:
            return values(point, [claimed])[0]

        self.add(where, fails, lambda P: proportional(value, truth, P), [claimed, *texts])

    def need(self, *radicands: sympy.Rational | int) -> None:
        """Square roots the tests take besides those of their formulas (the field ``K``'s)."""
        self.radicands |= {sympy.Rational(q) for q in radicands}

    def run(self) -> None:
        """Test every identity in each round (:class:`ClaimError` for the first that fails)."""
        for _ in range(ROUNDS):
            try:
                embedded = embedding(self.radicands, self.complex_unit)
            except AnalysisError as exc:
                raise ClaimError("the report", f"cannot be checked: {exc.message}") from None
            for item in self.items:
                if not _holds(item, embedded):
                    raise ClaimError(item.where, item.fails)


MAX_FACTORS = 12
"""Polynomials under square roots beyond which no more points are drawn for one identity."""


def _holds(item: Identity, embedded: Embedding) -> bool:
    for _ in range(item.attempts):
        try:
            return item.test(Point(embedded))
        except Redraw:
            continue
        except (ValueError, ZeroDivisionError, TypeError) as exc:  # a formula that is not one
            raise ClaimError(item.where, f"cannot be evaluated ({exc})") from None
    raise ClaimError(item.where, "cannot be checked: every point tried was a pole or a branch point")


def proportional(first: Callable[[Point], int], second: Callable[[Point], int], point: Point) -> bool:
    """Whether two functions are proportional (the same zero set: ``a·g = b·h`` for constants):
    ``first(P)·second(Q) = first(Q)·second(P)`` at two points, neither zero at ``P`` (a zero
    function is proportional to every other)."""
    other = point.fresh()
    a, b = first(point), second(point)
    c, d = first(other), second(other)
    return a != 0 and b != 0 and (a * d - b * c) % point.prime == 0
