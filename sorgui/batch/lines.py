"""The input of ``--each-line``: its lines, read as bytes a line at a time, in bounded memory.

Every line that holds an equation (``#``, ``//`` and ``%`` start a comment; blank lines are skipped) becomes one
:class:`Line`: its 1-based number, the equation, and :func:`line_hash`, the hash by which
``--resume`` recognises a line already done. A line that cannot be analysed is refused whole
(:attr:`Line.refusal`) and the batch goes on: a line longer than the limit of one equation
(however it ends: 3 MB of spaces and then an equation is refused, not read as its first
megabyte), a line that is not UTF-8. Only the first ``4·limit`` bytes of a line are ever held;
the rest of a long line is read in pieces, hashed and dropped. A NUL byte means the input is
not text (``-f /dev/zero`` is one endless line of them): its line is refused and the reader
stops, saying why (:attr:`LineReader.stopped`).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, BinaryIO

try:
    from _blake2 import blake2b  # hashlib's own BLAKE2: importing hashlib loads OpenSSL (2.5 ms of a batch's start)
except ImportError:  # another Python than CPython
    from hashlib import blake2b

SHOWN = 60
"""Characters of a refused line repeated in its error object (its beginning, then ``…``)."""
SKIP_CHUNK = 1 << 20
"""Bytes read at a time from the part of a long line that is skipped."""


@dataclass(frozen=True, slots=True)
class Line:
    """One line of the input that gives one output object."""

    number: int
    equation: str
    """The text to analyse (the line without its comment and surrounding blanks), or for a
    refused line its beginning, as shown in the error object."""
    digest: str
    """:func:`line_hash` of the line."""
    refusal: str | None = None
    """Why the line is refused whole, in words; ``None`` for a line to analyse."""


def line_hash(data: bytes) -> str:
    """The hash of a line's bytes (without its line break), as the JSON's ``line_hash`` holds it:
    BLAKE2b with a 16-byte digest, in hexadecimal."""
    return blake2b(data, digest_size=16).hexdigest()


class LineReader:
    """The :class:`Line` objects of a binary stream, lazily (:meth:`__iter__`), at most ``limit``
    characters each; :attr:`stopped` says why reading stopped before the end, if it did."""

    def __init__(self, stream: BinaryIO, limit: int) -> None:
        self._stream = stream
        self._limit = limit
        self._chunk = 4 * limit + 8  # bytes: at least limit + 1 characters of UTF-8
        self.stopped: str | None = None
        self.lines_read = 0
        """Lines read so far, comments and blank lines included (the progress counts them)."""

    def __iter__(self) -> Iterator[Line]:
        number = 0
        while True:
            head = self._stream.readline(self._chunk)
            if not head:
                return
            number += 1
            self.lines_read = number
            hasher = blake2b(digest_size=16)
            complete = head.endswith(b"\n") or len(head) < self._chunk
            nul = b"\0" in head
            if complete:
                hasher.update(_without_break(head))
            else:
                hasher.update(head)
                nul = self._skip_rest(hasher) or nul
            line = self._line(number, head, hasher.hexdigest(), complete, nul)
            if line is not None:
                yield line
            if nul:
                self.stopped = f"line {number} holds a NUL byte: this is not a text file"
                return

    def _skip_rest(self, hasher: Any) -> bool:
        """Read the rest of a long line, hashing it; whether it held a NUL byte (reading stops at
        the first piece that does: an endless binary line is not read to its end)."""
        while True:
            piece = self._stream.readline(SKIP_CHUNK)
            if not piece:
                return False
            if b"\0" in piece:
                return True
            if piece.endswith(b"\n"):
                hasher.update(_without_break(piece))
                return False
            hasher.update(piece)

    def _line(self, number: int, head: bytes, digest: str, complete: bool, nul: bool) -> Line | None:
        """The :class:`Line` of a line that starts with ``head``, or ``None`` for a blank line or a
        comment."""
        shown = head[: 4 * SHOWN].decode("utf-8", errors="replace").rstrip("\r\n")
        shown = shown[:SHOWN] + "…" if len(shown) > SHOWN or not complete else shown
        if nul:
            return Line(number, shown.replace("\0", ""), digest, "the line holds a NUL byte: this is not a text file")
        if not complete:
            return Line(number, shown, digest, f"the line is too long (more than {self._limit:,} characters)")
        try:
            text = _without_break(head).decode("utf-8")
        except UnicodeDecodeError as exc:
            return Line(number, shown, digest, f"the line is not UTF-8 text (byte {exc.start + 1} cannot be read)")
        if len(text) > self._limit:
            return Line(number, shown, digest, f"the line is too long (more than {self._limit:,} characters)")
        equation = _COMMENT.split(text, 1)[0].strip()
        return Line(number, equation, digest) if equation else None


_COMMENT = re.compile("#|//|%")
"""Where a comment starts: Python's and Maple's ``#``, Singular's ``//``, MATLAB's and LaTeX's
``%`` (none of them has a place in an equation)."""


def _without_break(line: bytes) -> bytes:
    """A line without its line break (``\\n`` or ``\\r\\n``)."""
    if line.endswith(b"\n"):
        line = line[:-1]
    return line[:-1] if line.endswith(b"\r") else line


def count_lines(stream: BinaryIO) -> int:
    """The number of lines of a seekable stream (a last line without a break counts), read in
    pieces; the stream is left at its start."""
    count, last = 0, b"\n"
    while piece := stream.read(SKIP_CHUNK):
        count += piece.count(b"\n")
        last = piece[-1:]
    stream.seek(0)
    return count + (last != b"\n")


def equations(text: str, limit: int = 1_000_000) -> list[tuple[int, str]]:
    """``(number, equation)`` of each line of ``text`` that holds one (comments and blank lines
    dropped): what the reader gives for a file of that text."""
    import io

    return [(line.number, line.equation) for line in LineReader(io.BytesIO(text.encode("utf-8")), limit)]
