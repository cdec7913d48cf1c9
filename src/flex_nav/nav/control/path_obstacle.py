"""Is a stretch of a path free in a costmap? The first sample of the path that lies on an obstacle cell.

Used by the controller's blocked-path watch (an obstacle on the path ahead ends following with ``blocked``)
and by pure pursuit (a nearer carrot may replace the far one only while the path itself is clear).
Pure: no ROS.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from flex_nav.nav.costmap.costmap_grid import INSCRIBED, NO_INFORMATION, CostmapGeometry


@dataclass(frozen=True)
class PathObstacle:
    """Where the path is blocked: the sample (x [m], y [m]) in the path frame and how far ahead [m] it is."""

    x: float
    y: float
    ahead_m: float


def obstacle_on_path(
    path: np.ndarray,
    lengths: np.ndarray,
    s_from: float,
    *,
    distance_m: float,
    costs: np.ndarray,
    geometry: CostmapGeometry,
    unknown_blocks: bool = False,
) -> Optional[PathObstacle]:
    """The first path sample in [``s_from``, ``s_from + distance_m``] [m of arc] lying on an obstacle cell.

    ``path`` (N, 2|3) and ``lengths`` (its cumulative arc lengths, N) are in the costmap's frame; samples
    are spaced one costmap cell apart and stop at the path's end. An obstacle cell costs >= INSCRIBED; a
    NO_INFORMATION cell is one only with ``unknown_blocks``. None when that stretch is free (or off the grid).
    """
    if path.shape[0] == 0 or distance_m <= 0.0:
        return None
    end = min(float(lengths[-1]), s_from + distance_m)
    if end < s_from:
        return None
    step = geometry.resolution
    samples = np.arange(max(s_from, 0.0), end + 1e-9, step)
    if samples.size == 0:
        samples = np.array([end])
    xs = np.interp(samples, lengths, path[:, 0])
    ys = np.interp(samples, lengths, path[:, 1])
    rows, cols = geometry.world_to_cells(xs, ys)
    inside = (rows >= 0) & (rows < geometry.height) & (cols >= 0) & (cols < geometry.width)
    if not inside.any():
        return None
    hit = np.zeros(samples.shape, dtype=bool)
    cell_costs = costs[rows[inside], cols[inside]]
    blocking = cell_costs >= INSCRIBED  # INSCRIBED, LETHAL and NO_INFORMATION
    if not unknown_blocks:
        blocking &= cell_costs != NO_INFORMATION
    hit[inside] = blocking
    found = np.flatnonzero(hit)
    if found.size == 0:
        return None
    k = int(found[0])
    return PathObstacle(float(xs[k]), float(ys[k]), float(samples[k] - s_from))
