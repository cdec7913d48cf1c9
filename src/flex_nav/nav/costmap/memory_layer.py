"""Obstacle memory: a semantic costmap layer of the obstacles found heavy (a push failed), so that plans route
around them without trying again.

Each remembered obstacle is a convex footprint (polygon [m] in the costmap frame), the time it was found and
what it was found to be (``heavy``). Its cells are stamped LETHAL into the master costs like the bumper layer's
marks (:mod:`flex_nav.nav.costmap.bumper_layer`): untouched by ray-trace clearing and by a ClearCostmap reset.
It is forgotten

- when it is ``memory_s`` [s] old (:meth:`ObstacleMemoryLayer.expire`; a hospital moves its furniture too);
- at once when the lidar no longer sees it there (:meth:`ObstacleMemoryLayer.observe_scan`): at least
  ``min_free_beams`` beams of a scan pass through its footprint and end beyond it (or have no return), while
  fewer than ``min_hits`` beams end on it (within ``tolerance_m`` [m] of the footprint). Beams ending before the
  footprint (something in front of it) say nothing; so do footprints farther than ``max_range_m`` [m] from the
  sensor (too few, too noisy beams);
- by the operator (:meth:`ObstacleMemoryLayer.clear`: one obstacle by id, or all).

Remembering an obstacle whose centre lies in (or within ``tolerance_m`` of) one already remembered replaces that
one (new footprint, new time) instead of adding a second. At most ``max_obstacles`` are remembered: a new one
beyond that forgets the oldest (the memory stays bounded however long the robot runs).

Times are arguments [s] (the caller's ROS time); no clock here. Pure numpy, no ROS.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Tuple

import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import LETHAL, CostmapGeometry
from flex_nav.nav.costmap.obstacle_layer import LaserScan

Box = Tuple[int, int, int, int]  # (row0, row1, col0, col1), half-open
DEFAULT_MEMORY_S = 600.0  # [s] how long a heavy obstacle is remembered


@dataclass(frozen=True)
class MemoryParams:
    """Parameters of :class:`ObstacleMemoryLayer`; units in comments."""

    memory_s: float = DEFAULT_MEMORY_S  # [s] a remembered obstacle is forgotten this long after it was found
    tolerance_m: float = 0.1  # [m] a beam ending this close to a footprint ends on the obstacle
    min_free_beams: int = 3  # beams through a footprint (without a hit on it) that show it gone
    min_hits: int = 2  # beams ending on a footprint that show it still there
    max_range_m: float = 4.0  # [m] footprints farther from the sensor are not judged from a scan
    max_obstacles: int = 100  # remembered at most; a new one beyond forgets the oldest

    def __post_init__(self) -> None:
        validation.number("obstacle memory", "memory_s", self.memory_s, positive=True, unit="[s]")
        validation.number("obstacle memory", "tolerance_m", self.tolerance_m, minimum=0.0, unit="[m]")
        validation.number("obstacle memory", "max_range_m", self.max_range_m, positive=True, unit="[m]")
        validation.integer("obstacle memory", "min_free_beams", self.min_free_beams, minimum=1)
        validation.integer("obstacle memory", "min_hits", self.min_hits, minimum=1)
        validation.integer("obstacle memory", "max_obstacles", self.max_obstacles, minimum=1)


@dataclass(frozen=True)
class RememberedObstacle:
    """One remembered obstacle: id, convex footprint (N, 2) [m] counter-clockwise, time found [s], what it is."""

    obstacle_id: int
    footprint: np.ndarray
    found_s: float
    what: str

    @property
    def centre(self) -> Tuple[float, float]:
        """Mean of the footprint's corners (x, y) [m]."""
        return float(self.footprint[:, 0].mean()), float(self.footprint[:, 1].mean())

    def describe(self) -> str:
        """``#3 heavy at (5.60, 2.10) m, 0.50 x 0.50 m, found at 41.2 s``."""
        span = self.footprint.max(axis=0) - self.footprint.min(axis=0)
        x, y = self.centre
        return (f"#{self.obstacle_id} {self.what} at ({x:.2f}, {y:.2f}) m, {span[0]:.2f} x {span[1]:.2f} m, "
                f"found at {self.found_s:.1f} s")


def convex_footprint(points: np.ndarray) -> np.ndarray:
    """``points`` (N >= 3, 2) [m] as a counter-clockwise convex polygon; ConfigError if not finite, degenerate
    or not convex."""
    poly = np.asarray(points, dtype=np.float64)
    if poly.ndim != 2 or poly.shape[1] != 2 or poly.shape[0] < 3:
        raise ConfigError(f"an obstacle footprint needs >= 3 (x, y) corners, got shape {poly.shape}")
    if not np.isfinite(poly).all():
        raise ConfigError("an obstacle footprint's corners must be finite")
    edges = np.roll(poly, -1, axis=0) - poly
    area2 = float(np.sum(poly[:, 0] * np.roll(poly[:, 1], -1) - np.roll(poly[:, 0], -1) * poly[:, 1]))
    if abs(area2) < 1e-9:
        raise ConfigError("an obstacle footprint must enclose an area (its corners are on one line)")
    if area2 < 0.0:  # clockwise: turn it round
        poly = poly[::-1].copy()
        edges = np.roll(poly, -1, axis=0) - poly
    turns = edges[:, 0] * np.roll(edges[:, 1], -1) - edges[:, 1] * np.roll(edges[:, 0], -1)
    if (turns < -1e-12).any():
        raise ConfigError("an obstacle footprint must be convex (corners in order around it)")
    return poly


