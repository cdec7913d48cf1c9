#!/usr/bin/env python3
"""rostest node: the pure pursuit controllers stop the robot (zero twist) on every failure path and on
cancel, and the goal ends with the reason (controller_safety.test). This node plays the robot and its
localizer: it publishes odometry, tf (map -> odom -> base_footprint) and an empty scan, and can stop any of
them or corrupt the odometry."""

import math
import os
import signal
import subprocess
import sys
import threading
import unittest
from pathlib import Path as FilePath

import actionlib
import rospy
import rostest
import tf2_ros
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped, TwistStamped
from message_log import MessageLog
from nav_msgs.msg import Odometry, Path
from robot_at_rest import BASE_FRAME, empty_scan, identity_tf, odom_at_rest
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String

from flex_nav.msg import (
    ClearCostmapAction,
    ClearCostmapGoal,
    FollowPathAction,
    FollowPathActionResult,
    FollowPathGoal,
    FollowPathResult,
    FollowTopicAction,
    FollowTopicActionResult,
    FollowTopicGoal,
)
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import ActionClientProxy

WAIT_S = 20.0  # [s] bound on servers appearing
RESULT_WAIT_S = 5.0  # [s] bound on each answer
PERIOD_S = 0.05  # [s] the controllers' control period (20 Hz, controller_safety.test)
SENSOR_TIMEOUT_S = 1.0  # [s] (controller_safety.test)
TOPIC_TIMEOUT_S = 2.0  # [s] pp_topic waits this long for the first Path (controller_safety.test)
CLIENT_TIMEOUT_S = 1.0  # [s] pp_path ends a goal whose client is gone this long (controller_safety.test)
FRESH_PASSES = 10  # the robot's 20 Hz passes over connected controllers before their sensors count as flowing:
# several of each message (each controller keeps the newest), as a goal needs odometry, scan and tf younger
# than SENSOR_TIMEOUT_S, and a scan of a broken test must be taken before its local costmap is cleared
# Real test durations: how long a test watches that nothing happens (these are not waits for something)
QUIET_S = 4 * PERIOD_S  # [s] after a stop, no moving twist for 4 control periods
LIVE_CLIENT_S = 2 * CLIENT_TIMEOUT_S  # [s] a live doomed_client's goal runs on, past the client timeout
OWN_GOAL_LIVES_S = 3 * CLIENT_TIMEOUT_S  # [s] this node's own goal runs on, well past the client timeout
DOOMED_CLIENT = FilePath(__file__).resolve().parent / "doomed_client.py"


def straight_path(frame="map", length=5.0, yaw=0.0):
    path = Path()
    path.header.frame_id = frame
    for k in range(int(length / 0.1) + 1):
        pose = PoseStamped()
        pose.header.frame_id = frame
        pose.pose.position.x = 0.1 * k * math.cos(yaw)
        pose.pose.position.y = 0.1 * k * math.sin(yaw)
        pose.pose.orientation.z, pose.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        path.poses.append(pose)
    return path


