"""Atomic writes: a failure half-way or a read-only folder leaves the old file as it was."""

from __future__ import annotations

import multiprocessing
import os
import stat
from collections.abc import Iterator

import pytest

from sorgui.export.atomic import atomic_write, atomic_write_bytes, atomic_write_text
from sorgui.export.files import export_analysis

OLD = "the old content\n"


def failing_chunks() -> Iterator[bytes]:
    yield b"half of the new "
    raise RuntimeError("the writer failed half-way")


def test_writer_failing_half_way_leaves_the_old_file(tmp_path) -> None:
    path = tmp_path / "report.txt"
    path.write_text(OLD, encoding="utf-8")
    with pytest.raises(RuntimeError, match="half-way"):
        atomic_write_bytes(path, failing_chunks)
    assert path.read_text(encoding="utf-8") == OLD
    assert os.listdir(tmp_path) == ["report.txt"]  # no temporary file left behind


def test_path_writer_failing_leaves_no_file(tmp_path) -> None:
    def write(temporary):  # noqa: ANN001, ANN202
        temporary.write_text("partial", encoding="utf-8")
        raise OSError(28, "No space left on device")

    with pytest.raises(OSError, match="No space"):
        atomic_write(tmp_path / "mesh.stl", write)
    assert os.listdir(tmp_path) == []


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_folder_leaves_the_old_file(tmp_path) -> None:
    path = tmp_path / "report.txt"
    path.write_text(OLD, encoding="utf-8")
    tmp_path.chmod(stat.S_IRUSR | stat.S_IXUSR)
    try:
        with pytest.raises(PermissionError):
            atomic_write_text(path, "new")
    finally:
        tmp_path.chmod(stat.S_IRWXU)
    assert path.read_text(encoding="utf-8") == OLD


def test_read_only_folder_as_root_too(tmp_path) -> None:
    """Root ignores permission bits, so the read-only folder is a read-only mount's stand-in: the
    replacement fails at the rename (simulated), after the new file was written in full."""
    path = tmp_path / "report.txt"
    path.write_text(OLD, encoding="utf-8")
    real_replace = os.replace

    def refuse(source, target):  # noqa: ANN001, ANN202
        raise PermissionError(13, "Read-only file system", str(target))

    os.replace = refuse
    try:
        with pytest.raises(PermissionError):
            atomic_write_text(path, "new")
    finally:
        os.replace = real_replace
    assert path.read_text(encoding="utf-8") == OLD
    assert os.listdir(tmp_path) == ["report.txt"]


def test_success_replaces_the_file_and_keeps_its_mode(tmp_path) -> None:
    path = tmp_path / "report.txt"
    path.write_text(OLD, encoding="utf-8")
    path.chmod(0o640)
    atomic_write_text(path, "new ✓\n")
    assert path.read_text(encoding="utf-8") == "new ✓\n"
    assert stat.S_IMODE(path.stat().st_mode) == 0o640


def test_export_failing_half_way_leaves_the_old_file(analyses, tmp_path, monkeypatch) -> None:
    path = tmp_path / "torus.tex"
    path.write_text(OLD, encoding="utf-8")

    def broken(_analysis):  # noqa: ANN001, ANN202
        raise OSError(5, "Input/output error")

    monkeypatch.setitem(__import__("sorgui.export.files", fromlist=["TEXT_WRITERS"]).TEXT_WRITERS, ".tex", broken)
    with pytest.raises(OSError):
        export_analysis(analyses["torus"], path)
    assert path.read_text(encoding="utf-8") == OLD


def test_command_line_reports_a_failed_write_in_one_line(tmp_path, monkeypatch, capsys) -> None:
    """The write fails after the command line's checks passed (the rename is refused, as on a
    file system that turned read-only): exit status 1, one line naming the file, old file kept."""
    from sorgui.cli import main
    from sorgui.export import atomic
    from sorgui.session import export_process

    target = tmp_path / "out.json"
    target.write_text(OLD, encoding="utf-8")

    def refuse(source, destination):  # noqa: ANN001, ANN202
        raise PermissionError(13, "Read-only file system", str(destination))

    monkeypatch.setattr(atomic.os, "replace", refuse)
    # the export child must be forked for the refusal to reach it (a test process with threads spawns)
    monkeypatch.setattr(export_process, "quick_context", lambda: multiprocessing.get_context("fork"))
    assert main(["analyze", "--recognition-only", "-o", str(target), "x^2 + y^2 - z^2 - 1"]) == 1
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines == [f"sorgui: cannot write {target}: Read-only file system"]
    assert target.read_text(encoding="utf-8") == OLD
    assert os.listdir(tmp_path) == ["out.json"]


def test_command_line_reports_a_missing_patch_in_one_line(tmp_path, capsys) -> None:
    from sorgui.cli import main

    target = tmp_path / "cubic.patch.stl"  # the cubic has only a complex parameterization
    assert main(["analyze", "-o", str(target), "y^2 + z^2 = x^3 + 3x^2 - 2x"]) == 1
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and str(target) in lines[0] and "no parametric patch" in lines[0]
    assert not target.exists()
