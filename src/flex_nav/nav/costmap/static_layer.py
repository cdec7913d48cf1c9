"""The static layer: costs from a map (a :class:`GridMap`), as costmap_2d's StaticLayer translates them.

Occupancy value -> cost: unknown (-1) -> NO_INFORMATION (or FREE without ``track_unknown_space``);
``>= lethal_threshold`` -> LETHAL; otherwise FREE (``trinary_costmap``) or ``int(value / lethal_threshold · 254)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import FREE, LETHAL, NO_INFORMATION, CostmapGeometry
from flex_nav.nav.costmap.grid_map import GridMap


@dataclass(frozen=True)
class StaticLayerParams:
    """How map values become costs (costmap_2d's static layer parameters)."""

    track_unknown_space: bool = True  # unknown map cells are NO_INFORMATION (else FREE)
    lethal_threshold: int = 100  # map values >= this are LETHAL
    trinary_costmap: bool = True  # values below the threshold are FREE (else scaled)

    def __post_init__(self) -> None:
        if isinstance(self.lethal_threshold, bool) or not isinstance(self.lethal_threshold, int):
            raise ConfigError(f"static layer lethal_threshold must be an integer 1..100, got {self.lethal_threshold!r}")
        if not 1 <= self.lethal_threshold <= 100:
            raise ConfigError(f"static layer lethal_threshold must be an integer 1..100, got {self.lethal_threshold!r}")


def occupancy_to_costs(occupancy: np.ndarray, params: StaticLayerParams) -> np.ndarray:
    """uint8 costs of int8 occupancy values (-1, 0..100)."""
    table = np.zeros(256, dtype=np.uint8)  # indexed by the value as uint8 (-1 -> 255)
    for value in range(101):
        if value >= params.lethal_threshold:
            table[value] = LETHAL
        elif params.trinary_costmap:
            table[value] = FREE
        else:
            table[value] = int(value / params.lethal_threshold * LETHAL)
    table[255] = NO_INFORMATION if params.track_unknown_space else FREE
    return table[np.asarray(occupancy, dtype=np.int8).view(np.uint8)]


class StaticLayer:
    """Costs of a static map, written into any costmap geometry (sampled by cell centre when not aligned)."""

    def __init__(self, grid: GridMap, params: StaticLayerParams = StaticLayerParams()) -> None:
        self.params = params
        self.set_map(grid)

    def set_map(self, grid: GridMap) -> None:
        """Replace the map (e.g. a new ``map`` message)."""
        self.grid = grid
        self.costs = occupancy_to_costs(grid.occupancy, self.params)

    def aligned_offset(self, geometry: CostmapGeometry) -> Tuple[int, int] | None:
        """(row, col) of the costmap's cell (0, 0) in the map when cells coincide exactly, else None."""
        grid = self.grid
        if grid.origin[2] != 0.0 or not math.isclose(grid.resolution, geometry.resolution, rel_tol=1e-9):
            return None
        col = (geometry.origin_x - grid.origin[0]) / grid.resolution
        row = (geometry.origin_y - grid.origin[1]) / grid.resolution
        if abs(col - round(col)) > 1e-6 or abs(row - round(row)) > 1e-6:
            return None
        return round(row), round(col)

    def costs_in(self, geometry: CostmapGeometry, rows: slice, cols: slice) -> np.ndarray:
        """The layer's costs on the costmap cells ``[rows, cols]`` of ``geometry`` (NO_INFORMATION off the map)."""
        r0, r1, _ = rows.indices(geometry.height)
        c0, c1, _ = cols.indices(geometry.width)
        out = np.full((r1 - r0, c1 - c0), NO_INFORMATION, dtype=np.uint8)
        offset = self.aligned_offset(geometry)
        if offset is not None:
            mr0, mc0 = offset[0] + r0, offset[1] + c0
            sr0, sc0 = max(mr0, 0), max(mc0, 0)
            sr1 = min(mr0 + out.shape[0], self.grid.height)
            sc1 = min(mc0 + out.shape[1], self.grid.width)
            if sr1 > sr0 and sc1 > sc0:
                out[sr0 - mr0 : sr1 - mr0, sc0 - mc0 : sc1 - mc0] = self.costs[sr0:sr1, sc0:sc1]
            return out
        cell_rows, cell_cols = np.mgrid[r0:r1, c0:c1]
        xs, ys = geometry.cells_to_world(cell_rows, cell_cols)
        map_rows, map_cols = self.grid.world_to_cells(xs, ys)
        inside = (map_rows >= 0) & (map_rows < self.grid.height) & (map_cols >= 0) & (map_cols < self.grid.width)
        out[inside] = self.costs[map_rows[inside], map_cols[inside]]
        return out
