"""The results in words: the verdict, the near case of rounded input, why a surface is not one
of revolution, and the tooltips of the results pane.

Only strings are built here, from the engine's result objects (no Qt, no mathematics): the
results pane and the Help menu show them. The terms are those of ``docs/math.md`` (the symmetry
algebra ``L``, the profile ``P``, Table 1 of Vršek & Lávička).
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from sorgui.engine.results import Analysis, Approximation, Canal, Conical, Recognition
from sorgui.engine.stage_results import CanalFamily
from sorgui.engine.vocabulary import UNDECIDED_NEARNESS, canal_kind, kind_noun, kind_phrase
from sorgui.export.text import float_text, unit_text
from sorgui.session.components import Component
from sorgui.session.model import STAGE_TITLES

CAPTION_TIPS = {
    "f(x, y, z)": "The equation as sorgui read it (exact, expanded): the surface X is f = 0",
    "point c": "A point of the axis with coordinates in the field K of the input",
    "direction a": "A direction vector of the axis (not normalised: it stays exact)",
    "line": "The axis as the line c + t·a",
    "Plücker (a : c × a)": "Plücker coordinates of the axis: the same for every choice of c and a",
    "p(x, y) = 0": "The profile curve: x along the axis, y the distance to it (docs/math.md §3)",
    "P²: y² → y": "The profile with y² replaced by y: the curve P² whose genus decides Table 1",
    "p̃(s, r) = f(c + s·a + r·u)": "The profile in the K-rational frame (c, a, u), exact",
    "frame": "The frame of the profile: c on the axis, a along it, u perpendicular to it",
    "checks": "Exact checks of the profile: evenness in r and f = p(x, √(y² + z²)) in the axis frame",
    "status": "Whether the rationality analysis ran, and if not, why",
    "genus(P)": "The geometric genus of the profile curve P (Singular); 'reducible' for a reducible P",
    "genus(P²)": "The geometric genus of P²; genus 0 means X is rational over ℂ (Table 1)",
    "X rational over ℂ": "Whether X has a rational parameterization with complex coefficients",
    "X unirational over ℝ": "Whether a real rational map covers X (not necessarily one-to-one)",
    "X rational over ℝ": "Whether X has a real rational parameterization that is one-to-one almost everywhere",
    "P² parameterized by": "A rational parameterization (φ, ρ) of the curve P²",
    "tubular surface T": "The tubular surface T of the paper's Section 3, through which X is parameterized",
    "h = r̂·q̂": "The polynomial whose real roots decide the real rationality (paper, Section 3)",
    "real roots of h": "Number of real roots of h: with none, X is rational over ℝ",
    "τ: X ⇢ T": "The birational map from X to the tubular surface T",
    "x": "x-coordinate of the parameterization",
    "y": "y-coordinate",
    "z": "z-coordinate",
    "tolerance": "The relative tolerance in force: from the digits printed in the input, or --tolerance",
    "near": "Whether f is, within the rounding of its coefficients, a surface of revolution",
    "relative distance": "‖f − f̄‖₂ / ‖f‖₂ over the coefficients, f̄ the nearest rotation-invariant polynomial",
    "in units of rounding": "The same distance measured in the rounding of the input: 1 or less is within it",
    "singular values": "The smallest singular values of the floating-point symmetry system (★), relative",
    "approximate axis": "The refined floating-point axis (length units of the input)",
    "nearest exact surface": "The exact surface of revolution the rounded input was meant to be",
    "max deviation": "The largest distance between the two zero sets inside the drawn ball (length units)",
    "axis": "The axis of this factor (a line with coordinates in K)",
    "centre": "The centre of this factor, a sphere: every line through it is an axis",
    "direction": "The direction of translation of an extrusion or a cylinder",
    "normal": "The normal of the plane: every line along it is an axis",
    "sum of the stages": (
        "The stages' times added up; the wall time under the 3D view (“Done in …”) also counts "
        "starting the worker and showing the results"
    ),
    "wall time": "From pressing Analyze to the last result, as the status line says “Done in …”",
    "in unit axes": "The base curve in lengths: the frame's U and W are exact but not of length 1",
    "section": "What the section across the direction is: its kind, centre and semi-axes (decimals)",
    "relative to the apex": "How the chart's curve makes the cone: the lines through the apex and its points",
    "opening": "The half-angle of a circular cone at its apex",
    "exactly": "The exact answer for the equation as typed: its decimals read as exact rationals",
    "note": "A remark of the engine on this result",
    "canal": "Whether X is the envelope of a one-parameter family of spheres (docs/math.md §9)",
    "certificate": "The exact proof that X is the envelope of the sphere family",
    "witness": "A line on which the canal condition fails exactly: the proof that X is not canal",
    "spine": "The curve m(t) of the spheres' centres: its degree, whether it is planar, its genus",
    "radius": "Whether the spheres all have the same radius (a pipe)",
    "m(t)": "A rational parameterization of the spine (the spheres' centres)",
    "r²(t)": "The squared radius of the sphere centred at m(t)",
}


def canal_verdict(canal: Canal) -> str:
    """The canal verdict in one sentence: canal or not, and of which kinds."""
    if canal.is_canal is None:
        return f"undecided ({canal.status})"
    if not canal.is_canal:
        return "not a canal surface: not the envelope of any one-parameter family of spheres"
    kinds = ", ".join(canal_kind(k) for k in canal.kinds)
    return "a canal surface, the envelope of a one-parameter family of spheres" + (f": {kinds}" if kinds else "")


def canal_evidence(canal: Canal) -> tuple[str, str] | None:
    """``(caption, sentence)``: the certificate of a *canal*, or the witness line of a *not canal*."""
    if canal.certificate is not None:
        check = "verified" if canal.certificate.verified else "NOT verified"
        return "certificate", f"{canal.certificate.statement} ({check})"
    witness = canal.witness
    if witness is not None:
        line = ""
        if witness.point is not None and witness.direction is not None:
            line = f" on the line ({', '.join(witness.point)}) + τ·({', '.join(witness.direction)})"
        return "witness", f"{witness.statement}{line}"
    return None


def spine_words(family: CanalFamily) -> str:
    """The spine of one sphere family in words: degree, planarity, genus."""
    if family.on_line:
        shape = "a line"
    else:
        shape = f"a {'plane' if family.planar else 'space'} curve of degree {family.degree}"
    genus = "genus undecided" if family.genus is None else f"genus {family.genus}"
    rational = " (rational)" if family.genus == 0 else ""
    return f"{shape}, {genus}{rational}"


def radius_words(family: CanalFamily) -> str:
    """Whether the radius of the family's spheres is constant."""
    if family.pipe:
        value = f": r² = {family.radius_squared} (radius squared)" if family.radius_squared else ""
        return "constant (a pipe)" + value
    return "varies along the spine"


