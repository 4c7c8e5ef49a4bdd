"""What ``sorgui analyze PART.step`` finds in a part: every face, and the faces about one axis
(docs/math.md §12). Plain immutable data, without Open CASCADE, so that the window and the
exports read it in a process that has not loaded OCP.

``PartReport.to_json`` is the JSON of ``sorgui analyze PART.step --json``; :func:`text_report`
is its text report, the same lines the window shows.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, fields
from typing import Any

from sorgui.engine.results import VERSION_KEY, ApproximateAxis
from sorgui.numerics import without_noise

Triple = tuple[float, float, float]

KIND_WORDS = {
    "plane": "a plane",
    "sphere": "a sphere",
    "cylinder": "a cylinder",
    "cone": "a cone",
    "torus": "a torus",
    "revolution": "a surface of revolution",
    "extrusion": "an extrusion (a cylinder over a curve)",
    "cone-over-curve": "a cone over a curve",
    "none": "not a surface of revolution, extrusion or cone",
}
"""Each kind in words."""


@dataclass(frozen=True)
class FaceReport:
    """One face: what the file calls its surface (STEP's entity name) and what it is.

    ``source`` is ``"file"`` when the file's own analytic surface says it (read as it is, no
    deviation), ``"samples"`` when it was recognised from sampled points and normals, within
    ``tolerance``; ``deviation`` is then the larger of ``to_surface`` (face samples to the fitted
    surface) and ``to_face`` (the fitted surface back to the face). A face of kind ``none`` keeps
    the kind it came ``nearest`` to and that deviation. ``error`` says why a face could not be
    evaluated (its kind is then ``none``)."""

    face: int
    type_in_file: str
    kind: str
    deviation: float | None
    tolerance: float
    source: str
    axis: ApproximateAxis | None = None
    center: Triple | None = None
    direction: Triple | None = None
    radius: float | None = None
    minor_radius: float | None = None
    half_angle: float | None = None
    to_surface: float | None = None
    to_face: float | None = None
    nearest: str | None = None
    error: str | None = None

    def to_json(self) -> dict[str, Any]:
        data = {f.name: getattr(self, f.name) for f in fields(self)}
        data["axis"] = (
            None if self.axis is None else {"point": list(self.axis.point), "direction": list(self.axis.direction)}
        )
        for key in ("center", "direction"):
            data[key] = None if data[key] is None else list(data[key])
        return data

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> FaceReport:
        names = {f.name for f in fields(cls)}
        plain = {k: v for k, v in data.items() if k in names}
        axis = data.get("axis")
        plain["axis"] = None if axis is None else ApproximateAxis(_triple(axis["point"]), _triple(axis["direction"]))
        for key in ("center", "direction"):
            plain[key] = None if data.get(key) is None else _triple(data[key])
        return cls(**plain)


@dataclass(frozen=True)
class AxisGroup:
    """Faces about one axis: together they lie on one surface of revolution about it (planes
    across the axis and spheres centred on it included)."""

    faces: tuple[int, ...]
    axis: ApproximateAxis
    kinds: tuple[str, ...]

    def to_json(self) -> dict[str, Any]:
        return {
            "faces": list(self.faces),
            "axis": {"point": list(self.axis.point), "direction": list(self.axis.direction)},
            "kinds": list(self.kinds),
        }

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> AxisGroup:
        axis = data["axis"]
        return cls(
            tuple(int(f) for f in data["faces"]),
            ApproximateAxis(_triple(axis["point"]), _triple(axis["direction"])),
            tuple(str(k) for k in data["kinds"]),
        )


@dataclass(frozen=True)
class PartReport:
    """Every face of a part and its groups, with the file's format and unit and what its reader
    left out."""

    file: str
    format: str
    units: str
    faces: tuple[FaceReport, ...]
    groups: tuple[AxisGroup, ...]
    warnings: tuple[str, ...] = ()
    seconds: float = 0.0

    def to_json(self) -> dict[str, Any]:
        """The JSON of ``sorgui analyze PART.step --json``: the version of sorgui that wrote it
        first, as in an equation's report (:func:`~sorgui.engine.results.report_json`)."""
        from sorgui import __version__

        return {
            VERSION_KEY: __version__,
            "file": self.file,
            "format": self.format,
            "units": self.units,
            "faces": [f.to_json() for f in self.faces],
            "groups": [g.to_json() for g in self.groups],
            "warnings": list(self.warnings),
            "seconds": self.seconds,
        }

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> PartReport:
        return cls(
            file=str(data["file"]),
            format=str(data["format"]),
            units=str(data["units"]),
            faces=tuple(FaceReport.from_json(f) for f in data["faces"]),
            groups=tuple(AxisGroup.from_json(g) for g in data["groups"]),
            warnings=tuple(str(w) for w in data.get("warnings", ())),
            seconds=float(data.get("seconds", 0.0)),
        )

    def counts(self) -> dict[str, int]:
        """How many faces are of each kind (kinds with none left out), in the order of the kinds."""
        found: dict[str, int] = {}
        for kind in KIND_WORDS:
            count = sum(1 for f in self.faces if f.kind == kind)
            if count:
                found[kind] = count
        return found


