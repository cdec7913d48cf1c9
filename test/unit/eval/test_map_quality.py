"""Scoring a built map against the ground truth: agreement, wall offsets, explored share, the picture; evo's ATE."""

import math

import numpy as np
import pytest
from unit.localization.room import asymmetric_room

from flex_nav.apps.eval.map_quality import aligned_placement, ate_rmse_cm, draw_map, reachable_free, score_map
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.planar import inverse_pose, transform_poses

START = (1.5, 1.2)
RADIUS = 0.18  # [m]


@pytest.fixture(scope="module")
def truth():
    return asymmetric_room()


def shifted(grid, cells):
    """The same map with its content moved by ``cells`` cells along x and along y (the origin kept)."""
    return GridMap(np.roll(grid.occupancy, (cells, cells), axis=(0, 1)), grid.resolution, grid.origin)


def test_the_truth_scores_perfectly_against_itself(truth):
    score = score_map(truth, truth, (0.0, 0.0, 0.0), START, RADIUS)
    assert score.agree == 1.0 and score.explored == 1.0
    assert score.wall_median_cm == 0.0 and score.ghost == 0.0


def test_a_map_placed_by_its_own_offset_scores_as_well(truth):
    moved = GridMap(truth.occupancy, truth.resolution, (-2.0, 1.0, 0.0))  # the same cells, origin moved
    score = score_map(moved, truth, (2.0, -1.0, 0.0), START, RADIUS)
    assert score.agree == pytest.approx(1.0) and score.wall_median_cm == pytest.approx(0.0)


def test_a_shifted_map_loses_agreement_and_its_walls_are_off(truth):
    score = score_map(shifted(truth, 4), truth, (0.0, 0.0, 0.0), START, RADIUS)  # 20 cm along x and y
    assert score.agree < 0.97
    assert 15.0 <= score.wall_median_cm <= 30.0
    assert score.ghost > 0.5


def test_half_a_map_is_half_explored(truth):
    half = truth.occupancy.copy()
    half[:, half.shape[1] // 2:] = -1
    score = score_map(GridMap(half, truth.resolution, truth.origin), truth, (0.0, 0.0, 0.0), START, RADIUS)
    assert 0.3 < score.explored < 0.7
    assert score.agree == 1.0  # what it knows is right


def test_reachable_free_needs_the_robots_clearance(truth):
    narrow = reachable_free(truth, START, 0.1)
    wide = reachable_free(truth, START, 1.5)  # too big to move anywhere
    assert narrow.sum() > 1000
    assert wide.sum() < 0.05 * narrow.sum()
    assert not reachable_free(truth, (100.0, 100.0), RADIUS).any()  # a start off the map reaches nothing


def test_the_picture_has_the_maps_shape_scaled(truth):
    image = draw_map(truth, truth, (0.0, 0.0, 0.0), [(1.0, 1.0), (2.0, 1.5)], [((1.0, 1.0), (2.0, 1.5))], scale=2)
    assert image.shape == (2 * truth.height, 2 * truth.width, 3)
    assert np.any(np.all(image == (0, 0, 120), axis=2))  # true walls drawn (where the built map has them too)
    assert np.any(np.all(image == (0, 180, 0), axis=2))  # a loop closure drawn


def test_ate_is_zero_for_the_truth_and_grows_with_an_offset():
    truths = [(0.1 * i, 0.05 * i * i, 0.1 * i) for i in range(20)]
    assert ate_rmse_cm(truths, truths, align=False) == pytest.approx(0.0, abs=1e-6)
    moved = [(x + 0.1, y, yaw) for x, y, yaw in truths]
    assert ate_rmse_cm(moved, truths, align=False) == pytest.approx(10.0, abs=1e-3)
    assert ate_rmse_cm(moved, truths, align=True) == pytest.approx(0.0, abs=1e-3)  # a rigid offset is aligned away
    noisy = [(x + 0.02 * math.sin(7 * i), y, yaw) for i, (x, y, yaw) in enumerate(truths)]
    noisy_cm = ate_rmse_cm(noisy, truths, align=True)
    assert noisy_cm is not None and 0.5 < noisy_cm < 2.0
    assert ate_rmse_cm(truths[:2], truths[:2]) is None


def test_the_aligned_placement_recovers_a_rigid_offset_and_refuses_a_line():
    truths = [(1.0 + 0.1 * i, 2.0 + 0.05 * i * i, 0.1 * i) for i in range(20)]
    placement = (0.3, -0.2, 0.05)  # the map frame in the world
    estimates = transform_poses(np.array(truths), *inverse_pose(placement))  # the same poses in that map frame
    found = aligned_placement([tuple(p) for p in estimates], truths)
    assert found is not None
    np.testing.assert_allclose(found, placement, atol=1e-9)
    line = [(0.1 * i, 0.0, 0.0) for i in range(10)]
    assert aligned_placement(line, line) is None  # on a line the rotation is not determined in the plane's terms
    assert aligned_placement(truths[:2], truths[:2]) is None
