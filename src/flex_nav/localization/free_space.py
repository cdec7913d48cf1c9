"""Uniform samples of poses in a map's free space: for global localization and the random particles of
Augmented MCL.

Free cells are those of value 0..19 (below map_server's ``free_thresh`` 0.196). A sample picks one uniformly,
a uniform point inside it and a uniform heading, so positions are uniform over the free area.
"""

from __future__ import annotations

import math

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import GridMap

FREE_MAX = 19  # highest occupancy value of a free cell (free_thresh 0.196)


class FreeSpace:
    """The free cells of one map."""

    def __init__(self, grid: GridMap) -> None:
        self.grid = grid
        occupancy = grid.occupancy
        self.cells = np.flatnonzero((occupancy >= 0) & (occupancy <= FREE_MAX))  # flat indices (row-major)

    @property
    def count(self) -> int:
        """Number of free cells."""
        return int(self.cells.size)

    def sample(self, count: int, rng: np.random.Generator) -> np.ndarray:
        """(count, 3) poses ``[x [m], y [m], yaw [rad]]``, uniform over the free area and in heading;
        :class:`ConfigError` if the map has no free cell."""
        if self.cells.size == 0:
            raise ConfigError("localization: the map has no free cell (value 0..19) to place particles in")
        grid = self.grid
        flat = self.cells[rng.integers(0, self.cells.size, size=count)]
        rows, cols = np.divmod(flat, grid.width)
        gx = (cols + rng.random(count)) * grid.resolution
        gy = (rows + rng.random(count)) * grid.resolution
        ox, oy, oyaw = grid.origin
        c, s = math.cos(oyaw), math.sin(oyaw)
        out = np.empty((count, 3))
        out[:, 0] = ox + c * gx - s * gy
        out[:, 1] = oy + s * gx + c * gy
        out[:, 2] = rng.uniform(-math.pi, math.pi, size=count)
        return out
