"""A layered costmap (costmap_2d's LayeredCostmap): static + obstacle layers, then inflation.

The master costs are rebuilt from the layers, in costmap_2d's order:

1. reset to the default (NO_INFORMATION when ``track_unknown_space``, else FREE),
2. static layer: overwrites (a rolling window takes the maximum instead, as costmap_2d does),
3. obstacle layer: maximum, NO_INFORMATION layer cells skipped,
4. bumper contacts and, with ``memory``, the remembered heavy obstacles (:mod:`~flex_nav.nav.costmap.memory_layer`):
   LETHAL,
5. inflation of every LETHAL cell (:mod:`flex_nav.nav.costmap.inflation`).

Updates are bounded like costmap_2d's: observations grow a "dirty" box, and :meth:`Costmap.update` rebuilds
only that box grown by the inflation radius (reading lethal cells one more radius out), so a scan on a
2000² global costmap costs a small window, not the whole map. A rolling window (local costmap) re-centres
on the robot with :meth:`Costmap.recentre`, keeping the observations it already has.

One instance per costmap; not thread-safe (a node calls it from one thread or under its own lock).
"""

from __future__ import annotations

import math
from typing import List, Optional, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.bumper_layer import DEFAULT_MEMORY_S, BumperLayer
from flex_nav.nav.costmap.costmap_grid import FREE, NO_INFORMATION, CostmapGeometry, costs_to_occupancy
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.costmap.inflation import InflationParams, Inflator
from flex_nav.nav.costmap.memory_layer import MemoryParams, ObstacleMemoryLayer, RememberedObstacle
from flex_nav.nav.costmap.obstacle_layer import LaserScan, ObstacleLayer, ObstacleLayerParams
from flex_nav.nav.costmap.static_layer import StaticLayer, StaticLayerParams

Box = Tuple[int, int, int, int]  # (row0, row1, col0, col1), half-open


