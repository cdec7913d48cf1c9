"""The occupancy grid a mapper builds from scans taken at known poses: log-odds per cell, free space ray-traced.

Each beam lowers the log-odds of the cells it passes through by ``log_odds_free`` and, when it hit something
(a valid range below ``range_max``), raises the cell of its end point by ``log_odds_occupied``; a beam that saw
nothing (no return, or a range at ``range_max``) clears the cells up to ``max_free_range`` [m] and marks none.
Values are clamped to ±``log_odds_clamp`` so that a cell can change its mind when the world does (a door
opening). Rays are walked cell by cell with an exact grid traversal (Amanatides & Woo), so no cell is skipped
and none counted twice.

The map is rebuilt from the keyframes whenever the pose graph moves them (:func:`rasterize`): after an
optimisation every scan is laid down again from its corrected pose, so a closed loop leaves no doubled walls.
Output as nav_msgs/OccupancyGrid values: -1 never seen (log-odds exactly 0), 100 where the log-odds is above
``occupied_threshold``, 0 below ``free_threshold``, else -1 (seen, undecided).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable, NamedTuple, Tuple

import numpy as np

from flex_nav import validation
from flex_nav.localization.jit import cached_njit
from flex_nav.localization.scan import ScanBeams
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.planar import Pose2D, compose_poses

UNKNOWN, FREE, OCCUPIED = -1, 0, 100  # nav_msgs/OccupancyGrid values


@dataclass(frozen=True)
class OccupancyParams:
    """How scans become cell values; validated at construction (ConfigError naming the field)."""

    resolution: float = 0.05  # [m] cell size
    log_odds_occupied: float = 0.85  # [-] added to a cell a beam ends in (p 0.70)
    log_odds_free: float = -0.4  # [-] added to a cell a beam passes through (p 0.40)
    log_odds_clamp: float = 5.0  # [-] |log-odds| kept at most this
    occupied_threshold: float = 0.2  # [-] log-odds above which a cell is published occupied
    free_threshold: float = -0.2  # [-] log-odds below which a cell is published free
    max_free_range: float = 5.0  # [m] a beam that saw nothing clears cells this far at most
    padding: float = 1.0  # [m] margin around what was seen, so the grid does not grow with every scan

    def __post_init__(self) -> None:
        owner = "mapping"
        validation.number(owner, "resolution", self.resolution, positive=True, unit="[m]")
        validation.number(owner, "log_odds_occupied", self.log_odds_occupied, positive=True)
        validation.number(owner, "log_odds_free", self.log_odds_free, maximum=0.0)
        validation.number(owner, "log_odds_clamp", self.log_odds_clamp, positive=True)
        validation.number(owner, "occupied_threshold", self.occupied_threshold, minimum=0.0)
        validation.number(owner, "free_threshold", self.free_threshold, maximum=0.0)
        validation.number(owner, "max_free_range", self.max_free_range, minimum=0.0, unit="[m]")
        validation.number(owner, "padding", self.padding, minimum=0.0, unit="[m]")


class ScanRays(NamedTuple):
    """One scan's rays in the robot frame: where each starts (the laser) and ends, and whether it hit."""

    origin: Tuple[float, float]  # [m] the laser in the robot frame
    end_x: np.ndarray  # (K,) [m] robot frame
    end_y: np.ndarray  # (K,) [m]
    hit: np.ndarray  # (K,) bool: the end point is an obstacle (else the ray saw nothing up to there)


def scan_rays(scan: ScanBeams, max_free_range: float) -> ScanRays:
    """The rays of ``scan``: valid ranges end where they hit; no return (inf, NaN read as nothing, or a range at
    or beyond range_max) becomes a free ray of min(range_max, ``max_free_range``); ranges below range_min and
    non-finite angles are dropped."""
    ranges = np.asarray(scan.ranges, dtype=np.float64).ravel()
    angles = np.asarray(scan.angles, dtype=np.float64).ravel()
    with np.errstate(invalid="ignore"):
        hit = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges < scan.range_max)
        nothing = ~hit & ~(ranges < scan.range_min) & np.isfinite(angles)  # +inf, NaN, >= range_max
    keep = (hit | nothing) & np.isfinite(angles)
    length = np.where(hit, ranges, min(float(scan.range_max), max_free_range))[keep]
    lx, ly, lyaw = (float(v) for v in scan.laser_pose)
    direction = lyaw + angles[keep]
    return ScanRays((lx, ly), lx + length * np.cos(direction), ly + length * np.sin(direction), hit[keep])


