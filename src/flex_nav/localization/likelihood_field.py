"""The likelihood field of a map: for every cell, the distance to the nearest occupied cell, built once per map.

Occupied cells are those of value >= 65 (map_server's ``occupied_thresh`` 0.65). :attr:`LikelihoodField.distance`
is the exact Euclidean distance between cell centres (OpenCV's ``distanceTransform`` with ``DIST_L2`` and
``DIST_MASK_PRECISE`` on the grid of occupied cells), in metres, capped at ``laser_likelihood_max_dist``.
Unknown cells (-1) are marked: an end point there, like one outside the map, tells nothing and gets the model's
floor.

What the sensor model scores is :attr:`LikelihoodField.edge_distance`, the distance to the obstacle's *edge*:
half a cell less than the distance between centres, and inside an obstacle its depth (distance to the nearest
non-occupied cell) less half a cell. A map marks a cell occupied when the obstacle covers its centre, so a surface
lies, on average, on the border between the last occupied and the first free cell, half a cell from either
centre. Scoring the distance to occupied centres instead would pull every pose half a cell (2.5 cm on a 5 cm
map) towards the walls it sees; scored on edge distances, the two cells either side of the border score alike,
and an end point deep inside a wall scores as badly as one short of it.
"""

from __future__ import annotations

import math
from typing import Tuple

import cv2
import numpy as np

from flex_nav.nav.costmap.grid_map import GridMap

OCCUPIED_MIN = 65  # occupancy value from which a cell is an obstacle (map_server's occupied_thresh 0.65)


def _distance_to_zeros(nonzero: np.ndarray, resolution: float, cap: float) -> np.ndarray:
    """Exact Euclidean distance [m] from each True cell of ``nonzero`` to the nearest False cell's centre, capped
    at ``cap`` (0 on False cells; ``cap`` everywhere if there is no False cell)."""
    if nonzero.all():
        return np.full(nonzero.shape, cap)
    cells = cv2.distanceTransform(nonzero.astype(np.uint8), cv2.DIST_L2, cv2.DIST_MASK_PRECISE)
    return np.asarray(np.minimum(cells.astype(np.float64) * resolution, cap))


class LikelihoodField:
    """Distances from each cell of ``grid`` to the nearest obstacle, capped at ``max_dist`` [m]."""

    def __init__(self, grid: GridMap, max_dist: float) -> None:
        self.grid = grid
        self.max_dist = float(max_dist)
        occupied = grid.occupancy >= OCCUPIED_MIN
        self.occupied = occupied  # (H, W) bool
        self.known = grid.occupancy >= 0  # (H, W) bool: False for unknown cells
        # (H, W) float64 [m]: centre to the nearest occupied cell's centre (0 on occupied cells)
        self.distance = _distance_to_zeros(~occupied, grid.resolution, self.max_dist)
        depth = _distance_to_zeros(occupied, grid.resolution, self.max_dist)  # inside obstacles
        # (H, W) float32 [m]: centre to the nearest obstacle edge, inside or out (>= half a cell)
        self.edge_distance = (np.where(occupied, depth, self.distance) - 0.5 * grid.resolution).astype(np.float32)

    @property
    def shape(self) -> Tuple[int, int]:
        """(rows, cols) of the grid."""
        return int(self.distance.shape[0]), int(self.distance.shape[1])

    def distance_at(self, x: float, y: float) -> float:
        """:attr:`distance` [m] of the cell holding map point (x, y) [m]; NaN outside the map and in unknown cells."""
        cell = self.grid.world_to_cell(x, y)
        if not self.grid.in_bounds(cell) or not self.known[cell]:
            return math.nan
        return float(self.distance[cell])

    def beam_table(self, z_hit: float, z_rand: float, sigma: float, range_max: float) -> np.ndarray:
        """Per-cell log-probability of one beam ending in that cell and, as the last element, of one ending outside
        the map: ``log(z_hit * exp(-e² / (2 sigma²)) + z_rand / range_max)`` with ``e`` the cell's
        :attr:`edge_distance` [m]; unknown cells and outside the map get the floor ``log(z_rand / range_max)``.
        Shape (H * W + 1,) float32, row-major as the grid."""
        floor = z_rand / range_max
        edge = self.edge_distance.astype(np.float64)
        probability = z_hit * np.exp(-(edge * edge) / (2.0 * sigma * sigma)) + floor
        probability = np.where(self.known, probability, floor)
        return np.asarray(np.log(np.append(probability.ravel(), floor)), dtype=np.float32)
