"""The operator side's heartbeat: the behavior runner publishes it, the robot's motion nodes listen for it.

``HEARTBEAT_TOPIC`` (std_msgs/Header, a relative name: the runner's namespace, which is the robot's) carries a
message every ``HEARTBEAT_PERIOD_S`` of wall time (stamp: the sender's ROS time; seq: a counter; frame_id: the
sender's node name). twist_relay and the controllers take ``~heartbeat_timeout`` [s of wall time] (0: off, the
default): with it set, no heartbeat for that long stops the robot (see :mod:`flex_nav.nav.control.operator_link`).
"""

from __future__ import annotations

import threading
import time
from typing import Callable, Optional

import rospy
from std_msgs.msg import Header

from flex_nav.nav.control.operator_link import OperatorLink

HEARTBEAT_TOPIC = "operator_heartbeat"
HEARTBEAT_PERIOD_S = 0.1  # [s] wall time between two heartbeats (a timeout of 0.5 s tolerates four lost ones)


class HeartbeatPublisher:
    """Publishes the heartbeat from a thread of its own, paced on wall time (ROS time may stop with /clock)."""

    def __init__(self, topic: str = HEARTBEAT_TOPIC, period_s: float = HEARTBEAT_PERIOD_S) -> None:
        self.publisher = rospy.Publisher(topic, Header, queue_size=1, tcp_nodelay=True)
        self._period_s = period_s
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._beat, name="operator heartbeat", daemon=True)
        self._thread.start()

    def _beat(self) -> None:
        msg = Header(frame_id=rospy.get_name())
        while not self._stop.wait(self._period_s) and not rospy.is_shutdown():
            msg.seq += 1
            msg.stamp = rospy.Time.now()
            try:
                self.publisher.publish(msg)
            except rospy.ROSException:  # the node is shutting down
                return

    def close(self) -> None:
        self._stop.set()
        self._thread.join(2.0 * self._period_s + 1.0)
        self.publisher.unregister()


class HeartbeatListener:
    """Feeds an :class:`OperatorLink` from the heartbeat topic; subscribes only when the watch is on."""

    def __init__(self, timeout_s: float, topic: str = HEARTBEAT_TOPIC,
                 on_heard: Optional[Callable[[], None]] = None) -> None:
        self.link = OperatorLink(timeout_s)
        self.topic = rospy.resolve_name(topic)
        self._lock = threading.Lock()
        self._on_heard = on_heard
        self.subscriber = (rospy.Subscriber(topic, Header, self._on_heartbeat, queue_size=1, tcp_nodelay=True)
                           if self.link.enabled else None)

    def _on_heartbeat(self, _msg: Header) -> None:
        with self._lock:
            self.link.heard(time.monotonic())
        if self._on_heard is not None:
            self._on_heard()

    def lost(self) -> bool:
        with self._lock:
            return self.link.lost(time.monotonic())

    def why_lost(self) -> str:
        with self._lock:
            return self.link.why_lost(time.monotonic(), self.topic)
