"""Report files: Markdown and HTML, and a saved JSON report read back (the JSON and text reports
themselves are :mod:`sorgui.export.text`'s, which needs no sympy).

Markdown and HTML say the same things in the same order — the verdict, the axis, the profile,
the Table 1 row and the genera, the tubular surface, every parameterization with its parameter
domain and the points it misses, the rounded-input verdict when there is one — with formulas as
LaTeX between ``$…$`` (inline) and ``$$…$$`` (display), the delimiters KaTeX's auto-render and
most Markdown viewers understand. A PNG picture of the surface and its axis is added when one is
given (the caller renders it with :func:`sorgui.export.picture.render_png`): beside a Markdown
file as ``NAME.png``, inside an HTML file as a ``data:`` URI, so the HTML is one file.

The reports are tolerant of results added later: top-level keys of the JSON that they do not
know are listed under "Further results" as JSON.
"""

from __future__ import annotations

import base64
import html
import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, BinaryIO

import sympy

from sorgui import __version__
from sorgui.engine.errors import SorguiError
from sorgui.engine.results import VERSION_KEY, Analysis, Canal
from sorgui.engine.stage_results import Rationality
from sorgui.engine.vocabulary import canal_kind
from sorgui.export.cas import LATEX_STYLE, latex_name, verdict
from sorgui.export.formulas import (
    Formula,
    canal_formulas,
    nearest_analysis_formulas,
    nearest_formulas,
    surface_formulas,
)
from sorgui.export.quoting import code_fence, markup_text
from sorgui.export.text import (
    TABLE_1,
    approximation_lines,
    conical_lines,
    parametric_lines,
    symmetry_name,
)

KNOWN_KEYS = frozenset(
    {
        "input",
        "polynomial",
        "field",
        "method",
        "degree",
        "is_sor",
        "symmetry",
        "symmetry_dimension",
        "symmetry_basis",
        "axis",
        "center",
        "normal",
        "direction",
        "profile",
        "factors",
        "squarefree",
        "rationality",
        "parametrizations",
        "timings",
        "approximate",
        "real_locus",
        "unfinished",
        "canal",
        "conical",
        "input_kind",
        "parametric",
    }
)
"""The JSON keys the Markdown and HTML reports present in words."""

DISPLAY_LENGTH = 60
"""LaTeX longer than this is displayed on its own line."""


class ReportError(SorguiError):
    """A file is not a JSON report of sorgui (unreadable, not JSON, or not an analysis)."""


MAX_REPORT_BYTES = 64 * 1024 * 1024
"""A report larger than this is refused before it is decoded (sorgui's largest are a few MB)."""


BATCH_KEYS = ("line", "line_hash", "options")
"""What a line's object of ``sorgui analyze --each-line`` holds beside its report."""


