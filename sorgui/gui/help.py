"""The Help menu: input syntax, mouse and keys, what the results mean, the paper, known limits.

Each topic is a page of HTML shown in one non-modal :class:`HelpDialog` (a ``QTextBrowser``),
so the user can keep it open beside the window. The examples in the input-syntax page are
equations the parser accepts (a test parses every one of them).
"""

from __future__ import annotations

import html

from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
)

from sorgui.export.text import TABLE_1, TABLE_1_WORDS
from sorgui.gui.viewport import (
    APPROXIMATE_AXIS_COLOR,
    AXIS_COLOR,
    BACK_COLOR,
    BASE_CURVE_COLOR,
    CANAL_CIRCLE_COLOR,
    CANAL_SPINE_COLOR,
    CENTER_COLOR,
    FACTOR_AXES_COLOR,
    FRONT_COLOR,
    LATITUDE_COLOR,
    NORMAL_COLOR,
    PATCH_COLOR,
    PROFILE_COLOR,
    STALE_COLOR,
    TOUCH_SPHERE_COLOR,
)

SYNTAX_EXAMPLES = (
    ("(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)", "a torus: powers with ^, implicit multiplication"),
    ("x**2 + y**2 = z**2", "a cone: ** works too, and an equation sides = sides"),
    ("2xy^2 + 2(x+1) - z", "implicit multiplication of numbers, variables and brackets"),
    ("x² + y² − 1 = 0", "Unicode superscripts and minus sign"),
    ("0.25x^2 + y^2/4 + z^2 - 1", "decimals are exact: 0.25 is 1/4"),
    ("x^2 + y^2 - 2z^2 + sqrt(2)·x·z", "square roots of rationals, the dot · as multiplication"),
    ("1.5E-3x^2 + y^2 + z^2 - 1", "E-notation (rounded input: sorgui also looks for a nearby exact surface)"),
    ("f := pow(x, 2) + y^2 - z;", "a statement of Maple or C: its label, pow and the final ; are read"),
    ("poly f = x2+y2-z2-1;", "Singular's print: x2 is x^2"),
    ("$x^{2} + y^{2} = \\frac{1}{2} z$", "LaTeX as typeset, inside $ $"),
    (
        "x = (1-t^2)/(1+t^2)*(2+s), y = 2t/(1+t^2)*(2+s), z = s^2",
        "a parametrization: x = …, y = …, z = … in two parameters (here a surface of revolution)",
    ),
    ("(u, v, u^3 - 3u*v^2)", "a parametrization as a triple (X, Y, Z)"),
)
"""Input the parser accepts (equations and parametrizations), with what each shows."""

PARAMETRIZATIONS_HTML = """
<h3>Parametrizations</h3>
<p>A surface may also be given as a rational map (s, t) ↦ (x, y, z): <b>x = X, y = Y, z = Z</b> in
any order, separated by commas, semicolons or line breaks (<tt>x(u, v) = …</tt> names the
parameters), or a triple <b>(X, Y, Z)</b>, <b>[X, Y, Z]</b> or <b>{X, Y, Z}</b> (also after
<tt>P(u, v) =</tt>, <tt>\\mathbf{r}(u, v) =</tt> or a name, as Maple's <tt>X1 := [X, Y, Z];</tt>;
after <tt>(u, v) -&gt;</tt>, <tt>lambda u, v:</tt> or <tt>return</tt>; inside
<tt>np.array(…)</tt>). The parameters are the two names other than x, y, z that the components use;
the components are rational functions with coefficients as for equations (decimals, square roots).
sorgui decides <b>from the map itself, exactly</b>, whether its image is a surface of revolution
(every normal line meets the axis), a cone or a cylinder, then finds its implicit equation and
analyses that as it would a typed one; the given map is the first of the parameterizations shown. A
map printed with decimals is also asked whether it is, within its rounding, a surface of
revolution. A parameter written only in cos(k·u) and sin(k·u) is an angle, read exactly in
tan(u/2). A curve or a point, a constant component, a function such as exp or tan, one or three
parameters and a zero denominator are refused in one line (docs/math.md §13).</p>
"""

KEYS = (
    ("Ctrl+Return", "analyse the equation"),
    ("Esc", "cancel the running analysis (Singular included)"),
    ("Ctrl++ / Ctrl+− / Ctrl+0", "zoom the formulas in, out, back to normal"),
    ("Ctrl+N, Ctrl+O, Ctrl+S, Ctrl+Shift+S", "new, open, save, save as an equation file"),
    ("Ctrl+E", "export the results to files"),
    ("Ctrl+Shift+C", "copy the report"),
    ("Ctrl+Shift+P", "save a screenshot of the 3D view"),
    ("F1", "this help: the input syntax"),
    ("Ctrl+Q", "quit"),
    ("Ctrl+1 … Ctrl+9", "the examples"),
    ("Ctrl+R", "reset the 3D view"),
    ("Ctrl+Alt+A / Ctrl+Alt+C", "view along / across the axis"),
    ("Ctrl+Alt+X / Y / Z", "view along a coordinate axis"),
    ("Ctrl+Alt+O", "orthographic or perspective projection"),
    ("Ctrl+Alt+W", "wireframe or shaded surface"),
    ("Ctrl+Alt+M", "meridian section: cut along the plane through the axis and the profile"),
    ("P (in the 3D view)", "inspect the surface under the mouse"),
)
MOUSE = (
    ("left drag", "rotate the view"),
    ("Shift + left drag, or middle drag", "move the view"),
    ("wheel, or right drag", "zoom the view"),
    (
        "right click on the surface",
        "inspect the point: its normal, whether the normal meets the axis, and the circle of latitude through it",
    ),
)

