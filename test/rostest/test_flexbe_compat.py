#!/usr/bin/env python3
"""rostest node: a FlexBE state library (imported through `flexbe_core` = flex_nav.compat.flexbe_core) runs unmodified
in flex_nav's executor against real action servers, topics and a real master; two behaviors in one process keep
separate connections."""

import sys
import threading
import time
import unittest
from pathlib import Path

import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path as PathMsg
from readiness import poll_until
from std_msgs.msg import Int32
from std_srvs.srv import Trigger, TriggerRequest

from flex_nav.behavior import Autonomy, BehaviorContext, BehaviorExecutor, BehaviorStatus, using_context
from flex_nav.compat import install_aliases
from flex_nav.exceptions import NotReadyError
from flex_nav.msg import GetPathAction, GetPathGoal
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import RosProxies

WAIT_S = 20.0  # [s] bound of every wait; never reached when things work
DATA_DIR = Path(__file__).resolve().parents[1] / "data" / "compat"

install_aliases(["flexbe_core"])
sys.path.insert(0, str(DATA_DIR))
from example_flexbe_states.example_behaviors import ExampleSM, ListenSM, PlanAndFollowSM  # noqa: E402
from flexbe_core import build_behavior  # noqa: E402
from flexbe_core.proxy import (  # noqa: E402
    ProxyActionClient,
    ProxyPublisher,
    ProxyServiceCaller,
    ProxySubscriberCached,
)


def wait_for(predicate, timeout_s=WAIT_S):
    return poll_until(predicate, timeout_s)


def goal_pose():
    pose = PoseStamped()
    pose.header.frame_id = "map"
    pose.pose.position.x = 1.0
    pose.pose.orientation.w = 1.0
    return pose


class Run:
    """One behavior with its own RosProxies and context, optionally run in a thread."""

    def __init__(self, behavior_class, parameters=None, inputs=None, name="behavior"):
        self.proxies = RosProxies()
        self.context = BehaviorContext(name, autonomy=Autonomy.FULL, proxies=self.proxies)
        self.logs = []
        self.context.hooks.log.append(self.logs.append)
        self.behavior = build_behavior(behavior_class, context=self.context, parameters=parameters or {})
        self.executor = BehaviorExecutor(self.behavior, context=self.context, inputs=inputs or {})
        self.result = None
        self._thread = None

    def run(self):
        try:
            self.result = self.executor.run(timeout_s=WAIT_S)
        finally:
            self.proxies.shutdown()
        return self.result

    def start(self):
        self._thread = threading.Thread(target=self.run, daemon=True)
        self._thread.start()

    def join(self):
        self._thread.join(WAIT_S)
        return self.result

    def messages(self):
        return [(e.level.name, e.message) for e in self.logs]


