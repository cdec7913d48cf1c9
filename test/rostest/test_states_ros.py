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

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry, Path

from flex_nav.behavior import BehaviorExecutor, BehaviorStatus, LogLevel, StateMachine
from flex_nav.msg import ClearCostmapAction, ClearCostmapActionResult, FollowPathAction
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
SERVER_WAIT_S = 30.0  # [s] bound on a server node coming up
STOP_WAIT_S = 5.0  # [s] bound on odometry showing the robot stopped


def run(root, inputs=None, preempt_once_active=None, proxies=None):
    """Run ``root`` with ``proxies`` (default: fresh ones); returns (result, logs, proxies), to be shut down after.

    ``preempt_once_active``: (action name, action class); the behavior is preempted once its goal there is ACTIVE.
    """
    proxies = proxies if proxies is not None else RosProxies()
    executor = BehaviorExecutor(root, inputs=inputs, clock=RosClock(), proxies=proxies)
    logs = []
    executor.context.hooks.log.append(logs.append)
    done = threading.Event()
    watcher = None
    if preempt_once_active is not None:
        client = proxies.action_client(*preempt_once_active)  # the client the state will use
        watcher = threading.Thread(target=preempt_when_active, args=(executor, client, done), daemon=True)
        watcher.start()
    try:
        result = executor.run(timeout_s=RUN_TIMEOUT_S)
    finally:
        done.set()
        if watcher is not None:
            watcher.join()
    return result, logs, proxies


def preempt_when_active(executor, client, done):
    """Preempt ``executor`` once the server accepted ``client``'s goal (a cancel before that recalls it); gives up
    when ``done`` is set (the run ended, bounded by RUN_TIMEOUT_S)."""
    while not done.is_set():
        if client.state() == GoalStatus.ACTIVE:
            executor.preempt()
            return
        done.wait(0.01)


def stopped(odom):
    return abs(odom.twist.twist.linear.x) <= 1e-6 and abs(odom.twist.twist.angular.z) <= 1e-6


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
        result, logs, proxies = run(FollowPlannerState(), inputs={"plan": plan},
                                    preempt_once_active=("follow_path_server", FollowPathAction))
        client = proxies.action_client("follow_path_server", FollowPathAction)
        deadline = time.monotonic() + 5.0
        while client.state() != GoalStatus.PREEMPTED and time.monotonic() < deadline:
            time.sleep(0.01)
        state = client.state()
        proxies.shutdown()
        self.assertIs(result.status, BehaviorStatus.PREEMPTED, texts(logs))
        self.assertEqual(state, GoalStatus.PREEMPTED, texts(logs))  # the server saw the cancel and ended the goal
        self.assertTrue(any("goal cancelled" in t for t in texts(logs)), texts(logs))

    def test_clear_costmaps_concurrently(self):
        proxies = RosProxies()
        for name in ("global_clear", "local_clear"):  # the state's 5 s bound includes connecting: connect first
            client = proxies.action_client(name, ClearCostmapAction)
            self.assertTrue(client.is_available(SERVER_WAIT_S), f"{name} did not come up within {SERVER_WAIT_S} s")
        results, lock, subs = {}, threading.Lock(), []
        for name in ("global_clear", "local_clear"):
            def record(msg, name=name):
                with lock:
                    results[name] = msg
            subs.append(rospy.Subscriber(f"{name}/result", ClearCostmapActionResult, record))
        deadline = time.monotonic() + SERVER_WAIT_S
        while any(sub.get_num_connections() == 0 for sub in subs) and time.monotonic() < deadline:
            time.sleep(0.01)
        state = ClearCostmapsState(costmaps=["global_clear", "local_clear"], timeout_s=5.0)
        result, logs, proxies = run(state, proxies=proxies)
        deadline = time.monotonic() + 5.0
        while len(results) < 2 and time.monotonic() < deadline:
            time.sleep(0.01)
        proxies.shutdown()
        for sub in subs:
            sub.unregister()
        self.assertEqual(result.outcome, "done", texts(logs))  # both answered within the state's timeout_s
        with lock:
            first, second = results["global_clear"], results["local_clear"]
        # concurrent: each goal was sent (its goal_id stamp) before the other server (1 s per goal) answered
        self.assertLess(first.status.goal_id.stamp, second.header.stamp, (first, second))
        self.assertLess(second.status.goal_id.stamp, first.header.stamp, (first, second))

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
        deadline = time.monotonic() + STOP_WAIT_S  # odometry of the stopped robot (messages may be in flight)
        while time.monotonic() < deadline and not stopped(odom.last()):
            time.sleep(0.01)
        last = odom.last()
        proxies.shutdown()
        self.assertEqual(result.outcome, "done", texts(logs))
        self.assertTrue(stopped(last), f"odometry did not show the robot stopped within {STOP_WAIT_S} s: {last.twist}")
        self.assertAlmostEqual(last.pose.pose.position.x - start, -0.25, delta=0.03)
        q = last.pose.pose.orientation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        self.assertAlmostEqual(yaw, math.pi / 2, delta=0.08)


if __name__ == "__main__":
    init_node("test_states_ros")
    rostest.rosrun("flex_nav", "test_states_ros", TestStatesRos, sys.argv)