def invalid_heading(message: str) -> str:
    """The heading of a refused equation: what is wrong with it, in a few words (a degree above
    the limit is a polynomial, just too large; an empty editor holds no equation at all)."""
    if "degree is too high" in message:
        return "The degree is above sorgui's limit"
    if "too long" in message or "more than" in message and "digits" in message:
        return "The equation is too large"
    if "is empty" in message or "editor is empty" in message:
        return "No equation"
    if re.search(r"(?<![-\w])constant", message) or "no variables" in message:  # not "non-constant"
        return "No surface: the equation is constant"
    return "Not a polynomial in x, y, z"


INVALID_NOTICE = "<b>Not analysed.</b> Correct the equation, then press Analyze (Ctrl+Return)."
"""The run panel's notice of a refused equation: what to do, not the reason again (the editor's
line and the results pane's banner say that, one above it and one below)."""


def no_surface_caption(message: str) -> str:
    """What the 3D view's header says of a refused equation: its real reason, in a few words."""
    heading = invalid_heading(message)
    if heading == "Not a polynomial in x, y, z":
        return "No surface: the equation is not a polynomial in x, y, z"
    if heading == "No equation":
        return "No surface: there is no equation"
    if heading.startswith("No surface"):
        return heading
    return "No surface: " + heading[0].lower() + heading[1:]


def caption_tip(caption: str) -> str:
    """The tooltip of a caption of the results pane (a stage name in the timings gets its title)."""
    if caption in CAPTION_TIPS:
        return CAPTION_TIPS[caption]
    if caption in STAGE_TITLES:
        return f"Time taken by the stage “{STAGE_TITLES[caption]}”"
    if caption.startswith("family "):
        return "A one-parameter family of spheres whose envelope is X (a Dupin cyclide has two)"
    if caption.startswith("factor "):
        return "An irreducible factor of f over K (with its power), recognised on its own"
    return ""


def floats(values: tuple[float, ...] | None, digits: int = 6, tolerance: float | None = None) -> str:
    """A float vector for people: ``digits`` significant digits, rounding noise (below 1e-12, or
    the input's rounding ``tolerance``, of the largest entry or of 1) shown as 0."""
    if not values:
        return "–"
    return float_text(values, digits, tolerance)


LONG_NUMBER = re.compile(r"[0-9]{25,}")
"""A number too long to read in the window: one unbreakable line of 126 digits (the ``d`` of a
field ``QQ(√d)`` of a nearest surface on an irrational axis) widened the results pane beyond
the window."""


