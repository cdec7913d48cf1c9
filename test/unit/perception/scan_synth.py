"""A synthetic 360-beam laser scan of circles in a rectangular room, for tracker and yield tests (no ROS)."""

import numpy as np

ANGLES = np.radians(np.arange(-180.0, 180.0, 1.0))  # 360 beams, 1 degree


def ray_scan(sensor, circles, room=None):
    """Beam end points (NaN: no return) of a 360-beam scan from ``sensor`` (x, y) hitting ``circles``
    [(x, y, r)] and, if given, the walls of the axis-aligned ``room`` (xmin, ymin, xmax, ymax)."""
    sx, sy = sensor
    dx, dy = np.cos(ANGLES), np.sin(ANGLES)
    best = np.full(ANGLES.shape, np.inf)
    for cx, cy, r in circles:
        ox, oy = sx - cx, sy - cy
        b = ox * dx + oy * dy
        c = ox * ox + oy * oy - r * r
        disc = b * b - c
        with np.errstate(invalid="ignore"):
            t = -b - np.sqrt(disc)
        best = np.where((disc >= 0) & (t > 0) & (t < best), t, best)
    if room is not None:
        xmin, ymin, xmax, ymax = room
        with np.errstate(divide="ignore", invalid="ignore"):
            for t in ((xmin - sx) / dx, (xmax - sx) / dx, (ymin - sy) / dy, (ymax - sy) / dy):
                best = np.where((t > 0) & (t < best), t, best)
    best = np.where(np.isfinite(best) & (best < 12.0), best, np.nan)
    return sx + best * dx, sy + best * dy
