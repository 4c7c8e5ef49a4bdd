"""The fast evaluators agree with term-by-term numpy evaluation and never overflow."""

from __future__ import annotations

import numpy as np
import pytest

from sorgui.render.sampling import (
    evaluate_points,
    gradient_points,
    profile_terms,
    sample_grid,
    sample_grid_2d,
    term_arrays,
    total_degree,
    value_and_gradient,
)
from tests.render.surfaces import (
    SPHERE,
    TORUS,
    TORUS_PROFILE_SR,
    corpus_terms,
    direct,
    random_terms,
)


@pytest.mark.parametrize("seed", range(5))
def test_grid_matches_direct_evaluation_on_random_terms(seed):
    rng = np.random.default_rng(seed)
    terms = random_terms(rng, n=25, degree=6)
    xs, ys, zs = (np.sort(rng.uniform(-2, 2, n)) for n in (7, 5, 4))
    z, y, x = np.meshgrid(zs, ys, xs, indexing="ij")
    expected = direct(terms, x, y, z)
    got = sample_grid(terms, xs, ys, zs, normalise=False)
    assert got.shape == (4, 5, 7) and got.flags.c_contiguous
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


@pytest.mark.parametrize("seed", range(3))
def test_grid_2d_matches_direct_evaluation(seed):
    rng = np.random.default_rng(seed)
    terms = random_terms(rng, n=15, degree=6, nvars=2)
    ss, rs = np.linspace(-3, 1, 9), np.linspace(-1, 2, 6)
    r, s = np.meshgrid(rs, ss, indexing="ij")
    expected = sum(c * s**i * r**j for (i, j), c in terms)
    got = sample_grid_2d(terms, ss, rs, normalise=False)
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


@pytest.mark.parametrize("seed", range(3))
def test_points_value_and_gradient_match_direct_evaluation(seed):
    rng = np.random.default_rng(seed)
    terms = random_terms(rng, n=20, degree=5)
    pts = rng.normal(size=(50, 3))
    x, y, z = pts.T
    grad = np.column_stack(
        [
            direct([((i - 1, j, k), c * i) for (i, j, k), c in terms if i], x, y, z),
            direct([((i, j - 1, k), c * j) for (i, j, k), c in terms if j], x, y, z),
            direct([((i, j, k - 1), c * k) for (i, j, k), c in terms if k], x, y, z),
        ]
    )
    values, grads = value_and_gradient(terms, pts)
    scale = np.abs(direct(terms, x, y, z)).max()
    np.testing.assert_allclose(values, direct(terms, x, y, z), rtol=1e-12, atol=1e-12 * scale)
    np.testing.assert_allclose(grads, grad, rtol=1e-11, atol=1e-11 * np.abs(grad).max())
    np.testing.assert_allclose(evaluate_points(terms, pts), values)
    np.testing.assert_allclose(gradient_points(terms, pts), grads)


def test_points_in_two_variables_and_nonfinite_points():
    values, grads = value_and_gradient(TORUS_PROFILE_SR, [[0.0, 1.0], [0.0, 3.0], [np.nan, 0]])
    np.testing.assert_allclose(values[:2], [0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(grads[0], [0.0, 4 * 1 * 4 - 32], atol=1e-12)
    assert np.isnan(values[2]) and np.all(np.isnan(grads[2]))


def test_normalised_grid_has_unit_peak_and_the_same_signs():
    axis = np.linspace(-1.3, 1.1, 11)
    raw = sample_grid(SPHERE, axis, axis, axis, normalise=False)
    normalised = sample_grid(SPHERE, axis, axis, axis)
    assert np.abs(normalised).max() == pytest.approx(1.0)
    np.testing.assert_array_equal(np.sign(raw), np.sign(normalised))


def test_huge_coefficients_and_coordinates_do_not_overflow():
    # x^10 + y^10 + z^10 - 1e300 on a box of size 1e31: the raw values overflow float64.
    terms = [((10, 0, 0), 1.0), ((0, 10, 0), 1.0), ((0, 0, 10), 1.0), ((0, 0, 0), -1e300)]
    axis = np.linspace(-2e30, 2e30, 20)  # no node on the surface
    values = sample_grid(terms, axis, axis, axis)
    assert np.all(np.isfinite(values))
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    expected_sign = np.sign((x / 1e30) ** 10 + (y / 1e30) ** 10 + (z / 1e30) ** 10 - 1.0)
    np.testing.assert_array_equal(np.sign(values), expected_sign)
    _, grads = value_and_gradient(terms, [[1e30, 0.0, 0.0]], normalise=True)
    assert np.all(np.isfinite(grads)) and grads[0, 0] > 0 and grads[0, 1] == 0
    tiny = [(e, c * 1e-300) for e, c in SPHERE]
    axis = np.linspace(-2, 2, 9)
    expected = sample_grid(SPHERE, axis, axis, axis)
    np.testing.assert_allclose(sample_grid(tiny, axis, axis, axis), expected)


def test_term_arrays_merges_drops_and_validates():
    exps, coefs = term_arrays([((1, 0, 0), 2.0), ((1, 0, 0), -0.5), ((0, 0, 0), 0.0)], 3)
    assert exps.tolist() == [[1, 0, 0]] and coefs.tolist() == [1.5]
    assert total_degree(TORUS) == 4 and total_degree([]) == -1
    for bad in ([((-1, 0, 0), 1.0)], [((1, 0), 1.0)], [((1, 0, 0), np.nan)], [((0.5, 0, 0), 1)]):
        with pytest.raises(ValueError):
            term_arrays(bad, 3)


def test_zero_polynomial_samples_to_zero():
    axis = np.linspace(-1, 1, 4)
    assert not np.any(sample_grid([], axis, axis, axis))


def test_profile_terms_of_the_torus():
    got = dict(profile_terms(TORUS, (0, 0, 0), (0, 0, 1), (1, 0, 0)))
    assert got == pytest.approx(dict(TORUS_PROFILE_SR))


def test_profile_terms_agree_with_substitution_at_random_points():
    rng = np.random.default_rng(7)
    terms = random_terms(rng, n=12, degree=3)
    c, a = rng.normal(size=3), rng.normal(size=3)
    u = np.cross(a, rng.normal(size=3))
    sr = rng.normal(size=(20, 2))
    p = c + sr[:, :1] * a + sr[:, 1:] * u
    expected = direct(terms, *p.T)
    got = evaluate_points(profile_terms(terms, c, a, u), sr)
    np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())


def test_profile_terms_of_paper_example_1_match_math_md():
    # docs/math.md §7: c = (3/5, -4/5, 0), a = (4, 3, 0)/5, u = (0, 0, 1) gives
    # 15625·(r⁶ + 12r⁴s - 29r⁴ + 26r²s² - 48r²s + 200r² - s⁴ - 104s² - 400).
    terms = corpus_terms("paper-example-1")
    got = dict(profile_terms(terms, (0.6, -0.8, 0), (0.8, 0.6, 0), (0, 0, 1)))
    expected = {
        (0, 6): 1, (1, 4): 12, (0, 4): -29, (2, 2): 26, (1, 2): -48, (0, 2): 200,
        (4, 0): -1, (2, 0): -104, (0, 0): -400,
    }  # fmt: skip
    significant = {k: v / 15625 for k, v in got.items() if abs(v) > 1e-6 * 15625}
    assert significant == pytest.approx(expected, rel=1e-9)
