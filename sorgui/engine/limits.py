"""What both readers of an equation accept (:mod:`.expanded`, the fast path, and :mod:`.syntax`,
the general parser): the limits on degree, digits, nesting and work that make hostile or mistyped
input fail fast, checked before anything is expanded, and the optional ``f(x, y, z) =`` in front.
Light to import: the parser's entry points (:mod:`.parsing`) load the general parser only for a
text that the fast path declines."""

from __future__ import annotations

import re

from sorgui import MAX_PRINTED_DIGITS as MAX_PRINTED_DIGITS  # re-exported: the bound the parser keeps

MAX_DEGREE: int = 60
"""The largest total degree accepted (checked on the AST, before anything is expanded)."""
MAX_LENGTH = 1_000_000  # characters of input
MAX_NESTING = 200  # parentheses and '^' nested inside each other
MAX_EXPONENT = 10_000  # |n| in c^n for a constant c
MAX_DECIMAL_EXPONENT = 1_000  # |e| in 1.5e-3
MAX_DIGITS = 20_000  # digits of one number literal
MAX_BITS = 66_439  # size of any constant (numerator or denominator): 20,000 digits
# Python refuses to print integers of more than 4,300 digits by default; the engine prints the
# numbers it derives from the input (products of a few coefficients), so every process of sorgui
# raises that limit to MAX_PRINTED_DIGITS (sorgui/__init__.py), which the limits above keep at
# least ten times MAX_DIGITS: an accepted input is analysed, never refused by ``str``.
MAX_RADICAND_DIGITS = 50  # sqrt(n) needs the square part of n: factoring must stay fast
MAX_RADICANDS = 4  # [K : QQ] <= 16
MAX_WORK = 5_000_000  # coefficient multiplications while expanding (a few seconds)


class Limits:
    """The limits that an expanded polynomial can reach, for the fast path (:mod:`.expanded`)."""

    __slots__ = ("bits", "decimal_exponent", "degree", "digits")

    def __init__(self, degree: int, digits: int, bits: int, decimal_exponent: int) -> None:
        self.degree = degree
        self.digits = digits
        self.bits = bits
        self.decimal_exponent = decimal_exponent


LIMITS = Limits(degree=MAX_DEGREE, digits=MAX_DIGITS, bits=MAX_BITS, decimal_exponent=MAX_DECIMAL_EXPONENT)

FUNCTION_NAME = re.compile(r"\s*[A-Za-z]\w*\s*\(\s*x\s*,\s*y\s*,\s*z\s*\)\s*:?=", re.ASCII)
"""A leading ``f(x, y, z) =`` (any name, ``=`` or ``:=``): skipped, ``f(x,y,z) = g`` is ``g = 0``."""
