#!/usr/bin/env python3
"""rostest node (clock_faults.test): faults of the clock and of the operator link stop the robot.

This node is the simulator (it publishes /clock, and can stop it or rewind it as a crashed, paused or restarted
simulator does), the robot (odometry, tf map -> odom -> base_footprint, an empty scan, all stamped with its
clock), the local planner (a Path on ``plan``) and the operator side (the heartbeat). Everything it does is paced
on wall time: its own ROS time stands still with the clock it stops.
"""

import threading
import time
import unittest

import actionlib
import rospy
import rostest
import tf2_ros
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped, Twist, TwistStamped
from message_log import MessageLog
from nav_msgs.msg import Odometry, Path
from robot_at_rest import BASE_FRAME, empty_scan, identity_tf, odom_at_rest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Header, String

from flex_nav.msg import FollowTopicAction, FollowTopicGoal
from flex_nav.ros.heartbeat import HEARTBEAT_TOPIC

STEP_S = 0.01  # [s] wall period of the clock; it advances by the same amount (real-time factor 1)
SENSOR_PERIOD_S = 0.05  # [s] wall period of odometry, tf, scan and the plan
HEARTBEAT_PERIOD_S = 0.1  # [s] wall
TIMEOUT_S = 0.5  # [s] the relay's ~timeout and ~heartbeat_timeout, the controller's sensor_timeout (clock_faults.test)
STOP_BOUND_S = TIMEOUT_S + 1.0  # [s] wall: generous bound on the stop (the figure printed is what counts)
WAIT_S = 20.0  # [s] wall bound on the nodes coming up


class Simulator:
    """/clock, the robot's sensors and tf, the plan, and the operator's heartbeat; each can be stopped."""

    def __init__(self):
        self.lock = threading.Lock()
        self.clock_s = 100.0  # [s] simulated time
        self.clock_on = threading.Event()
        self.clock_on.set()
        self.heartbeat_on = threading.Event()
        self.heartbeat_on.set()
        self.clock_pub = rospy.Publisher("/clock", Clock, queue_size=1)
        self.odom_pub = rospy.Publisher("odom", Odometry, queue_size=1)
        self.scan_pub = rospy.Publisher("scan", LaserScan, queue_size=1)
        self.plan_pub = rospy.Publisher("plan", Path, queue_size=1)
        self.heartbeat_pub = rospy.Publisher(HEARTBEAT_TOPIC, Header, queue_size=1)
        self.tf = tf2_ros.TransformBroadcaster()
        for target in (self.run_clock, self.run_sensors, self.run_heartbeat):
            threading.Thread(target=target, daemon=True).start()

    def now(self):
        with self.lock:
            return rospy.Time.from_sec(self.clock_s)

    def rewind(self, by_s):
        with self.lock:
            self.clock_s -= by_s

    def run_clock(self):
        while not rospy.is_shutdown():
            time.sleep(STEP_S)
            if self.clock_on.is_set():
                with self.lock:
                    self.clock_s += STEP_S
                    stamp = rospy.Time.from_sec(self.clock_s)
                try:
                    self.clock_pub.publish(Clock(clock=stamp))
                except rospy.ROSException:  # the node is shutting down
                    return

    def run_sensors(self):
        while not rospy.is_shutdown():
            time.sleep(SENSOR_PERIOD_S)
            if not self.clock_on.is_set():
                continue  # a stopped simulator sends nothing
            stamp = self.now()
            self.tf.sendTransform([identity_tf("map", "odom", stamp), identity_tf("odom", BASE_FRAME, stamp)])
            self.odom_pub.publish(odom_at_rest(stamp))
            self.scan_pub.publish(empty_scan(stamp))
            self.plan_pub.publish(straight_path(stamp))

    def run_heartbeat(self):
        beat = Header(frame_id="test_clock_faults")
        while not rospy.is_shutdown():
            time.sleep(HEARTBEAT_PERIOD_S)
            if self.heartbeat_on.is_set():
                beat.seq += 1
                self.heartbeat_pub.publish(beat)


def straight_path(stamp, length=5.0):
    path = Path()
    path.header.frame_id = "map"
    path.header.stamp = stamp
    for k in range(int(length / 0.1) + 1):
        pose = PoseStamped()
        pose.header.frame_id = "map"
        pose.pose.position.x = 0.1 * k
        pose.pose.orientation.w = 1.0
        path.poses.append(pose)
    return path


