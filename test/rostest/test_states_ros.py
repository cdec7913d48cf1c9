#!/usr/bin/env python3
"""rostest node: flex_nav_states with the real RosProxies and ROS time (namespace robot1).

Checks what the unit tests' fake proxies cannot: goals, cancels and reasons through actionlib, a missing
server bounded in wall time, and closed-loop motion on real odometry messages through a twist_relay.
"""

import math
import sys
import threading
import time
import unittest

import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry, Path

from flex_nav.behavior import BehaviorExecutor, BehaviorStatus, LogLevel, StateMachine
from flex_nav.msg import FollowPathAction
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import RosProxies
from flex_nav.ros.ros_clock import RosClock
from flex_nav_states.clear_costmaps_state import ClearCostmapsState
from flex_nav_states.follow_path_state import FollowPlannerState
from flex_nav_states.get_path_state import GetPathState
from flex_nav_states.goal_list_state import GoalListState
from flex_nav_states.messages import to_stamp
from flex_nav_states.move_distance_state import MoveDistanceState
from flex_nav_states.rotate_angle_state import RotateAngleState

RUN_TIMEOUT_S = 30.0  # [s] bound of every behavior run


def run(root, inputs=None, preempt_after_s=None):
    """Run ``root`` with fresh proxies; returns (result, logs, proxies). Proxies are shut down after."""
    proxies = RosProxies()
    executor = BehaviorExecutor(root, inputs=inputs, clock=RosClock(), proxies=proxies)
    logs = []
    executor.context.hooks.log.append(logs.append)
    timer = None
    if preempt_after_s is not None:
        timer = threading.Timer(preempt_after_s, executor.preempt)
        timer.start()
    try:
        result = executor.run(timeout_s=RUN_TIMEOUT_S)
    finally:
        if timer is not None:
            timer.cancel()
    return result, logs, proxies


def texts(logs, level=LogLevel.INFO):
    return [e.message for e in logs if e.level >= level]


class TestStatesRos(unittest.TestCase):
    def test_get_path_reports_the_server_reason(self):
        sm = StateMachine(outcomes=["planned", "empty", "failed"])
        sm.add("Goal", GoalListState(goals=[[9.0, 9.0, 0.0]]), transitions={"next": "Plan", "done": "failed"})
        sm.add("Plan", GetPathState(), transitions={"planned": "planned", "empty": "empty", "failed": "failed"})
        result, logs, proxies = run(sm)
        proxies.shutdown()
        self.assertEqual(result.outcome, "empty", texts(logs))
        self.assertTrue(any("inside an obstacle" in t for t in texts(logs, LogLevel.WARN)), texts(logs))

    def test_missing_server_fails_within_its_bound(self):
        sm = StateMachine(outcomes=["planned", "failed"])
        sm.add("Goal", GoalListState(goals=[[1.0, 1.0, 0.0]]), transitions={"next": "Plan", "done": "failed"})
        sm.add("Plan", GetPathState(action_name="nobody_serves_this", server_timeout_s=1.0),
               transitions={"planned": "planned", "empty": "failed", "failed": "failed"})
        started = time.monotonic()
        result, logs, proxies = run(sm)
        proxies.shutdown()
        self.assertEqual(result.outcome, "failed")
        self.assertLess(time.monotonic() - started, 10.0)
        self.assertTrue(any("nobody_serves_this" in t and "not available" in t for t in texts(logs, LogLevel.ERROR)))

    def test_preempt_cancels_the_follow_goal_on_the_server(self):
        plan = Path()
        plan.header.frame_id = "map"
        plan.header.stamp = to_stamp(0.0)
        for x in (0.0, 1.0, 2.0):
            pose = PoseStamped()
            pose.header.frame_id = "map"
            pose.pose.position.x = x
            pose.pose.orientation.w = 1.0
            plan.poses.append(pose)
        result, logs, proxies = run(FollowPlannerState(), inputs={"plan": plan}, preempt_after_s=1.5)
        client = proxies.action_client("follow_path_server", FollowPathAction)
        deadline = time.monotonic() + 5.0
        while client.state() != GoalStatus.PREEMPTED and time.monotonic() < deadline:
            time.sleep(0.01)
        state = client.state()
        proxies.shutdown()
        self.assertIs(result.status, BehaviorStatus.PREEMPTED)
        self.assertEqual(state, GoalStatus.PREEMPTED)  # the server saw the cancel and ended the goal
        self.assertTrue(any("goal cancelled" in t for t in texts(logs)), texts(logs))

    def test_clear_costmaps_concurrently(self):
        state = ClearCostmapsState(costmaps=["global_clear", "local_clear"], timeout_s=5.0)
        started = time.monotonic()
        result, logs, proxies = run(state)
        proxies.shutdown()
        self.assertEqual(result.outcome, "done", texts(logs))
        self.assertLess(time.monotonic() - started, 5.0)

    def test_back_up_and_turn_closed_loop_on_odometry(self):
        proxies = RosProxies()
        odom = proxies.subscription("odom", Odometry)
        deadline = time.monotonic() + 10.0
        while not odom.has_msg() and time.monotonic() < deadline:
            time.sleep(0.01)
        self.assertTrue(odom.has_msg(), "no odometry from the kinematic robot")
        start = odom.last().pose.pose.position.x
        sm = StateMachine(outcomes=["done", "failed"])
        sm.add("BackUp", MoveDistanceState(distance_m=-0.25, speed_mps=0.2, frame_id="robot1/base_footprint"),
               transitions={"done": "Turn", "failed": "failed"})
        sm.add("Turn", RotateAngleState(angle_rad=math.pi / 2, angular_speed_radps=1.0),
               transitions={"done": "done", "failed": "failed"})
        executor = BehaviorExecutor(sm, clock=RosClock(), proxies=proxies)
        logs = []
        executor.context.hooks.log.append(logs.append)
        result = executor.run(timeout_s=RUN_TIMEOUT_S)
        time.sleep(0.3)  # let the robot settle on the zero twist
        last = odom.last()
        proxies.shutdown()
        self.assertEqual(result.outcome, "done", texts(logs))
        self.assertAlmostEqual(last.pose.pose.position.x - start, -0.25, delta=0.03)
        q = last.pose.pose.orientation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        self.assertAlmostEqual(yaw, math.pi / 2, delta=0.08)
        self.assertAlmostEqual(last.twist.twist.linear.x, 0.0, delta=1e-6)
        self.assertAlmostEqual(last.twist.twist.angular.z, 0.0, delta=1e-6)


if __name__ == "__main__":
    init_node("test_states_ros")
    rostest.rosrun("flex_nav", "test_states_ros", TestStatesRos, sys.argv)