def _triple(values: Sequence[float]) -> Triple:
    x, y, z = (float(v) for v in values)
    return (x, y, z)


# --- the text report --------------------------------------------------------------------------------


def number(value: float) -> str:
    """A length or coordinate in six significant digits, without a negative zero."""
    text = f"{value:.6g}"
    return "0" if text in ("-0", "0") else text


def point_words(values: Sequence[float]) -> str:
    """``(x, y, z)`` without rounding noise."""
    return "(" + ", ".join(number(v) for v in without_noise(list(values))) + ")"


def axis_words(axis: ApproximateAxis) -> str:
    """``through (x, y, z) along (dx, dy, dz)``."""
    return f"through {point_words(axis.point)} along {point_words(axis.direction)}"


def face_words(face: FaceReport) -> str:
    """What a face is, in one line (without its number)."""
    if face.error is not None:
        return f"cannot be evaluated: {face.error}"
    words = KIND_WORDS[face.kind]
    if face.kind == "plane" and face.axis is not None:
        words += f", normal {point_words(face.axis.direction)} through {point_words(face.axis.point)}"
    elif face.kind == "sphere" and face.center is not None:
        words += f", centre {point_words(face.center)}, radius {number(face.radius or 0.0)}"
    elif face.kind == "cone-over-curve" and face.center is not None:
        words += f", apex {point_words(face.center)}"
    elif face.kind == "extrusion" and face.direction is not None:
        words += f" along {point_words(face.direction)}"
    elif face.axis is not None:
        words += f" about the axis {axis_words(face.axis)}"
        if face.kind == "cylinder":
            words += f", radius {number(face.radius or 0.0)}"
        elif face.kind == "cone" and face.half_angle is not None and face.center is not None:
            words += f", apex {point_words(face.center)}, half-angle {number(math.degrees(face.half_angle))}°"
        elif face.kind == "torus":
            words += f", radii {number(face.radius or 0.0)} and {number(face.minor_radius or 0.0)}"
    if face.source == "file":
        return words + " (as the file says)"
    if face.kind == "none":
        if face.nearest is not None and face.deviation is not None:
            words += f" (nearest: {KIND_WORDS[face.nearest]}, {face.deviation:.2g} away"
            return words + f"; tolerance {face.tolerance:.2g})"
        return words
    return words + f"; deviation {(face.deviation or 0.0):.2g} (tolerance {face.tolerance:.2g})"


def faces_words(numbers: Sequence[int]) -> str:
    """``face 3``, ``faces 3, 7, 9`` or ``faces 1–50, 52`` (a run of three or more in one)."""
    runs: list[list[int]] = []
    for n in sorted(numbers):
        if runs and n == runs[-1][-1] + 1:
            runs[-1].append(n)
        else:
            runs.append([n])
    parts = [f"{run[0]}–{run[-1]}" if len(run) >= 3 else ", ".join(map(str, run)) for run in runs]
    return f"{'face' if len(numbers) == 1 else 'faces'} {', '.join(parts)}"


def group_words(group: AxisGroup) -> str:
    """``faces 3, 7, 9: one surface of revolution about the axis through … along …``."""
    return f"{faces_words(group.faces)}: one surface of revolution about the axis {axis_words(group.axis)}"


def unevaluated_words(report: PartReport) -> str | None:
    """The faces that could not be evaluated, in one line (``None`` when there are none): said
    on standard error beside the report, where each has its own line."""
    failed = [f for f in report.faces if f.error is not None]
    if not failed:
        return None
    first = failed[0].error if len(failed) == 1 else f"the first: {failed[0].error}"
    return (
        f"{report.file}: {faces_words([f.face for f in failed])} of {len(report.faces)} cannot be evaluated ({first})"
    )


def text_report(report: PartReport) -> str:
    """The report as text: a header, one line a face, one line a group."""
    counts = ", ".join(f"{n} {kind}" for kind, n in report.counts().items())
    faces = f"{len(report.faces)} face{'s' if len(report.faces) != 1 else ''}"
    lines = [f"{report.file}: {report.format}, {faces} ({counts}), lengths in {report.units}"]
    lines += [f"warning: {w}" for w in report.warnings]
    width = max((len(f.type_in_file) for f in report.faces), default=0)
    for face in report.faces:
        lines.append(f"face {face.face:>3}  {face.type_in_file:<{width}}  {face_words(face)}")
    if report.groups:
        lines.append("")
        lines.append("Faces about one axis:")
        lines += [f"  {group_words(g)}" for g in report.groups]
    else:
        lines.append("")
        lines.append("No faces share an axis of revolution.")
    return "\n".join(lines)
