"""Safe reader of a rational parametrization: ``x = X(s, t), y = Y(s, t), z = Z(s, t)`` or ``(X, Y, Z)``.

The forms (docs/math.md §13)::

    x = X, y = Y, z = Z     in any order, separated by ',' or ';' or line breaks; a label may
                            name the parameters: x(u, v) = X
    (X, Y, Z)               a triple, also after 'P(u, v) =', '\\mathbf{r}(u, v) =', '(x, y, z) ='
                            or a name, in parentheses, brackets or braces (Maple's
                            X1 := [X, Y, Z];, Mathematica's X1 = {X, Y, Z};), or without them:
                            X, Y, Z; and after a function's head, after a name or none: Maple's
                            P := (u, v) -> [X, Y, Z], LaTeX's (u, v) \\mapsto (X, Y, Z), Python's
                            lambda u, v: (X, Y, Z), def P(u, v): return (X, Y, Z), return X, Y, Z,
                            numpy's np.array([X, Y, Z]); a module's name before a function
                            is read as Python means it: np.cos(v), math.sqrt(2)

The parameters are the two names other than ``x, y, z`` that the components use (one-letter names
run together are products, as ``x, y, z`` are in equations: ``st`` is ``s·t``), in the order a
label, a prefix or a function's head gives, else in alphabetical order. Each component is read
by the equation parser's own tokenizer and recursive descent (:mod:`.parsing`) with the
parameters as its variables, checked by its first pass (sizes, exponents, square roots: the
field ``K`` is the same as for an equation), then evaluated as a fraction ``N/D`` of polynomials
in ``K[s, t]`` (python-flint over ``QQ``). Nothing typed is evaluated as code. A parameter
written only in ``cos(k·u)`` and ``sin(k·u)`` is an angle, read in ``t = tan(u/2)``
(:func:`_angles`).

Refused, each in one line with its position: a component count other than three, a label given
twice, parameters named differently twice, a function's head that takes other than two, an
empty or a constant component, ``x``, ``y`` or ``z`` inside a component, a function other than
``sqrt`` of a number and ``cos`` and ``sin`` of a whole multiple of a parameter (the components
are rational functions), a parameter both inside and outside them, one, three or more parameters, a
denominator that is identically zero, a map whose image is a curve or a point
(``P_s × P_t ≡ 0``), and the limits of the equation parser (degree 60 over a common
denominator, number sizes, nesting).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from . import parsing, syntax
from .errors import ParseError
from .limits import MAX_DEGREE, MAX_LENGTH, MAX_WORK, statement_span, without_comments
from .parsing import is_parametrization
from .syntax import Neg, Node, Num, Power, Product, Reciprocal, Sqrt, Sum, Var

if TYPE_CHECKING:
    from sympy.polys.domains.domain import Domain

    from .parametric.maps import ParameterRing, RationalMap

COORDINATES = ("x", "y", "z")
TRANSCENDENTAL = frozenset(
    {"tan", "cot", "sec", "csc", "exp", "log", "ln", "sinh", "cosh", "tanh", "atan", "asin", "acos"}
    | {"arctan", "arcsin", "arccos", "pi", "abs"}
)
"""Names a user may write that have no place in a rational function (``cos`` and ``sin`` of a
parameter have: :func:`_angles`)."""
FUNCTIONS = frozenset({"sqrt", "pow", "Sqrt"}) | syntax.TRIGONOMETRIC
"""The functions a component may call: no parameter's name."""
ANGLE_NAMES = ("t", "s", "w", "r")
"""The names of ``tan(u/2)`` for an angle ``u``, the first not otherwise taken."""

