"""STEP (AP242), IGES and BRep files of an Open CASCADE shape, every real at full precision.

Open CASCADE's writers keep 12 significant digits (STEP) and 9 decimals (IGES); here every real
is written with ``%.16E`` (17 significant digits, read back to the same double) through the
writers' own ``FloatWriter`` (zero suppression off: it truncates long numbers). Files are
written atomically (:mod:`sorgui.export.atomic`), and nothing is printed on standard output.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from OCP.BRepTools import BRepTools
from OCP.IFSelect import IFSelect_ReturnStatus
from OCP.IGESControl import IGESControl_Reader, IGESControl_Writer
from OCP.IGESData import IGESData_IGESWriter
from OCP.Interface import Interface_Static
from OCP.Message import Message, Message_Gravity
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
from OCP.StepData import StepData_StepWriter
from OCP.TopoDS import TopoDS_Shape

from sorgui.export.atomic import atomic_write_bytes

REAL_FORMAT = "%.16E"
"""17 significant digits: every double reads back to itself."""

UNIT_NAMES = {"mm": "MM", "cm": "CM", "m": "M", "um": "UM", "in": "IN", "ft": "FT"}
"""sorgui's unit names → Open CASCADE's."""


def _quiet() -> None:
    """Keep Open CASCADE's transfer statistics off standard output, which carries
    ``sorgui analyze --json``: its printers report failures only."""
    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)


_quiet()


@dataclass(frozen=True)
class CadHeader:
    """What a CAD file states about where it came from."""

    equation: str
    description: tuple[str, ...]
    version: str
    units: str = "mm"


def _full_precision(writer: Any) -> None:
    floats = writer.FloatWriter()
    floats.SetFormat(REAL_FORMAT)
    floats.SetZeroSuppress(False)


def write_step(shape: TopoDS_Shape, path: Path, header: CadHeader) -> Path:
    """An AP242 STEP file of ``shape``."""
    Interface_Static.SetCVal_s("write.step.schema", "AP242DIS")
    Interface_Static.SetCVal_s("write.step.unit", UNIT_NAMES[header.units])
    writer = STEPControl_Writer()
    writer.Transfer(shape, STEPControl_AsIs)
    step = StepData_StepWriter(writer.Model())
    _full_precision(step)
    step.SendModel(writer.WS().Protocol())
    out = io.BytesIO()
    step.Print(out)
    comments = "".join(f"/* {_ascii(line)} */\n" for line in header_lines(header))
    text = out.getvalue().decode("ascii", "replace").replace("HEADER;", comments + "HEADER;", 1)
    return atomic_write_bytes(path, text.encode("ascii"))


def write_iges(shape: TopoDS_Shape, path: Path, header: CadHeader) -> Path:
    """An IGES 5.3 file of ``shape`` (trimmed surfaces)."""
    writer = IGESControl_Writer(UNIT_NAMES[header.units], 0)
    writer.AddShape(shape)
    writer.ComputeModel()
    iges = IGESData_IGESWriter(writer.Model())
    _full_precision(iges)
    iges.SendModel(writer.Model().Protocol())
    out = io.BytesIO()
    iges.Print(out)
    return atomic_write_bytes(path, out.getvalue())


def write_brep(shape: TopoDS_Shape, path: Path, header: CadHeader) -> Path:
    """Open CASCADE's own BRep text (it keeps 17 digits; the format has no header)."""
    out = io.BytesIO()
    BRepTools.Write_s(shape, out)
    return atomic_write_bytes(path, out.getvalue())


def header_lines(header: CadHeader) -> list[str]:
    return [f"{header.equation} = 0", *header.description, f"sorgui {header.version}", f"units: {header.units}"]


def _ascii(text: str) -> str:
    return text.replace("*/", "* /").encode("ascii", "replace").decode("ascii")


def read_shape(path: Path) -> TopoDS_Shape:
    """Read a STEP, IGES or BRep file back with Open CASCADE's own readers."""
    suffix = Path(path).suffix.lower()
    if suffix in (".step", ".stp", ".iges", ".igs"):
        reader = STEPControl_Reader() if suffix in (".step", ".stp") else IGESControl_Reader()
        if reader.ReadFile(str(path)) != IFSelect_ReturnStatus.IFSelect_RetDone:
            raise ValueError(f"Open CASCADE cannot read {path}")
        reader.TransferRoots()
        return reader.OneShape()
    from OCP.BRep import BRep_Builder

    shape = TopoDS_Shape()
    if not BRepTools.Read_s(shape, str(path), BRep_Builder()):
        raise ValueError(f"Open CASCADE cannot read {path}")
    return shape


WRITERS = {".step": write_step, ".stp": write_step, ".iges": write_iges, ".igs": write_iges, ".brep": write_brep}
