"""The newest nav_msgs/Path on a topic named in a FollowTopic goal, with a bounded wait for the first one.

Shared by ``follow_topic_server`` and ``pure_pursuit_topic``. The name in the goal is used exactly as
given (a relative name resolves in the node's namespace, as every ROS name does); the subscription is
kept while consecutive goals name the same topic, so a latched or frequent topic answers at once.
"""

from __future__ import annotations

import threading
import time
from typing import Optional

import rospy
from nav_msgs.msg import Path


class TopicPath:
    """Subscription to one topic: the newest Path and how many have arrived."""

    def __init__(self, topic: str, wake: threading.Condition) -> None:
        self.topic = topic
        self._wake = wake
        self.msg: Optional[Path] = None
        self.count = 0
        self.subscriber = rospy.Subscriber(topic, Path, self._on_path, queue_size=1)

    def _on_path(self, msg: Path) -> None:
        with self._wake:
            self.msg = msg
            self.count += 1
            self._wake.notify_all()

    def close(self) -> None:
        self.subscriber.unregister()

    def no_path_reason(self, timeout_s: float) -> str:
        publishers = self.subscriber.get_num_connections()
        return (f"no Path on {self.topic} within {timeout_s:.1f} s "
                f"({publishers} publisher{'' if publishers == 1 else 's'} connected)")


class TopicPaths:
    """Owns the current :class:`TopicPath`; ``wake`` is notified on every new Path (and by cancels)."""

    def __init__(self, wake: threading.Condition) -> None:
        self._wake = wake
        self.current: Optional[TopicPath] = None

    def subscribe(self, topic: str) -> TopicPath:
        resolved = rospy.resolve_name(topic)
        if self.current is None or self.current.topic != resolved:
            if self.current is not None:
                self.current.close()
            self.current = TopicPath(resolved, self._wake)
        return self.current

    def wait_first(self, source: TopicPath, timeout_s: float, cancelled: threading.Event) -> bool:
        """True once ``source`` has a Path; False after ``timeout_s`` [s] or when ``cancelled`` is set
        (whoever sets it must notify ``wake``)."""
        deadline = time.monotonic() + timeout_s
        with self._wake:
            while source.msg is None and not cancelled.is_set():
                left = deadline - time.monotonic()
                if left <= 0.0:
                    return False
                self._wake.wait(left)
        return source.msg is not None and not cancelled.is_set()