_RIGHT = re.compile(r"\\right\s*$")
"""LaTeX's ``\\right`` of the closing parenthesis of a triple, left at the end of its last component."""
_DECIMAL_COMMA = re.compile(r"(?<![\w.^*])\d+,\d+(?![\d.,])")
"""A number written with a decimal comma, ``1,5``: no separator of components."""
_LABEL = re.compile(r"\s*+([xyz])\s*+(?:\(\s*+([A-Za-z]++)\s*+,\s*+([A-Za-z]++)\s*+\))?+\s*+(?::?=(?!=)|->)")
"""``x =``, ``x(u, v) =`` or Mathematica's rule ``x ->`` in front of a component (possessive, as
:data:`.limits._LABEL`)."""
_NAME = r"(?:[A-Za-z_]\w*+|\\[A-Za-z]++(?:\s*+\{\s*+[A-Za-z]\w*+\s*+\}|\s++[A-Za-z]\w*+))"
"""The name of a map: ``P``, ``X1``, or one in a LaTeX command, ``\\mathbf{r}``, ``\\vec r``."""
_PREFIX = re.compile(
    rf"\s*+(?:(?![xyz]\s*+\(){_NAME}\s*+[(\[]\s*+([A-Za-z]++)_?+\s*+,\s*+([A-Za-z]++)_?+\s*+[)\]]"
    r"|(\(\s*+x\s*+,\s*+y\s*+,\s*+z\s*+\))"
    rf"|(?![xyz0-9]+\b){_NAME})\s*+:?=(?!=)",
    re.ASCII,
)
"""What may come before the components: ``P(u, v) =``, ``\\mathbf{r}(u, v) =`` or Mathematica's
``P[u_, v_] :=`` (naming the parameters), ``(x, y, z) =`` (then a triple follows) or a name
that is not a monomial (Maple's ``X1 := [X, Y, Z]``)."""
_ARGUMENTS = r"\s*+([A-Za-z]++(?:\s*+,\s*+[A-Za-z]++)*+)\s*+"
"""The names a function takes, ``u, v``: one group."""
_HEAD = re.compile(
    rf"\s*+(?:\({_ARGUMENTS}\)\s*+(?:->|\\mapsto(?![A-Za-z])|↦)|lambda\s{_ARGUMENTS}:"
    rf"|(?:def\s++[A-Za-z_]\w*+\s*+\({_ARGUMENTS}\)\s*+:\s*+)?+return\b)",
    re.ASCII,
)
"""A function's head before the components, after a name or none: Maple's ``(u, v) ->``,
LaTeX's ``(u, v) \\mapsto``, Python's ``lambda u, v:``, ``def P(u, v): return`` or ``return``."""
_MODULE = re.compile(
    rf"\b(?:np|numpy|math|sympy|sp)\s*+\.\s*+(?=(?:{'|'.join(sorted(FUNCTIONS | TRANSCENDENTAL))})\b)", re.ASCII
)
"""A module's name before a function, as Python code writes it: ``np.cos(v)``, ``math.sqrt(2)``
(read as ``cos(v)``, ``sqrt(2)``: the same positions, the prefix made blanks)."""
_DISPLAY_JOINT = re.compile(r"(\\[\])]|\$\$?+)([^\S\n]*+\n\s*+)(\\[(\[]|\$\$?+)")
"""The end of one LaTeX display and the start of the next on a later line (``\\]`` line break
``\\[``): the components of a map written as three displays, as sorgui's LaTeX file writes them,
are read as three lines."""
_CALL = re.compile(r"\s*+((?:(?:np|numpy)\s*+\.\s*+)?+array)\s*+(?=\()", re.ASCII)
"""numpy's ``np.array`` before the parentheses that hold the triple: ``np.array([X, Y, Z])``."""


@dataclass(frozen=True)
class ParsedParametrization:
    """The parsed map: ``components`` are the texts of ``x(s, t), y(s, t), z(s, t)`` as typed,
    ``parameters`` the typed names of ``s`` and ``t``; ``map`` holds them over ``field``."""

    text: str
    components: tuple[str, str, str]
    parameters: tuple[str, str]
    map: RationalMap
    field: Domain
    radicands: tuple[int, ...]
    angles: tuple[tuple[str, str], ...] = ()
    """For each parameter ``u`` written in ``cos`` and ``sin`` only, ``(u, t)``: the map's
    parameter is ``t = tan(u/2)`` (:func:`_angles`)."""

    @property
    def names(self) -> tuple[str, str] | None:
        """The names of the map's parameters when an angle was replaced (``None``: as typed)."""
        if not self.angles:
            return None
        renamed = dict(self.angles)
        return renamed.get(self.parameters[0], self.parameters[0]), renamed.get(self.parameters[1], self.parameters[1])

    @property
    def notes(self) -> tuple[str, ...]:
        """What was done to read the typed map as a rational one."""
        return tuple(
            f"{u} is an angle: cos({u}) = (1 - {t}^2)/(1 + {t}^2) and sin({u}) = 2*{t}/(1 + {t}^2) with"
            f" {t} = tan({u}/2), so the map is rational in {t} (all of the circle but {u} = pi)"
            for u, t in self.angles
        )


