"""The line complex of sampled normals (docs/math.md §12): points and normals sampled on known
surfaces about an oblique axis give back the kind, the axis and the radii; noise of 1e-9 stays
within 1e-8; a surface with no symmetry fits nothing."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sorgui.engine.rounded import line_complex as lc

CENTRE = np.array([1.0, 2.0, 3.0])
AXIS = np.array([1.0, 1.0, 1.0]) / math.sqrt(3.0)
Profile = Callable[[float], tuple[float, float, float, float]]
"""``t ↦ (h, r, dh/dt, dr/dt)``: a meridian curve and its derivative."""


def revolved(profile: Profile, noise: float = 0.0, seed: int = 0, turn: float = 4.0) -> lc.Samples:
    """Samples of the surface of revolution of ``profile`` about the axis through ``CENTRE``
    along ``AXIS``, over ``turn`` radians, with ``noise`` added to the points."""
    e1, e2 = lc.across(AXIS)
    points, normals = [], []
    for t in np.linspace(0.0, 1.0, 20):
        h, r, dh, dr = profile(float(t))
        for theta in np.linspace(0.0, turn, 20):
            radial = math.cos(theta) * e1 + math.sin(theta) * e2
            tangent = -math.sin(theta) * e1 + math.cos(theta) * e2
            points.append(CENTRE + h * AXIS + r * radial)
            n = np.cross(dh * AXIS + dr * radial, tangent)
            normals.append(n / np.linalg.norm(n))
    p = np.array(points)
    if noise:
        p = p + noise * np.random.default_rng(seed).standard_normal(p.shape)
    return lc.Samples(p, np.array(normals))


def cylinder(t: float) -> tuple[float, float, float, float]:
    return 3 * t, 2.0, 3.0, 0.0


def cone(t: float) -> tuple[float, float, float, float]:
    return 3 * t, 1 + t, 3.0, 1.0


def torus(t: float) -> tuple[float, float, float, float]:
    return math.cos(3 * t), 4 + math.sin(3 * t), -3 * math.sin(3 * t), 3 * math.cos(3 * t)


def sphere(t: float) -> tuple[float, float, float, float]:
    a = 2 * t + 0.3
    return 2 * math.cos(a), 2 * math.sin(a), -4 * math.sin(a), 4 * math.cos(a)


def wavy(t: float) -> tuple[float, float, float, float]:
    return 3 * t, 2 + math.sin(3 * t), 3.0, 3 * math.cos(3 * t)


def first_fit(samples: lc.Samples, tolerance: float) -> lc.SurfaceFit | None:
    for fit in lc.analytic_fits(samples, tolerance):
        if fit.deviation is not None and fit.deviation <= tolerance:
            return fit
    return None


def on_axis(fit: lc.SurfaceFit, within: float) -> None:
    assert fit.axis is not None
    d = np.array(fit.axis.direction)
    assert np.linalg.norm(np.cross(d, AXIS)) < within
    assert np.linalg.norm(np.cross(np.array(fit.axis.point) - CENTRE, AXIS)) < within


@pytest.mark.parametrize(
    ("profile", "kind"), [(cylinder, lc.CYLINDER), (cone, lc.CONE), (torus, lc.TORUS), (sphere, lc.SPHERE)]
)
@pytest.mark.parametrize("noise", [0.0, 1e-9])
def test_analytic_kinds_about_an_oblique_axis(profile: Profile, kind: str, noise: float) -> None:
    samples = revolved(profile, noise)
    fit = first_fit(samples, 1e-7)
    assert fit is not None and fit.kind == kind
    assert fit.deviation is not None and fit.deviation <= (1e-12 if noise == 0 else 1e-8)
    if kind == lc.SPHERE:
        assert np.linalg.norm(np.array(fit.center) - CENTRE) < 1e-8 and fit.radius == pytest.approx(2.0, abs=1e-8)
        return
    on_axis(fit, 1e-8)
    if kind == lc.CYLINDER:
        assert fit.radius == pytest.approx(2.0, abs=1e-8)
    elif kind == lc.CONE:
        assert fit.half_angle == pytest.approx(math.atan(1 / 3), abs=1e-8)
        assert np.linalg.norm(np.array(fit.center) - (CENTRE - 3 * AXIS)) < 1e-7
    else:
        assert (fit.radius, fit.minor_radius) == (pytest.approx(4.0, abs=1e-8), pytest.approx(1.0, abs=1e-8))


def test_a_general_profile_is_no_analytic_surface_but_has_the_axis() -> None:
    samples = revolved(wavy)
    assert first_fit(samples, 1e-7) is None
    fit = lc.revolution_fit(samples)
    assert fit is not None and fit.axis is not None
    on_axis(fit, 1e-10)
    assert lc.normal_miss(samples, fit.axis).max() < 1e-10
    _, r = lc.reduced(fit, samples.points).T
    height = (samples.points - CENTRE) @ AXIS
    assert np.abs(r - (2 + np.sin(height))).max() < 1e-10


def test_the_smallest_singular_values_count_the_motions() -> None:
    """One small singular value for a surface of revolution, two for a cylinder, three for a
    sphere (the classification of docs/math.md §2)."""
    for profile, small in ((wavy, 1), (cylinder, 2), (sphere, 3)):
        sigma, _ = lc.normal_lines(revolved(profile))
        assert np.all(sigma[6 - small :] < 1e-12) and sigma[5 - small] > 1e-3


def test_extrusion_and_cone_over_a_curve() -> None:
    t = np.linspace(0.0, 2.0, 25)
    curve = np.column_stack([t, np.sin(2 * t), np.zeros_like(t)])
    tangent = np.column_stack([np.ones_like(t), 2 * np.cos(2 * t), np.zeros_like(t)])
    d = np.array([0.3, 0.2, 3.0])
    d /= np.linalg.norm(d)
    points = np.vstack([curve + s * d for s in np.linspace(0, 2, 10)])
    normals = np.vstack([np.cross(tangent, d) for _ in range(10)])
    samples = lc.Samples(points, normals / np.linalg.norm(normals, axis=1)[:, None])
    extrusion = lc.extrusion_fit(samples)
    assert extrusion.direction is not None and np.linalg.norm(np.cross(extrusion.direction, d)) < 1e-12
    apex = np.array([1.0, 0.5, 5.0])
    rays = [(apex + s * (curve - apex), np.cross(tangent, curve - apex)) for s in np.linspace(0.2, 1, 10)]
    points = np.vstack([p for p, _ in rays])
    normals = np.vstack([n / np.linalg.norm(n, axis=1)[:, None] for _, n in rays])
    cone = lc.cone_over_curve_fit(lc.Samples(points, normals))
    assert cone.deviation is not None and cone.deviation < 1e-12
    assert np.linalg.norm(np.array(cone.center) - apex) < 1e-10


@settings(max_examples=20, deadline=None)
@given(st.integers(0, 10_000))
def test_no_symmetry_fits_nothing(seed: int) -> None:
    """A bumpy graph ``z = g(x, y)`` is no analytic surface, and its normals meet no line."""
    rng = np.random.default_rng(seed)
    a = rng.uniform(0.3, 1.0, 4)
    x, y = np.meshgrid(np.linspace(0, 3, 15), np.linspace(0, 3, 15))
    x, y = x.ravel(), y.ravel()
    z = a[0] * np.sin(x + a[1] * y) + a[2] * np.cos(a[3] * x * y)
    gx = a[0] * np.cos(x + a[1] * y) - a[2] * a[3] * y * np.sin(a[3] * x * y)
    gy = a[0] * a[1] * np.cos(x + a[1] * y) - a[2] * a[3] * x * np.sin(a[3] * x * y)
    normals = np.column_stack([-gx, -gy, np.ones_like(x)])
    samples = lc.Samples(np.column_stack([x, y, z]), normals / np.linalg.norm(normals, axis=1)[:, None])
    assert first_fit(samples, 1e-4) is None
    fit = lc.revolution_fit(samples)
    assert fit is None or fit.axis is None or lc.normal_miss(samples, fit.axis).max() > 1e-3
