"""``sorgui analyze PART.step`` as a user runs it (real processes): the JSON of every face and
group, the text report, ``-o`` canonical parts and reports, bad files and bad use in one line
each with exit status 2, and the time limit."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from sorgui import __version__

pytest.importorskip("OCP")

from sorgui.cad.reading import read_part  # noqa: E402
from sorgui.cad.writers import WRITERS, CadHeader  # noqa: E402

from . import parts  # noqa: E402

SORGUI = [sys.executable, "-m", "sorgui.cli", "analyze"]


def run(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*SORGUI, *args], capture_output=True, text=True, timeout=300, cwd=cwd)


def one_line(err: str) -> str:
    assert err.count("\n") == 1 and err.startswith("sorgui: ") and "Traceback" not in err, err
    return err


@pytest.fixture(scope="module")
def boolean_step(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("parts") / "Boolean Part.STEP"
    path.write_bytes(WRITERS[".step"](parts.boolean_part(), CadHeader("", ("test",), "0", path.name)))
    return path


def test_the_json_of_a_part(boolean_step: Path) -> None:
    done = run(str(boolean_step), "--json")
    assert done.returncode == 0 and done.stderr == ""
    data = json.loads(done.stdout)
    assert list(data)[:2] == ["sorgui_version", "file"] and data["sorgui_version"] == __version__
    assert data["file"] == str(boolean_step) and data["format"] == "STEP" and data["units"] == "mm"
    faces = data["faces"]
    assert [f["face"] for f in faces] == list(range(1, 10))
    assert all(f["type_in_file"] == "B_SPLINE_SURFACE" for f in faces)
    assert sorted(f["kind"] for f in faces) == sorted(["plane"] * 6 + ["cylinder", "torus", "sphere"])
    for face in faces:
        assert face["deviation"] <= face["tolerance"] == 1e-7
        if face["kind"] in ("cylinder", "torus"):
            assert set(face["axis"]) == {"point", "direction"}
    (group,) = data["groups"]
    assert len(group["faces"]) == 4 and set(group["kinds"]) == {"plane", "cylinder", "torus"}


def test_the_text_report_and_the_outputs(boolean_step: Path, tmp_path: Path) -> None:
    canonical, report, text = tmp_path / "canonical.stp", tmp_path / "report.json", tmp_path / "report.txt"
    done = run(str(boolean_step), "-o", str(canonical), "-o", str(report), "-o", str(text))
    assert done.returncode == 0
    assert done.stdout.startswith(f"{boolean_step}: STEP, 9 faces (6 plane, 1 sphere, 1 cylinder, 1 torus)")
    assert "one surface of revolution about the axis through" in done.stdout
    assert text.read_text() == done.stdout
    assert json.loads(report.read_text())["faces"][0]["face"] == 1
    assert one_line(done.stderr) == f"sorgui: wrote {canonical}: 9 faces on native surfaces; valid (BRepCheck)\n"
    again = run(str(canonical), "--json")
    assert {f["source"] for f in json.loads(again.stdout)["faces"]} == {"file"}
    assert len(read_part(canonical).faces) == 9


@pytest.mark.parametrize(
    ("name", "data", "words"),
    [
        ("text.step", b"x^2+y^2-1\n", "is not a STEP file"),
        ("empty.igs", b"", "is empty"),
        ("garbage.brep", b"\x00\x01garbage", "is not a BRep file"),
    ],
)
def test_bad_files_in_one_line(tmp_path: Path, name: str, data: bytes, words: str) -> None:
    path = tmp_path / name
    path.write_bytes(data)
    done = run(str(path))
    assert done.returncode == 2 and done.stdout == "" and words in one_line(done.stderr)
    as_json = run(str(path), "--json")
    assert as_json.returncode == 2 and words in json.loads(as_json.stdout)["error"]["message"]


def test_a_truncated_part_and_a_missing_one(boolean_step: Path, tmp_path: Path) -> None:
    cut = tmp_path / "cut.step"
    cut.write_bytes(boolean_step.read_bytes()[:5000])
    done = run(str(cut))
    assert done.returncode == 2 and "truncated" in one_line(done.stderr) and done.stdout == ""
    missing = run(str(tmp_path / "missing.stp"))
    assert missing.returncode == 2 and "No such file" in one_line(missing.stderr)


def test_a_part_with_no_faces(boolean_step: Path, tmp_path: Path) -> None:
    """A STEP file of no entities, and one whose every surface entity is of an unknown type (so
    that Open CASCADE leaves the faces out): one line each, saying why, exit status 2."""
    empty = tmp_path / "nothing.step"
    empty.write_bytes(b"ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n")
    done = run(str(empty))
    assert done.returncode == 2 and done.stdout == ""
    assert one_line(done.stderr) == f"sorgui: {empty} holds no faces (no surface to analyse)\n"
    unknown = tmp_path / "unknown.step"
    unknown.write_bytes(
        boolean_step.read_bytes().replace(b"B_SPLINE_SURFACE_WITH_KNOTS", b"B_SPLINE_SURFACE_WITH_NOTS")
    )
    done = run(str(unknown))
    assert done.returncode == 2 and done.stdout == ""
    assert f"sorgui: {unknown} holds no faces: " in one_line(done.stderr) and "faulty and left out" in done.stderr


def test_the_parser_s_words_are_a_user_s(tmp_path: Path) -> None:
    """Bytes after a STEP file's first line: where the parser stopped, in words, not its tokens."""
    path = tmp_path / "noise.step"
    path.write_bytes(b"ISO-10303-21;\n" + bytes(range(256)) * 40)
    done = run(str(path))
    err = one_line(done.stderr)
    assert done.returncode == 2 and "is not a readable STEP file" in err and "QUID" not in err, err


