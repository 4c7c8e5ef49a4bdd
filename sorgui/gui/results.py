"""The results pane: the verdict, the axis, the profile, Table 1 and the parameterizations.

It only reads an :class:`~sorgui.engine.results.Analysis` (possibly partial: the results known
so far). Every formula is readable the moment its row is built, as Unicode math
(:mod:`sorgui.session.formulas`); the pane then asks the window's typesetting process
(:class:`~sorgui.gui.typesetter.Typesetter`) for the typeset pictures, the rows on screen first
(as Qt's item views paint only the rows on screen), and each picture replaces its text when it
comes; scrolling asks for the newly visible rows first. Nothing here computes mathematics.
Table 1 of the paper is shown whole, with the surface's row highlighted, so the user sees where
the answer comes from; stages still running are named as such. A *no* is explained in words
(:mod:`sorgui.gui.wording`), the near case of rounded input too. ``plain_text()`` is the CLI's
report (:func:`sorgui.export.text.plain_text`).
"""

from __future__ import annotations

from collections.abc import Collection, Sequence

from PySide6.QtCore import QEvent, QRect, Qt, QTimer
from PySide6.QtGui import QColor, QFont, QFontInfo, QResizeEvent
from PySide6.QtWidgets import (
    QAbstractItemView,
    QFrame,
    QHeaderView,
    QLabel,
    QScrollArea,
    QTableWidget,
    QTableWidgetItem,
    QWidget,
)

from sorgui.engine.results import UNDECIDED, Analysis, Approximation, Canal, Conical, Recognition
from sorgui.engine.stage_results import ParametricInput, Rationality
from sorgui.engine.vocabulary import kind_noun
from sorgui.export.text import (
    TABLE_1,
    TABLE_1_WORDS,
    component_words,
    float_text,
    nearly_canal,
    outside_words,
    plain_text,
    symmetry_name,
    typed_canal_note,
)
from sorgui.gui.formula_view import FormulaView
from sorgui.gui.page import CAPTION_WIDTH, Page, Row
from sorgui.gui.stages import seconds_text
from sorgui.gui.typesetter import Typesetter
from sorgui.gui.wording import (
    canal_evidence,
    canal_verdict,
    caption_tip,
    radius_words,
    spine_words,
    tolerance_words,
    verdict,
    why_not,
)
from sorgui.session.base_curves import base_curve_rows
from sorgui.session.components import Component
from sorgui.session.formulas import TypesetFormula, expression_formula, pane_formulas
from sorgui.session.typesetting import Style, Typeset

TABLE_HEADERS = ("row", "genus(P)", "genus(P²)", "X over ℂ", "X over ℝ")
HIGHLIGHT = QColor("#ffe08a")
YES_NO = {True: "yes", False: "no", None: "undecided"}
FORMULA_MARGIN = CAPTION_WIDTH + 120
"""Pixels of the pane's width that are not the formula column (caption, copy button, margins)."""

ASK_DELAY_MS = 40
"""Scrolling or resizing asks for the newly visible formulas this long after it stops."""

_BANNER_STYLE = {
    "sor": "background: #e3f2e5; color: #1b5e20; border: 1px solid #a5d6a7;",
    "near": "background: #f1f8e9; color: #33691e; border: 1px solid #c5e1a5;",
    "not": "background: #fbe9e7; color: #8d2b0b; border: 1px solid #ffab91;",
    "info": "background: #eef2f7; color: #263238; border: 1px solid #cfd8dc;",
    "error": "background: #fdecea; color: #b71c1c; border: 1px solid #ef9a9a;",
}


LONG_NUMBER = 12
"""An exact axis whose numbers print longer than this is shown in decimals first."""