def parse_input(text: str) -> parsing.ParsedPolynomial | ParsedParametrization:
    """An equation or a parametrization, whichever ``text`` is (:func:`is_parametrization`)."""
    return parse_parametrization(text) if is_parametrization(text) else parsing.parse_polynomial(text)


def parse_parametrization(text: str) -> ParsedParametrization:
    """Read ``text`` as a rational parametrization; raises :class:`ParseError` (and nothing
    else) when it is not one of a surface."""
    from .algebra.polys import number_field
    from .parametric.maps import ParameterRing, RationalMap

    if len(text) > MAX_LENGTH:
        raise ParseError(f"the input is too long (more than {MAX_LENGTH:,} characters)", 0, len(text))
    typed, text = text, _without_joints(_MODULE.sub(lambda m: " " * len(m.group()), text))  # the same positions
    spans, named = _layout(text)
    _refuse_characters(text, spans)
    parameters = named or _discover(text, spans)
    _check_names(text, spans, parameters)
    checker = syntax.Evaluator(fractions=True)
    trees = [_tree(text, span, parameters, checker) for span in spans]
    angles = _angles(text, trees, parameters)
    radicands = tuple(sorted(checker.radicands))
    field = number_field(radicands)
    ring = ParameterRing(field)
    reader = _Fractions(ring, checker, syntax.square_roots(field, radicands) if radicands else {})
    fractions = []
    for name, span, tree in zip(COORDINATES, spans, trees):
        try:
            numerator, denominator = reader.value(tree)
        except RecursionError:
            raise ParseError("the expression is nested too deeply", *span) from None
        if ring.is_constant(numerator) and ring.is_constant(denominator):
            raise ParseError(
                f"the component {name} is constant: a parametrization's components depend on {' and '.join(parameters)}"
                f" (type a plane as an equation, e.g. {name} = {text[span[0] : span[1]].strip()[:20]})",
                *span,
            )
        fractions.append((numerator, denominator))
    surface = RationalMap.from_fractions(ring, fractions)
    if surface.degree > MAX_DEGREE:
        raise ParseError(
            f"the degree is too high: over a common denominator the map has degree {surface.degree},"
            f" the limit is {MAX_DEGREE}",
            0,
            len(text),
        )
    if _is_degenerate(surface):
        raise ParseError("the image is a curve or a point, not a surface: P_s × P_t is identically zero", 0, len(text))
    plain = _without_joints(without_comments(typed))
    components = tuple(_RIGHT.sub("", _MODULE.sub("", plain[a:b])).strip() for a, b in spans)
    return ParsedParametrization(
        typed, (components[0], components[1], components[2]), parameters, surface, field, radicands, angles
    )


def _without_joints(text: str) -> str:
    """``text`` with each :data:`_DISPLAY_JOINT` replaced by spaces and its line breaks: the
    same positions."""
    return _DISPLAY_JOINT.sub(lambda m: " " * len(m.group(1)) + m.group(2) + " " * len(m.group(3)), text)