def read_report(path: str | Path, line: int | None = None) -> Analysis:
    """The analysis saved in the JSON report ``path`` (the inverse of :func:`.text.json_report`),
    validated (:func:`sorgui.export.validation.validate`): a report is a file from elsewhere.
    A results file of ``--each-line`` (JSON Lines) gives the object of its input's ``line``
    (:func:`_batch_line`), and a file of one such object that object.

    At most :data:`MAX_REPORT_BYTES` are read (``/dev/zero`` is refused, not read whole)."""
    from sorgui.engine.claims.report import check_report
    from sorgui.engine.errors import ClaimError
    from sorgui.export.validation import ReportInvalid, validate

    try:
        with open(path, "rb") as stream:
            raw = stream.read(MAX_REPORT_BYTES + 1) if line is None else _batch_line(stream, line, path)
    except OSError as exc:
        raise ReportError(f"cannot read {path}: {exc.strerror or exc}") from None
    if len(raw) > MAX_REPORT_BYTES:
        raise ReportError(f"{path} is too large to be a report (more than {MAX_REPORT_BYTES // 2**20} MB)")
    try:
        data = json.loads(raw.decode("utf-8"), object_pairs_hook=_unique_keys, parse_constant=_no_constant)
    except _Duplicate as exc:
        raise ReportError(f"{path} is not a sorgui report: the key {exc.key!r} occurs twice in one object") from None
    except (UnicodeDecodeError, ValueError) as exc:  # JSONDecodeError, and integers too long to read
        if line is None and _is_json_lines(raw):
            raise ReportError(
                f"{path} holds the results of a batch (JSON Lines, one object per line of its input): "
                "give --line N to open the one of input line N"
            ) from None
        raise ReportError(f"{path} is not a JSON report: {_one_line(str(exc))}") from None
    except RecursionError:
        raise ReportError(f"{path} is not a sorgui report: it is nested too deeply") from None
    if not isinstance(data, dict):
        raise ReportError(f"{path} is not a sorgui report: it is not a JSON object")
    if isinstance(data.get("line"), int) and isinstance(data.get("line_hash"), str):  # a batch's line
        if "error" in data:
            message = data["error"].get("message") if isinstance(data["error"], dict) else None
            raise ReportError(f"line {data['line']} of {path} is an error, not an analysis: {_one_line(str(message))}")
        for key in BATCH_KEYS:
            data.pop(key, None)
    if "error" in data and "input" not in data:
        raise ReportError(f"{path} holds an error, not an analysis")
    if isinstance(data.get("faces"), list) and "input" not in data:
        named = data.get("file")
        part = named if isinstance(named, str) else "a CAD file"
        raise ReportError(
            f"{path} is the report of the faces of a CAD part ({_one_line(part)}, sorgui analyze PART.step), not of "
            "an equation: open the part itself to see it (sorgui analyze PART.step, or File → Open in the window)"
        )
    _check_version(data.pop(VERSION_KEY, None), path)
    try:
        analysis = Analysis.from_json(data)
    except (KeyError, TypeError, AttributeError, ValueError) as exc:
        raise ReportError(f"{path} is not a sorgui report ({_missing_words(exc)})") from None
    except RecursionError:
        raise ReportError(f"{path} is not a sorgui report: it is nested too deeply") from None
    try:
        validate(analysis)
    except ReportInvalid as exc:
        raise ReportError(f"{path} is not a valid sorgui report: {exc.message}") from None
    stray = _not_written(data, analysis.to_json(), "")
    if stray is not None:
        raise ReportError(f"{path} is not a valid sorgui report: {stray}")
    try:
        check_report(analysis)
    except ClaimError as exc:
        raise ReportError(f"{path} is refused: its {exc.message}") from None
    return analysis


def _batch_line(stream: BinaryIO, line: int, path: str | Path) -> bytes:
    """The object of input line ``line`` in a results file of ``--each-line``: the file's line
    that starts ``{"line": N,`` (as every one sorgui writes does), found without decoding the
    others; at most :data:`MAX_REPORT_BYTES` of it."""
    prefix = b'{"line": %d,' % line
    for count, raw in enumerate(iter(lambda: stream.readline(MAX_REPORT_BYTES + 1), b"")):
        if raw.startswith(prefix):
            return raw
        if count == 0 and not raw.startswith(b'{"line": '):
            raise ReportError(f"{path} is not a results file of --each-line: --line picks a result of one")
        if len(raw) > MAX_REPORT_BYTES:  # a line this long is no line of a results file: skip its rest
            while raw and not raw.endswith(b"\n"):
                raw = stream.readline(MAX_REPORT_BYTES + 1)
    raise ReportError(f"{path} holds no result of input line {line}")


def _is_json_lines(raw: bytes) -> bool:
    """Whether ``raw`` is a results file of ``--each-line``: more than one line, the first an
    object with ``"line"`` in front."""
    first, _, rest = raw.partition(b"\n")
    return first.startswith(b'{"line": ') and bool(rest.strip())


class _Duplicate(ValueError):
    def __init__(self, key: str) -> None:
        super().__init__(key)
        self.key = key


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """A JSON object whose keys are all different (else the last would silently win)."""
    data: dict[str, Any] = {}
    for key, value in pairs:
        if key in data:
            raise _Duplicate(key)
        data[key] = value
    return data


def _no_constant(name: str) -> None:
    """JSON's ``NaN``, ``Infinity`` and ``-Infinity`` are no numbers sorgui writes."""
    raise ValueError(f"{name} is not a number")


def _check_version(version: Any, path: str | Path) -> None:  # noqa: ANN401 - from the file
    """A report written by a newer sorgui may hold results this one cannot check: refused. A
    report without a version was written before reports carried one."""
    if version is None:
        return
    if not isinstance(version, str) or _VERSION.fullmatch(version) is None:
        raise ReportError(f"{path} is not a sorgui report: its {VERSION_KEY} is not a version")
    if _release(version) > _release(__version__):
        raise ReportError(
            f"{path} was written by sorgui {version}, newer than this one ({__version__}): update sorgui to open it"
        )


