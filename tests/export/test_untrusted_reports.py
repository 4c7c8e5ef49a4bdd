"""Reports are files from elsewhere: a crafted report is refused with one line naming the field,
or, when its text is harmless words, every export shows that text literally and runs nothing.

The crafted reports are built here from a real analysis (the torus, with its parameterizations
and canal families): every string field in turn carries a breakout for one format (Python's
``\"\"\"``, a newline before Maple's ``system(…)``, Mathematica's ``*)``, LaTeX's ``\\write18``,
HTML's ``<script>``). The exported files are run or parsed by their own tools where they are
installed (Python itself, sympy's Mathematica parser, pdflatex).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from sorgui import __version__
from sorgui.engine.results import Analysis
from sorgui.export.files import export_analysis
from sorgui.export.reports import ReportError, read_report
from sorgui.export.text import json_report

MARKER = "PWNED"
BREAKOUTS = {
    ".py": f'""" + __import__("pathlib").Path("{MARKER}").touch() + """ \\',
    ".py.newline": f'"""\nimport pathlib; pathlib.Path("{MARKER}").touch()\n"""',
    ".mpl": f'\nsystem("touch {MARKER}");',
    ".m": f'*) Run["touch {MARKER}"] (*',
    ".tex": "\\immediate\\write18{touch " + MARKER + "}\\input{/etc/hostname}",
    ".md": f"<script>document.title='{MARKER}'</script><img src=x onerror=alert(1)>",
    ".html": f"</p><script>document.title='{MARKER}'</script>",
}


def string_paths(data: Any, path: tuple = ()) -> Iterator[tuple]:
    """The paths of every string in a JSON document (keys and indices)."""
    if isinstance(data, dict):
        for key, value in data.items():
            yield from string_paths(value, (*path, key))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            yield from string_paths(value, (*path, index))
    elif isinstance(data, str):
        yield path


def replaced(data: Any, path: tuple, value: str) -> Any:
    copy = json.loads(json.dumps(data))
    target = copy
    for step in path[:-1]:
        target = target[step]
    target[path[-1]] = value
    return copy


@pytest.fixture(scope="module")
def torus_report(analyses: dict[str, Analysis]) -> dict[str, Any]:
    return json.loads(json_report(analyses["torus"]))


def write(tmp_path: Path, data: Any, name: str = "crafted.sorgui.json") -> Path:
    path = tmp_path / name
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


@pytest.mark.parametrize("suffix", sorted(BREAKOUTS))
def test_every_field_of_a_crafted_report_is_refused_or_shown_literally(
    tmp_path: Path, torus_report, suffix: str
) -> None:
    payload = BREAKOUTS[suffix]
    refused = shown = 0
    for path in string_paths(torus_report):
        if path[0] == "timings" or (len(path) > 1 and path[-2] == "timings"):
            continue
        crafted = write(tmp_path, replaced(torus_report, path, payload))
        try:
            analysis = read_report(crafted)
        except ReportError as exc:
            message = exc.message
            assert "\n" not in message and message.count("is not") >= 1, message
            refused += 1
            continue
        shown += 1
        target = tmp_path / f"export{suffix.removesuffix('.newline')}"
        export_analysis(analysis, target)
        check_literal(target, target.suffix, payload, tmp_path)
    assert refused > 0
    assert shown > 0 or "\n" in payload  # words without a line break are harmless text: shown
    assert not (tmp_path / MARKER).exists()


def check_literal(target: Path, suffix: str, payload: str, folder: Path) -> None:
    """The exported file holds the payload only as text, and its tool runs nothing."""
    text = target.read_text(encoding="utf-8")
    if suffix == ".py":
        done = subprocess.run(
            [sys.executable, "-c", f"import runpy; runpy.run_path({str(target)!r})"],
            cwd=folder,
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert done.returncode == 0, done.stderr[-2000:]
        assert not (folder / MARKER).exists()
    elif suffix == ".mpl":
        assert all(line.startswith("#") for line in text.splitlines() if MARKER in line)
    elif suffix == ".m":
        outside = _without_comments(text)
        assert MARKER not in outside and "Run[" not in outside
        from sympy.parsing.mathematica import parse_mathematica

        for statement in outside.split(";"):
            if statement.strip():
                parse_mathematica(statement.split("=", 1)[1])
    elif suffix == ".tex":
        assert "\\write18" not in text and "\\input{/etc" not in text
        if shutil.which("pdflatex"):
            done = subprocess.run(
                ["pdflatex", "-no-shell-escape", "-interaction=nonstopmode", "-halt-on-error", target.name],
                cwd=folder,
                capture_output=True,
                text=True,
                timeout=180,
            )
            assert done.returncode == 0, done.stdout[-2000:]
            assert not (folder / MARKER).exists()
    else:
        assert "<script>" not in text and "<img" not in text


def _without_comments(text: str) -> str:
    """Mathematica source with its ``(* … *)`` comments removed (they do not nest in sorgui's files)."""
    out, depth, i = [], 0, 0
    while i < len(text):
        if text.startswith("(*", i):
            depth, i = depth + 1, i + 2
        elif text.startswith("*)", i) and depth:
            depth, i = depth - 1, i + 2
        else:
            if not depth:
                out.append(text[i])
            i += 1
    return "".join(out)


@pytest.mark.parametrize(
    ("where", "value", "named"),
    [
        (("parametrizations", 0, "parameters", 0), "s); import os; os.system('id')#", "parameters"),
        (("symmetry",), "<b>revolution</b>", "symmetry"),
        (("axis", "point", 0), "((2^10000)^10000)^10000", "axis.point"),
        (("axis", "point", 0), "__import__('os')", "axis.point"),
        (("rationality", "notes", 0), "two\nlines", "rationality.notes"),
        (("field",), "QQ; import os", "field"),
        (("input",), "x^2 + sin(y)", "input"),
        (("canal", "kinds", 0), "wormhole", "canal.kinds"),
    ],
)
def test_a_value_sorgui_does_not_write_is_refused_with_its_field(
    tmp_path: Path, torus_report, where, value, named: str
) -> None:
    crafted = write(tmp_path, replaced(torus_report, where, value))
    with pytest.raises(ReportError) as caught:
        read_report(crafted)
    message = caught.value.message
    assert named in message and "\n" not in message, message


def test_a_report_of_sorgui_reads_back_whole(tmp_path: Path, analyses: dict[str, Analysis]) -> None:
    for name, analysis in analyses.items():
        assert read_report(write(tmp_path, analysis.to_json(), f"{name}.json")) == analysis


@pytest.mark.parametrize(
    "content",
    [
        "[" * 100_000 + "]" * 100_000,
        '{"input": "x", "degree": ' + "9" * 300_000 + "}",
        '{"input": ' + "(" * 50_000 + "x" + ")" * 50_000 + "}",
    ],
)
def test_hostile_json_is_refused_in_one_line(tmp_path: Path, content: str) -> None:
    path = tmp_path / "hostile.json"
    path.write_text(content, encoding="utf-8")
    with pytest.raises(ReportError) as caught:
        read_report(path)
    assert "\n" not in caught.value.message and len(caught.value.message) < 400


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_a_device_is_not_read_whole(device: str) -> None:
    if not Path(device).exists():
        pytest.skip(f"no {device}")
    with pytest.raises(ReportError) as caught:
        read_report(device)
    assert "\n" not in caught.value.message


def _text(data: Any) -> str:
    return json.dumps(data)


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (lambda text: text.replace('"field": "QQ",', '"field": "QQ", "field": "QQ(sqrt(2))",', 1), "occurs twice"),
        (lambda text: text.replace('"degree": 4,', '"degree": NaN,', 1), "NaN is not a number"),
        (
            lambda text: text.replace(f'"sorgui_version": "{__version__}"', '"sorgui_version": "99.0"'),
            "newer than this one",
        ),
        (lambda text: text.replace(f'"sorgui_version": "{__version__}"', '"sorgui_version": 7'), "is not a version"),
        (lambda text: text.replace("{", '{"frobnicate": 1, ', 1), "frobnicate is not a field sorgui writes"),
        (lambda text: text.replace('"is_sor": true', '"is_sor": false', 1), "is_sor is false"),
        (
            lambda text: text.replace('"approximate": null', '"approximate": {"near_sor": true}', 1),
            "its Approximation object lacks 'tolerance'",
        ),
    ],
    ids=["duplicate key", "NaN", "future version", "bad version", "unknown key", "is_sor", "approximate"],
)
def test_a_file_sorgui_did_not_write_is_refused_in_one_line(tmp_path: Path, torus_report, change, words: str) -> None:
    path = tmp_path / "crafted.json"
    path.write_text(change(_text(torus_report)), encoding="utf-8")
    with pytest.raises(ReportError) as caught:
        read_report(path)
    assert words in caught.value.message and "\n" not in caught.value.message, caught.value.message


