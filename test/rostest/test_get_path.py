#!/usr/bin/env python3
"""rostest node: get_path_server against a real master, map_server and a robot in tf (get_path.test)."""

import math
import sys
import threading
import unittest

import actionlib
import rospkg
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from readiness import wait_until_goal_succeeds

from flex_nav.msg import ClearCostmapAction, ClearCostmapGoal, ClearCostmapResult, GetPathAction, GetPathGoal
from flex_nav.msg import GetPathResult as R
from flex_nav.nav.costmap.map_io import load_map
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import ActionClientProxy

SERVER_WAIT_S = 30.0  # [s] nodes start slowly on a loaded machine
READY_WAIT_S = 30.0  # [s] bound on get_path_server planning its first goal (latched map and robot tf received)
RESULT_WAIT_S = 5.0  # [s] bound on every answer
START = (1.0, 1.0)  # robot start in the map (get_path.test)
MAP = "test/data/maps/test_rooms.yaml"


def goal_msg(x, y, frame="map", q=(0.0, 0.0, 0.0, 1.0)):
    goal = GetPathGoal(pose=PoseStamped())
    goal.pose.header.frame_id = frame
    goal.pose.pose.position.x, goal.pose.pose.position.y = x, y
    o = goal.pose.pose.orientation
    o.x, o.y, o.z, o.w = q
    return goal


