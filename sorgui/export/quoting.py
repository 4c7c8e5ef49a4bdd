"""Each file format's own quoting of text that came from elsewhere.

A report read from a file is validated (:mod:`.validation`), and every exporter writes values
through these as well, so that no text can leave its place in the file: a Python string
literal (``repr``) for docstrings, one line for a comment (``#`` in Python and Maple, ``(* *)``
in Mathematica), HTML's entities for Markdown and HTML, and a code fence longer than any run of
backticks inside it.
"""

from __future__ import annotations

import html
import re
import unicodedata

_BREAKING = frozenset({"Cc", "Cf", "Zl", "Zp"})


def one_line(text: str) -> str:
    """``text`` with every control, format and line-breaking character replaced by a space: it
    cannot end the line of a comment it is written on."""
    return "".join(" " if unicodedata.category(char) in _BREAKING else char for char in text)


def python_literal(text: str) -> str:
    """A Python string literal that reads back as ``text`` and can hold anything."""
    return repr(text)


def mathematica_comment(text: str) -> str:
    """``(* text *)`` with the comment's own delimiters broken apart inside."""
    return "(* " + one_line(text).replace("*)", "* )").replace("(*", "( *") + " *)"


def hash_comment(text: str) -> str:
    """``# text`` on one line (Python, Maple)."""
    return "# " + one_line(text)


def markup_text(text: str) -> str:
    """Words for Markdown or HTML (never inside an attribute): ``&``, ``<``, ``>`` as entities, on one line, so
    that no markup of a report's text is taken as markup."""
    return html.escape(one_line(text), quote=False)


def code_fence(text: str) -> str:
    """A Markdown fence longer than every run of backticks in ``text``."""
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    return "`" * max(3, longest + 1)