def test_a_number_beyond_any_length_is_refused_at_once(boolean_step: Path, tmp_path: Path) -> None:
    """A coordinate of 1e400 (infinite as a double): Open CASCADE's transfer would run until the
    time limit; the file is refused in one line before it, with the number and its line."""
    data = boolean_step.read_bytes()
    start = data.index(b"CARTESIAN_POINT('',(") + len(b"CARTESIAN_POINT('',(")
    path = tmp_path / "infinite.step"
    path.write_bytes(data[:start] + b"1.E+400," + data[data.index(b",", start) + 1 :])
    line = data[:start].count(b"\n") + 1
    done = run(str(path), "--timeout", "60")
    assert done.returncode == 2 and done.stdout == ""
    assert one_line(done.stderr) == (
        f"sorgui: {path} holds a number beyond 1e200 (1.E+400 at line {line}): no part has such a length\n"
    )


def test_a_face_open_cascade_cannot_evaluate(tmp_path: Path) -> None:
    """Its own line in the report, the other faces recognised, one line on standard error, exit
    status 0 (the report is whole); the canonical part is still written."""
    path = tmp_path / "broken.brep"
    path.write_bytes(WRITERS[".brep"](parts.unevaluable(), CadHeader("", (), "0", path.name)))
    canonical = tmp_path / "canonical.brep"
    done = run(str(path), "-o", str(canonical))
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == f"{path}: BRep, 2 faces (1 revolution, 1 none), lengths in mm"
    assert "a surface of revolution about the axis" in lines[1]
    assert (
        lines[2].startswith("face   2  OFFSET_SURFACE ")
        and "cannot be evaluated: Open CASCADE raises Geom_Undefined" in lines[2]
    )
    err = done.stderr.splitlines()
    assert len(err) == 2 and err[0].startswith(f"sorgui: wrote {canonical}: 1 face on native surfaces")
    assert err[1].startswith(f"sorgui: {path}: face 2 of 2 cannot be evaluated (Open CASCADE raises Geom_Undefined")
    (_, broken) = json.loads(run(str(path), "--json").stdout)["faces"]
    assert broken["kind"] == "none" and broken["type_in_file"] == "OFFSET_SURFACE"
    assert broken["error"].startswith("Open CASCADE raises Geom_Undefined")
    assert len(read_part(canonical).faces) == 2


def test_bad_use_in_one_line(boolean_step: Path, tmp_path: Path) -> None:
    mesh = run(str(boolean_step), "-o", str(tmp_path / "part.stl"))
    assert mesh.returncode == 2 and "cannot write" in one_line(mesh.stderr)
    unknown = run(str(boolean_step), "-o", str(tmp_path / "part.xyz"))
    assert unknown.returncode == 2 and "cannot write" in one_line(unknown.stderr) and ".step" in unknown.stderr
    lines = run(str(boolean_step), "--each-line")
    assert lines.returncode == 2 and "--each-line does not apply to a CAD part" in one_line(lines.stderr)
    region = run(str(boolean_step), "--region", "3")
    assert region.returncode == 2 and "--region does not apply to a CAD part" in one_line(region.stderr)
    itself = run(str(boolean_step), "-o", str(boolean_step))
    assert itself.returncode == 2 and "refusing to overwrite the input file" in one_line(itself.stderr)


def test_the_tolerance_is_a_length(tmp_path: Path) -> None:
    path = tmp_path / "noisy.brep"
    path.write_bytes(WRITERS[".brep"](parts.noisy(parts.revolved_spline(), 1e-4), CadHeader("", (), "0", "n")))
    strict = json.loads(run(str(path), "--json").stdout)["faces"][0]
    loose = json.loads(run(str(path), "--json", "--tolerance", "1e-3").stdout)["faces"][0]
    assert (strict["kind"], loose["kind"]) == ("none", "revolution")
    assert loose["tolerance"] == 1e-3


def test_the_time_limit(tmp_path: Path) -> None:
    path = tmp_path / "shaft.step"
    path.write_bytes(WRITERS[".step"](parts.turned_part(), CadHeader("", (), "0", "shaft.step")))
    done = run(str(path), "--timeout", "0.5")
    assert done.returncode == 1 and "did not finish within 0.5 s" in one_line(done.stderr)


def test_the_part_route_loads_no_sympy_and_no_vtk(boolean_step: Path) -> None:
    """Reading, recognising and rewriting a part needs neither sympy nor the render layer (VTK):
    the command pays only for Open CASCADE (docs/benchmarks.md, the 50-face part)."""
    code = (
        "import sys, json; from sorgui.session.part_job import PartRequest, run_part; "
        f"answer = run_part(PartRequest({str(boolean_step)!r}, canonical=('c.step',))); "
        "assert answer.report is not None and answer.files[0].valid; print(json.dumps(sorted(sys.modules)))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True)
    modules = {m.split(".")[0] for m in json.loads(done.stdout)}
    assert not modules & {"sympy", "mpmath", "vtkmodules", "pyvista"}, sorted(modules)
