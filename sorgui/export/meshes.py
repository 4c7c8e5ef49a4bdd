"""Mesh files for CAD and visualisation: STL (binary), OBJ, PLY and VTP, written with pyvista/VTK.

Two meshes can be written: the triangulated **surface** ``f = 0`` of the viewport's ball
(:class:`~sorgui.render.mesh.MeshData`), and the **patch** of the first real parameterization
(:class:`~sorgui.render.scene.PatchData`, its quads split into triangles). Each file states, where
the format has room for it, the units (those of ``x, y, z`` in the equation: sorgui attaches
none), the bounding box and the equation:

* STL (binary): the 80-byte header holds ``sorgui``, the units and the bounding box (the
  equation rarely fits in 80 bytes and is left out);
* OBJ: ``#`` comment lines before the data;
* PLY (binary): ``comment`` lines in the header;
* VTP: string arrays ``equation``, ``units``, ``bounds`` and ``mesh`` in the field data.

pyvista and VTK are imported when a mesh is written, so the command line starts without them.
Every file is written atomically (:mod:`sorgui.export.atomic`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from sorgui.export.atomic import atomic_path
from sorgui.export.formats import is_patch_path

if TYPE_CHECKING:
    import pyvista
    from vtkmodules.vtkIOCore import vtkWriter

    from sorgui.render import MeshData, PatchData

MESH_SUFFIXES = (".stl", ".obj", ".ply", ".vtp")
"""The mesh formats; ``name.patch.stl`` (and so on) writes the parametric patch instead of the surface."""

UNITS = "units of x, y, z as in the equation (sorgui attaches no unit)"


class Scene(Protocol):
    """What the mesh writers need of a scene (``sorgui.session.scene_data.SceneData`` has it)."""

    surface: MeshData
    patch: PatchData | None
    notes: tuple[str, ...]


@dataclass(frozen=True)
class MeshInfo:
    """The facts a mesh file states: the equation, which mesh it is, and its bounding box."""

    equation: str
    kind: str
    bounds: tuple[float, float, float, float, float, float]

    def bounds_text(self) -> str:
        b = self.bounds
        return f"x [{b[0]:.6g}, {b[1]:.6g}] y [{b[2]:.6g}, {b[3]:.6g}] z [{b[4]:.6g}, {b[5]:.6g}]"

    def lines(self) -> list[str]:
        """The header lines of the text formats."""
        return [
            f"sorgui: {self.kind}",
            f"equation: {self.equation} = 0",
            f"units: {UNITS}",
            f"bounding box: {self.bounds_text()}",
        ]


def mesh_polydata(scene: Scene, patch: bool) -> pyvista.PolyData:
    """The surface (or the patch, triangulated) of ``scene`` as a ``pyvista.PolyData``.

    Raises ``ValueError`` when that mesh is empty (no real points drawn, or no real patch).
    """
    from sorgui.render import mesh_to_polydata

    if patch:
        if scene.patch is None:
            raise ValueError("there is no parametric patch to export (no real parameterization)")
        if scene.patch.is_empty:
            raise ValueError("there is no parametric patch to export: no map's patch has a point inside the drawn ball")
        triangles: pyvista.PolyData = scene.patch.to_polydata().triangulate()
        return triangles
    if scene.surface.is_empty:
        why = scene.notes[0] if scene.notes else "The surface has no real points in the drawn ball."
        raise ValueError(f"there is no mesh to export: {why[0].lower()}{why[1:].rstrip('.')}")
    poly = mesh_to_polydata(scene.surface)
    return poly


def write_mesh(
    scene: Scene,
    equation: str,
    path: str | Path,
    fmt: str | None = None,
    patch: bool | None = None,
    patch_words: str = "parametric patch of the first real parameterization",
) -> Path:
    """Write the surface (or the patch) of ``scene`` to ``path``.

    ``fmt`` is one of :data:`MESH_SUFFIXES` (default: the suffix of ``path``); ``patch`` chooses
    the parametric patch (default: whether the name ends in ``.patch.<suffix>``), described in
    the header as ``patch_words``.
    """
    path = Path(path)
    suffix = (fmt or path.suffix).lower()
    if suffix not in MESH_SUFFIXES:
        raise ValueError(f"unknown mesh format {suffix!r}; use one of {', '.join(MESH_SUFFIXES)}")
    patch = is_patch_path(path) if patch is None else patch
    if not patch and not equation:
        raise ValueError(
            f"the implicit equation of this parametrization is not known, so there is no mesh of f = 0;"
            f" write {path.stem}.patch{suffix} for the given map's patch"
        )
    poly = mesh_polydata(scene, patch)
    kind = patch_words if patch else "triangulated surface f = 0 inside the drawn ball"
    xmin, xmax, ymin, ymax, zmin, zmax = (float(v) for v in poly.bounds)
    info = MeshInfo(equation, kind, (xmin, xmax, ymin, ymax, zmin, zmax))
    writer = {".stl": _write_stl, ".obj": _write_obj, ".ply": _write_ply, ".vtp": _write_vtp}[suffix]
    with atomic_path(path) as temporary:
        writer(poly, info, temporary)
    return path


def _write_stl(poly: pyvista.PolyData, info: MeshInfo, path: Path) -> None:
    from vtkmodules.vtkIOGeometry import vtkSTLWriter

    b = info.bounds
    header = (
        f"sorgui {_stl_kind(info.kind)}; input units; "
        f"bbox {b[0]:.4g} {b[1]:.4g} {b[2]:.4g} {b[3]:.4g} {b[4]:.4g} {b[5]:.4g}"
    )
    writer = vtkSTLWriter()
    writer.SetInputData(poly)
    writer.SetFileName(str(path))
    writer.SetFileTypeToBinary()
    writer.SetHeader(header[:80])
    _run(writer, path)


def _stl_kind(kind: str) -> str:
    """The few words of an STL header (80 bytes in all) for a mesh of ``kind``."""
    if "nearest" in kind:
        return "nearest exact SOR's patch"
    return "parametric patch" if "patch" in kind else "f=0 surface"  # a typed map's f may be unknown


def _write_obj(poly: pyvista.PolyData, info: MeshInfo, path: Path) -> None:
    plain = poly.copy()
    plain.point_data.clear()  # positions and faces only: what CAD programs read
    plain.save(str(path))
    body = path.read_bytes()
    comments = "".join(f"# {line}\n" for line in info.lines()).encode("utf-8")
    path.write_bytes(comments + body)


def _write_ply(poly: pyvista.PolyData, info: MeshInfo, path: Path) -> None:
    from vtkmodules.vtkIOPLY import vtkPLYWriter

    writer = vtkPLYWriter()
    writer.SetInputData(poly)
    writer.SetFileName(str(path))
    writer.SetFileTypeToBinary()
    for line in info.lines():
        writer.AddComment(line.replace("\n", " "))
    _run(writer, path)


def _write_vtp(poly: pyvista.PolyData, info: MeshInfo, path: Path) -> None:
    out = poly.copy()
    out.field_data["equation"] = [info.equation]
    out.field_data["units"] = [UNITS]
    out.field_data["bounds"] = [info.bounds_text()]
    out.field_data["mesh"] = [info.kind]
    out.save(str(path))


def _run(writer: vtkWriter, path: Path) -> None:
    """Run a VTK writer; VTK reports failures through an error code, not an exception."""
    ok = writer.Write()
    if not ok or writer.GetErrorCode():
        raise OSError(f"VTK could not write {path}")
