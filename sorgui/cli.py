"""The command line: ``sorgui`` opens the window, ``sorgui analyze`` analyses on the terminal.

Exit status of ``sorgui analyze``: 0 for every analysed input (surface of revolution or not),
2 for bad input (a one-line message on stderr, no traceback; with ``--json`` an ``error``
object on stdout), 1 when the analysis itself fails.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from sorgui.engine import ParseError, SorguiError, analyze
from sorgui.export.files import FORMATS, export_analysis
from sorgui.export.text import format_report

DEFAULT_EXAMPLE = "paper-example-1"


def _analyze_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="sorgui analyze",
        description="Decide exactly whether f(x, y, z) = 0 is a surface of revolution.",
    )
    parser.add_argument("expression", nargs="?", help="the equation, or '-' to read standard input")
    parser.add_argument("-f", "--file", type=Path, help="read the equation from a file")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--recognition-only", action="store_true", help="skip the rationality analysis")
    parser.add_argument("--method", choices=("symmetry", "paper"), default="symmetry",
                        help="symmetry algebra (default, deterministic) or the paper's Algorithm II")
    parser.add_argument("--timeout", type=float, default=60.0, help="time limit per Singular call, in seconds")
    parser.add_argument("-o", "--output", type=Path, action="append", default=[],
                        help="also write the results to a file: .json, .txt, .tex (LaTeX), .mpl (Maple) "
                             "or .m (Mathematica); may be given several times")
    return parser


def _read_input(args: argparse.Namespace) -> str:
    """The equation text from the argument, a file, or standard input."""
    if args.file is not None:
        if args.expression is not None:
            raise _UsageError("give either an expression or -f FILE, not both")
        try:
            return args.file.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as exc:
            raise _UsageError(f"cannot read {args.file}: {exc}") from None
    if args.expression is None:
        from sorgui.examples import example_text

        return example_text(DEFAULT_EXAMPLE)
    if args.expression == "-":
        return sys.stdin.read()
    return args.expression


class _UsageError(Exception):
    """Bad command-line use (a missing file, conflicting options)."""


def _fail(message: str, position: int | None, as_json: bool, status: int) -> int:
    if as_json:
        print(json.dumps({"error": {"message": message, "position": position}}))
    print(f"sorgui: {message}", file=sys.stderr)
    return status


def analyze_main(argv: Sequence[str]) -> int:
    """``sorgui analyze``: print the report (or JSON) of one equation."""
    args = _analyze_parser().parse_args(argv)
    unknown = [str(p) for p in args.output if p.suffix.lower() not in FORMATS]
    if unknown:
        return _fail(f"unknown export format of {', '.join(unknown)}; use {', '.join(FORMATS)}", None, args.json, 2)
    try:
        text = _read_input(args)
        result = analyze(text, method=args.method, recognition_only=args.recognition_only,
                         singular_timeout=args.timeout)
    except _UsageError as exc:
        return _fail(str(exc), None, args.json, 2)
    except ParseError as exc:
        return _fail(str(exc), exc.position, args.json, 2)
    except SorguiError as exc:
        return _fail(exc.message, None, args.json, 1)
    except Exception as exc:  # noqa: BLE001 - a bug must still end in one line, not a traceback
        return _fail(f"internal error ({type(exc).__name__}: {exc}); please report it with the input",
                     None, args.json, 1)
    try:
        for path in args.output:
            export_analysis(result, path)
    except OSError as exc:
        return _fail(f"cannot write {exc.filename}: {exc.strerror}", None, args.json, 2)
    if args.json:
        print(json.dumps(result.to_json(), indent=1))
    else:
        print(format_report(result))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``sorgui`` console script."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] == "analyze":
        return analyze_main(argv[1:])
    parser = argparse.ArgumentParser(prog="sorgui", description="sorgui: surfaces of revolution, exactly.",
                                     epilog="Use 'sorgui analyze --help' for the command line.")
    parser.add_argument("file", nargs="?", help="an equation file to open")
    args = parser.parse_args(argv)
    from sorgui.gui.app import run_gui

    return run_gui(args.file)


if __name__ == "__main__":
    sys.exit(main())