class TestFlexBECompat(unittest.TestCase):
    def test_get_path_and_follow_path_states_reach_the_servers(self):
        run = Run(PlanAndFollowSM, inputs={"goal": goal_pose()})
        result = run.run()
        self.assertIs(result.status, BehaviorStatus.FINISHED, result.reason)
        self.assertEqual(result.outcome, "finished")
        self.assertIsInstance(result.outputs["plan"], PathMsg)

    def test_failing_server_gives_the_failed_outcome_with_its_reason(self):
        run = Run(PlanAndFollowSM, parameters={"planner_topic": "failing_get_path"}, inputs={"goal": goal_pose()})
        result = run.run()
        self.assertIs(result.status, BehaviorStatus.FINISHED, result.reason)
        self.assertEqual(result.outcome, "failed")
        self.assertIn(("WARN", "GetPath failed: no path to the goal"), run.messages())

    def test_preempt_cancels_the_goal_on_the_server_in_on_exit(self):
        run = Run(PlanAndFollowSM, parameters={"follower_topic": "slow_follow"}, inputs={"goal": goal_pose()})
        client = run.proxies.get_action_client("slow_follow")
        run.start()
        self.assertTrue(wait_for(lambda: client.state() == GoalStatus.ACTIVE))
        run.executor.preempt()
        result = run.join()
        self.assertIs(result.status, BehaviorStatus.PREEMPTED, result.reason)
        self.assertTrue(wait_for(client.has_result))
        self.assertEqual(client.state(), GoalStatus.PREEMPTED)
        self.assertIn(("INFO", "Cancelled active action goal."), run.messages())

    def test_two_behaviors_in_one_process_keep_separate_action_clients(self):
        """Both behaviors use the same server (a SimpleActionServer: a new goal preempts the previous one). With
        shared clients (FlexBE), the first behavior would see the second's goal as its own and, leaving, cancel it."""
        first = Run(PlanAndFollowSM, parameters={"follower_topic": "slow_follow"}, inputs={"goal": goal_pose()})
        second = Run(PlanAndFollowSM, parameters={"follower_topic": "slow_follow"}, inputs={"goal": goal_pose()})
        first_client = first.proxies.get_action_client("slow_follow")
        second_client = second.proxies.get_action_client("slow_follow")
        self.assertIsNot(first_client, second_client)
        first.start()
        self.assertTrue(wait_for(lambda: first_client.state() == GoalStatus.ACTIVE))
        second.start()
        self.assertTrue(wait_for(lambda: second_client.state() == GoalStatus.ACTIVE))
        first_result = first.join()  # its goal was preempted by the server for the second's: Follow fails
        self.assertIs(first_result.status, BehaviorStatus.FINISHED, first_result.reason)
        self.assertEqual(first_result.outcome, "failed")
        self.assertEqual(first_client.state(), GoalStatus.PREEMPTED)
        time.sleep(0.3)  # give a wrongly shared cancel time to arrive (not a timing assertion)
        self.assertTrue(second_client.is_active())
        self.assertIs(second.executor.status, BehaviorStatus.RUNNING)
        second.executor.preempt()
        self.assertIs(second.join().status, BehaviorStatus.PREEMPTED)
        self.assertTrue(wait_for(lambda: second_client.state() == GoalStatus.PREEMPTED))

    def test_publisher_state_of_one_behavior_reaches_subscriber_state_of_another(self):
        listener = Run(ListenSM, parameters={"topic": "compat_chatter"}, name="listener")
        talker = Run(ExampleSM, parameters={"topic": "compat_chatter", "limit": 1}, name="talker")
        self.assertIsNot(listener.proxies, talker.proxies)
        publisher = talker.proxies.get_publisher("compat_chatter")
        self.assertTrue(wait_for(lambda: publisher.get_num_connections() >= 1))
        listener.start()
        talked = talker.run()
        self.assertIs(talked.status, BehaviorStatus.FINISHED, talked.reason)
        heard = listener.join()
        self.assertIs(heard.status, BehaviorStatus.FINISHED, heard.reason)
        self.assertEqual(heard.outputs["message"].data, "hello")
        self.assertEqual(listener.messages(), [("HINT", "listening")])

    def test_flexbe_proxy_methods_on_real_connections(self):
        proxies = RosProxies()
        ctx = BehaviorContext("proxy_methods", proxies=proxies)
        logs = []
        ctx.hooks.log.append(logs.append)
        received = []
        try:
            with using_context(ctx):
                pub = ProxyPublisher({"compat_numbers": Int32})
                sub = ProxySubscriberCached()
                sub.subscribe("compat_numbers", Int32, callback=received.append, buffered=True)
                self.assertTrue(pub.wait_for_any("compat_numbers", timeout=WAIT_S))
                for value in (1, 2, 3):
                    pub.publish("compat_numbers", Int32(value))
                self.assertTrue(wait_for(lambda: len(received) == 3))
                self.assertEqual(sub.get_last_msg("compat_numbers").data, 3)
                self.assertEqual([sub.get_from_buffer("compat_numbers").data for _ in range(3)], [1, 2, 3])
                self.assertFalse(sub.has_buffered("compat_numbers"))
                sub.disable_buffer("compat_numbers")
                sub.unsubscribe_topic("compat_numbers")
                pub.publish("compat_numbers", Int32(4))
                self.assertTrue(wait_for(lambda: sub.get_last_msg("compat_numbers").data == 4))
                self.assertEqual(len(received), 3)  # the callback is gone, the cache still works
                self.assertFalse(sub.has_buffered("compat_numbers"))

                client = ProxyActionClient({"get_path": GetPathAction}, wait_duration=WAIT_S)
                self.assertTrue(client.is_available("get_path"))
                client.send_goal("get_path", GetPathGoal(pose=goal_pose()))
                self.assertTrue(wait_for(lambda: client.has_result("get_path")))
                self.assertEqual(client.get_state("get_path"), GoalStatus.SUCCEEDED)
                client.remove_result("get_path")
                self.assertFalse(client.has_result("get_path"))

                caller = ProxyServiceCaller({"no_such_service": Trigger}, wait_duration=0.5)
                self.assertFalse(caller.is_available("no_such_service"))
                with self.assertRaises(NotReadyError):
                    caller.call("no_such_service", TriggerRequest())
        finally:
            proxies.shutdown()
        self.assertIn("Service client no_such_service timed out", " ".join(e.message for e in logs))


if __name__ == "__main__":
    init_node("test_flexbe_compat", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_flexbe_compat", TestFlexBECompat, sys.argv)
