"""The words for the kinds of surface, one list for every place that names them: the engine's
notes, the text and file reports, and the window.

A symmetry kind (the classification of the symmetry algebra, docs/math.md §2) has a noun
phrase ("a cylinder of revolution") and what makes it that kind ("rotations about its axis and
translations along it"); a canal kind (docs/math.md §9) has one phrase.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .stage_results import RealLocus

SYMMETRY_KINDS: dict[str, tuple[str, str]] = {
    "revolution": ("a surface of revolution", "about one axis"),
    "cylinder_of_revolution": ("a cylinder of revolution", "rotations about its axis and translations along it"),
    "sphere": ("a sphere", "every line through the centre is an axis"),
    "plane": ("a plane", "every line along the normal is an axis"),
    "extrusion": (
        "an extrusion (a cylindrical surface over a plane curve)",
        "invariant only under translations along one direction",
    ),
    "none": ("no continuous symmetry", "no rotation and no translation leaves it invariant"),
    "undecided": ("undecided", "the recognition did not finish within the time limit"),
}
"""Each symmetry kind: its noun phrase and what makes it that kind."""

UNDECIDED_NEARNESS = (
    "its decimals are exact rationals of which it is not one; whether it is one within the rounding "
    "of its digits was not decided (the analysis did not finish)"
)
"""The verdict of rounded input that is no surface of revolution exactly, stopped (cancelled, or
at its time limit) before the analysis of its rounding (docs/math.md §8) ended: not a plain "no"."""

CANAL_KINDS: dict[str, str] = {
    "pipe": "a pipe (all spheres of one radius)",
    "revolution": "a surface of revolution (the spheres' centres on a line)",
    "dupin": "a Dupin cyclide (canal in two ways)",
    "developable": "developable (a cone or a cylinder)",
}
"""Each canal kind in words."""


def kind_noun(kind: str | None) -> str:
    """The noun phrase of a symmetry kind (``"a sphere"``); the kind itself if unknown."""
    return SYMMETRY_KINDS.get(kind or "", (kind or "", ""))[0]


def kind_phrase(kind: str | None) -> str:
    """The noun phrase with what makes the kind: ``"a sphere (every line through the centre is
    an axis)"``, ``"a surface of revolution about one axis"``."""
    noun, reason = SYMMETRY_KINDS.get(kind or "", (kind or "", ""))
    if not reason:
        return noun
    return f"{noun} {reason}" if kind == "revolution" else f"{noun} ({reason})"


def canal_kind(kind: str) -> str:
    """A canal kind in words; the kind itself if unknown."""
    return CANAL_KINDS.get(kind, kind)


def no_surface(
    kind: str, points: int | None = None, circles: int | None = None, axis_line: bool | None = None
) -> str | None:
    """Why a surface whose real points are of ``kind`` (docs/math.md §3.4: ``empty``, ``points``,
    ``curve``) has no surface to write as a mesh or a CAD file, in words; ``None`` for a real
    surface (or one undecided)."""
    if kind == "empty":
        return "the surface has no real points"
    if kind == "points":
        many = "an isolated real point" if points == 1 else "isolated real points"
        return f"the surface's real points are {many}, not a surface"
    if kind == "curve":
        pieces = ["the axis"] if axis_line else []
        if circles:
            pieces.append("a circle about the axis" if circles == 1 else f"{circles} circles about the axis")
        return f"the surface's real points are a curve ({' and '.join(pieces) or 'a line'}), not a surface"
    return None


def no_surface_words(locus: RealLocus | None) -> str | None:
    """:func:`no_surface` of a real locus, said for a picture: no region can show such points
    (a region to give was suggested for ``x² + y² + z² + 1``). ``None`` when they may make a
    surface (or the locus is not known)."""
    if locus is None:
        return None
    why = no_surface(locus.kind, locus.points, locus.circles, locus.axis_line)
    return None if why is None else f"{why}: there is nothing to draw, in any region"
