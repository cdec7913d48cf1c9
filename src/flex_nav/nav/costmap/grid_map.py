"""An occupancy grid in ROS ``nav_msgs/OccupancyGrid`` conventions, as a plain numpy array.

``occupancy[row, col]`` holds -1 (unknown) or 0..100 (probability of occupancy in percent). Row 0 is
the row of cells at the map origin and rows grow along the map's +y axis (y up, the OccupancyGrid
``data`` order), so ``occupancy.ravel()`` *is* the message's ``data``. The origin is the pose of the
lower-left corner of cell (0, 0) in the map frame; a non-zero yaw rotates the grid about it.

Cells are addressed as :class:`Cell` ``(row, col)`` so the tuple indexes the array directly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError

UNKNOWN = -1  # occupancy value of a cell nobody has observed
FREE = 0
OCCUPIED = 100


class Cell(NamedTuple):
    """Index of one grid cell; ``grid.occupancy[cell]`` is its value."""

    row: int  # along the map's +y axis
    col: int  # along the map's +x axis


@dataclass
class GridMap:
    """An occupancy grid: values, cell size and where cell (0, 0) lies in the map frame.

    Validated on construction: a 2-D integer array with values in -1..100 (converted to int8),
    a finite positive resolution and a finite origin; anything else raises :class:`ConfigError`.
    """

    occupancy: np.ndarray  # int8 (H, W): -1 unknown, 0..100; row 0 at the origin, y up
    resolution: float  # [m/cell]
    origin: Tuple[float, float, float] = (0.0, 0.0, 0.0)  # (x [m], y [m], yaw [rad]) of cell (0, 0)'s corner

    def __post_init__(self) -> None:
        occ = np.asarray(self.occupancy)
        if occ.ndim != 2 or occ.shape[0] == 0 or occ.shape[1] == 0:
            raise ConfigError(f"GridMap occupancy must be a non-empty 2-D array, got shape {occ.shape}")
        if not np.issubdtype(occ.dtype, np.integer):
            raise ConfigError(f"GridMap occupancy must hold integers (-1..100), got dtype {occ.dtype}")
        if occ.dtype != np.int8:
            if occ.size and (int(occ.min()) < UNKNOWN or int(occ.max()) > OCCUPIED):
                raise ConfigError(
                    f"GridMap occupancy values must be in -1..100, got {int(occ.min())}..{int(occ.max())}"
                )
            occ = occ.astype(np.int8)
        elif occ.size and (int(occ.min()) < UNKNOWN or int(occ.max()) > OCCUPIED):
            raise ConfigError(f"GridMap occupancy values must be in -1..100, got {int(occ.min())}..{int(occ.max())}")
        self.occupancy = occ
        res = float(self.resolution)
        if not math.isfinite(res) or res <= 0.0:
            raise ConfigError(f"GridMap resolution must be a finite number > 0 [m/cell], got {self.resolution!r}")
        self.resolution = res
        if len(self.origin) != 3:
            raise ConfigError(f"GridMap origin must be (x [m], y [m], yaw [rad]), got {self.origin!r}")
        origin = (float(self.origin[0]), float(self.origin[1]), float(self.origin[2]))
        if not all(math.isfinite(v) for v in origin):
            raise ConfigError(f"GridMap origin must be finite, got {self.origin!r}")
        self.origin = origin

    @property
    def height(self) -> int:
        """Number of rows [cells] (along +y)."""
        return int(self.occupancy.shape[0])

    @property
    def width(self) -> int:
        """Number of columns [cells] (along +x)."""
        return int(self.occupancy.shape[1])

    @property
    def size_m(self) -> Tuple[float, float]:
        """(width [m], height [m]) of the whole grid."""
        return self.width * self.resolution, self.height * self.resolution

    def in_bounds(self, cell: Tuple[int, int]) -> bool:
        """True if ``(row, col)`` is a cell of this grid."""
        return 0 <= cell[0] < self.height and 0 <= cell[1] < self.width

    def world_to_grid(self, x: float, y: float) -> Tuple[float, float]:
        """Continuous grid coordinates (col, row) [cells] of map-frame point (x [m], y [m]).

        Cell (r, c) covers ``c <= col < c + 1`` and ``r <= row < r + 1``.
        """
        ox, oy, yaw = self.origin
        dx, dy = x - ox, y - oy
        if yaw != 0.0:
            c, s = math.cos(yaw), math.sin(yaw)
            dx, dy = c * dx + s * dy, -s * dx + c * dy
        return dx / self.resolution, dy / self.resolution

    def world_to_cell(self, x: float, y: float) -> Cell:
        """The cell containing map-frame point (x [m], y [m]); may lie outside the grid (check in_bounds)."""
        gx, gy = self.world_to_grid(x, y)
        return Cell(math.floor(gy), math.floor(gx))

    def cell_to_world(self, row: int, col: int) -> Tuple[float, float]:
        """Map-frame centre (x [m], y [m]) of cell (row, col)."""
        return self.grid_to_world(col + 0.5, row + 0.5)

    def grid_to_world(self, gx: float, gy: float) -> Tuple[float, float]:
        """Map-frame point (x [m], y [m]) of continuous grid coordinates (col gx, row gy) [cells]."""
        ox, oy, yaw = self.origin
        dx, dy = gx * self.resolution, gy * self.resolution
        if yaw != 0.0:
            c, s = math.cos(yaw), math.sin(yaw)
            dx, dy = c * dx - s * dy, s * dx + c * dy
        return ox + dx, oy + dy

    def world_to_cells(self, xs: np.ndarray, ys: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """Vectorised :meth:`world_to_cell`: (rows, cols) int64 arrays; may lie outside the grid."""
        ox, oy, yaw = self.origin
        dx = np.asarray(xs, dtype=np.float64) - ox
        dy = np.asarray(ys, dtype=np.float64) - oy
        if yaw != 0.0:
            c, s = math.cos(yaw), math.sin(yaw)
            dx, dy = c * dx + s * dy, -s * dx + c * dy
        return (
            np.floor(dy / self.resolution).astype(np.int64),
            np.floor(dx / self.resolution).astype(np.int64),
        )

    def cells_to_world(self, rows: np.ndarray, cols: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """Vectorised :meth:`cell_to_world`: (xs [m], ys [m]) of cell centres."""
        ox, oy, yaw = self.origin
        dx = (np.asarray(cols, dtype=np.float64) + 0.5) * self.resolution
        dy = (np.asarray(rows, dtype=np.float64) + 0.5) * self.resolution
        if yaw != 0.0:
            c, s = math.cos(yaw), math.sin(yaw)
            dx, dy = c * dx - s * dy, s * dx + c * dy
        return ox + dx, oy + dy

    def copy(self) -> GridMap:
        """A deep copy (the occupancy array is copied)."""
        return GridMap(self.occupancy.copy(), self.resolution, self.origin)
