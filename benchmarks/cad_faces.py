"""Benchmark: the faces of a 50-face part recognised (issue 35).

Run as ``python -m benchmarks.cad_faces [--repeats N] [--write]``. The part is a turned shaft:
a profile of 50 pieces (a disk at each end, then twelve times a cylinder, a cone, a torus and a
B-spline surface of revolution) turned about an oblique axis, every face converted to a B-spline
(``BRepBuilderAPI_NurbsConvert``) and written as STEP, so that nothing of the file says what the
faces are. Timed: reading the STEP file, recognising every face (sampling, the line complex,
the native surface measured both ways), writing the canonical part, and the whole command
``sorgui analyze PART.step`` in a new process (Python's start, Open CASCADE's import and the
child process included, with the CPU time of both processes). The promise is under 5 s for the
recognition of such a part.
"""

from __future__ import annotations

import ctypes
import math
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

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

from benchmarks.report import run
from sorgui.cad.canonical import canonical_file
from sorgui.cad.reading import read_part
from sorgui.cad.recognition import analyse_part
from sorgui.cad.writers import WRITERS, CadHeader

T = TypeVar("T")

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


def _adopt_orphans() -> None:
    """Become the reaper of this process's orphaned descendants (Linux ``PR_SET_CHILD_SUBREAPER``):
    the command ends by ``os._exit`` without waiting for its analysis process, whose CPU time
    would otherwise be counted nowhere."""
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0)


def _reap_orphans() -> None:
    """Wait for every descendant adopted by :func:`_adopt_orphans` (it dies with its parent)."""
    while True:
        try:
            os.waitpid(-1, 0)
        except ChildProcessError:
            return


def command_times(path: Path) -> tuple[float, float]:
    """``sorgui analyze PART.step`` in a new process, start to end: wall time, and CPU time (user
    and system) of the command and its analysis process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "sorgui.cli", "analyze", str(path)], capture_output=True, check=True)
    wall = time.perf_counter() - start
    _reap_orphans()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def timed(run: Callable[[], T], repeats: int) -> tuple[float, float, T]:
    """The median wall time and median CPU time (of this process) of ``run()``, and its last result."""
    walls, cpus, result = [], [], None
    for _ in range(repeats):
        wall, cpu = time.perf_counter(), time.process_time()
        result = run()
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    return statistics.median(walls), statistics.median(cpus), result  # type: ignore[return-value]


def table(repeats: int) -> str:
    _adopt_orphans()
    uptime = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "shaft.step"
        path.write_bytes(WRITERS[".step"](shaft(), CadHeader("", ("benchmark",), "0", path.name)))
        reading = timed(lambda: read_part(path), repeats)
        part = reading[2]
        recognising = timed(lambda: analyse_part(part), repeats)
        report, found = recognising[2]
        writing = timed(lambda: canonical_file(part, found, "canonical.step", ".step"), repeats)
        canonical = writing[2][1]
        commands = [command_times(path) for _ in range(repeats)]
        whole = (statistics.median(c[0] for c in commands), statistics.median(c[1] for c in commands))
        size = path.stat().st_size / 1024
    kinds = ", ".join(f"{n} {kind}" for kind, n in sorted(Counter(f.kind for f in report.faces).items()))
    worst = max(f.deviation or 0.0 for f in report.faces)
    rows = [
        "| step | median wall s | median CPU s |",
        "| --- | --- | --- |",
        f"| read the STEP file ({len(part.faces)} B-spline faces, {size:,.0f} KiB) | {reading[0]:.2f} "
        f"| {reading[1]:.2f} |",
        f"| recognise every face ({kinds}; largest deviation {worst:.1e}) | {recognising[0]:.2f} "
        f"| {recognising[1]:.2f} |",
        f"| write the canonical part ({canonical.summary()}) | {writing[0]:.2f} | {writing[1]:.2f} |",
        f"| `sorgui analyze shaft.step`, a new process (and its analysis process) | {whole[0]:.2f} | {whole[1]:.2f} |",
    ]
    machine = f"{platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} cores"
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    text = "\n".join(rows) + (
        f"\n\nMedian of {repeats} runs, {machine}, load average {uptime:.1f} before and {load:.1f} after "
        "(a shared machine: the CPU times are the steadier figures); command: "
        "`python -m benchmarks.cad_faces --repeats 3 --write`."
    )
    print(text)
    return text


if __name__ == "__main__":
    run("cad-faces", __doc__.splitlines()[0], table)