def _angles(text: str, trees: Sequence[Node], parameters: tuple[str, str]) -> tuple[tuple[str, str], ...]:
    """The parameters written inside ``cos`` and ``sin`` (an angle ``u``), each with the name of
    ``tan(u/2)``, which replaces it (docs/math.md §13): ``cos(k·u)`` and ``sin(k·u)`` are then
    rational, the real and imaginary parts of ``((1 − t² + 2i·t)/(1 + t²))^k``. A parameter
    written also outside them is refused: the map is not rational in it."""
    inside: dict[int, Node] = {}
    outside: dict[int, Node] = {}
    stack = list(trees)
    while stack:
        node = stack.pop()
        match node:
            case syntax.Trig():
                inside.setdefault(node.index, node)
            case Var():
                outside.setdefault(node.index, node)
            case Neg() | Reciprocal() | Sqrt():
                stack.append(node.arg)
            case Sum():
                stack.extend(node.terms)
            case Product():
                stack.extend(node.factors)
            case Power():
                stack.extend((node.base, node.exponent))
    for index in inside:
        if index in outside:
            name = parameters[index]
            raise ParseError(
                f"{name} is written both inside cos or sin and outside them: the map is rational in"
                f" neither {name} nor tan({name}/2) (write {name} only as an angle, or not at all in cos and sin)",
                outside[index].start,
                outside[index].end,
            )
    taken = set(parameters)
    angles = []
    for index in sorted(inside):
        name = next(n for n in ANGLE_NAMES if n not in taken)
        taken.add(name)
        angles.append((parameters[index], name))
    return tuple(angles)


# --- the layout: which characters hold x(s, t), y(s, t), z(s, t) ----------------------------


def _layout(text: str) -> tuple[list[tuple[int, int]], tuple[str, str] | None]:
    """The spans of the three components in the order x, y, z, and the parameters a prefix, a
    function's head or the labels name (``None`` when none does); comments, LaTeX's ``$ $`` and a
    final ``;`` aside (:func:`.limits.statement_span`), and what comes in front of the components
    (:data:`_PREFIX`, :data:`_HEAD`, :data:`_CALL` with its parentheses)."""
    plain = without_comments(text)  # the same positions
    start, end = statement_span(plain)
    text, named = plain[:end], None
    prefix = _PREFIX.match(text, start)
    if prefix is not None:
        start = prefix.end()
        if prefix.group(1) is not None:
            named = (prefix.group(1), prefix.group(2))
    head = _HEAD.match(text, start)
    if head is not None:
        start = head.end()
        if head.lastindex is not None:  # the one group of _ARGUMENTS that matched
            span = head.span(head.lastindex)
            named = _agreeing(named, _two(text, *span), *span)
    call = _CALL.match(text, start)
    if call is not None:  # np.array(…): what its parentheses hold
        around = _structure(text, call.end())[1]
        if around is None:
            raise ParseError(
                f"{call.group(1)}(…) holds the whole triple: write {call.group(1)}([X, Y, Z])",
                call.start(1),
                len(text),
            )
        text, start = text[: around[1]], around[0] + 1
    cuts, outer = _structure(text, start)
    if outer is not None and cuts[1]:  # '(X, Y, Z)': the commas inside the parentheses
        segments = _between(outer[0] + 1, cuts[1], outer[1])
    elif prefix is not None and prefix.group(3) is not None:
        raise ParseError("after '(x, y, z) =' write the triple '(X, Y, Z)'", start, len(text))
    else:
        segments = _between(start, cuts[0], len(text))
    labelled = [(_LABEL.match(text, a, b), a, b) for a, b in segments]
    if (prefix or head or call) and any(m is not None for m, _, _ in labelled):
        m = next(m for m, _, _ in labelled if m is not None)
        raise ParseError("the components of a triple have no labels 'x =', 'y =', 'z ='", m.start(1), m.end())
    if len(segments) != 3:
        raise _count_error(text, start, cuts, len(segments))
    if all(m is None for m, _, _ in labelled):
        spans = [_nonempty(text, a, b, name) for (a, b), name in zip(segments, COORDINATES)]
        return spans, named
    by_name: dict[str, tuple[int, int]] = {}
    for label, a, b in labelled:
        if label is None:
            raise ParseError("this component has no label: write all three as 'x = …', 'y = …', 'z = …'", a, b)
        name = label.group(1)
        if name in by_name:
            raise ParseError(f"'{name}' is given twice", label.start(1), label.end(1))
        if label.group(2) is not None:
            named = _agreeing(named, (label.group(2), label.group(3)), label.start(2), label.end(3))
        by_name[name] = _nonempty(text, label.end(), b, name)
    return [by_name[name] for name in COORDINATES], named


def _agreeing(named: tuple[str, str] | None, given: tuple[str, str], start: int, end: int) -> tuple[str, str]:
    """The parameters ``given`` at ``start:end``, the same as those ``named`` before, if any."""
    if named is not None and given != named:
        raise ParseError(
            f"the parameters are named ({', '.join(named)}) before and ({', '.join(given)}) here", start, end
        )
    return given


