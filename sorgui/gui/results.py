"""The results pane: the verdict, the axis, the profile, Table 1 and the parameterizations.

It only reads an :class:`~sorgui.engine.results.Analysis` (possibly partial: the results known
so far) and the typeset formulas the worker made for it (:mod:`sorgui.session.formulas`);
formulas not typeset yet are shown as their exact text. Nothing here computes mathematics.
Table 1 of the paper is shown whole, with the surface's row highlighted, so the user sees where
the answer comes from; stages still running are named as such. A *no* is explained in words
(:mod:`sorgui.gui.wording`), the near case of rounded input too. ``plain_text()`` is the CLI's
report (:func:`sorgui.export.text.plain_text`).
"""

from __future__ import annotations

from collections.abc import Collection, Sequence

from PySide6.QtCore import Qt
from PySide6.QtGui import QColor, QFont
from PySide6.QtWidgets import (
    QAbstractItemView,
    QFrame,
    QGridLayout,
    QHeaderView,
    QLabel,
    QScrollArea,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from sorgui.engine.results import (
    Analysis,
    Approximation,
    Canal,
    Conical,
    ParametricInput,
    Rationality,
    Recognition,
)
from sorgui.export.text import (
    TABLE_1,
    TABLE_1_WORDS,
    component_words,
    float_text,
    nearly_canal,
    plain_text,
    symmetry_name,
)
from sorgui.gui.formula_view import FormulaView
from sorgui.gui.wording import (
    canal_evidence,
    canal_verdict,
    caption_tip,
    radius_words,
    spine_words,
    verdict,
    why_not,
)
from sorgui.session.components import Component
from sorgui.session.formulas import TypesetFormula, pane_formulas

TABLE_HEADERS = ("row", "genus(P)", "genus(P²)", "X over ℂ", "X over ℝ")
HIGHLIGHT = QColor("#ffe08a")
YES_NO = {True: "yes", False: "no", None: "undecided"}
CAPTION_WIDTH = 130
"""Width of the caption column, the same in every section so that formulas line up."""
FORMULA_MARGIN = CAPTION_WIDTH + 120
"""Pixels of the pane's width that are not the formula column (caption, copy button, margins)."""

_BANNER_STYLE = {
    "sor": "background: #e3f2e5; color: #1b5e20; border: 1px solid #a5d6a7;",
    "near": "background: #f1f8e9; color: #33691e; border: 1px solid #c5e1a5;",
    "not": "background: #fbe9e7; color: #8d2b0b; border: 1px solid #ffab91;",
    "info": "background: #eef2f7; color: #263238; border: 1px solid #cfd8dc;",
    "error": "background: #fdecea; color: #b71c1c; border: 1px solid #ef9a9a;",
}


class ResultsPane(QScrollArea):
    """A scrolling column of sections, rebuilt for every analysis."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("resultsPane")
        self.setWidgetResizable(True)
        self.setFrameShape(QFrame.Shape.NoFrame)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAsNeeded)
        self._analysis: Analysis | None = None
        self._formulas: dict[str, TypesetFormula] = {}
        self._message = ""
        self._zoom = 1.0
        self._base_size = self.font().pointSizeF()
        self._building = QWidget()
        self.banner = QLabel()
        self.table: QTableWidget | None = None
        self.views: dict[str, FormulaView] = {}
        """The formula views of the shown page, by formula key."""
        self.stale = False
        self.show_message("No analysis yet", "Type an equation and press Analyze (Ctrl+Return).", "info")

    # --- public API ---

    @property
    def analysis(self) -> Analysis | None:
        return self._analysis

    def plain_text(self) -> str:
        """The shown result as plain text: the CLI's report, or the shown message."""
        return plain_text(self._analysis) if self._analysis is not None else self._message

    def show_message(self, title: str, message: str, kind: str = "info") -> None:
        """Replace the results by a message (``kind``: ``info`` or ``error``)."""
        self._analysis, self._formulas = None, {}
        self._message = f"{title}\n{message}"
        column = self._new_column()
        self._banner(column, title, message, kind)
        column.addStretch(1)
        self._show_page()

    def show_analysis(
        self,
        analysis: Analysis,
        formulas: dict[str, TypesetFormula],
        worker_timings: Sequence[tuple[str, float]] = (),
        pending: Collection[str] = (),
        nearest: bool = False,
        components: Sequence[Component] = (),
    ) -> None:
        """Show ``analysis`` with its typeset ``formulas`` (keys of :func:`pane_formulas`;
        missing ones are shown as text). ``pending`` names the stages still to come (shown as
        such); ``nearest`` says that ``analysis`` is that of the nearest exact surface;
        ``components`` are the typed components of a blend, to explain a *no*."""
        self._analysis = analysis
        self._formulas = {**pane_formulas(analysis, plain=True), **formulas}
        rec = analysis.recognition
        column = self._new_column()
        title, detail, kind = verdict(analysis)
        if nearest:
            title = "The nearest exact surface: " + title.lower()
            detail = (
                "the exact analysis of the surface of revolution that the rounded input was meant to be · " + detail
            )
        self._banner(column, title, detail, kind)
        if analysis.parametric is not None:
            self._parametric_section(column, analysis.parametric)
        equation = "polynomial" if rec.polynomial else "not known"
        if not rec.polynomial and analysis.parametric is not None:
            equation = "not known: " + analysis.parametric.implicit_status.removeprefix("not found: ")
        self._section(column, "Equation", [("f(x, y, z)", equation)])
        if analysis.approximate is not None:
            self._approximation_section(column, analysis.approximate)
        reasons = why_not(analysis, components)
        if reasons:
            self._section(column, "Why it is not a surface of revolution", [("", line) for line in reasons])
        self._recognition_sections(column, rec, "")
        if len(analysis.factors) > 1 or analysis.factors[0].multiplicity > 1:
            self._factor_section(column, analysis)
        if analysis.rationality is not None:
            self._rationality_section(column, analysis.rationality)
        elif "rationality" in pending and rec.is_sor and analysis.rationality is None:
            self._section(
                column,
                "Rationality (Table 1 of the paper)",
                [("", "being decided (Singular): the row, the genera and the parameterizations follow")],
            )
        self._parametrization_section(column, analysis)
        conical = analysis.conical
        if conical is not None and conical.kind != "none":
            self._conical_section(column, conical)
        elif conical is not None and conical.near_residual is not None:  # nearly a cone or a cylinder
            self._near_conical_section(column, conical)
        elif "conical" in pending:
            self._section(column, "Cone or cylinder", [("", "being decided: the apex or the direction follows")])
        if analysis.canal is not None:
            self._canal_section(column, analysis.canal, nearly_canal(analysis))
        elif "canal" in pending:
            self._section(
                column, "Canal surface", [("", "being decided: the sphere family and its certificate follow")]
            )
        if analysis.rationality is not None and "parametrizations" in pending:
            self._section(column, "Parameterizations", [("", "being computed and verified…")])
        self._timings_section(column, tuple(analysis.timings) + tuple(worker_timings))
        column.addStretch(1)
        self._show_page()
        self.set_stale(self.stale)

    def update_formulas(self, formulas: dict[str, TypesetFormula]) -> None:
        """Put newly typeset ``formulas`` into the shown page in place (no rebuild of the page)."""
        self._formulas.update(formulas)
        ratio = self.devicePixelRatioF()
        for key, view in self.views.items():
            formula = formulas.get(key)
            if formula is not None and formula is not view.formula:
                view._ratio = ratio
                view.set_formula(formula)

    def set_stale(self, stale: bool) -> None:
        """Grey the results out (they belong to the previous equation) or show them normally."""
        self.stale = stale
        page = self.widget()
        if page is not None:
            page.setEnabled(not stale)

    def set_zoom(self, zoom: float) -> None:
        """Scale the pane's text by ``zoom`` (the caller has the formulas typeset again)."""
        self._zoom = zoom
        font = self.font()
        font.setPointSizeF(self._base_size * zoom)
        self.setFont(font)

    def _parametric_section(self, column: QVBoxLayout, record: ParametricInput) -> None:
        """The parametrization as typed, what its normal lines decide, and whether it is proper."""
        names = ", ".join(record.parameters)
        rows = [(f"{c}({names})", value) for c, value in zip("xyz", record.components)]
        rows.append(("degree", f"{record.degree} over {record.field} (over a common denominator)"))
        decided = "being decided" if record.symmetry == "undecided" else symmetry_name(record.symmetry)
        rows.append(("normal lines", f"{decided} (dim L = {record.symmetry_dimension})"))
        if record.profile_check is not None:
            rows.append(
                ("cross-check", "∂(h, ρ)/∂(s, t) ≡ 0 about the axis: " + ("yes" if record.profile_check else "NO"))
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
        self._section(column, "Parametrization (as typed)", rows)

    def _approximation_section(self, column: QVBoxLayout, approx: Approximation) -> None:
        source = "from the digits of the input" if approx.tolerance_source == "input" else "given"
        smallest = ", ".join(f"{v:.2g}" for v in approx.singular_values[-3:])
        rows = [
            ("tolerance", f"{approx.tolerance:.2g} (relative, {source})"),
            ("near", ("yes: " if approx.near_sor else "no: ") + (approx.kind or "no symmetry kind")),
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
                    f"found lies outside it (coefficient distance {nearest.relative_distance:.3g}, relative), "
                    "and its analysis is shown only when you switch the view to it",
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
        self._section(column, "Rounded input", rows)

    # --- building blocks ---

    def _new_column(self) -> QVBoxLayout:
        old = self.takeWidget()
        if old is not None:
            old.deleteLater()
        self.table = None
        self.views = {}
        page = QWidget()
        page.setObjectName("resultsPage")
        column = QVBoxLayout(page)
        column.setContentsMargins(10, 10, 10, 10)
        column.setSpacing(6)
        self._building = page
        return column

    def _show_page(self) -> None:
        """Put the page just built on screen. Built before it is shown, its rows are laid out
        at once; built on screen, each row would appear only at the next turn of the event loop,
        over the others until the layout catches up."""
        self.setWidget(self._building)

    def _banner(self, column: QVBoxLayout, title: str, detail: str, kind: str) -> None:
        self.banner = QLabel(f"<div style='font-size: 15pt; font-weight: 600'>{title}</div><div>{detail}</div>")
        self.banner.setObjectName("verdictBanner")
        self.banner.setWordWrap(True)
        self.banner.setTextFormat(Qt.TextFormat.RichText)
        self.banner.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.banner.setStyleSheet(f"QLabel {{ {_BANNER_STYLE[kind]} border-radius: 6px; padding: 8px; }}")
        column.addWidget(self.banner)

    def _heading(self, column: QVBoxLayout, text: str) -> None:
        label = QLabel(text)
        font = label.font()
        font.setBold(True)
        font.setPointSizeF(font.pointSizeF() * 1.1)
        label.setFont(font)
        label.setContentsMargins(0, 8, 0, 0)
        column.addWidget(label)

    def _section(self, column: QVBoxLayout, heading: str, rows: Sequence[tuple[str, str]]) -> None:
        """A heading and a grid of ``(caption, formula key or text)`` rows.

        A value that is a key of the formulas is typeset; any other value is shown as text.
        """
        self._heading(column, heading)
        grid = QGridLayout()
        grid.setHorizontalSpacing(10)
        grid.setVerticalSpacing(4)
        grid.setColumnStretch(1, 1)
        grid.setColumnMinimumWidth(0, CAPTION_WIDTH)
        ratio = self.devicePixelRatioF()
        width = self.viewport().width() - FORMULA_MARGIN
        for index, (caption, value) in enumerate(rows):
            label = QLabel(caption)
            label.setObjectName("caption")
            label.setToolTip(caption_tip(caption))
            label.setStyleSheet("color: #546e7a;")
            label.setWordWrap(True)
            label.setFixedWidth(CAPTION_WIDTH)
            grid.addWidget(label, index, 0, Qt.AlignmentFlag.AlignTop)
            if value in self._formulas:
                view = FormulaView(self._formulas[value], ratio=ratio, max_width=width)
                view.setToolTip(caption_tip(caption))
                self.views[value] = view
                grid.addWidget(view, index, 1)
            else:
                text = QLabel(value)
                text.setWordWrap(True)
                text.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
                grid.addWidget(text, index, 1)
        column.addLayout(grid)

    def _recognition_sections(self, column: QVBoxLayout, rec: Recognition, key: str) -> None:
        if rec.axis is not None:
            self._section(
                column,
                "Axis",
                [
                    ("point c", f"{key}axis.point"),
                    ("direction a", f"{key}axis.direction"),
                    ("line", f"{key}axis.line"),
                    ("Plücker (a : c × a)", f"{key}axis.plucker"),
                ],
            )
        if rec.center is not None:
            rows = [("centre", f"{key}center")]
            if rec.radius_squared is not None:
                rows.append(("radius²", f"{key}radius_squared"))
            self._section(column, "Centre (every line through it is an axis)", rows)
        if rec.normal is not None:
            self._section(column, "Normal (every line along it is an axis)", [("normal", f"{key}normal")])
        if rec.direction is not None:
            self._section(column, "Direction of translation", [("direction", f"{key}direction")])
        if rec.profile is not None and not key:
            profile = rec.profile
            self._section(
                column,
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

    def _factor_section(self, column: QVBoxLayout, analysis: Analysis) -> None:
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
        self._section(column, f"Factors over {analysis.field}", rows)

    def _rationality_section(self, column: QVBoxLayout, rat: Rationality) -> None:
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
        self._heading(column, "Rationality (Table 1 of the paper)")
        column.addWidget(self._table_1(rat.table_row))
        self._section(column, "Genera and rationality", rows)

    def _table_1(self, row: int | None) -> QTableWidget:
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
        self.table = table
        return table

    def _parametrization_section(self, column: QVBoxLayout, analysis: Analysis) -> None:
        for index, param in enumerate(analysis.parametrizations):
            kind = "real" if param.real else "complex"
            proper = {True: "proper", False: "not proper", None: "properness unknown"}[param.proper]
            check = "verified by substitution" if param.verified else "NOT verified"
            names = ", ".join(param.parameters)
            self._section(
                column,
                f"Parameterization {index + 1} ({names})",
                [
                    ("", f"{param.method} · {kind}, {proper}, over {param.field} · {check}"),
                    ("x", f"parametrization.{index}.x"),
                    ("y", f"parametrization.{index}.y"),
                    ("z", f"parametrization.{index}.z"),
                ],
            )

    def _conical_section(self, column: QVBoxLayout, conical: Conical) -> None:
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
                rows.append(("base curve", f"the top-degree form of f in the chart {base.chart}"))
            else:
                rows.append(("base curve", "the section by the plane u·U + v·W across the direction"))
                rows += [("U", "conical.base.frame_u"), ("W", "conical.base.frame_w")]
            rows.append(("", "conical.base"))
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
        self._section(column, "Cone or cylinder", rows)

    def _near_conical_section(self, column: QVBoxLayout, conical: Conical) -> None:
        """Rounded input that is exactly neither, but nearly a cone or nearly a cylinder."""
        kind, caption, vector = (
            ("cone", "apex (about)", conical.near_apex)
            if conical.near_apex is not None
            else ("cylinder", "direction (about)", conical.near_direction)
        )
        assert vector is not None and conical.near_residual is not None  # the caller checked
        rows = [
            ("kind", f"not exactly a {kind}, but nearly: a {kind} within the rounding of the input"),
            (caption, float_text(vector, 10)),
            ("relative residual", f"{conical.near_residual:.2g}"),
        ]
        self._section(column, "Cone or cylinder", rows)

    def _canal_section(self, column: QVBoxLayout, canal: Canal, nearly: str = "") -> None:
        rows = [("canal", canal_verdict(canal))]
        if nearly:
            rows.append(("rounded input", nearly))
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
                rows.append(("ρ(t)", f"canal.{index}.radius"))
        rows += [("note", note) for note in canal.notes]
        self._section(column, "Canal surface", rows)

    def _timings_section(self, column: QVBoxLayout, timings: Sequence[tuple[str, float]]) -> None:
        total = sum(seconds for _name, seconds in timings)
        rows = [(name, f"{seconds * 1000:.0f} ms") for name, seconds in timings]
        rows.append(("sum of the stages", f"{total * 1000:.0f} ms"))
        self._section(column, "Timings", rows)


def _value(value: object) -> str:
    return "undecided" if value is None else str(value)
