"""Axis, profile curve, latitude circles, normals, markers and parametric overlays."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sorgui.render.geometry import ClipBox, ClipSphere
from sorgui.render.sampling import evaluate_points, profile_terms
from sorgui.render.scene import (
    LineData,
    axis_line,
    latitude_circle,
    normal_line,
    parametric_patch,
    profile_curve,
    sphere_center_marker,
    to_polydata,
)
from tests.render.surfaces import EMPTY_ELLIPSOID, TORUS, TORUS_PROFILE_SR

CUBE = (-4, 4, -4, 4, -4, 4)


def assert_two_unit_circles_at_distance_2(curve: LineData, tol: float) -> None:
    """The torus profile: circles of radius 1 about (±2, 0, 0) in the plane y = 0."""
    polylines = curve.polylines()
    assert len(polylines) == 2
    centres = []
    for line in polylines:
        assert np.array_equal(line[0], line[-1])  # closed
        centre = np.array([2.0 * np.sign(line[:, 0].mean()), 0.0, 0.0])
        np.testing.assert_allclose(np.linalg.norm(line - centre, axis=1), 1.0, atol=tol)
        np.testing.assert_allclose(line[:, 1], 0.0, atol=1e-12)
        centres.append(centre[0])
    assert sorted(centres) == [-2.0, 2.0]


def test_torus_profile_curve_is_two_unit_circles_at_distance_2_from_the_axis():
    curve = profile_curve(TORUS_PROFILE_SR, (0, 0, 0), (0, 0, 1), (1, 0, 0), CUBE, 300)
    assert_two_unit_circles_at_distance_2(curve, tol=1e-6)


def test_profile_curve_with_non_unit_frame_vectors():
    # c on the axis but not at the centre, |a| = 2, |u| = 3: p̃ is f(c + s·a + r·u).
    c, a, u = (0.0, 0.0, 0.5), (0.0, 0.0, 2.0), (3.0, 0.0, 0.0)
    curve = profile_curve(profile_terms(TORUS, c, a, u), c, a, u, ClipSphere((0, 0, 0), 5.0))
    assert_two_unit_circles_at_distance_2(curve, tol=1e-6)


def test_profile_curve_is_clipped_to_the_region():
    curve = profile_curve(TORUS_PROFILE_SR, (0, 0, 0), (0, 0, 1), (1, 0, 0), (-2.5, 2.5) * 3)
    assert len(curve.polylines()) == 2  # two arcs, cut at x = ±2.5
    assert np.abs(curve.points[:, 0]).max() == pytest.approx(2.5)
    assert np.abs(curve.points[:, 0]).min() == pytest.approx(1.0, abs=1e-2)  # inner arcs
    for line in curve.polylines():
        assert not np.array_equal(line[0], line[-1])


def test_profile_curve_without_real_points_is_empty():
    empty = profile_terms(EMPTY_ELLIPSOID, (0, 0, 0), (0, 0, 1), (1, 0, 0))
    assert profile_curve(empty, (0, 0, 0), (0, 0, 1), (1, 0, 0), CUBE).is_empty
    assert to_polydata(LineData.empty()).n_points == 0


def test_profile_curve_rejects_u_not_orthogonal_to_the_axis():
    with pytest.raises(ValueError):
        profile_curve(TORUS_PROFILE_SR, (0, 0, 0), (0, 0, 1), (1, 0, 1), CUBE)


@pytest.mark.parametrize("region", [ClipBox(CUBE), ClipSphere((1.0, 0.5, 0.0), 3.0), CUBE])
def test_axis_line_endpoints_lie_on_the_line_and_the_region_boundary(region):
    c, a = np.array([0.6, -0.8, 0.0]), np.array([4.0, 3.0, 0.0])
    line = axis_line(c, a, region)
    assert line.points.shape == (2, 3) and line.lines.tolist() == [2, 0, 1]
    for p in line.points:
        np.testing.assert_allclose(np.cross(p - c, a), 0.0, atol=1e-12)
    if isinstance(region, ClipSphere):
        np.testing.assert_allclose(np.linalg.norm(line.points - region.center, axis=1), 3.0)
    else:
        assert np.all(np.isclose(np.abs(line.points), 4.0).any(axis=1))
        assert np.all(np.abs(line.points) <= 4.0 + 1e-12)


def test_axis_line_missing_the_region_is_empty():
    assert axis_line((10, 10, 0), (0, 0, 1), CUBE).is_empty
    assert axis_line((10, 10, 0), (0, 0, 1), ClipSphere((0, 0, 0), 1)).is_empty


def test_latitude_circle_of_the_torus_is_on_the_surface_and_about_the_axis():
    p = np.array([2.0 + math.cos(0.7), 0.0, math.sin(0.7)])
    p = np.array([p[0] * math.cos(1.1), p[0] * math.sin(1.1), p[2]])
    circle = latitude_circle(p, (0, 0, -3), (0, 0, 5), n=64)
    points = circle.polylines()[0]
    assert len(points) == 65 and np.array_equal(points[0], points[-1])
    np.testing.assert_allclose(points[0], p)
    np.testing.assert_allclose(np.hypot(points[:, 0], points[:, 1]), np.hypot(p[0], p[1]))
    np.testing.assert_allclose(points[:, 2], p[2])
    assert np.abs(evaluate_points(TORUS, points)).max() < 1e-12


def test_latitude_circle_through_a_point_of_the_axis_is_empty():
    assert latitude_circle((0, 0, 1), (0, 0, 0), (0, 0, 1)).is_empty


def test_normal_line_is_centred_along_the_gradient():
    line = normal_line((1, 2, 3), (0, 0, 5), 2.0)
    np.testing.assert_allclose(line.points, [[1, 2, 2], [1, 2, 4]])
    assert normal_line((1, 2, 3), (0, 0, 0), 2.0).is_empty


def test_sphere_center_marker():
    marker = sphere_center_marker((1, 0, 0), ClipSphere((0, 0, 0), 10.0), relative_size=0.02)
    assert marker.center == (1.0, 0.0, 0.0) and marker.radius == pytest.approx(0.2)
    poly = to_polydata(marker)
    np.testing.assert_allclose(poly.center, (1, 0, 0), atol=1e-2)


def test_parametric_patch_masks_poles_and_failing_points():
    # The unit sphere by stereographic projection has a pole at infinity; 1/s has one at 0.
    def fx(s, t):
        return 2 * s / (1 + s * s + t * t)

    def fz(s, t):
        return 1.0 / s  # inf (vectorised) at s = 0

    patch = parametric_patch(fx, 0.0, fz, (-1, 1), (-1, 1), n=(5, 4))
    assert patch.points.shape == (5, 4, 3) and patch.mask.shape == (5, 4)
    assert not patch.mask[2].any() and patch.mask[[0, 1, 3, 4]].all()
    assert np.isnan(patch.points[2]).all()
    poly = to_polydata(patch)
    assert poly.n_cells == 2 * 3  # rows 0-1 and 3-4, three quads each
    assert np.all(np.isfinite(poly.points))

    def scalar_only(s, t):
        return 1.0 / (s - t) if isinstance(s, float) else float(s)  # not vectorised

    patch = parametric_patch(scalar_only, 0.0, 0.0, (0, 1), (0, 1), n=3)
    np.testing.assert_array_equal(patch.mask, ~np.eye(3, dtype=bool))


def test_parametric_patch_region_mask():
    unit_cube = (-1, 1, -1, 1, -1, 1)
    patch = parametric_patch(lambda s, t: s, lambda s, t: t, 0.0, (-2, 2), (-2, 2), 9, unit_cube)
    assert patch.mask.sum() == 25  # |s|, |t| ≤ 1 on the 9-point grid


def test_plain_data_survives_pickling():
    # Scenes are built in a worker process and cross to the GUI by pickling.
    import pickle

    from sorgui.render.mesh import surface_mesh
    from sorgui.render.picking import pick_info

    items = [
        surface_mesh(TORUS, CUBE, resolution=30),
        profile_curve(TORUS_PROFILE_SR, (0, 0, 0), (0, 0, 1), (1, 0, 0), CUBE, 100),
        sphere_center_marker((0, 0, 0), CUBE),
        parametric_patch(lambda s, t: s, lambda s, t: t, 0.0, (0, 1), (0, 1), 4),
        pick_info(TORUS, (3.0, 0.0, 0.0), axis=((0, 0, 0), (0, 0, 1))),
    ]
    for item in items:
        copy = pickle.loads(pickle.dumps(item))
        for name, value in vars(item).items():
            if isinstance(value, np.ndarray):
                np.testing.assert_array_equal(getattr(copy, name), value)
