"""STEP (AP242), IGES and BRep files of an Open CASCADE shape, every real at full precision.

Open CASCADE's writers keep 12 significant digits (STEP) and 9 decimals (IGES); here every real
is written with ``%.16E`` (17 significant digits, read back to the same double) through the
writers' own ``FloatWriter`` (zero suppression off: it truncates long numbers). The equation,
the route and sorgui's version go where each format keeps such text: STEP's
``FILE_DESCRIPTION`` and ``FILE_NAME``, IGES's start and global sections. The writers return
the file's bytes (the export layer writes them atomically), and nothing is printed on standard
output.
"""

from __future__ import annotations

import io
import re
from collections.abc import Callable
from dataclasses import dataclass, replace
from itertools import accumulate
from pathlib import Path
from typing import Any

from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.BRepTools import BRepTools
from OCP.IFSelect import IFSelect_ReturnStatus
from OCP.IGESControl import IGESControl_Reader, IGESControl_Writer
from OCP.IGESData import IGESData_IGESWriter
from OCP.Interface import Interface_Static
from OCP.Message import Message, Message_Gravity
from OCP.OCP.collections import HArray1_TCollection_HAsciiString
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
from OCP.StepData import StepData_StepWriter
from OCP.TCollection import TCollection_HAsciiString
from OCP.TopoDS import TopoDS_Shape

REAL_FORMAT = "%.16E"
"""17 significant digits: every double reads back to itself."""

STEP_STRING = 256
"""The longest string of a STEP header's description list (ISO 10303-21's ``STRING(256)``)."""
IGES_START = 72
"""The characters of a line of IGES's start section (columns 1-72)."""

UNITS = {
    "mm": ("MM", 1.0),
    "cm": ("CM", 10.0),
    "m": ("M", 1000.0),
    "um": ("UM", 0.001),
    "in": ("INCH", 25.4),
    "ft": ("FT", 304.8),
}
"""sorgui's unit names → Open CASCADE's, and millimetres per unit. A file declares the unit and
keeps the numbers as they are: Open CASCADE is told that the shape is in that unit too, or it
would convert the numbers from millimetres."""


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
    name: str
    """The file's name (STEP's ``FILE_NAME``, IGES's global section); its stem names the product."""
    units: str = "mm"
    uncertainty: float = 1e-7
    """The precision of the part's edges and vertices: STEP's ``UNCERTAINTY_MEASURE_WITH_UNIT``."""


def _full_precision(writer: Any) -> None:
    floats = writer.FloatWriter()
    floats.SetFormat(REAL_FORMAT)
    floats.SetZeroSuppress(False)


def step_bytes(shape: TopoDS_Shape, header: CadHeader) -> bytes:
    """An AP242 STEP file of ``shape`` (:func:`step_file`, without what it says of the file)."""
    return step_file(shape, header)[0]


def step_file(shape: TopoDS_Shape, header: CadHeader) -> tuple[bytes, str]:
    """An AP242 STEP file of ``shape``, one product (a compound of shells or solids is not made
    an assembly), its uncertainty the part's precision; :func:`header_lines` are its
    ``FILE_DESCRIPTION``. With it, what the file holds beyond the part's route, in words (``""``
    when nothing).

    The file is read back and its area compared with the shape's: a face on a sphere, trimmed
    by one loop that bounds two regions of the sphere, was read back as the other region (a
    sphere times a plane on a turned axis, capped in a box: the volume 29.23 instead of 25.04),
    a valid file of the wrong solid. Such a shape is written again with its faces converted to
    B-splines (:data:`BSPLINE_NOTE`, said in the header too), which read back as written; one
    that still does not is refused (:class:`StepReadBackError`)."""
    data = _step(shape, header)
    if _reads_back(data, shape):
        return data, ""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_NurbsConvert

    converted = BRepBuilderAPI_NurbsConvert(shape, True).Shape()
    data = _step(converted, replace(header, description=(*header.description, BSPLINE_NOTE)))
    if _reads_back(data, converted):
        return data, BSPLINE_NOTE
    raise StepReadBackError(
        "Open CASCADE's STEP file of the part does not read back as the part (its area differs); "
        "write the part as .brep"
    )