def short_numbers(text: str) -> str:
    """``text`` with each number of 25 digits or more shortened to its first and last digits and
    its length (``QQ(sqrt(4258300637…634111 [126 digits]))``), for the window's words; the
    formulas, their copy buttons and the exports keep every digit."""
    return LONG_NUMBER.sub(lambda m: f"{m.group()[:10]}…{m.group()[-6:]} [{len(m.group())} digits]", text)


LONG_WORD = re.compile(r"\S{25,}")
"""A run of text without a space long enough to widen the results pane beyond a narrow window."""
BREAK_AFTER = re.compile(r"([*/(,^])")


def breakable(text: str) -> str:
    """``text`` with a zero-width space after each ``*``, ``/``, ``(``, ``,`` and ``^`` of its
    long words (:data:`LONG_WORD`), where a line may break: a note holding a formula of
    20-digit numbers (``30303833264442169684*sqrt(82216202341731479742)*s``) was one unbreakable
    word, and the pane scrolled sideways in a window 800 pixels wide. The copies and exports are
    of the analysis, not of these words."""
    return LONG_WORD.sub(lambda m: BREAK_AFTER.sub("\\1\u200b", m.group()), text)


def near_words(approx: Approximation) -> str:
    """The near case in one sentence, as the issue's user expects it."""
    axis = approx.axis
    about = (
        f" about the line {floats(axis.point, tolerance=approx.tolerance)} + "
        f"t·{unit_text(axis.direction, 6, approx.tolerance)}"
        if axis is not None
        else ""
    )
    kind = "a surface of revolution" if approx.kind in (None, "revolution") else kind_noun(approx.kind)
    return f"not exactly, but within {approx.relative_distance:.2g} (relative) of {kind}{about}"


def tolerance_words(approx: Approximation) -> str:
    """The relative tolerance in force, or why there is none (numbers beyond floating point:
    ``1e400``)."""
    return "beyond floating point" if approx.tolerance is None else f"{approx.tolerance:.2g}"


def far_words(approx: Approximation) -> str:
    """Why rounded input is *not* near a surface of revolution: how far it is, or what it is
    near instead (an extrusion: its distance and residual are those of the extrusion)."""
    if approx.kind not in (None, "none", "revolution") and approx.relative_distance is not None:
        along = "" if approx.normal is None else f" along {unit_text(approx.normal, 6, approx.tolerance)}"
        residual = "" if approx.residual is None else f", {approx.residual:.3g} times the rounding of the input"
        return (
            f"not near one either, but within the rounding it is {kind_noun(approx.kind)}{along}: "
            f"{approx.relative_distance:.2g} away (relative){residual} (tolerance {tolerance_words(approx)})"
        )
    distance = "–" if approx.relative_distance is None else f"{approx.relative_distance:.2g}"
    residual = "" if approx.residual is None else f", {approx.residual:.3g} times the rounding of the input"
    return (
        f"not near one either: the nearest rotation-invariant polynomial is {distance} "
        f"away (relative){residual} (tolerance {tolerance_words(approx)})"
    )


def _over(conical: Conical) -> str:
    """`` over a curve of degree d, genus g (rational)``: the cone's or cylinder's class in brief."""
    base = conical.base_curve
    if base is None or base.reducible or base.genus is None:
        return ""
    rational = {True: "rational", False: "not rational", None: "rationality undecided"}[conical.rational]
    return f" over a curve of degree {base.degree}, genus {base.genus} ({rational})"