def _two(text: str, start: int, end: int) -> tuple[str, str]:
    """The parameters a function's head takes at ``start:end``: two (one names a curve)."""
    names = [name.strip() for name in text[start:end].split(",")]
    if len(names) == 2:
        return names[0], names[1]
    raise ParseError(
        f"the map takes one parameter ({names[0]}): the image is a curve, not a surface"
        if len(names) == 1
        else f"the map takes {len(names)} parameters ({', '.join(names)}): a surface is given by two",
        start,
        end,
    )


def _decimal_comma(text: str, start: int = 0) -> ParseError | None:
    """The error of a decimal comma (``1,5``) in ``text`` from ``start``, if there is one."""
    comma = _DECIMAL_COMMA.search(text, start)
    if comma is None:
        return None
    at = comma.start() + 1
    return ParseError(
        f"'{comma.group()}' reads as two components of a parametrization: write decimals with a point "
        f"({comma.group().replace(',', '.')})",
        at,
        at + 1,
    )


def _count_error(text: str, start: int, cuts: tuple[list[int], list[int]], count: int) -> ParseError:
    """Why the text is not three components, where it shows: a decimal comma (``1,5``), text
    around a triple ``(X, Y, Z)``, or the first separator of what is otherwise an equation."""
    comma = _decimal_comma(text, start)
    if comma is not None:
        return comma
    if not cuts[0] and len(cuts[1]) == 2:
        around = _around_triple(text, start, cuts[1][0])
        if around is not None:
            return around
    words = f"a parametrization has three components (x = …, y = …, z = …), not {count}; an equation has no ',' or ';'"
    separators = cuts[0] or cuts[1]
    return ParseError(words, separators[0], separators[0] + 1) if separators else ParseError(words, 0, len(text))


def _around_triple(text: str, start: int, inner: int) -> ParseError | None:
    """The text before or after the parentheses of a triple ``(X, Y, Z)`` that holds ``inner``."""
    depth, opened = 0, -1
    for position in range(start, len(text)):
        character = text[position]
        if character in "({[":
            opened = position if depth == 0 else opened
            depth += 1
        elif character in ")}]":
            depth -= 1
            if depth == 0 and opened < inner < position:
                after = text[position + 1 :]
                if after.strip():
                    at = position + 1 + len(after) - len(after.lstrip())
                    return ParseError(
                        f"'{after.strip()[:12]}' follows the triple (X, Y, Z): a parametrization ends with its ')'",
                        at,
                        len(text.rstrip()),
                    )
                before = text[start:opened]
                if before.strip():
                    at = start + len(before) - len(before.lstrip())
                    return ParseError(
                        f"'{before.strip()[:12]}' comes before the triple (X, Y, Z): write it as '(X, Y, Z)'",
                        at,
                        opened,
                    )
                return None
    return None


def _structure(text: str, start: int) -> tuple[tuple[list[int], list[int]], tuple[int, int] | None]:
    """Where components end: the ``,`` and ``;`` at depth 0 (and the line breaks there that a
    label follows), and those at depth 1; and the span of one pair of parentheses around all of
    the rest, if there is one (a triple ``(X, Y, Z)`` when it holds cuts). The comma of a
    ``pow(a, n)`` is none."""
    depth = 0
    cuts: tuple[list[int], list[int]] = ([], [])
    pairs: list[tuple[int, int]] = []
    opened: list[int] = []
    first = last = -1
    after_separator = after_pow = False
    inside_pow: list[bool] = []  # for each parenthesis open, whether it is a pow's
    for match in syntax.TOKEN.finditer(text, start):
        kind, word, position = match.lastgroup, match.group(), match.start()
        if kind == "space":
            if "\n" in word and depth == 0 and first >= 0 and not after_separator and _LABEL.match(text, match.end()):
                cuts[0].append(position + word.index("\n"))
            continue
        first = position if first < 0 else first
        last = position
        after_separator = kind == "bad" and word in ",;" and not (inside_pow and inside_pow[-1])
        if kind == "op" and word in "({[":
            if depth == 0:
                opened.append(position)
            depth += 1
            inside_pow.append(after_pow)
        elif kind == "op" and word in ")}]":
            depth -= 1
            if depth < 0:
                raise ParseError("unmatched ')'", position, position + 1)
            inside_pow.pop()
            if depth == 0 and opened:
                pairs.append((opened.pop(), position))
        elif after_separator and depth in (0, 1):
            cuts[depth].append(position)
        after_pow = kind == "name" and word == "pow"
    if depth > 0 and opened:
        raise ParseError("unmatched '('", opened[-1], opened[-1] + 1)
    return cuts, pairs[0] if len(pairs) == 1 and pairs[0] == (first, last) else None


