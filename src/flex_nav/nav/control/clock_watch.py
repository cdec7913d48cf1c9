"""Watching the node's clock itself: ROS time that stops advancing, or that moves backwards, is a fault.

On simulated time (``use_sim_time``) ROS time is whatever the simulator last published on ``/clock``. When the
simulator crashes or is paused, ROS time stands still: every age and timeout measured on it stands still too,
so a stale sensor is never stale and a command never times out. When the simulator restarts (or a bag loops),
ROS time jumps back and whatever was computed on the old timeline means nothing. :class:`ClockWatch` tells the
motion nodes when either happens, by comparing ROS time with wall time (``time.monotonic``), which never stops.

Pure logic: the caller passes both readings; nothing here reads a clock.
"""

from __future__ import annotations

import enum
import math
from typing import Optional

from flex_nav.exceptions import ConfigError


class ClockChange(enum.Enum):
    """What one :meth:`ClockWatch.observe` found."""

    STEADY = "steady"  # ROS time advances (or stands still for less than the stall timeout), or stays stalled
    STALLED = "stalled"  # ROS time has just been found standing still for longer than the stall timeout
    RESUMED = "resumed"  # ROS time advances again after a stall
    JUMPED_BACK = "jumped back"  # ROS time is earlier than at the previous observation


class ClockWatch:
    """Finds a stopped or rewound ROS clock.

    ``stall_timeout_s`` [s of wall time]: ROS time that has not advanced for longer than this is stalled
    (0 disables the stall check; jumps back are always reported). The stall check is armed once ROS time has
    been seen advancing: before the simulator's first ``/clock`` a node has nothing to stop.
    """

    def __init__(self, stall_timeout_s: float) -> None:
        if not math.isfinite(stall_timeout_s) or stall_timeout_s < 0.0:
            raise ConfigError(f"clock stall timeout must be a finite number >= 0 [s], got {stall_timeout_s!r}")
        self.stall_timeout_s = stall_timeout_s
        self._last_ros_s: Optional[float] = None  # [s] ROS time at the previous observation
        self._advanced_wall_s = 0.0  # [s] wall time when ROS time was last seen advancing
        self._armed = False  # ROS time has been seen advancing
        self.stalled = False
        self.jump_s = 0.0  # [s] how far ROS time went back at the last JUMPED_BACK

    def observe(self, ros_s: float, wall_s: float) -> ClockChange:
        """Look at the clocks once: ``ros_s`` ROS time [s], ``wall_s`` monotonic wall time [s]."""
        last = self._last_ros_s
        self._last_ros_s = ros_s
        if last is None:
            self._advanced_wall_s = wall_s
            return ClockChange.STEADY
        if ros_s < last:
            self.jump_s = last - ros_s
            self._advanced_wall_s = wall_s
            self.stalled = False
            return ClockChange.JUMPED_BACK
        if ros_s > last:
            self._advanced_wall_s = wall_s
            self._armed = True
            if self.stalled:
                self.stalled = False
                return ClockChange.RESUMED
            return ClockChange.STEADY
        still_s = wall_s - self._advanced_wall_s
        if self._armed and self.stall_timeout_s > 0.0 and not self.stalled and still_s > self.stall_timeout_s:
            self.stalled = True
            return ClockChange.STALLED
        return ClockChange.STEADY

    def still_for_s(self, wall_s: float) -> float:
        """[s of wall time] since ROS time was last seen advancing (0 before the first observation)."""
        return wall_s - self._advanced_wall_s if self._last_ros_s is not None else 0.0
