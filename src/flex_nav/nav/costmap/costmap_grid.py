"""Cost values (costmap_2d's) and the geometry of a costmap grid.

Costs are ``uint8`` with costmap_2d's meaning:

- :data:`NO_INFORMATION` 255: nothing known about the cell
- :data:`LETHAL` 254: an obstacle is in the cell
- :data:`INSCRIBED` 253: the robot's centre here puts its inscribed circle on an obstacle
- 1..252: inflation, ``252·exp(−k·(d − r_inscribed))`` down to the inflation radius
- :data:`FREE` 0

The array layout is the same as :class:`flex_nav.nav.costmap.grid_map.GridMap`: ``costs[row, col]``, row 0 at
the origin, rows along +y, so ``costs.ravel()`` is in OccupancyGrid ``data`` order. Costmaps have no
yaw (as in costmap_2d): the grid is axis-aligned with its frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import Cell

NO_INFORMATION = 255
LETHAL = 254
INSCRIBED = 253
MAX_NON_OBSTACLE = 252
FREE = 0


def _occupancy_table() -> np.ndarray:
    # costmap_2d's publisher: 0 -> 0, 1..252 -> 1..98 (integer scaling), 253 -> 99, 254 -> 100, 255 -> -1
    table = np.zeros(256, dtype=np.int8)
    for cost in range(1, 253):
        table[cost] = 1 + (97 * (cost - 1)) // 251
    table[INSCRIBED] = 99
    table[LETHAL] = 100
    table[NO_INFORMATION] = -1
    return table


OCCUPANCY_OF_COST = _occupancy_table()
OCCUPANCY_OF_COST.setflags(write=False)


def costs_to_occupancy(costs: np.ndarray) -> np.ndarray:
    """OccupancyGrid values of uint8 costs, as costmap_2d publishes them.

    int8: 0 free, 1..98 scaled, 99 inscribed, 100 lethal, -1 unknown.
    """
    if costs.dtype != np.uint8:
        raise ConfigError(f"costs must be uint8, got {costs.dtype}")
    occupancy: np.ndarray = OCCUPANCY_OF_COST[costs]
    return occupancy


@dataclass
class CostmapGeometry:
    """Size and placement of a costmap grid: ``width`` x ``height`` cells of ``resolution`` [m].

    The origin is the outer corner of cell (0, 0) in the costmap's frame. A rolling window moves it.
    """

    width: int  # [cells] along +x
    height: int  # [cells] along +y
    resolution: float  # [m/cell]
    origin_x: float = 0.0  # [m]
    origin_y: float = 0.0  # [m]

    def __post_init__(self) -> None:
        if int(self.width) != self.width or int(self.height) != self.height or self.width < 1 or self.height < 1:
            raise ConfigError(f"costmap size must be positive whole cells, got {self.width!r} x {self.height!r}")
        self.width, self.height = int(self.width), int(self.height)
        if not math.isfinite(self.resolution) or self.resolution <= 0.0:
            raise ConfigError(f"costmap resolution must be a finite number > 0 [m/cell], got {self.resolution!r}")
        if not (math.isfinite(self.origin_x) and math.isfinite(self.origin_y)):
            raise ConfigError(f"costmap origin must be finite, got ({self.origin_x!r}, {self.origin_y!r})")
        self.resolution = float(self.resolution)
        self.origin_x, self.origin_y = float(self.origin_x), float(self.origin_y)

    @property
    def shape(self) -> Tuple[int, int]:
        """(rows, cols) of the cost array."""
        return self.height, self.width

    def world_to_cell(self, x: float, y: float) -> Cell:
        """The cell containing point (x [m], y [m]); may be outside the grid (check :meth:`in_bounds`)."""
        return Cell(
            math.floor((y - self.origin_y) / self.resolution), math.floor((x - self.origin_x) / self.resolution)
        )

    def cell_to_world(self, row: int, col: int) -> Tuple[float, float]:
        """Centre (x [m], y [m]) of cell (row, col)."""
        return self.origin_x + (col + 0.5) * self.resolution, self.origin_y + (row + 0.5) * self.resolution

    def in_bounds(self, cell: Tuple[int, int]) -> bool:
        """True if ``(row, col)`` is a cell of this grid."""
        return 0 <= cell[0] < self.height and 0 <= cell[1] < self.width

    def contains(self, x: float, y: float) -> bool:
        """True if point (x [m], y [m]) lies on the grid."""
        return self.in_bounds(self.world_to_cell(x, y))

    def cells_to_world(self, rows: np.ndarray, cols: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """Vectorised :meth:`cell_to_world`."""
        return (
            self.origin_x + (np.asarray(cols, dtype=np.float64) + 0.5) * self.resolution,
            self.origin_y + (np.asarray(rows, dtype=np.float64) + 0.5) * self.resolution,
        )

    def world_to_cells(self, xs: np.ndarray, ys: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """Vectorised :meth:`world_to_cell`: (rows, cols) int64 arrays; may lie outside the grid."""
        return (
            np.floor((np.asarray(ys, dtype=np.float64) - self.origin_y) / self.resolution).astype(np.int64),
            np.floor((np.asarray(xs, dtype=np.float64) - self.origin_x) / self.resolution).astype(np.int64),
        )
