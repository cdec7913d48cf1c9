#!/usr/bin/env python3
"""rostest node: navigation.launch drives a kinematic robot to a goal through the whole chain, stops it on
cancel, and its follow_topic_server replans along a path from a topic (navigation_drive.test)."""

import math
import os
import sys
import threading
import unittest

import cv2
import numpy as np
import rospkg
import rospy
import rostest
import tf2_ros
import yaml
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PolygonStamped, PoseStamped
from nav_msgs.msg import Odometry, Path
from std_msgs.msg import String

from flex_nav.msg import (
    FollowPathAction,
    FollowPathGoal,
    FollowTopicAction,
    FollowTopicGoal,
    FollowTopicResult,
    GetPathAction,
    GetPathGoal,
)
from flex_nav.nav.costmap.map_io import load_map
from flex_nav.ros.conversions import path_msg
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import ActionClientProxy

NS = "/robot1/"
BASE = "robot1/base_footprint"
WAIT_S = 40.0  # [s] bound on the servers appearing (eight nodes start on a shared 2-core machine)
DRIVE_WAIT_S = 60.0  # [s] bound on reaching the goal
RADIUS = 0.177  # [m] TurtleBot 2 (config/turtlebot2.yaml)
MAP = os.path.join(rospkg.RosPack().get_path("flex_nav"), "test", "data", "maps", "test_rooms.yaml")
RVIZ = os.path.join(rospkg.RosPack().get_path("flex_nav"), "rviz", "flex_nav.rviz")


def goal_pose(x, y, yaw=0.0):
    msg = PoseStamped()
    msg.header.frame_id = "map"
    msg.pose.position.x, msg.pose.position.y = x, y
    msg.pose.orientation.z, msg.pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
    return msg


def angle_error(a, b):
    """a - b [rad], wrapped into (-pi, pi]."""
    return math.atan2(math.sin(a - b), math.cos(a - b))


