"""GridMap: validation and world <-> cell conversions."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import Cell, GridMap


def test_world_cell_round_trip_without_yaw():
    grid = GridMap(np.zeros((4, 6), dtype=np.int8), 0.5, (-1.0, 2.0, 0.0))
    assert grid.width == 6 and grid.height == 4
    assert grid.size_m == (3.0, 2.0)
    assert grid.world_to_cell(-1.0, 2.0) == Cell(0, 0)
    assert grid.world_to_cell(-0.01, 2.49) == Cell(0, 1)
    assert grid.world_to_cell(0.26, 3.6) == Cell(3, 2)
    assert grid.cell_to_world(3, 2) == pytest.approx((0.25, 3.75))
    assert grid.world_to_cell(-1.01, 2.0) == Cell(0, -1)
    assert not grid.in_bounds(grid.world_to_cell(-1.01, 2.0))
    assert grid.in_bounds(Cell(3, 5)) and not grid.in_bounds(Cell(4, 5))


def test_world_cell_with_yaw_rotates_about_origin():
    grid = GridMap(np.zeros((10, 10), dtype=np.int8), 1.0, (1.0, 1.0, math.pi / 2))
    # +x of the grid points along the map's +y: cell (row 0, col 3) centre is at (0.5, 4.5)
    x, y = grid.cell_to_world(0, 3)
    assert (x, y) == pytest.approx((0.5, 4.5))
    assert grid.world_to_cell(x, y) == Cell(0, 3)
    rows, cols = grid.world_to_cells(np.array([x]), np.array([y]))
    assert (int(rows[0]), int(cols[0])) == (0, 3)
    xs, ys = grid.cells_to_world(np.array([0]), np.array([3]))
    assert (xs[0], ys[0]) == pytest.approx((x, y))


def test_vectorised_matches_scalar():
    grid = GridMap(np.zeros((20, 30), dtype=np.int8), 0.05, (-0.3, 0.7, 0.4))
    rng = np.random.default_rng(1)
    xs = rng.uniform(-2, 2, 50)
    ys = rng.uniform(-2, 2, 50)
    rows, cols = grid.world_to_cells(xs, ys)
    for x, y, r, c in zip(xs, ys, rows, cols):
        assert grid.world_to_cell(float(x), float(y)) == Cell(int(r), int(c))


def test_int_array_is_converted_to_int8_and_copy_is_deep():
    grid = GridMap(np.array([[0, 100], [-1, 50]], dtype=np.int64), 1.0)
    assert grid.occupancy.dtype == np.int8
    dup = grid.copy()
    dup.occupancy[0, 0] = 100
    assert grid.occupancy[0, 0] == 0


@pytest.mark.parametrize(
    ("occupancy", "resolution", "origin", "needle"),
    [
        (np.zeros((0, 3), dtype=np.int8), 1.0, (0.0, 0.0, 0.0), "non-empty 2-D"),
        (np.zeros(5, dtype=np.int8), 1.0, (0.0, 0.0, 0.0), "2-D"),
        (np.zeros((2, 2)), 1.0, (0.0, 0.0, 0.0), "integers"),
        (np.array([[0, 101]]), 1.0, (0.0, 0.0, 0.0), "-1..100"),
        (np.array([[0, -2]], dtype=np.int8), 1.0, (0.0, 0.0, 0.0), "-1..100"),
        (np.zeros((2, 2), dtype=np.int8), 0.0, (0.0, 0.0, 0.0), "resolution"),
        (np.zeros((2, 2), dtype=np.int8), float("nan"), (0.0, 0.0, 0.0), "resolution"),
        (np.zeros((2, 2), dtype=np.int8), 1.0, (0.0, float("inf"), 0.0), "origin"),
        (np.zeros((2, 2), dtype=np.int8), 1.0, (0.0, 0.0), "origin"),
    ],
)
def test_bad_construction_raises_config_error(occupancy, resolution, origin, needle):
    with pytest.raises(ConfigError, match=needle):
        GridMap(occupancy, resolution, origin)
