#!/usr/bin/env python3
"""rostest node for localizer.test: the localizer's ROS interface on the simulator without its oracle.

The tests run in the order of their names (unittest sorts them): localize from the simulator's initialpose,
follow a turn, ignore bad initial poses, drop bad beams and unknown scan frames (through the probe localizer),
then kidnap the robot: lost, no map -> odom, global localization finds it again; last, global localization on
request (the global_localization service) with the robot standing.
"""

import math
import sys
import threading
import time
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import PoseArray, PoseWithCovarianceStamped, Twist, Vector3
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.ros.node import init_node
from flex_nav.srv import Teleport

WAIT_S = 60.0  # [s] wall-time bound on every wait


class Latest:
    """Keeps the messages of one topic, with the wall time [s, monotonic] each arrived."""

    def __init__(self, topic, msg_type):
        self.messages = []
        self.arrived = []
        self.lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, msg_type, self._on, queue_size=200)

    def _on(self, msg):
        with self.lock:
            self.messages.append(msg)
            self.arrived.append(time.monotonic())

    def wait(self, predicate=None, what="", after=0, timeout_s=WAIT_S):
        """The newest message after the first ``after`` that satisfies ``predicate``."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            with self.lock:
                found = [m for m in self.messages[after:] if predicate is None or predicate(m)]
            if found:
                return found[-1]
            time.sleep(0.05)
        with self.lock:
            last = self.messages[-1] if self.messages else None
        raise AssertionError(f"no {what or self.sub.name} within {timeout_s} s (last: {last})")

    def first_arrival(self, predicate, after=0):
        """Wall time the first message after the first ``after`` satisfying ``predicate`` arrived, or None."""
        with self.lock:
            return next((t for m, t in zip(self.messages[after:], self.arrived[after:]) if predicate(m)), None)

    def count(self):
        with self.lock:
            return len(self.messages)


def initial_pose(frame, x, w):
    """An initialpose message in ``frame`` at (x, 0) with quaternion (0, 0, 0, w)."""
    msg = PoseWithCovarianceStamped()
    msg.header.frame_id = frame
    msg.pose.pose.position.x = x
    msg.pose.pose.orientation.w = w
    return msg


def planar(pose):
    q = pose.orientation
    return pose.position.x, pose.position.y, yaw_of_quaternion(q.x, q.y, q.z, q.w)


class TestLocalizer(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        init_node("test_localizer")
        cls.truth = Latest("/robot1/ground_truth", Odometry)
        cls.estimate = Latest("/robot1/amcl_pose", PoseWithCovarianceStamped)
        cls.status = Latest("/robot1/localizer/status", String)
        cls.probe_estimate = Latest("/probe/amcl_pose", PoseWithCovarianceStamped)
        cls.rosout = Latest("/rosout_agg", Log)
        cls.scans = Latest("/robot1/scan", LaserScan)
        cls.cloud = Latest("/robot1/particlecloud", PoseArray)
        cls.cmd = rospy.Publisher("/robot1/cmd_vel", Twist, queue_size=1)
        cls.initial = rospy.Publisher("/robot1/initialpose", PoseWithCovarianceStamped, queue_size=1)
        cls.probe_initial = rospy.Publisher("/probe/initialpose", PoseWithCovarianceStamped, queue_size=1,
                                            latch=True)
        cls.probe_scan = rospy.Publisher("/probe/scan", LaserScan, queue_size=5)
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)

    def error_now(self):
        """(position [m], heading [rad]) error of the newest estimate against the ground truth at its stamp."""
        estimate = self.estimate.wait(what="amcl_pose")
        stamp = estimate.header.stamp
        # the ground truth at (or after) the estimate's stamp: the localizer can be localized before this node's
        # ground_truth subscription has its first message
        self.truth.wait(lambda m: m.header.stamp >= stamp, what="ground_truth at the estimate's stamp")
        with self.truth.lock:
            truth = min(self.truth.messages, key=lambda m: abs((m.header.stamp - stamp).to_sec()))
        ex, ey, eyaw = planar(estimate.pose.pose)
        tx, ty, tyaw = planar(truth.pose.pose)
        return math.hypot(ex - tx, ey - ty), abs(math.atan2(math.sin(eyaw - tyaw), math.cos(eyaw - tyaw)))

    def logged(self, text, after):
        return self.rosout.wait(lambda m: text in m.msg, what=f"a log line with {text!r}", after=after)


    def drive(self, v, w, duration_s):
        end = rospy.get_time() + duration_s
        while rospy.get_time() < end and not rospy.is_shutdown():
            self.cmd.publish(Twist(linear=Vector3(x=v), angular=Vector3(z=w)))
            time.sleep(0.05)
        self.cmd.publish(Twist())

    def map_to_odom_age_s(self):
        tf = self.tf_buffer.lookup_transform("map", "robot1/odom", rospy.Time(0), rospy.Duration(2.0))
        return (rospy.Time.now() - tf.header.stamp).to_sec()

    def test_1_localizes_from_the_simulators_initial_pose(self):
        self.status.wait(lambda m: m.data.startswith("localized"), what="status 'localized'")
        position, heading = self.error_now()
        self.assertLess(position, 0.10)
        self.assertLess(heading, math.radians(5.0))
        # map -> odom is published, post-dated (transform_tolerance 0.1 s) and fresh
        self.assertLess(self.map_to_odom_age_s(), 0.5)
        tf = self.tf_buffer.lookup_transform("map", "robot1/base_footprint", rospy.Time(0), rospy.Duration(2.0))
        truth = planar(self.truth.wait().pose.pose)
        self.assertLess(math.hypot(tf.transform.translation.x - truth[0], tf.transform.translation.y - truth[1]), 0.1)
        # the covariance comes from the particles: positive on the diagonal, small once localized
        covariance = np.array(self.estimate.wait().pose.covariance).reshape(6, 6)
        self.assertTrue(0.0 < covariance[0, 0] < 0.05 and 0.0 < covariance[5, 5] < 0.1, covariance.diagonal())

    def test_2_follows_a_turn_in_place(self):
        before = self.estimate.count()
        clouds = self.cloud.count()
        self.drive(0.0, 1.0, 4.0)
        self.estimate.wait(what="an estimate after the turn", after=before + 5)
        # the particles, published with every update once someone listens: in the map frame, at least min_particles
        cloud = self.cloud.wait(what="a particle cloud after the turn", after=clouds)
        self.assertEqual(cloud.header.frame_id, "map")
        self.assertGreaterEqual(len(cloud.poses), 500)
        truth = planar(self.truth.wait().pose.pose)
        xs = [p.position.x for p in cloud.poses]
        self.assertLess(abs(sum(xs) / len(xs) - truth[0]), 0.1)
        time.sleep(0.5)
        position, heading = self.error_now()
        self.assertLess(position, 0.05)
        self.assertLess(heading, math.radians(2.0))

    def test_3_bad_initial_poses_are_ignored(self):
        mark = self.rosout.count()
        status_before = self.status.wait().data
        self.initial.publish(initial_pose("robot1/odom", 5.0, 1.0))
        self.logged("initialpose ignored: header.frame_id 'robot1/odom' is not the global frame 'map'", mark)
        self.initial.publish(initial_pose("map", 5.0, 2.0))
        self.logged("is not normalised", mark)
        self.initial.publish(initial_pose("map", math.nan, 1.0))
        self.logged("is not finite", mark)
        time.sleep(1.0)
        self.assertEqual(self.status.wait().data.split(":")[0], status_before.split(":")[0])
        position, _ = self.error_now()
        self.assertLess(position, 0.10)

    def test_4_probe_drops_bad_beams_and_unknown_frames(self):
        truth = self.truth.wait().pose.pose
        initial = PoseWithCovarianceStamped()
        initial.header.frame_id = "map"
        initial.pose.pose = truth
        initial.pose.covariance[0] = initial.pose.covariance[7] = 0.01
        initial.pose.covariance[35] = 0.01
        self.probe_initial.publish(initial)
        mark = self.rosout.count()
        count = self.probe_estimate.count()
        deadline = time.monotonic() + WAIT_S
        dropped = "beams NaN, -inf or outside [0.02, 5.6] m: dropped"
        while self.rosout.first_arrival(lambda m: dropped in m.msg, mark) is None and time.monotonic() < deadline:
            scan = self.scans.wait()
            ranges = list(scan.ranges)
            for i in range(0, len(ranges) // 2):  # the first half of every scan is broken, four ways
                ranges[i] = (math.nan, -math.inf, -1.0, 1e6)[i % 4]
            scan.ranges = ranges
            self.probe_scan.publish(scan)
            time.sleep(0.2)
        line = self.logged("of 681 " + dropped, mark).msg
        self.assertEqual(int(line.split("scan: ")[1].split(" of ")[0]), 340, line)  # +inf ("no return") is not bad
        estimate = self.probe_estimate.wait(what="/probe/amcl_pose", after=count)
        ex, ey, _ = planar(estimate.pose.pose)
        tx, ty, _ = planar(self.truth.wait().pose.pose)
        self.assertLess(math.hypot(ex - tx, ey - ty), 0.10)
        scan = self.scans.wait()
        scan.header.frame_id = "nowhere"
        self.probe_scan.publish(scan)
        self.logged("scan ignored: its frame 'nowhere' cannot be placed in the base frame 'robot1/base_footprint'",
                    mark)

    def test_5_kidnapped_robot_is_lost_then_found(self):
        tf_seen = Latest("/tf", TFMessage)
        teleport = rospy.ServiceProxy("/sim/teleport", Teleport)
        teleport.wait_for_service(WAIT_S)
        nomotion = rospy.ServiceProxy("/robot1/request_nomotion_update", Empty)
        mark = self.status.count()
        answer = teleport(robot="robot1", x=4.0, y=1.9, yaw=math.pi / 2)
        self.assertTrue(answer.ok, answer.message)
        deadline = time.monotonic() + WAIT_S
        while self.status.first_arrival(lambda m: m.data.startswith("lost"), mark) is None:
            self.assertLess(time.monotonic(), deadline, f"never reported lost; status {self.status.wait().data}")
            nomotion()  # the robot stands: ask for the sensor updates that reveal the kidnapping
            time.sleep(0.15)
        lost_at = self.status.first_arrival(lambda m: m.data.startswith("lost"), mark)
        # global localization (started by the lost filter) with the robot standing: a sensor update every scan
        deadline = time.monotonic() + WAIT_S
        while self.status.first_arrival(lambda m: m.data.startswith("localized"), mark) is None:
            self.assertLess(time.monotonic(), deadline, f"not found again; status {self.status.wait().data}")
            time.sleep(0.2)
        found_at = self.status.first_arrival(lambda m: m.data.startswith("localized"), mark)
        self.assertGreater(found_at, lost_at)
        # no map -> odom while lost: the controllers' localization_timeout stops the robot. The status and /tf are
        # two connections: a transform sent just before "lost" or just after "localized" may overtake the status
        # by a few ms, hence the margin at both ends
        with tf_seen.lock:
            while_lost = [t for msg, t in zip(tf_seen.messages, tf_seen.arrived)
                          if lost_at + 0.05 < t < found_at - 0.05
                          and any(tf.child_frame_id == "robot1/odom" for tf in msg.transforms)]
        self.assertEqual(while_lost, [], "map -> robot1/odom published while lost")
        time.sleep(0.5)
        position, heading = self.error_now()
        self.assertLess(position, 0.10)
        self.assertLess(heading, math.radians(5.0))
        self.assertLess(self.map_to_odom_age_s(), 0.5)

    def test_6_global_localization_service(self):
        mark = self.status.count()
        rospy.ServiceProxy("/robot1/global_localization", Empty)()
        self.status.wait(lambda m: m.data.startswith("localizing: global"), what="status 'localizing: global ...'",
                         after=mark)
        deadline = time.monotonic() + WAIT_S
        while self.status.first_arrival(lambda m: m.data.startswith("localized"), mark) is None:
            self.assertLess(time.monotonic(), deadline, f"global localization did not converge; {self.status.wait()}")
            time.sleep(0.2)  # standing still: the node runs a sensor update on every scan
        time.sleep(0.5)
        position, heading = self.error_now()
        self.assertLess(position, 0.10)
        self.assertLess(heading, math.radians(5.0))


if __name__ == "__main__":
    rostest.rosrun("flex_nav", "localizer_check", TestLocalizer, sys.argv)
