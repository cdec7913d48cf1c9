"""The behavior executor's clock on ROS time, so behaviors follow ``/clock`` when ``use_sim_time`` is set."""

from __future__ import annotations

import math
import threading

import rospy

SIM_TIME_POLL_S = 0.002  # [s] wall period at which a wait on simulated time re-reads the clock


class RosClock:
    """``now()`` is ``rospy.get_time()``; waits end at the deadline, on a wake-up, or on shutdown."""

    def __init__(self) -> None:
        self._sim_time = bool(rospy.get_param("/use_sim_time", False))

    def now(self) -> float:
        return float(rospy.get_time())

    def wait_until(self, deadline_s: float, wake: threading.Event) -> None:
        remaining_s = deadline_s - self.now()
        if remaining_s <= 0.0:
            return
        if not math.isfinite(remaining_s):
            wake.wait(0.1)
            return
        # On simulated time the wall duration of a sim interval is unknown: poll briefly (the executor loops).
        wake.wait(min(remaining_s, SIM_TIME_POLL_S) if self._sim_time else remaining_s)