def _outward_normals(poly: np.ndarray) -> np.ndarray:
    """(N, 2) outward unit normals of the edges (corner i -> corner i + 1) of a counter-clockwise polygon."""
    edges = np.roll(poly, -1, axis=0) - poly
    normals = np.column_stack((edges[:, 1], -edges[:, 0]))
    unit: np.ndarray = normals / np.hypot(normals[:, 0], normals[:, 1])[:, None]
    return unit


def ray_spans(poly: np.ndarray, sx: float, sy: float, directions: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """(t_in, t_out) [m] of rays from (sx, sy) along unit ``directions`` (B, 2) through a convex CCW polygon:
    where each ray enters and leaves it (t_in > t_out: the ray misses it)."""
    normals = _outward_normals(poly)
    num = (sx - poly[:, 0])[None, :] * normals[None, :, 0] + (sy - poly[:, 1])[None, :] * normals[None, :, 1]
    den = directions[:, 0:1] * normals[None, :, 0] + directions[:, 1:2] * normals[None, :, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        limit = -num / den
    entering = den < 0.0
    leaving = den > 0.0
    t_in = np.where(entering, limit, -np.inf).max(axis=1)
    t_out = np.where(leaving, limit, np.inf).min(axis=1)
    parallel_outside = ((den == 0.0) & (num > 0.0)).any(axis=1)
    return t_in, np.where(parallel_outside, -np.inf, t_out)


class ObstacleMemoryLayer:
    """The remembered obstacles; see the module docstring. Not thread-safe (the costmap's owner serialises)."""

    def __init__(self, params: MemoryParams = MemoryParams()) -> None:
        self.params = params
        self._obstacles: List[RememberedObstacle] = []
        self._next_id = 1

    @property
    def obstacles(self) -> Tuple[RememberedObstacle, ...]:
        return tuple(self._obstacles)

    def remember(self, footprint: np.ndarray, now_s: float, what: str = "heavy") -> RememberedObstacle:
        """Remember an obstacle of convex ``footprint`` (N, 2) [m] found at ``now_s`` [s]; replaces a remembered
        obstacle whose footprint (grown by ``tolerance_m``) holds the new one's centre, and forgets the oldest
        when more than ``max_obstacles`` would be remembered."""
        validation.number("obstacle memory", "now_s", now_s, unit="[s]")
        poly = convex_footprint(footprint)
        centre = poly.mean(axis=0)
        kept = [o for o in self._obstacles if not self._holds(o.footprint, centre)]
        entry = RememberedObstacle(self._next_id, poly, float(now_s), validation.text("obstacle memory", "what", what))
        self._next_id += 1
        while len(kept) >= self.params.max_obstacles:
            kept.remove(min(kept, key=lambda o: o.found_s))
        self._obstacles = [*kept, entry]
        return entry

    def expire(self, now_s: float) -> List[RememberedObstacle]:
        """Forget the obstacles found more than ``memory_s`` before ``now_s`` [s]; returns them. A clock that
        jumped back (now before an obstacle was found) keeps it."""
        gone = [o for o in self._obstacles if now_s - o.found_s > self.params.memory_s]
        self._obstacles = [o for o in self._obstacles if o not in gone]
        return gone

    def clear(self, obstacle_id: Optional[int] = None) -> List[RememberedObstacle]:
        """The operator's clear: forget obstacle ``obstacle_id`` (None: all); returns what was forgotten
        (ConfigError for an id that is not remembered, naming the ones that are)."""
        if obstacle_id is None:
            gone, self._obstacles = self._obstacles, []
            return gone
        gone = [o for o in self._obstacles if o.obstacle_id == obstacle_id]
        if not gone:
            known = ", ".join(str(o.obstacle_id) for o in self._obstacles) or "none"
            raise ConfigError(f"obstacle memory: no obstacle #{obstacle_id} (remembered: {known})")
        self._obstacles = [o for o in self._obstacles if o.obstacle_id != obstacle_id]
        return gone

    def observe_scan(self, scan: LaserScan) -> List[RememberedObstacle]:
        """Forget the obstacles this scan (sensor pose in the costmap frame) sees through and not on; returns them."""
        if not self._obstacles:
            return []
        scan.validate()
        ranges = np.asarray(scan.ranges, dtype=np.float64)
        angles = scan.sensor_yaw + scan.angle_min + scan.angle_increment * np.arange(ranges.shape[0])
        with np.errstate(invalid="ignore"):
            usable = ~np.isnan(ranges) & (ranges >= scan.range_min)
            hit = usable & (ranges < scan.range_max)
        reach = np.where(hit, ranges, scan.range_max)  # a beam without a return saw free space to range_max
        directions = np.column_stack((np.cos(angles), np.sin(angles)))
        gone = []
        for obstacle in self._obstacles:
            if self._seen_gone(obstacle.footprint, scan, directions, reach, usable):
                gone.append(obstacle)
        self._obstacles = [o for o in self._obstacles if o not in gone]
        return gone

    def _seen_gone(self, poly: np.ndarray, scan: LaserScan, directions: np.ndarray, reach: np.ndarray,
                   usable: np.ndarray) -> bool:
        p = self.params
        t_in, t_out = ray_spans(poly, scan.sensor_x, scan.sensor_y, directions)
        crosses = usable & (t_in < t_out) & (t_in > 0.0) & (t_in <= p.max_range_m)
        on_it = crosses & (reach >= t_in - p.tolerance_m) & (reach <= t_out + p.tolerance_m)
        through = crosses & (reach > t_out + p.tolerance_m)
        return int(through.sum()) >= p.min_free_beams and int(on_it.sum()) < p.min_hits

    def _holds(self, poly: np.ndarray, point: np.ndarray) -> bool:
        normals = _outward_normals(poly)
        offsets = ((point[None, :] - poly) * normals).sum(axis=1)
        return bool((offsets <= self.params.tolerance_m).all())

    # ------------------------------------------------------------------ costmap interface (as the bumper layer)
    def cells(self, geometry: CostmapGeometry, obstacle: RememberedObstacle) -> Tuple[np.ndarray, np.ndarray]:
        """(rows, cols) of the cells an obstacle covers: every cell whose centre lies in its footprint grown by
        half a cell (so a footprint never marks fewer cells than it touches by more than half a cell)."""
        poly = obstacle.footprint
        (row0, col0), (row1, col1) = (geometry.world_to_cell(*poly.min(axis=0)),
                                      geometry.world_to_cell(*poly.max(axis=0)))
        rows, cols = np.mgrid[row0:row1 + 1, col0:col1 + 1]
        xs, ys = geometry.cells_to_world(rows.ravel(), cols.ravel())
        normals = _outward_normals(poly)
        offsets = ((xs[:, None] - poly[None, :, 0]) * normals[None, :, 0]
                   + (ys[:, None] - poly[None, :, 1]) * normals[None, :, 1])
        inside = (offsets <= 0.5 * geometry.resolution + 1e-9).all(axis=1)
        return rows.ravel()[inside], cols.ravel()[inside]

    def box(self, geometry: CostmapGeometry, obstacles: List[RememberedObstacle]) -> Optional[Box]:
        """Cell box (row0, row1, col0, col1) covering ``obstacles`` on the grid (their corners' bounds and half a
        cell), or None if none is on it."""
        if not obstacles:
            return None
        corners = np.concatenate([o.footprint for o in obstacles])
        margin = 0.5 * geometry.resolution
        low = geometry.world_to_cell(*(corners.min(axis=0) - margin))
        high = geometry.world_to_cell(*(corners.max(axis=0) + margin))
        row0, col0 = max(0, low[0]), max(0, low[1])
        row1, col1 = min(geometry.height, high[0] + 1), min(geometry.width, high[1] + 1)
        return (row0, row1, col0, col1) if row0 < row1 and col0 < col1 else None

    def stamp(self, work: np.ndarray, geometry: CostmapGeometry, row0: int, col0: int) -> None:
        """Set LETHAL the cells of the remembered obstacles inside ``work``, a window whose cell (0, 0) is grid
        (row0, col0)."""
        for obstacle in self._obstacles:
            rows, cols = self.cells(geometry, obstacle)
            rows, cols = rows - row0, cols - col0
            inside = (rows >= 0) & (rows < work.shape[0]) & (cols >= 0) & (cols < work.shape[1])
            work[rows[inside], cols[inside]] = LETHAL


def box_footprint(x: float, y: float, length_m: float, width_m: float, yaw: float = 0.0) -> np.ndarray:
    """(4, 2) counter-clockwise corners [m] of a ``length_m`` x ``width_m`` rectangle centred on (x, y) [m],
    its length along ``yaw`` [rad]."""
    validation.number("obstacle footprint", "length_m", length_m, positive=True, unit="[m]")
    validation.number("obstacle footprint", "width_m", width_m, positive=True, unit="[m]")
    c, s = math.cos(yaw), math.sin(yaw)
    half = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]]) * [length_m / 2.0, width_m / 2.0]
    return np.column_stack((x + c * half[:, 0] - s * half[:, 1], y + s * half[:, 0] + c * half[:, 1]))
