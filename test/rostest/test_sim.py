#!/usr/bin/env python3
"""rostest node: two robots in one simulated world, through a real master (see sim.test)."""

import math
import sys
import threading
import time
import unittest

import rospy
import rostest
import tf2_ros
import yaml
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from readiness import connected
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan

from flex_nav.msg import BumperEvent, BumperState, CreateBumper, SimEvent
from flex_nav.ros.node import init_node

WAIT_S = 40.0  # [s] wall-time bound on every wait
WORLD_EVENT_T_S = 10.0  # [s] simulated time of open_room's one world event (late_walker starts walking)


class Latest:
    """Keeps every message of one topic."""

    def __init__(self, topic, msg_type):
        self.messages = []
        self._lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, msg_type, self._on, queue_size=100)

    def _on(self, msg):
        with self._lock:
            self.messages.append(msg)

    def wait(self, count=1, predicate=None, what=""):
        deadline = time.monotonic() + WAIT_S
        while time.monotonic() < deadline:
            with self._lock:
                found = [m for m in self.messages if predicate is None or predicate(m)]
            if len(found) >= count:
                return found
            time.sleep(0.02)
        raise AssertionError(f"no {what or self.sub.name} message within {WAIT_S} s (got {len(self.messages)} in all)")

    def last(self):
        return self.wait()[-1]


def distance(a, b):
    return math.hypot(a.pose.pose.position.x - b.pose.pose.position.x, a.pose.pose.position.y - b.pose.pose.position.y)


