"""The command line: ``sorgui`` opens the window, ``sorgui analyze`` analyses on the terminal.

Exit status of ``sorgui analyze``: 0 for every analysed input (surface of revolution or not),
2 for bad input or bad use (a one-line message on stderr, no traceback; with ``--json`` an
``error`` object on stdout), 1 when the analysis itself fails or the output cannot be written,
130 on Ctrl+C (``SIGINT``), 128 + N on the signals ``SIGTERM`` and ``SIGHUP``, which end
sorgui cleanly: Singular is killed on the way out (and dies with sorgui even on ``kill -9``).

``--timeout`` bounds the whole analysis; stages not finished by then are reported as
undecided. The analysis runs in a child process (:mod:`sorgui.session.supervised`), which is
killed at the time limit or on a signal even when it is stuck inside one C call, so sorgui
always answers within a second of either. ``--each-line`` analyses one equation per line
(:mod:`sorgui.batch`, JSON Lines).

The engine (sympy, flint, Singular) is imported only once an equation is to be analysed, so
that ``--help`` and bad command lines answer at once.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import os
import signal
import stat
import sys
import time
import unicodedata
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import AbstractContextManager, contextmanager, nullcontext
from dataclasses import dataclass
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any, NoReturn

from sorgui import __version__
from sorgui.launcher import interrupted

if TYPE_CHECKING:
    from sorgui.engine import Analysis

_started: list[float] = []
"""When the command started (``--timeout`` counts from there): the start of this process when
:func:`main` is the program (Python's start-up, reading the input and importing the engine
included), else the call of :func:`main` (a test or a script calling it)."""

DEFAULT_EXAMPLE = "paper-example-1"
DEFAULT_TIMEOUT = 120.0
"""Seconds for the whole analysis of one equation unless ``--timeout`` says otherwise."""
MAX_INPUT = 1_000_000
"""Characters of input read at most (plus one, to tell that there is more); the parser's
``MAX_LENGTH``, repeated here so that reading needs no engine import (a test checks they agree)."""
EXPORT_SUFFIXES = (
    ".json",
    ".txt",
    ".md",
    ".html",
    ".tex",
    ".mpl",
    ".m",
    ".py",
    ".stl",
    ".obj",
    ".ply",
    ".vtp",
    ".step",
    ".stp",
    ".iges",
    ".igs",
    ".brep",
    ".png",
)
"""Suffixes ``-o`` accepts (the keys of ``sorgui.export.formats.FORMATS``; a test checks it)."""
CAD_SUFFIXES = (".step", ".stp", ".iges", ".igs", ".brep")
"""The CAD formats of ``-o`` (``sorgui.cad.CAD_SUFFIXES``; a test checks it)."""
CAD_UNITS = ("mm", "cm", "m", "um", "in", "ft")
"""The units ``--units`` accepts (``sorgui.cad.UNITS``; a test checks it)."""


class UsageError(Exception):
    """Bad command-line use (a missing file, conflicting options, a bad value)."""


class _Terminated(BaseException):
    """``SIGTERM`` or ``SIGHUP`` arrived: unwind (killing Singular) and exit."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line (raised, not printed with the usage)."""

    def error(self, message: str) -> NoReturn:
        raise UsageError(message)


def positive_seconds(text: str) -> float:
    """A time limit: a finite number of seconds greater than 0 (``nan``, ``inf``, 0 and negative
    values are refused)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number of seconds: {text!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"the time limit must be a positive number of seconds, not {text!r}")
    return value


def fit_tolerance(text: str) -> float:
    """A relative fitting tolerance: a finite number in (0, 1)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not (math.isfinite(value) and 0 < value < 1):
        raise argparse.ArgumentTypeError(f"the fitting tolerance must lie between 0 and 1, not {text!r}")
    return value


@dataclass(frozen=True)
class UserRegion:
    """``--region``: where meshes, pictures and CAD files look. One of ``radius`` (the drawn
    ball's, about its automatic centre), ``center`` with ``radius`` (a ball), or ``bounds``
    (a box, ``(xmin, xmax, ymin, ymax, zmin, zmax)``)."""

    radius: float | None = None
    center: tuple[float, float, float] | None = None
    bounds: tuple[float, float, float, float, float, float] | None = None


def region_value(text: str) -> UserRegion:
    """``R``, ``X,Y,Z,R`` or ``XMIN:XMAX,YMIN:YMAX,ZMIN:ZMAX``, every number (a decimal or a
    fraction ``1/3``, as an equation's) finite and each radius and side positive; spaces around
    the numbers, not inside them (``1 2`` was read as 12)."""
    usage = "give R, X,Y,Z,R or XMIN:XMAX,YMIN:YMAX,ZMIN:ZMAX"
    parts = [p.split(":") for p in text.split(",")]
    try:
        numbers = [_region_number(v) for part in parts for v in part]
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"not a region: {text!r} ({usage})") from None
    if not all(map(math.isfinite, numbers)):
        raise argparse.ArgumentTypeError(f"the region's numbers must be finite, not {text!r}")
    if any(abs(v) > REGION_REACH for v in numbers):
        raise argparse.ArgumentTypeError(f"the region's numbers must lie within ±{REGION_REACH:g}, not {text!r}")
    shape = [len(part) for part in parts]
    if shape in ([1], [1, 1, 1, 1]):
        if numbers[-1] <= 0:
            raise argparse.ArgumentTypeError(f"the ball's radius must be positive, not {text!r}")
        _drawable(numbers, [numbers[-1]], text)
        if len(numbers) == 1:
            return UserRegion(radius=numbers[0])
        return UserRegion(radius=numbers[3], center=(numbers[0], numbers[1], numbers[2]))
    if shape == [2, 2, 2]:
        if any(high <= low for low, high in zip(numbers[0::2], numbers[1::2])):
            raise argparse.ArgumentTypeError(f"each side of the box must go from low to high, not {text!r}")
        _drawable(numbers, [high - low for low, high in zip(numbers[0::2], numbers[1::2])], text)
        x0, x1, y0, y1, z0, z1 = numbers
        return UserRegion(bounds=(x0, x1, y0, y1, z0, z1))
    raise argparse.ArgumentTypeError(f"not a region: {text!r} ({usage})")


