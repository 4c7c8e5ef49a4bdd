"""The words of an export that was ended before it wrote its file (sorgui/session/export_process.py)."""

from __future__ import annotations

from pathlib import Path

from sorgui.session.export_process import _kept


def test_an_export_ended_early_names_an_old_file_only_when_there_is_one(tmp_path: Path) -> None:
    """'--timeout 3 -o new.step' said "(an old file is left as it was)" of a file that had never
    existed."""
    target = tmp_path / "part.step"
    assert _kept(target) == " (no file was written)"
    target.write_text("ISO-10303-21;", encoding="ascii")
    assert _kept(target) == " (the old file is left as it was)"