class TestSim(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        init_node("test_sim")
        cls.odom = {r: Latest(f"/{r}/odom", Odometry) for r in ("robot1", "robot2")}
        cls.truth = {r: Latest(f"/{r}/ground_truth", Odometry) for r in ("robot1", "robot2")}
        cls.scan = {r: Latest(f"/{r}/scan", LaserScan) for r in ("robot1", "robot2")}
        cls.events = {r: Latest(f"/{r}/sim_events", SimEvent) for r in ("robot1", "robot2")}
        cls.state = {r: Latest(f"/{r}/bumper_state", BumperState) for r in ("robot1", "robot2")}
        cls.kobuki_bumper = Latest("/robot1/events/bumper", BumperEvent)
        cls.create_bumper = Latest("/robot2/bumper", CreateBumper)
        cls.clock = Latest("/clock", Clock)
        cls.world_events = Latest("/sim_events", SimEvent)  # latched: the event is there however late we subscribe
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        cls.cmd = {r: rospy.Publisher(f"/{r}/cmd_vel", Twist, queue_size=1) for r in ("robot1", "robot2")}
        # bumpers and contacts publish only on change, unlatched: a press sent before a subscription is connected
        # is lost (a loaded CI once connected /robot1/events/bumper after the head-on press; the first press seen was
        # the left zone's, ~9 s later, when the robot had turned against the wall)
        logs = [*cls.events.values(), *cls.state.values(), cls.kobuki_bumper, cls.create_bumper]
        connected(*[log.sub for log in logs], *cls.cmd.values(), timeout_s=WAIT_S)

    def test_1_clock_advances(self):
        first = self.clock.wait(2)
        later = self.clock.wait(len(first) + 20)
        self.assertGreater(later[-1].clock, first[0].clock)

    def test_2_frames_and_topics_are_per_robot(self):
        for robot, beams in (("robot1", 681), ("robot2", 681)):
            odom = self.odom[robot].last()
            self.assertEqual((odom.header.frame_id, odom.child_frame_id), (f"{robot}/odom", f"{robot}/base_footprint"))
            for covariance in (odom.pose.covariance, odom.twist.covariance):  # planar: small, positive, diagonal
                diagonal = [covariance[7 * i] for i in range(6)]
                self.assertEqual(diagonal, [0.001, 0.001, 1e-6, 1e-6, 1e-6, 0.003])
                self.assertEqual(sum(abs(c) for c in covariance), sum(diagonal))
            truth = self.truth[robot].last()
            self.assertEqual((truth.header.frame_id, truth.child_frame_id), ("map", f"{robot}/base_footprint"))
            scan = self.scan[robot].last()
            self.assertEqual(scan.header.frame_id, f"{robot}/laser")
            self.assertEqual(len(scan.ranges), beams)
        topics = dict(rospy.get_published_topics())
        self.assertNotIn("/robot1/camera/rgb/image_raw", topics)  # ~camera false
        self.assertEqual(topics.get("/robot1/events/bumper"), "flex_nav/BumperEvent")  # kobuki driver style
        self.assertNotIn("/robot1/bumper", topics)
        self.assertEqual(topics.get("/robot2/bumper"), "flex_nav/CreateBumper")  # create driver style
        self.assertNotIn("/robot2/events/bumper", topics)
        for name in topics:  # nothing of one robot is published under the other's namespace
            if name.startswith("/robot1/"):
                self.assertNotIn("robot2", name)
        self.assertEqual(self.state["robot1"].last().zones, ["left", "center", "right"])
        self.assertEqual(self.state["robot2"].last().zones, ["left", "right"])
        bump = self.create_bumper.last()
        self.assertEqual(bump.header.frame_id, "robot2/base_footprint")

    def test_3_tf_trees_are_separate(self):
        deadline = time.monotonic() + WAIT_S
        while not self.tf_buffer.can_transform("map", "robot2/laser", rospy.Time(0)):
            self.assertLess(time.monotonic(), deadline, "no tf map -> robot2/laser")
            time.sleep(0.05)
        frames = yaml.safe_load(self.tf_buffer.all_frames_as_yaml())
        parents = {child: info["parent"] for child, info in frames.items()}
        for robot in ("robot1", "robot2"):
            self.assertEqual(parents[f"{robot}/base_footprint"], f"{robot}/odom")
            self.assertEqual(parents[f"{robot}/odom"], "map")
            self.assertEqual(parents[f"{robot}/laser"], f"{robot}/base_footprint")
        for child, parent in parents.items():  # no frame hangs below the other robot's frames
            if child.startswith("robot1/"):
                self.assertTrue(parent == "map" or parent.startswith("robot1/"), (child, parent))
            if child.startswith("robot2/"):
                self.assertTrue(parent == "map" or parent.startswith("robot2/"), (child, parent))
        # ground-truth localization: map -> base_footprint through tf equals the ground truth
        truth = self.truth["robot2"].last()
        tf = self.tf_buffer.lookup_transform("map", "robot2/base_footprint", truth.header.stamp, rospy.Duration(5.0))
        self.assertAlmostEqual(tf.transform.translation.x, truth.pose.pose.position.x, places=6)
        self.assertAlmostEqual(tf.transform.translation.y, truth.pose.pose.position.y, places=6)

    def test_4_command_moves_only_its_robot_into_the_wall(self):
        start1, start2 = self.truth["robot1"].last(), self.truth["robot2"].last()
        twist = Twist()
        twist.linear.x = 0.5
        deadline = time.monotonic() + WAIT_S
        bumped = []
        while not bumped:
            self.assertLess(time.monotonic(), deadline, "robot1 never hit the west wall")
            self.cmd["robot1"].publish(twist)
            time.sleep(0.05)
            bumped = [e for e in self.kobuki_bumper.messages if e.state == BumperEvent.PRESSED]
        contacts = [
            (e.kind, e.other, e.zones, round(e.position.x, 3), round(e.position.y, 3))
            for e in self.events["robot1"].messages
        ]
        self.assertEqual(  # head-on into the wall
            bumped[0].bumper,
            BumperEvent.CENTER,
            f"first press {bumped[0].bumper} (0 left, 1 center, 2 right); robot1's sim events {contacts}, "
            f"truth at the press {self.truth['robot1'].last().pose.pose}",
        )
        moved1 = distance(self.truth["robot1"].last(), start1)
        self.assertGreater(moved1, 0.6)
        self.assertLess(distance(self.truth["robot2"].last(), start2), 0.005)  # robot2 unaffected
        contact = self.events["robot1"].wait(predicate=lambda e: e.kind == SimEvent.CONTACT_BEGIN, what="contact")
        self.assertEqual((contact[0].other, contact[0].other_kind, contact[0].zones), ("room_west", "wall", ["center"]))
        self.assertFalse([e for e in self.events["robot2"].messages if e.kind == SimEvent.CONTACT_BEGIN])
        state = self.state["robot1"].wait(predicate=lambda s: any(s.pressed), what="pressed bumper_state")
        self.assertEqual(state[-1].pressed, [False, True, False])
        # odometry (noisy) agrees with the truth about the distance driven
        odom_moved = math.hypot(
            self.odom["robot1"].last().pose.pose.position.x, self.odom["robot1"].last().pose.pose.position.y
        )
        self.assertAlmostEqual(odom_moved, moved1, delta=0.05)

    def test_5_nan_command_ignored_and_reported_to_its_robot_only(self):
        twist = Twist()
        twist.linear.x = float("nan")
        self.cmd["robot2"].publish(twist)
        deadline = time.monotonic() + WAIT_S
        ignored = []
        while not ignored:
            self.assertLess(time.monotonic(), deadline, "no COMMAND event for the NaN command")
            self.cmd["robot2"].publish(twist)
            time.sleep(0.1)
            ignored = [
                e for e in self.events["robot2"].messages if e.kind == SimEvent.COMMAND and e.other_kind == "ignored"
            ]
        self.assertEqual(ignored[0].robot, "robot2")
        self.assertIn("not finite", ignored[0].detail)
        self.assertFalse([e for e in self.events["robot1"].messages if e.other_kind == "ignored"])

    def test_7_world_event_published(self):
        # open_room starts late_walker at t = 10 s (simulated)
        event = self.world_events.wait(predicate=lambda e: e.kind == SimEvent.WORLD_EVENT, what="world event")[0]
        self.assertEqual((event.other_kind, event.other), ("start_walking", "late_walker"))
        self.assertAlmostEqual(event.header.stamp.to_sec(), WORLD_EVENT_T_S, delta=0.01)


if __name__ == "__main__":
    rostest.rosrun("flex_nav", "sim_two_robots", TestSim, sys.argv)