RESULTS_HTML = """
<h3>The verdict</h3>
<p>sorgui computes the <b>symmetry algebra L</b> of the surface X: f = 0, the infinitesimal
isometries X ↦ ω × X + b that keep f = 0 (docs/math.md §2). Its dimension and its elements say
what symmetry X has:</p>
<ul>
<li><b>surface of revolution</b>: L is spanned by the rotations about one line, the <b>axis</b>;</li>
<li><b>cylinder of revolution</b>: rotations about the axis and translations along it;</li>
<li><b>sphere</b>: every line through the centre is an axis; <b>plane</b>: every line along the normal;</li>
<li><b>extrusion</b>: only translations along one direction (a cylinder over a plane curve): not a
surface of revolution;</li>
<li><b>none</b>: dim L = 0, no continuous symmetry at all.</li>
</ul>
<p>The <b>profile</b> p(x, y) = 0 is the section by a plane through the axis, with x along the
axis and y the distance to it; <b>P²</b> is the profile with y² replaced by y.</p>
<h3>Table 1 of the paper</h3>
<p>Whether X can be parameterized by rational functions depends on the genera of P and P²
(the geometric genus: 0 for a rational curve):</p>
{table}
<p><b>Rational over ℂ</b>: a parameterization with complex coefficients exists.
<b>Unirational over ℝ</b>: a real rational map covers X, possibly several times.
<b>Rational over ℝ</b>: a real parameterization that is one-to-one almost everywhere exists; for
rows 3 and 4 it depends on the number of real components, decided by the real roots of h.
Every parameterization sorgui shows has been verified exactly by substitution.</p>
<h3>Rounded input</h3>
<p>Decimals in the input are read exactly, but sorgui also asks whether the equation is, within
the rounding of its printed digits, a surface of revolution: it then shows the relative distance,
the approximate axis, and the <b>nearest exact surface</b>, whose exact analysis you can switch to.</p>
"""

CANAL_HTML = """
<h3>Canal surfaces</h3>
<p>A <b>canal surface</b> is the envelope of a one-parameter family of spheres: each sphere touches
the surface along a circle, its <b>characteristic circle</b>. sorgui decides exactly whether X is
one (docs/math.md §9): <b>not canal</b> is proved by a <b>witness line</b> on which the condition
fails exactly; <b>canal</b> by a certificate that X is the envelope of the family found.</p>
<ul>
<li>A <b>family</b> is given by its sphere centres m(t), the <b>spine</b>, and the squared radii
r²(t) (ρ in docs/math.md); the <b>SMAT</b> equations are the curve of (centre, r²) in the space of
spheres. A surface may have several families: a Dupin cyclide, such as a torus, has two.</li>
<li><b>Kinds</b>: a <b>pipe</b> has a constant radius (shown as r², the radius squared); a surface of
revolution has a family whose spine is its axis; a <b>Dupin cyclide</b> is canal in two ways; a
<b>developable</b> canal surface is a cone or a cylinder of revolution.</li>
<li>A spine of genus 0 has a rational m(t), r²(t); its characteristic circles then give a
parameterization of X (checked exactly on f). A spine of positive genus is given in square roots
and drawn numerically.</li>
<li>Inspect a point of a canal surface (right click): the <b>touching sphere</b> of each family there
is drawn, with its characteristic circle.</li>
<li>For rounded input the verdict is about the equation as typed; when it is exactly not canal but its
nearest exact surface of revolution is, the window says "not exactly canal, but nearly".</li>
</ul>
"""

COLOURS = (
    (FRONT_COLOR, "the surface, on the side its mesh normals face"),
    (BACK_COLOR, "the other side of the surface"),
    (AXIS_COLOR, "the axis of revolution"),
    (PROFILE_COLOR, "the profile curve in the meridian plane"),
    (CENTER_COLOR, "the centre of a sphere, the apex of a cone"),
    (BASE_CURVE_COLOR, "the base curve of a cone or a cylinder over a curve, where it lies on the surface"),
    (PATCH_COLOR, "the patch of the first real parameterization (wireframe)"),
    (APPROXIMATE_AXIS_COLOR, "the approximate axis of rounded input"),
    (FACTOR_AXES_COLOR, "the axes of the factors or typed components of a blend"),
    (CANAL_SPINE_COLOR, "the spine of a canal surface (the sphere centres)"),
    (CANAL_CIRCLE_COLOR, "characteristic circles of a canal surface"),
    (NORMAL_COLOR, "the normal line at an inspected point"),
    (LATITUDE_COLOR, "the circle of latitude through an inspected point"),
    (TOUCH_SPHERE_COLOR, "the sphere touching a canal surface at an inspected point"),
    (STALE_COLOR, "a surface of the previous equation (out of date)"),
)
"""Each colour of the 3D view (the viewport's own constants) and what it shows."""


