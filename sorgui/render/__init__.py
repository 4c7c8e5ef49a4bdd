"""The render layer: plain-data meshes, curves and picking for the 3D viewport.

Workers call these functions with plain polynomial terms and get frozen dataclasses of
``numpy`` arrays back; only the ``to_polydata`` converters build ``pyvista`` objects, on the
GUI thread. Nothing here imports Qt or the engine (STYLE.md: engine → render → export → gui).

The names below are loaded on first use (PEP 562): importing a light module of the layer
(:mod:`sorgui.render.geometry`, :mod:`sorgui.render.canal_touch`) does not import VTK, which
:mod:`sorgui.render.mesh` and :mod:`sorgui.render.scene` need, so that the window opens before
VTK is loaded (docs/benchmarks.md, "The window beside the command line").
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sorgui.render.geometry import ClipBox, ClipSphere
    from sorgui.render.mesh import MeshData, mesh_to_polydata, surface_mesh
    from sorgui.render.picking import AxisTest, PickInfo, normal_meets_axis, pick_info
    from sorgui.render.scene import (
        PATCH_RANGE,
        PATCH_RANGES,
        LineData,
        MarkerData,
        PatchData,
        axis_line,
        latitude_circle,
        normal_line,
        parametric_patch,
        profile_curve,
        sphere_center_marker,
        to_polydata,
    )

_MODULES = {
    "geometry": ("ClipBox", "ClipSphere"),
    "mesh": ("MeshData", "mesh_to_polydata", "surface_mesh"),
    "picking": ("AxisTest", "PickInfo", "normal_meets_axis", "pick_info"),
    "scene": (
        "PATCH_RANGE",
        "PATCH_RANGES",
        "LineData",
        "MarkerData",
        "PatchData",
        "axis_line",
        "latitude_circle",
        "normal_line",
        "parametric_patch",
        "profile_curve",
        "sphere_center_marker",
        "to_polydata",
    ),
}
"""The modules of the layer and the public names each defines (those of :data:`__all__`)."""

_MODULE_OF = {name: module for module, names in _MODULES.items() for name in names}

__all__ = [
    "PATCH_RANGE",
    "PATCH_RANGES",
    "AxisTest",
    "ClipBox",
    "ClipSphere",
    "LineData",
    "MarkerData",
    "MeshData",
    "PatchData",
    "PickInfo",
    "axis_line",
    "latitude_circle",
    "mesh_to_polydata",
    "normal_line",
    "normal_meets_axis",
    "parametric_patch",
    "pick_info",
    "profile_curve",
    "sphere_center_marker",
    "surface_mesh",
    "to_polydata",
]


def __getattr__(name: str) -> object:
    """The public ``name``, imported from its module on first use."""
    if name not in _MODULE_OF:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{_MODULE_OF[name]}"), name)
    globals()[name] = value
    return value