_VERSION = re.compile(r"\d{1,6}(\.\d{1,6}){0,3}([.+-]?[A-Za-z0-9.]{0,20})?")


def _release(version: str) -> tuple[int, ...]:
    """The numbers of ``version`` (``0.1.0`` → ``(0, 1, 0)``; a suffix such as ``.dev1`` aside)."""
    numbers = re.match(r"\d+(\.\d+)*", version)
    assert numbers is not None
    return tuple(int(n) for n in numbers.group().split("."))


def _not_written(data: Any, written: Any, where: str) -> str | None:  # noqa: ANN401 - JSON data
    """Where ``data`` (read from a file) holds what sorgui would not write for the analysis it
    decodes to (``written``): a key sorgui does not write (a newer version's, or crafted), or a
    value that disagrees with the rest (a ``spine`` that is not the first family). Keys a report
    of an older version lacks are no fault."""
    if isinstance(data, dict) and isinstance(written, dict):
        for key, value in data.items():
            inner = f"{where}.{key}".lstrip(".")
            if key not in written:
                return f"{inner} is not a field sorgui writes"
            found = _not_written(value, written[key], inner)
            if found is not None:
                return found
        return None
    if isinstance(data, list) and isinstance(written, list):
        if len(data) != len(written):
            return f"{where} does not agree with the rest of the report"
        for i, (a, b) in enumerate(zip(data, written)):
            found = _not_written(a, b, f"{where}[{i}]")
            if found is not None:
                return found
        return None
    return None if data == written else f"{where} does not agree with the rest of the report"


def _missing_words(exc: Exception) -> str:
    """What a report lacks, in words: "its Approximation object lacks 'tolerance', 'kind'", not
    Python's "Approximation.__init__() missing 6 required positional arguments"."""
    text = _one_line(str(exc))
    missing = _MISSING.search(text)
    if missing is not None:
        return f"its {missing.group(1)} object lacks {missing.group(2)}"
    return f"missing or bad {text}"


_MISSING = re.compile(r"(\w+)\.__init__\(\) missing \d+ required (?:positional |keyword-only )?arguments?: (.*)")


def _one_line(text: str) -> str:
    """``text`` on one line of at most 120 characters (a message quoting a file's content)."""
    flat = " ".join(text.split())
    return flat if len(flat) <= 120 else flat[:120] + "…"


@dataclass(frozen=True)
class Block:
    """A piece of a report: ``kind`` is ``"h1"``, ``"h2"``, ``"p"``, ``"math"``, ``"list"``, ``"code"``
    or ``"image"``; ``text`` is words with ``$…$`` formulas (or LaTeX for ``"math"``, or lines for
    ``"list"``)."""

    kind: str
    text: str | tuple[str, ...]


def _inline(latex: str) -> str:
    return f"${latex}$"


def _formula_blocks(formula: Formula) -> list[Block]:
    name = latex_name(formula.name)
    args = "(" + ", ".join(sympy.latex(p) for p in formula.parameters) + ")" if formula.parameters else ""
    if formula.is_vector:
        latex = r"\left(" + ", ".join(sympy.latex(c) for c in formula.value) + r"\right)"
    else:
        latex = sympy.latex(formula.value)
    lhs = name + args
    blocks = [Block("p", formula.description[0].upper() + formula.description[1:] + ":")]
    if len(latex) <= DISPLAY_LENGTH:
        blocks.append(Block("p", _inline(f"{lhs} = {latex}")))
    else:
        blocks.append(Block("math", f"{lhs} = {latex}"))
    if formula.coverage is not None:
        blocks.append(Block("list", tuple(formula.coverage.lines(LATEX_STYLE))))
    return blocks