class ResultsPane(QScrollArea):
    """A scrolling column of sections, rebuilt for every analysis; its formulas are typeset by
    ``typesetter`` (none: they stay text)."""

    def __init__(self, parent: QWidget | None = None, typesetter: Typesetter | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("resultsPane")
        self.setWidgetResizable(True)
        self.setFrameShape(QFrame.Shape.NoFrame)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAsNeeded)
        self.typesetter = typesetter
        self._analysis: Analysis | None = None
        self._formulas: dict[str, TypesetFormula] = {}
        self._message = ""
        self._zoom = 1.0
        self._base_size = self.font().pointSizeF()
        self._base_pixels = QFontInfo(self.font()).pixelSize()
        self.page = Page()
        self.setWidget(self.page)
        self._shown_input: str | None = None
        self.stale = False
        self._ask_timer = QTimer(self)
        self._ask_timer.setSingleShot(True)
        self._ask_timer.setInterval(ASK_DELAY_MS)
        self._ask_timer.timeout.connect(self.ask_typesetter)
        self.verticalScrollBar().valueChanged.connect(self._on_scroll_change)
        if typesetter is not None:
            typesetter.typeset.connect(self._on_typeset_change)
        self.show_message("No analysis yet", "Type an equation and press Analyze (Ctrl+Return).", "info")

    # --- public API ---

    @property
    def analysis(self) -> Analysis | None:
        return self._analysis

    @property
    def views(self) -> dict[str, FormulaView]:
        """The formula views of the shown page, by formula key."""
        return self.page.views

    @property
    def banner(self) -> QLabel:
        """The verdict banner (or the message) at the top of the page."""
        widget = self.page.widget_named("verdictBanner")
        assert isinstance(widget, QLabel)  # every page starts with its banner
        return widget

    @property
    def table(self) -> QTableWidget | None:
        """Table 1 of the paper, when shown."""
        return self.page.table

    def plain_text(self) -> str:
        """The shown result as plain text: the CLI's report, or the shown message."""
        return plain_text(self._analysis) if self._analysis is not None else self._message

    def show_message(self, title: str, message: str, kind: str = "info") -> None:
        """Replace the results by a message (``kind``: ``info`` or ``error``)."""
        self._analysis, self._formulas = None, {}
        self._message = f"{title}\n{message}"
        self._begin(None)
        self._banner(title, message, kind)
        self._end()

    def show_analysis(
        self,
        analysis: Analysis,
        stages: Sequence[tuple[str, float]] = (),
        pending: Collection[str] = (),
        nearest: bool = False,
        components: Sequence[Component] = (),
        wall: float | None = None,
        unfinished: Collection[str] = (),
        limit: float | None = None,
        beyond: bool = False,
        stopped: Collection[str] = (),
    ) -> None:
        """Show ``analysis``, every formula as text at once and typeset when the typesetting
        process has it. ``stages`` are the run's finished stages with their times and ``wall``
        its wall time so far (the Timings section: the same figures as the stage line);
        ``pending`` names the stages still to come (shown as such), ``unfinished`` those the time
        limit of ``limit`` seconds cut short (shown as undecided), ``stopped`` those cancelled or
        cut short (rounded input stopped in its rounding's stage is not a plain *no*); ``nearest`` says that
        ``analysis`` is that of the nearest exact surface (its numbers in decimals, as rounded
        input's), ``beyond`` that it lies outside the input's rounding; ``components`` are the
        typed components of a blend, to explain a *no*."""
        self._analysis = analysis
        self._formulas = pane_formulas(analysis, "decimal" if nearest else None)
        rec = analysis.recognition
        name = "g" if nearest else "f"  # the nearest exact surface is g, as in the reports
        if nearest and rec.polynomial:
            self._formulas["polynomial"] = expression_formula(rec.polynomial, "g =", "decimal")
        self._begin(analysis.input)
        title, detail, kind = verdict(
            analysis, rounding_pending="approximate" in pending, rounding_stopped="approximate" in stopped
        )
        if nearest:
            title = "The nearest exact surface: " + title.lower()
            meant = (
                "the exact analysis of the surface of revolution found nearest the rounded input, outside its "
                "rounding: not known to be the one meant"
                if beyond
                else "the exact analysis of the surface of revolution that the rounded input was meant to be"
            )
            detail = f"{meant} · {detail}"
        self._banner(title, detail, kind)
        if analysis.parametric is not None:
            self._parametric_section(analysis.parametric)
        equation = "polynomial" if rec.polynomial else "not known"
        if not rec.polynomial and analysis.parametric is not None:
            equation = "not known: " + analysis.parametric.implicit_status.removeprefix("not found: ")
        self._section("Equation", [(f"{name}(x, y, z)", equation)])
        if analysis.approximate is not None:
            self._approximation_section(analysis.approximate, pending)
        reasons = why_not(analysis, components)
        if reasons:
            self._section("Why it is not a surface of revolution", [("", line) for line in reasons])
        self._recognition_sections(rec, "")
        if len(analysis.factors) > 1 or any(factor.multiplicity > 1 for factor in analysis.factors):
            self._factor_section(analysis)
        if analysis.rationality is not None:
            self._rationality_section(analysis.rationality)
        elif "rationality" in pending and rec.is_sor and analysis.rationality is None:
            self._section(
                "Rationality (Table 1 of the paper)",
                [("", "being decided (Singular): the row, the genera and the parameterizations follow")],
            )
        self._parametrization_section(analysis)
        conical = analysis.conical
        if conical is not None and conical.kind != "none":
            self._conical_section(conical)
        elif conical is not None and conical.near_residual is not None:  # nearly a cone or a cylinder
            self._near_conical_section(conical)
        elif "conical" in pending:
            self._section("Cone or cylinder", [("", "being decided: the apex or the direction follows")])
        elif "conical" in unfinished:
            self._section("Cone or cylinder", [("", _undecided(limit))])
        if analysis.canal is not None:
            near = analysis.verdict == "near"
            self._canal_section(
                analysis.canal, nearly_canal(analysis), near and "nearest" in pending, typed_canal_note(analysis)
            )
        elif "canal" in pending:
            self._section("Canal surface", [("", "being decided: the sphere family and its certificate follow")])
        elif "canal" in unfinished:
            self._section("Canal surface", [("canal", _undecided(limit))])
        if analysis.rationality is not None and "parametrizations" in pending:
            self._section("Parameterizations", [("", "being computed and verified…")])
        self._timings_section(stages or tuple(analysis.timings), wall)
        self._end()
        self.set_stale(self.stale)
        self._ask_soon(0)

    def set_stale(self, stale: bool) -> None:
        """Grey the results out (they belong to the previous equation) or show them normally."""
        self.stale = stale
        self.page.setEnabled(not stale)

    def set_zoom(self, zoom: float) -> None:
        """Scale the pane's text and formulas by ``zoom`` (they are typeset again)."""
        self._zoom = zoom
        font = self.font()
        font.setPointSizeF(self._base_size * zoom)
        self.setFont(font)

    @property
    def zoom(self) -> float:
        return self._zoom

    def formula_style(self) -> Style:
        """Formulas typeset at the text's size on this screen (times the zoom), wrapped to the
        width the pane has now."""
        ratio = self.devicePixelRatioF()
        width = 0.85 * (self.viewport().width() - FORMULA_MARGIN)  # pieces join a bit wider
        points = self._base_pixels * 72.0 / 96.0 + 1.5  # mathtext at 96 dpi: same pixels
        return Style(dpi=96.0 * ratio, size=round(points * self._zoom, 2), width=round(max(width, 200) * ratio))

    def ask_typesetter(self) -> None:
        """Ask the typesetting process for every formula still shown as text: those on screen
        first, then those below them, then those above (the order Qt's views paint in)."""
        self._ask_timer.stop()
        page = self.page
        if self.typesetter is None or not self.views:
            return
        style = self.formula_style()
        seen = self.viewport().rect().translated(0, self.verticalScrollBar().value())
        visible: list[tuple[str, ...]] = []
        below: list[tuple[str, ...]] = []
        above: list[tuple[str, ...]] = []
        for view in self.views.values():
            pieces = view.formula.pieces
            if not pieces:
                continue
            known = self.typesetter.known(pieces, style)
            if known is not None:
                view.set_typeset(known)
                continue
            if view.typeset_style == style:
                continue  # typeset already (mathtext rejected it: it stays text)
            where = QRect(view.mapTo(page, view.rect().topLeft()), view.size())
            (visible if where.intersects(seen) else below if where.top() >= seen.top() else above).append(pieces)
        self.typesetter.request([*visible, *below, *reversed(above)], style)

    # --- handlers ---

    def _ask_soon(self, delay: int = ASK_DELAY_MS) -> None:
        self._ask_timer.start(delay)

    def _on_scroll_change(self, _value: int) -> None:
        if self.typesetter is not None and self.typesetter.busy:
            self._ask_soon()

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 (Qt override)
        super().resizeEvent(event)
        if self.views:
            self._ask_soon(4 * ASK_DELAY_MS)

    def changeEvent(self, event: QEvent) -> None:  # noqa: N802 (Qt override)
        super().changeEvent(event)
        if event.type() == QEvent.Type.FontChange and self.views:
            self._ask_soon(0)  # a new font (the zoom): typeset again

    def _on_typeset_change(self, answers: list[Typeset]) -> None:
        """Typeset formulas of the shown page replace their text, in place (no rebuild)."""
        style = self.formula_style()
        fresh = {answer.pieces: answer for answer in answers if answer.style == style}
        if not fresh:
            return
        for view in self.views.values():
            answer = fresh.get(view.formula.pieces)
            if answer is not None:
                view.set_typeset(answer)

    def _parametric_section(self, record: ParametricInput) -> None:
        """The parametrization as typed, what its normal lines decide, and whether it is proper."""
        names = ", ".join(record.parameters)
        rows = [(f"{c}({names})", value) for c, value in zip("xyz", record.components)]
        rows.append(("degree", f"{record.degree} over {record.field} (over a common denominator)"))
        decided = "being decided" if record.symmetry == UNDECIDED else symmetry_name(record.symmetry)
        rows.append(("normal lines", f"{decided} (dim L = {record.symmetry_dimension})"))
        if record.profile_check is not None:
            rows.append(
                (
                    "cross-check",
                    f"∂(h, ρ)/∂({', '.join(record.map_parameters)}) ≡ 0 about the axis: "
                    + ("yes" if record.profile_check else "NO"),
                )
            )
        if record.implicit_status:
            rows.append(("implicit equation", record.implicit_status))
        if record.proper is not None:
            fibre = "one parameter point" if record.fibre == 1 else f"{record.fibre} parameter points"
            rows.append(
                ("proper", f"{'yes' if record.proper else 'no'}: {fibre} over a point of X ({record.proper_method})")
            )
        elif record.proper_method:
            rows.append(("proper", record.proper_method))
        else:
            rows.append(("proper", "being decided (Singular)"))
        rows += [("note", note) for note in record.notes]
        self._section("Parametrization (as typed)", rows)

    def _approximation_section(self, approx: Approximation, pending: Collection[str] = ()) -> None:
        source = "from the digits of the input" if approx.tolerance_source == "input" else "given"
        smallest = ", ".join(f"{v:.2g}" for v in approx.singular_values[-3:])
        rows = [
            ("tolerance", f"{tolerance_words(approx)} (relative, {source})"),
            ("near", _near_words(approx)),
            ("relative distance", "–" if approx.relative_distance is None else f"{approx.relative_distance:.3g}"),
            ("in units of rounding", "–" if approx.residual is None else f"{approx.residual:.3g}"),
            ("singular values", f"smallest: {smallest}" if smallest else "–"),
        ]
        if approx.axis is not None:
            rows.append(("approximate axis", "approximate.axis"))
        nearest = approx.nearest
        if nearest is not None and not nearest.within_rounding:
            rows.append(
                (
                    "nearest exact surface",
                    "none within the rounding: no simple exact surface was found within it; the nearest one "
                    f"found lies outside it ({outside_words(nearest)}; coefficient distance "
                    f"{nearest.relative_distance:.3g}, relative), and its analysis is shown only when you "
                    "switch the view to it",
                )
            )
        elif nearest is not None:
            rows.append(("nearest exact surface", "approximate.nearest"))
            if nearest.axis is not None:  # decimals first, the exact line below (each with its copy button)
                if "approximate.nearest.axis.decimal" in self._formulas:
                    rows.append(("its axis", "approximate.nearest.axis.decimal"))
                rows.append(("exactly", "approximate.nearest.axis"))
            deviation = "–" if nearest.max_deviation is None else f"{nearest.max_deviation:.3g} (length units)"
            rows.append(("max deviation", deviation))
            rows.append(
                (
                    "",
                    f"coefficient distance {nearest.relative_distance:.3g} (relative); "
                    + (
                        "within the rounding of the input"
                        if nearest.within_rounding
                        else "NOT within the rounding of the input"
                    ),
                )
            )
        rows += [("note", note) for note in approx.notes]
        self._section("Rounded input", rows)

    # --- building blocks ---

    def _begin(self, shown: str | None) -> None:
        """Start describing the page of the equation ``shown`` (``None``: a message); another
        equation's page starts at the top."""
        if shown != self._shown_input:
            self.verticalScrollBar().setValue(0)
        self._shown_input = shown
        self.page.begin()

    def _end(self) -> None:
        self.page.end()

    def _banner(self, title: str, detail: str, kind: str) -> None:
        def build() -> QLabel:
            banner = QLabel(f"<div style='font-size: 15pt; font-weight: 600'>{title}</div><div>{detail}</div>")
            banner.setObjectName("verdictBanner")
            banner.setWordWrap(True)
            banner.setTextFormat(Qt.TextFormat.RichText)
            banner.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            banner.setStyleSheet(f"QLabel {{ {_BANNER_STYLE[kind]} border-radius: 6px; padding: 8px; }}")
            return banner

        self.page.block(("banner", title, detail, kind), build)

    def _heading(self, text: str) -> None:
        def build() -> QLabel:
            label = QLabel(text)
            label.setObjectName("sectionHeading")
            font = label.font()
            font.setBold(True)
            font.setPointSizeF(font.pointSizeF() * 1.1)
            label.setFont(font)
            label.setContentsMargins(0, 8, 0, 0)
            return label

        self.page.block(("heading", text), build)

    def _section(self, heading: str, rows: Sequence[tuple[str, str]]) -> None:
        """A heading and a grid of ``(caption, formula key or text)`` rows.

        A value that is a key of the formulas is shown as that formula; any other as text.
        """
        shown: list[Row] = [
            (caption, (value, self._formulas[value]) if value in self._formulas else value) for caption, value in rows
        ]
        self.page.section(heading, shown, self._formula_view, caption_tip)

    def _formula_view(self, formula: TypesetFormula, caption: str) -> FormulaView:
        style = self.formula_style()
        known = self.typesetter.known(formula.pieces, style) if self.typesetter is not None else None
        width = self.viewport().width() - FORMULA_MARGIN
        view = FormulaView(formula, ratio=self.devicePixelRatioF(), max_width=width, typeset=known)
        view.setToolTip(caption_tip(caption))
        return view

    def _recognition_sections(self, rec: Recognition, key: str) -> None:
        if rec.axis is not None:
            rows = [
                ("point c", f"{key}axis.point"),
                ("direction a", f"{key}axis.direction"),
                ("line", f"{key}axis.line"),
                ("Plücker (a : c × a)", f"{key}axis.plucker"),
            ]
            long = max(len(v) for v in rec.axis.point + rec.axis.direction) > LONG_NUMBER
            if long and f"{key}axis.decimal" in self._formulas:  # a snapped axis of 20-digit integers: readable first
                rows.insert(0, ("≈ line (unit a)", f"{key}axis.decimal"))
            self._section("Axis", rows)
        if rec.center is not None:
            rows = [("centre", f"{key}center")]
            if rec.radius_squared is not None:
                rows.append(("radius²", f"{key}radius_squared"))
            self._section("Centre (every line through it is an axis)", rows)
        if rec.normal is not None:
            self._section("Normal (every line along it is an axis)", [("normal", f"{key}normal")])
        if rec.direction is not None:
            self._section("Direction of translation", [("direction", f"{key}direction")])
        if rec.profile is not None and not key:
            profile = rec.profile
            self._section(
                "Profile curve",
                [
                    ("p(x, y) = 0", "profile.polynomial"),
                    ("", "x along the axis, y the distance to it"),
                    ("P²: y² → y", "profile.square"),
                    ("p̃(s, r) = f(c + s·a + r·u)", "profile.rational"),
                    ("frame", "profile.frame_point"),
                    ("", "profile.frame_direction"),
                    ("", "profile.frame_normal"),
                    (
                        "checks",
                        f"p̃ even in r: {YES_NO[profile.even]} · f = p(x, √(y² + z²)) "
                        f"in the axis frame: {YES_NO[profile.verified]}",
                    ),
                ],
            )

    def _factor_section(self, analysis: Analysis) -> None:
        rows = []
        for index, factor in enumerate(analysis.factors):
            rec = factor.recognition
            rows.append(
                (
                    f"factor {index + 1}" + (f"  (power {factor.multiplicity})" if factor.multiplicity > 1 else ""),
                    f"factor.{index}",
                )
            )
            rows.append(("", symmetry_name(rec.symmetry)))
            if rec.axis is not None:
                rows.append(("axis", f"factor.{index}.axis.line"))
            if rec.center is not None:
                rows.append(("centre", f"factor.{index}.center"))
        self._section(f"Factors over {analysis.field}", rows)

    def _rationality_section(self, rat: Rationality) -> None:
        genus_p = "reducible" if rat.profile_reducible else _value(rat.genus_profile)
        rows = [
            ("status", rat.status),
            ("genus(P)", genus_p),
            ("genus(P²)", _value(rat.genus_profile_square)),
            ("X rational over ℂ", YES_NO[rat.complex_rational]),
            ("X unirational over ℝ", YES_NO[rat.unirational]),
            ("X rational over ℝ", YES_NO[rat.real_rational]),
        ]
        if rat.square_parametrization:
            rows += [
                ("P² parameterized by", "rationality.square_parametrization.0"),
                ("", "rationality.square_parametrization.1"),
            ]
        if rat.tubular_surface:
            rows.append(("tubular surface T", "rationality.tubular_surface"))
        if rat.h:
            rows.append(("h = r̂·q̂", "rationality.h"))
        if rat.real_roots_of_h is not None:
            rows.append(("real roots of h", str(rat.real_roots_of_h)))
        if rat.tau:
            rows += [("τ: X ⇢ T", "rationality.tau.x"), ("", "rationality.tau.y"), ("", "rationality.tau.z")]
        rows += [("note", note) for note in rat.notes]
        self._heading("Rationality (Table 1 of the paper)")
        row = rat.table_row
        self.page.block(("table1", row), lambda: _table_1(row))
        self._section("Genera and rationality", rows)

    def _parametrization_section(self, analysis: Analysis) -> None:
        for index, param in enumerate(analysis.parametrizations):
            kind = "real" if param.real else "complex"
            proper = {True: "proper", False: "not proper", None: "properness unknown"}[param.proper]
            check = f"verified: {param.verification}" if param.verified else "NOT verified"
            names = ", ".join(param.parameters)
            self._section(
                f"Parameterization {index + 1} ({names})",
                [
                    ("", f"{param.method} · {kind}, {proper}, over {param.field} · {check}"),
                    ("x", f"parametrization.{index}.x"),
                    ("y", f"parametrization.{index}.y"),
                    ("z", f"parametrization.{index}.z"),
                ],
            )

    def _conical_section(self, conical: Conical) -> None:
        """A cone or a cylinder over a curve (docs/math.md §10): apex or direction, base curve,
        genus and the parameterizations."""
        rows: list[tuple[str, str]] = []
        if conical.kind == "cone":
            rows += [("kind", "a cone over a curve: every line through the apex"), ("apex", "conical.apex")]
        else:
            rows += [("kind", "a cylinder over a curve: every line along the direction")]
            rows += [("direction", "conical.direction")]
            if conical.apex is not None:
                rows += [("apex", "conical.apex"), ("", "planes through the line there (a cone as well)")]
        base = conical.base_curve
        if base is not None:
            if base.chart is not None:
                rows.append(("base curve", f"the top-degree form of f in the chart {base.chart}, relative to the apex"))
            else:
                rows.append(("base curve", "the section by the plane u·U + v·W across the direction"))
                rows += [("U", "conical.base.frame_u"), ("W", "conical.base.frame_w")]
            rows.append(("", "conical.base"))
            rows += base_curve_rows(conical)
            if base.reducible:
                facts = "reducible over K: so is the surface, one component over each factor"
            elif base.genus is not None:
                facts = f"degree {base.degree}, genus {base.genus}"
            else:
                facts = f"degree {base.degree}, genus undecided"
            rows.append(("genus", facts))
            rows += [(f"component {i}", component_words(c)) for i, c in enumerate(conical.components, 1)]
        rows.append(("rational", YES_NO[conical.rational]))
        for index, param in enumerate(conical.parametrizations):
            kind = "real" if param.real else "complex"
            check = "verified by substitution" if param.verified else "NOT verified"
            rows.append((f"map {index + 1}", f"{kind}, proper, over {param.field} · {check}"))
            rows += [(name, f"conical.parametrization.{index}.{name}") for name in "xyz"]
        rows += [("note", note) for note in conical.notes]
        self._section("Cone or cylinder", rows)

    def _near_conical_section(self, conical: Conical) -> None:
        """Rounded input that is exactly neither, but nearly a cone or nearly a cylinder."""
        kind, caption, vector = (
            ("cone", "apex (about)", conical.near_apex)
            if conical.near_apex is not None
            else ("cylinder", "direction (about)", conical.near_direction)
        )
        assert vector is not None and conical.near_residual is not None  # the caller checked
        rows = [
            ("kind", f"not exactly a {kind}, but nearly: a {kind} within the rounding of the input"),
            (caption, float_text(vector, 6)),
            ("relative residual", f"{conical.near_residual:.2g}"),
        ]
        self._section("Cone or cylinder", rows)

    def _canal_section(self, canal: Canal, nearly: str = "", nearest_pending: bool = False, typed: str = "") -> None:
        """The canal verdict; for rounded input near a surface of revolution, the nearest exact
        surface's verdict first (what was meant), then that of the typed rationals; for other
        rounded input, the ``typed`` note that the verdict is of the typed rationals."""
        if nearly:
            rows = [("canal", nearly), ("exactly", canal_verdict(canal) + " (the typed rationals)")]
        elif nearest_pending and canal.is_canal is False:
            rows = [
                ("canal", "not exactly canal; the answer of the nearest exact surface is being decided"),
                ("exactly", canal_verdict(canal) + " (the typed rationals)"),
            ]
        else:
            rows = [("canal", canal_verdict(canal))]
        if typed:
            rows.append(("rounded input", typed))
        evidence = canal_evidence(canal)
        if evidence is not None:
            rows.append(evidence)
        several = len(canal.families) > 1
        for index, family in enumerate(canal.families):
            if several:
                rows.append((f"family {index + 1}", ""))
            rows.append(("spine", spine_words(family)))
            rows.append(("radius", radius_words(family)))
            if f"canal.{index}.spine" in self._formulas:
                rows.append(("m(t)", f"canal.{index}.spine"))
            if f"canal.{index}.radius" in self._formulas and not family.pipe:
                rows.append(("r²(t)", f"canal.{index}.radius"))
        rows += [("note", note) for note in canal.notes]
        self._section("Canal surface", rows)

    def _timings_section(self, timings: Sequence[tuple[str, float]], wall: float | None) -> None:
        """Each finished stage's time, as the stage line shows it, and the run's wall time, as
        the status line says it (the stages add up to less: starting, showing)."""
        rows = [(name, seconds_text(seconds)) for name, seconds in timings]
        rows.append(("sum of the stages", seconds_text(sum(seconds for _name, seconds in timings))))
        if wall is not None:
            rows.append(("wall time", seconds_text(wall)))
        self._section("Timings", rows)


