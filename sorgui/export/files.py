"""Writing an :class:`~sorgui.engine.results.Analysis` to files, in the format the suffix names.

:data:`~sorgui.export.formats.FORMATS` lists every format: reports (JSON, text, Markdown, HTML), formula files (LaTeX,
Maple, Mathematica, Python), meshes (STL, OBJ, PLY, VTP; ``NAME.patch.stl`` is the parametric
patch instead of the surface), CAD files (STEP, IGES, OCCT's BRep: the native surface, or with
``NAME.patch.step`` the parameterization's patch, :mod:`sorgui.cad`) and a PNG picture.
The format follows the file's suffix, or the ``fmt`` argument (``"stl"``, ``".stl"`` or
``"patch.stl"``). Meshes, CAD files and pictures need the scene
(``sorgui.session.scene_data.SceneData``) the caller built; Markdown and HTML add a picture
when a scene is given and an off-screen renderer is available. Every file is written
atomically (:mod:`sorgui.export.atomic`): a failure raises ``OSError`` and leaves any old file
unchanged.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from sorgui.engine.patches import patch_stand_in
from sorgui.engine.results import Analysis
from sorgui.engine.vocabulary import no_surface
from sorgui.export.atomic import atomic_write_bytes, atomic_write_text
from sorgui.export.cas import latex_document, maple_file, mathematica_file
from sorgui.export.formats import Format, format_of, wants_patch
from sorgui.export.python_module import python_module
from sorgui.export.reports import html_report, markdown_report
from sorgui.export.text import json_report, text_report

PNG_SIZE = (1600, 1200)
"""The size of a PNG written from the command line (the window saves the viewport's own)."""


NEAREST_PATCH = "the patch of a map of the nearest exact surface of revolution (rounded input: not the typed surface's)"
"""What a mesh file of rounded input's patch holds, said when it is written."""

TEXT_WRITERS: dict[str, Callable[[Analysis], str]] = {
    ".json": json_report,
    ".txt": text_report,
    ".tex": latex_document,
    ".mpl": maple_file,
    ".m": mathematica_file,
    ".py": python_module,
}


def export_file(
    analysis: Analysis,
    path: str | Path,
    fmt: str | None = None,
    scene: Any = None,
    units: str = "mm",
    tolerance: float | None = None,
    picture: bytes | None = None,
    cap: bool = False,
) -> tuple[Path, str]:
    """:func:`export_analysis`, and what a CAD file holds in words (``""`` for the other formats):
    its route, its faces and a fitted profile's measured deviation. ``cap``: a CAD file's part
    closed by the region into the solid ``f ≤ 0``."""
    path = Path(path)
    form = format_of(path, fmt)
    _has_a_surface(analysis, form, wants_patch(path, fmt))
    if form.kind != "cad":
        written = export_analysis(analysis, path, fmt, scene=scene, picture=picture, units=units, tolerance=tolerance)
        nearest = form.kind == "mesh" and wants_patch(path, fmt) and _nearest_patch_words(analysis) is not None
        return written, NEAREST_PATCH if nearest else ""
    if scene is not None and not wants_patch(path, fmt) and scene.surface.is_empty:
        # nothing for Open CASCADE to cut: a sphere of radius 10^200 about a ball of radius 2 kept
        # its Boolean busy for minutes, one of radius 10^20 gave a file of no face
        why = (scene.notes[0] if scene.notes else "the surface has no real points inside the ball").rstrip(".")
        raise ValueError(f"{why[0].lower()}{why[1:]}")
    from sorgui.cad import cad_file, summary

    data, model = cad_file(analysis, scene, path.name, form.suffix, wants_patch(path, fmt), units, tolerance, cap)
    unitless = ""
    if form.suffix == ".brep" and units != "mm":  # Open CASCADE's own format: numbers, no unit
        words = UNIT_NAMES.get(units, units)
        unitless = (
            f"; a .brep file holds no unit: its lengths are {words} (--units {units}), which the file does not say"
        )
    return atomic_write_bytes(path, data), summary(model, form.suffix) + unitless


UNIT_NAMES = {"cm": "centimetres", "m": "metres", "um": "micrometres", "in": "inches", "ft": "feet"}
"""The units of ``--units`` in words, for the note of a ``.brep`` file, which holds none."""


def _has_a_surface(analysis: Analysis, form: Format, patch: bool) -> None:
    """A mesh or a CAD file of the surface needs a real surface: ``ValueError`` saying what the
    real points are otherwise (a point, the axis), rather than that none were found in the ball."""
    locus = analysis.real_locus
    if form.kind in ("mesh", "cad") and not patch and locus is not None:
        reason = no_surface(locus.kind, locus.points, locus.circles, locus.axis_line)
        if reason is not None:
            raise ValueError(f"{reason}: there is no surface to write")


def _patch_words(analysis: Analysis) -> str:
    """What a mesh file's patch is of: the analysis's first map, or the nearest exact surface's
    for rounded input (:func:`~sorgui.engine.patches.patch_maps`)."""
    substitute = _nearest_patch_words(analysis)
    if substitute is None:
        return "parametric patch of the first real parameterization"
    return f"parametric patch of the nearest exact surface of revolution {substitute}"


def _nearest_patch_words(analysis: Analysis) -> str | None:
    """``g = 0 (rounded input; …)`` when a patch of ``analysis`` is the nearest exact surface's."""
    nearest = patch_stand_in(analysis)
    if nearest is None:
        return None
    within = "within" if nearest.within_rounding else "BEYOND"
    return (
        f"{nearest.polynomial} = 0 (rounded input; its coefficients {nearest.relative_distance:.2g} "
        f"(relative) from the typed ones, {within} their rounding)"
    )


def export_analysis(
    analysis: Analysis,
    path: str | Path,
    fmt: str | None = None,
    scene: Any = None,
    picture: bytes | None = None,
    units: str = "mm",
    tolerance: float | None = None,
) -> Path:
    """Write ``analysis`` to ``path`` in the format of its suffix (or ``fmt``); return ``path``.

    ``scene`` is needed for meshes and pictures (``ValueError`` without it) and gives Markdown
    and HTML their picture; ``picture`` (PNG bytes) is used instead of rendering one. A Markdown
    report's picture is written beside it as ``NAME.png``. A CAD file declares ``units`` and fits
    a profile with no exact form within ``tolerance`` (relative to the drawn ball's radius).
    """
    path = Path(path)
    form = format_of(path, fmt)
    _has_a_surface(analysis, form, wants_patch(path, fmt))
    if form.needs_scene and scene is None:
        raise ValueError(f"{form.name} needs the drawn scene of the analysis")
    if form.suffix in TEXT_WRITERS:
        return atomic_write_text(path, TEXT_WRITERS[form.suffix](analysis))
    patch = wants_patch(path, fmt)
    if form.kind == "mesh":
        from sorgui.export.meshes import write_mesh

        return write_mesh(scene, analysis.recognition.polynomial, path, form.suffix, patch, _patch_words(analysis))
    if form.kind == "cad":
        from sorgui.cad import cad_file

        return atomic_write_bytes(path, cad_file(analysis, scene, path.name, form.suffix, patch, units, tolerance)[0])
    if form.kind == "picture":
        from sorgui.export.picture import render_png

        return atomic_write_bytes(path, picture or render_png(scene, PNG_SIZE))
    if picture is None and scene is not None:
        picture = report_picture(scene)
    if form.suffix == ".html":
        return atomic_write_text(path, html_report(analysis, picture))
    image = None
    if picture is not None:
        image = path.with_suffix(".png")
        atomic_write_bytes(image, picture)
    return atomic_write_text(path, markdown_report(analysis, image.name if image else None))


def report_picture(scene: Any) -> bytes | None:
    """The report's PNG of ``scene``, or ``None`` when no off-screen renderer is available."""
    from sorgui.export.picture import render_png

    try:
        return render_png(scene)
    except RuntimeError:
        return None
