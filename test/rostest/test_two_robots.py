#!/usr/bin/env python3
"""rostest node: two robots' navigation side by side in namespaces robot1 and robot2 (two_robots.test)."""

import math
import sys
import unittest

import rospy
import rostest
import tf2_ros
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from readiness import wait_until_goal_succeeds
from std_msgs.msg import Header

from flex_nav.msg import (
    ClearCostmapAction,
    ClearCostmapGoal,
    FollowPathAction,
    FollowPathGoal,
    GetPathAction,
    GetPathGoal,
)
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import ActionClientProxy

WAIT_S = 40.0  # [s] bound on the servers appearing
DRIVE_WAIT_S = 40.0  # [s] bound on reaching the goals
READY_WAIT_S = 30.0  # [s] bound on each planner planning its first goal (map and robot tf received)
ROBOTS = {"robot1": ((1.0, 1.0), (3.0, 1.0)), "robot2": ((1.0, 2.4), (3.0, 2.4))}  # start, goal in the map


def goal_pose(xy):
    pose = PoseStamped()
    pose.header.frame_id = "map"
    pose.pose.position.x, pose.pose.position.y = xy
    pose.pose.orientation.w = 1.0
    return pose


class TestTwoRobots(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tf = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.tf)
        cls.planners, cls.controllers = {}, {}
        for robot in ROBOTS:
            cls.planners[robot] = ActionClientProxy(f"/{robot}/get_path_server", GetPathAction)
            cls.controllers[robot] = ActionClientProxy(f"/{robot}/pure_pursuit_path", FollowPathAction)
            for client in (cls.planners[robot], cls.controllers[robot]):
                assert client.is_available(WAIT_S), f"{robot}'s servers did not come up"
        for robot, (start, goal) in ROBOTS.items():
            wait_until_goal_succeeds(cls.planners[robot], GetPathGoal(pose=goal_pose(goal)),
                                     f"{robot}'s get_path_server planning its goal", READY_WAIT_S)
            # a one-pose path where the robot stands: reached at once, once the controller has odometry
            here = Path(header=Header(frame_id="map"), poses=[goal_pose(start)])
            wait_until_goal_succeeds(cls.controllers[robot], FollowPathGoal(path=here),
                                     f"{robot}'s pure_pursuit_path following a path to where it stands", READY_WAIT_S)

    def robot_xy(self, robot):
        tf = self.tf.lookup_transform("map", f"{robot}/base_footprint", rospy.Time(0), rospy.Duration(2.0))
        return tf.transform.translation.x, tf.transform.translation.y

    def test_each_robot_plans_from_its_own_pose_and_drives_to_its_own_goal(self):
        plans = {}
        for robot, (_start, goal) in ROBOTS.items():
            self.planners[robot].send_goal(GetPathGoal(pose=goal_pose(goal)))
        for robot, (start, _goal) in ROBOTS.items():
            client = self.planners[robot]
            self.assertTrue(client.wait_for_result(10.0))
            self.assertEqual(client.state(), GoalStatus.SUCCEEDED, client.result().message)
            plans[robot] = client.result().plan
            first = plans[robot].poses[0].pose.position
            self.assertAlmostEqual(first.x, start[0], delta=0.05, msg=robot)
            self.assertAlmostEqual(first.y, start[1], delta=0.05, msg=robot)
        for robot, plan in plans.items():
            self.controllers[robot].send_goal(FollowPathGoal(path=plan))
        for robot, (_start, goal) in ROBOTS.items():
            client = self.controllers[robot]
            self.assertTrue(client.wait_for_result(DRIVE_WAIT_S), f"{robot} did not arrive")
            self.assertEqual(client.state(), GoalStatus.SUCCEEDED, client.result().message)
            x, y = self.robot_xy(robot)
            self.assertLess(math.hypot(x - goal[0], y - goal[1]), 0.25, robot)
            end = client.result().pose.position
            self.assertAlmostEqual(end.x, x, delta=0.1)

    def test_clear_costmap_per_robot(self):
        for robot in ROBOTS:
            client = ActionClientProxy(f"/{robot}/pure_pursuit_path/clear_costmap", ClearCostmapAction)
            self.assertTrue(client.is_available(WAIT_S))
            client.send_goal(ClearCostmapGoal())
            self.assertTrue(client.wait_for_result(5.0))
            self.assertEqual(client.state(), GoalStatus.SUCCEEDED, client.result().message)
            self.assertIn("cleared", client.result().message)


if __name__ == "__main__":
    init_node("test_two_robots", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_two_robots", TestTwoRobots, sys.argv)
