"""The surfaces an equation was typed from, to explain a *no*.

A blend is typed as a product of surfaces plus a small constant, ``g·h − c``: the result is
irreducible, so its factors say nothing, but each typed component may be a surface of
revolution, and the blend is one only when they share an axis. :func:`typed_components` finds
the non-constant factors of the products in the top-level sum of the typed text (with the
engine's own syntax tree, never evaluating anything) and recognises each one exactly.
"""

from __future__ import annotations

from dataclasses import dataclass

from sorgui.engine import SorguiError, analyze
from sorgui.engine.results import Recognition
from sorgui.engine.syntax import Neg, Node, Num, Power, Product, Sum, Var, syntax_tree

MAX_COMPONENTS = 4
"""More typed factors than this are not a blend one explains factor by factor."""


@dataclass(frozen=True)
class Component:
    """One typed factor: its text and its exact recognition."""

    text: str
    recognition: Recognition


def _has_variable(node: Node) -> bool:
    if isinstance(node, Var):
        return True
    if isinstance(node, Num):
        return False
    return any(_has_variable(child) for child in _children(node))


def _children(node: Node) -> tuple[Node, ...]:
    if isinstance(node, Sum):
        return node.terms
    if isinstance(node, Product):
        return node.factors
    return tuple(getattr(node, name) for name in ("arg", "base", "exponent") if hasattr(node, name))


def component_texts(text: str) -> tuple[str, ...]:
    """The texts of the non-constant factors of the products in the top-level sum of ``text``
    (empty unless there are at least two)."""
    try:
        tree = syntax_tree(text)
    except SorguiError:
        return ()
    terms = tree.terms if isinstance(tree, Sum) else (tree,)
    found: list[str] = []
    for term in terms:
        while isinstance(term, Neg):
            term = term.arg
        if isinstance(term, Product):
            surfaces = [f for f in term.factors if _is_surface(f)]
            if len(surfaces) >= 2:
                found += [text[f.start : f.end] for f in surfaces]
    return tuple(found) if 2 <= len(found) <= MAX_COMPONENTS else ()


def _is_surface(node: Node) -> bool:
    """A bracketed sum with a variable (or a power of one): a surface typed as a factor, not a
    monomial's variable such as the ``y^2`` of ``2y^2``."""
    if isinstance(node, Power):
        node = node.base
    return isinstance(node, Sum) and _has_variable(node)


def typed_components(text: str) -> tuple[Component, ...]:
    """Each typed component of ``text`` with its exact recognition (see the module docstring)."""
    out = []
    for part in component_texts(text):
        try:
            out.append(Component(part, analyze(part, recognition_only=True).recognition))
        except SorguiError:
            return ()
    return tuple(out)
