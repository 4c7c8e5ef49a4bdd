"""Benchmark: the faces of a 50-face part recognised (issue 35).

Run as ``python -m benchmarks.cad_faces [--repeats N] [--write]``. The part is a turned shaft:
a profile of 50 pieces (a disk at each end, then twelve times a cylinder, a cone, a torus and a
B-spline surface of revolution) turned about an oblique axis, every face converted to a B-spline
(``BRepBuilderAPI_NurbsConvert``) and written as STEP, so that nothing of the file says what the
faces are. Timed: reading the STEP file, recognising every face (sampling, the line complex,
the native surface measured both ways), writing the canonical part, and the whole command
``sorgui analyze PART.step`` in a new process (Python's start, Open CASCADE's import and the
child process included). The promise is under 5 s for the recognition of such a part.
"""

from __future__ import annotations

import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_NurbsConvert,
    BRepBuilderAPI_Transform,
)
from OCP.BRepPrimAPI import BRepPrimAPI_MakeRevol
from OCP.GC import GC_MakeArcOfCircle, GC_MakeSegment
from OCP.GeomAPI import GeomAPI_PointsToBSpline
from OCP.gp import gp_Ax1, gp_Ax3, gp_Dir, gp_Pnt, gp_Trsf
from OCP.OCP.collections import Array1_gp_Pnt
from OCP.TopoDS import TopoDS_Shape

from benchmarks.report import median_time, run
from sorgui.cad.canonical import canonical_file
from sorgui.cad.reading import read_part
from sorgui.cad.recognition import analyse_part
from sorgui.cad.writers import WRITERS, CadHeader

STEPS = 12
"""Times the four pieces (cylinder, cone, torus, B-spline) repeat: 4 × 12 + 2 disks = 50 faces."""


def shaft() -> TopoDS_Shape:
    """The turned shaft of the module's description, as B-spline faces about an oblique axis."""
    wire = BRepBuilderAPI_MakeWire()
    point = gp_Pnt(0, 0, 0)

    def to(curve_or_point: object) -> None:
        nonlocal point
        if isinstance(curve_or_point, gp_Pnt):
            curve = GC_MakeSegment(point, curve_or_point).Value()
            point = curve_or_point
        else:
            curve = curve_or_point
            point = curve.EndPoint()
        wire.Add(BRepBuilderAPI_MakeEdge(curve).Edge())

    to(gp_Pnt(4, 0, 0))
    z = 0.0
    for k in range(STEPS):
        r = 4.0 + 0.5 * (k % 3)
        to(gp_Pnt(r, 0, z + 1.0))  # a cone from the last radius (a cylinder when it is the same)
        to(gp_Pnt(r, 0, z + 2.0))  # a cylinder
        middle = gp_Pnt(r + 0.4, 0, z + 2.5)
        to(GC_MakeArcOfCircle(point, middle, gp_Pnt(r, 0, z + 3.0)).Value())  # a torus
        points = Array1_gp_Pnt(1, 4)
        for i, (x, dz) in enumerate([(r, 3.0), (r - 0.3, 3.3), (r + 0.2, 3.7), (4.0, 4.0)], start=1):
            points.SetValue(i, gp_Pnt(x, 0, z + dz))
        to(GeomAPI_PointsToBSpline(points).Curve())  # a general surface of revolution
        z += 4.0
    to(gp_Pnt(0, 0, z))
    to(gp_Pnt(0, 0, 0))
    face = BRepBuilderAPI_MakeFace(wire.Wire(), True).Face()
    solid = BRepPrimAPI_MakeRevol(face, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2 * math.pi).Shape()
    trsf = gp_Trsf()
    trsf.SetTransformation(gp_Ax3(gp_Pnt(10, -20, 30), gp_Dir(1, 2, 3), gp_Dir(2, -1, 0)), gp_Ax3())
    placed = BRepBuilderAPI_Transform(solid, trsf, True).Shape()
    return BRepBuilderAPI_NurbsConvert(placed, True).Shape()


def command_seconds(path: Path) -> float:
    """``sorgui analyze PART.step`` in a new process, start to end."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "sorgui.cli", "analyze", str(path)], capture_output=True, check=True)
    return time.perf_counter() - start


def table(repeats: int) -> str:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "shaft.step"
        path.write_bytes(WRITERS[".step"](shaft(), CadHeader("", ("benchmark",), "0", path.name)))
        reading, part = median_time(lambda: read_part(path), repeats)
        recognising, (report, found) = median_time(lambda: analyse_part(part), repeats)
        writing, (_, canonical) = median_time(lambda: canonical_file(part, found, "canonical.step", ".step"), repeats)
        whole, _ = median_time(lambda: command_seconds(path), repeats)
        size = path.stat().st_size / 1024
    kinds = ", ".join(f"{n} {kind}" for kind, n in sorted(Counter(f.kind for f in report.faces).items()))
    worst = max(f.deviation or 0.0 for f in report.faces)
    rows = [
        "| step | median s |",
        "| --- | --- |",
        f"| read the STEP file ({len(part.faces)} B-spline faces, {size:,.0f} KiB) | {reading:.2f} |",
        f"| recognise every face ({kinds}; largest deviation {worst:.1e}) | {recognising:.2f} |",
        f"| write the canonical part ({canonical.summary()}) | {writing:.2f} |",
        f"| `sorgui analyze shaft.step`, a new process | {whole:.2f} |",
    ]
    machine = f"{platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} cores"
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    text = "\n".join(rows) + (
        f"\n\nMedian of {repeats} runs, {machine}, load average {load:.1f} while measured; command: "
        "`python -m benchmarks.cad_faces --repeats 3 --write`."
    )
    print(text)
    return text


if __name__ == "__main__":
    run("cad-faces", __doc__.splitlines()[0], table)
