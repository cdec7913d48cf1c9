"""A behavior's subscription in a lockstep simulation takes a message in only once ROS time has passed its stamp,
and never lets an older message replace a newer one (``flex_nav.ros.proxies.Subscription``; rospy faked)."""

from __future__ import annotations

from typing import Any, List

import genpy
import pytest
import rospy
from sensor_msgs.msg import LaserScan

from flex_nav.ros import proxies


class FakeSubscriber:
    """Stands in for rospy.Subscriber: keeps the callback, connects nowhere."""

    def __init__(self, topic: str, msg_type: type, callback: Any, queue_size: int = 1) -> None:
        self.callback = callback

    def unregister(self) -> None:
        pass


@pytest.fixture
def ros_time(monkeypatch: pytest.MonkeyPatch) -> List[float]:
    """ROS time [s] as the test sets it (``ros_time[0]``)."""
    now = [0.0]
    monkeypatch.setattr(proxies.rospy, "Subscriber", FakeSubscriber)
    monkeypatch.setattr(proxies.rospy, "get_time", lambda: now[0])
    return now


def scan(stamp_s: float) -> LaserScan:
    msg = LaserScan()
    msg.header.stamp = rospy.Time.from_sec(stamp_s)
    return msg


def arrive(sub: proxies.Subscription[Any], msg: Any) -> None:
    sub._subscriber.callback(msg)  # what rospy's thread would call


def stamp_of(msg: Any) -> float:
    return round(float(msg.header.stamp.to_sec()), 4)


def test_a_message_stamped_now_is_seen_once_time_has_passed_it(ros_time: List[float]) -> None:
    sub: proxies.Subscription[LaserScan] = proxies.Subscription("scan", LaserScan, lockstep=True)
    ros_time[0] = 38.0
    arrive(sub, scan(37.9))
    arrive(sub, scan(38.0))
    assert stamp_of(sub.last()) == 37.9
    ros_time[0] = 38.05
    assert stamp_of(sub.last()) == 38.0


def test_a_message_that_waited_does_not_replace_a_newer_one(ros_time: List[float]) -> None:
    """The scan of 38.0 s came while the simulation stood at 38.0 s; the scans after it came once time had passed
    their stamps. Read only at 39.05 s, the newest is the scan of 38.9 s (it was the one of 38.0 s)."""
    sub: proxies.Subscription[LaserScan] = proxies.Subscription("scan", LaserScan, lockstep=True)
    ros_time[0] = 38.0
    arrive(sub, scan(38.0))
    for stamp_s in (38.18, 38.37, 38.55, 38.73, 38.91):
        ros_time[0] = stamp_s + 0.02
        arrive(sub, scan(stamp_s))
    ros_time[0] = 39.05
    assert stamp_of(sub.last()) == 38.91


def test_a_buffered_subscription_hands_out_in_stamp_order(ros_time: List[float]) -> None:
    sub: proxies.Subscription[LaserScan] = proxies.Subscription("goal", LaserScan, buffer_size=5, lockstep=True)
    ros_time[0] = 20.0
    arrive(sub, scan(20.0))
    ros_time[0] = 20.1
    arrive(sub, scan(20.05))
    assert [stamp_of(sub.pop_buffered()), stamp_of(sub.pop_buffered())] == [20.0, 20.05]
    assert sub.pop_buffered() is None


def test_without_lockstep_every_message_is_taken_as_it_comes(ros_time: List[float]) -> None:
    sub: proxies.Subscription[LaserScan] = proxies.Subscription("scan", LaserScan)
    ros_time[0] = 38.0
    arrive(sub, scan(38.0))
    assert stamp_of(sub.last()) == 38.0


def test_a_message_stamped_by_genpy_from_the_time_now_counts_as_stamped_now(ros_time: List[float]) -> None:
    """A state stamps with genpy.Time.from_sec, which truncates: 20.2 s becomes 20.199999999 s. A plan a behavior
    published at its tick at 20.2 s was taken in at once (before the stamp), so another state of the same tick saw
    it or not by a wall-time race (S4 seed 1 move_base_like: its FollowTopic goal went at 20.2 s or 20.3 s)."""
    sub: proxies.Subscription[LaserScan] = proxies.Subscription("plan", LaserScan, lockstep=True)
    ros_time[0] = 20.2
    msg = LaserScan()
    msg.header.stamp = genpy.Time.from_sec(20.2)
    assert msg.header.stamp.to_sec() < 20.2  # the truncation this is about
    arrive(sub, msg)
    assert sub.last() is None
    ros_time[0] = 20.2 + 1.0 / 240.0  # the next physics step
    assert stamp_of(sub.last()) == 20.2
