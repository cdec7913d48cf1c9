#!/usr/bin/env python3
"""rostest node: bumper_relay turns presses (generic zone state, Create style) into contact points, per namespace."""

import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import PointStamped
from readiness import connected

from flex_nav.msg import BumperState, CreateBumper
from flex_nav.ros.node import init_node

WAIT_S = 10.0  # [s]


class Collector:
    def __init__(self, topic):
        self.msgs = []
        self.lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, PointStamped, self._on)

    def _on(self, msg):
        with self.lock:
            self.msgs.append(msg)

    def wait(self, count):
        deadline = time.monotonic() + WAIT_S
        while time.monotonic() < deadline:
            with self.lock:
                if len(self.msgs) >= count:
                    return list(self.msgs)
            time.sleep(0.02)
        with self.lock:
            return list(self.msgs)


class TestBumperRelay(unittest.TestCase):
    def test_zone_state_press_gives_one_contact_ahead(self):
        hits = Collector("/robot1/bumper_hits")
        other = Collector("/robot2/bumper_hits")
        pub = rospy.Publisher("/robot1/bumper_state", BumperState, queue_size=10)
        connected(pub, hits.sub, other.sub, timeout_s=WAIT_S)
        for pressed in ([False, True, False], [False, True, False], [False, False, False]):
            pub.publish(BumperState(zones=["left", "center", "right"], pressed=pressed))
            time.sleep(0.05)
        msgs = hits.wait(1)
        time.sleep(0.5)
        with hits.lock:
            count = len(hits.msgs)
        self.assertEqual(count, 5, "one press of the 60 deg centre zone: 5 points 15 deg apart; held: no more")
        self.assertEqual(msgs[0].header.frame_id, "robot1/base_footprint")
        self.assertTrue(all(m.point.x > 0.15 for m in hits.msgs))
        self.assertAlmostEqual(sum(m.point.y for m in hits.msgs), 0.0, places=6)
        self.assertEqual(other.msgs, [], "robot2 must not see robot1's contacts")

    def test_create_left_press(self):
        hits = Collector("/robot2/bumper_hits")
        pub = rospy.Publisher("/robot2/bumper", CreateBumper, queue_size=10)
        connected(pub, hits.sub, timeout_s=WAIT_S)
        pub.publish(CreateBumper(is_left_pressed=True, is_right_pressed=False))
        hits.wait(1)
        time.sleep(0.5)  # the press's other points (summing the first alone could give its sign; they would also
        with hits.lock:  # reach the next test's robot2 collector)
            msgs = list(hits.msgs)
        self.assertGreaterEqual(len(msgs), 1)
        self.assertGreater(sum(m.point.y for m in msgs), 0.0, "the left zone lies mostly on the left")
        self.assertEqual(msgs[0].header.frame_id, "robot2/base_footprint")


if __name__ == "__main__":
    init_node("test_bumper_relay", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_bumper_relay", TestBumperRelay, sys.argv)
