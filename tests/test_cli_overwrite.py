"""Nothing is overwritten that the user did not name, and nothing is replaced that is not a file.

Real ``sorgui analyze`` processes: the input read on standard input, the input named by ``-f``
met again as the picture a Markdown report writes beside itself, a named pipe and ``/dev/null``
as targets (written in place, never replaced by a regular file), and no temporary file left
behind when the process is ended while it writes.
"""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

SORGUI = [sys.executable, "-m", "sorgui.cli", "analyze"]
EQUATION = "x^2 + y^2 - z\n"


def run(args: list[str], cwd: Path, stdin: object = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*SORGUI, *args], cwd=cwd, stdin=stdin, capture_output=True, text=True, timeout=300)


def test_the_equation_read_on_standard_input_is_not_overwritten(tmp_path: Path) -> None:
    equation = tmp_path / "eq.txt"
    equation.write_text(EQUATION, encoding="utf-8")
    inode = equation.stat().st_ino
    with open(equation, encoding="utf-8") as stdin:
        done = run(["--recognition-only", "-", "-o", "eq.txt"], tmp_path, stdin)
    assert done.returncode == 2 and done.stderr == "sorgui: refusing to overwrite the input file eq.txt\n"
    assert equation.read_text(encoding="utf-8") == EQUATION and equation.stat().st_ino == inode


def test_a_reports_picture_never_replaces_the_input(tmp_path: Path) -> None:
    source = tmp_path / "surf.png"
    source.write_text(EQUATION, encoding="utf-8")  # an equation file that happens to end in .png
    done = run(["--recognition-only", "-f", "surf.png", "-o", "surf.md"], tmp_path)
    assert (
        done.returncode == 2 and "refusing to overwrite the input file surf.png (written beside surf.md)" in done.stderr
    )
    assert source.read_text(encoding="utf-8") == EQUATION and not (tmp_path / "surf.md").exists()


def test_a_reports_picture_replaces_only_a_picture_sorgui_wrote(tmp_path: Path) -> None:
    """``-o r.md`` writes ``r.png`` beside it: a photo of that name is refused (it was replaced
    without a word), sorgui's own picture of an earlier run is replaced, and so is a file the
    user names with ``-o``."""
    photo = tmp_path / "r.png"
    photo.write_bytes(b"my holiday photo")
    args = ["--recognition-only", "x^2 + y^2 - z", "-o", "r.md"]
    done = run(args, tmp_path)
    assert done.returncode == 2, done.stderr
    assert "refusing to overwrite r.png (the picture written beside r.md): it is not a picture sorgui wrote" in (
        done.stderr
    )
    assert photo.read_bytes() == b"my holiday photo" and not (tmp_path / "r.md").exists()
    photo.unlink()
    for _ in range(2):
        done = run(args, tmp_path)
        assert done.returncode == 0, done.stderr
    photo.write_bytes(b"my holiday photo")
    done = run([*args, "-o", "r.png"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert photo.read_bytes().startswith(b"\x89PNG")


def test_a_target_without_a_format_says_how_to_name_one(tmp_path: Path) -> None:
    done = run(["--recognition-only", "x^2 + y^2 - z", "-o", "/dev/null"], tmp_path)
    assert done.returncode == 2 and "of /dev/null (no suffix): give --format FORMAT" in done.stderr
    done = run(["--recognition-only", "x^2 + y^2 - z", "--format", "docx", "-o", "a.txt"], tmp_path)
    assert done.returncode == 2 and "unknown export format 'docx' (--format)" in done.stderr


def test_a_patch_of_a_report_is_refused(tmp_path: Path) -> None:
    """``r.patch.json`` wrote the ordinary report without a word: only CAD files and meshes have
    a patch."""
    done = run(["--recognition-only", "x^2 + y^2 - z", "-o", "r.patch.json"], tmp_path)
    assert done.returncode == 2 and "a .json file has no patch" in done.stderr
    assert not (tmp_path / "r.patch.json").exists()


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs named pipes")
def test_a_named_pipe_is_written_in_place(tmp_path: Path) -> None:
    pipe = tmp_path / "out.json"
    os.mkfifo(pipe)
    reader = subprocess.Popen(["cat", str(pipe)], stdout=subprocess.PIPE, text=True)
    done = run(["--recognition-only", "x^2 + y^2 - z", "-o", "out.json"], tmp_path)
    out, _ = reader.communicate(timeout=60)
    assert done.returncode == 0, done.stderr
    assert stat.S_ISFIFO(pipe.stat().st_mode) and '"is_sor": true' in out


def test_dev_null_stays_a_device(tmp_path: Path) -> None:
    done = run(["--recognition-only", "--format", "json", "x^2 + y^2 - z", "-o", os.devnull], tmp_path)
    assert done.returncode == 0, done.stderr
    assert stat.S_ISCHR(os.stat(os.devnull).st_mode)


def test_a_folder_is_refused(tmp_path: Path) -> None:
    (tmp_path / "out.json").mkdir()
    done = run(["--recognition-only", "x^2 + y^2 - z", "-o", "out.json"], tmp_path)
    assert done.returncode == 2 and "it is a folder" in done.stderr


def test_no_temporary_file_is_left_when_ended_while_writing(tmp_path: Path) -> None:
    """SIGTERM the moment a temporary export file appears: it is removed with the process's exit."""
    left = 0
    for attempt in range(6):
        folder = tmp_path / str(attempt)
        folder.mkdir()
        proc = subprocess.Popen(
            [
                *SORGUI,
                "--recognition-only",
                "x^2 + y^2 - z",
                "-o",
                "a.json",
                "-o",
                "b.txt",
                "-o",
                "c.tex",
                "-o",
                "d.py",
            ],
            cwd=folder,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        deadline = time.monotonic() + 60
        while proc.poll() is None and time.monotonic() < deadline:
            if any(p.name.startswith(".") and ".tmp" in p.name for p in folder.iterdir()):
                proc.send_signal(signal.SIGTERM)
                break
            time.sleep(0.0005)
        proc.communicate(timeout=60)
        left += sum(1 for p in folder.iterdir() if ".tmp" in p.name)
    assert left == 0
