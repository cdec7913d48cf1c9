#!/usr/bin/env python3
"""rostest node: a FlexBE state library (imported through `flexbe_core` = flex_nav.compat.flexbe_core) runs unmodified
in flex_nav's executor against real action servers, topics and a real master; the FlexBE proxies' connections are
process-wide, as in FlexBE; a behavior in the FlexBE App's generated layout runs under behavior_runner."""

import sys
import threading
import unittest
from pathlib import Path

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path as PathMsg
from readiness import poll_until
from std_msgs.msg import Int32
from std_srvs.srv import Trigger, TriggerRequest

from flex_nav.behavior import Autonomy, BehaviorContext, BehaviorExecutor, BehaviorStatus, using_context
from flex_nav.compat import install_aliases
from flex_nav.compat.flexbe_core.proxy import process_proxies
from flex_nav.exceptions import NotReadyError
from flex_nav.msg import BehaviorStatus as BehaviorStatusMsg
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
    """One behavior with its context, optionally run in a thread; its FlexBE proxies use the process-wide
    connections (``proxies``)."""

    def __init__(self, behavior_class, parameters=None, inputs=None, name="behavior"):
        self.proxies = process_proxies()
        self.context = BehaviorContext(name, autonomy=Autonomy.FULL, proxies=self.proxies)
        self.logs = []
        self.context.hooks.log.append(self.logs.append)
        self.behavior = build_behavior(behavior_class, context=self.context, parameters=parameters or {})
        self.executor = BehaviorExecutor(self.behavior, context=self.context, inputs=inputs or {})
        self.result = None
        self._thread = None

    def run(self):
        self.result = self.executor.run(timeout_s=WAIT_S)
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

    def test_two_behaviors_in_one_process_share_the_action_client_as_in_flexbe(self):
        """Both behaviors use the same server: with FlexBE's process-wide proxies they share one client, so the second
        behavior's goal replaces the first's (FlexBE semantics, kept by the compat layer on purpose)."""
        first = Run(PlanAndFollowSM, parameters={"follower_topic": "slow_follow"}, inputs={"goal": goal_pose()})
        second = Run(PlanAndFollowSM, parameters={"follower_topic": "slow_follow"}, inputs={"goal": goal_pose()})
        client = first.proxies.get_action_client("slow_follow")
        self.assertIs(client, second.proxies.get_action_client("slow_follow"))
        first.start()
        self.assertTrue(wait_for(lambda: client.state() == GoalStatus.ACTIVE))
        first.executor.preempt()
        self.assertIs(first.join().status, BehaviorStatus.PREEMPTED)
        self.assertTrue(wait_for(lambda: client.state() == GoalStatus.PREEMPTED))

    def test_generated_behavior_runs_under_behavior_runner(self):
        statuses = []
        rospy.Subscriber("/flexbe_generated/behavior_runner/status", BehaviorStatusMsg, statuses.append)
        self.assertTrue(
            wait_for(lambda: any(m.code == BehaviorStatusMsg.FINISHED for m in list(statuses))),
            [(m.behavior, m.code, m.reason) for m in statuses],
        )
        finished = [m for m in list(statuses) if m.code == BehaviorStatusMsg.FINISHED][-1]
        self.assertEqual((finished.behavior, finished.outcome), ("Hello FlexBE", "finished"))

    def test_publisher_state_of_one_behavior_reaches_subscriber_state_of_another(self):
        listener = Run(ListenSM, parameters={"topic": "compat_chatter"}, name="listener")
        talker = Run(ExampleSM, parameters={"topic": "compat_chatter", "limit": 1}, name="talker")
        self.assertIs(listener.proxies, talker.proxies)  # one set per process, as in FlexBE
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
        proxies = RosProxies()  # the behavior's own connections: the FlexBE proxies do not use them
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
                pub.publish("compat_numbers", Int32(4))
                self.assertTrue(wait_for(lambda: sub.get_last_msg("compat_numbers").data == 4))
                self.assertFalse(sub.has_buffered("compat_numbers"))
                sub.unsubscribe_topic("compat_numbers")  # gone for the whole process, as in FlexBE
                self.assertFalse(sub.is_available("compat_numbers"))
                self.assertIsNone(proxies.get_subscription("compat_numbers"))

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
