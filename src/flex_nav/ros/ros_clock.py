"""ROS time for everything that paces or times out, so nodes and behaviors follow ``/clock`` with ``use_sim_time``.

One clock for the behavior executor, the controllers and the follow servers: deadlines are in ROS time; a wait
for one is a bounded wall-time wait (on simulated time the wall duration of a sim interval is unknown, so such a
wait polls). Whether ROS time itself still runs is watched with :class:`flex_nav.nav.control.clock_watch.ClockWatch`.
"""

from __future__ import annotations

import math
import threading
from typing import Callable, Optional

import rospy

from flex_nav.behavior.state import DUE_SLACK_S
from flex_nav.ros.lockstep import LockstepParticipant

SIM_TIME_POLL_S = 0.002  # [s] wall period at which a wait on simulated time re-reads the clock
IDLE_WAIT_S = 0.1  # [s] wall bound of a wait with no finite deadline
GRID_SLACK_S = 1e-6  # [s] a grid point k * period is due this much early (k * period is not exact in floats)


def next_grid_point(now_s: float, period_s: float) -> float:
    """[s] the first point of the grid k * ``period_s`` [s] after ``now_s`` (each due GRID_SLACK_S early): a
    timer on it ticks at the same times whenever it was started, so a run does not depend on when its node came up."""
    return (math.floor((now_s + 2.0 * GRID_SLACK_S) / period_s) + 1.0) * period_s - GRID_SLACK_S


class RosClock:
    """``now()`` is ``rospy.get_time()``; waits end at the deadline, on a wake-up, or on shutdown.

    ``poll_s`` [s]: on simulated time, the longest wall-time wait before ROS time is read again. ``lockstep``: a
    participant that holds a lockstep simulation at every deadline :meth:`wait_until` waits for (its owner
    releases it when the loop ends).
    """

    def __init__(self, poll_s: float = SIM_TIME_POLL_S, lockstep: Optional[LockstepParticipant] = None) -> None:
        self._sim_time = bool(rospy.get_param("/use_sim_time", False))
        self._poll_s = poll_s
        self.lockstep = lockstep

    def now(self) -> float:
        return float(rospy.get_time())

    def wall_wait_s(self, deadline_s: float, now_s: float) -> float:
        """[s of wall time] to wait, from ROS time ``now_s``, before looking at ROS deadline ``deadline_s`` again."""
        remaining_s = deadline_s - now_s
        if remaining_s <= 0.0:
            return 0.0
        if not math.isfinite(remaining_s):
            return IDLE_WAIT_S
        return min(remaining_s, self._poll_s) if self._sim_time else remaining_s

    def wait_until(self, deadline_s: float, wake: threading.Event) -> None:
        if self.lockstep is not None:  # at the step that makes the deadline due (within the behaviors' DUE_SLACK_S)
            self.lockstep.hold_clock(deadline_s - DUE_SLACK_S)
        wait_s = self.wall_wait_s(deadline_s, self.now())
        if wait_s > 0.0:
            wake.wait(wait_s)


class LockstepTimer:
    """``callback(now_s)`` every ``period_s`` [s] of ROS time on a daemon thread named ``name``, holding a lockstep
    simulation at each call until it returns (a rospy.Timer fires beside the stepping simulation, at whatever
    step its thread gets to run). The calls fall on the grid k * ``period_s`` (:func:`next_grid_point`), not on
    the time the timer started. A call comes late rather than twice; ROS time moving back starts afresh. It runs
    until rospy shuts down (the costmaps keep theirs for the node's life)."""

    def __init__(self, period_s: float, callback: Callable[[float], None], participant: LockstepParticipant,
                 name: str) -> None:
        self._period_s = period_s
        self._callback = callback
        self._clock = RosClock(lockstep=participant)
        self._never = threading.Event()  # nothing wakes the wait early: each ends at its deadline or shutdown
        self._thread = threading.Thread(target=self._loop, name=name, daemon=True)
        self._thread.start()

    def _loop(self) -> None:
        next_s = next_grid_point(self._clock.now(), self._period_s)
        while not rospy.is_shutdown():
            now_s = self._clock.now()
            if now_s < next_s - 2.0 * self._period_s:  # ROS time went back (a restarted simulation)
                next_s = next_grid_point(now_s, self._period_s)
            if now_s >= next_s:
                self._callback(now_s)
                next_s = next_grid_point(now_s, self._period_s)  # ticks missed while late are skipped
                continue
            self._clock.wait_until(next_s, self._never)
