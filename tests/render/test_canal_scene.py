"""The canal scene data (spines and characteristic circles) as plain arrays, without Qt."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sorgui.engine.algebra.polys import to_flint
from sorgui.engine.canal.verdict import analyze_canal
from sorgui.engine.parsing import parse_polynomial
from sorgui.numerics import real_roots
from sorgui.render.canal_scene import canal_scene
from sorgui.session.canal_data import family_curves

EXAMPLES = Path(__file__).resolve().parents[1] / "data" / "canal-examples.txt"


def example(prefix: str) -> str:
    lines = EXAMPLES.read_text(encoding="utf-8").splitlines()
    return next(lines[i + 1] for i, line in enumerate(lines) if line.startswith("## " + prefix))


def relative_values(text: str, points: np.ndarray) -> np.ndarray:
    """``|f(p)| / Σ|c_α p^α|``: the value of ``f`` relative to the size of its terms."""
    f = to_flint(parse_polynomial(text).polynomial)
    value, size = np.zeros(len(points)), np.zeros(len(points))
    for monom, coeff in zip(f.monoms(), f.coeffs()):
        term = float(coeff) * np.prod(points ** np.array(monom, dtype=float), axis=1)
        value += term
        size += np.abs(term)
    return np.abs(value) / size


@pytest.fixture(scope="module")
def blend() -> tuple[str, object]:
    text = example("blend cyl R=2 / plane 3x+4z=0")
    return text, canal_scene(family_curves(analyze_canal(parse_polynomial(text).polynomial)), bound=10.0)


def test_spine_is_the_ellipse_of_ball_centres(blend) -> None:
    _, scene = blend
    points = np.vstack(scene.spines)
    assert len(points) > 100
    # The ball centres: x² + y² = 9 on the plane 3x + 4z = 5.
    assert np.allclose(points[:, 0] ** 2 + points[:, 1] ** 2, 9, atol=1e-8)
    assert np.allclose(3 * points[:, 0] + 4 * points[:, 2], 5, atol=1e-8)


def test_a_closed_spine_is_drawn_closed(blend) -> None:
    """The ellipse of ball centres passes through its point at ``t = ∞``: it was drawn from
    ``t = tan(−π/2 + ε)`` to ``tan(π/2 − ε)``, with a gap of 0.09 there."""
    _, scene = blend
    closed = [spine for spine in scene.spines if len(spine) > 100]
    assert closed and all(np.allclose(spine[0], spine[-1], atol=1e-9) for spine in closed)


def test_characteristic_circles_lie_on_the_surface(blend) -> None:
    text, scene = blend
    assert len(scene.circles) >= 6
    for ring in scene.circles:
        assert ring.shape[1] == 3 and np.allclose(ring[0], ring[-1])
        assert relative_values(text, ring).max() < 1e-9


def test_no_rational_family_gives_an_empty_scene() -> None:
    from sorgui.engine.results import Canal

    scene = canal_scene(family_curves(Canal(False, "not canal")))
    assert scene.spines == () and scene.circles == ()


def test_touching_sphere_of_a_spine_of_genus_1() -> None:
    """The two-cylinder blend's spine has genus 1 (no m(t)): the sphere touching the surface at
    a point is found from the SMAT equations on the normal line, its centre on the spine
    (y² + z² = 16, x² + z² = 9), its radius 1, and its characteristic circle on the surface."""
    from sorgui.engine.canal.verdict import analyze_canal
    from sorgui.engine.rounded import dense
    from sorgui.engine.values import polynomial_terms
    from sorgui.render.canal_scene import SmatFamily
    from sorgui.render.canal_touch import touching_spheres
    from sorgui.render.picking import pick_info

    text = example("blend cylinders R=2")
    canal = analyze_canal(parse_polynomial(text).polynomial, full=False)
    families = family_curves(canal)
    assert len(families) == 1 and isinstance(families[0], SmatFamily)
    terms = polynomial_terms(text)
    array = dense.from_terms({tuple(e): c for e, c in terms}, 24)
    rng = np.random.default_rng(7)
    touched = 0
    for _ in range(12):
        start, direction = rng.normal(size=3) * 2, rng.normal(size=3)
        for t in real_roots(dense.restriction_to_line(array, start, direction)):
            info = pick_info(terms, start + t * direction, axis=None, normal_length=1.0, snap_distance=0.1)
            for touch in touching_spheres(families, info.point, 1e-6, normal=info.normal_direction):
                x, y, z = touch.center
                assert abs(y * y + z * z - 16) < 1e-6 and abs(x * x + z * z - 9) < 1e-6
                assert abs(touch.radius - 1) < 1e-9 and abs(np.linalg.norm(info.point - touch.center) - 1) < 1e-6
                assert relative_values(text, touch.circle).max() < 1e-6
                touched += 1
    assert touched >= 10


def test_a_spine_of_genus_1_is_traced_with_its_circles() -> None:
    """The two-cylinder blend's spine (y² + z² = 16, x² + z² = 9: two closed curves) is traced
    from points of the surface, and its characteristic circles lie on the surface."""
    from sorgui.engine.canal.verdict import analyze_canal
    from sorgui.engine.rounded import dense
    from sorgui.engine.values import polynomial_terms
    from sorgui.render.canal_trace import smat_scene
    from sorgui.render.sampling import value_and_gradient

    text = example("blend cylinders R=2")
    families = family_curves(analyze_canal(parse_polynomial(text).polynomial, full=False))
    terms = polynomial_terms(text)
    array = dense.from_terms({tuple(e): c for e, c in terms}, 24)
    rng = np.random.default_rng(3)
    points = []
    for _ in range(30):
        start, direction = rng.normal(size=3) * 2, rng.normal(size=3)
        points += [start + t * direction for t in real_roots(dense.restriction_to_line(array, start, direction))]
    points = np.array(points)
    _, gradients = value_and_gradient(terms, points)
    scene = smat_scene(
        families, points, gradients / np.linalg.norm(gradients, axis=1, keepdims=True), bound=12.0, step=0.1
    )
    assert len(scene.spines) == 2
    for spine in scene.spines:
        x, y, z = spine.T
        assert len(spine) > 100 and np.allclose(spine[0], spine[-1])
        assert np.abs(y * y + z * z - 16).max() < 1e-5 and np.abs(x * x + z * z - 9).max() < 1e-5
    assert len(scene.circles) == 12
    assert max(relative_values(text, ring).max() for ring in scene.circles) < 1e-9


def test_a_polyline_is_cut_where_it_crosses_the_ball() -> None:
    """The pieces inside the ball end on its sphere (exactly where the segments cross it), and
    a non-finite point ends a piece."""
    from sorgui.render.geometry import ClipSphere, clip_to_ball

    ball = ClipSphere((0.0, 0.0, 0.0), 1.0)
    line = np.array([[-2.0, 0, 0], [-0.5, 0, 0], [0.5, 0, 0], [np.nan, 0, 0], [0.2, 0, 0], [0.6, 0, 0], [3.0, 0, 0]])
    pieces = clip_to_ball(line, ball)
    assert [piece[:, 0].tolist() for piece in pieces] == [[-1.0, -0.5, 0.5], [0.2, 0.6, 1.0]]
    circle = np.array([[np.cos(a), np.sin(a), 0.0] for a in np.linspace(0, 2 * np.pi, 65)]) * 2.0
    assert clip_to_ball(circle, ball) == []
    assert len(clip_to_ball(circle, ClipSphere((2.0, 0.0, 0.0), 1.0))) == 2  # the arc each side of its start


def test_the_canal_circles_of_a_cylinder_lie_in_the_drawn_ball() -> None:
    """A cylinder's characteristic circles beyond the drawn ball floated above and below the
    surface: they are cut to the ball, as the surface is."""
    from sorgui.engine.analysis import analyze
    from sorgui.session.scene_data import build_scene, with_canal

    analysis = analyze("x^2 + y^2 - 1")
    scene = with_canal(build_scene(analysis, 2.0, 40, patch=False), analysis)
    points = np.asarray(scene.canal_circles.points)
    assert len(points) > 0
    distances = np.linalg.norm(points - np.asarray(scene.region.center), axis=1)
    assert distances.max() <= scene.region.radius * (1 + 1e-9)
    assert np.allclose(np.hypot(points[:, 0], points[:, 1]), 1.0)  # on the cylinder