def test_a_report_carries_the_version_that_wrote_it(torus_report) -> None:
    assert torus_report["sorgui_version"] == __version__


@pytest.mark.parametrize(
    ("where", "value", "named"),
    [
        (("center",), ["10**300", "0", "0"], "center"),
        (("radius_squared",), "10**400", "radius_squared"),
        (("radius_squared",), "I", "radius_squared"),
        (("normal",), ["10**400*x", "0", "1"], "normal"),
        (("profile", "frame_direction"), ["0", "0", "0"], "profile.frame_direction"),
        (("profile", "frame_normal"), ["0", "0", "1"], "profile.frame_normal"),
        (("axis", "direction"), ["0", "I", "1"], "axis.direction"),
        (("profile", "square"), "sin(x) + cos(y)", "profile.square"),
        (("parametrizations", 0, "coordinates", 0), "1/(s**2+1)**5000", "parametrizations[0].coordinates"),
        (("profile", "square"), "(x+y+1)**10000", "profile.square"),
        (("canal", "spine", "radius_squared"), "7", "canal.spine.radius_squared"),
        (("input",), "x^3+y^3+z^3-1", "polynomial"),
    ],
)
def test_a_crafted_value_that_reads_as_formulas_is_refused_before_any_export(
    tmp_path: Path, torus_report, where, value, named: str
) -> None:
    """The probes that used to pass the checks and then fail in CAD, hang in Open CASCADE, or run
    out of memory: each refused at once, in one line naming its field."""
    data = torus_report
    if where == ("center",) or where == ("radius_squared",):
        from sorgui.engine import analyze

        data = json.loads(json_report(analyze("x^2 + y^2 + z^2 - 4")))
    if where == ("normal",):
        from sorgui.engine import analyze

        data = json.loads(json_report(analyze("3x - 4y + z - 7")))
    crafted = write(tmp_path, replaced(data, where, value))
    with pytest.raises(ReportError) as caught:
        read_report(crafted)
    message = caught.value.message
    assert named in message and "\n" not in message, message


def test_a_parts_report_is_said_to_be_one(tmp_path: Path) -> None:
    """The JSON of ``sorgui analyze PART.step`` given to ``sorgui open``: it said "not a sorgui
    report (missing or bad 'polynomial')", although sorgui wrote it."""
    path = tmp_path / "part.json"
    path.write_text(
        json.dumps({"sorgui_version": "0.1.0", "file": "mixed.step", "format": "STEP", "units": "mm", "faces": []}),
        encoding="utf-8",
    )
    with pytest.raises(ReportError, match=r"is the report of the faces of a CAD part \(mixed.step"):
        read_report(path)