class Costmap:
    """A costmap: geometry, optional static and obstacle layers, optional inflation, and the master costs."""

    def __init__(
        self,
        geometry: CostmapGeometry,
        *,
        static_map: Optional[GridMap] = None,
        static_params: StaticLayerParams = StaticLayerParams(),  # noqa: B008
        obstacles: Optional[ObstacleLayerParams] = None,
        inflation: Optional[InflationParams] = None,
        rolling_window: bool = False,
        track_unknown_space: bool = False,
        bumper_memory_s: float = DEFAULT_MEMORY_S,
        memory: Optional[MemoryParams] = None,
    ) -> None:
        self.geometry = geometry
        self.bumper_layer = BumperLayer(bumper_memory_s)
        self.memory_layer = ObstacleMemoryLayer(memory) if memory is not None else None
        self.rolling_window = rolling_window
        self.default_value = NO_INFORMATION if track_unknown_space else FREE
        self.static_layer = StaticLayer(static_map, static_params) if static_map is not None else None
        self.obstacle_layer = ObstacleLayer(geometry, obstacles) if obstacles is not None else None
        self.inflator = Inflator(inflation, geometry.resolution) if inflation is not None else None
        self.costs = np.full(geometry.shape, self.default_value, dtype=np.uint8)
        self._dirty: Optional[Box] = (0, geometry.height, 0, geometry.width)
        self.update()

    # ------------------------------------------------------------------ construction helpers
    @classmethod
    def from_map(
        cls,
        grid: GridMap,
        *,
        static_params: StaticLayerParams = StaticLayerParams(),  # noqa: B008
        obstacles: Optional[ObstacleLayerParams] = None,
        inflation: Optional[InflationParams] = None,
        track_unknown_space: bool = True,
        memory: Optional[MemoryParams] = None,
    ) -> Costmap:
        """A global costmap covering ``grid`` exactly (same cells), static layer from it; ``memory``: with an
        obstacle memory layer."""
        if grid.origin[2] != 0.0:
            raise ConfigError(
                f"a costmap from a map needs map origin yaw 0 (costmaps are axis-aligned), got {grid.origin[2]!r}"
            )
        geometry = CostmapGeometry(grid.width, grid.height, grid.resolution, grid.origin[0], grid.origin[1])
        return cls(
            geometry,
            static_map=grid,
            static_params=static_params,
            obstacles=obstacles,
            inflation=inflation,
            track_unknown_space=track_unknown_space,
            memory=memory,
        )

    @classmethod
    def rolling(
        cls,
        width_m: float,
        height_m: float,
        resolution: float,
        *,
        obstacles: Optional[ObstacleLayerParams] = None,
        inflation: Optional[InflationParams] = None,
        static_map: Optional[GridMap] = None,
        static_params: StaticLayerParams = StaticLayerParams(),  # noqa: B008
        centre: Tuple[float, float] = (0.0, 0.0),
        track_unknown_space: bool = False,
        bumper_memory_s: float = DEFAULT_MEMORY_S,
    ) -> Costmap:
        """A rolling-window (local) costmap of ``width_m`` x ``height_m`` [m] centred on ``centre`` (x, y) [m]."""
        for name, value in (("width_m", width_m), ("height_m", height_m), ("resolution", resolution)):
            if not math.isfinite(value) or value <= 0:
                raise ConfigError(f"rolling costmap {name} must be a finite number > 0, got {value!r}")
        width = max(1, round(width_m / resolution))
        height = max(1, round(height_m / resolution))
        geometry = CostmapGeometry(width, height, resolution)
        geometry.origin_x, geometry.origin_y = cls._snapped_origin(geometry, centre[0], centre[1])
        return cls(
            geometry,
            static_map=static_map,
            static_params=static_params,
            obstacles=obstacles if obstacles is not None else ObstacleLayerParams(),
            inflation=inflation,
            rolling_window=True,
            track_unknown_space=track_unknown_space,
            bumper_memory_s=bumper_memory_s,
        )

    # ------------------------------------------------------------------ observations
    def add_scan(self, scan: LaserScan) -> None:
        """Clear and mark one laser scan (pose in this costmap's frame); call :meth:`update` afterwards."""
        layer = self._obstacles("add_scan")
        self._grow_dirty(layer.add_scan(scan))
        if self.memory_layer is not None:  # a remembered obstacle the scan sees through is gone: forget it at once
            self._forgotten(self.memory_layer.observe_scan(scan))

    def mark_obstacles(self, xs: np.ndarray, ys: np.ndarray) -> None:
        """Mark LETHAL obstacle points (x [m], y [m]) in the obstacle layer: later scans may clear them."""
        layer = self._obstacles("mark_obstacles")
        self._grow_dirty(layer.mark_points(xs, ys))

    def add_bumper_hits(self, xs: np.ndarray, ys: np.ndarray, now_s: float = 0.0) -> None:
        """Mark LETHAL where the bumpers touched something (points in this costmap's frame [m]) at ``now_s`` [s].

        The marks survive lidar clearing and :meth:`reset`; :meth:`expire_bumper_hits` forgets old ones.
        """
        self.bumper_layer.add(xs, ys, now_s)
        points = [(float(x), float(y)) for x, y in zip(np.atleast_1d(xs), np.atleast_1d(ys))]
        self._grow_dirty(self.bumper_layer.box(self.geometry, points))

    def expire_bumper_hits(self, now_s: float) -> int:
        """Forget bumper marks older than the layer's memory; returns how many were forgotten."""
        gone = self.bumper_layer.expire(now_s)
        self._grow_dirty(self.bumper_layer.box(self.geometry, gone))
        return len(gone)

    def remember_obstacle(self, footprint: np.ndarray, now_s: float, what: str = "heavy") -> RememberedObstacle:
        """Remember an obstacle (convex ``footprint`` (N, 2) [m] in this costmap's frame) found at ``now_s`` [s]:
        LETHAL until it expires, a scan sees it gone, or :meth:`clear_memory`; survives :meth:`reset`. An obstacle
        it replaces (or the oldest, when the memory is full) is no longer marked."""
        layer = self._memory("remember_obstacle")
        before = layer.obstacles
        entry = layer.remember(footprint, now_s, what)
        kept = {o.obstacle_id for o in layer.obstacles}
        displaced = [o for o in before if o.obstacle_id not in kept]  # replaced, or the oldest when full
        self._grow_dirty(layer.box(self.geometry, [entry, *displaced]))  # their cells are no longer LETHAL
        return entry

    def expire_memory(self, now_s: float) -> List[RememberedObstacle]:
        """Forget remembered obstacles older than the memory's ``memory_s`` at ``now_s`` [s]; returns them."""
        return self._forgotten(self._memory("expire_memory").expire(now_s))

    def clear_memory(self, obstacle_id: Optional[int] = None) -> List[RememberedObstacle]:
        """The operator's clear: forget remembered obstacle ``obstacle_id`` (None: all); returns them."""
        return self._forgotten(self._memory("clear_memory").clear(obstacle_id))

    def set_static_map(self, grid: GridMap) -> None:
        """Replace the static map (a new ``map`` message); the whole costmap is rebuilt on the next update."""
        if self.static_layer is None:
            self.static_layer = StaticLayer(grid)
        else:
            self.static_layer.set_map(grid)
        self._dirty = (0, self.geometry.height, 0, self.geometry.width)

    def recentre(self, x: float, y: float) -> None:
        """Move a rolling window so that it is centred on (x [m], y [m]), keeping what overlaps."""
        if not self.rolling_window:
            raise ConfigError("recentre() is for rolling-window costmaps; this costmap is static-size")
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ConfigError(f"recentre needs a finite position, got ({x!r}, {y!r})")
        geo = self.geometry
        new_x, new_y = self._snapped_origin(geo, x, y)
        d_cols = round((new_x - geo.origin_x) / geo.resolution)
        d_rows = round((new_y - geo.origin_y) / geo.resolution)
        if d_cols == 0 and d_rows == 0:
            return
        geo.origin_x, geo.origin_y = new_x, new_y
        if self.obstacle_layer is not None:
            self.obstacle_layer.shift(d_rows, d_cols)
        self._dirty = (0, geo.height, 0, geo.width)

    def reset(self, forget_contacts: bool = False) -> None:
        """Full clear (ClearCostmap): forget every sensor observation and rebuild from the static map.

        Bumper contacts are kept (they are what a bumper recovery must avoid next) unless ``forget_contacts``;
        remembered obstacles are kept (:meth:`clear_memory` forgets them).
        """
        if self.obstacle_layer is not None:
            self.obstacle_layer.reset()
        if forget_contacts:
            self.bumper_layer.forget()
        self._dirty = (0, self.geometry.height, 0, self.geometry.width)
        self.update()

    # ------------------------------------------------------------------ master costs
    def update(self) -> Optional[Box]:
        """Rebuild the master costs where observations changed them; returns the rebuilt box or None."""
        if self._dirty is None:
            return None
        geo = self.geometry
        radius = self.inflator.radius_cells if self.inflator is not None else 0
        row0, row1, col0, col1 = self._dirty
        self._dirty = None
        inner = _grow((row0, row1, col0, col1), radius, geo.shape)
        outer = _grow(inner, radius, geo.shape)
        rows, cols = slice(outer[0], outer[1]), slice(outer[2], outer[3])
        work = np.full((outer[1] - outer[0], outer[3] - outer[2]), self.default_value, dtype=np.uint8)
        if self.static_layer is not None:
            static = self.static_layer.costs_in(geo, rows, cols)
            if self.rolling_window:
                known = static != NO_INFORMATION
                take = known & ((work == NO_INFORMATION) | (work < static))
                work[take] = static[take]
            else:
                work[...] = static
        if self.obstacle_layer is not None:
            layer = self.obstacle_layer.costs[rows, cols]
            take = (layer != NO_INFORMATION) & ((work == NO_INFORMATION) | (work < layer))
            work[take] = layer[take]
        self.bumper_layer.stamp(work, geo, outer[0], outer[2])
        if self.memory_layer is not None:
            self.memory_layer.stamp(work, geo, outer[0], outer[2])
        if self.inflator is not None:
            self.inflator.apply(work)
        r_off, c_off = inner[0] - outer[0], inner[2] - outer[2]
        self.costs[inner[0] : inner[1], inner[2] : inner[3]] = work[
            r_off : r_off + inner[1] - inner[0], c_off : c_off + inner[3] - inner[2]
        ]
        return inner

    def cost_at(self, x: float, y: float) -> int:
        """Master cost at (x [m], y [m]); NO_INFORMATION off the grid."""
        cell = self.geometry.world_to_cell(x, y)
        if not self.geometry.in_bounds(cell):
            return NO_INFORMATION
        return int(self.costs[cell])

    def to_occupancy(self) -> np.ndarray:
        """Master costs as OccupancyGrid values (int8 (H, W)): 0..100, 99 inscribed, 100 lethal, -1 unknown."""
        return costs_to_occupancy(self.costs)

    # ------------------------------------------------------------------ internals
    @staticmethod
    def _snapped_origin(geo: CostmapGeometry, x: float, y: float) -> Tuple[float, float]:
        # origin on a multiple of the resolution so cells of successive windows coincide
        res = geo.resolution
        return (
            math.floor((x - geo.width * res / 2.0) / res) * res,
            math.floor((y - geo.height * res / 2.0) / res) * res,
        )

    def _memory(self, what: str) -> ObstacleMemoryLayer:
        if self.memory_layer is None:
            raise ConfigError(f"{what}: this costmap has no obstacle memory (construct it with memory=...)")
        return self.memory_layer

    def _forgotten(self, gone: List[RememberedObstacle]) -> List[RememberedObstacle]:
        if gone and self.memory_layer is not None:
            self._grow_dirty(self.memory_layer.box(self.geometry, gone))
        return gone

    def _obstacles(self, what: str) -> ObstacleLayer:
        if self.obstacle_layer is None:
            raise ConfigError(f"{what}: this costmap has no obstacle layer (construct it with obstacles=...)")
        return self.obstacle_layer

    def _grow_dirty(self, box: Optional[Box]) -> None:
        if box is None:
            return
        if self._dirty is None:
            self._dirty = box
        else:
            d = self._dirty
            self._dirty = (min(d[0], box[0]), max(d[1], box[1]), min(d[2], box[2]), max(d[3], box[3]))


def _grow(box: Box, cells: int, shape: Tuple[int, int]) -> Box:
    return (
        max(0, box[0] - cells),
        min(shape[0], box[1] + cells),
        max(0, box[2] - cells),
        min(shape[1], box[3] + cells),
    )