def _region_number(text: str) -> float:
    """A number of ``--region``: a decimal, or a fraction of decimals (``1/3``, ``-2/7``)."""
    if "/" not in text:
        return float(text)
    from fractions import Fraction  # not at the start of every command

    return float(Fraction(text.strip()))


REGION_REACH = 1e12
"""The largest coordinate or radius ``--region`` takes: beyond it a degree-60 surface's values
leave the range of doubles, and CAD kernels work to a fixed absolute precision."""
REGION_FINENESS = 1e-9
"""A ball's radius or a box's side is at least this fraction of ``max(1, largest |number|)``:
a smaller one cannot be sampled in doubles (``0:1e-300,0:1,0:1``)."""


def _drawable(numbers: list[float], sizes: list[float], text: str) -> None:
    """Refuse a region too small to be drawn beside its own coordinates."""
    least = REGION_FINENESS * max(1.0, *map(abs, numbers))
    if min(sizes) < least:
        raise argparse.ArgumentTypeError(
            f"the region is too small to draw: its radius or sides must be at least {least:.3g}, not {text!r}"
        )


def tolerance_value(text: str) -> float | None:
    """``--tolerance``: ``auto`` (``None``: from the input's printed digits) or a relative
    tolerance strictly between 0 and 1."""
    if text.strip().lower() == "auto":
        return None
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a tolerance: {text!r} (use 'auto' or a number such as 1e-8)") from None
    if not math.isfinite(value) or not 0.0 < value < 1.0:
        raise argparse.ArgumentTypeError(f"the tolerance must be a number between 0 and 1, not {text!r}")
    return value


