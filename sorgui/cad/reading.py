"""Reading a CAD part: STEP (``.step``, ``.stp``), IGES (``.iges``, ``.igs``) and OCCT's BRep
(``.brep``) with Open CASCADE's own readers, every fault said in one line.

A file that is not one of these formats, a truncated STEP file (Open CASCADE's parser names the
line where it stopped), a file whose entities transfer to no shape, and a shape with no face are
each a :class:`PartError` whose message is one sentence. The numbers are read in millimetres
(the unit the file declares is converted), as sorgui's own CAD files write them. Open CASCADE's
parser reports go to a temporary file instead of standard output, which carries
``sorgui analyze --json``.
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from OCP.BRep import BRep_Builder
from OCP.BRepTools import BRepTools
from OCP.IFSelect import IFSelect_ReturnStatus
from OCP.IGESControl import IGESControl_Reader
from OCP.Interface import Interface_Static
from OCP.Message import Message, Message_Gravity, Message_PrinterOStream
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

from .failures import OCCT_ERRORS

FORMATS = {".step": "STEP", ".stp": "STEP", ".iges": "IGES", ".igs": "IGES", ".brep": "BRep"}
"""The formats a part is read from, by suffix."""

MAX_BYTES = 1 << 30
"""The largest part file read (1 GiB)."""


class PartError(ValueError):
    """A part file that cannot be read: the message is one line naming the file."""


@dataclass(frozen=True)
class Part:
    """A part as read: its shape, its faces in Open CASCADE's order (face ``k`` of a report is
    ``faces[k - 1]``), the file and its format."""

    shape: TopoDS_Shape
    faces: tuple[TopoDS_Face, ...]
    path: Path
    format: str
    warnings: tuple[str, ...] = ()
    """What the reader read past (entities it could not read and left out), in sentences."""


def faces_of(shape: TopoDS_Shape) -> list[TopoDS_Face]:
    """The faces of ``shape``, in the order Open CASCADE explores them."""
    found = []
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        found.append(TopoDS.Face(explorer.Current()))
        explorer.Next()
    return found


def is_part_path(path: str | Path) -> bool:
    """Whether ``path`` names a part by its suffix (any case)."""
    return Path(path).suffix.lower() in FORMATS


def read_part(path: str | Path) -> Part:
    """The shape of the STEP, IGES or BRep file ``path`` (:class:`PartError` if it has none)."""
    path = Path(path)
    kind = FORMATS.get(path.suffix.lower())
    if kind is None:
        raise PartError(f"{path} is not a CAD part (give a {', '.join(sorted(set(FORMATS)))} file)")
    try:
        size = path.stat().st_size
        with open(path, "rb") as stream:
            head = stream.read(200)
    except OSError as exc:
        raise PartError(f"cannot read {path}: {exc.strerror or exc}") from None
    if not path.is_file():
        raise PartError(f"cannot read {path}: it is not a regular file")
    if size == 0:
        raise PartError(f"{path} is empty")
    if size > MAX_BYTES:
        raise PartError(f"{path} is too large ({size / 2**20:.0f} MiB; at most {MAX_BYTES >> 20} MiB are read)")
    if not _looks_like(kind, head):
        raise PartError(f"{path} is not {'an' if kind == 'IGES' else 'a'} {kind} file ({SIGNS[kind]})")
    huge = _huge_number(path, HUGE[kind])
    if huge is not None:
        raise PartError(f"{path} holds a number beyond 1e200 ({huge}): no part has such a length")
    try:
        with _parser_messages() as messages:
            shape, warnings = _read(path, kind)
    except OCCT_ERRORS as exc:
        raise PartError(f"Open CASCADE cannot read {path}: {_first_line(str(exc))}") from None
    if shape is None:
        raise PartError(f"{path} is not a readable {kind} file{_reason(messages(), kind)}")
    faces = tuple(faces_of(shape)) if not shape.IsNull() else ()
    if not faces:
        why = f": {warnings[0]}" if warnings else " (no surface to analyse)"
        raise PartError(f"{path} holds no faces{why}")
    return Part(shape, faces, path, kind, warnings)


_EXPONENT = rb"\+?0*(?:[2-9][0-9]{2}|[1-9][0-9]{3,})(?![0-9])"
HUGE = {
    "STEP": re.compile(rb"\.[0-9]*[eE]" + _EXPONENT),
    "IGES": re.compile(rb"\.[0-9]*[eEdD]" + _EXPONENT),
    "BRep": re.compile(rb"[0-9.][eE]" + _EXPONENT),
}
"""A number written with an exponent of 200 or more (``1.E+400``), by format (a STEP or IGES
real has a decimal point, which keeps IGES's sequence numbers such as ``0D0000200`` out):
Open CASCADE's transfer of such a shape runs for minutes (it ends at the time limit), so the
file is refused at once."""
CHUNK = 1 << 24
"""Bytes scanned for :data:`HUGE` at a time (a 20 MB STEP file takes about 0.3 s)."""


def _huge_number(path: Path, pattern: re.Pattern[bytes]) -> str | None:
    """The first number of the file beyond 1e200 and its line (``1.E+400 at line 23``), if any."""
    lines, tail = 1, b""
    with open(path, "rb") as stream:
        while chunk := stream.read(CHUNK):
            data = tail + chunk
            found = pattern.search(data)
            if found is not None:
                mantissa = re.search(rb"[-+0-9.]*$", data[max(0, found.start() - 40) : found.start() + 1])
                number = (mantissa.group() if mantissa else b"") + data[found.start() + 1 : found.end()]
                line = lines + data.count(b"\n", 0, found.start())
                return f"{number.decode('ascii')} at line {line}"
            keep = min(len(data), 64)
            lines += data.count(b"\n", 0, len(data) - keep)
            tail = data[len(data) - keep :]
    return None


SIGNS = {
    "STEP": "it does not begin with ISO-10303-21",
    "IGES": "its first line is not an IGES record, 80 columns with S or G in column 73",
    "BRep": "it does not begin with Open CASCADE's CASCADE Topology header",
}
"""What each format's first bytes show, said when they do not."""


def _looks_like(kind: str, head: bytes) -> bool:
    """Whether the file's first bytes are those of a ``kind`` file (the readers take some
    garbage for an empty model, and the BRep reader prints on standard output)."""
    if kind == "STEP":
        return head.lstrip().startswith(b"ISO-10303-21")
    if kind == "IGES":
        first = head.split(b"\n", 1)[0].rstrip(b"\r")
        return len(first) >= 73 and first[72:73] in (b"S", b"G")
    return b"CASCADE Topology" in head


def _read(path: Path, kind: str) -> tuple[TopoDS_Shape | None, tuple[str, ...]]:
    """The file's shape (``None`` when the reader refuses the file) and what it read past."""
    if kind == "BRep":
        shape = TopoDS_Shape()
        return (shape if BRepTools.Read_s(shape, str(path), BRep_Builder()) else None), ()
    Interface_Static.SetCVal_s("xstep.cascade.unit", "MM")
    reader = STEPControl_Reader() if kind == "STEP" else IGESControl_Reader()
    if reader.ReadFile(str(path)) != IFSelect_ReturnStatus.IFSelect_RetDone:
        return None, ()
    faults = _faults(reader)
    reader.TransferRoots()
    return reader.OneShape(), faults


def _faults(reader: STEPControl_Reader | IGESControl_Reader) -> tuple[str, ...]:
    """The entities the reader could not read (they are left out of the shape), in a sentence."""
    checks = reader.WS().ModelCheckList(False)
    first, count = "", 0
    checks.Start()
    while checks.More():
        check = checks.Value()
        if check.NbFails() and check.HasEntity():  # not the model's own ("DATA NOT AVAILABLE FOR CHECK")
            count += 1
            first = first or check.CFail(1, True)
        checks.Next()
    if not count:
        return ()
    entities = "entity of the file is" if count == 1 else "entities of the file are"
    return (f"{count} {entities} faulty and left out (the first: {first.strip()})",)


@contextmanager
def _parser_messages() -> Iterator[Callable[[], str]]:
    """Open CASCADE's messages while inside, kept in a temporary file (read by the function
    yielded) rather than printed on standard output."""
    messenger = Message.DefaultMessenger_s()
    kept = list(messenger.Printers())
    handle, name = tempfile.mkstemp(prefix="sorgui-occt-", suffix=".log")
    os.close(handle)
    text: list[str] = []
    try:
        messenger.ChangePrinters().Clear()
        printer = Message_PrinterOStream(name, False, Message_Gravity.Message_Fail)
        messenger.AddPrinter(printer)
        try:
            yield lambda: "".join(text)
        finally:
            messenger.RemovePrinter(printer)
            del printer
            with open(name, encoding="utf-8", errors="replace") as stream:
                text.append(stream.read())
    finally:
        messenger.ChangePrinters().Clear()
        for printer in kept:
            messenger.AddPrinter(printer)
        os.unlink(name)


def _reason(messages: str, kind: str) -> str:
    """What Open CASCADE's parser said, in a few words (``: unexpected end of file at line 306``)."""
    found = re.search(r"Line (\d+):\s*([^*\n]*?)\s*\*\*\*\*", messages)
    if found is None:
        return ""
    line, words = found.group(1), found.group(2).removeprefix("Incorrect syntax: ")
    if "end of file" in words:
        return f": it ends in the middle (a truncated {kind} file?)"
    words = re.sub(r"\b[A-Z]+\b", lambda token: TOKENS.get(token.group(), token.group()), words)
    return f": {words} at line {line}"


TOKENS = {
    "QUID": "value",
    "IDENT": "reference #n",
    "ENTITY": "entity #n =",
    "TYPE": "entity name",
    "TEXT": "string",
    "STEP": "ISO-10303-21;",
    "ENDSTEP": "END-ISO-10303-21;",
}
"""Open CASCADE's STEP parser names its tokens as its grammar does (``unexpected QUID``): in words."""


def _first_line(text: str) -> str:
    return text.strip().splitlines()[0] if text.strip() else "an error in Open CASCADE"
