#!/usr/bin/env python3
"""rostest node: the per-behavior ROS proxies against a real master and scripted action servers."""

import os
import subprocess
import sys
import time
import unittest

import rosgraph
import rospy
import rostest
from actionlib.action_client import CommState
from actionlib_msgs.msg import GoalStatus
from readiness import poll_until
from std_msgs.msg import Int32, String
from std_srvs.srv import Trigger, TriggerRequest

from flex_nav.exceptions import ConfigError, NotReadyError, TimedOutError
from flex_nav.msg import (
    FollowPathAction,
    FollowPathActionResult,
    FollowPathGoal,
    GetPathAction,
    GetPathGoal,
    GetPathResult,
)
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import RosProxies

WAIT_S = 10.0  # [s]


def wait_for(predicate, timeout_s=WAIT_S):
    return poll_until(predicate, timeout_s)


def _own_topics(kind):
    """Topics this node is registered for at the master (``kind``: 0 publishers, 1 subscribers)."""
    state = rosgraph.Master(rospy.get_name()).getSystemState()
    me = rospy.get_name()
    return {topic for topic, nodes in state[kind] if me in nodes}


def subscribed_topics():
    return _own_topics(1)


def published_topics():
    return _own_topics(0)


class TestProxies(unittest.TestCase):
    def test_publish_and_cached_subscription_with_buffer(self):
        proxies = RosProxies()
        sub = proxies.subscription("chatter", Int32, buffer_size=5)
        pub = proxies.publisher("chatter", Int32)
        self.assertTrue(wait_for(lambda: pub.get_num_connections() > 0))
        for value in range(3):
            pub.publish(Int32(value))
        self.assertTrue(wait_for(lambda: sub.has_msg() and sub.last().data == 2))
        self.assertEqual([sub.pop_buffered().data for _ in range(3)], [0, 1, 2])
        self.assertFalse(sub.has_buffered())
        sub.remove_last()
        self.assertFalse(sub.has_msg())
        self.assertEqual(sub.age_s(), float("inf"))
        proxies.shutdown()

    def test_shutdown_delivers_what_was_published_just_before(self):
        # a state's last command (e.g. the zero twist of its on_exit) is published right before the behavior's
        # proxies shut down; rospy drops what is still queued for a connection when the publisher unregisters.
        # Large messages keep the connection's queue busy, as a loaded machine does.
        received = []
        listener = rospy.Subscriber("last_words", String, lambda msg: received.append(msg.data[:8]), queue_size=100)
        payload = "x" * 2_000_000
        for attempt in range(5):
            proxies = RosProxies()
            publisher = proxies.publisher("last_words", String, queue_size=50)
            self.assertTrue(wait_for(lambda: publisher.get_num_connections() > 0))  # noqa: B023 (called here)
            del received[:]
            for value in range(10):
                publisher.publish(String(f"{value:08d}{payload}"))
            proxies.shutdown()
            self.assertTrue(wait_for(lambda: len(received) == 10, 5.0),
                            f"attempt {attempt}: {len(received)} of 10 messages arrived")
            self.assertEqual(received[-1], f"{9:08d}")
        listener.unregister()

    def test_same_topic_is_shared_and_type_clash_is_refused(self):
        proxies = RosProxies()
        first = proxies.subscription("shared", String)
        self.assertIs(proxies.subscription("shared", String), first)
        with self.assertRaisesRegex(ConfigError, "already used with type String"):
            proxies.subscription("shared", Int32)
        proxies.shutdown()

    def test_wait_for_message_is_bounded(self):
        proxies = RosProxies()
        sub = proxies.subscription("silence", String)
        started = time.monotonic()
        with self.assertRaises(TimedOutError):
            sub.wait_for_message(0.3)
        self.assertLess(time.monotonic() - started, 5.0)
        proxies.shutdown()

    def test_action_client_result_and_reason(self):
        proxies = RosProxies()
        client = proxies.action_client("failing_get_path", GetPathAction)
        client.send_goal(GetPathGoal(), server_timeout_s=WAIT_S)
        self.assertTrue(wait_for(client.has_result))
        self.assertEqual(client.state(), GoalStatus.ABORTED)
        self.assertEqual(client.result().code, GetPathResult.EMPTY)
        self.assertEqual(client.result().message, "no path to the goal")
        proxies.shutdown()

    def test_result_arriving_before_send_returns_is_kept(self):
        # actionlib's SimpleActionClient drops transitions that arrive before its send_goal returns
        # (ros/actionlib#206); a loaded machine can delay the return past a fast server's answer. Delay it here.
        proxies = RosProxies()
        client = proxies.action_client("failing_get_path", GetPathAction)
        actionlib_client = client._client
        real_send = actionlib_client.send_goal
        answered = []

        def send_then_stall(*args, **kwargs):
            handle = real_send(*args, **kwargs)
            answered.append(wait_for(lambda: handle.get_comm_state() == CommState.DONE))
            return handle

        actionlib_client.send_goal = send_then_stall
        for _ in range(3):
            client.send_goal(GetPathGoal(), server_timeout_s=WAIT_S)
            self.assertTrue(answered[-1], "the server did not answer while send_goal stalled")
            self.assertTrue(wait_for(client.has_result, timeout_s=2.0), "the result that came early was lost")
            self.assertEqual(client.state(), GoalStatus.ABORTED)
            self.assertEqual(client.result().message, "no path to the goal")
        proxies.shutdown()

    def test_shutdown_cancels_the_active_goal_and_unregisters_the_client(self):
        results = []
        observer = rospy.Subscriber("slow_follow/result", FollowPathActionResult, results.append, queue_size=10)
        self.assertTrue(wait_for(lambda: observer.get_num_connections() > 0))
        proxies = RosProxies()
        client = proxies.action_client("slow_follow", FollowPathAction)
        client.send_goal(FollowPathGoal(), server_timeout_s=WAIT_S)
        self.assertTrue(wait_for(lambda: client.state() == GoalStatus.ACTIVE))
        self.assertTrue(client.is_active())
        self.assertIn("/slow_follow/status", subscribed_topics())
        proxies.shutdown()
        # the cancel reached the server (the client itself no longer listens: it was unregistered)
        self.assertTrue(wait_for(lambda: any(r.status.status == GoalStatus.PREEMPTED for r in results)))
        observer.unregister()
        # a runner that starts behavior after behavior must not keep every old behavior's action clients
        for topic in ("status", "result", "feedback"):
            self.assertTrue(wait_for(lambda t=topic: f"/slow_follow/{t}" not in subscribed_topics()), topic)
        for topic in ("goal", "cancel"):
            self.assertTrue(wait_for(lambda t=topic: f"/slow_follow/{t}" not in published_topics()), topic)

    def test_two_behaviors_do_not_share_connections(self):
        first, second = RosProxies(), RosProxies()
        a = first.action_client("slow_follow", FollowPathAction)
        b = second.action_client("slow_follow", FollowPathAction)
        self.assertIsNot(a, b)
        a.send_goal(FollowPathGoal(), server_timeout_s=WAIT_S)
        self.assertTrue(wait_for(lambda: a.state() == GoalStatus.ACTIVE))
        second.shutdown()  # must not cancel the first behavior's goal
        time.sleep(0.3)
        self.assertTrue(a.is_active())
        first.shutdown()

    def test_missing_server_and_service_fail_within_bound(self):
        proxies = RosProxies()
        started = time.monotonic()
        with self.assertRaisesRegex(NotReadyError, "no_such_server is not available after 0.5 s"):
            proxies.action_client("no_such_server", GetPathAction).send_goal(GetPathGoal(), server_timeout_s=0.5)
        with self.assertRaisesRegex(NotReadyError, "no_such_service is not available"):
            proxies.service_caller("no_such_service", Trigger).call(TriggerRequest(), timeout_s=0.5)
        self.assertLess(time.monotonic() - started, 10.0)
        proxies.shutdown()

    def test_a_server_that_dies_during_a_goal_is_seen_gone(self):
        """is_available(0) turns False when the server's node dies: the state base fails such a goal
        instead of waiting for it forever."""
        server = subprocess.Popen(["rosrun", "flex_nav", "mock_action_server", "__name:=doomed_follow",
                                   "_action:=FollowPath", "_duration:=30.0"], env=dict(os.environ),
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        proxies = RosProxies()
        try:
            client = proxies.action_client("doomed_follow", FollowPathAction)
            self.assertTrue(client.is_available(WAIT_S), "doomed_follow did not come up")
            client.send_goal(FollowPathGoal(), server_timeout_s=1.0)
            self.assertTrue(wait_for(client.is_active))
            self.assertTrue(client.is_available(0.0))
            server.terminate()
            server.wait(timeout=WAIT_S)
            self.assertTrue(wait_for(lambda: not client.is_available(0.0)), "still 'available' after it died")
        finally:
            if server.poll() is None:
                server.kill()
            proxies.shutdown()


if __name__ == "__main__":
    init_node("test_proxies", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_proxies", TestProxies, sys.argv)