def colours_html() -> str:
    rows = "".join(
        f"<tr><td style='background:{colour}'>&nbsp;&nbsp;&nbsp;&nbsp;&nbsp;&nbsp;</td><td>{words}</td></tr>"
        for colour, words in COLOURS
    )
    return f"<h3>Colours of the 3D view</h3><table cellspacing='4'>{rows}</table>"


LIMITS_HTML = """
<ul>
<li>Total degree at most 60; coefficients rational or in ℚ(√n₁, √n₂, …).</li>
<li>The rationality analysis uses Singular (a subprocess) and stops after the time limit; then
the Table 1 row stays undecided and the recognition is still shown.</li>
<li>Reducible surfaces are recognised as a whole and factor by factor; the rationality analysis
needs an irreducible surface.</li>
<li>The 3D view samples the surface on a grid inside a ball: thin parts, isolated real points and
singular curves may not be drawn.</li>
<li>For rounded input the nearness is a floating-point judgement against the tolerance; the
nearest exact surface is exact, and its own analysis is exact.</li>
</ul>
"""

PAPER_HTML = """
<p>sorgui implements</p>
<blockquote>J. Vršek, M. Lávička, <i>Determining surfaces of revolution from their implicit
equations</i>, Journal of Computational and Applied Mathematics.</blockquote>
<p>Its DOI, and the journal's page, are one search away:
<a href="https://search.crossref.org/search/works?q=Determining+surfaces+of+revolution+from+their+implicit+equations&from_ui=yes">Crossref</a>
(sorgui does not print a DOI it could not check against the paper's source).</p>
<p>Its Section 2 is the recognition (the symmetry algebra and the axis), its Section 3 the
rationality (Table 1 and the tubular surface), its Appendix the two examples in the Examples menu.
The repository's own account of the mathematics is <tt>docs/math.md</tt>.</p>
"""


def _rows(rows: tuple[tuple[str, str], ...]) -> str:
    cells = "".join(f"<tr><td><b>{html.escape(a)}</b></td><td>{html.escape(b)}</td></tr>" for a, b in rows)
    return f"<table cellspacing='4'>{cells}</table>"


def table_1_html() -> str:
    head = "<tr><th>row</th><th>genus(P)</th><th>genus(P²)</th><th>X over ℂ</th><th>X over ℝ</th></tr>"
    body = "".join(
        f"<tr><td align='center'>{i + 1}</td>" + "".join(f"<td align='center'>{c}</td>" for c in row) + "</tr>"
        for i, row in enumerate(TABLE_1)
    )
    words = "".join(f"<li>Row {i + 1}: {html.escape(w)}</li>" for i, w in enumerate(TABLE_1_WORDS))
    return f"<table border='1' cellspacing='0' cellpadding='4'>{head}{body}</table><ul>{words}</ul>"


TOPICS = {
    "syntax": (
        "Input Syntax",
        "<h3>Input syntax</h3><p>Type a polynomial in x, y, z, an equation (left = right), or a "
        "parametrization x = …, y = …, z = … in two parameters. Nothing you type is ever run as code: "
        "sorgui has its own parser.</p>" + _rows(SYNTAX_EXAMPLES) + PARAMETRIZATIONS_HTML,
    ),
    "keys": (
        "Mouse and Keys",
        "<h3>Keys</h3>"
        + _rows(KEYS)
        + "<h3>Mouse in the 3D view</h3>"
        + _rows(MOUSE)
        + "<p>VTK's own keys (wireframe, stereo, quit, …) are switched off.</p>",
    ),
    "results": ("What the Results Mean", RESULTS_HTML.replace("{table}", table_1_html())),
    "canal": ("Canal Surfaces", CANAL_HTML),
    "colours": ("Colours of the 3D View", colours_html()),
    "paper": ("The Paper", PAPER_HTML),
    "limits": ("Known Limits", "<h3>Known limits</h3>" + LIMITS_HTML),
}
"""Help topic → (menu title, HTML page)."""


class HelpDialog(QDialog):
    """A non-modal window showing one help topic at a time."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("helpDialog")
        self.resize(640, 560)
        self.browser = QTextBrowser(self)
        self.browser.setOpenExternalLinks(True)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close, self)
        buttons.rejected.connect(self.close)
        layout = QVBoxLayout(self)
        layout.addWidget(self.browser)
        layout.addWidget(buttons)

    def show_topic(self, topic: str) -> None:
        title, page = TOPICS[topic]
        self.setWindowTitle(f"{title} — sorgui")
        self.browser.setHtml(page)
        self.show()
        self.raise_()
