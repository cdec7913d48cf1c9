"""The newest nav_msgs/Path on a topic named in a FollowTopic goal, with a bounded wait for the first one.

Shared by ``follow_topic_server`` and ``pure_pursuit_topic``. The name in the goal is used exactly as
given (a relative name resolves in the node's namespace, as every ROS name does); the subscription is
kept while consecutive goals name the same topic, so a latched or frequent topic answers at once.

A Path stamped before the goal started is most likely what the topic held for the previous goal (a
planner's latched plan): following it, a controller already at its end would report success at once.
Such a Path is used only if no newer one arrives within ``STALE_GRACE_S`` (a one-shot latched publisher).
Both waits run on ROS time (:class:`flex_nav.ros.ros_clock.RosClock`), like every other timeout of the nodes.
In a lockstep simulation each Path taken in is reported to the simulator (``lockstep``, a participant of the node),
which waits for a Path its publisher announced (a behavior's plans) until it is in: a controller sees each new plan
at the same step whatever the load.
A client that already waited for a fresh Path says from when it counted (the goal's ``newer_than``), so the
server does not wait again for one newer than the goal.
"""

from __future__ import annotations

import math
import threading
from typing import Optional

import rospy
from nav_msgs.msg import Path

from flex_nav.ros.lockstep import LockstepParticipant, stamped_before
from flex_nav.ros.ros_clock import RosClock

STALE_GRACE_S = 1.0  # [s] ROS time: how long to wait for a Path newer than the goal before using an older one


class TopicPath:
    """Subscription to one topic: the newest Path and how many have arrived."""

    def __init__(self, topic: str, wake: threading.Condition, lockstep: Optional[LockstepParticipant] = None,
                 ) -> None:
        self.topic = topic
        self._wake = wake
        self._lockstep = lockstep
        self.msg: Optional[Path] = None
        self.count = 0
        self.arrived_s = -math.inf  # [s] ROS time the newest Path arrived at
        if lockstep is not None:
            lockstep.received(topic, -math.inf)  # from now on announced Paths there are waited for
        self.subscriber = rospy.Subscriber(topic, Path, self._on_path, queue_size=1)

    def _on_path(self, msg: Path) -> None:
        with self._wake:
            self.msg = msg
            self.count += 1
            self.arrived_s = rospy.get_time()
            self._wake.notify_all()
        if self._lockstep is not None:
            self._lockstep.received(self.topic, msg.header.stamp.to_sec())

    def new_for_tick(self, used: int, tick_s: float, defer_same_step: bool) -> bool:
        """(``wake`` held) Whether a loop that used Path number ``used`` takes the newest at its tick at ROS time
        ``tick_s`` [s]. ``defer_same_step`` (lockstep): only a Path that arrived before the tick's simulated time and
        is stamped before it -- one sent at the same step may arrive before or after the tick, so it waits for the
        next tick either way. The stamp decides where the arrival time cannot: this node's clock may still show the
        step before when a Path sent at the tick's step comes in (the Path and the clock come from two processes)."""
        return self.msg is not None and takes_path(
            self.count, used, arrived_s=self.arrived_s, stamp_s=self.msg.header.stamp.to_sec(), tick_s=tick_s,
            defer_same_step=defer_same_step)

    def close(self) -> None:
        self.subscriber.unregister()
        if self._lockstep is not None:
            self._lockstep.received(self.topic, math.inf)

    def no_path_reason(self, timeout_s: float) -> str:
        publishers = self.subscriber.get_num_connections()
        return (f"no Path on {self.topic} within {timeout_s:.1f} s "
                f"({publishers} publisher{'' if publishers == 1 else 's'} connected)")


class TopicPaths:
    """Owns the current :class:`TopicPath`; ``wake`` is notified on every new Path (and by cancels). ``lockstep``:
    the node's participant that reports the Paths taken in (see the module docstring)."""

    def __init__(self, wake: threading.Condition, clock: RosClock, lockstep: Optional[LockstepParticipant] = None,
                 ) -> None:
        self._wake = wake
        self._clock = clock
        self._lockstep = lockstep if lockstep is not None and lockstep.enabled else None
        self.current: Optional[TopicPath] = None

    def subscribe(self, topic: str) -> TopicPath:
        resolved = rospy.resolve_name(topic)
        if self.current is None or self.current.topic != resolved:
            if self.current is not None:
                self.current.close()
            self.current = TopicPath(resolved, self._wake, self._lockstep)
        return self.current

    def wait_first(
        self,
        source: TopicPath,
        timeout_s: float,
        cancelled: threading.Event,
        newer_than: Optional[rospy.Time] = None,
        grace_s: float = STALE_GRACE_S,
    ) -> bool:
        """True once ``source`` has a Path; False after ``timeout_s`` [s] or when ``cancelled`` is set
        (whoever sets it must notify ``wake``). With ``newer_than`` (the goal's start), a Path stamped
        before it is used only when no newer Path arrives within ``grace_s`` [s]."""
        deadline_s = self._clock.now() + timeout_s
        with self._wake:
            while source.msg is None and not cancelled.is_set():
                now_s = self._clock.now()
                if now_s >= deadline_s:
                    return False
                self._wake.wait(self._clock.wall_wait_s(deadline_s, now_s))
            if newer_than is not None and source.msg is not None and is_older(source.msg, newer_than):
                count = source.count
                fresh_by_s = min(deadline_s, self._clock.now() + grace_s)
                while source.count == count and not cancelled.is_set():
                    now_s = self._clock.now()
                    if now_s >= fresh_by_s:
                        break
                    self._wake.wait(self._clock.wall_wait_s(fresh_by_s, now_s))
        return source.msg is not None and not cancelled.is_set()


def takes_path(count: int, used: int, *, arrived_s: float, stamp_s: float, tick_s: float,
               defer_same_step: bool) -> bool:
    """Whether a loop that used Path number ``used`` takes Path number ``count`` (arrived at ROS time ``arrived_s``,
    stamped ``stamp_s`` [s]) at its tick at ``tick_s`` [s] (see :meth:`TopicPath.new_for_tick`)."""
    return count != used and not (defer_same_step and (arrived_s >= tick_s or not stamped_before(stamp_s, tick_s)))


def fresh_from(goal_newer_than: rospy.Time) -> rospy.Time:
    """The time from which a Path counts as this goal's: the goal's ``newer_than`` when its client set one (it
    saw a fresh Path before sending: no need to wait for another), else now (the goal's start)."""
    return goal_newer_than if not goal_newer_than.is_zero() else rospy.Time.now()


def is_older(msg: Path, time_point: rospy.Time) -> bool:
    """True for a Path stamped (non-zero stamp) before ``time_point``."""
    stamp = msg.header.stamp
    return bool(stamp != rospy.Time(0) and stamp < time_point)
