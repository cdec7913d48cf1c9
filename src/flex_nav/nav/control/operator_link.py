"""Is the operator side still there? Its heartbeat, timed on wall time.

A network link that drops does not close TCP connections for a long time: a robot whose controllers got their
goals from a behavior runner on another computer would drive on, unseen and unstoppable. The runner publishes a
heartbeat (:mod:`flex_nav.ros.heartbeat`); the motion nodes on the robot give up when it stops coming.
Wall time, not ROS time: the simulated clock may come over the same link.

Pure logic: the caller passes the wall time [s] (``time.monotonic``); nothing here reads a clock.
"""

from __future__ import annotations

import math
from typing import Optional

from flex_nav.exceptions import ConfigError


class OperatorLink:
    """Heartbeats heard from the operator side; lost when none came for ``timeout_s`` [s of wall time].

    ``timeout_s`` 0 disables the watch (the link is never lost). With it on, the link counts as lost until the
    first heartbeat: nothing moves before the operator side has been heard.
    """

    def __init__(self, timeout_s: float) -> None:
        if not math.isfinite(timeout_s) or timeout_s < 0.0:
            raise ConfigError(f"heartbeat timeout must be a finite number >= 0 [s], got {timeout_s!r}")
        self.timeout_s = timeout_s
        self._last_heard_s: Optional[float] = None  # [s] wall time of the newest heartbeat

    @property
    def enabled(self) -> bool:
        return self.timeout_s > 0.0

    def heard(self, wall_s: float) -> None:
        """A heartbeat arrived at ``wall_s``."""
        self._last_heard_s = wall_s

    def lost(self, wall_s: float) -> bool:
        """True when the watch is on and no heartbeat came within ``timeout_s`` before ``wall_s``."""
        if not self.enabled:
            return False
        return self._last_heard_s is None or wall_s - self._last_heard_s > self.timeout_s

    def why_lost(self, wall_s: float, topic: str) -> str:
        """The reason to report when :meth:`lost` is True."""
        if self._last_heard_s is None:
            return f"no operator heartbeat on {topic} yet (heartbeat_timeout {self.timeout_s:.2f} s)"
        return (f"link to the operator lost: no heartbeat on {topic} for {wall_s - self._last_heard_s:.2f} s "
                f"(heartbeat_timeout {self.timeout_s:.2f} s)")