def canal_blocks(canal: Canal) -> list[Block]:
    """The Canal section (docs/math.md §9): the verdict and kinds, each sphere family in words,
    its formulas (spine, m(t), ρ(t), characteristic circles), the certificate or witness."""
    answer = {True: "a canal surface", False: "not a canal surface", None: "undecided whether canal"}[canal.is_canal]
    blocks = [
        Block("h2", "Canal"),
        Block(
            "p",
            f"The surface is {answer} ({canal.status}). A canal surface is the "
            "envelope of a one-parameter family of spheres: each family below "
            "gives their centres $m$ (the spine) and squared radii $r^2$.",
        ),
    ]
    if canal.kinds:
        blocks.append(Block("p", "Kinds: " + "; ".join(canal_kind(k) for k in canal.kinds) + "."))
    formulas = canal_formulas(canal)
    for i, fam in enumerate(canal.families, 1):
        shape = "on a line" if fam.on_line else ("planar" if fam.planar else "not planar")
        genus = "undecided" if fam.genus is None else str(fam.genus)
        facts = [
            f"spine of degree {fam.degree} ({shape}); SMAT curve of degree {fam.smat_degree} and genus {genus}",
            "radius constant (a pipe)" if fam.pipe else "radius varying",
        ]
        if fam.parametrization is not None:
            facts.append(
                f"rational parameterization $m(t)$, $r^2(t)$ over {fam.field}: "
                + ("verified by substitution" if fam.verified else "NOT verified")
            )
        else:
            facts.append("no rational parameterization of the spine")
        blocks += [Block("p", f"Sphere family {i}:"), Block("list", tuple(facts))]
        for formula in formulas:
            if formula.name.startswith(f"canal{i}") and formula.name[len(f"canal{i}")].isalpha():
                blocks += _formula_blocks(formula)
    for label, evidence in (("Certificate", canal.certificate), ("Witness", canal.witness)):
        if evidence is not None:
            state = "checked" if evidence.verified else "FAILED"
            blocks.append(Block("p", f"{label} ({evidence.method}, {state}): {evidence.statement}"))
    if canal.notes:
        blocks.append(Block("list", tuple(f"note: {n}" for n in canal.notes)))
    return blocks


def _rationality_facts(rat: Rationality) -> tuple[str, ...]:
    """The rationality stage as a list: status, the row of Table 1, the genera and the verdicts."""
    facts = [f"status: {rat.status}"]
    if rat.table_row is not None:
        row = TABLE_1[rat.table_row - 1]
        facts.append(
            f"Table 1, row {rat.table_row}: genus($P$) {row[0]}, genus($P^2$) {row[1]}, "
            f"$X_{{\\mathbb{{C}}}}$ {row[2]}, $X$ {row[3]}"
        )
    genus_p = "reducible" if rat.profile_reducible else rat.genus_profile
    facts.append(f"genus($P$) = {genus_p}, genus($P^2$) = {rat.genus_profile_square}")
    for label, value in (
        ("$X_{\\mathbb{C}}$ rational", rat.complex_rational),
        ("$X$ unirational", rat.unirational),
        ("$X$ rational over the reals", rat.real_rational),
    ):
        facts.append(f"{label}: {'undecided' if value is None else ('yes' if value else 'no')}")
    facts += [f"note: {n}" for n in rat.notes]
    return tuple(facts)


def report_blocks(analysis: Analysis, picture: str | None = None) -> list[Block]:
    """The report as blocks; ``picture`` is the image's address (file name or ``data:`` URI)."""
    rec = analysis.recognition
    blocks = [Block("h1", f"sorgui: {verdict(analysis)}")]
    if analysis.parametric is not None:
        blocks.append(Block("h2", "The given parametrization"))
        blocks.append(Block("list", tuple(line.strip() for line in parametric_lines(analysis))))
    equation = (
        f"Equation: $f(x, y, z) = 0$ of degree {rec.degree} over the field $K$ = "
        f"{analysis.field} (the polynomial is under Formulas)."
        if rec.polynomial
        else f"Equation: the implicit equation is not known (the field $K$ = {analysis.field})."
    )
    blocks.append(Block("p", equation))
    dimension = f" (the symmetry algebra has dimension {rec.symmetry_dimension})" if rec.decided else ""
    blocks.append(Block("p", f"Symmetry: {symmetry_name(rec.symmetry)}{dimension}."))
    locus = analysis.to_json().get("real_locus")
    if locus:
        dimension = f" (dimension {locus['dimension']})" if locus.get("dimension") is not None else ""
        blocks.append(Block("p", f"Real points: {locus['kind']}{dimension}."))
    if analysis.unfinished:
        blocks.append(
            Block("p", "Not finished within the time limit (undecided): " + ", ".join(analysis.unfinished) + ".")
        )
    if picture is not None:
        blocks.append(Block("image", picture))
    if analysis.rationality is not None:
        blocks.append(Block("h2", "Rationality"))
        blocks.append(Block("list", _rationality_facts(analysis.rationality)))
    if analysis.approximate is not None:
        blocks.append(Block("h2", "Rounded input"))
        blocks.append(
            Block(
                "list",
                tuple([line.strip() for line in approximation_lines(analysis, nested=False)]),
            )
        )
        nearest = analysis.approximate.nearest
        exact = nearest.analysis if nearest is not None else None
        if nearest is not None and exact is not None and exact.rationality is not None:
            where = "within" if nearest.within_rounding else "beyond"
            blocks.append(Block("h2", f"Rationality of the nearest exact surface $g$ ({where} the rounding)"))
            blocks.append(Block("list", _rationality_facts(exact.rationality)))
    blocks.append(Block("h2", "Formulas"))
    for formula in surface_formulas(analysis) + nearest_formulas(analysis) + nearest_analysis_formulas(analysis):
        blocks += _formula_blocks(formula)
    if analysis.conical is not None and analysis.conical.kind != "none":
        blocks += [
            Block("h2", "Cone or cylinder"),
            Block("list", tuple(s.strip() for s in conical_lines(analysis.conical))),
        ]
    if analysis.canal is not None:
        blocks += canal_blocks(analysis.canal)
    extra = {k: v for k, v in analysis.to_json().items() if k not in KNOWN_KEYS and v not in (None, [], {})}
    if extra:
        blocks.append(Block("h2", "Further results"))
        blocks.append(Block("code", json.dumps(extra, indent=1)))
    timing = ", ".join(f"{name} {seconds:.3f} s" for name, seconds in analysis.timings)
    blocks.append(Block("p", f"Method: {analysis.method}. Timings: {timing or 'none recorded'}."))
    return blocks


