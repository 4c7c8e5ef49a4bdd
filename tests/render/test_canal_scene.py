"""The canal scene data (spines and characteristic circles) as plain arrays, without Qt."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sorgui.engine.canal import analyze_canal
from sorgui.engine.parsing import parse_polynomial
from sorgui.engine.polys import to_flint
from sorgui.render.canal_scene import canal_scene

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
    return text, canal_scene(analyze_canal(parse_polynomial(text).polynomial), bound=10.0)


def test_spine_is_the_ellipse_of_ball_centres(blend) -> None:
    _, scene = blend
    points = np.vstack(scene.spines)
    assert len(points) > 100
    # The ball centres: x² + y² = 9 on the plane 3x + 4z = 5.
    assert np.allclose(points[:, 0] ** 2 + points[:, 1] ** 2, 9, atol=1e-8)
    assert np.allclose(3 * points[:, 0] + 4 * points[:, 2], 5, atol=1e-8)


def test_characteristic_circles_lie_on_the_surface(blend) -> None:
    text, scene = blend
    assert len(scene.circles) >= 6
    for ring in scene.circles:
        assert ring.shape[1] == 3 and np.allclose(ring[0], ring[-1])
        assert relative_values(text, ring).max() < 1e-9


def test_no_rational_family_gives_an_empty_scene() -> None:
    from sorgui.engine.report import Canal

    scene = canal_scene(Canal(False, "not canal"))
    assert scene.spines == () and scene.circles == ()
