"""The polynomial editor: syntax highlighting and live validation of the pasted equation.

While the user types, the text is checked with the engine's own reader
(:func:`~sorgui.engine.parametric_parsing.parse_input`: an equation, or a parametrization
``x = X(s, t), y = …, z = …``; an equation over ``QQ`` by flint alone, :func:`summary`) after a
pause of :data:`VALIDATION_DELAY_MS`.
The parser is cheap (it refuses huge degrees in milliseconds), so it runs on the GUI thread;
texts longer than :data:`LIVE_VALIDATION_LIMIT` characters are parsed by the analysis worker
instead, which reports errors back here. A parse error is underlined with a red wave from its position to its end and
explained in a label under the editor.
"""

from __future__ import annotations

import re

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import (
    QColor,
    QFont,
    QFontDatabase,
    QSyntaxHighlighter,
    QTextCharFormat,
    QTextCursor,
    QTextDocument,
    QTextOption,
)
from PySide6.QtWidgets import QLabel, QPlainTextEdit, QTextEdit, QVBoxLayout, QWidget

from sorgui.engine.errors import ParseError
from sorgui.engine.limits import COMMENT, refuse_text_report
from sorgui.engine.parametric_parsing import ParsedParametrization, parse_input
from sorgui.engine.parsing import is_parametrization, parse_rational
from sorgui.gui.wording import short_numbers

VALIDATION_DELAY_MS = 250
"""Debounce of the live validation: the parser runs this long after the last keystroke."""

LIVE_VALIDATION_LIMIT = 20_000
"""Longer texts are parsed by the analysis worker, never on the GUI thread."""

WORD_WRAP_LIMIT = 4000
"""Characters up to which the editor wraps its lines between terms (a number split over two lines,
``- 0.`` and ``0618315``, misreads); a longer equation wraps anywhere: Qt's wrapping at word
boundaries takes seconds for the 200,000 characters of a dense surface of degree 40 (0.1 s
anywhere)."""

ERROR_COLOR = QColor("#c62828")
OK_COLOR = QColor("#2e7d32")


def summary(text: str) -> str:
    """What the editor says of valid input: its degree and its field; :class:`ParseError` otherwise.

    An equation over ``QQ`` is read by flint alone (:func:`~sorgui.engine.parsing.parse_rational`):
    the window checks its first equation before the first verdict, and sympy, which the general
    reader needs for square roots and parametrizations, is then not loaded on the GUI thread."""
    refuse_text_report(text)
    if not is_parametrization(text):
        rational = parse_rational(text)
        if rational is not None:
            return f"✓ degree {rational.total_degree()} over QQ"
    from sorgui.engine.algebra.polys import field_name, total_degree

    parsed = parse_input(text)
    if isinstance(parsed, ParsedParametrization):
        names = " and ".join(parsed.parameters)
        field = short_numbers(field_name(parsed.field))
        angles = (", in " + " and ".join(f"tan({u}/2)" for u, _ in parsed.angles)) if parsed.angles else ""
        return f"✓ a parametrization in {names} of degree {parsed.map.degree} over {field}{angles}"
    return f"✓ degree {total_degree(parsed.polynomial)} over {short_numbers(field_name(parsed.field))}"


class PolynomialHighlighter(QSyntaxHighlighter):
    """Colours numbers, the variables x, y, z, operators and function names (in lines of up
    to :data:`LIVE_VALIDATION_LIMIT` characters)."""

    def __init__(self, document: QTextDocument) -> None:
        super().__init__(document)
        self._rules: list[tuple[re.Pattern[str], QTextCharFormat]] = [
            (re.compile(r"\d+(?:\.\d*)?|\.\d+"), _char_format("#1565c0")),
            (
                re.compile(r"(?<![A-Za-z_])(?:[xyz]++|[XYZ]++)(?![A-Za-z_])"),
                _char_format("#6a1b9a", bold=True),
            ),  # xy, x2, X
            (re.compile(r"\*\*|[-+*/^=]"), _char_format("#ef6c00")),
            (re.compile(r"[()\[\]{}]"), _char_format("#616161")),
            (re.compile(r"\b(?:sqrt|pow)\b"), _char_format("#00838f", italic=True)),
            (re.compile(COMMENT), _char_format("#9e9e9e", italic=True)),  # last: over what it holds
        ]

    def highlightBlock(self, text: str) -> None:  # noqa: N802 (Qt override)
        if len(text) > LIVE_VALIDATION_LIMIT:
            return  # a pasted giant: colouring it would slow every keystroke down
        for pattern, fmt in self._rules:
            for match in pattern.finditer(text):
                self.setFormat(match.start(), match.end() - match.start(), fmt)


def _char_format(color: str, bold: bool = False, italic: bool = False) -> QTextCharFormat:
    fmt = QTextCharFormat()
    fmt.setForeground(QColor(color))
    if bold:
        fmt.setFontWeight(QFont.Weight.Bold)
    fmt.setFontItalic(italic)
    return fmt