def markdown_report(analysis: Analysis, picture: str | None = None) -> str:
    """The report as Markdown (``picture``: the PNG's file name beside it, if any)."""
    out = []
    for block in report_blocks(analysis, picture):
        if block.kind == "h1":
            out.append(f"# {markup_text(str(block.text))}")
        elif block.kind == "h2":
            out.append(f"## {markup_text(str(block.text))}")
        elif block.kind == "math":
            out.append(f"$$\n{block.text}\n$$")
        elif block.kind == "list":
            out.append("\n".join(f"- {markup_text(line)}" for line in block.text))
        elif block.kind == "code":
            fence = code_fence(str(block.text))
            out.append(f"{fence}json\n{block.text}\n{fence}")
        elif block.kind == "image":
            out.append(f"![The surface and its axis]({block.text})")
        else:
            out.append(markup_text(str(block.text)))
    return "\n\n".join(out) + "\n"


def _html_words(text: str) -> str:
    """Words with ``$…$`` formulas: the words escaped, the formulas kept for KaTeX (escaped too)."""
    parts = text.split("$")
    return "".join(
        markup_text(part) if i % 2 == 0 else f'<span class="math">${markup_text(part)}$</span>'
        for i, part in enumerate(parts)
    )


HTML_STYLE = """body { font-family: sans-serif; max-width: 60em; margin: 2em auto; line-height: 1.5; }
.display { overflow-x: auto; } img { max-width: 100%; } pre { background: #f4f6fa; padding: 1em; }"""


def html_report(analysis: Analysis, png: bytes | None = None) -> str:
    """The report as one HTML file (the picture embedded as a ``data:`` URI)."""
    picture = None if png is None else "data:image/png;base64," + base64.b64encode(png).decode("ascii")
    body = []
    for block in report_blocks(analysis, picture):
        if block.kind in ("h1", "h2"):
            body.append(f"<{block.kind}>{html.escape(str(block.text))}</{block.kind}>")
        elif block.kind == "math":
            body.append(f'<div class="display">$${html.escape(str(block.text))}$$</div>')
        elif block.kind == "list":
            body.append("<ul>" + "".join(f"<li>{_html_words(line)}</li>" for line in block.text) + "</ul>")
        elif block.kind == "code":
            body.append(f"<pre>{html.escape(str(block.text))}</pre>")
        elif block.kind == "image":
            body.append(f'<p><img alt="The surface and its axis" src="{block.text}"></p>')
        else:
            body.append(f"<p>{_html_words(str(block.text))}</p>")
    title = html.escape(f"sorgui: {verdict(analysis)}")
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{title}</title>\n<style>\n{HTML_STYLE}\n</style>\n</head>\n<body>\n"
        + "\n".join(body)
        + "\n</body>\n</html>\n"
    )
