"""Picking: f, ∇f, the normal line and whether it meets an axis (docs/math.md §2)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sorgui.render.mesh import surface_mesh
from sorgui.render.picking import (
    axis_coordinates,
    normal_meets_axis,
    pick_info,
    pick_many,
    snap_to_surface,
)
from sorgui.render.sampling import evaluate_points
from tests.render.surfaces import CONE, ELLIPSOID, TORUS

Z_AXIS = ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))


def torus_point(phi: float, theta: float) -> np.ndarray:
    """The torus point at angle ``phi`` about the z-axis and ``theta`` around the tube."""
    rho = 2.0 + math.cos(theta)
    return np.array([rho * math.cos(phi), rho * math.sin(phi), math.sin(theta)])


@pytest.mark.parametrize("phi,theta", [(0.3, 0.4), (2.0, 2.5), (-1.0, -2.0), (4.0, 1.2)])
def test_torus_normal_meets_the_z_axis(phi, theta):
    info = pick_info(TORUS, torus_point(phi, theta), axis=Z_AXIS, normal_length=2.0)
    assert abs(info.value) < 1e-12
    assert info.meets_axis is True
    assert info.axis_distance == pytest.approx(0.0, abs=1e-12)
    assert info.normal.points.shape == (2, 3)
    assert info.height == pytest.approx(math.sin(theta))
    assert info.radius == pytest.approx(2.0 + math.cos(theta))
    assert "meets the axis" in info.summary()


def test_torus_mesh_points_all_have_normals_meeting_the_axis():
    mesh = surface_mesh(TORUS, (-3.2, 3.2, -3.2, 3.2, -1.2, 1.2), resolution=60)
    assert pick_many(TORUS, mesh.points, Z_AXIS).all()
    info = pick_info(TORUS, mesh.points[17], axis=((0, 0, 2), (0, 0, -3)))
    assert info.meets_axis


def test_ellipsoid_normal_misses_a_wrong_axis():
    x, y = 0.5, 0.3
    p = (x, y, math.sqrt((1 - x * x - 2 * y * y) / 3))
    info = pick_info(ELLIPSOID, p, axis=Z_AXIS)
    assert abs(info.value) < 1e-15
    np.testing.assert_allclose(info.gradient, [2 * x, 4 * y, 6 * p[2]])
    assert info.meets_axis is False
    assert info.axis_distance > 0.1
    assert "misses the axis" in info.summary()


def test_parallel_normal_counts_as_meeting():
    # On the top circle of the torus the normal is parallel to the axis: they meet at infinity.
    info = pick_info(TORUS, (2.0, 0.0, 1.0), axis=((5.0, 0.0, 0.0), (0.0, 0.0, 1.0)))
    np.testing.assert_allclose(info.normal_direction, [0, 0, 1], atol=1e-15)
    assert info.meets_axis and info.axis_distance == 0.0


def test_normal_meets_axis_distance_of_skew_lines():
    test = normal_meets_axis((0, 0, 1), (1, 0, 0), (0, 0, 0), (0, 1, 0))
    assert test.distance == pytest.approx(1.0) and test.skew == pytest.approx(1.0)
    assert not test.meets
    with pytest.raises(ValueError):
        normal_meets_axis((0, 0, 1), (0, 0, 0), (0, 0, 0), (0, 1, 0))


def test_singular_point_has_no_normal():
    info = pick_info(CONE, (0.0, 0.0, 0.0), axis=((0, 0, 0), (1, 0, 1)))
    assert info.is_singular and info.axis_test is None and info.normal.is_empty
    assert info.latitude.is_empty  # the vertex lies on the axis
    assert "singular" in info.summary()


def test_pick_without_axis():
    info = pick_info(TORUS, torus_point(0.1, 0.2))
    assert info.axis_test is None and info.meets_axis is None and info.latitude.is_empty
    assert math.isnan(info.radius)


def test_snap_moves_a_picked_point_onto_the_surface():
    p = torus_point(0.5, 0.9) * 1.01
    snapped = snap_to_surface(TORUS, p, max_distance=0.1)
    assert abs(evaluate_points(TORUS, snapped)[0]) < 1e-10
    assert np.linalg.norm(snapped - p) < 0.1
    bounded = snap_to_surface(TORUS, p, max_distance=1e-3)
    assert np.linalg.norm(bounded - p) == pytest.approx(1e-3)
    info = pick_info(TORUS, p, axis=Z_AXIS, snap_distance=0.1)
    np.testing.assert_allclose(info.point, snapped)


def test_latitude_circle_of_a_pick_lies_on_the_surface_of_revolution():
    info = pick_info(TORUS, torus_point(1.0, 2.2), axis=((0, 0, 7), (0, 0, 2)))
    points = info.latitude.points
    radii = np.hypot(points[:, 0], points[:, 1])
    np.testing.assert_allclose(radii, info.radius)
    assert np.abs(evaluate_points(TORUS, points)).max() < 1e-12
    # On the ellipsoid the circle about a wrong axis leaves the surface.
    x, y = 0.5, 0.3
    p = (x, y, math.sqrt((1 - x * x - 2 * y * y) / 3))
    off = pick_info(ELLIPSOID, p, axis=Z_AXIS).latitude.points
    assert np.abs(evaluate_points(ELLIPSOID, off)).max() > 0.1


def test_axis_coordinates():
    height, radius = axis_coordinates((3, 4, 5), (0, 0, 1), (0, 0, 2))
    assert (height, radius) == (pytest.approx(4.0), pytest.approx(5.0))


def test_a_normal_nearly_parallel_to_the_axis_is_said_to_meet_it_without_a_noisy_distance():
    """At a torus's tube top the normal is nearly parallel to the axis: the distance between the
    two lines is the skew divided by a sine near 0, noise (0.0586 on a rounded torus, where other
    points gave 1e-9); the words say the normal meets the axis, nearly parallel to it."""
    tilted = np.array([1e-4, 3e-12, 1.0])  # the normal of a rounded torus at its tube's top
    test = normal_meets_axis((2.0, 0.0, 1.0), tilted, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    assert test.meets and test.sine < 1e-3 and test.distance > 1e-9
    assert test.words() == "normal meets the axis (nearly parallel)"
    assert test.words(lambda verb: f"<b>{verb}</b>") == "normal <b>meets</b> the axis (nearly parallel)"
    exact = normal_meets_axis((2.0, 0.0, 1.0), (0.0, 0.0, 1.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    assert exact.words() == "normal meets the axis (distance 0)"  # an exact torus's: parallel, at infinity
    skew = normal_meets_axis((0, 0, 1), (1, 0, 0), (0, 0, 0), (0, 1, 0))
    assert skew.words() == "normal misses the axis (distance 1)"