def _between(start: int, cuts: Sequence[int], end: int) -> list[tuple[int, int]]:
    bounds = [start, *[c for c in cuts if start <= c < end], end]
    return [(bounds[i] + (i > 0), bounds[i + 1]) for i in range(len(bounds) - 1)]


def _nonempty(text: str, start: int, end: int, name: str) -> tuple[int, int]:
    if not text[start:end].strip():
        raise ParseError(f"the component {name} is empty", start, max(end, start + 1))
    return start, end


# --- the parameters ---------------------------------------------------------------------------


def _names(text: str, span: tuple[int, int]) -> list[tuple[str, int]]:
    """The names written in a component (its functions and LaTeX commands aside), with positions."""
    out = []
    for match in syntax.TOKEN.finditer(text, *span):
        if match.lastgroup == "name" and match.group() not in FUNCTIONS:
            out.append((match.group(), match.start()))
    return out


def _discover(text: str, spans: Sequence[tuple[int, int]]) -> tuple[str, str]:
    """The two parameters the components use, alphabetically (see the module docstring)."""
    words = [(w, p) for span in spans for w, p in _names(text, span)]
    _refuse_names(text, words)
    singles = {w for w, _ in words if len(w) == 1}
    runs = {w for w, _ in words if len(w) > 1}
    letters = singles.union(*map(set, runs))
    if len(letters) <= 2:
        found = letters
    else:
        found = singles | {w for w in runs if not set(w) <= singles}
    for word, position in words:
        called = text[position + len(word) : position + len(word) + 1] == "("
        if word in found and called and (len(word) > 1 or len(found) > 2):
            raise ParseError(
                f"'{word}(…)' is not allowed: the components must be rational functions of the parameters"
                " (the functions are pow and sqrt of a number, cos and sin of a parameter)",
                position,
                position + len(word),
            )
    names = sorted(found)
    if len(names) == 2:
        return names[0], names[1]
    if not names:
        raise ParseError("the components use no parameter: the map is constant, its image a point", 0, len(text))
    if len(names) == 1:
        raise ParseError(
            f"the components use one parameter ({names[0]}): the image is a curve, not a surface", 0, len(text)
        )
    if "I" in names and len(names) == 3:  # Maple's and Mathematica's imaginary unit
        at = next(p for w, p in words if w == "I")
        raise ParseError(
            "'I' is taken for a third parameter: a map with complex coefficients (Maple's and Mathematica's I) "
            "is not read, only real ones",
            at,
            at + 1,
        )
    raise ParseError(
        f"the components use {len(names)} parameters ({', '.join(names)}): a surface is given by two",
        *_last_new(words, found),
    )


def _last_new(words: Sequence[tuple[str, int]], names: set[str]) -> tuple[int, int]:
    """Where the name of ``names`` that comes last to be written first is written: the odd one
    out of ``x = s, y = t, z = s + r`` is ``r``, not the third in alphabetical order."""
    first: dict[str, int] = {}
    for word, position in words:
        if word in names:
            first.setdefault(word, position)
    word, position = max(first.items(), key=lambda item: item[1])
    return position, position + len(word)


def _refuse_characters(text: str, spans: Sequence[tuple[int, int]]) -> None:
    """A character that has no place in a component (``@``, a ``#`` glued to it) is the error,
    before any name is counted as a parameter (the comma of a ``pow`` aside)."""
    for span in spans:
        for match in syntax.TOKEN.finditer(text, *span):
            if match.lastgroup == "bad" and match.group() != ",":
                raise ParseError(f"unexpected character {match.group()!r}", match.start(), match.end())


