"""The render layer: plain-data meshes, curves and picking for the 3D viewport.

Workers call these functions with plain polynomial terms and get frozen dataclasses of
``numpy`` arrays back; only the ``to_polydata`` converters build ``pyvista`` objects, on the
GUI thread. Nothing here imports Qt or the engine (STYLE.md: engine → render → export → gui).
"""

from sorgui.render.geometry import ClipBox, ClipSphere
from sorgui.render.mesh import MeshData, mesh_to_polydata, surface_mesh
from sorgui.render.picking import AxisTest, PickInfo, normal_meets_axis, pick_info
from sorgui.render.scene import (
    PATCH_RANGE,
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

__all__ = [
    "PATCH_RANGE",
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
