r"""Three gaps of sympy met by square roots of large integers, closed where sympy looks its
helpers up. ``sympy.sqrt`` of an integer factors it by trial division and tests the cofactor
(docs/benchmarks.md, the tails entry of 2026-12-06), and such a root becomes a generator of
sympy's polynomials. The first two are gaps of the flint ground types that sorgui sets
(``sorgui/__init__.py``).

- sympy's strong BPSW probable-prime test runs in pure Python under flint ground types (its
  gmpy2 version is used only with gmpy2 ground types): 7 s for the cofactor of a 5000-digit
  radicand. flint runs the same test in C (:func:`probable_prime`).
- sympy's integer roots return flint's ``fmpz`` under flint ground types, and its perfect-power
  test takes ``math.log`` of them, which converts an ``fmpz`` to a float: beyond 10³⁰⁸ that
  raised ``OverflowError`` and stopped the analysis of ``z = c·(x² + y²)`` for a 2000-digit
  ``c``. Its roots are made Python integers (:func:`integer_root`).
- sympy sorts a polynomial's generators by splitting each one's text into a name and trailing
  digits with ``^(.*?)(\d*)$``, whose lazy match takes quadratic time on a long run of digits:
  5 s to export the maps of that sphere to Maple, over ``sqrt(c)``. :data:`GENERATOR` splits
  the same way in linear time.
"""

from __future__ import annotations

import re

from flint import fmpz
from sympy.external import gmpy
from sympy.ntheory import factor_, primetest
from sympy.polys import polyutils

GENERATOR = re.compile(r"^((?:.*\D)?)(\d*)$", re.MULTILINE)
r"""sympy's ``^(.*?)(\d*)$`` on a generator's text: the name is everything up to the last
character that is not a digit (greedy, so one pass), the index the digits after it."""


def probable_prime(n: int) -> bool:
    """sympy's ``is_strong_bpsw_prp``, done by flint in C (``fmpz.is_probable_prime``)."""
    return bool(fmpz(n).is_probable_prime())


def integer_root(x: int, n: int) -> tuple[int, bool]:
    """sympy's ``iroot`` (the integer part of ``x^(1/n)`` and whether it is exact), as Python
    integers, which ``math.log`` takes at any size."""
    root, exact = gmpy.iroot(x, n)
    return int(root), bool(exact)


def install() -> None:
    """Put the three in the sympy modules that call them (each imported its helpers by name). Called
    where sorgui's processes meet sympy's numbers: :mod:`..algebra.polys` (the analysis) and
    :mod:`..expressions` (the exports and the window reading the engine's strings)."""
    primetest.is_strong_bpsw_prp = probable_prime
    factor_.iroot = integer_root
    polyutils._re_gen = GENERATOR
