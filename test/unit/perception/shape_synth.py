"""Synthetic laser scans of boxes (convex polygons) and round bodies (circles) with range noise, for the lidar-shape
classifier and the obstacle memory tests (no ROS)."""

from __future__ import annotations

from typing import Optional, Sequence, Tuple

import numpy as np

from flex_nav.nav.costmap.memory_layer import box_footprint

Circle = Tuple[float, float, float]  # x, y, radius [m]


def box_corners(x: float, y: float, length_m: float, width_m: float, yaw: float) -> np.ndarray:
    """(4, 2) corners [m], counter-clockwise, of a ``length_m`` x ``width_m`` box centred on (x, y) turned by yaw."""
    return box_footprint(x, y, length_m, width_m, yaw)


def ranges_of(sensor: Tuple[float, float], angles: np.ndarray, polygons: Sequence[np.ndarray] = (),
              circles: Sequence[Circle] = (), max_range_m: float = 12.0) -> np.ndarray:
    """Exact range [m] of every beam (angles [rad] in the frame of the points) to the nearest polygon edge or
    circle; inf where nothing is hit within ``max_range_m``."""
    sx, sy = sensor
    dx, dy = np.cos(angles), np.sin(angles)
    best = np.full(angles.shape, np.inf)
    for polygon in polygons:
        for a, b in zip(polygon, np.roll(polygon, -1, axis=0)):
            ex, ey = b[0] - a[0], b[1] - a[1]
            denom = dx * ey - dy * ex
            with np.errstate(divide="ignore", invalid="ignore"):
                t = ((a[0] - sx) * ey - (a[1] - sy) * ex) / denom
                u = ((a[0] - sx) * dy - (a[1] - sy) * dx) / denom
            best = np.where((np.abs(denom) > 1e-12) & (t > 0) & (u >= 0) & (u <= 1) & (t < best), t, best)
    for cx, cy, r in circles:
        ox, oy = sx - cx, sy - cy
        b = ox * dx + oy * dy
        disc = b * b - (ox * ox + oy * oy - r * r)
        with np.errstate(invalid="ignore"):
            t = -b - np.sqrt(disc)
        best = np.where((disc >= 0) & (t > 0) & (t < best), t, best)
    return np.where(best < max_range_m, best, np.inf)


def noisy_scan(sensor: Tuple[float, float], polygons: Sequence[np.ndarray] = (), circles: Sequence[Circle] = (),
               *, rng: Optional[np.random.Generator] = None, noise_fraction: float = 0.005,
               increment_deg: float = 1.0, phase_deg: float = 0.0) -> Tuple[np.ndarray, np.ndarray]:
    """End points (NaN: no return) of a 360-degree scan at ``increment_deg`` from ``sensor``, range noise one
    sigma ``noise_fraction`` of the range (the RPLidar A1's 1 % as two sigma) when ``rng`` is given."""
    angles = np.radians(np.arange(-180.0, 180.0, increment_deg) + phase_deg)
    ranges = ranges_of(sensor, angles, polygons, circles)
    if rng is not None:
        finite = np.isfinite(ranges)
        ranges[finite] += rng.normal(0.0, 1.0, int(finite.sum())) * noise_fraction * ranges[finite]
    seen = np.isfinite(ranges)
    ranges = np.where(seen, ranges, 0.0)  # inf * sin(pi) is NaN with a warning
    xs = np.where(seen, sensor[0] + ranges * np.cos(angles), np.nan)
    ys = np.where(seen, sensor[1] + ranges * np.sin(angles), np.nan)
    return xs, ys
