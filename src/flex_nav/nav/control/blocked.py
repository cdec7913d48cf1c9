"""Blocked-path detection: is there an obstacle on the path within a distance ahead of the robot?

A controller's collision check looks at the arc it is about to drive; a behavior that wants to *react*
to an obstacle (classify it, push it, wait for it, plan around it) needs to know that the path itself is
blocked, as early as the sensors see it. :func:`obstacle_on_path` (:mod:`flex_nav.nav.control.path_obstacle`)
samples the path every costmap cell from the robot's arc position ``s_from`` [m] up to ``distance_m``
ahead and reports the first sample whose cell is an obstacle for the robot's centre (cost >= INSCRIBED
and not NO_INFORMATION: unknown space outside a rolling window does not block). :class:`BlockedPathWatch`
adds the time rule: blocked only once the same condition held for ``timeout_s`` [s], so one noisy scan
does not end a goal.

Pure: no ROS, no clock of its own (times are passed in [s]).
"""

from __future__ import annotations

import math
from typing import Optional

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.path_obstacle import PathObstacle, obstacle_on_path

__all__ = ["BlockedPathWatch", "PathObstacle", "obstacle_on_path"]


class BlockedPathWatch:
    """Blocked when an obstacle sat on the path within ``distance_m`` [m] for ``timeout_s`` [s] without a
    free tick in between. ``distance_m`` 0 disables the watch (it never reports)."""

    def __init__(self, distance_m: float, timeout_s: float) -> None:
        for name, value in (("blocked_distance_m", distance_m), ("blocked_timeout_s", timeout_s)):
            if not math.isfinite(value) or value < 0.0:
                raise ConfigError(f"{name} must be a finite number >= 0, got {value!r}")
        self.distance_m = distance_m
        self.timeout_s = timeout_s
        self._since_s: Optional[float] = None

    @property
    def enabled(self) -> bool:
        return self.distance_m > 0.0

    def reset(self) -> None:
        self._since_s = None

    def update(self, obstacle: Optional[PathObstacle], now_s: float) -> Optional[str]:
        """The abort reason (starting with ``blocked``) once the path stayed blocked long enough, else None."""
        if obstacle is None:
            self._since_s = None
            return None
        if self._since_s is None:
            self._since_s = now_s
        held_s = now_s - self._since_s
        if held_s < self.timeout_s:
            return None
        return (
            f"blocked: obstacle on the path {obstacle.ahead_m:.2f} m ahead at ({obstacle.x:.2f}, {obstacle.y:.2f}) "
            f"for {held_s:.2f} s (blocked_distance {self.distance_m:g} m)"
        )