class TestNavigationDrive(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.clients = {}
        for name, action in (("get_path_server", GetPathAction), ("follow_path_server", FollowPathAction),
                             ("follow_topic_server", FollowTopicAction), ("pure_pursuit_path", FollowPathAction),
                             ("pure_pursuit_topic", FollowTopicAction)):
            client = ActionClientProxy(NS + name, action)
            assert client.is_available(WAIT_S), f"{NS + name} did not come up"
            cls.clients[name] = client
        cls.tf = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.tf)
        assert cls.tf.can_transform("map", BASE, rospy.Time(0), rospy.Duration(WAIT_S)), f"no tf map -> {BASE}"
        grid = load_map(MAP)
        free = (grid.occupancy < 50).astype(np.uint8)
        cls.clearance = cv2.distanceTransform(free, cv2.DIST_L2, 5) * grid.resolution  # [m] to occupied cells
        cls.grid = grid
        cls.odom = []
        rospy.Subscriber(NS + "odom", Odometry, cls.odom.append, queue_size=100)
        cls.global_plan = rospy.Publisher(NS + "test_global_plan", Path, queue_size=1, latch=True)

    def robot_xy(self):
        tf = self.tf.lookup_transform("map", BASE, rospy.Time(0), rospy.Duration(2.0))
        return tf.transform.translation.x, tf.transform.translation.y

    def robot_pose(self):
        tf = self.tf.lookup_transform("map", BASE, rospy.Time(0), rospy.Duration(2.0))
        q = tf.transform.rotation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        return tf.transform.translation.x, tf.transform.translation.y, yaw

    def plan_to(self, x, y, yaw=0.0):
        client = self.clients["get_path_server"]
        client.send_goal(GetPathGoal(pose=goal_pose(x, y, yaw)))
        self.assertTrue(client.wait_for_result(10.0))
        self.assertEqual(client.state(), GoalStatus.SUCCEEDED, client.result().message)
        return client.result().plan

    def test_0_footprint_is_latched_in_the_base_frame(self):
        msg = rospy.wait_for_message(NS + "footprint", PolygonStamped, timeout=10.0)
        self.assertEqual(msg.header.frame_id, BASE)
        radii = [math.hypot(p.x, p.y) for p in msg.polygon.points]
        self.assertEqual(len(radii), 24)
        self.assertAlmostEqual(min(radii), max(radii), places=5)
        self.assertTrue(RADIUS < radii[0] < RADIUS * 1.01, radii[0])  # around the robot_radius circle

    def test_0_rviz_config_shows_what_the_stack_publishes(self):
        with open(RVIZ) as f:
            config = yaml.safe_load(f)["Visualization Manager"]
        shown = {d.get("Topic") or d["Marker Topic"] for d in config["Displays"] if "Topic" in d or "Marker Topic" in d}
        published = {name for name, _ in rospy.get_published_topics()}
        self.assertIn(NS + "get_path_server/global_costmap/obstacle_memory", published)  # the profile's memory is on
        not_here = {NS + "particlecloud", NS + "move_base_like/plan",  # no localizer or behavior in this test
                    NS + "bumper_hits",  # no bumper relay
                    NS + "obstacle_class_marker",  # no obstacle classifier
                    NS + "pure_pursuit_path/people", NS + "pure_pursuit_topic/people"}  # yield_to_people is off
        self.assertEqual(sorted(shown - published - not_here), [])
        self.assertTrue(not_here <= shown)

    def test_1_follow_topic_server_replans_along_a_topic_path(self):
        start = self.robot_xy()
        points = np.array([[start[0] + 0.1 * k, start[1]] for k in range(25)])  # 2.4 m east
        self.global_plan.publish(path_msg(points, "map", rospy.Time.now()))
        local = []
        event = threading.Event()

        def on_plan(msg):
            local.append(msg)
            event.set()

        sub = rospy.Subscriber(NS + "follow_topic_server/plan", Path, on_plan)
        client = self.clients["follow_topic_server"]
        client.send_goal(FollowTopicGoal(topic=String(data=NS + "test_global_plan")))
        self.assertTrue(event.wait(10.0), "no local plan published")
        plan = local[-1]
        first, last = plan.poses[0].pose.position, plan.poses[-1].pose.position
        self.assertAlmostEqual(first.x, start[0], delta=0.05)
        self.assertAlmostEqual(last.x, start[0] + 1.5, delta=0.06)  # lookahead_distance 1.5 m along the path
        self.assertAlmostEqual(last.y, start[1], delta=0.06)
        client.cancel()
        self.assertTrue(client.wait_for_result(5.0))
        self.assertEqual(client.state(), GoalStatus.PREEMPTED)
        sub.unregister()

    def test_1b_follow_topic_server_without_publisher(self):
        client = self.clients["follow_topic_server"]
        client.send_goal(FollowTopicGoal(topic=String(data="silent_topic")))
        self.assertTrue(client.wait_for_result(10.0))
        self.assertEqual(client.state(), GoalStatus.ABORTED)
        self.assertEqual(client.result().code, FollowTopicResult.FAILURE)
        self.assertIn(f"no Path on {NS}silent_topic within 2.0 s", client.result().message)

    def test_2_follow_path_server_rejects_bad_paths(self):
        client = self.clients["follow_path_server"]
        for path, reason in ((Path(), "the path is empty"),
                             (path_msg(np.array([[1.0, 1.0], [2.0, 1.0]]), "atlantis", rospy.Time.now()),
                              "'atlantis' cannot be transformed")):
            client.send_goal(FollowPathGoal(path=path))
            self.assertTrue(client.wait_for_result(5.0))
            self.assertEqual(client.state(), GoalStatus.ABORTED)
            self.assertIn(reason, client.result().message)

    def test_3_drive_to_goal_through_the_chain(self):
        goal = (3.0, 3.5)  # beside the block x 1.5..2.5, y 3..4: the plan bends around its corner
        plan = self.plan_to(*goal)
        planner, controller = self.clients["follow_path_server"], self.clients["pure_pursuit_topic"]
        # the controller subscribes first: the planner's first local plan is not lost before it listens
        controller.send_goal(FollowTopicGoal(topic=String(data=NS + "follow_path_server/plan")))
        planner.send_goal(FollowPathGoal(path=plan))
        worst = math.inf
        deadline = rospy.get_time() + DRIVE_WAIT_S
        while rospy.get_time() < deadline and controller.state() in (GoalStatus.PENDING, GoalStatus.ACTIVE):
            x, y = self.robot_xy()
            row, col = self.grid.world_to_cell(x, y)
            worst = min(worst, float(self.clearance[row, col]))
            rospy.sleep(0.1)
        self.assertEqual(controller.state(), GoalStatus.SUCCEEDED, controller.result())
        self.assertTrue(planner.wait_for_result(10.0))
        self.assertEqual(planner.state(), GoalStatus.SUCCEEDED, planner.result().message)
        x, y = self.robot_xy()
        self.assertLess(math.hypot(x - goal[0], y - goal[1]), 0.25)
        self.assertGreater(worst, RADIUS, f"the robot came within {worst:.3f} m of a wall")

    def navigate(self, plan, ignore_final_heading):
        """follow_path_server decides arrival; pure_pursuit_topic follows its local plans and is sent a new goal
        when it reaches the end of one first (flex_navigate's Controller with follow_next_path). The planner's
        result."""
        planner, controller = self.clients["follow_path_server"], self.clients["pure_pursuit_topic"]
        topic = String(data=NS + "follow_path_server/plan")
        controller.send_goal(FollowTopicGoal(topic=topic, ignore_final_heading=ignore_final_heading))
        planner.send_goal(FollowPathGoal(path=plan, ignore_final_heading=ignore_final_heading))
        deadline = rospy.get_time() + DRIVE_WAIT_S
        while rospy.get_time() < deadline and planner.state() in (GoalStatus.PENDING, GoalStatus.ACTIVE):
            if controller.state() == GoalStatus.SUCCEEDED:
                controller.send_goal(FollowTopicGoal(topic=topic, newer_than=rospy.Time.now(),
                                                     ignore_final_heading=ignore_final_heading))
            self.assertIn(controller.state(), (GoalStatus.PENDING, GoalStatus.ACTIVE, GoalStatus.SUCCEEDED),
                          controller.result())
            rospy.sleep(0.05)
        controller.cancel()
        self.assertEqual(planner.state(), GoalStatus.SUCCEEDED, planner.result())
        return planner.result()

    def test_3b_goal_heading_is_reached_within_the_tolerance(self):
        goal = (1.0, 2.0, math.pi / 2)  # from the corner of the block, arriving heading south-west: a 135+ deg turn
        plan = self.plan_to(*goal)
        yaw = plan.poses[-1].pose.orientation
        self.assertAlmostEqual(2.0 * math.atan2(yaw.z, yaw.w), goal[2], places=6)  # the plan carries the goal's yaw
        result = self.navigate(plan, ignore_final_heading=False)
        x, y, heading = self.robot_pose()
        error = angle_error(heading, goal[2])
        rospy.loginfo(f"goal heading 90 deg reached at ({x:.3f}, {y:.3f}), heading error "
                      f"{math.degrees(error):+.1f} deg; planner: {result.message}")
        self.assertLess(math.hypot(x - goal[0], y - goal[1]), 0.25)
        self.assertLessEqual(abs(error), 0.25, f"heading error {math.degrees(error):.1f} deg")  # yaw_goal_tolerance
        self.assertIn("heading", result.message)

    def test_3c_goal_heading_ignored_when_the_goal_says_so(self):
        goal = (3.0, 2.0, math.pi)  # the robot comes from the west: arriving, it faces about 0, not pi
        plan = self.plan_to(*goal)
        self.navigate(plan, ignore_final_heading=True)
        x, y, heading = self.robot_pose()
        self.assertLess(math.hypot(x - goal[0], y - goal[1]), 0.25)
        self.assertGreater(abs(angle_error(heading, goal[2])), 1.0, "the robot turned to a heading it should ignore")

    def test_4_cancel_stops_the_robot(self):
        plan = self.plan_to(1.0, 1.0)
        controller = self.clients["pure_pursuit_path"]
        start = self.robot_xy()
        controller.send_goal(FollowPathGoal(path=plan))
        deadline = rospy.get_time() + 20.0
        while rospy.get_time() < deadline and math.dist(self.robot_xy(), start) < 0.3:
            rospy.sleep(0.05)
        self.assertGreaterEqual(math.dist(self.robot_xy(), start), 0.3, "the robot did not move")
        mark = len(self.odom)
        controller.cancel()
        self.assertTrue(controller.wait_for_result(5.0))
        self.assertEqual(controller.state(), GoalStatus.PREEMPTED)
        deadline = rospy.get_time() + 5.0
        stopped = None
        while stopped is None and rospy.get_time() < deadline:
            stopped = next((m for m in self.odom[mark:] if m.twist.twist.linear.x == 0.0
                            and m.twist.twist.angular.z == 0.0), None)
            rospy.sleep(0.02)
        self.assertIsNotNone(stopped, "the robot kept moving after the cancel")
        rospy.sleep(0.5)
        here, later = stopped.pose.pose.position, self.odom[-1].pose.pose.position  # odometry, not a lagging tf
        self.assertLess(math.dist((here.x, here.y), (later.x, later.y)), 1e-3, "the robot moved after it stopped")


if __name__ == "__main__":
    init_node("test_navigation_drive", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_navigation_drive", TestNavigationDrive, sys.argv)
