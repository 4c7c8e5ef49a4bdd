"""What both readers of an equation accept (:mod:`.expanded`, the fast path, and :mod:`.syntax`,
the general parser): the limits on degree, digits, nesting and work that make hostile or mistyped
input fail fast, checked before anything is expanded, and what a pasted statement may wrap the equation in
(a label ``f(x, y, z) =``, a final ``;``, LaTeX's ``$ $``).
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
MAX_BITS = 66_500  # size of any constant (numerator or denominator): 20,000 digits (66,439 bits) and the few
# bits a bound of a product of sums adds: (10^20000 - 1)·z·(x + 1) has no larger coefficient
# Python refuses to print integers of more than 4,300 digits by default; the engine prints the
# numbers it derives from the input (products of a few coefficients), so every process of sorgui
# raises that limit to MAX_PRINTED_DIGITS (sorgui/__init__.py), which the limits above keep at
# least ten times MAX_DIGITS: an accepted input is analysed, never refused by ``str``.
MAX_RADICAND_DIGITS = 50  # sqrt(n) needs the square part of n: factoring must stay fast
MAX_RADICANDS = 4  # [K : QQ] <= 16
MAX_WORK = 5_000_000  # coefficient multiplications while expanding (a few seconds)
MAX_TOTAL_BITS = 128_000_000
"""The bits of an expanded polynomial's coefficients, all together (terms × the bits of each, a
bound read off the syntax tree): 16 MB. ``(a·x + b·y + c·z + 1)^60`` with 300-digit ``a, b, c``
(a kilobyte, within every other limit) expanded to 39,711 terms of 18,000 digits, printed 537 MB
and used 5 GB. A dense degree-60 polynomial of 900-digit coefficients is within it."""


class Limits:
    """The limits that an expanded polynomial can reach, for the fast path (:mod:`.expanded`)."""

    __slots__ = ("bits", "decimal_exponent", "degree", "digits")

    def __init__(self, degree: int, digits: int, bits: int, decimal_exponent: int) -> None:
        self.degree = degree
        self.digits = digits
        self.bits = bits
        self.decimal_exponent = decimal_exponent


LIMITS = Limits(degree=MAX_DEGREE, digits=MAX_DIGITS, bits=MAX_BITS, decimal_exponent=MAX_DECIMAL_EXPONENT)

_LABEL = re.compile(
    r"\s*+(?:poly\s++)?([A-Za-z_]\w*+)\s*+"
    r"(\(\s*+x\s*+,\s*+y\s*+,\s*+z\s*+\)|\[\s*+x_?\s*+,\s*+y_?\s*+,\s*+z_?\s*+\])?+\s*+:?=(?!=)",
    re.ASCII,
)
"""A label in front of an equation: ``f(x, y, z) =``, Maple's ``f :=``, Singular's ``poly f =``,
Mathematica's ``f[x_, y_, z_] :=`` (any name, ``=`` or ``:=``). Possessive: a run of spaces is
read once, never again in another way (a megabyte of them takes a few milliseconds)."""
_MONOMIAL_NAME = re.compile(r"[xyz0-9]*", re.ASCII)
"""A name that is a monomial (``xy``, Singular's ``x2``): the left side of an equation, no label."""
COMMENT = r"(?:(?<=\s)|(?<![\s\S]))(?:#|//|%)[^\n]*+"
"""A comment to the end of its line: Python's and Maple's ``#``, Singular's ``//``, MATLAB's and
LaTeX's ``%``, at the start of a line or after a space (``x%2`` is no comment, but an error)."""
_COMMENT = re.compile(COMMENT)
_OPENING = re.compile(r"\s*(\$\$?|\\\[|\\\(|\\begin\{(?:multline|equation|align|gather|displaymath)\*?\})")
_CLOSING = {"$": "$", "$$": "$$", "\\[": "\\]", "\\(": "\\)"}
"""Each math delimiter's closing one; an environment ``\\begin{multline*}`` (sorgui's LaTeX
files set a long equation in one) closes with its ``\\end``."""


_TEXT_REPORT = re.compile(r"\s*+f = [^\n]*+\r?\nfield K = ")
"""The first two lines of sorgui's own text report (``NAME.txt``, the terminal's answer)."""


def refuse_text_report(text: str) -> None:
    """A :class:`ParseError` for sorgui's own text report, which is no equation: opened or pasted
    back it said "the components of a triple have no labels" (its lines hold commas)."""
    if _TEXT_REPORT.match(text):
        from .errors import ParseError

        first = text.find("\n")
        raise ParseError(
            "this is sorgui's text report, which is not read back: open its JSON report "
            "(sorgui open REPORT.json, or File → Open in the window), or take the equation of its first line",
            0,
            first if first > 0 else len(text),
        )


def without_comments(text: str) -> str:
    """``text`` with each comment (:data:`COMMENT`) replaced by spaces: the same positions."""
    if "#" not in text and "//" not in text and "%" not in text:
        return text
    return _COMMENT.sub(lambda match: " " * len(match.group()), text)


def statement_span(text: str) -> tuple[int, int]:
    """The characters ``start:end`` of ``text`` that hold the equation or the parametrization a
    user pasted as a statement of another program: without comments around it, LaTeX's math
    delimiters (``$ $``, ``$$ $$``, ``\\[ \\]``, ``\\( \\)``, a ``multline*``, ``equation``,
    ``align`` or ``gather`` environment) and a final ``;`` or ``:``
    (Maple, Singular, Mathematica, MATLAB) or ``,`` (an item of a list). The readers read only
    these characters, so every position they report is one of ``text``."""
    text = without_comments(text)
    end = _unterminated(text, 0, len(text))
    start = len(text) - len(text.lstrip()) if text[:1].isspace() else 0
    opening = _OPENING.match(text)
    if opening is not None:
        delimiter = opening.group(1)
        closing = _CLOSING.get(delimiter) or delimiter.replace("\\begin", "\\end", 1)
        if end - len(closing) >= opening.end() and text.endswith(closing, opening.end(), end):
            start, end = opening.end(), _unterminated(text, opening.end(), end - len(closing))
    return start, end


def _unterminated(text: str, start: int, end: int) -> int:
    """``end`` moved back over trailing white space and one final ``;``, ``:`` or ``,``."""
    while end > start and text[end - 1].isspace():
        end -= 1
    return end - 1 if end > start and text[end - 1] in ";:," else end


def equation_span(text: str) -> tuple[int, int]:
    """:func:`statement_span` without a label in front (:data:`_LABEL`): ``f(x,y,z) = g`` and
    ``f := g`` are the equation ``g = 0``. A left side that is a monomial (``z = x^2 + y^2``)
    is no label."""
    plain = without_comments(text)  # once: statement_span finds no comment left in it
    start, end = statement_span(plain)
    label = _LABEL.match(plain, start, end)
    if label is None or (label.group(2) is None and _MONOMIAL_NAME.fullmatch(label.group(1))):
        return start, end
    return label.end(), end