def _table_1(row: int | None) -> QTableWidget:
    """Table 1 of the paper, the surface's row highlighted."""
    table = QTableWidget(len(TABLE_1), len(TABLE_HEADERS))
    table.setObjectName("table1")
    table.setHorizontalHeaderLabels(TABLE_HEADERS)
    table.verticalHeader().setVisible(False)
    table.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
    table.setSelectionMode(QAbstractItemView.SelectionMode.NoSelection)
    table.setFocusPolicy(Qt.FocusPolicy.NoFocus)
    bold = QFont(table.font())
    bold.setBold(True)
    for r, cells in enumerate(TABLE_1):
        for c, text in enumerate((str(r + 1), *cells)):
            item = QTableWidgetItem(text)
            item.setTextAlignment(Qt.AlignmentFlag.AlignCenter)
            words = f"Row {r + 1}. {TABLE_1_WORDS[r]}"
            if row == r + 1:
                item.setBackground(HIGHLIGHT)
                item.setFont(bold)
                words += "\nThis is the row of this surface."
            item.setToolTip(words)
            table.setItem(r, c, item)
    header = table.horizontalHeader()
    header.setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
    header.setSectionResizeMode(0, QHeaderView.ResizeMode.ResizeToContents)
    table.resizeRowsToContents()
    height = header.sizeHint().height() + sum(table.rowHeight(r) for r in range(table.rowCount()))
    table.setFixedHeight(height + 2 * table.frameWidth())
    table.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
    return table


def _undecided(limit: float | None) -> str:
    within = f" within the time limit of {limit:g} s" if limit is not None else " within the time limit"
    return f"not finished{within}: undecided (Analysis → Time Limit… allows more)"


def _value(value: object) -> str:
    return "undecided" if value is None else str(value)


def _near_words(approx: Approximation) -> str:
    """What rounded input is near, in words: "yes: a cylinder of revolution", or what it is
    nearly instead."""
    if approx.near_sor:
        return f"yes: {kind_noun(approx.kind)}"
    if approx.residual is None and not approx.singular_values:  # numbers beyond floats, or too coarse
        return "not decided (see the note)"
    if approx.kind in (None, "none"):
        return "no: no continuous symmetry within the tolerance"
    return f"no: nearly {kind_noun(approx.kind)}"
