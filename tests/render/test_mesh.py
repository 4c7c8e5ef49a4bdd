"""Meshes of implicit surfaces: geometry, orientation, clipping, empty and extreme input."""

from __future__ import annotations

import numpy as np
import pytest

from sorgui.render.geometry import ClipBox, ClipSphere, view_direction, view_up
from sorgui.render.mesh import (
    GRID_OFFSET,
    THIN_SIDE,
    MeshData,
    grid_bounds,
    mesh_to_polydata,
    sampling_grid,
    surface_mesh,
)
from sorgui.render.picking import pick_many
from sorgui.render.sampling import value_and_gradient
from tests.render.surfaces import (
    CONE,
    EMPTY_ELLIPSOID,
    SPHERE,
    TORUS,
    corpus_terms,
    direct,
)

BOX = (-1.5, 1.5, -1.5, 1.5, -1.5, 1.5)


@pytest.fixture(scope="module")
def sphere_mesh() -> MeshData:
    return surface_mesh(SPHERE, BOX, resolution=60)


def edge_counts(triangles: np.ndarray) -> np.ndarray:
    """How many triangles share each undirected edge."""
    edges = np.sort(triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    return np.unique(edges, axis=0, return_counts=True)[1]


def test_sphere_mesh_lies_on_the_unit_sphere(sphere_mesh):
    assert sphere_mesh.n_points > 1000 and sphere_mesh.n_faces > 2000
    radii = np.linalg.norm(sphere_mesh.points, axis=1)
    assert np.abs(radii - 1).max() < 1e-6  # after the Newton step
    coarse = surface_mesh(SPHERE, BOX, resolution=60, refine=False)
    spacing = coarse.spacing
    assert np.abs(np.linalg.norm(coarse.points, axis=1) - 1).max() < spacing
    assert coarse.n_points == sphere_mesh.n_points


def test_sphere_mesh_is_closed(sphere_mesh):
    counts = edge_counts(sphere_mesh.triangles)
    assert np.all(counts == 2)
    assert sphere_mesh.n_points - len(counts) + sphere_mesh.n_faces == 2  # Euler characteristic


def test_sphere_normals_point_to_f_positive_and_faces_are_wound_to_match(sphere_mesh):
    normals, points = sphere_mesh.normals, sphere_mesh.points
    assert normals.dtype == np.float32 and points.dtype == np.float64
    np.testing.assert_allclose(np.einsum("ij,ij->i", normals, points), 1.0, atol=1e-6)
    corners = points[sphere_mesh.triangles]
    face_normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    assert np.all(np.einsum("ij,ij->i", face_normals, corners.mean(axis=1)) > 0)
    assert np.all(sphere_mesh.side == 1)
    assert sphere_mesh.faces[::4].tolist() == [3] * sphere_mesh.n_faces


def test_mesh_data_is_read_only(sphere_mesh):
    with pytest.raises(ValueError):
        sphere_mesh.points[0, 0] = 5.0


def test_a_thin_box_is_sampled_across_its_thickness() -> None:
    """A slab 0.01 thick of the torus ``R = 3, r = 1`` (``--region -5:5,-5:5,0:0.01 --cap``) had
    two nodes across it 0.07 apart, no triangle inside, and was refused as holding no real point."""
    from sorgui.engine.values import polynomial_terms

    slab = (-5.0, 5.0, -5.0, 5.0, 0.0, 0.01)
    grid = sampling_grid(slab, 150)
    assert grid.dims[2] >= THIN_SIDE and grid.step[2] <= 0.01 / THIN_SIDE and grid.step[0] == grid.spacing
    assert grid_bounds(grid)[5] <= 0.01 and grid.axes()[2][-1] <= 0.01
    torus = "x**4 + 2*x**2*y**2 + 2*x**2*z**2 - 20*x**2 + y**4 + 2*y**2*z**2 - 20*y**2 + z**4 + 16*z**2 + 64"
    mesh = surface_mesh(polynomial_terms(torus), slab, clip=ClipBox(slab))
    assert not mesh.is_empty and np.all(mesh.points[:, 2] >= -1e-12) and np.all(mesh.points[:, 2] <= 0.01 + 1e-12)


def test_grid_is_offset_so_simple_points_are_not_nodes():
    grid = sampling_grid((-1, 1, -2, 2, -1, 1), 100)  # unshifted nodes would include 0
    assert grid.dims == (50, 100, 50) and grid.spacing == pytest.approx(0.04)
    for axis, offset, low in zip(grid.axes(), GRID_OFFSET, (-1, -2, -1)):
        assert np.abs(axis).min() > 0.1 * grid.spacing
        assert axis[0] == pytest.approx(low + offset * grid.spacing)
        assert axis[-1] <= -low


def test_cone_mesh_reaches_the_vertex():
    mesh = surface_mesh(CONE, (-1, 1, -1, 1, -1, 1), resolution=80)
    assert not mesh.is_empty
    assert np.linalg.norm(mesh.points, axis=1).min() < 2 * mesh.spacing
    values, grads = value_and_gradient(CONE, mesh.points)
    assert np.abs(values).max() < mesh.spacing**2
    assert np.all(np.isfinite(mesh.normals))
    assert set(np.unique(mesh.side)) <= {-1.0, 0.0, 1.0}


def test_surface_without_real_points_gives_an_empty_mesh():
    mesh = surface_mesh(EMPTY_ELLIPSOID, BOX)
    assert mesh.is_empty and mesh.n_points == 0 and mesh.points.shape == (0, 3)
    assert mesh_to_polydata(mesh).n_points == 0


@pytest.mark.parametrize("terms", [[], [((0, 0, 0), 3.0)], SPHERE])
def test_constant_or_distant_surfaces_give_an_empty_mesh(terms):
    assert surface_mesh(terms, (5, 6, 5, 6, 5, 6), resolution=20).is_empty


def test_clip_sphere_removes_far_points(sphere_mesh):
    clip = ClipSphere((1.0, 0.0, 0.0), 0.6)
    mesh = surface_mesh(SPHERE, BOX, resolution=60, clip=clip)
    assert 0 < mesh.n_points < sphere_mesh.n_points
    distance = np.linalg.norm(mesh.points - [1.0, 0.0, 0.0], axis=1)
    assert distance.max() < 0.6 + 0.01 * mesh.spacing  # the Newton step may leave the clip a little
    assert distance.max() > 0.6 - 0.1 * mesh.spacing  # cut along the clip sphere, not jagged
    assert np.abs(np.linalg.norm(mesh.points, axis=1) - 1).max() < 1e-6


def test_clip_box_keeps_the_inside():
    clip = ClipBox((0, 3.5, -3.5, 3.5, -1.5, 1.5))
    mesh = surface_mesh(TORUS, (-3.5, 3.5, -3.5, 3.5, -1.5, 1.5), resolution=80, clip=clip)
    assert mesh.points[:, 0].min() >= -1e-9
    assert mesh.points[:, 0].max() == pytest.approx(3.0, abs=1e-3)
    assert np.abs(direct(TORUS, *mesh.points.T)).max() < 1e-3  # |∇f| ≈ 32: distance ≤ 3e-5


def test_huge_coefficients_give_the_same_mesh(sphere_mesh):
    huge = [(e, c * 1e200) for e, c in SPHERE]
    mesh = surface_mesh(huge, BOX, resolution=60)
    assert mesh.n_points == sphere_mesh.n_points
    np.testing.assert_allclose(mesh.points, sphere_mesh.points, atol=1e-12)


def test_huge_box_does_not_overflow():
    scaled = [((2, 0, 0), 1.0), ((0, 2, 0), 1.0), ((0, 0, 2), 1.0), ((0, 0, 0), -1e200)]
    mesh = surface_mesh(scaled, tuple(1.5e100 * np.array(BOX)), resolution=40)
    assert not mesh.is_empty
    np.testing.assert_allclose(np.linalg.norm(mesh.points / 1e100, axis=1), 1.0, rtol=1e-5)
    assert np.all(mesh.side == 1)


@pytest.mark.parametrize("bounds", [(0, 1, 0, 1, 0), (0, 1, 0, 1, 1, 0), (0, np.inf, 0, 1, 0, 1)])
def test_invalid_bounds_raise(bounds):
    with pytest.raises(ValueError):
        surface_mesh(SPHERE, bounds)


def test_too_fine_a_grid_is_refused_before_allocating():
    with pytest.raises(ValueError, match="exceeds"):
        sampling_grid(BOX, 10_000)


def test_mesh_to_polydata_carries_normals_and_side(sphere_mesh):
    poly = mesh_to_polydata(sphere_mesh)
    assert poly.n_points == sphere_mesh.n_points and poly.n_cells == sphere_mesh.n_faces
    assert poly.is_all_triangles
    np.testing.assert_array_equal(poly.point_data["side"], sphere_mesh.side)
    np.testing.assert_array_equal(poly.point_normals, sphere_mesh.normals)


def test_paper_example_1_mesh_is_on_the_surface_and_its_normals_meet_the_axis():
    terms = corpus_terms("paper-example-1")
    mesh = surface_mesh(terms, (-7.4, 8.6, -8.8, 7.2, -8, 8), resolution=100)
    assert mesh.n_points > 10000
    values, grads = value_and_gradient(terms, mesh.points)
    distance = np.abs(values) / np.linalg.norm(grads, axis=1)  # first-order distance to X
    assert np.median(distance) < 1e-4 * mesh.spacing
    # Two sheets 0.24 apart (r = 2 and r = √5 at s = 0) are under-resolved; still within a cell.
    assert distance.max() < mesh.spacing
    assert pick_many(terms, mesh.points, ((0.6, -0.8, 0.0), (4.0, 3.0, 0.0))).all()
    assert not pick_many(terms, mesh.points, ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))).all()