class Recorder(MessageLog):
    """Every message on a command topic as (wall time [s] it arrived, twist); waits on the wall clock (the test
    fakes ROS time)."""

    def __init__(self, topic, msg_type):
        super().__init__(topic, msg_type, queue_size=100, poll_s=0.05)

    def record(self, msg):
        return time.monotonic(), (msg.twist if isinstance(msg, TwistStamped) else msg)

    def now_s(self):
        return time.monotonic()

    def wait_for(self, condition, after=0, timeout_s=None):
        """(wall time, twist) of the first message from ``after`` on whose twist meets ``condition``, or None."""
        return super().wait_for(lambda entry: condition(entry[1]), after, timeout_s)


def moving(twist):
    return twist.linear.x != 0.0 or twist.angular.z != 0.0


def is_zero(twist):
    return not moving(twist)


class TestClockFaults(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_clock_faults")
        cls.sim = Simulator()
        cls.relayed = Recorder("cmd_vel", Twist)
        cls.commanded = Recorder("cmd_vel_stamped", TwistStamped)
        cls.controller = actionlib.SimpleActionClient("pp_topic", FollowTopicAction)
        cls.follower = actionlib.SimpleActionClient("follow_topic_server", FollowTopicAction)
        deadline = time.monotonic() + WAIT_S
        for client in (cls.controller, cls.follower):
            while not client.wait_for_server(rospy.Duration(0.1)):  # sim time runs: a Duration is fine here
                assert time.monotonic() < deadline, "action servers did not come up"

    def setUp(self):
        self.sim.clock_on.set()
        self.sim.heartbeat_on.set()
        time.sleep(1.0)  # the relay and the controller see time move and the heartbeat again

    def tearDown(self):
        self.controller.cancel_all_goals()
        self.follower.cancel_all_goals()
        time.sleep(0.3)

    def drive(self):
        """Send a FollowTopic goal on ``plan`` and wait until the relay forwards motion; the goal's handle."""
        mark = self.relayed.count()
        self.controller.send_goal(FollowTopicGoal(topic=String(data="plan")))
        self.assertIsNotNone(self.relayed.wait_for(moving, mark, 5.0), "the robot never got a moving command")

    def test_a_stopped_clock_stops_the_robot_until_it_moves_again(self):
        self.drive()
        mark_relay, mark_cmd = self.relayed.count(), self.commanded.count()
        stopped_at = time.monotonic()
        self.sim.clock_on.clear()  # the simulator freezes: no /clock, no sensors
        zero = self.relayed.wait_for(is_zero, mark_relay, STOP_BOUND_S)
        self.assertIsNotNone(zero, "twist_relay sent no zero Twist after the clock stopped")
        print(f"[measured] clock stopped -> zero Twist from twist_relay after {zero[0] - stopped_at:.3f} s wall "
              f"(~timeout {TIMEOUT_S} s)", flush=True)
        time.sleep(2.0)  # an outage of several timeouts
        relayed = self.relayed.since(mark_relay)
        after_zero = [entry for entry in relayed if entry[0] > zero[0]]
        self.assertFalse(any(moving(t) for _, t in after_zero),
                         f"twist_relay forwarded {sum(moving(t) for _, t in after_zero)} moving commands while "
                         "the clock stood still")
        commanded = self.commanded.since(mark_cmd)
        late = [t for w, t in commanded if w > stopped_at + STOP_BOUND_S]
        self.assertFalse(any(moving(t) for t in late), "the controller kept commanding motion on a stopped clock")
        self.assertTrue(any(is_zero(t) for _, t in commanded), "the controller sent no zero twist")
        self.assertEqual(self.controller.get_state(), GoalStatus.ACTIVE, "a paused clock must not end the goal")
        mark = self.relayed.count()
        self.sim.clock_on.set()
        self.assertIsNotNone(self.relayed.wait_for(moving, mark, 5.0), "the goal did not go on when time moved")

    def test_a_clock_that_jumps_back_aborts_the_goal_and_stops_the_robot(self):
        self.drive()
        self.follower.send_goal(FollowTopicGoal(topic=String(data="plan")))
        time.sleep(0.5)
        mark = self.relayed.count()
        jumped_at = time.monotonic()
        self.sim.rewind(50.0)  # a restarted simulation
        self.assertTrue(self.wait_done(self.controller), "the controller kept the goal of the old timeline")
        self.assertEqual(self.controller.get_state(), GoalStatus.ABORTED)
        self.assertIn("moved backwards", self.controller.get_result().message)
        self.assertTrue(self.wait_done(self.follower), "the follow server kept the goal of the old timeline")
        self.assertEqual(self.follower.get_state(), GoalStatus.ABORTED)
        self.assertIn("moved backwards", self.follower.get_result().message)
        zero = self.relayed.wait_for(is_zero, mark, STOP_BOUND_S)
        self.assertIsNotNone(zero, "no zero Twist after the jump")
        print(f"[measured] clock jumped back -> zero Twist from twist_relay after {zero[0] - jumped_at:.3f} s wall",
              flush=True)
        time.sleep(1.0)
        self.assertFalse(any(moving(t) for w, t in self.relayed.since(mark) if w > zero[0]),
                         "a command of the old goal went out after the jump")
        # the servers take the new timeline's goals (actionlib's SimpleActionServer cancelled every goal stamped
        # before the old timeline's last one)
        self.drive()

    def test_a_clock_that_jumps_back_between_goals_leaves_the_next_goal_alone(self):
        # the controller watches the clock across goals: the jump it finds when the next goal starts happened before
        # that goal, which belongs to the new timeline and must drive (it was aborted 'moved backwards' at first)
        self.drive()
        self.controller.cancel_all_goals()
        self.assertTrue(self.wait_done(self.controller))
        time.sleep(0.5)
        self.sim.rewind(50.0)  # restarted while no goal runs
        time.sleep(1.0)
        self.drive()
        self.assertEqual(self.controller.get_state(), GoalStatus.ACTIVE)

    def wait_done(self, client, timeout_s=5.0):
        """True once the goal has ended and its result arrived (the status topic may tell the end before the
        result topic brings the result: get_result() is None until then), False after ``timeout_s`` [s]."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if client.get_state() not in (GoalStatus.PENDING, GoalStatus.ACTIVE) and client.get_result() is not None:
                return True
            time.sleep(0.02)
        return False

    def test_a_lost_operator_heartbeat_stops_the_robot_and_aborts_the_goal(self):
        self.drive()
        mark = self.relayed.count()
        lost_at = time.monotonic()
        self.sim.heartbeat_on.clear()  # the link to the operator's computer drops
        zero = self.relayed.wait_for(is_zero, mark, STOP_BOUND_S)
        self.assertIsNotNone(zero, "twist_relay sent no zero Twist after the heartbeat stopped")
        print(f"[measured] heartbeat lost -> zero Twist from twist_relay after {zero[0] - lost_at:.3f} s wall "
              f"(~heartbeat_timeout {TIMEOUT_S} s, last heartbeat up to {HEARTBEAT_PERIOD_S} s before)", flush=True)
        self.assertTrue(self.wait_done(self.controller), "the controller kept its goal without the operator")
        self.assertEqual(self.controller.get_state(), GoalStatus.ABORTED)
        self.assertIn("link to the operator lost", self.controller.get_result().message)
        time.sleep(1.0)
        self.assertFalse(any(moving(t) for w, t in self.relayed.since(mark) if w > zero[0]))
        self.sim.heartbeat_on.set()  # the link is back: a new goal drives
        time.sleep(0.5)
        self.drive()

    def test_illegal_topic_names_are_refused_at_once(self):
        for name in ("", "..", "a b", "plan/"):
            for client in (self.controller, self.follower):
                started = time.monotonic()
                client.send_goal(FollowTopicGoal(topic=String(data=name)))
                self.assertTrue(self.wait_done(client, 1.5), f"goal naming {name!r} not refused at once")
                self.assertEqual(client.get_state(), GoalStatus.ABORTED, name)
                self.assertIn("bad topic", client.get_result().message, name)
                self.assertLess(time.monotonic() - started, 1.5)


if __name__ == "__main__":
    rostest.rosrun("flex_nav", "clock_faults", TestClockFaults)