BSPLINE_NOTE = "faces written as B-splines: the STEP file of the analytic faces did not read back as the part"
"""What a STEP file written again with B-spline faces says of itself, in its header and in the
line that reports it."""


def write_cad(suffix: str, shape: TopoDS_Shape, header: CadHeader) -> tuple[bytes, str]:
    """The bytes of ``shape`` in the CAD format of ``suffix``, and what the file holds beyond the
    part's route, in words (``""`` when nothing: only a STEP file may be written again)."""
    if suffix in (".step", ".stp"):
        return step_file(shape, header)
    return WRITERS[suffix](shape, header), ""


class StepReadBackError(ValueError):
    """A STEP file that Open CASCADE reads back as another shape than the one written (a
    ``ValueError``, as :class:`.geometry.CadGeometryError` is, without loading that module: the
    part route rewrites parts without sympy)."""


READ_BACK = 1e-3
"""The relative difference of area between a shape and its STEP file read back above which the
file is not the shape: Open CASCADE's areas of a B-spline face and of the same face read back
(its trimming curves made again) differ by up to about 1e-4; a face read back as the other
region of its sphere changed the part's area by 1 %."""


def _reads_back(data: bytes, shape: TopoDS_Shape) -> bool:
    """Whether the STEP ``data`` read back has the area of ``shape`` (within :data:`READ_BACK`)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    reader = STEPControl_Reader()
    if reader.ReadStream("part.step", io.BytesIO(data)) != IFSelect_ReturnStatus.IFSelect_RetDone:
        return False
    reader.TransferRoots()
    areas = []
    for part in (shape, reader.OneShape()):
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(part, props)
        areas.append(props.Mass())
    return bool(abs(areas[0] - areas[1]) <= READ_BACK * max(abs(areas[0]), 1e-300))


def _step(shape: TopoDS_Shape, header: CadHeader) -> bytes:
    """The STEP file of :func:`step_bytes`, as Open CASCADE writes it."""
    writer = STEPControl_Writer()
    name = UNITS[header.units][0]
    settings = {
        "write.step.schema": "AP242DIS",
        "write.step.assembly": "Off",
        "write.precision.mode": "User",
        "write.step.unit": name,
        "xstep.cascade.unit": name,
        "write.step.product.name": _step_text(Path(header.name).stem),
    }
    for key, value in settings.items():
        if not Interface_Static.SetCVal_s(key, value):
            raise RuntimeError(f"Open CASCADE refused {key} = {value}")
    Interface_Static.SetRVal_s("write.precision.val", header.uncertainty)
    writer.Transfer(shape, STEPControl_AsIs)
    made = APIHeaderSection_MakeHeader(writer.Model())
    lines = _step_strings(header)
    description = HArray1_TCollection_HAsciiString(1, len(lines))
    for number, line in enumerate(lines, 1):
        description.SetValue(number, TCollection_HAsciiString(line))
    made.SetDescription(description)
    made.SetName(TCollection_HAsciiString(_step_text(header.name)))
    made.SetOriginatingSystem(TCollection_HAsciiString(f"sorgui {header.version}"))
    made.SetAuthorValue(1, TCollection_HAsciiString(""))
    made.SetOrganizationValue(1, TCollection_HAsciiString(""))
    step = StepData_StepWriter(writer.Model())
    _full_precision(step)
    step.SendModel(writer.WS().Protocol())
    out = io.BytesIO()
    step.Print(out)
    return out.getvalue()


def iges_bytes(shape: TopoDS_Shape, header: CadHeader) -> bytes:
    """An IGES 5.3 file of ``shape`` (trimmed surfaces); :func:`header_lines` are its start section."""
    name, millimetres = UNITS[header.units]
    writer = IGESControl_Writer(name, 0)
    model = writer.Model()
    section = model.GlobalSection()
    section.SetCascadeUnit(millimetres)
    model.SetGlobalSection(section)
    writer.AddShape(shape)
    writer.ComputeModel()
    for line in header_lines(header):
        for piece in _pieces(_ascii(line), IGES_START):
            model.AddStartLine(piece)
    section = model.GlobalSection()
    section.SetSendName(TCollection_HAsciiString(_ascii(Path(header.name).stem)))
    section.SetFileName(TCollection_HAsciiString(_ascii(header.name)))
    section.SetSystemId(TCollection_HAsciiString(f"sorgui {header.version}"))
    model.SetGlobalSection(section)
    iges = IGESData_IGESWriter(model)
    _full_precision(iges)
    iges.SendModel(model.Protocol())
    out = io.BytesIO()
    iges.Print(out)
    return out.getvalue()


def brep_bytes(shape: TopoDS_Shape, header: CadHeader) -> bytes:
    """Open CASCADE's own BRep text (it keeps 17 digits; the format has no header)."""
    out = io.BytesIO()
    BRepTools.Write_s(shape, out)
    return out.getvalue()


