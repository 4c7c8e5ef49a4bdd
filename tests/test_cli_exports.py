"""The ``-o`` files are written in a child process under the one time limit, and every fault of
writing them is one line (real ``sorgui analyze`` processes, real Open CASCADE)."""

from __future__ import annotations

import json
import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

SORGUI = [sys.executable, "-m", "sorgui.cli"]
SLOW_EXPORT = "(x^2+y^2)^30+z^60-1"
"""A degree-60 surface of revolution whose STEP file fits its profile for a second or two (it
took most of a minute before the fit was made faster): ten of them take longer than the limit."""


def sorgui(*args: str, timeout: float = 300, **kwargs) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*SORGUI, *args], capture_output=True, text=True, timeout=timeout, **kwargs)


def lines(stderr: str) -> list[str]:
    """The lines of ``stderr``, each a sorgui message (no traceback)."""
    assert "Traceback" not in stderr, stderr
    found = stderr.splitlines()
    assert all(line.startswith("sorgui: ") for line in found), stderr
    return found


def leftovers(folder: Path) -> list[Path]:
    """Temporary files of an atomic write left behind."""
    return [p for p in folder.iterdir() if ".tmp" in p.name]


def test_the_time_limit_bounds_the_files_too(tmp_path: Path) -> None:
    """``--timeout 6`` with CAD files that take longer together: the answer comes within the
    limit and a second (with room for a busy machine), the last file not written is named, its
    old one is kept, and the analysis is still printed."""
    step = tmp_path / "out9.step"
    step.write_text("the old file\n", encoding="ascii")
    targets = [a for i in range(10) for a in ("-o", str(tmp_path / f"out{i}.step"))]
    start = time.monotonic()
    done = sorgui("analyze", "--json", SLOW_EXPORT, "--timeout", "6", "-o", str(tmp_path / "out.stl"), *targets)
    elapsed = time.monotonic() - start
    assert done.returncode == 1
    assert f"cannot write {step}: not written within the time limit of 6 s" in lines(done.stderr)[-1]
    assert elapsed < 6 + 6, elapsed
    assert json.loads(done.stdout)["degree"] == 60
    assert step.read_text(encoding="ascii") == "the old file\n"
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize("delay", [0.5, 1.0, 1.5, 2.0, 2.5, 2.9])
def test_sigterm_while_a_cad_file_is_written_ends_sorgui_with_143(tmp_path: Path, delay: float) -> None:
    """Whenever the signal comes (the engine loading, Open CASCADE being imported, the file being
    written), sorgui ends with 128 + 15 and says nothing (but that a file was written, when it was
    before the signal came); no half-written file is left."""
    pytest.importorskip("OCP")
    proc = subprocess.Popen(
        [*SORGUI, "analyze", "x^2+y^2-z", "-o", str(tmp_path / "out.step")],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    time.sleep(delay)
    proc.send_signal(signal.SIGTERM)
    _out, err = proc.communicate(timeout=60)
    if proc.returncode == 0:
        pytest.skip("the file was written before the signal came")
    written = "".join(f"{line}\n" for line in err.splitlines() if line.startswith("sorgui: wrote "))
    assert proc.returncode == 128 + signal.SIGTERM and err == written, err
    time.sleep(0.5)  # the killed export process is gone by then
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize(
    "region",
    ["1e308", "1e-300", "-1e308:1e308,-1:1,-1:1", "0:1e-300,0:1,0:1", "-1e200:1e200,-1:1,-1:1"],
)
def test_a_region_beyond_what_can_be_drawn_is_refused_in_one_line(tmp_path: Path, region: str) -> None:
    done = sorgui("analyze", "x^2+y^2-z", f"--region={region}", "-o", str(tmp_path / "out.stl"), timeout=60)
    assert done.returncode == 2 and "region" in lines(done.stderr)[0] and len(lines(done.stderr)) == 1
    assert not (tmp_path / "out.stl").exists()


def test_a_file_name_with_a_newline_keeps_the_wrote_line_one_line(tmp_path: Path) -> None:
    pytest.importorskip("OCP")
    target = tmp_path / "a\nb.step"
    done = sorgui("analyze", "x^2+y^2+z^2-1", "-o", str(target))
    assert done.returncode == 0, done.stderr
    (line,) = lines(done.stderr)
    assert line.startswith(f"sorgui: wrote {tmp_path}/a\\nb.step: ") and target.exists()


def test_a_file_name_of_255_characters_is_written(tmp_path: Path) -> None:
    """The longest name a folder takes: the temporary file beside it gets a shorter one."""
    target = tmp_path / ("n" * (255 - len(".json")) + ".json")
    done = sorgui("analyze", "--recognition-only", "x^2+y^2-z", "-o", str(target), timeout=60)
    assert done.returncode == 0, done.stderr
    assert json.loads(target.read_text(encoding="utf-8"))["is_sor"] is True
    assert leftovers(tmp_path) == []


def test_no_export_process_outlives_sorgui(tmp_path: Path) -> None:
    """A file not written by the limit: its process is killed, nothing of sorgui is left running."""
    targets = [a for i in range(10) for a in ("-o", str(tmp_path / f"out{i}.step"))]
    proc = subprocess.Popen(
        [*SORGUI, "analyze", SLOW_EXPORT, "--timeout", "4", *targets],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    _out, err = proc.communicate(timeout=60)
    assert proc.returncode == 1 and "not written within the time limit" in err
    time.sleep(0.5)
    survivors = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                cmdline = (entry / "cmdline").read_bytes()
            except OSError:
                continue
            if str(tmp_path / "out9.step").encode() in cmdline and int(entry.name) != os.getpid():
                survivors.append(entry.name)
    assert survivors == []


def step_strings(text: str, entity: str) -> list[str]:
    """The strings of the first ``entity(…)`` of a STEP file, decoded as ISO 10303-21 says."""
    import re

    start = text.index(entity + "(")
    body = text[start : text.index(";", start)].replace("\n", "")
    return [_decoded(raw) for raw in re.findall(r"'((?:[^']|'')*)'", body)]


def _decoded(raw: str) -> str:
    out, i = [], 0
    raw = raw.replace("''", "'")
    while i < len(raw):
        if raw.startswith("\\\\", i):
            out.append("\\")
            i += 2
        elif raw.startswith("\\X2\\", i):
            end = raw.index("\\X0\\", i)
            digits = raw[i + 4 : end]
            out += [chr(int(digits[k : k + 4], 16)) for k in range(0, len(digits), 4)]
            i = end + 4
        elif raw.startswith("\\X\\", i):
            out.append(chr(int(raw[i + 3 : i + 5], 16)))
            i += 5
        elif raw.startswith("\\S\\", i):
            out.append(chr(ord(raw[i + 3]) + 128))
            i += 4
        else:
            assert raw[i] != "\\", f"a lone backslash in {raw!r}"
            out.append(raw[i])
            i += 1
    return "".join(out)


def test_a_backslash_in_a_step_header_reads_back_as_a_backslash(tmp_path: Path) -> None:
    """STEP's escapes in a file name (``\\X2\\000D\\X0\\`` is a carriage return, ``\\S\\`` shifts
    a character) are written as the characters they are: the header decodes to the name itself."""
    pytest.importorskip("OCP")
    name = "n\\X\\0A\\X2\\000D\\X0\\\\S\\a'b.step"
    target = tmp_path / name
    done = sorgui("analyze", "x^2+y^2+z^2-1", "-o", str(target))
    assert done.returncode == 0, done.stderr
    text = target.read_text(encoding="ascii")
    assert step_strings(text, "FILE_NAME")[0] == name
    assert step_strings(text, "PRODUCT")[0].startswith(name.removesuffix(".step"))  # Open CASCADE adds " 1"


def test_a_reports_method_in_a_patch_header_reads_back_literally(tmp_path: Path) -> None:
    """The same escapes through a report's parameterization ``method``, written in the patch's header."""
    pytest.importorskip("OCP")
    report = tmp_path / "paraboloid.json"
    assert sorgui("analyze", "x^2+y^2-z", "-o", str(report)).returncode == 0
    data = json.loads(report.read_text(encoding="utf-8"))
    method = "rotated \\X2\\000D\\X0\\ profile \\S\\a"
    for param in data["parametrizations"]:
        param["method"] = method
    report.write_text(json.dumps(data), encoding="utf-8")
    patch = tmp_path / "part.patch.step"
    done = sorgui("open", str(report), "-o", str(patch))
    assert done.returncode == 0, done.stderr
    description = " ".join(step_strings(patch.read_text(encoding="ascii"), "FILE_DESCRIPTION"))
    assert method in description and "\r" not in description


def _a_safe_cut(before: str, after: str, width: int) -> bool:
    """Two pieces of a header line meet between terms or words, else (a term longer than a
    piece) after a ``*`` or ``/`` between factors, else inside a number longer than a piece."""
    if after.startswith(" ") or re.search(r"[^*/][*/]$", before) and after[0].isalnum():
        return True
    number = re.search(r"\d*$", before).group() + re.match(r"\d*", after).group()
    return len(number) > width and before[-1].isdigit() and after[0].isdigit()


def test_a_long_equation_reads_back_from_the_header_as_it_was_written(tmp_path: Path) -> None:
    """A rounded torus's equation (25 terms) and its nearest surface's (numbers of 80 digits)
    span several STEP strings and IGES start lines: each is cut between two terms, so the pieces
    joined as they are give the equation back, and joined by line breaks sorgui reads the same
    polynomial (a cut inside ``**`` or a number, ``'...z*'`` then ``'*2...'``, read as another
    one). Open CASCADE's and gmsh's readers take both files, and sorgui reads the part's torus."""
    pytest.importorskip("OCP")
    pytest.importorskip("gmsh")
    from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
    from OCP.IGESControl import IGESControl_Reader
    from OCP.STEPControl import STEPControl_Reader

    from sorgui.engine.parsing import parse_polynomial

    from .cad.readback import gmsh_part

    typed = Path(__file__).parent / "data" / "rounded-torus-6-digits.txt"
    step, iges = tmp_path / "torus.step", tmp_path / "torus.igs"
    done = sorgui("analyze", "-f", str(typed), "-o", str(step), "-o", str(iges))
    assert done.returncode == 0, done.stderr
    reader = STEPControl_Reader()
    reader.ReadFile(str(step))
    header = APIHeaderSection_MakeHeader(reader.StepModel())
    strings = [header.DescriptionValue(i).ToCString() for i in range(1, header.NbDescription() + 1)]
    assert strings == step_strings(step.read_text(encoding="ascii"), "FILE_DESCRIPTION")
    assert max(map(len, strings)) <= 256
    reader = IGESControl_Reader()
    reader.ReadFile(str(iges))
    model = reader.IGESModel()
    start = [model.StartLine(i) for i in range(1, model.NbStartLines() + 1)]
    assert max(map(len, start)) <= 72
    expected = parse_polynomial(typed.read_text(encoding="utf-8")).polynomial
    equations = []
    for pieces in (strings, start):
        ends = [i for i, piece in enumerate(pieces) if piece.endswith(" = 0")]
        assert len(ends) >= 2, pieces  # the typed equation, then the nearest surface's
        equation = pieces[: ends[0] + 1]
        assert len(equation) > 1 and all(piece.startswith(" ") for piece in equation[1:])
        assert parse_polynomial("".join(equation)).polynomial == expected
        assert parse_polynomial("\n".join(equation)).polynomial == expected
        nearest = "".join(pieces[ends[0] + 1 : ends[1] + 1])
        assert nearest.startswith("rounded input: the part of the nearest exact surface of revolution ")
        for before, after in zip(pieces[ends[0] + 1 : ends[1]], pieces[ends[0] + 2 : ends[1] + 1]):
            assert _a_safe_cut(before, after, 72 if pieces is start else 256), (before, after)
        equations.append("".join(equation))
    assert equations[0] == equations[1]
    for path in (step, iges):
        assert gmsh_part(path).surfaces == 1
    done = sorgui("analyze", "--json", str(step))
    assert done.returncode == 0, done.stderr
    assert [face["kind"] for face in json.loads(done.stdout)["faces"]] == ["torus"]


@pytest.mark.parametrize(
    ("equation", "suffix", "words"),
    [
        ("x^2+y^2+z^2", ".step", "real points are an isolated real point, not a surface"),
        ("x^2+y^2+z^2", ".stl", "real points are an isolated real point, not a surface"),
        ("x^2+y^2", ".step", "real points are a curve (the axis), not a surface"),
        ("x^2+y^2", ".obj", "real points are a curve (the axis), not a surface"),
        ("(x^2+y^2+z^2-1)^2+z^2", ".stl", "a curve (a circle about the axis)"),
        ("x^2+y^2+z^2+1", ".iges", "the surface has no real points"),
    ],
)
def test_a_surface_without_a_surface_to_write_says_what_its_real_points_are(
    tmp_path: Path, equation: str, suffix: str, words: str
) -> None:
    if suffix in (".step", ".iges"):
        pytest.importorskip("OCP")
    target = tmp_path / f"out{suffix}"
    done = sorgui("analyze", equation, "-o", str(target))
    assert done.returncode == 1 and words in lines(done.stderr)[-1] and not target.exists(), done.stderr


def test_a_sphere_of_degree_60_is_written_as_its_sphere(tmp_path: Path) -> None:
    """``(x² + y² + z² + 1)³⁰ − 2`` is the sphere of radius² ``2^(1/30) − 1`` (a root of its
    restriction to a line through the centre): one spherical face of that area."""
    pytest.importorskip("OCP")
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.STEPControl import STEPControl_Reader

    target = tmp_path / "sphere.step"
    done = sorgui("analyze", "(x^2+y^2+z^2+1)^30-2", "-o", str(target))
    assert done.returncode == 0 and "1 face in 1 solid" in done.stderr, done.stderr
    reader = STEPControl_Reader()
    reader.ReadFile(str(target))
    reader.TransferRoots()
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(reader.OneShape(), props)
    assert props.Mass() == pytest.approx(4 * math.pi * (2 ** (1 / 30) - 1), rel=1e-9)


@pytest.mark.parametrize("suffix", [".stl", ".step"])
def test_a_surface_beyond_floating_point_says_so(tmp_path: Path, suffix: str) -> None:
    """A sphere of radius about 10^1000 (a 2000-digit constant): its exact analysis stands, and a
    mesh or CAD file says that its numbers are beyond floating point, not that a ball holds no real
    point of it (no ``--region`` would help); the report is still written."""
    if suffix == ".step":
        pytest.importorskip("OCP")
    constant = "7" * 2000
    report, shape = tmp_path / "s.json", tmp_path / f"s{suffix}"
    done = sorgui("analyze", f"x^2+y^2+z^2-{constant}", "--timeout", "60", "-o", str(report), "-o", str(shape))
    assert done.returncode == 1 and "cannot be drawn: its coefficients span about 10^2000" in lines(done.stderr)[-1]
    assert "give --region" not in done.stderr and "no real points" not in done.stderr
    assert json.loads(report.read_text(encoding="utf-8"))["is_sor"] and not shape.exists()


def test_a_cad_file_of_a_surface_outside_the_drawn_ball_is_refused_before_open_cascade(tmp_path: Path) -> None:
    """A sphere of radius 10^200 about a ball of radius 2 kept Open CASCADE's cut busy for
    minutes: said at once, that its numbers are beyond floating point (one of radius 10^20, which
    gave a STEP file of no face and then a ball of radius 2, is now drawn whole:
    tests/cad/test_parts.py). A unit sphere in a ball of radius 1000 falls
    between the mesh's grid points: it was said to have no real points there."""
    pytest.importorskip("OCP")
    for radius_squared, words in (
        ("10^400", "cannot be drawn: its coefficients span about 10^400"),
        ("1 --region 1000", "the ball of radius 1000 about (0, 0, 0) asked for is too large to draw the surface in"),
    ):
        constant, *region = radius_squared.split()
        done = sorgui("analyze", f"x^2+y^2+z^2-{constant}", *region, "--timeout", "60", "-o", str(tmp_path / "s.step"))
        assert done.returncode == 1 and words in lines(done.stderr)[-1]
        assert not (tmp_path / "s.step").exists()


@pytest.mark.parametrize(
    ("equation", "region", "suffix", "words"),
    [
        ("x^2+y^2-z^2", "0,0,1e6,1", ".step", "the ball of radius 1 about (0, 0, 1e+06) asked for: give a region"),
        ("x^2+y^2-1", "100:101,100:101,0:1", ".step", "the box (100, 100, 0) to (101, 101, 1) asked for: give"),
        ("x^2+y^2-z", "0.1,0,-1,0.5", ".step", "the ball of radius 0.5 about (0.1, 0, -1) asked for: give"),
        ("x^2+y^2-z^2+1", "0.5", ".stl", "the ball of radius 0.5 about (0, 0, 0) asked for: give a region"),
        ("x^2+y^2-z^2-1", "0,0,50,1", ".iges", "the ball of radius 1 about (0, 0, 50) asked for: give a region"),
        # the mesh's grid passes between the points of an unbounded surface (it was said to lie
        # "within about 1.77 of its centre")
        ("x^2+y^2-1", "1e9", ".step", "the ball of radius 1e+09 about (0, 0, 0) asked for is too large to draw"),
        ("x^2+y^2-z", "1e9", ".stl", "the ball of radius 1e+09 about (0, 0, 0.5) asked for is too large to draw"),
    ],
)
def test_a_region_that_misses_the_surface_is_named_and_not_asked_for_again(
    tmp_path: Path, equation: str, region: str, suffix: str, words: str
) -> None:
    """An unbounded surface (a cone, a cylinder, a paraboloid, hyperboloids) and a --region that
    holds none of it: the line names the region and what is wrong with it, and the ball chosen
    without one; it said "(give --region)" of the region given with --region."""
    if suffix != ".stl":
        pytest.importorskip("OCP")
    target = tmp_path / f"out{suffix}"
    done = sorgui("analyze", equation, f"--region={region}", "-o", str(target))
    message = lines(done.stderr)[-1]
    assert done.returncode == 1 and words in message and not target.exists(), done.stderr
    assert "give --region" not in message and "lies within" not in message
    if "too large" in message:
        assert "give a smaller one (the ball chosen for it has radius 1." in message
    else:
        assert "meets it (without one, the ball of radius " in message


def test_a_nearly_revolving_surface_without_an_exact_one_is_not_called_no_surface_of_revolution(tmp_path: Path) -> None:
    """A cylinder about the irrational axis (1, √2, √3) printed with 15 digits: near a cylinder of
    revolution, with no exact surface to build the part from. The refusal says that, offers no
    patch file (there is no parameterization to write), and names the tolerance that finds one
    (a double printed in full got no part at all)."""
    pytest.importorskip("OCP")
    text = Path(__file__).parent / "data" / "near-cylinder-irrational-axis.txt"
    target = tmp_path / "near.step"
    done = sorgui("analyze", "-f", str(text), "-o", str(target))
    message = lines(done.stderr)[-1]
    assert done.returncode == 1 and not target.exists(), done.stderr
    assert "not exactly a surface of revolution, only within" in message and "cylinder of revolution" in message
    assert "patch" not in message and "nor a canal surface" not in message
    # 15 digits: finer than the arithmetic that printed them; the tolerance it names finds a part
    assert "a larger tolerance (--tolerance 1e-10) may find one" in message
    done = sorgui("analyze", "-f", str(text), "--tolerance", "1e-10", "-o", str(target))
    assert done.returncode == 0 and target.exists(), done.stderr
    assert "the nearest exact surface's part" in lines(done.stderr)[-1]


def test_a_recognition_only_part_of_rounded_input_says_what_it_lacks(tmp_path: Path) -> None:
    """With --recognition-only the nearest exact surface of a rounded torus is found but not
    analysed, and its part is built from that analysis: the refusal says so (it said that no
    exact surface was found within the rounding)."""
    pytest.importorskip("OCP")
    text = Path(__file__).parent / "data" / "rounded-torus-6-digits.txt"
    target = tmp_path / "torus.step"
    done = sorgui("analyze", "--recognition-only", "-f", str(text), "-o", str(target))
    message = lines(done.stderr)[-1]
    assert done.returncode == 1 and not target.exists(), done.stderr
    assert "with --recognition-only its nearest exact surface is not analysed" in message
    assert "analyse without --recognition-only for its part" in message and "was found" not in message


def test_a_recognition_only_part_of_an_elliptic_cone_says_it_was_not_analysed(tmp_path: Path) -> None:
    """An elliptic cone is a cone over a conic, but with --recognition-only that stage does not
    run: the refusal said it is not a cone over a rational curve."""
    pytest.importorskip("OCP")
    target = tmp_path / "cone.step"
    done = sorgui("analyze", "--recognition-only", "4*x^2+5*y^2-z^2", "-o", str(target))
    message = lines(done.stderr)[-1]
    assert done.returncode == 1 and not target.exists(), done.stderr
    assert "with --recognition-only it is not analysed as a cylinder or cone over a curve" in message
    assert "nor a cylinder or cone" not in message
    assert sorgui("analyze", "4*x^2+5*y^2-z^2", "-o", str(target)).returncode == 0 and target.exists()


def test_a_nearest_surface_beyond_the_rounding_is_written_and_says_so(tmp_path: Path) -> None:
    """A cone of 7.5° printed with 6 decimals whose nearest exact surface found lies beyond the
    rounding (one coefficient 2.7 times its rounding off): its part is written, and the line
    says it is beyond."""
    pytest.importorskip("OCP")
    text = Path(__file__).parent / "data" / "rounded-cone-outside.txt"
    target = tmp_path / "cone.step"
    done = sorgui("analyze", "-f", str(text), "-o", str(target))
    assert done.returncode == 0 and target.exists(), done.stderr
    assert "BEYOND the input's rounding" in lines(done.stderr)[-1]


def test_an_iges_file_says_it_holds_faces_not_a_solid(tmp_path: Path) -> None:
    """IGES gets the trimmed surfaces (entity 144, which every reader takes), not the solid the
    STEP file holds: the line says so, instead of "in 1 solid"."""
    pytest.importorskip("OCP")
    done = sorgui(
        "analyze", "(x^2+y^2+z^2+3)^2-16(x^2+y^2)", "-o", str(tmp_path / "t.iges"), "-o", str(tmp_path / "t.step")
    )
    iges, step = [line for line in lines(done.stderr) if line.startswith("sorgui: wrote")]
    assert done.returncode == 0 and "IGES holds no solid" in iges and "in 1 solid" not in iges
    assert "1 face in 1 solid" in step


TURNED_TORUS = (
    "((x-3/10)^2+(y+7/10)^2+(z-11/10)^2+351/100)^2"
    "-16*((x-3/10)^2+(y+7/10)^2+(z-11/10)^2-((x-3/10)+2*(y+7/10)+2*(z-11/10))^2/9)"
)
"""The torus R = 2, r = 0.7 about the axis through (3/10, −7/10, 11/10) along (1, 2, 2)."""


def test_the_patch_of_a_map_with_a_parameter_of_another_scale_covers_the_surface(tmp_path: Path) -> None:
    """This torus's map through its tube had ``t`` of order 10⁶: the patch over ``t ∈ [−3, 3]``
    was a sliver of area 0.00016 against the torus's 55. Its parameters are now balanced
    (``t ↦ 10⁶·t``) and its numbers smaller."""
    import pyvista

    patch, whole = tmp_path / "t.patch.stl", tmp_path / "t.stl"
    done = sorgui("analyze", "--json", TURNED_TORUS, "-o", str(patch), "-o", str(whole))
    assert done.returncode == 0, done.stderr
    area = pyvista.read(patch).area
    assert area > 0.5 * pyvista.read(whole).area, area
    tube = next(p for p in json.loads(done.stdout)["parametrizations"] if p["method"].startswith("via tubular"))
    assert max(len(n) for n in re.findall(r"[0-9]+", " ".join(tube["coordinates"]))) <= 12


ROUNDED_HYPERBOLOID = (
    "0.912239*x^2 - 0.534922*x*y + 0.620593*x*z - 3.0135*x + 0.184881*y^2 + 1.89133*y*z - 0.564965*y"
    " - 0.09712*z^2 + 0.315604*z + 0.623847"
)
"""x² + y² − z² = 1 turned and moved, printed with 6 digits (as a CAD system prints it)."""


def test_a_patch_is_the_first_map_that_meets_the_ball(tmp_path: Path) -> None:
    """The nearest exact hyperboloid's maps had numbers of 13 digits: its first map (the rotated
    profile's) met the drawn ball only outside ``[−3, 3]²``, and its second, through ``T``, had
    ``x ≈ 1.8 + 417·t`` over a denominator without ``t``, and both patch files were refused
    ("no real parameterization", "no point inside the drawn ball") until that map was balanced.
    In the frame of the axis snapped as an integer direction, its maps have numbers of 5 digits,
    the first meets the ball, and both files take its patch."""
    import pyvista

    pytest.importorskip("OCP")
    stl, step = tmp_path / "h.patch.stl", tmp_path / "h.patch.step"
    done = sorgui("analyze", "--json", ROUNDED_HYPERBOLOID, "-o", str(stl), "-o", str(step))
    assert done.returncode == 0, done.stderr
    assert pyvista.read(stl).n_cells > 100 and " faces;" in done.stderr
    maps = json.loads(done.stdout)["approximate"]["nearest"]["analysis"]["parametrizations"]
    assert len(maps) == 2 and all(len(n) <= 6 for p in maps for n in re.findall(r"[0-9]+", " ".join(p["coordinates"])))
    description = " ".join(step_strings(step.read_text(encoding="ascii"), "FILE_DESCRIPTION"))
    assert maps[0]["method"] in description


def test_a_patch_widens_its_box_until_it_meets_the_ball(tmp_path: Path) -> None:
    """A hyperboloid with a neck of radius 0.055 is drawn in a ball of its own size; its map
    reaches the neck at ``t ≈ 9``, so no patch over ``[−3, 3]²`` met the ball. Both patch files
    take the box ``[−30, 30]²``, and the CAD file says so."""
    import pyvista

    pytest.importorskip("OCP")
    stl, step = tmp_path / "h.patch.stl", tmp_path / "h.patch.step"
    done = sorgui("analyze", "0.5*x^2+0.5*y^2-0.25*z^2-1.5e-3", "-o", str(stl), "-o", str(step))
    assert done.returncode == 0, done.stderr
    assert pyvista.read(stl).n_cells > 100
    description = " ".join(step_strings(step.read_text(encoding="ascii"), "FILE_DESCRIPTION"))
    assert "s, t in [-30, 30]" in description


def test_a_mesh_patch_is_written_where_the_cad_patch_is(tmp_path: Path) -> None:
    """``.patch.stl`` takes the map ``.patch.step`` takes: a cylinder over a curve's map by its
    lines (it was refused, "no real parameterization", while ``.patch.step`` was written)."""
    import pyvista

    patch = tmp_path / "nodal.patch.stl"
    done = sorgui("analyze", "y^2 - x^3 - x^2", "-o", str(patch), "-o", str(tmp_path / "nodal.patch.step"))
    assert done.returncode == 0, done.stderr
    assert pyvista.read(patch).n_cells > 100


def test_the_mesh_patch_of_rounded_input_is_the_nearest_surfaces_and_says_so(tmp_path: Path) -> None:
    """Rounded input has no map of its own: its mesh patch is that of the nearest exact surface,
    as its ``.patch.step`` is, and the header and the line on stderr say so."""
    import pyvista

    data = Path(__file__).parent / "data" / "rounded-torus-6-digits.txt"
    stl, obj = tmp_path / "t.patch.stl", tmp_path / "t.patch.obj"
    done = sorgui("analyze", "-f", str(data), "-o", str(stl), "-o", str(obj))
    assert done.returncode == 0, done.stderr
    assert "nearest exact surface of revolution (rounded input: not the typed surface's)" in done.stderr
    assert stl.read_bytes()[:80].startswith(b"sorgui nearest exact SOR's patch;")
    header = obj.read_text(encoding="utf-8").splitlines()[0]
    assert header.startswith("# sorgui: parametric patch of the nearest exact surface of revolution ")
    assert "(rounded input; its coefficients" in header
    assert pyvista.read(stl).n_cells > 100


ROUNDED_CONE = (
    "-0.675000*x^2 - 0.250000*x*y + 0.612372*x*z - 0.675000*y^2 - 0.612372*y*z - 0.050000*z^2"
    " + 2.462372*x + 2.337628*y + 0.512372*z - 3.312628"
)
"""A cone of ``tan²θ = 1/4`` about ``(1, −1, √6)`` through its apex, printed with ``%.6f``: exactly
a cone over a conic, whose own map by its lines has coefficients of 80 digits in a quadratic
field."""


def test_a_rounded_cone_s_patch_mesh_and_patch_step_are_one_surface(tmp_path: Path) -> None:
    """The mesh patch took the typed cone's own map (on ``f``), the ``.patch.step`` the nearest
    exact cone's (on ``g``): both are now the nearest cone's, and the header says so."""
    import pyvista

    obj = tmp_path / "c.patch.obj"
    done = sorgui("analyze", ROUNDED_CONE, "-o", str(obj))
    assert done.returncode == 0, done.stderr
    header = obj.read_text(encoding="utf-8").splitlines()[0]
    assert header.startswith("# sorgui: parametric patch of the nearest exact surface of revolution ")
    points = pyvista.read(obj).points.astype(float)
    x, y, z = points.T
    s6 = np.sqrt(6)
    g = (  # the nearest exact cone, as the header prints it
        -27 / 40 * x**2
        - x * y / 4
        + s6 / 4 * x * z
        - 27 / 40 * y**2
        - s6 / 4 * y * z
        - z**2 / 20
        + (s6 / 4 + 37 / 20) * x
        + (59 / 20 - s6 / 4) * y
        - (1 / 10 - s6 / 4) * z
        - (157 / 40 - s6 / 4)
    )
    assert np.max(np.abs(g)) < 1e-9 * max(1.0, float(np.max(np.abs(points))) ** 2)


SPHERE_TIMES_PLANE = (
    "11*x^3/15 + 2*x^2*y/3 + 2*x^2*z/15 - 44*x^2/45 + 11*x*y^2/15 + 4*x*y/5 + 11*x*z^2/15 - 28*x*z/45"
    " + 55*x/108 + 2*y^3/3 + 2*y^2*z/15 + 49*y^2/45 + 2*y*z^2/3 - 8*y*z/45 - 67*y/270 + 2*z^3/15 - z^2/3"
    " + 19*z/90 - 143/1620"
)
"""``(x² + y² + z² − 1)(z − 1/2)`` turned by the rotation of the quaternion ``(1, 2, 3, 4)`` and
moved by ``(1/2, −1, 1/3)``."""


def test_a_step_file_reads_back_as_the_part_it_was_written_of(tmp_path: Path) -> None:
    """Capped in a box, one face of the sphere is bounded by one loop, which bounds two regions
    of the sphere: Open CASCADE read the STEP file back with the other region, a valid file of a
    solid of volume 29.23 instead of 25.04 (the BRep and IGES files were right). The file is now
    written with B-spline faces, which read back as written, and says so in its header and in
    the line that reports it (which said "an analytic surface" alone)."""
    pytest.importorskip("OCP")
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    from sorgui.cad.writers import read_shape

    step, brep = tmp_path / "part.step", tmp_path / "part.brep"
    done = sorgui(
        "analyze", SPHERE_TIMES_PLANE, "--region=-2:2,-2:2,-1.5:1.5", "--cap", "-o", str(step), "-o", str(brep)
    )
    assert done.returncode == 0, done.stderr
    volumes = []
    for path in (step, brep):
        props = GProp_GProps()
        BRepGProp.VolumeProperties_s(read_shape(path), props)
        volumes.append(props.Mass())
    assert volumes[0] == pytest.approx(volumes[1], rel=2e-3)  # Open CASCADE's volumes of B-spline faces
    assert volumes[1] == pytest.approx(25.0432, rel=1e-4)  # f <= 0 in the box, integrated numerically
    assert "faces written as B-splines" in step.read_text(encoding="ascii")
    wrote = next(line for line in done.stderr.splitlines() if "part.step" in line)
    assert "faces written as B-splines" in wrote, done.stderr
    assert "faces written as B-splines" not in next(line for line in done.stderr.splitlines() if "part.brep" in line)


def test_sorgui_s_own_text_report_given_back_says_what_it_is(tmp_path: Path) -> None:
    """``sorgui analyze -f r.txt`` of sorgui's own text report (and File → Open in the window)
    said "the components of a triple have no labels 'x =', 'y =', 'z ='"."""
    report = tmp_path / "r.txt"
    assert sorgui("analyze", "x^2+y^2-z", "-o", str(report)).returncode == 0
    done = sorgui("analyze", "-f", str(report))
    assert done.returncode == 2
    assert "this is sorgui's text report, which is not read back: open its JSON report" in done.stderr


def test_a_brep_file_in_other_units_says_it_holds_none(tmp_path: Path) -> None:
    """A .brep file has no unit: written with ``--units in`` it read back as millimetres, where
    the STEP and IGES files of the same part say inches, and nothing was said."""
    pytest.importorskip("OCP")
    torus = "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)"
    done = sorgui("analyze", torus, "--recognition-only", "--units", "in", "-o", str(tmp_path / "t.brep"))
    assert done.returncode == 0
    assert "a .brep file holds no unit: its lengths are inches (--units in)" in lines(done.stderr)[-1]
    plain = sorgui("analyze", torus, "--recognition-only", "-o", str(tmp_path / "t2.brep"))
    assert plain.returncode == 0 and "holds no unit" not in plain.stderr


def test_a_cad_part_with_nothing_in_its_ball_names_the_ball(tmp_path: Path) -> None:
    """A ball of radius 2 about the torus's centre (it touches the tube's inner equator only)
    was refused with "no real points inside the drawn ball": no ball named, no advice."""
    pytest.importorskip("OCP")
    path = tmp_path / "touch.step"
    torus = "(x^2+y^2+z^2+8)^2-36(x^2+y^2)"
    out = sorgui("analyze", "--recognition-only", torus, "--region", "0,0,0,2", "-o", str(path))
    assert out.returncode == 1 and not path.exists()
    assert "no real points inside the ball of radius 2 about (0, 0, 0): give a region that meets it" in out.stderr


def test_a_large_hyperboloid_gets_its_exact_profile(tmp_path: Path) -> None:
    """``x² + y² − z² = 1000²`` was written with a fitted profile (waists 1, 10 and 100 with the
    exact one): the crossings of its hyperbola with the ball were lost to the roots' noise floor."""
    pytest.importorskip("OCP")
    path = tmp_path / "waist.step"
    out = sorgui("analyze", "x^2+y^2-z^2-1000^2", "-o", str(path))
    assert out.returncode == 0, out.stderr
    assert "a surface of revolution of the exact rational profile" in out.stderr
