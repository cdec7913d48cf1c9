"""Which scan points the static map explains: hits on (or within a tolerance of) a mapped obstacle.

A moving-obstacle tracker must not follow walls: a wall broken up by the shadow of a person walking in
front of it leaves short wall pieces whose ends move with the shadow and look like something walking.
Points within ``tolerance_m`` [m] of an occupied map cell are dropped before clustering.

Pure numpy on a :class:`~flex_nav.nav.costmap.grid_map.GridMap` (no ROS).
"""

from __future__ import annotations

import math

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import GridMap

OCCUPIED_THRESHOLD = 65  # occupancy >= this is an obstacle (map_server's occupied_thresh 0.65)


class StaticMask:
    """Occupied cells of a map grown by ``tolerance_m`` [m]; :meth:`explained` tells points on them."""

    def __init__(self, grid: GridMap, tolerance_m: float) -> None:
        if not math.isfinite(tolerance_m) or tolerance_m < 0.0:
            raise ConfigError(f"static map tolerance must be a finite number >= 0 [m], got {tolerance_m!r}")
        self.grid = grid
        self.tolerance_m = tolerance_m
        occupied = grid.occupancy >= OCCUPIED_THRESHOLD
        reach = math.ceil(tolerance_m / grid.resolution)
        grown = occupied.copy()
        height, width = occupied.shape
        for dr in range(-reach, reach + 1):
            for dc in range(-reach, reach + 1):
                if (dr == 0 and dc == 0) or math.hypot(dr, dc) * grid.resolution > tolerance_m + 1e-9:
                    continue
                src = occupied[max(0, -dr):height - max(0, dr), max(0, -dc):width - max(0, dc)]
                grown[max(0, dr):height - max(0, -dr), max(0, dc):width - max(0, -dc)] |= src
        self._grown = grown

    def explained(self, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
        """Boolean array: True where the point (x [m], y [m]) lies on a grown occupied cell (off-map: False)."""
        rows, cols = self.grid.world_to_cells(np.asarray(xs), np.asarray(ys))
        height, width = self._grown.shape
        inside = (rows >= 0) & (rows < height) & (cols >= 0) & (cols < width)
        out = np.zeros(rows.shape, dtype=bool)
        out[inside] = self._grown[rows[inside], cols[inside]]
        return out