def _refuse_names(text: str, words: Sequence[tuple[str, int]]) -> None:
    for word, position in words:
        end = position + len(word)
        if text[end : end + 1] and text[end] in "0123456789":  # not str.isdigit: t² is a power
            digits = len(text[end:]) - len(text[end:].lstrip("0123456789"))
            power = f"{word[-1]}^{text[end : end + digits]}"
            raise ParseError(
                f"'{text[position : end + digits]}': write {power} for a power; a parameter's name is letters only"
                " (s and t, u and v, …)",
                position,
                end + digits,
            )
        if set(word) & set(COORDINATES) and set(word) <= set(COORDINATES):
            comma = _decimal_comma(text)  # x^2 + 1,5*y^2 + 2,5*z^2 - 1: three "components"
            if comma is not None:
                raise comma
            raise ParseError(
                f"a component cannot use '{word}': x, y, z are the coordinates; name the parameters"
                " otherwise (s, t; u, v; …)",
                position,
                end,
            )
        if word in TRANSCENDENTAL:
            raise ParseError(
                f"'{word}' is not allowed: the components must be rational functions of the parameters"
                " (the functions are pow and sqrt of a number, cos and sin of a parameter)",
                position,
                end,
            )


def _check_names(text: str, spans: Sequence[tuple[int, int]], parameters: tuple[str, str]) -> None:
    """Every name is a parameter or a run of one-letter parameters (``st`` is ``s·t``)."""
    words = [(w, p) for span in spans for w, p in _names(text, span)]
    _refuse_names(text, words)
    if parameters[0] == parameters[1] or set(parameters) & set(COORDINATES):
        raise ParseError(
            f"the parameters must be two names other than x, y, z, not ({', '.join(parameters)})", 0, len(text)
        )
    for word, position in words:
        if word not in parameters and not set(word) <= set(parameters):
            raise ParseError(
                f"unknown name '{word}' (the parameters are {parameters[0]} and {parameters[1]};"
                " the functions are sqrt, pow, cos and sin)",
                position,
                position + len(word),
            )


# --- reading and evaluating one component --------------------------------------------------------


def _tree(text: str, span: tuple[int, int], parameters: tuple[str, str], checker: syntax.Evaluator) -> Node:
    """The syntax tree of one component, checked by the equation parser's first pass."""
    for match in syntax.TOKEN.finditer(text, *span):
        if match.lastgroup == "op" and match.group() == "=":
            raise ParseError("a component cannot hold '='", match.start(), match.end())
    tokens = syntax.token_stream(text, span, parameters)
    try:
        tree = syntax.Parser(text, tokens).equation()
    except RecursionError:
        raise ParseError("the expression is nested too deeply", *span) from None
    try:
        checker.check(tree)
    except RecursionError:
        raise ParseError("the expression is nested too deeply", *span) from None
    return tree


