"""CAD files of an analysis: STEP (AP242), IGES and OCCT's BRep, made with Open CASCADE.

Every use of Open CASCADE is in this package (its modules import ``OCP``; the rest of sorgui
speaks its own types): the export layer (:mod:`sorgui.export.files`) writes the bytes made here.

Each kind sorgui recognises is written as the native surface a CAD kernel uses (docs/math.md
§11): an analytic plane, sphere, cylinder, cone or torus where it is one, otherwise a
``SURFACE_OF_REVOLUTION`` about the exact axis whose profile is the exact rational B-spline of
a verified parameterization, or a B-spline fitted within a stated tolerance, measured both
ways; a cylinder over a curve as the linear extrusion of its exact base curve, a cone over a
curve ruled through its apex, a canal surface swept through its characteristic circles; rounded
input as the nearest exact surface's part. The faces are sewn, closed shells made solids,
checked (:mod:`.sewing`). ``NAME.patch.step`` (and ``.iges``, ``.brep``) writes the first
verified real parameterization as rational Bézier patches instead. Open CASCADE (the
``sorgui[cad]`` extra, ``cadquery-ocp-novtk``) is imported only here, when such a file is
written; without it :class:`CadUnavailable` says how to get it. Importing the package loads
none of its modules: reading a part (:mod:`.reading`, :mod:`.recognition`) needs neither sympy
nor the render layer, which the writers of an analysis (:mod:`.geometry`, :mod:`.model`) import.
"""

from __future__ import annotations

import weakref
from dataclasses import replace
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from sorgui.engine.results import Analysis

    from .model import CadModel, Scene

CAD_SUFFIXES = (".step", ".stp", ".iges", ".igs", ".brep")
"""The CAD formats; ``NAME.patch.step`` (and so on) writes the parameterization's patch."""

UNITS = ("mm", "cm", "m", "um", "in", "ft")
"""The length units a CAD file can declare (the numbers are written as they are, unscaled)."""

INSTALL_HINT = "STEP, IGES and BRep files need Open CASCADE: pip install cadquery-ocp-novtk (the sorgui[cad] extra)"


class CadUnavailable(ValueError):
    """Open CASCADE's Python bindings are not installed (a ValueError: the export cannot be done)."""


__all__ = [
    "CAD_SUFFIXES",
    "INSTALL_HINT",
    "UNITS",
    "CadUnavailable",
    "cad_file",
    "cad_model",
    "summary",
]


_BUILT: weakref.WeakKeyDictionary[Any, dict[tuple[int, bool, float | None, bool], tuple[Analysis, Any]]] = (
    weakref.WeakKeyDictionary()
)
"""The models built for each scene (while it lives), by analysis and options: a STEP, an IGES
and a BRep file of one analysis share one model (building a degree-12 part takes seconds)."""


def cad_model(
    analysis: Analysis, scene: Scene, patch: bool = False, tolerance: float | None = None, cap: bool = False
) -> CadModel:
    """The part a CAD file of ``analysis`` holds (``patch``: the parameterization's patch;
    ``cap``: the part capped by the region into a solid), built once per scene, analysis and
    options (a failure too: it is said again)."""
    try:
        from .model import patch_model, surface_model
    except ImportError as exc:
        raise CadUnavailable(INSTALL_HINT) from exc
    from .geometry import CadGeometryError  # loaded with the model (sympy, the render layer)

    built = _BUILT.setdefault(scene, {})
    key = (id(analysis), patch, tolerance, cap)
    if key not in built or built[key][0] is not analysis:
        try:
            made: Any = patch_model(analysis, scene) if patch else surface_model(analysis, scene, tolerance, cap)
        except CadGeometryError as exc:
            made = exc
        built[key] = (analysis, made)
    result = built[key][1]
    if isinstance(result, CadGeometryError):
        raise CadGeometryError(str(result))
    model: CadModel = result
    return model


def cad_file(
    analysis: Analysis,
    scene: Scene,
    name: str,
    suffix: str,
    patch: bool = False,
    units: str = "mm",
    tolerance: float | None = None,
    cap: bool = False,
) -> tuple[bytes, CadModel]:
    """The bytes of the CAD file ``name`` of ``analysis`` (format ``suffix``; ``patch``: the
    parameterization's patch), and the faces it holds (for :func:`summary`)."""
    from sorgui import __version__

    model = cad_model(analysis, scene, patch, tolerance, cap)
    from .writers import CadHeader, write_cad

    header = CadHeader(analysis.recognition.polynomial, model.description, __version__, name, units, model.precision)
    data, note = write_cad(suffix, model.shape, header)
    return data, replace(model, file_note=note)


ROUTES = {
    "analytic": "an analytic surface",
    "exact": "a surface of revolution of the exact rational profile",
    "fitted": "a surface of revolution of a fitted profile",
    "patch": "rational B-spline patches of the parameterization",
    "extrusion": "a cylinder over a curve: the linear extrusion of its exact base curve",
    "ruled": "a cone over a curve: ruled through its apex over its exact base curve",
    "canal": "a canal surface swept through its characteristic circles",
}
"""What each route of :class:`~.model.CadModel` writes, in words."""


def summary(model: CadModel, suffix: str = ".step") -> str:
    """What a CAD file holds, in one line: the route, the faces (and solids) and a fit's measured
    deviation. An IGES file (``suffix``) holds the trimmed faces only, not their shells and solids
    (entity 144, which every reader takes)."""
    faces = f"{model.faces} face{'s' if model.faces != 1 else ''}"
    if suffix.lower() in (".igs", ".iges"):
        faces += " (trimmed surfaces: IGES holds no solid; STEP and BRep do)" if model.solids else ""
    elif model.solids:
        faces += f" in {model.solids} solid{'s' if model.solids != 1 else ''}"
    words = f"{ROUTES[model.route]}, {faces}"
    if model.file_note:
        words += f" ({model.file_note})"
    if model.deviation is not None and model.tolerance is not None:
        verdict = "within" if model.deviation <= model.tolerance else "ABOVE"
        words += f"; measured deviation {model.deviation:.2g} ({verdict} the tolerance {model.tolerance:.2g})"
    if model.typed_deviation is not None:
        words += f"; the nearest exact surface's part, {model.typed_deviation:.2g} from the typed surface"
        if model.beyond_rounding:
            words += " (BEYOND the input's rounding: no simple exact surface was found within it)"
    return words
