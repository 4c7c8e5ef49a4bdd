"""The output object of one line of ``--each-line``, and what it counts as in the summary.

A line's object is the report JSON of ``sorgui analyze --json`` (``"sorgui_version"`` and the
analysis: :func:`~sorgui.engine.results.report_json`) with ``"line"`` (its 1-based number),
``"line_hash"`` (:func:`.lines.line_hash`) and ``"options"`` (:func:`options_of`: what
``--resume`` must find the same) in front, or
``{"line", "line_hash", "options", "input", "error": {"message", "position", "exit_status"}}``. The object is made where
the analysis ran (a worker process of this machine, or a Dask worker), so that every way of
running a batch writes the same text.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from .lines import Line

if TYPE_CHECKING:
    from sorgui.session.messages import FinalMessage
    from sorgui.session.supervised import AnalysisRequest

Options = dict[str, Any]

SURFACE_OF_REVOLUTION = "sor"
NOT_SURFACE_OF_REVOLUTION = "not"
NEARLY = "nearly"
ERROR = "error"
UNFINISHED = "unfinished"
KINDS = (SURFACE_OF_REVOLUTION, NOT_SURFACE_OF_REVOLUTION, NEARLY, ERROR, UNFINISHED)
"""What a line counts as in the summary: exactly one of these (an error first, then an
analysis whose time limit came before its verdict, then its verdict, also when a later stage
was left unfinished; rounded input that is not exactly a surface of revolution but within its
rounding of one is "nearly")."""

UNDECIDED = "undecided"
"""The JSON's ``symmetry`` of a recognition that met its time limit (``engine.results.UNDECIDED``,
not imported: the batch's own process does not load the result classes, 15 ms of its start)."""

ANALYSED, FAILED, NOT_A_POLYNOMIAL = 0, 1, 2
"""A line's status; the batch exits with 1 when a line failed, else 2 when a line was not a
polynomial, else 0 (:func:`batch_status`). An error object holds its status as ``"exit_status"``."""


def batch_status(statuses: Iterable[int]) -> int:
    """The exit status of a batch whose lines have ``statuses``."""
    seen = set(statuses)
    return FAILED if FAILED in seen else (NOT_A_POLYNOMIAL if NOT_A_POLYNOMIAL in seen else ANALYSED)


@dataclass(frozen=True, slots=True)
class Answer:
    """One output line: its JSON text (no line break), status and kind."""

    text: str
    status: int
    kind: str


def options_of(request: AnalysisRequest) -> Options:
    """The options a line was analysed with, as its object holds them: what changes its answer."""
    return {
        "method": request.method,
        "recognition_only": request.recognition_only,
        "tolerance": request.tolerance,
        "timeout": request.timeout,
    }


def options_text(options: Options | None) -> str:
    """``options`` as the command line gives them (``--method symmetry --recognition-only``)."""
    if not isinstance(options, dict):
        return "options this version does not record"
    words = [f"--method {options.get('method')}"]
    if options.get("recognition_only"):
        words.append("--recognition-only")
    if options.get("tolerance") is not None:
        words.append(f"--tolerance {options['tolerance']:g}")
    words.append(f"--timeout {options['timeout']:g}" if options.get("timeout") is not None else "no --timeout")
    return " ".join(words)


def answer_of(line: Line, message: FinalMessage, options: Options) -> Answer:
    """The answer for the final message of a line's analysis with ``options``."""
    from sorgui.engine.results import report_json
    from sorgui.session.messages import Failed, Finished, Invalid

    match message:
        case Finished(analysis):
            data = {"line": line.number, "line_hash": line.digest, "options": options, **report_json(analysis)}
            return Answer(json_line(data), ANALYSED, kind_of(data))
        case Invalid(text_of, position):
            return error_answer(line, text_of, NOT_A_POLYNOMIAL, options, position)
        case Failed(reason):
            return error_answer(line, reason, FAILED, options)
    return error_answer(line, "the analysis was cancelled", FAILED, options)


LONG_TEXT = 2048
"""Characters from which :func:`json_line` encodes a text once, however often it occurs."""


def json_line(data: dict[str, Any]) -> str:
    """``json.dumps(data)``, each long text encoded once: a report holds the equation up to five
    times (the input, the polynomial, its factor and that factor's recognition, the square-free
    part), 150 kB each at degree 20, and encoding dominates the time of the whole object. The
    long texts are set aside (one token each), the rest encoded, and each token replaced by its
    text encoded once; were a token written elsewhere than where it was set (it never is), the
    object is encoded whole instead."""
    tokens: dict[str, str] = {}
    uses: dict[str, int] = {}

    def set_aside(value: Any) -> Any:  # noqa: ANN401 - any JSON value
        if isinstance(value, str):
            if len(value) < LONG_TEXT:
                return value
            token = tokens.get(value)
            if token is None:
                token = tokens[value] = f"\0sorgui-text-{len(tokens)}\0"
            uses[token] = uses.get(token, 0) + 1
            return token
        if isinstance(value, dict):
            return {k: set_aside(v) for k, v in value.items()}
        if isinstance(value, list):
            return [set_aside(v) for v in value]
        return value

    skeleton = json.dumps(set_aside(data))
    encoded = [json.dumps(text) for text in tokens]
    pieces = _TOKEN.split(skeleton)  # text, token number, text, …: the skeleton is small
    numbers = pieces[1::2]
    if any(numbers.count(str(i)) != uses[token] for i, token in enumerate(tokens.values())):
        return json.dumps(data)
    pieces[1::2] = [encoded[int(n)] for n in numbers]
    return "".join(pieces)


_TOKEN = re.compile(r'"\\u0000sorgui-text-([0-9]+)\\u0000"')
"""A token of :func:`json_line` as ``json.dumps`` writes it."""


def refused(line: Line, options: Options) -> Answer:
    """The answer of a line refused whole (too long, not text): not a polynomial."""
    assert line.refusal is not None
    return error_answer(line, line.refusal, NOT_A_POLYNOMIAL, options)


def error_answer(line: Line, message: str, status: int, options: Options, position: int | None = None) -> Answer:
    """The error object of a line analysed with ``options``."""
    data = {
        "line": line.number,
        "line_hash": line.digest,
        "options": options,
        "input": line.equation,
        "error": {"message": message, "position": position, "exit_status": status},
    }
    return Answer(json.dumps(data), status, ERROR)


def kind_of(data: dict[str, Any]) -> str:
    """What an output object counts as (:data:`KINDS`)."""
    if "error" in data:
        return ERROR
    if data.get("symmetry") == UNDECIDED:  # the recognition met the time limit: no verdict
        return UNFINISHED
    if data.get("is_sor"):
        return SURFACE_OF_REVOLUTION
    approximate = data.get("approximate")
    return NEARLY if isinstance(approximate, dict) and approximate.get("near_sor") else NOT_SURFACE_OF_REVOLUTION