class _Fractions:
    """Pass 2 over a checked tree: its value ``N/D`` in ``K[s, t]``, reduced, ``D`` with leading
    coefficient 1; the degrees of ``N`` and ``D`` stay within :data:`MAX_DEGREE` and the work
    within :data:`MAX_WORK` coefficient products."""

    def __init__(self, ring: ParameterRing, checked: syntax.Evaluator, roots: dict[int, Any]) -> None:
        self.ring = ring
        self.checked = checked
        self.roots = roots
        self.work = 0

    def value(self, node: Node) -> tuple[Any, Any]:
        ring = self.ring
        match node:
            case Num():
                return ring.constant(node.value), ring.one
            case Var():
                return ring.gens[node.index], ring.one
            case Neg():
                n, d = self.value(node.arg)
                return -n, d
            case Sqrt():
                return self._surd(node), ring.one
            case syntax.Trig():
                return self._trig(node)
            case Sum():
                return self._sum(node)
            case Product():
                n, d = self.value(node.factors[0])
                for factor in node.factors[1:]:
                    if isinstance(factor, Reciprocal):
                        q, r = self.value(factor.arg)
                        if not q:
                            written = self.checked.check(factor.arg)[0] > 0  # a parameter is written in it
                            message = "the denominator is identically zero" if written else "division by zero"
                            raise ParseError(message, factor.start, factor.end)
                        n, d = self._reduced(node, n * r, d * q)
                    else:
                        q, r = self.value(factor)
                        self._charge(node, len(n) * len(q) + len(d) * len(r))
                        n, d = self._reduced(node, n * q, d * r)
                return n, d
            case Power():
                if node in self.checked._surds:
                    return self._surd(node), ring.one
                exponent = int(self.checked._exponents[node])
                n, d = self.value(node.base)
                if exponent < 0:  # 1/base^|exponent|
                    n, d, exponent = d, n, -exponent
                    if not d:
                        written = self.checked.check(node.base)[0] > 0  # a parameter is written in it
                        raise ParseError(
                            "the denominator is identically zero" if written else "division by zero",
                            node.start,
                            node.end,
                        )
                result = ring.one, ring.one
                for _ in range(exponent):
                    self._charge(node, len(result[0]) * len(n) + len(result[1]) * len(d))
                    result = self._reduced(node, result[0] * n, result[1] * d)
                return result
        raise TypeError(node)

    def _trig(self, node: syntax.Trig) -> tuple[Any, Any]:
        """``cos(k·u)`` or ``sin(k·u)`` in ``t = tan(u/2)`` (the ring's generator for ``u``): the
        real or imaginary part of ``(1 − t² + 2i·t)^k``, over ``(1 + t²)^k``."""
        ring = self.ring
        t = ring.gens[node.index]
        one = ring.one
        real, imaginary = one, one - one  # (1 − t² + 2i·t)^0
        for _ in range(node.multiple):
            real, imaginary = real * (one - t * t) - imaginary * 2 * t, real * 2 * t + imaginary * (one - t * t)
        denominator = (one + t * t) ** node.multiple
        return self._reduced(node, real if node.function == "cos" else imaginary, denominator)

    def _surd(self, node: Node) -> Any:
        c, m = self.checked._surds[node]
        value = self.ring.constant(c)
        return value * self.ring.constant(self.roots[m]) if m > 1 else value

    def _sum(self, node: Sum) -> tuple[Any, Any]:
        """Terms over the same denominator are added first (a pasted polynomial has only ``1``)."""
        groups: list[tuple[Any, Any]] = []
        for term in node.terms:
            n, d = self.value(term)
            for i, (total, denominator) in enumerate(groups):
                if denominator == d:
                    groups[i] = (total + n, denominator)
                    break
            else:
                groups.append((n, d))
        n, d = groups[0]
        for m, e in groups[1:]:
            self._charge(node, len(n) * len(e) + len(m) * len(d))
            n, d = self._reduced(node, n * e + m * d, d * e)
        return self._reduced(node, n, d)

    def _reduced(self, node: Node, n: Any, d: Any) -> tuple[Any, Any]:
        ring = self.ring
        if not ring.is_constant(d):
            g = ring.gcd(n, d)
            if not ring.is_constant(g):
                n, d = ring.exquo(n, g), ring.exquo(d, g)
        lead = ring.leading_coefficient(d)
        if lead != ring.K.one:
            inverse = ring.constant(ring.K.quo(ring.K.one, lead))
            n, d = n * inverse, d * inverse
        for part in (n, d):
            if ring.degree(part) > MAX_DEGREE:
                raise ParseError(
                    f"the degree is too high: this part has degree {ring.degree(part)} in the parameters,"
                    f" the limit is {MAX_DEGREE}",
                    node.start,
                    node.end,
                )
        return n, d

    def _charge(self, node: Node, products: int) -> None:
        self.work += products * (1 if self.ring.is_flint else 8)
        if self.work > MAX_WORK:
            raise ParseError(
                f"the expression is too large to expand (it needs more than {MAX_WORK:,} coefficient multiplications)",
                node.start,
                node.end,
            )


def _is_degenerate(surface: RationalMap) -> bool:
    """``P_s × P_t ≡ 0``: decided at a few points first (a nonzero value settles it), then as a
    polynomial identity."""
    for point in surface.sample_points(4):
        if any(surface.values(point)[2]):
            return False
    return not any(surface.normal)
