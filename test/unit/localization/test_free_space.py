"""Uniform poses over the free cells (0..19) only."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.localization import GridMap
from flex_nav.localization.free_space import FreeSpace


def test_samples_only_free_cells_uniformly():
    occupancy = np.array([[0, 19, 20, -1], [100, 10, 65, 50]], dtype=np.int8)
    grid = GridMap(occupancy, 0.5, (1.0, -2.0, 0.0))
    poses = FreeSpace(grid).sample(30_000, np.random.default_rng(0))
    rows, cols = grid.world_to_cells(poses[:, 0], poses[:, 1])
    values = occupancy[rows, cols]
    assert set(np.unique(values).tolist()) == {0, 10, 19}
    counts = np.array([(values == v).sum() for v in (0, 10, 19)])
    np.testing.assert_allclose(counts / counts.sum(), 1 / 3, atol=0.02)
    assert poses[:, 2].min() >= -math.pi and poses[:, 2].max() <= math.pi
    assert np.abs(poses[:, 2]).mean() == pytest.approx(math.pi / 2, rel=0.02)


def test_rotated_origin():
    occupancy = np.full((4, 6), 100, dtype=np.int8)
    occupancy[2, 3] = 0
    grid = GridMap(occupancy, 0.1, (0.5, 0.5, 0.7))
    poses = FreeSpace(grid).sample(1000, np.random.default_rng(1))
    rows, cols = grid.world_to_cells(poses[:, 0], poses[:, 1])
    assert (rows == 2).all() and (cols == 3).all()


def test_no_free_cell_is_an_error():
    grid = GridMap(np.full((3, 3), 100, dtype=np.int8), 0.1)
    with pytest.raises(ConfigError, match="no free cell"):
        FreeSpace(grid).sample(10, np.random.default_rng(2))