class FakeRobot:
    """Odometry + tf (map -> odom as a localizer publishes it, odom -> base_footprint) + an empty 360-beam scan,
    all at 20 Hz."""

    def __init__(self):
        self.odom_on = threading.Event()
        self.scan_on = threading.Event()
        self.odom_on.set()
        self.scan_on.set()
        self.bad_velocity = False
        self.obstacle_ahead = False  # the scan sees something 0.35 m straight ahead
        self.odom_frame = "odom"
        self.passes = 0  # loop passes done; each published what was on at its start
        self.passed = threading.Condition()
        self.odom_pub = rospy.Publisher("odom", Odometry, queue_size=1)
        self.scan_pub = rospy.Publisher("scan", LaserScan, queue_size=1)
        self.localizer_on = threading.Event()  # map -> odom, as a localizer publishes it (with the odometry)
        self.localizer_on.set()
        self.tf = tf2_ros.TransformBroadcaster()
        self.thread = threading.Thread(target=self.loop, daemon=True)
        self.thread.start()

    def loop(self):
        while not rospy.is_shutdown():
            stamp = rospy.Time.now()
            transforms = [identity_tf("odom", BASE_FRAME, stamp)]
            if self.localizer_on.is_set():
                transforms.append(identity_tf("map", "odom", stamp))
            self.tf.sendTransform(transforms)
            if self.odom_on.is_set():
                odom = odom_at_rest(stamp, self.odom_frame)
                if self.bad_velocity:
                    odom.twist.twist.linear.x = float("nan")
                self.odom_pub.publish(odom)
            if self.scan_on.is_set():
                scan = empty_scan(stamp)
                if self.obstacle_ahead:
                    scan.ranges[170:191] = [0.35] * 21  # beams within +-10 deg of straight ahead
                self.scan_pub.publish(scan)
            with self.passed:
                self.passes += 1
                self.passed.notify_all()
            rospy.sleep(0.05)

    def healthy(self):
        """Undo what a test broke; True if something was broken."""
        broken = (self.odom_frame != "odom" or self.bad_velocity or not self.odom_on.is_set()
                  or not self.scan_on.is_set() or self.obstacle_ahead or not self.localizer_on.is_set())
        self.odom_frame = "odom"
        self.bad_velocity = False
        self.obstacle_ahead = False
        self.odom_on.set()
        self.scan_on.set()
        self.localizer_on.set()
        return broken

    def wait_passes(self, count, timeout_s):
        """True once ``count`` whole passes that began after this call are published (what a test switched on
        or off before it is in all of them); False after ``timeout_s``."""
        deadline = rospy.get_time() + timeout_s
        with self.passed:
            target = self.passes + count + 1  # the pass under way may have read the switches before they changed
            while self.passes < target:
                left = deadline - rospy.get_time()
                if left <= 0:
                    return False
                self.passed.wait(min(left, 0.1))
        return True

    def wait_heard_by(self, odom_subscribers, scan_subscribers, tf_subscribers, timeout_s):
        """True once that many nodes are connected to odometry, to the scan and to tf (as this node's publishers
        count them: ready to deliver), and FRESH_PASSES of each have gone out over those connections."""
        deadline = rospy.get_time() + timeout_s
        while rospy.get_time() < deadline:
            if (self.odom_pub.get_num_connections() >= odom_subscribers
                    and self.scan_pub.get_num_connections() >= scan_subscribers
                    and self.tf.pub_tf.get_num_connections() >= tf_subscribers):
                return self.wait_passes(FRESH_PASSES, deadline - rospy.get_time())
            rospy.sleep(0.05)
        return False


class Commands(MessageLog):
    """Every TwistStamped a controller published, with a wait (at most RESULT_WAIT_S unless told) for one matching a
    condition."""

    def __init__(self, topic):
        super().__init__(topic, TwistStamped, queue_size=50, wait_s=RESULT_WAIT_S)

    def wait_publishers_gone(self, timeout_s=RESULT_WAIT_S):
        """True once no publisher is connected: all a stopped node sent has been read (its connection closes
        after its last message)."""
        deadline = rospy.get_time() + timeout_s
        while self.sub.get_num_connections() > 0:
            if rospy.get_time() > deadline:
                return False
            rospy.sleep(0.01)
        return True


def is_zero(msg):
    t = msg.twist
    return (t.linear.x, t.linear.y, t.linear.z, t.angular.x, t.angular.y, t.angular.z) == (0.0,) * 6


def moving(msg):
    return not is_zero(msg)


class Results:
    """ActionResult messages of a server (their header stamps tell when the server ended each goal)."""

    def __init__(self, topic, msg_type):
        self.msgs = []
        rospy.Subscriber(topic, msg_type, self.msgs.append, queue_size=50)

    def for_goal(self, goal_id, timeout_s=RESULT_WAIT_S):
        deadline = rospy.get_time() + timeout_s
        while rospy.get_time() < deadline:
            for msg in list(self.msgs):
                if msg.status.goal_id.id == goal_id:
                    return msg
            rospy.sleep(0.01)
        return None

    def has_goal(self, goal_id):
        return any(msg.status.goal_id.id == goal_id for msg in list(self.msgs))


