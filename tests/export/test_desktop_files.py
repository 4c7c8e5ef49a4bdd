"""The desktop files in resources/ and packaging/: validated, complete, installable and removable."""

from __future__ import annotations

import configparser
import os
import shutil
import stat
import struct
import subprocess
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
RESOURCES = ROOT / "resources"
APP_ID = "org.sorgui.Sorgui"
SIZES = (16, 24, 32, 48, 64, 128, 256, 512)
MIME_TYPES = ("text/x-sorgui-equation", "application/x-sorgui-report+json")


def desktop_entry() -> configparser.SectionProxy:
    parser = configparser.ConfigParser(interpolation=None, delimiters=("=",))
    parser.optionxform = str  # keys are case-sensitive
    parser.read(RESOURCES / f"{APP_ID}.desktop", encoding="utf-8")
    return parser["Desktop Entry"]


def test_desktop_entry_names_the_categories_icon_and_file_types() -> None:
    entry = desktop_entry()
    assert entry["Categories"] == "Education;Science;Math;"
    assert entry["Icon"] == APP_ID and entry["Exec"] == "sorgui %f"
    assert entry["MimeType"].split(";")[:-1] == list(MIME_TYPES)
    mime = ET.parse(RESOURCES / f"{APP_ID}.mime.xml").getroot()
    declared = [m.get("type") for m in mime]
    assert declared == list(MIME_TYPES)


@pytest.mark.skipif(
    shutil.which("desktop-file-validate") is None,
    reason="desktop-file-validate is not installed (.ci/run installs desktop-file-utils)",
)
def test_desktop_file_validates() -> None:
    run = subprocess.run(
        ["desktop-file-validate", str(RESOURCES / f"{APP_ID}.desktop")], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 0, run.stdout + run.stderr
    assert "error" not in run.stdout


@pytest.mark.skipif(
    shutil.which("appstreamcli") is None, reason="appstreamcli is not installed (.ci/run installs appstream)"
)
def test_metainfo_validates_and_has_a_screenshot() -> None:
    path = RESOURCES / f"{APP_ID}.metainfo.xml"
    run = subprocess.run(
        ["appstreamcli", "validate", "--no-net", str(path)], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 0, run.stdout + run.stderr
    root = ET.parse(path).getroot()
    assert root.findtext("id") == APP_ID and root.findtext("project_license") == "MIT"
    assert root.find("screenshots/screenshot/image") is not None
    assert (RESOURCES / "screenshots" / "main-window.png").stat().st_size > 10_000


def png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()[:24]
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def test_icon_in_svg_and_every_png_size() -> None:
    svg = ET.parse(RESOURCES / "icons" / f"{APP_ID}.svg").getroot()
    assert svg.tag.endswith("svg") and svg.get("viewBox") == "0 0 256 256"
    for size in SIZES:
        assert png_size(RESOURCES / "icons" / "hicolor" / f"{size}x{size}" / "apps" / f"{APP_ID}.png") == (size, size)


def test_install_and_uninstall_for_the_current_user(tmp_path) -> None:
    executable = tmp_path / "bin" / "sorgui"
    executable.parent.mkdir()
    executable.write_text("#!/bin/sh\n", encoding="utf-8")
    executable.chmod(stat.S_IRWXU)
    data = tmp_path / "share"
    env = {**os.environ, "XDG_DATA_HOME": str(data), "HOME": str(tmp_path)}
    script = ROOT / "packaging" / "install-desktop.sh"
    run = subprocess.run(
        ["bash", str(script), "--exec", str(executable)], env=env, capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stderr
    launcher = data / "applications" / f"{APP_ID}.desktop"
    assert f'Exec="{executable}" %f' in launcher.read_text(encoding="utf-8")
    expected = [
        launcher,
        data / "metainfo" / f"{APP_ID}.metainfo.xml",
        data / "mime" / "packages" / f"{APP_ID}.xml",
        data / "icons" / "hicolor" / "scalable" / "apps" / f"{APP_ID}.svg",
        *[data / "icons" / "hicolor" / f"{s}x{s}" / "apps" / f"{APP_ID}.png" for s in SIZES],
    ]
    assert all(path.is_file() for path in expected)
    run = subprocess.run(["bash", str(script), "--uninstall"], env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert not any(path.exists() for path in expected)
    assert f"removed {len(expected)} files" in run.stdout


def test_pyproject_declares_license_scripts_and_bounds() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert project["license"] == "MIT"
    assert project["scripts"]["sorgui"] == "sorgui.launcher:main"
    assert project["gui-scripts"]["sorgui-gui"] == "sorgui.launcher:main"
    assert all(">=" in requirement for requirement in project["dependencies"])
    assert any(c.startswith("Topic :: Scientific/Engineering :: Mathematics") for c in project["classifiers"])
    assert any(r.startswith("build") for r in project["optional-dependencies"]["test"])
