"""The likelihood field: exact Euclidean distances, the cap, unknown cells and outside, the edge distance, and the
per-cell beam table."""

import math

import numpy as np
import pytest

from flex_nav.localization import GridMap
from flex_nav.localization.likelihood_field import LikelihoodField

RES = 0.1  # [m]


def grid_with(occupied, unknown=(), shape=(9, 11), value=100):
    occupancy = np.zeros(shape, dtype=np.int8)
    for cell in occupied:
        occupancy[cell] = value
    for cell in unknown:
        occupancy[cell] = -1
    return GridMap(occupancy, RES, (-0.5, 1.0, 0.0))


def test_distances_are_exact_euclidean_between_cell_centres():
    field = LikelihoodField(grid_with([(4, 5), (0, 0)]), max_dist=10.0)
    rows, cols = np.indices((9, 11))
    expected = RES * np.minimum(np.hypot(rows - 4, cols - 5), np.hypot(rows, cols))
    np.testing.assert_allclose(field.distance, expected, atol=1e-5)
    assert field.distance[4, 8] == pytest.approx(0.3, abs=1e-6)
    assert field.distance[7, 9] == pytest.approx(0.5, abs=1e-6)  # 3-4-5 triangle, not a chamfer value
    assert field.distance[1, 1] == pytest.approx(RES * math.sqrt(2), abs=1e-6)


def test_occupied_from_65_as_map_server_occupied_thresh():
    assert LikelihoodField(grid_with([(4, 5)], value=64), 10.0).distance.min() == pytest.approx(10.0)
    assert LikelihoodField(grid_with([(4, 5)], value=65), 10.0).distance[4, 5] == 0.0


def test_distances_are_capped():
    field = LikelihoodField(grid_with([(4, 5)]), max_dist=0.25)
    assert field.distance.max() == pytest.approx(0.25)
    assert field.distance[4, 7] == pytest.approx(0.2, abs=1e-6)
    assert field.distance[4, 8] == pytest.approx(0.25)


def test_no_obstacle_at_all_is_the_cap_everywhere():
    field = LikelihoodField(grid_with([]), max_dist=2.0)
    assert (field.distance == 2.0).all()


def test_distance_at_world_points_nan_outside_and_unknown():
    grid = grid_with([(4, 5)], unknown=[(2, 2)])
    field = LikelihoodField(grid, max_dist=10.0)
    x, y = grid.cell_to_world(4, 8)
    assert field.distance_at(x, y) == pytest.approx(0.3, abs=1e-6)
    assert math.isnan(field.distance_at(*grid.cell_to_world(2, 2)))
    assert math.isnan(field.distance_at(-0.6, 1.5))  # left of the grid
    assert math.isnan(field.distance_at(0.0, 1.0 + 9 * RES + 0.01))  # above it


def test_edge_distance_is_half_a_cell_less_inside_and_out():
    occupied = [(r, c) for r in range(3, 6) for c in range(4, 7)]  # a 3 x 3 block
    field = LikelihoodField(grid_with(occupied), max_dist=10.0)
    assert field.edge_distance[4, 5] == pytest.approx(2 * RES - RES / 2)  # centre of the block: depth 2 cells
    assert field.edge_distance[3, 4] == pytest.approx(RES / 2)  # border cell inside
    assert field.edge_distance[2, 4] == pytest.approx(RES / 2)  # border cell outside
    assert field.edge_distance[4, 9] == pytest.approx(3 * RES - RES / 2)


def test_beam_table_values_and_floor_for_unknown_and_outside():
    grid = grid_with([(4, 5)], unknown=[(0, 10)])
    field = LikelihoodField(grid, max_dist=2.0)
    z_hit, z_rand, sigma, range_max = 0.9, 0.1, 0.2, 5.0
    table = field.beam_table(z_hit, z_rand, sigma, range_max)
    assert table.shape == (9 * 11 + 1,) and table.dtype == np.float32
    floor = z_rand / range_max
    e = 0.3 - RES / 2  # cell (4, 8): 3 cells from the obstacle's centre
    assert table[4 * 11 + 8] == pytest.approx(math.log(z_hit * math.exp(-e * e / (2 * sigma * sigma)) + floor),
                                              rel=1e-6)
    assert table[0 * 11 + 10] == pytest.approx(math.log(floor), rel=1e-6)  # unknown cell
    assert table[-1] == pytest.approx(math.log(floor), rel=1e-6)  # outside the grid
    assert table.max() == pytest.approx(math.log(z_hit * math.exp(-(RES / 2) ** 2 / (2 * sigma**2)) + floor),
                                        rel=1e-6)