def verdict(analysis: Analysis, rounding_pending: bool = False, rounding_stopped: bool = False) -> tuple[str, str, str]:
    """``(title, detail, kind)`` of the verdict banner; ``kind`` is ``sor``, ``near``, ``not``
    or ``info`` (rounded input's exact *no*, while whether it is one within its rounding is
    ``rounding_pending``, or once its stage was ``rounding_stopped``: cancelled, cut short)."""
    rec = analysis.recognition
    approx = analysis.approximate
    if rounding_pending and not rec.is_sor and approx is None:
        return (
            "Not exactly a surface of revolution",
            "the equation's decimals are exact rationals of which it is not one; whether it is one "
            f"within the rounding of its digits is being decided · degree {rec.degree}",
            "info",
        )
    kind = kind_phrase(rec.symmetry)
    degree = f"degree {rec.degree}" if rec.polynomial else "degree unknown"  # a map's equation may not be found
    answer = analysis.verdict
    if rounding_stopped and answer == "not" and approx is None:
        answer = "not exactly"
    if answer == "undecided":
        return "Undecided within the time limit", f"{kind} · {degree} over {short_numbers(analysis.field)}", "info"
    if answer == "not exactly":
        return "Not exactly a surface of revolution", f"{UNDECIDED_NEARNESS} · {degree}", "info"
    detail = f"{kind} · {degree} over {short_numbers(analysis.field)} · dim L = {rec.symmetry_dimension}"
    conical = analysis.conical
    if conical is not None and conical.kind == "cone" and conical.apex is not None:
        detail += f" · a cone with apex ({', '.join(conical.apex)}){_over(conical)}"
    elif conical is not None and conical.kind == "cylinder" and conical.direction is not None:
        detail += f" · a cylinder along ({', '.join(conical.direction)}){_over(conical)}"
    elif conical is not None and conical.near_apex is not None:
        detail += f" · nearly a cone about {float_text(conical.near_apex, 4)}"
    elif conical is not None and conical.near_direction is not None:
        detail += f" · nearly a cylinder along {float_text(conical.near_direction, 4)}"
    canal = analysis.canal
    if not rec.is_sor and canal is not None and canal.is_canal:
        kinds = ", ".join(canal_kind(k) for k in canal.kinds if k != "revolution")
        detail += " · a canal surface" + (f": {kinds}" if kinds else "")
    if answer == "sor":
        return "Surface of revolution", detail, "sor"
    if answer == "near" and approx is not None:
        return "Nearly a surface of revolution", near_words(approx) + f" · {degree}", "near"
    if approx is not None:
        return "Not a surface of revolution", far_words(approx), "not"
    return "Not a surface of revolution", detail, "not"


def why_not(analysis: Analysis, components: Sequence[Component] = ()) -> list[str]:
    """Sentences that explain a *no*: the symmetry algebra, the symmetry there is, the factors,
    and the typed components of a blend (:mod:`sorgui.session.components`)."""
    rec = analysis.recognition
    if rec.is_sor or not rec.decided:
        return []
    lines = _symmetry_lines(analysis)
    if components:
        lines.append(f"It was typed from {len(components)} surfaces (the factors of its product):")
        for index, component in enumerate(components):
            lines.append(f"Component {index + 1}, {component.text.strip()}: {_factor_words(component.recognition)}.")
        sor = [c.recognition for c in components if c.recognition.is_sor]
        axes = {r.axis.plucker for r in sor if r.axis is not None}
        centres = [r.center for r in sor if r.center is not None]
        if len(axes) > 1 or (axes and centres):
            lines.append(
                "They have no axis in common (their axes are drawn in the 3D view), so the surface "
                "made from them is not one of revolution."
            )
    return lines


def _symmetry_lines(analysis: Analysis) -> list[str]:
    rec = analysis.recognition
    lines = [_dimension_sentence(rec)]
    if rec.symmetry == "extrusion" and rec.direction is not None:
        lines.append(
            f"It is an extrusion: invariant under the translations along ({', '.join(rec.direction)}), "
            "but under no rotation, so it has no axis of revolution."
        )
    elif rec.symmetry == "none":
        lines.append(
            "A surface of revolution is invariant under the rotations about its axis, a "
            "one-dimensional family of isometries; this surface has none, so no line is an axis."
        )
    factors = analysis.factors
    if len(factors) > 1:
        sor = [(i, f) for i, f in enumerate(factors) if f.recognition.is_sor]
        for index, factor in enumerate(factors):
            lines.append(f"Factor {index + 1}: {_factor_words(factor.recognition)}.")
        axes = {f.recognition.axis.plucker for _, f in sor if f.recognition.axis is not None}
        if len(axes) > 1:
            lines.append(
                "The factors are surfaces of revolution about different axes (drawn in the 3D "
                "view), so their union is not one."
            )
    return lines


def _dimension_sentence(rec: Recognition) -> str:
    dim = rec.symmetry_dimension
    if dim == 0:
        return (
            "The symmetry algebra L (the infinitesimal isometries ω × X + b that keep f = 0, docs/math.md §2) "
            "is zero: the surface has no continuous symmetry."
        )
    return (
        f"The symmetry algebra L (the infinitesimal isometries ω × X + b that keep f = 0, docs/math.md §2) "
        f"has dimension {dim}, but contains no rotation about a line."
    )


def _factor_words(rec: Recognition) -> str:
    words = kind_phrase(rec.symmetry)
    if rec.axis is not None:
        words += f", axis ({', '.join(rec.axis.point)}) + t·({', '.join(rec.axis.direction)})"
    if rec.center is not None:
        words += f", centre ({', '.join(rec.center)})"
    return words
