"""The obstacle layer: marks obstacles seen by a laser scanner (and bumpers) and clears free space by ray tracing.

As costmap_2d's ObstacleLayer: all rays of an observation are cleared first (every cell from the sensor
cell to the end cell, at most ``raytrace_range`` [m] long), then hits closer than ``obstacle_range`` [m]
are marked LETHAL. Marks persist until a later ray passes through them or the layer is reset.

One deliberate difference: a beam that hit something within ``raytrace_range`` does not clear the cell it
hit. costmap_2d clears that cell too, so an obstacle the robot drives away from vanishes as soon as it is
between ``obstacle_range`` and ``raytrace_range`` away although the beams still end on it; a planner
replanning at 1 Hz then flips between a route around the obstacle and one through it (found in the S5
scenario: the baseline turned back and forth at 2.5 m from a heavy box for the whole run).

Readings: NaN and readings below ``range_min`` are ignored. A reading ``>= range_max`` or +inf is a
"no return": with ``clear_on_no_return`` (like costmap_2d's ``inf_is_valid``) it clears the whole beam
up to ``min(range_max, raytrace_range)`` and marks nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import FREE, LETHAL, NO_INFORMATION, CostmapGeometry
from flex_nav.nav.costmap.raytrace import set_rays


@dataclass(frozen=True)
class ObstacleLayerParams:
    """costmap_2d ObstacleLayer parameters (2-D subset)."""

    obstacle_range: float = 2.5  # [m] mark hits closer than this to the sensor
    raytrace_range: float = 3.0  # [m] clear free space up to this far from the sensor
    track_unknown_space: bool = False  # unobserved cells are NO_INFORMATION (else FREE)
    clear_on_no_return: bool = True  # readings >= range_max / +inf clear the whole beam

    def __post_init__(self) -> None:
        for name in ("obstacle_range", "raytrace_range"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
                raise ConfigError(f"obstacle layer {name} must be a finite number >= 0 [m], got {value!r}")


@dataclass(frozen=True)
class LaserScan:
    """A planar laser scan (sensor_msgs/LaserScan fields) with the sensor's pose in the costmap frame."""

    ranges: np.ndarray  # [m] one per beam
    angle_min: float  # [rad] angle of the first beam in the sensor frame
    angle_increment: float  # [rad] between beams
    range_min: float  # [m]
    range_max: float  # [m]
    sensor_x: float  # [m] sensor position in the costmap frame
    sensor_y: float  # [m]
    sensor_yaw: float  # [rad] sensor heading in the costmap frame

    def validate(self) -> None:
        """Raise :class:`ConfigError` for a scan that cannot be placed (bad pose/geometry; NaN ranges are fine)."""
        for name in ("angle_min", "angle_increment", "range_min", "range_max", "sensor_x", "sensor_y", "sensor_yaw"):
            if not math.isfinite(getattr(self, name)):
                raise ConfigError(f"laser scan {name} must be finite, got {getattr(self, name)!r}")
        if self.range_min < 0 or self.range_max <= self.range_min:
            raise ConfigError(
                f"laser scan needs 0 <= range_min < range_max, got {self.range_min!r}, {self.range_max!r}"
            )
        if np.ndim(self.ranges) != 1:
            raise ConfigError(f"laser scan ranges must be 1-D, got shape {np.shape(self.ranges)}")

    def endpoints(self, max_range: float) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(xs, ys, distances [m], is_hit) of every usable beam's end, beams cut at ``max_range`` [m].

        Non-hits ("no return") have ``is_hit`` False and end at ``min(range_max, max_range)``.
        """
        ranges = np.asarray(self.ranges, dtype=np.float64)
        count = ranges.shape[0]
        angles = self.sensor_yaw + self.angle_min + self.angle_increment * np.arange(count)
        with np.errstate(invalid="ignore"):
            hit = (ranges >= self.range_min) & (ranges < self.range_max)
        dist = np.where(hit, ranges, self.range_max)
        dist = np.minimum(dist, max_range)
        return (
            self.sensor_x + dist * np.cos(angles),
            self.sensor_y + dist * np.sin(angles),
            dist,
            hit,
        )


class ObstacleLayer:
    """Obstacle marks in the costmap's geometry (shares the costmap's :class:`CostmapGeometry`)."""

    def __init__(self, geometry: CostmapGeometry, params: ObstacleLayerParams = ObstacleLayerParams()) -> None:
        self.geometry = geometry
        self.params = params
        self.default_value = NO_INFORMATION if params.track_unknown_space else FREE
        self.costs = np.full(geometry.shape, self.default_value, dtype=np.uint8)

    def reset(self) -> None:
        """Forget every observation."""
        self.costs.fill(self.default_value)

    def shift(self, d_rows: int, d_cols: int) -> None:
        """The window moved by (d_rows, d_cols) cells: keep what overlaps, new cells get the default value."""
        self.costs = shifted(self.costs, d_rows, d_cols, self.default_value)

    def add_scan(self, scan: LaserScan) -> Tuple[int, int, int, int] | None:
        """Clear along each beam, then mark its hit; returns the touched box (row0, row1, col0, col1) or None."""
        scan.validate()
        geo = self.geometry
        ranges = np.asarray(scan.ranges, dtype=np.float64)
        finite_or_inf = ~np.isnan(ranges)
        with np.errstate(invalid="ignore"):
            usable = finite_or_inf & (ranges >= scan.range_min)
        xs, ys, _, hit = scan.endpoints(self.params.raytrace_range)
        clear = usable & (hit | self.params.clear_on_no_return)
        row0, col0 = geo.world_to_cell(scan.sensor_x, scan.sensor_y)
        sensor_inside = geo.in_bounds((row0, col0))
        if sensor_inside:  # like costmap_2d: no clearing from a sensor off the grid, marking still happens
            end_rows, end_cols = geo.world_to_cells(xs[clear], ys[clear])
            with np.errstate(invalid="ignore"):  # the end cell of a beam that hit within reach stays
                ended_on_hit = (hit & (ranges <= self.params.raytrace_range))[clear]
            set_rays(self.costs, row0, col0, end_rows, end_cols, FREE, ended_on_hit)
        # marks: hits closer than obstacle_range (measured on the uncut reading)
        with np.errstate(invalid="ignore"):
            mark = usable & hit & (ranges < self.params.obstacle_range)
        angles = scan.sensor_yaw + scan.angle_min + scan.angle_increment * np.flatnonzero(mark)
        mark_x = scan.sensor_x + ranges[mark] * np.cos(angles)
        mark_y = scan.sensor_y + ranges[mark] * np.sin(angles)
        marked = self._mark(mark_x, mark_y)
        if not sensor_inside:
            return marked
        reach = max(self.params.raytrace_range, self.params.obstacle_range) / geo.resolution + 1
        return (
            max(0, int(row0 - reach)),
            min(geo.height, int(row0 + reach) + 1),
            max(0, int(col0 - reach)),
            min(geo.width, int(col0 + reach) + 1),
        )

    def mark_points(self, xs: np.ndarray, ys: np.ndarray) -> Tuple[int, int, int, int] | None:
        """Mark LETHAL the cells of points (x [m], y [m]) in the costmap frame, e.g. bumper hits.

        Non-finite points raise :class:`ConfigError`; points off the grid are ignored.
        Returns the touched box (row0, row1, col0, col1) or None when nothing was marked.
        """
        xs = np.atleast_1d(np.asarray(xs, dtype=np.float64))
        ys = np.atleast_1d(np.asarray(ys, dtype=np.float64))
        if xs.shape != ys.shape:
            raise ConfigError(f"mark_points needs as many xs as ys, got {xs.shape} and {ys.shape}")
        if not (np.isfinite(xs).all() and np.isfinite(ys).all()):
            raise ConfigError("mark_points got a non-finite point")
        return self._mark(xs, ys)

    def _mark(self, xs: np.ndarray, ys: np.ndarray) -> Tuple[int, int, int, int] | None:
        rows, cols = self.geometry.world_to_cells(xs, ys)
        inside = (rows >= 0) & (rows < self.geometry.height) & (cols >= 0) & (cols < self.geometry.width)
        if not inside.any():
            return None
        rows, cols = rows[inside], cols[inside]
        self.costs[rows, cols] = LETHAL
        return int(rows.min()), int(rows.max()) + 1, int(cols.min()), int(cols.max()) + 1

    def combine_into(self, master: np.ndarray, rows: slice, cols: slice) -> None:
        """costmap_2d's updateWithMax on ``master[rows, cols]``: NO_INFORMATION layer cells are skipped."""
        layer = self.costs[rows, cols]
        target = master[rows, cols]
        known = layer != NO_INFORMATION
        take = known & ((target == NO_INFORMATION) | (target < layer))
        target[take] = layer[take]


def shifted(array: np.ndarray, d_rows: int, d_cols: int, fill: int) -> np.ndarray:
    """A copy of ``array`` seen from a window moved by (d_rows, d_cols) cells; uncovered cells get ``fill``.

    New cell (r, c) holds old cell (r + d_rows, c + d_cols).
    """
    height, width = array.shape
    out = np.full_like(array, fill)
    if abs(d_rows) >= height or abs(d_cols) >= width:
        return out
    src_r0, src_r1 = max(d_rows, 0), height + min(d_rows, 0)
    src_c0, src_c1 = max(d_cols, 0), width + min(d_cols, 0)
    out[src_r0 - d_rows : src_r1 - d_rows, src_c0 - d_cols : src_c1 - d_cols] = array[src_r0:src_r1, src_c0:src_c1]
    return out