@cached_njit
def _trace(  # noqa: PLR0917 - a compiled kernel takes plain positional arguments
    log_odds: np.ndarray, x0: float, y0: float, xs: np.ndarray, ys: np.ndarray, hits: np.ndarray,
    occupied: float, free: float, clamp: float,
) -> None:  # pragma: no cover  (compiled)
    """Walk each ray from (x0, y0) to (xs[k], ys[k]) (grid coordinates [cells]) through ``log_odds`` (H, W):
    ``free`` added to every cell passed, ``occupied`` to the end cell of a hit (else ``free``); clamped."""
    height, width = log_odds.shape
    for k in range(xs.shape[0]):
        x1, y1 = xs[k], ys[k]
        cx, cy = math.floor(x0), math.floor(y0)
        ex, ey = math.floor(x1), math.floor(y1)
        dx, dy = x1 - x0, y1 - y0
        step_x = 1 if dx > 0 else -1
        step_y = 1 if dy > 0 else -1
        t_delta_x = abs(1.0 / dx) if dx != 0.0 else 1e30
        t_delta_y = abs(1.0 / dy) if dy != 0.0 else 1e30
        t_max_x = ((cx + 1 - x0) if dx > 0 else (x0 - cx)) * t_delta_x if dx != 0.0 else 1e30
        t_max_y = ((cy + 1 - y0) if dy > 0 else (y0 - cy)) * t_delta_y if dy != 0.0 else 1e30
        cells = abs(ex - cx) + abs(ey - cy)
        for _ in range(cells):
            if 0 <= cx < width and 0 <= cy < height:
                value = log_odds[cy, cx] + free
                log_odds[cy, cx] = value if value > -clamp else -clamp
            if t_max_x < t_max_y:
                t_max_x += t_delta_x
                cx += step_x
            else:
                t_max_y += t_delta_y
                cy += step_y
        if 0 <= ex < width and 0 <= ey < height:
            value = log_odds[ey, ex] + (occupied if hits[k] else free)
            log_odds[ey, ex] = min(max(value, -clamp), clamp)


class OccupancyGrid:
    """Log-odds over a fixed window of the plane (origin and size set at construction)."""

    def __init__(self, params: OccupancyParams, origin: Tuple[float, float], shape: Tuple[int, int]) -> None:
        self.params = params
        self.origin = (float(origin[0]), float(origin[1]))  # [m] corner of cell (0, 0)
        self.log_odds = np.zeros(shape, dtype=np.float64)  # (H, W)

    def integrate(self, pose: Pose2D, rays: ScanRays) -> None:
        """Lay down one scan's ``rays`` taken with the robot at ``pose`` (map frame)."""
        p = self.params
        inv = 1.0 / p.resolution
        c, s = math.cos(pose[2]), math.sin(pose[2])
        ox, oy = self.origin
        lx, ly, _ = compose_poses(pose, (rays.origin[0], rays.origin[1], 0.0))
        # a hit marks the cell half a cell behind the surface it measured: the surface of a wall lies on a cell
        # edge as often as not, and the obstacle is behind it (without this, range noise splits every wall over
        # two cells, the one in front of it included)
        dx, dy = rays.end_x - rays.origin[0], rays.end_y - rays.origin[1]
        extend = np.where(rays.hit, 0.5 * p.resolution / np.maximum(np.hypot(dx, dy), 1e-9), 0.0)
        end_x, end_y = rays.end_x + extend * dx, rays.end_y + extend * dy
        xs = (pose[0] + c * end_x - s * end_y - ox) * inv
        ys = (pose[1] + s * end_x + c * end_y - oy) * inv
        _trace(self.log_odds, (lx - ox) * inv, (ly - oy) * inv, np.ascontiguousarray(xs), np.ascontiguousarray(ys),
               np.ascontiguousarray(rays.hit), p.log_odds_occupied, p.log_odds_free, p.log_odds_clamp)

    def to_grid_map(self) -> GridMap:
        """The published values (-1 / 0 / 100) as a GridMap (row 0 at the origin, as map_server's)."""
        p = self.params
        values = np.full(self.log_odds.shape, UNKNOWN, dtype=np.int8)
        values[self.log_odds > p.occupied_threshold] = OCCUPIED
        values[self.log_odds < p.free_threshold] = FREE
        return GridMap(values, p.resolution, (self.origin[0], self.origin[1], 0.0))


def bounds(poses: Iterable[Pose2D], rays: Iterable[ScanRays]) -> Tuple[float, float, float, float]:
    """(min x, min y, max x, max y) [m] of the scans' rays laid down from ``poses`` (map frame)."""
    low_x = low_y = math.inf
    high_x = high_y = -math.inf
    for pose, scan in zip(poses, rays):
        c, s = math.cos(pose[2]), math.sin(pose[2])
        xs = pose[0] + c * scan.end_x - s * scan.end_y
        ys = pose[1] + s * scan.end_x + c * scan.end_y
        low_x = min(low_x, pose[0], float(xs.min(initial=pose[0])))
        low_y = min(low_y, pose[1], float(ys.min(initial=pose[1])))
        high_x = max(high_x, pose[0], float(xs.max(initial=pose[0])))
        high_y = max(high_y, pose[1], float(ys.max(initial=pose[1])))
    return low_x, low_y, high_x, high_y


def rasterize(params: OccupancyParams, poses: Iterable[Pose2D], rays: Iterable[ScanRays]) -> OccupancyGrid:
    """A grid holding every scan (``rays[k]`` taken at ``poses[k]``, map frame), sized to what they saw plus
    ``padding``, its origin on a multiple of the resolution (so that rebuilt maps line up cell for cell)."""
    poses, rays = list(poses), list(rays)
    if not poses:
        return OccupancyGrid(params, (0.0, 0.0), (1, 1))
    low_x, low_y, high_x, high_y = bounds(poses, rays)
    res = params.resolution
    x0 = math.floor((low_x - params.padding) / res) * res
    y0 = math.floor((low_y - params.padding) / res) * res
    width = math.ceil((high_x + params.padding - x0) / res) + 1
    height = math.ceil((high_y + params.padding - y0) / res) + 1
    grid = OccupancyGrid(params, (x0, y0), (height, width))
    for pose, scan in zip(poses, rays):
        grid.integrate(pose, scan)
    return grid