def positive_int(text: str) -> int:
    """A count of at least 1 (``--jobs``)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, not {value}")
    return value


def analyze_parser() -> argparse.ArgumentParser:
    """The options of ``sorgui analyze`` (the one place that declares them)."""
    parser = _Parser(
        prog="sorgui analyze",
        description="Decide exactly whether f(x, y, z) = 0 is a surface of revolution.",
        epilog="A CAD part in place of the equation (sorgui analyze PART.step; also .stp, .iges, .igs, "
        ".brep): every face recognised (plane, sphere, cylinder, cone, torus, surface of revolution, "
        "extrusion, cone over a curve) and the faces about one axis grouped; --tolerance T is then a "
        "length (default: each face's own tolerance, at least 1e-7 and 1e-9 of the largest coordinate); "
        "-o CANONICAL.step writes the part with its recognised faces on native surfaces, -o REPORT.json "
        "or .txt the report.",
        allow_abbrev=False,
    )
    parser.add_argument(
        "expression", nargs="?", help="the equation (it may start with '-'), or '-' to read standard input"
    )
    parser.add_argument("-f", "--file", type=Path, help="read the equation from a file ('-': standard input)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--recognition-only", action="store_true", help="skip the rationality analysis")
    parser.add_argument(
        "--method",
        choices=("symmetry", "paper"),
        default="symmetry",
        help="symmetry algebra (default, deterministic) or the paper's Algorithm II",
    )
    parser.add_argument(
        "--timeout",
        type=positive_seconds,
        default=DEFAULT_TIMEOUT,
        help=f"time limit of the whole analysis, in seconds (default {DEFAULT_TIMEOUT:g}); "
        "stages not finished are reported as undecided",
    )
    parser.add_argument(
        "--tolerance",
        type=tolerance_value,
        default=None,
        metavar="auto|T",
        help="also ask whether the surface is, within a relative tolerance T (e.g. 1e-8), "
        "a surface of revolution, and find the exact surface it was meant to be; "
        "'auto' (the default) does so whenever the input prints decimals, with the "
        "tolerance their digits give",
    )
    add_export_options(parser)
    parser.add_argument(
        "--each-line",
        action="store_true",
        help="analyse every line of the input (-f FILE or '-') on its own and print JSON Lines; "
        "'#', '//' and '%%' start a comment",
    )
    parser.add_argument(
        "--jobs", type=positive_int, default=None, help="with --each-line: the number of worker processes (default 1)"
    )
    parser.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="with --each-line: analyse the lines on the Dask cluster whose scheduler is at ADDRESS "
        "(tcp://host:8786; default: $DASK_SCHEDULER_ADDRESS unless --jobs is given); needs sorgui[cluster]",
    )
    parser.add_argument(
        "--resume",
        action="store_true",
        help="with --each-line -o RESULTS.jsonl: keep the lines RESULTS.jsonl already holds and analyse the rest",
    )
    return parser


def add_export_options(parser: argparse.ArgumentParser) -> None:
    """The options of the ``-o`` files, the same for ``sorgui analyze`` and ``sorgui open``."""
    parser.add_argument(
        "-o",
        "--output",
        type=Path,
        action="append",
        default=[],
        help="also write the results to a file, in the format its suffix names: reports "
        ".json .txt .md .html; formulas .tex (LaTeX) .mpl (Maple) .m (Mathematica) "
        ".py (NumPy/SymPy); meshes .stl .obj .ply .vtp (NAME.patch.stl: the "
        "parametric patch); CAD files .step .stp .iges .igs .brep (the native surface; "
        "NAME.patch.step: the parameterization's patch; needs sorgui[cad]); .png (a picture); "
        "may be given several times",
    )
    parser.add_argument(
        "--units",
        choices=CAD_UNITS,
        default="mm",
        help="the length unit a STEP or IGES file declares for x, y, z (default mm; numbers are not scaled)",
    )
    parser.add_argument(
        "--fit-tolerance",
        type=fit_tolerance,
        default=None,
        metavar="T",
        help="a CAD file's fitted profile (when it has no exact rational form) stays within T times "
        "the drawn ball's radius (default 1e-7)",
    )
    parser.add_argument(
        "--cap",
        action="store_true",
        help="a CAD file holds the solid f <= 0 inside --region: the part capped by the ball or the box",
    )
    parser.add_argument(
        "--region",
        type=region_value,
        default=UserRegion(),
        metavar="R|X,Y,Z,R|X0:X1,Y0:Y1,Z0:Z1",
        help="where -o meshes, pictures and CAD files look: the drawn ball's radius about its automatic "
        "centre, a ball, or an axis-aligned box (the mesh and the CAD faces are cut to it); default: "
        "a ball chosen from the surface",
    )
    parser.add_argument(
        "--format",
        dest="export_format",
        metavar="FORMAT",
        help="the format of every -o file whatever its suffix (json, md, tex, stl, patch.stl, ...)",
    )


def parse_arguments(parser: argparse.ArgumentParser, argv: Sequence[str]) -> argparse.Namespace:
    """``parser.parse_args`` where an equation starting with ``-`` (``-x^2-y^2+z^2-1``) is the
    expression, not an option: every such argument that is neither an option nor an option's
    value is moved behind ``--``."""
    options = {s: a for a in parser._actions for s in a.option_strings}
    kept: list[str] = []
    expressions: list[str] = []
    rest = iter(argv)
    for arg in rest:
        if arg == "--":
            expressions += rest
        elif len(arg) > 1 and arg.startswith("-") and not _is_option(arg, options):
            expressions.append(arg)
        else:
            action = options.get(arg)
            value = next(rest, None) if action is not None and action.nargs != 0 else None
            if value is None or not value.startswith("-"):
                kept += [arg] if value is None else [arg, value]
            else:  # its value follows, even "-5" or "-1:1,-1:1,0:2", which argparse takes for an option
                kept.append(f"{arg}={value}" if arg.startswith("--") else arg + value)
    args = parser.parse_args([*kept, "--", *expressions] if expressions else kept)
    if getattr(args, "file", None) == Path("-") and args.expression is None:
        args.file, args.expression = None, "-"  # -f - reads standard input, as - does (./- names a file)
    return args


def _is_option(arg: str, options: dict[str, argparse.Action]) -> bool:
    """``--name``, ``--name=value``, ``-f`` or ``-fVALUE`` for a declared option."""
    if arg.split("=", 1)[0] in options:
        return True
    return not arg.startswith("--") and arg[:2] in options


# --- input and output --------------------------------------------------------------------


def read_input(args: argparse.Namespace) -> tuple[str, Path | None]:
    """The equation text (at most :data:`MAX_INPUT` characters) and the file it came from, read
    within the time limit (:func:`_read_within`)."""
    if args.file is not None:
        if args.expression is not None:
            raise UsageError("give either an expression or -f FILE, not both")
        path = args.file
        return _bounded(_read_within(lambda: open(path, "rb"), str(path), args.timeout), str(path)), path
    if args.expression is None:
        from sorgui.examples import example_text

        print(
            "sorgui: no equation given: the paper's Example 1 (give an equation, -f FILE, or - to read standard input)",
            file=sys.stderr,
        )
        return example_text(DEFAULT_EXAMPLE), None
    if args.expression == "-":
        if stdin_closed():
            raise UsageError("standard input is closed (the shell's <&-): nothing to read with -")
        stdin = getattr(sys.stdin, "buffer", None)
        if stdin is None:  # a text stream in its place (a caller of main() in the same process)
            return _bounded(sys.stdin.read(MAX_INPUT + 1), "standard input"), None
        text = _read_within(lambda: nullcontext(stdin), "standard input", args.timeout)
        return _bounded(text, "standard input"), None
    return _bounded(args.expression, "the expression"), None


class InputTimeout(Exception):
    """The equation was not read within the time limit (a named pipe without a writer, a slow
    standard input): the limit counts reading the input (README, "Time limits")."""


def _read_within(opener: Callable[[], AbstractContextManager[IO[bytes]]], source: str, timeout: float) -> str:
    """The text of the stream ``opener`` opens, as UTF-8, read by a thread the command waits for
    until ``timeout`` seconds after its start: opening a named pipe without a writer, or reading
    a slow standard input, blocks in the system call, which no signal handler interrupts
    (``--timeout 3`` waited 200 s for such a pipe). The thread is left blocked: the command ends.
    The same bytes and the same refusal of what is not UTF-8 for a file and standard input."""
    import threading

    read: list[bytes | OSError] = []

    def reader() -> None:
        try:
            with opener() as stream:
                read.append(stream.read(4 * (MAX_INPUT + 1)))  # UTF-8: at most 4 bytes a character
        except OSError as exc:
            read.append(exc)

    worker = threading.Thread(target=reader, name="sorgui input", daemon=True)
    worker.start()
    started = _started[-1] if _started else time.monotonic()
    worker.join(max(0.0, started + timeout - time.monotonic()))
    if not read:
        from sorgui.engine.timelimit import limit_message

        raise InputTimeout(f"{limit_message(timeout)} (while reading the equation from {source})")
    data = read[0]
    if isinstance(data, OSError):
        raise UsageError(f"cannot read {source}: {data.strerror or data}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise UsageError(f"cannot read {source}: {_not_text(exc)}") from None
    nul = data.find(b"\0")
    if nul >= 0:  # /dev/zero is UTF-8: "too long" said nothing of what it is
        raise UsageError(f"cannot read {source}: byte {nul + 1} is a NUL byte: this is not a text file")
    return text


def _not_text(error: UnicodeDecodeError) -> str:
    """Why bytes that are not UTF-8 are no equation, and where."""
    return f"it is not UTF-8 text (byte {error.start + 1} is 0x{error.object[error.start]:02x}): an equation is text"


def _bounded(text: str, source: str) -> str:
    """``text`` within :data:`MAX_INPUT`, without the line breaks that end a file or ``echo``'s
    output (the JSON's ``input`` kept them)."""
    if len(text) > MAX_INPUT:
        raise UsageError(f"{source} is too long (more than {MAX_INPUT:,} characters)")
    return text.rstrip("\r\n")


SIDE_FILES = {".md": ".png"}
"""The file a format writes beside its target (a Markdown report's picture ``NAME.png``)."""


def check_outputs(outputs: Sequence[Path], source: Path | None, fmt: str | None = None, cap: bool = False) -> None:
    """Refuse, before any analysis, ``-o`` targets that cannot be written: an unknown format, a
    missing or read-only folder, a folder or read-only file in the way, the input file itself
    (also when it was read on standard input), a file that is neither a regular file nor a
    character device or a pipe. The file a format writes beside its target (the Markdown
    report's picture) gets the same checks. ``--cap`` (``cap``) needs a CAD file of the
    surface among them: a mesh or a patch was written uncapped without a word."""
    inputs = [os.stat(source)] if source is not None and source.exists() else []
    inputs += _stdin_file()
    for path in outputs:
        if fmt is not None and not fmt.strip(" ."):
            raise UsageError("--format needs the name of a format (json, md, tex, stl, ...)")
        suffix = "." + fmt.lower().lstrip(".").removeprefix("patch.") if fmt else path.suffix.lower()
        if suffix not in EXPORT_SUFFIXES:
            formats = ", ".join(EXPORT_SUFFIXES)
            if fmt:
                raise UsageError(f"unknown export format {fmt!r} (--format); use one of {formats}")
            if not path.suffix:
                raise UsageError(
                    f"unknown export format of {path} (no suffix): give --format FORMAT or a name ending in {formats}"
                )
            raise UsageError(f"unknown export format of {path}; use {formats}")
        if _patch_of_a_report(path, fmt, suffix):
            raise UsageError(
                f"{path}: NAME.patch.FORMAT writes the parameterization's patch as a CAD file or a mesh "
                f"(.step, .stl, ...); a {suffix} file has no patch, name it without '.patch'"
            )
        if suffix in CAD_SUFFIXES and importlib.util.find_spec("OCP") is None:
            from sorgui.cad import INSTALL_HINT

            raise UsageError(f"cannot write {path}: {INSTALL_HINT}")
        side = [path.with_suffix(SIDE_FILES[suffix])] if suffix in SIDE_FILES else []
        if side:
            from sorgui.export.picture import is_sorgui_picture  # a Markdown report's earlier NAME.png
        for target in (path, *side):
            _check_target(target, inputs, beside=path if target is not path else None)
        for picture in side:
            if picture not in outputs and picture.is_file() and not is_sorgui_picture(picture):
                raise UsageError(
                    f"refusing to overwrite {picture} (the picture written beside {path}): it is not a "
                    "picture sorgui wrote; move it, or name it with -o to replace it"
                )
    if cap and not any(_capped(path, fmt) for path in outputs):
        raise UsageError(
            f"--cap applies to CAD files of the surface ({' '.join(CAD_SUFFIXES)}; not a NAME.patch.step "
            "patch): give -o PART.step"
        )


def _patch_of_a_report(path: Path, fmt: str | None, suffix: str) -> bool:
    """Whether ``path`` asks for a patch (``r.patch.json``) in a format that has none: it wrote
    the ordinary report without a word."""
    from sorgui.export.formats import FORMATS, wants_patch

    return wants_patch(path, fmt) and FORMATS[suffix].kind not in ("mesh", "cad")


def _capped(path: Path, fmt: str | None) -> bool:
    """Whether ``--cap`` applies to ``path``: a CAD file of the surface, not of the patch."""
    from sorgui.export.formats import format_of, wants_patch

    return format_of(path, fmt).suffix in CAD_SUFFIXES and not wants_patch(path, fmt)


def _stdin_file() -> list[os.stat_result]:
    """The status of standard input when it is a regular file (``< eq.txt``), to be protected."""
    try:
        status = os.fstat(sys.stdin.fileno())
    except (OSError, ValueError, AttributeError):
        return []
    return [status] if stat.S_ISREG(status.st_mode) else []


def _check_target(path: Path, inputs: list[os.stat_result], beside: Path | None) -> None:
    what = f"{path} (written beside {beside})" if beside is not None else str(path)
    try:
        status = os.stat(path)
    except FileNotFoundError:
        status = None
    except OSError as exc:
        raise UsageError(f"cannot write {what}: {exc.strerror or exc}") from None
    if status is not None and any((status.st_dev, status.st_ino) == (i.st_dev, i.st_ino) for i in inputs):
        raise UsageError(f"refusing to overwrite the input file {what}")
    folder = path.parent
    if not folder.is_dir():
        raise UsageError(f"cannot write {what}: the folder {folder} does not exist")
    if status is not None and stat.S_ISDIR(status.st_mode):
        raise UsageError(f"cannot write {what}: it is a folder")
    if status is not None and not (
        stat.S_ISREG(status.st_mode) or stat.S_ISCHR(status.st_mode) or stat.S_ISFIFO(status.st_mode)
    ):
        raise UsageError(f"cannot write {what}: it is not a regular file")
    if not os.access(folder, os.W_OK | os.X_OK) and (status is None or stat.S_ISREG(status.st_mode)):
        raise UsageError(f"cannot write {what}: permission denied")
    if status is not None and not os.access(path, os.W_OK):
        raise UsageError(f"cannot write {what}: permission denied")


def write_outputs(
    result: Analysis | None,
    outputs: Sequence[Path],
    fmt: str | None = None,
    units: str = "mm",
    fit_tolerance: float | None = None,
    region: UserRegion = UserRegion(),
    deadline: float | None = None,
    report: Path | None = None,
    limit: float | None = None,
    report_line: int | None = None,
    cap: bool = False,
) -> None:
    """Write ``result`` (or the saved report ``report``, read and checked there: the result of
    input line ``report_line`` in a results file of ``--each-line``) to every ``-o`` file,
    atomically, in a child process that is killed at ``deadline`` (``time.monotonic()``) or on a
    signal (:mod:`sorgui.session.export_process`). Each CAD file's content is said on stderr;
    every file is tried, and a file not written raises :class:`_OutputError` naming it (the
    others before it are said on stderr), a refused report :class:`_ReportRefused`."""
    if not outputs:
        return  # nothing to write: the export modules (and numpy) stay unloaded
    failures: list[str] = []
    if result is not None:
        plain = [path for path in outputs if _plain(path, fmt)]
        failures = [reason for path in plain if (reason := _write_plain(result, path, fmt)) is not None]
        outputs = [path for path in outputs if path not in plain]
        if not outputs:
            _raise_failures(failures)
            return
    from sorgui.session.export_process import (
        ExportRequest,
        ExportTarget,
        FileFailed,
        FileWritten,
        ReportRefused,
        export_supervised,
    )

    request = ExportRequest(
        targets=tuple(ExportTarget(str(path), fmt) for path in outputs),
        analysis=result,
        report=None if report is None else str(report),
        report_line=report_line,
        units=units,
        tolerance=fit_tolerance,
        radius=region.radius,
        center=region.center,
        bounds=region.bounds,
        cap=cap,
    )
    for message in export_supervised(request, deadline, limit):
        match message:
            case FileWritten(path, holds) if holds:
                print(f"sorgui: wrote {one_line(path)}: {holds}", file=sys.stderr, flush=True)
            case FileFailed(_, reason):
                failures.append(reason)
            case ReportRefused(reason):
                raise _ReportRefused(reason)
    _raise_failures(failures)


def _plain(path: Path, fmt: str | None) -> bool:
    """Whether ``path`` is a JSON or text report (:data:`~sorgui.export.text.PLAIN_SUFFIXES`)."""
    from sorgui.export.formats import format_of
    from sorgui.export.text import PLAIN_SUFFIXES

    return format_of(path, fmt).suffix in PLAIN_SUFFIXES


def _write_plain(result: Analysis, path: Path, fmt: str | None) -> str | None:
    """Write the JSON or text report ``path`` here, at once (milliseconds, no sympy: the report of
    an analysis that used up its time limit is kept as the terminal shows it); the reason it
    failed, else ``None``."""
    from sorgui.export.atomic import atomic_write_text
    from sorgui.export.formats import format_of
    from sorgui.export.text import json_report, text_report

    writer = json_report if format_of(path, fmt).suffix == ".json" else text_report
    try:
        atomic_write_text(path, writer(result))
    except OSError as exc:
        return f"cannot write {path}: {exc.strerror or exc}"
    return None


def _raise_failures(failures: list[str]) -> None:
    """Say every file not written on stderr, the last as :class:`_OutputError`."""
    for reason in failures[:-1]:
        print(f"sorgui: {one_line(reason)}", file=sys.stderr, flush=True)
    if failures:
        raise _OutputError(failures[-1])


def write_files(args: argparse.Namespace, result: Analysis | None = None, report: Path | None = None) -> None:
    """:func:`write_outputs` with the ``-o`` options of a command line, within its ``--timeout``."""
    write_outputs(
        result,
        args.output,
        args.export_format,
        args.units,
        args.fit_tolerance,
        args.region,
        deadline=export_deadline(args.timeout),
        report=report,
        limit=args.timeout,
        cap=args.cap,
        report_line=getattr(args, "line", None),
    )


def export_deadline(timeout: float) -> float | None:
    """When the ``-o`` files must be written by: ``timeout`` seconds from the command's start,
    less :data:`EXPORT_MARGIN` (the time to end the export process and answer)."""
    if not _started:
        return None
    return _started[-1] + timeout - EXPORT_MARGIN


EXPORT_MARGIN = 0.8
"""Seconds before the user's time limit at which the export process is killed: it is waited for
half a second (its half-written files are then removed), and the answer needs the rest."""


class _ReportRefused(Exception):
    """The report of ``sorgui open REPORT -o FILE`` was refused (unreadable, or its claims fail)."""


class _OutputError(Exception):
    """A result could not be written (a file, or standard output)."""


def emit(text: str) -> None:
    """Write ``text`` and one newline to standard output, flushed, so that a closed pipe or a
    full disk is noticed here (:class:`_OutputError`) and not at exit as a traceback."""
    try:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
        sys.stdout.flush()
    except (OSError, ValueError) as exc:  # ValueError: standard output was closed (>&-)
        _silence_stdout()
        reason = (exc.strerror or str(exc)) if isinstance(exc, OSError) else "standard output is closed"
        raise _OutputError(f"cannot write the output: {reason}") from None


def _silence_stdout() -> None:
    """Point standard output at /dev/null: Python's final flush must not fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass


def fail(message: str, position: int | None, as_json: bool, status: int) -> int:
    """Report an error in one line on stderr (and as an ``error`` object with ``--json``): a
    file name with a newline in it is shown escaped, so the message stays one line."""
    if as_json:
        try:
            emit(json.dumps({"error": {"message": message, "position": position, "exit_status": status}}))
        except _OutputError:
            pass
    try:
        print(f"sorgui: {one_line(message)}", file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass  # stderr is closed or full: the status still says it
    return status


def one_line(text: str) -> str:
    """``text`` with its control characters written as escapes (``\\n``)."""
    return "".join(repr(char)[1:-1] if unicodedata.category(char) in ("Cc", "Zl", "Zp") else char for char in text)


# --- the commands ------------------------------------------------------------------------


def analyze_main(argv: Sequence[str]) -> int:
    """``sorgui analyze``: print the report (or JSON) of one equation, or of each line."""
    as_json = "--json" in argv
    try:
        args = parse_arguments(analyze_parser(), argv)
        part = part_source(args)
        if part is not None:
            return part_main(args, part)
        _check_file_options(args)
        if args.each_line:
            return each_line(args)
        for option, given in (("--jobs", args.jobs), ("--scheduler", args.scheduler), ("--resume", args.resume)):
            if given:
                raise UsageError(f"{option} applies to --each-line only (one equation per line of -f FILE or -)")
        text, source = read_input(args)
        check_outputs(args.output, source, args.export_format, args.cap)
    except UsageError as exc:
        return fail(str(exc), None, as_json, 2)
    except InputTimeout as exc:
        return fail(str(exc), None, as_json, 1)
    except _OutputError as exc:
        return fail(str(exc), None, False, 1)
    from sorgui.session.messages import Failed, Finished, Invalid
    from sorgui.session.supervised import AnalysisRequest, analyze_supervised

    answer = analyze_supervised(
        AnalysisRequest(
            text,
            method=args.method,
            recognition_only=args.recognition_only,
            tolerance=args.tolerance,
            timeout=args.timeout,
        ),
        started=_started[-1] if _started else None,
    )
    match answer:
        case Invalid(message, position):
            return fail(message + _file_hint(args), position, args.json, 2)
        case Failed(message):
            return fail(message, None, args.json, 1)
        case Finished(result):
            pass
        case _:
            return fail("the analysis was cancelled", None, args.json, 1)
    unwritten = None
    try:
        write_files(args, result)
    except _OutputError as exc:
        unwritten = str(exc)  # the answer is still printed: nothing of the analysis is lost
    try:
        from sorgui.export.text import json_report, text_report  # what -o writes to .json and .txt

        emit(json_report(result) if args.json else text_report(result))
    except _OutputError as exc:
        return fail(str(exc), None, False, 1)
    return 0 if unwritten is None else fail(unwritten, None, False, 1)


def _file_hint(args: argparse.Namespace) -> str:
    """When the expression that is no polynomial names a file (``sorgui analyze part.txt``),
    how to read it: the equation is given as ``-f FILE``."""
    text = args.expression
    if args.file is not None or text in (None, "-") or len(text) > 4096 or "\n" in text:
        return ""
    try:
        named = Path(text).is_file()
    except (OSError, ValueError):
        return ""
    return f"; {text} is a file: give -f {text} to read the equation in it" if named else ""


def part_source(args: argparse.Namespace) -> Path | None:
    """The CAD part to analyse, when the input (``-f FILE`` or the expression) names one by its
    suffix (``PART.step``, ``.stp``, ``.iges``, ``.igs``, ``.brep``, any case)."""
    if args.file is not None:
        return args.file if args.file.suffix.lower() in CAD_SUFFIXES else None
    if args.expression is None or args.expression == "-" or "\n" in args.expression:
        return None
    path = Path(args.expression)
    return path if path.suffix.lower() in CAD_SUFFIXES else None


PART_OUTPUTS = (*CAD_SUFFIXES, ".json", ".txt")
"""What ``-o`` writes for a part: the canonical part (CAD), the report (JSON, text)."""


def part_main(args: argparse.Namespace, source: Path) -> int:
    """``sorgui analyze PART.step``: the faces of a CAD part (:mod:`sorgui.session.part_job`),
    the report on standard output and every ``-o`` file."""
    try:
        for option, given in (
            ("--each-line", args.each_line),
            ("--format", args.export_format),
            ("--region", args.region != UserRegion()),
            ("--recognition-only", args.recognition_only),
            ("--fit-tolerance", args.fit_tolerance),
        ):
            if given:
                raise UsageError(f"{option} does not apply to a CAD part")
        if args.file is not None and args.expression is not None:
            raise UsageError("give either an expression or -f FILE, not both")
        inputs = [os.stat(source)] if source.exists() else []
        for path in args.output:
            if path.suffix.lower() not in PART_OUTPUTS:
                raise UsageError(f"cannot write {path} for a part; use {', '.join(PART_OUTPUTS)}")
            _check_target(path, inputs, beside=None)
    except UsageError as exc:
        return fail(str(exc), None, args.json, 2)
    from sorgui.session.part_job import PartRequest, analyse_part_supervised

    canonical = tuple(str(p) for p in args.output if p.suffix.lower() in CAD_SUFFIXES)
    request = PartRequest(str(source), args.tolerance, canonical)
    answer = analyse_part_supervised(request, args.timeout, started=_started[-1] if _started else None)
    if answer.report is None:
        return fail(answer.error or "the part could not be analysed", None, args.json, 2 if answer.bad_input else 1)
    from sorgui.cad.part_report import text_report, unevaluated_words
    from sorgui.export.atomic import atomic_write_bytes, atomic_write_text

    data = json.dumps(answer.report.to_json(), indent=1)
    try:
        for path in args.output:
            try:
                if path.suffix.lower() in CAD_SUFFIXES:
                    written = next(f for f in answer.files if f.path == str(path))
                    atomic_write_bytes(path, written.data)
                    print(f"sorgui: wrote {one_line(str(path))}: {written.holds}", file=sys.stderr)
                else:
                    atomic_write_text(
                        path, data + "\n" if path.suffix.lower() == ".json" else text_report(answer.report) + "\n"
                    )
            except OSError as exc:
                raise _OutputError(f"cannot write {path}: {exc.strerror or exc}") from None
        emit(data if args.json else text_report(answer.report))
    except _OutputError as exc:
        return fail(str(exc), None, False, 1)
    unevaluated = unevaluated_words(answer.report)
    if unevaluated is not None:
        print(f"sorgui: {one_line(unevaluated)}", file=sys.stderr)
    return 0


def file_options_given(args: argparse.Namespace) -> list[str]:
    """The options of ``-o`` files given on the command line (:func:`add_export_options`)."""
    return [
        name
        for name, on in (
            ("--format", args.export_format is not None),
            ("--fit-tolerance", args.fit_tolerance is not None),
            ("--cap", args.cap),
            ("--region", args.region != UserRegion()),
            ("--units", args.units != "mm"),
        )
        if on
    ]


def _check_file_options(args: argparse.Namespace) -> None:
    """The options of ``-o`` files (formats, CAD) need a file of one equation: without ``-o``,
    or with ``--each-line`` (its ``-o`` is the JSON Lines of the results), they would be
    ignored, so they are refused in one line; so is ``--each-line -o`` of an export format."""
    given = file_options_given(args)
    if given and args.each_line:
        raise UsageError(f"{given[0]} applies to the -o files of one equation, not to --each-line")
    if given and not args.output:
        raise UsageError(f"{given[0]} applies to -o files: give -o FILE")
    suffix = Path(args.output[0]).suffix.lower() if args.each_line and args.output else ""
    if suffix in EXPORT_SUFFIXES and suffix != ".json":  # .json: the batch names .jsonl itself
        raise UsageError(
            f"--each-line writes JSON Lines, one object per line, not a {suffix} file: name the results "
            f"file {Path(args.output[0]).with_suffix('.jsonl').name}"
        )


def each_line(args: argparse.Namespace) -> int:
    """``--each-line``: the lines of ``-f FILE`` or standard input, read as they are analysed,
    to standard output or ``-o RESULTS.jsonl`` (:mod:`sorgui.batch`); each line may be as long
    as one equation (:data:`MAX_INPUT`)."""
    from sorgui.batch import BatchError, run_each_line

    if args.file is None and stdin_closed():
        raise UsageError("standard input is closed (the shell's <&-): give -f FILE")
    try:
        return run_each_line(args, emit, MAX_INPUT)
    except BatchError as exc:
        if exc.status == 2:
            raise UsageError(str(exc)) from None
        return fail(str(exc), None, False, exc.status)


def gui_main(argv: Sequence[str]) -> int:
    """``sorgui [FILE]``: the window."""
    parser = _Parser(
        prog="sorgui",
        description="sorgui: surfaces of revolution, exactly.",
        epilog="Use 'sorgui analyze --help' for the command line, 'sorgui open --help' for a saved report "
        "(shown in the window, or its files written with -o).",
    )
    parser.add_argument("file", nargs="?", help="an equation file to open")
    parser.add_argument("--version", action="version", version=f"sorgui {__version__}")
    try:
        args = parser.parse_args(argv)
    except UsageError as exc:
        return fail(str(exc), None, False, 2)
    if args.file is not None and not Path(args.file).exists():
        commands = ", ".join(sorted(COMMANDS))
        words = f"no such file or command: {args.file} (the commands are {commands}; see sorgui --help)"
        return fail(words, None, False, 2)
    return _window(args.file)


def _window(path: str | None, report: Analysis | None = None, line: int | None = None) -> int:
    """The window with ``path`` (the ``report`` it holds, read and checked already; that of input
    ``line`` of a batch's results file), or one line and status 1 when there is no display to
    show it on."""
    problem = display_problem(os.environ, sys.platform)
    if problem is not None:
        return fail(f"the window needs a display: {problem}", None, False, 1)
    with signals_held():  # run_gui lets them through once its own handlers are in place
        from sorgui.gui.app import run_gui

        return run_gui(path, report, line)


@contextmanager
def signals_held() -> Iterator[None]:
    """Ctrl+C, ``SIGTERM`` and ``SIGHUP`` wait while inside and are delivered on leaving (or
    when the code inside unblocks them). PySide6 runs Python code inside its C++, as its modules
    load (shiboken6's signature module) and whenever it first makes an enum: the exception
    that :func:`ending_signals` raises either aborts the process there ("libshiboken/signature:
    could not initialize", SIGABRT and a core dump) or is swallowed with the signal, and the
    window then opened and stayed (both seen with a SIGTERM in the window's first half-second
    on a loaded machine). The window's own handlers never raise (:class:`sorgui.gui.app.SignalEnding`)."""
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    from sorgui.session.child import ENDING

    previous = signal.pthread_sigmask(signal.SIG_BLOCK, ENDING)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


WINDOWLESS_PLATFORMS = ("offscreen", "minimal", "minimalegl", "vnc")
"""Qt platforms that give no OpenGL window: the 3D view (a ``QOpenGLWidget``) would crash there."""


def display_problem(
    environ: Mapping[str, str], platform: str, opens: Callable[[str], bool] | None = None
) -> str | None:
    """Why the window cannot be shown here (in words), or ``None``: Qt set to a platform without
    OpenGL windows (``QT_QPA_PLATFORM=offscreen``), or on Linux no X display (sorgui's window
    renders through X, also under Wayland), or one that cannot be opened (``opens``: by default
    :func:`x_display_opens`), where Qt would abort with a core dump."""
    opens = x_display_opens if opens is None else opens
    chosen = environ.get("QT_QPA_PLATFORM", "")
    name = chosen.split(":", 1)[0].strip().lower()
    advice = "use 'sorgui analyze' or 'sorgui open REPORT.json -o FILE' on the terminal"
    if name in WINDOWLESS_PLATFORMS:
        return f"QT_QPA_PLATFORM={chosen} has none for its 3D view; unset it, or {advice}"
    if platform.startswith("linux") and name in ("", "xcb"):
        display = environ.get("DISPLAY")
        if not display:
            return f"DISPLAY is not set; run it in a desktop session, or {advice}"
        if not opens(display):
            return (
                f"the X display DISPLAY={display} cannot be opened (no X server there, or one this user may not "
                f"use: an ssh session without X forwarding); run it in a desktop session, or {advice}"
            )
    return None


def x_display_opens(display: str) -> bool:
    """Whether a connection to the X display ``display`` can be made, asked of libxcb, which Qt's
    X platform loads too (``True`` when libxcb cannot be loaded: Qt then says why). Qt aborts the
    process with a core dump on a display it cannot open (``DISPLAY=:99``, exit 134)."""
    import ctypes

    try:
        xcb = ctypes.CDLL("libxcb.so.1")
    except OSError:
        return True
    xcb.xcb_connect.restype = ctypes.c_void_p
    xcb.xcb_connect.argtypes = [ctypes.c_char_p, ctypes.c_void_p]
    xcb.xcb_connection_has_error.argtypes = [ctypes.c_void_p]
    xcb.xcb_disconnect.argtypes = [ctypes.c_void_p]
    saved = os.dup(2)  # libxcb prints its reason ("Authorization required, ...") on standard error
    try:
        with open(os.devnull, "wb") as null:
            os.dup2(null.fileno(), 2)
            connection = xcb.xcb_connect(display.encode(errors="replace"), None)
    finally:
        os.dup2(saved, 2)
        os.close(saved)
    try:
        return bool(connection) and xcb.xcb_connection_has_error(connection) == 0
    finally:
        if connection:
            xcb.xcb_disconnect(connection)


def open_parser() -> argparse.ArgumentParser:
    """The options of ``sorgui open``."""
    parser = _Parser(
        prog="sorgui open",
        description="Show a report saved as JSON (sorgui analyze --json or -o FILE.json, File > Export) "
        "in the window, or with -o write its files, without analysing again; the report's claims "
        "are checked against its polynomial first.",
        allow_abbrev=False,
    )
    parser.add_argument("report", type=Path, help="the JSON report, or a results file of --each-line with --line")
    parser.add_argument(
        "--line",
        type=positive_int,
        default=None,
        metavar="N",
        help="in a results file of analyze --each-line (JSON Lines): the result of input line N",
    )
    parser.add_argument(
        "--timeout",
        type=positive_seconds,
        default=DEFAULT_TIMEOUT,
        help=f"with -o: time limit for reading the report and writing every file, in seconds "
        f"(default {DEFAULT_TIMEOUT:g}); a file not written by then is named and its old one kept",
    )
    add_export_options(parser)
    return parser


def open_main(argv: Sequence[str]) -> int:
    """``sorgui open REPORT.json``: the window with a saved report, shown without recomputing;
    with ``-o FILE`` its files, written without the window (the same checks, the same writers)."""
    try:
        args = open_parser().parse_args(argv)
        if Path(args.report).suffix.lower() in CAD_SUFFIXES:
            raise UsageError(
                f"{args.report} is a CAD part, not a report: 'sorgui analyze {args.report}' reads its surfaces "
                f"('sorgui {args.report}' shows them in the window)"
            )
        if args.output:
            check_outputs(args.output, args.report, args.export_format, args.cap)
        elif file_options_given(args):
            raise UsageError(f"{file_options_given(args)[0]} applies to -o files: give -o FILE")
    except UsageError as exc:
        return fail(str(exc), None, False, 2)
    if args.output:
        try:
            write_files(args, report=args.report)
        except _ReportRefused as exc:
            return fail(str(exc), None, False, 2)
        except _OutputError as exc:
            return fail(str(exc), None, False, 1)
        return 0
    from sorgui.export.reports import ReportError, read_report

    try:
        report = read_report(args.report, args.line)
    except ReportError as exc:
        return fail(exc.message, None, False, 2)
    return _window(str(args.report), report, args.line)  # shown as read here, not read again


COMMANDS: dict[str, Callable[[Sequence[str]], int]] = {"analyze": analyze_main, "open": open_main}
"""Subcommands by name; anything else opens the window."""


@contextmanager
def ending_signals() -> Iterator[None]:
    """``SIGTERM`` and ``SIGHUP`` raise :class:`_Terminated` in the main thread while inside, so
    that the stack unwinds (Singular killed, worker processes ended) before sorgui exits."""

    def terminate(signum: int, _frame: Any) -> None:
        raise _Terminated(signum)

    wanted = [s for s in (getattr(signal, "SIGTERM", None), getattr(signal, "SIGHUP", None)) if s is not None]
    previous = {s: signal.signal(s, terminate) for s in wanted}
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``sorgui`` console script (``argv`` ``None``: this process's own
    arguments; a finished subcommand, or the closed window, then ends the process at once, see
    :func:`_exit_now`)."""
    own_process = argv is None
    _started[:] = [time.monotonic() - (_process_age() if own_process else 0.0)]
    if own_process:
        _usable_streams()
        _writable_caches()
    argv = list(sys.argv[1:] if argv is None else argv)
    command = COMMANDS.get(argv[0]) if argv else None
    try:
        with ending_signals():
            status = command(argv[1:]) if command is not None else gui_main(argv)
    except KeyboardInterrupt:
        status = interrupted()
    except _Terminated as exc:
        status = 128 + exc.signum
    if own_process:
        _exit_now(status)
    return status


def _process_age() -> float:
    """Seconds since this process started (Python's start-up and imports included), so that
    ``--timeout`` counts from when the user ran the command; 0 where the kernel does not say."""
    try:
        fields = Path("/proc/self/stat").read_text(encoding="ascii").rsplit(")", 1)[1].split()
        started = int(fields[19]) / os.sysconf("SC_CLK_TCK")  # field 22: start time since boot
        return max(0.0, time.clock_gettime(time.CLOCK_BOOTTIME) - started)
    except (OSError, ValueError, IndexError, AttributeError):
        return 0.0


def _writable_caches() -> None:
    """Point matplotlib (the typesetting of formulas, the pictures) and Mesa (OpenGL's shader
    cache, the window and the pictures) at a folder they can write when the usual ones
    (``~/.config/matplotlib``, ``~/.cache``) cannot be made: a read-only home would otherwise
    print matplotlib's warning and rebuild its font cache in a new temporary folder every time,
    and Mesa's ``Failed to create …/mesa_shader_cache`` line. The folder is this user's own
    (``sorgui-matplotlib-UID`` in the temporary folder, checked to be a folder owned by the user
    and closed to others), else a new private one."""
    try:
        config = Path(os.environ.get("XDG_CONFIG_HOME") or Path.home() / ".config")
        cache = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    except RuntimeError:  # no home at all
        config = cache = Path("/nonexistent")
    needs = {
        name: folder
        for name, folder in (("MPLCONFIGDIR", config / "matplotlib"), ("MESA_SHADER_CACHE_DIR", cache))
        if name not in os.environ and not _writable_folder(folder)
    }
    if not needs:
        return
    private = _private_folder()
    if private is None:
        return
    if "MPLCONFIGDIR" in needs:
        os.environ["MPLCONFIGDIR"] = str(private)
    if "MESA_SHADER_CACHE_DIR" in needs:
        os.environ["MESA_SHADER_CACHE_DIR"] = str(private / "mesa_shader_cache")


def _writable_folder(folder: Path) -> bool:
    """Whether ``folder`` exists (made if need be) and can be written."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        return os.access(folder, os.W_OK | os.X_OK)
    except (OSError, RuntimeError):
        return False


def _private_folder() -> Path | None:
    """This user's own folder in the temporary folder, else a new private one."""
    import tempfile

    shared = Path(tempfile.gettempdir()) / f"sorgui-matplotlib-{os.getuid()}"
    try:
        shared.mkdir(mode=0o700, exist_ok=True)
        status = os.lstat(shared)
        if stat.S_ISDIR(status.st_mode) and status.st_uid == os.getuid() and not status.st_mode & 0o077:
            return shared
    except OSError:
        pass
    try:
        return Path(tempfile.mkdtemp(prefix="sorgui-matplotlib-"))
    except OSError:
        return None


def stdin_closed() -> bool:
    """Whether standard input is the stand-in :func:`_usable_streams` put for a closed one (a
    closed input read as empty was reported as 'the input is empty')."""
    return getattr(sys.stdin, "name", None) == os.devnull


def _usable_streams() -> None:
    """Standard streams that the shell closed (``<&-``, ``2>&-``) read as empty or discard what is
    written (a closed standard output is still reported, by :func:`emit`); text that the locale's
    encoding cannot hold (``LC_ALL=C``: the ``·`` of the report) is written escaped."""
    for name, mode in (("stdin", "r"), ("stdout", "w"), ("stderr", "w")):
        if getattr(sys, name) is None:
            setattr(sys, name, open(os.devnull, mode, encoding="utf-8"))  # noqa: SIM115 - for the process
            if name == "stdout":
                sys.stdout.close()  # emit() then reports that the output cannot be written
    for stream in (sys.stdout, sys.stderr):
        if not stream.closed and hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="backslashreplace")


def _exit_now(status: int) -> None:
    """End the process without the interpreter's teardown, which spends a quarter of a second
    of CPU freeing sympy's objects (half a second after the window, with Qt's and VTK's: several
    seconds on a loaded machine, after a ``SIGTERM`` too). Everything is written by then: every
    output line was flushed by :func:`emit`, exported files are closed, worker processes are
    joined or killed, the window's settings are synced when it closes."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(status)


if __name__ == "__main__":
    sys.exit(main())