class TestGetPath(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.clients = {}
        cls.grid = load_map(rospkg.RosPack().get_path("flex_nav") + "/" + MAP)
        for name in ("get_path_server", "get_path_no_map", "get_path_no_tf"):
            client = ActionClientProxy(name, GetPathAction)
            assert client.is_available(SERVER_WAIT_S), f"{name} did not come up"
            cls.clients[name] = client
        wait_until_goal_succeeds(cls.clients["get_path_server"], goal_msg(3.0, 1.0), "get_path_server planning a "
                                 "simple goal", READY_WAIT_S, RESULT_WAIT_S)
        cls.plans = []
        cls.plan_cond = threading.Condition()
        rospy.Subscriber("get_path_server/plan", Path, cls._on_plan)

    @classmethod
    def _on_plan(cls, msg):
        with cls.plan_cond:
            cls.plans.append(msg)
            cls.plan_cond.notify_all()

    def ask(self, goal, server="get_path_server"):
        client = self.clients[server]
        client.send_goal(goal)
        self.assertTrue(client.wait_for_result(RESULT_WAIT_S), "no answer within the bound")
        return client.state(), client.result()

    def assert_fails(self, goal, code, reason_part, server="get_path_server"):
        state, result = self.ask(goal, server)
        self.assertEqual(state, GoalStatus.ABORTED, result.message)
        self.assertEqual(result.code, code, result.message)
        self.assertIn(reason_part, result.message)
        self.assertEqual(len(result.plan.poses), 0)
        self.assert_still_serving()

    def assert_still_serving(self):
        state, result = self.ask(goal_msg(3.0, 1.0))
        self.assertEqual((state, result.code), (GoalStatus.SUCCEEDED, R.SUCCESS), result.message)

    def points(self, plan):
        return [(p.pose.position.x, p.pose.position.y) for p in plan.poses]

    def assert_on_free_cells(self, plan):
        """No plan point on an occupied cell. The unknown patch (x 6.0..7.0, y 0.5..1.0) counts as free: the global
        costmap runs without track_unknown_space, as costmap_2d's default; a plan to (7.0, 1.0), the patch's
        corner, may run along its top row or the row above at the same cost."""
        for x, y in self.points(plan):
            row, col = self.grid.world_to_cell(x, y)
            self.assertIn(self.grid.occupancy[row, col], (0, -1), f"plan point ({x:.2f}, {y:.2f}) is not free")

    def test_plan_around_the_wall(self):
        state, result = self.ask(goal_msg(7.0, 1.0, q=(0.0, 0.0, math.sin(0.5), math.cos(0.5))))
        self.assertEqual((state, result.code), (GoalStatus.SUCCEEDED, R.SUCCESS), result.message)
        points = self.points(result.plan)
        self.assertGreaterEqual(len(points), 2)
        self.assertEqual(result.plan.header.frame_id, "map")
        self.assertAlmostEqual(points[0][0], START[0], delta=0.05)
        self.assertAlmostEqual(points[0][1], START[1], delta=0.05)
        self.assertAlmostEqual(points[-1][0], 7.0, delta=1e-6)
        self.assertAlmostEqual(points[-1][1], 1.0, delta=1e-6)
        q = result.plan.poses[-1].pose.orientation
        self.assertAlmostEqual(2.0 * math.atan2(q.z, q.w), 1.0, delta=1e-6)  # goal heading kept
        # the wall x 4.0..4.1 ends at y 3.5: the path crosses x = 4.05 above it, clear of the inflation
        crossing = [y for (x0, y), (x1, _) in zip(points, points[1:]) if min(x0, x1) <= 4.05 <= max(x0, x1)]
        self.assertTrue(crossing and min(crossing) > 3.5 + 0.18, crossing)
        self.assert_on_free_cells(result.plan)
        # ~plan is latched and earlier goals published theirs: wait for this one, not for any message
        with self.plan_cond:
            published = self.plan_cond.wait_for(lambda: any(self.points(p) == points for p in self.plans),
                                                timeout=RESULT_WAIT_S)
        self.assertTrue(published, f"the plan was not published on ~plan within {RESULT_WAIT_S} s")

    def test_goal_in_another_frame_is_transformed(self):
        # odom starts at the robot's start pose (1, 1, 0): odom (2, 0.5) is map (3, 1.5)
        state, result = self.ask(goal_msg(2.0, 0.5, frame="odom"))
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.message)
        x, y = self.points(result.plan)[-1]
        self.assertAlmostEqual(x, 3.0, delta=1e-6)
        self.assertAlmostEqual(y, 1.5, delta=1e-6)

    def test_nan_position(self):
        self.assert_fails(goal_msg(float("nan"), 1.0), R.FAILURE, "not finite")

    def test_inf_position(self):
        self.assert_fails(goal_msg(2.0, float("inf")), R.FAILURE, "not finite")

    def test_nan_orientation(self):
        self.assert_fails(goal_msg(2.0, 1.0, q=(0.0, 0.0, float("nan"), 1.0)), R.FAILURE, "not finite")

    def test_unnormalised_quaternion(self):
        self.assert_fails(goal_msg(2.0, 1.0, q=(0.0, 0.0, 0.0, 2.0)), R.FAILURE, "not normalised")

    def test_zero_quaternion(self):
        self.assert_fails(goal_msg(2.0, 1.0, q=(0.0, 0.0, 0.0, 0.0)), R.FAILURE, "not normalised")

    def test_empty_frame(self):
        self.assert_fails(goal_msg(2.0, 1.0, frame=""), R.FAILURE, "frame_id is empty")

    def test_unknown_frame(self):
        self.assert_fails(goal_msg(2.0, 1.0, frame="mars"), R.FAILURE, "'mars' cannot be transformed")

    def test_outside_the_map(self):
        self.assert_fails(goal_msg(20.0, 1.0), R.FAILURE, "outside the costmap")

    def test_goal_in_obstacle_beyond_tolerance(self):
        self.assert_fails(goal_msg(2.0, 3.5), R.EMPTY, "GOAL_BLOCKED")

    def test_goal_in_obstacle_within_tolerance_moves(self):
        state, result = self.ask(goal_msg(1.42, 3.5))  # 0.08 m from the block: inscribed, 0.3 m tolerance
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.message)
        self.assertIn("goal moved", result.message)
        x, y = self.points(result.plan)[-1]
        self.assertLessEqual(math.hypot(x - 1.42, y - 3.5), 0.3 + 1e-6)
        self.assert_on_free_cells(result.plan)

    def test_unreachable_goal(self):
        self.assert_fails(goal_msg(6.5, 3.75), R.EMPTY, "NO_PATH")

    def test_no_map(self):
        self.assert_fails(goal_msg(2.0, 1.0), R.FAILURE, "no map yet", server="get_path_no_map")

    def test_no_robot_transform(self):
        self.assert_fails(goal_msg(2.0, 1.0), R.FAILURE, "robot pose unknown", server="get_path_no_tf")

    def test_back_to_back_goals_all_end(self):
        handles = []
        ac = actionlib.ActionClient("get_path_server", GetPathAction)
        self.assertTrue(ac.wait_for_server(rospy.Duration(SERVER_WAIT_S)))
        for index in range(10):
            handles.append(ac.send_goal(goal_msg(2.0 + 0.1 * index, 1.5)))
        deadline = rospy.Time.now() + rospy.Duration(RESULT_WAIT_S)
        terminal = (GoalStatus.SUCCEEDED, GoalStatus.PREEMPTED, GoalStatus.RECALLED, GoalStatus.ABORTED)
        while rospy.Time.now() < deadline and not all(h.get_goal_status() in terminal for h in handles):
            rospy.sleep(0.02)
        states = [h.get_goal_status() for h in handles]
        self.assertTrue(all(s in terminal for s in states), states)
        self.assertEqual(states[-1], GoalStatus.SUCCEEDED)
        self.assertNotIn(GoalStatus.ABORTED, states)
        self.assert_still_serving()

    def test_clear_costmap(self):
        client = ActionClientProxy("get_path_server/clear_costmap", ClearCostmapAction)
        self.assertTrue(client.is_available(SERVER_WAIT_S))
        client.send_goal(ClearCostmapGoal())
        self.assertTrue(client.wait_for_result(RESULT_WAIT_S))
        self.assertEqual(client.result().code, ClearCostmapResult.SUCCESS, client.result().message)
        self.assert_still_serving()


if __name__ == "__main__":
    init_node("test_get_path", master_timeout_s=SERVER_WAIT_S)
    rostest.rosrun("flex_nav", "test_get_path", TestGetPath, sys.argv)
