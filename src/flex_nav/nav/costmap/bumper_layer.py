"""Contacts the bumpers felt: obstacles no other sensor sees (e.g. below the lidar plane).

A lidar beam passing over a low obstacle would clear an ordinary obstacle-layer mark at once, and a
ClearCostmap recovery would forget it, so the robot would replan straight back into it. Bumper marks
therefore live in their own layer: kept as points in the costmap frame, stamped LETHAL into the master
costs, untouched by ray-trace clearing and by :meth:`Costmap.reset`, and forgotten only when they are
``memory_s`` old (or on :meth:`BumperLayer.forget`). Points, not cells, so a rolling window keeps them.
"""

from __future__ import annotations

import math
from typing import List, Optional, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import LETHAL, CostmapGeometry

DEFAULT_MEMORY_S = 60.0  # [s] how long a contact stays an obstacle


class BumperLayer:
    """Bumper contact points with their time; ``memory_s`` [s] > 0."""

    def __init__(self, memory_s: float = DEFAULT_MEMORY_S) -> None:
        if not (math.isfinite(memory_s) and memory_s > 0.0):
            raise ConfigError(f"bumper memory_s must be a finite number > 0 [s], got {memory_s!r}")
        self.memory_s = float(memory_s)
        self.marks: List[Tuple[float, float, float]] = []  # (x [m], y [m], time felt [s])

    def add(self, xs: np.ndarray, ys: np.ndarray, now_s: float) -> None:
        xs = np.atleast_1d(np.asarray(xs, dtype=np.float64))
        ys = np.atleast_1d(np.asarray(ys, dtype=np.float64))
        if xs.shape != ys.shape:
            raise ConfigError(f"bumper hits need as many xs as ys, got {xs.shape} and {ys.shape}")
        if not (np.isfinite(xs).all() and np.isfinite(ys).all() and math.isfinite(now_s)):
            raise ConfigError("bumper hits must be finite points at a finite time")
        self.marks.extend((float(x), float(y), float(now_s)) for x, y in zip(xs, ys))

    def expire(self, now_s: float) -> List[Tuple[float, float]]:
        """Forget marks older than ``memory_s``; returns the forgotten points."""
        kept = [m for m in self.marks if now_s - m[2] <= self.memory_s]
        gone = [(m[0], m[1]) for m in self.marks if now_s - m[2] > self.memory_s]
        self.marks = kept
        return gone

    def forget(self) -> List[Tuple[float, float]]:
        gone = [(m[0], m[1]) for m in self.marks]
        self.marks = []
        return gone

    def box(self, geometry: CostmapGeometry, points: List[Tuple[float, float]]) -> Optional[Tuple[int, int, int, int]]:
        """Cell box (row0, row1, col0, col1) covering ``points`` on the grid, or None if none is on it."""
        if not points:
            return None
        rows, cols = geometry.world_to_cells(np.array([p[0] for p in points]), np.array([p[1] for p in points]))
        inside = (rows >= 0) & (rows < geometry.height) & (cols >= 0) & (cols < geometry.width)
        if not inside.any():
            return None
        rows, cols = rows[inside], cols[inside]
        return int(rows.min()), int(rows.max()) + 1, int(cols.min()), int(cols.max()) + 1

    def stamp(self, work: np.ndarray, geometry: CostmapGeometry, row0: int, col0: int) -> None:
        """Set LETHAL the cells of the marks inside ``work``, a window whose cell (0, 0) is grid (row0, col0)."""
        if not self.marks:
            return
        rows, cols = geometry.world_to_cells(np.array([m[0] for m in self.marks]), np.array([m[1] for m in self.marks]))
        rows, cols = rows - row0, cols - col0
        inside = (rows >= 0) & (rows < work.shape[0]) & (cols >= 0) & (cols < work.shape[1])
        work[rows[inside], cols[inside]] = LETHAL