def header_lines(header: CadHeader) -> list[str]:
    """The equation (none for a part sorgui rewrote), what the faces are, sorgui's version and the
    declared unit."""
    equation = [f"{header.equation} = 0"] if header.equation else []
    return [*equation, *header.description, f"sorgui {header.version}", f"units: {header.units}"]


def _step_strings(header: CadHeader) -> list[str]:
    """:func:`header_lines` cut into strings a STEP description list takes (long equations span
    several), each escaped (:func:`_step_text`) and at most :data:`STEP_STRING` long."""
    return [piece for line in header_lines(header) for piece in _pieces(_ascii(line), STEP_STRING, _step_text)]


def _pieces(line: str, width: int, encoded: Callable[[str], str] = str) -> list[str]:
    """``line`` cut into pieces of at most ``width`` characters once ``encoded``, which joined as
    they are give it back: each cut before a space (between an equation's terms, ``... + 3*x*y -``
    then `` z**2 ...``, or words), else after a ``*`` or ``/`` between the factors of a term, else
    (a number longer than a piece) where the piece is full. Cut anywhere, a reader that shows the
    pieces apart or joins them with a space saw ``z*`` and ``*2`` of a ``z**2``."""
    pieces = []
    while len(encoded(line[: width + 1])) > width:  # a character is at least one once encoded
        fits = sum(1 for length in accumulate(len(encoded(c)) for c in line[:width]) if length <= width)
        space = line.rfind(" ", 1, fits + 1)
        factors = [m.end() for m in FACTOR_SIGN.finditer(line, 0, fits + 1) if m.end() <= fits]
        cut = space if space > 0 else factors[-1] if factors else fits
        pieces.append(encoded(line[:cut]))
        line = line[cut:]
    return [*pieces, encoded(line)]


FACTOR_SIGN = re.compile(r"(?<![*/])[*/](?![*/])")
"""A multiplication or division sign between factors (not a power's ``**``)."""


def _step_text(text: str) -> str:
    """``text`` for a STEP string: printable ASCII, each backslash written ``\\X2\\005C\\X0\\``
    (U+005C in STEP's own escape). The backslash starts STEP's escapes (``\\X2\\…\\X0\\``,
    ``\\S\\``), and Open CASCADE doubles a backslash only where it does not start one, so a file
    name such as ``n\\X2\\000D\\X0\\.step`` was written to decode to a carriage return; in its
    own escape it reads back as it is."""
    return _ascii(text).replace("\\", BACKSLASH)


BACKSLASH = "\\X2\\005C\\X0\\"
"""A backslash in a STEP string, as the escape that Open CASCADE passes through unchanged."""


def _ascii(text: str) -> str:
    """``text`` in the printable ASCII both formats' strings take (others become ``?``)."""
    return "".join(c if " " <= c <= "~" else "?" for c in text)


def read_shape(path: Path, units: str = "mm") -> TopoDS_Shape:
    """Read a STEP, IGES or BRep file back with Open CASCADE's own readers, its numbers
    converted to ``units`` (the unit the file declares is taken into account)."""
    suffix = Path(path).suffix.lower()
    if suffix in (".step", ".stp", ".iges", ".igs"):
        Interface_Static.SetCVal_s("xstep.cascade.unit", UNITS[units][0])
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


WRITERS = {".step": step_bytes, ".stp": step_bytes, ".iges": iges_bytes, ".igs": iges_bytes, ".brep": brep_bytes}
"""The bytes of each CAD format, by suffix."""