@pytest.mark.parametrize("normal", [(1, -1, 0), (-1, 1, 0), (0, 0, 1), (1, 1, 1), (2, -1, -1)])
def test_a_plane_is_seen_from_its_front_and_never_edge_on(normal) -> None:  # noqa: ANN001
    a, b, c = normal
    plane = [((1, 0, 0), a), ((0, 1, 0), b), ((0, 0, 1), c), ((0, 0, 0), 0.1)]
    mesh = surface_mesh(plane, BOX, resolution=40)
    direction = view_direction(mesh.normals, mesh.side)
    front = (mesh.normals * mesh.side[:, None]).mean(axis=0)
    n = np.asarray(normal) / np.linalg.norm(normal)
    assert np.linalg.norm(direction) == pytest.approx(1.0)
    assert abs(direction @ n) > 0.89  # within 27° of the normal: never edge-on
    assert direction @ front > 0  # the front faces turn to the camera
    assert abs(view_up(direction) @ direction) < 0.99


def test_a_curved_surface_keeps_the_isometric_view(sphere_mesh) -> None:  # noqa: ANN001
    assert np.allclose(view_direction(sphere_mesh.normals, sphere_mesh.side), np.ones(3) / np.sqrt(3))
    assert np.allclose(view_direction(np.zeros((0, 3)), np.zeros(0)), np.ones(3) / np.sqrt(3))


def test_a_mesh_clipped_to_a_ball_reaches_the_ball_where_it_touches_the_balls_box() -> None:
    """The plane x = y in the unit ball: its rim is the ball's circle up to the top and bottom
    (where the ball touches its box), not a flat cut where the last row of grid cells ends."""
    mesh = surface_mesh([((1, 0, 0), 1.0), ((0, 1, 0), -1.0)], BOX_OF_BALL, resolution=40, clip=BALL)
    assert np.linalg.norm(mesh.points, axis=1).max() == pytest.approx(1.0, abs=1e-4)
    heights = mesh.points[:, 2]
    assert heights.max() == pytest.approx(1.0, abs=1e-3) and heights.min() == pytest.approx(-1.0, abs=1e-3)


BALL = ClipSphere((0.0, 0.0, 0.0), 1.0)
BOX_OF_BALL = (-1.0, 1.0, -1.0, 1.0, -1.0, 1.0)