class EquationEditor(QWidget):
    """A plain-text editor for ``f(x, y, z) = 0`` with live validation.

    :attr:`validity_changed` carries ``True``/``False`` after each check, and ``None`` while
    the text is unchecked (being typed, or too long to check live).
    """

    validity_changed = Signal(object)
    text_changed = Signal()

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.text_edit = QPlainTextEdit(self)
        self.text_edit.setObjectName("equationEdit")
        self.text_edit.setPlaceholderText(
            "Paste f(x, y, z), e.g. (x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2),"
            " or a parametrization x = (1-t^2)/(1+t^2)*(2+s), y = 2t/(1+t^2)*(2+s), z = s^2"
        )
        font = QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont)
        font.setPointSizeF(max(font.pointSizeF(), 10.5))
        self.text_edit.setFont(font)
        self.text_edit.setTabChangesFocus(True)
        self.text_edit.setLineWrapMode(QPlainTextEdit.LineWrapMode.WidgetWidth)
        self.text_edit.setWordWrapMode(QTextOption.WrapMode.WrapAtWordBoundaryOrAnywhere)
        self.text_edit.document().contentsChange.connect(self._wrap_for_length)
        self.highlighter = PolynomialHighlighter(self.text_edit.document())

        self.status_label = QLabel(self)
        self.status_label.setObjectName("validationLabel")
        self.status_label.setWordWrap(True)
        self.status_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)

        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(4)
        layout.addWidget(self.text_edit, 1)
        layout.addWidget(self.status_label)

        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(VALIDATION_DELAY_MS)
        self._timer.timeout.connect(self._validate)
        self._valid: bool | None = None
        self._error: ParseError | None = None
        self.text_edit.textChanged.connect(self._on_text_change)

    # --- public API ---

    def text(self) -> str:
        return self.text_edit.toPlainText()

    def set_text(self, text: str) -> None:
        """Replace the content (one undo step) and check it at once if it is short."""
        cursor = self.text_edit.textCursor()
        cursor.select(QTextCursor.SelectionType.Document)
        cursor.insertText(text)
        self.text_edit.moveCursor(QTextCursor.MoveOperation.Start)
        self.check()

    @property
    def error(self) -> ParseError | None:
        """The parse error of the last check, if any."""
        return self._error

    @property
    def is_valid(self) -> bool | None:
        """The result of the last check (``None``: not checked)."""
        return self._valid

    def check(self) -> bool | None:
        """Check the text now and show the result: ``True``/``False``, or ``None`` when it is
        too long to parse on the GUI thread (the analysis worker parses it then)."""
        self._timer.stop()
        text = self.text()
        if not text.strip():
            self._show_result(
                None, None, "Type or paste a polynomial f(x, y, z), or x = …, y = …, z = … in two parameters."
            )
            return False
        if not self._is_short():
            self._show_result(None, None, _LONG_TEXT_MESSAGE)
            return None
        try:
            message = summary(text)
        except ParseError as exc:
            self.show_error(exc)
            return False
        self._show_result(True, None, message)
        return True

    def show_error(self, error: ParseError) -> None:
        """Underline ``error`` and explain it (also for errors found by the worker)."""
        self._show_result(False, error, f"✗ {error.message} (at character {error.position + 1})")

    def error_selections(self) -> list[QTextEdit.ExtraSelection]:
        """The extra selections that underline the current error (for tests and tooltips)."""
        return list(self.text_edit.extraSelections())

    # --- handlers ---

    def _wrap_for_length(self, _position: int, _removed: int, _added: int) -> None:
        """Wrap between terms up to :data:`WORD_WRAP_LIMIT` characters, anywhere beyond: switched
        as the text changes, before Qt lays the new text out."""
        short = self.text_edit.document().characterCount() <= WORD_WRAP_LIMIT
        wanted = QTextOption.WrapMode.WrapAtWordBoundaryOrAnywhere if short else QTextOption.WrapMode.WrapAnywhere
        if self.text_edit.wordWrapMode() != wanted:
            self.text_edit.setWordWrapMode(wanted)

    def _on_text_change(self) -> None:
        self.text_changed.emit()
        if self._valid is not None or self._error is not None:
            self._show_result(None, None, "Checking…" if self._is_short() else _LONG_TEXT_MESSAGE)
        if self._is_short():
            self._timer.start()
        else:
            self._timer.stop()

    def _validate(self) -> None:
        self.check()

    # --- helpers ---

    def _is_short(self) -> bool:
        return self.text_edit.document().characterCount() <= LIVE_VALIDATION_LIMIT

    def _show_result(self, valid: bool | None, error: ParseError | None, message: str) -> None:
        self._error = error
        self.text_edit.setExtraSelections(self._underline(error) if error is not None else [])
        color = None if valid is None else OK_COLOR if valid else ERROR_COLOR
        self.status_label.setStyleSheet(f"color: {color.name()};" if color is not None else "")
        self.status_label.setText(message)
        self.text_edit.setToolTip(message if error is not None else "")
        self._valid = valid
        self.validity_changed.emit(valid)

    def _underline(self, error: ParseError) -> list[QTextEdit.ExtraSelection]:
        """A red wavy underline over ``error.position .. error.end`` (at least one character)."""
        length = len(self.text())
        start = min(max(error.position, 0), max(length - 1, 0))
        end = min(max(error.end, start + 1), length)
        selection = QTextEdit.ExtraSelection()
        fmt = QTextCharFormat()
        fmt.setUnderlineStyle(QTextCharFormat.UnderlineStyle.WaveUnderline)
        fmt.setUnderlineColor(ERROR_COLOR)
        fmt.setBackground(QColor(198, 40, 40, 40))
        selection.format = fmt
        cursor = QTextCursor(self.text_edit.document())
        cursor.setPosition(start)
        cursor.setPosition(end, QTextCursor.MoveMode.KeepAnchor)
        selection.cursor = cursor
        return [selection]


_LONG_TEXT_MESSAGE = f"Long input (over {LIVE_VALIDATION_LIMIT:,} characters): the analysis will check it."