class TestControllerSafety(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.robot = FakeRobot()
        cls.path_cmds = Commands("pp_path/cmd")
        cls.topic_cmds = Commands("pp_topic/cmd")
        cls.path_results = Results("pp_path/result", FollowPathActionResult)
        cls.topic_results = Results("pp_topic/result", FollowTopicActionResult)
        cls.path_client = actionlib.ActionClient("pp_path", FollowPathAction)
        cls.topic_client = actionlib.ActionClient("pp_topic", FollowTopicAction)
        cls.blind_cmds = Commands("pp_blind/cmd")
        cls.blind_results = Results("pp_blind/result", FollowPathActionResult)
        cls.blind_client = actionlib.ActionClient("pp_blind", FollowPathAction)
        assert cls.blind_client.wait_for_server(rospy.Duration(WAIT_S)), "pp_blind did not come up"
        assert cls.path_client.wait_for_server(rospy.Duration(WAIT_S)), "pp_path did not come up"
        assert cls.topic_client.wait_for_server(rospy.Duration(WAIT_S)), "pp_topic did not come up"
        # a goal sent before a controller has odometry is rightly aborted ("no odometry received yet")
        assert cls.robot.wait_heard_by(3, 2, 3, WAIT_S), "the controllers did not subscribe to odom, scan and tf"
        cls.plan_pub = rospy.Publisher("test_plan", Path, queue_size=1, latch=True)
        cls.clear_clients = [ActionClientProxy(name + "/clear_costmap", ClearCostmapAction)
                             for name in ("pp_path", "pp_topic")]
        for client in cls.clear_clients:
            assert client.is_available(WAIT_S), "a controller's clear_costmap did not come up"

    def setUp(self):
        if self.robot.healthy():  # sensors fresh again after a test that stopped them
            self.assertTrue(self.robot.wait_passes(FRESH_PASSES, WAIT_S), "the fake robot stopped publishing")
            for client in self.clear_clients:  # no obstacle mark of the previous test left in a local costmap
                client.send_goal(ClearCostmapGoal())
                self.assertTrue(client.wait_for_result(RESULT_WAIT_S), "clear_costmap did not answer")

    # ------------------------------------------------------------------ helpers
    def send_path(self, path):
        return self.path_client.send_goal(FollowPathGoal(path=path))

    def wait_terminal(self, handle, timeout_s=RESULT_WAIT_S):
        deadline = rospy.get_time() + timeout_s
        while rospy.get_time() < deadline:
            if handle.get_comm_state() == actionlib.CommState.DONE:
                return handle.get_goal_status()
            rospy.sleep(0.01)
        self.fail(f"no result within {timeout_s} s")

    def assert_aborted_and_stopped(self, handle, results, cmds, mark, reason_part):
        self.assertEqual(self.wait_terminal(handle), GoalStatus.ABORTED)
        result = handle.get_result()
        self.assertEqual(result.code, FollowPathResult.FAILURE, result.message)
        self.assertIn(reason_part, result.message)
        ended = results.for_goal(handle.comm_state_machine.action_goal.goal_id.id)
        self.assertIsNotNone(ended)
        zero = cmds.wait_for(is_zero, mark)
        self.assertIsNotNone(zero, "no zero twist published")
        # the zero went out before the goal was reported aborted, and nothing moved the robot after it
        self.assertLessEqual(zero.header.stamp, ended.header.stamp)
        rospy.sleep(QUIET_S)
        after = cmds.since(cmds.msgs.index(zero))
        self.assertFalse(any(moving(m) for m in after), "a non-zero twist followed the stop")

    def start_driving(self, path=None):
        mark = self.path_cmds.count()
        handle = self.send_path(path or straight_path())
        self.assertIsNotNone(self.path_cmds.wait_for(moving, mark), "the controller never drove")
        return handle

    # ------------------------------------------------------------------ bad goals
    def test_empty_path(self):
        mark = self.path_cmds.count()
        handle = self.send_path(Path())
        self.assert_aborted_and_stopped(handle, self.path_results, self.path_cmds, mark, "the path is empty")

    def test_path_in_unknown_frame(self):
        mark = self.path_cmds.count()
        handle = self.send_path(straight_path(frame="nowhere"))
        self.assert_aborted_and_stopped(handle, self.path_results, self.path_cmds, mark,
                                        "'nowhere' cannot be transformed")

    def test_path_with_nan(self):
        path = straight_path()
        path.poses[3].pose.position.y = float("nan")
        mark = self.path_cmds.count()
        self.assert_aborted_and_stopped(self.send_path(path), self.path_results, self.path_cmds, mark,
                                        "path pose 3")

    # ------------------------------------------------------------------ sensors
    def test_stale_odometry(self):
        handle = self.start_driving()
        mark = self.path_cmds.count()
        self.robot.odom_on.clear()
        self.assert_aborted_and_stopped(handle, self.path_results, self.path_cmds, mark, "stale odom")

    def test_stale_scan(self):
        handle = self.start_driving()
        mark = self.path_cmds.count()
        self.robot.scan_on.clear()
        self.assert_aborted_and_stopped(handle, self.path_results, self.path_cmds, mark, "stale scan")

    def test_odometry_in_unknown_frame(self):
        handle = self.start_driving()
        mark = self.path_cmds.count()
        self.robot.odom_frame = "lost_odom"
        self.assert_aborted_and_stopped(handle, self.path_results, self.path_cmds, mark, "robot pose unknown")

    def test_localization_stopped(self):
        mark = self.blind_cmds.count()
        handle = self.blind_client.send_goal(FollowPathGoal(path=straight_path()))
        self.assertIsNotNone(self.blind_cmds.wait_for(moving, mark), "the controller never drove")
        mark = self.blind_cmds.count()
        self.robot.localizer_on.clear()  # odometry and odom -> base_footprint go on
        self.assert_aborted_and_stopped(handle, self.blind_results, self.blind_cmds, mark,
                                        "the newest transform 'map' -> 'odom' is")

    def test_non_finite_velocity(self):
        handle = self.start_driving()
        mark = self.path_cmds.count()
        self.robot.bad_velocity = True
        self.assert_aborted_and_stopped(handle, self.path_results, self.path_cmds, mark, "velocity is not finite")

    def test_obstacle_ahead_in_the_local_costmap(self):
        self.robot.obstacle_ahead = True  # pp_path has collision_timeout 0: abort at the first collision
        self.assertTrue(self.robot.wait_passes(FRESH_PASSES, WAIT_S))  # scans of it into the rolling local costmap
        mark = self.path_cmds.count()
        handle = self.send_path(straight_path())
        self.assert_aborted_and_stopped(handle, self.path_results, self.path_cmds, mark, "collision ahead")

    # ------------------------------------------------------------------ cancel / replace
    def test_cancel_stops_every_time(self):
        for attempt in range(5):
            handle = self.start_driving()
            mark = self.path_cmds.count()
            handle.cancel()
            self.assertEqual(self.wait_terminal(handle), GoalStatus.PREEMPTED, f"attempt {attempt}")
            self.assertEqual(handle.get_result().code, FollowPathResult.PREEMPT)
            ended = self.path_results.for_goal(handle.comm_state_machine.action_goal.goal_id.id)
            zero = self.path_cmds.wait_for(is_zero, mark)
            self.assertIsNotNone(zero, f"attempt {attempt}: no zero twist after cancel")
            # published from the cancel callback itself, before the goal was reported preempted
            self.assertLessEqual(zero.header.stamp, ended.header.stamp, f"attempt {attempt}")
            rospy.sleep(QUIET_S)
            after = self.path_cmds.since(self.path_cmds.msgs.index(zero))
            self.assertFalse(any(moving(m) for m in after), f"attempt {attempt}: moved after the cancel")

    def test_new_goal_replaces_old(self):
        first = self.start_driving()
        second = self.send_path(straight_path(yaw=0.3))
        self.assertEqual(self.wait_terminal(first), GoalStatus.PREEMPTED)
        self.assertIn("replaced by a newer goal", first.get_result().message)
        mark = self.path_cmds.count()
        turning = self.path_cmds.wait_for(lambda m: m.twist.angular.z > 0.05, mark)
        self.assertIsNotNone(turning, "the new path (to the left) is not being followed")
        second.cancel()
        self.assertEqual(self.wait_terminal(second), GoalStatus.PREEMPTED)

    # ------------------------------------------------------------------ the controller shuts down
    def test_a_controller_shut_down_mid_goal_sends_a_zero_twist_last(self):
        """Ctrl-C on the launch (SIGINT): the controller's last command is a stop, not its last drive."""
        cmds = Commands("pp_stopping/cmd")
        node = subprocess.Popen(["rosrun", "flex_nav", "pure_pursuit_path", "__name:=pp_stopping",
                                 "cmd_vel_stamped:=pp_stopping/cmd", "_controller_frequency:=20.0",
                                 "_sensor_timeout:=1.0", "_pure_pursuit/desired_linear_vel:=0.3"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=dict(os.environ))
        try:
            client = actionlib.ActionClient("pp_stopping", FollowPathAction)
            self.assertTrue(client.wait_for_server(rospy.Duration(WAIT_S)), "pp_stopping did not come up")
            deadline = rospy.get_time() + WAIT_S
            handle = None
            while rospy.get_time() < deadline:  # its odometry subscription may take a moment
                mark = cmds.count()
                handle = client.send_goal(FollowPathGoal(path=straight_path()))
                if cmds.wait_for(moving, mark, 2.0) is not None:
                    break
                handle.cancel()
            self.assertIsNotNone(handle)
            mark = cmds.count()
            self.assertIsNotNone(cmds.wait_for(moving, mark), "pp_stopping never drove")
            mark = cmds.count()
            node.send_signal(signal.SIGINT)
            node.wait(RESULT_WAIT_S)
            self.assertTrue(cmds.wait_publishers_gone(), "the stopped node's connection stayed open")
            sent = cmds.since(mark)
            self.assertTrue(sent, "nothing was published after the signal")
            self.assertTrue(is_zero(sent[-1]), f"the last command was {sent[-1].twist}")
        finally:
            if node.poll() is None:
                node.kill()
                node.wait(RESULT_WAIT_S)

    # ------------------------------------------------------------------ the client's node dies
    def start_doomed_client(self, *args):
        return subprocess.Popen([sys.executable, str(DOOMED_CLIENT), "pp_path", *args], stdout=subprocess.PIPE,
                                text=True, env=dict(os.environ))

    def end_process(self, proc):
        proc.kill()
        proc.wait(RESULT_WAIT_S)
        proc.stdout.close()

    def drive_for_doomed_client(self, client):
        """The goal id of ``client``'s goal, once it drives and has outlived the client timeout untouched."""
        mark = self.path_cmds.count()
        self.assertIsNotNone(self.path_cmds.wait_for(moving, mark, WAIT_S), "the client's goal never drove")
        goal_id = client.stdout.readline().strip()  # printed before the goal could drive
        self.assertTrue(goal_id.startswith("/doomed_client-"), goal_id)
        rospy.sleep(LIVE_CLIENT_S)  # the client alive: its goal runs on
        self.assertFalse(self.path_results.has_goal(goal_id), "a live client's goal was ended")
        return goal_id

    def assert_abandoned_and_stopped(self, goal_id, mark):
        ended = self.path_results.for_goal(goal_id, 3 * CLIENT_TIMEOUT_S + RESULT_WAIT_S)
        self.assertIsNotNone(ended, "the goal of a gone client was never ended")
        self.assertEqual(ended.status.status, GoalStatus.ABORTED)
        self.assertEqual(ended.result.code, FollowPathResult.FAILURE)
        self.assertIn("the client /doomed_client that sent this goal is gone", ended.result.message)
        zero = self.path_cmds.wait_for(is_zero, mark)
        self.assertIsNotNone(zero, "no zero twist published")
        self.assertLessEqual(zero.header.stamp, ended.header.stamp)
        rospy.sleep(QUIET_S)
        after = self.path_cmds.since(self.path_cmds.msgs.index(zero))
        self.assertFalse(any(moving(m) for m in after), "the robot moved after the stop")

    def test_goal_of_a_killed_client_stops(self):
        live = self.start_driving()  # this node stays: its goal outlives the client timeout untouched
        rospy.sleep(OWN_GOAL_LIVES_S)
        self.assertNotEqual(live.get_comm_state(), actionlib.CommState.DONE, live.get_goal_status_text())
        live.cancel()
        self.assertEqual(self.wait_terminal(live), GoalStatus.PREEMPTED)

        client = self.start_doomed_client()
        try:
            goal_id = self.drive_for_doomed_client(client)
            mark = self.path_cmds.count()
            client.send_signal(signal.SIGKILL)
        finally:
            self.end_process(client)
        self.assert_abandoned_and_stopped(goal_id, mark)

    def test_goal_of_a_client_replaced_under_its_name_stops(self):
        # a node started under a taken name makes the master shut the old one down (as a respawn would): the
        # new node connects at once under the same caller id, but it does not know the old node's goal
        client = self.start_doomed_client()
        successor = None
        try:
            goal_id = self.drive_for_doomed_client(client)
            mark = self.path_cmds.count()
            successor = self.start_doomed_client("quiet")
            self.assertEqual(successor.stdout.readline().strip(), "connected")
            self.assert_abandoned_and_stopped(goal_id, mark)
        finally:
            self.end_process(client)
            if successor is not None:
                self.end_process(successor)

    # ------------------------------------------------------------------ FollowTopic
    def send_topic(self, topic):
        goal = FollowTopicGoal(topic=String(data=topic))
        return self.topic_client.send_goal(goal)

    def test_topic_without_publisher_fails_with_reason(self):
        mark = self.topic_cmds.count()
        handle = self.send_topic("nobody_publishes_this")
        self.assert_aborted_and_stopped(handle, self.topic_results, self.topic_cmds, mark,
                                        f"no Path on /nobody_publishes_this within {TOPIC_TIMEOUT_S:.1f} s "
                                        "(0 publishers connected)")

    def test_topic_follows_the_newest_path_and_cancels(self):
        self.plan_pub.publish(straight_path(yaw=0.0))
        mark = self.topic_cmds.count()
        handle = self.send_topic("/test_plan")
        straight = self.topic_cmds.wait_for(moving, mark)
        self.assertIsNotNone(straight)
        self.assertAlmostEqual(straight.twist.angular.z, 0.0, places=6)
        mark = self.topic_cmds.count()
        self.plan_pub.publish(straight_path(yaw=-0.4))  # newer path to the right
        right = self.topic_cmds.wait_for(lambda m: m.twist.angular.z < -0.05, mark)
        self.assertIsNotNone(right, "the newer path was not followed")
        mark = self.topic_cmds.count()
        self.plan_pub.publish(Path(header=straight_path().header))  # an empty path on the topic
        self.assert_aborted_and_stopped(handle, self.topic_results, self.topic_cmds, mark, "the path is empty")

    def test_topic_goal_cancel_stops(self):
        # a topic of its own: pp_topic may still hold the last (empty) path of /test_plan from another test
        plan_pub = rospy.Publisher("test_plan_cancel", Path, queue_size=1, latch=True)
        plan_pub.publish(straight_path())
        mark = self.topic_cmds.count()
        handle = self.send_topic("/test_plan_cancel")
        self.assertIsNotNone(self.topic_cmds.wait_for(moving, mark))
        mark = self.topic_cmds.count()
        handle.cancel()
        self.assertEqual(self.wait_terminal(handle), GoalStatus.PREEMPTED)
        ended = self.topic_results.for_goal(handle.comm_state_machine.action_goal.goal_id.id)
        zero = self.topic_cmds.wait_for(is_zero, mark)
        self.assertIsNotNone(zero)
        self.assertLessEqual(zero.header.stamp, ended.header.stamp)


if __name__ == "__main__":
    init_node("test_controller_safety", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_controller_safety", TestControllerSafety, sys.argv)
