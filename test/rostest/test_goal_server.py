#!/usr/bin/env python3
"""rostest node: flex_nav.ros.goal_server.GoalServer through a real master (goal_server.test).

The server runs in this node with scripted ``run`` behaviours chosen by the goal's path length."""

import sys
import threading
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from readiness import wait_until_active

from flex_nav.action_types import action_type
from flex_nav.msg import FollowPathAction, FollowPathGoal, FollowPathResult
from flex_nav.ros.goal_server import GoalOutcome, GoalServer
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import ActionClientProxy

WAIT_S = 10.0  # [s]
BURST_GOALS = 30  # goals sent back to back before the one that succeeds
SUCCEED, RAISE, FORGET, WAIT = 1, 2, 3, 4  # behaviour = number of poses in the goal path


def goal(behaviour):
    path = Path()
    path.poses = [PoseStamped() for _ in range(behaviour)]
    return FollowPathGoal(path=path)


class Script:
    def __init__(self):
        self.events = []
        self.lock = threading.Lock()
        self.server = GoalServer("scripted", action_type("FollowPath"), self.run, self.on_cancel, self.on_error)
        self.server.start()

    def log(self, *event):
        with self.lock:
            self.events.append(event)

    def run(self, ticket):
        behaviour = len(ticket.goal.path.poses)
        self.log("run", ticket.number, threading.current_thread().name)
        if behaviour == SUCCEED:
            self.server.finish(ticket, GoalOutcome.SUCCEEDED, self.server.result("SUCCESS", "done"))
        elif behaviour == RAISE:
            raise ValueError("boom")
        elif behaviour == WAIT:
            ticket.cancelled.wait(WAIT_S)
            self.log("run saw cancel", ticket.number, ticket.cancelled.is_set())
        # FORGET: return without a result

    def on_cancel(self, ticket, replaced):
        self.log("cancel", ticket.number, replaced, self.server.server.is_active())

    def on_error(self, ticket, error):
        self.log("error", ticket.number, repr(error))


class TestGoalServer(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.script = Script()
        cls.client = ActionClientProxy("scripted", FollowPathAction)
        assert cls.client.is_available(WAIT_S)

    def send(self, behaviour):
        self.client.send_goal(goal(behaviour))

    def result(self):
        self.assertTrue(self.client.wait_for_result(WAIT_S))
        return self.client.state(), self.client.result()

    def test_success_runs_on_the_worker_thread(self):
        self.send(SUCCEED)
        state, result = self.result()
        self.assertEqual((state, result.code, result.message), (GoalStatus.SUCCEEDED, FollowPathResult.SUCCESS, "done"))
        runs = [e for e in self.script.events if e[0] == "run"]
        self.assertTrue(runs and runs[-1][2].startswith("goals:"), runs)

    def test_exception_aborts_with_reason_after_the_error_hook(self):
        self.send(RAISE)
        state, result = self.result()
        self.assertEqual(state, GoalStatus.ABORTED)
        self.assertEqual(result.code, FollowPathResult.FAILURE)
        self.assertEqual(result.message, "internal error: ValueError('boom')")
        self.assertIn("ValueError('boom')", [e[2] for e in self.script.events if e[0] == "error"])
        self.send(SUCCEED)
        self.assertEqual(self.result()[0], GoalStatus.SUCCEEDED, "the server must keep serving")

    def test_run_without_result_is_aborted(self):
        self.send(FORGET)
        state, result = self.result()
        self.assertEqual(state, GoalStatus.ABORTED)
        self.assertEqual(result.message, "the server ended without a result")

    def test_cancel_calls_hook_while_the_goal_is_still_active(self):
        self.send(WAIT)
        wait_until_active(self.client, WAIT_S)
        self.client.cancel()
        state, result = self.result()
        self.assertEqual(state, GoalStatus.PREEMPTED)
        self.assertEqual((result.code, result.message), (FollowPathResult.PREEMPT, "preempted"))
        cancels = [e for e in self.script.events if e[0] == "cancel"]
        self.assertEqual(cancels[-1][2:], (False, True))  # not replaced; hook ran before the goal ended
        deadline = rospy.get_time() + WAIT_S
        while rospy.get_time() < deadline and not any(
                e[0] == "run saw cancel" and e[1] == cancels[-1][1] for e in self.script.events):
            rospy.sleep(0.02)
        self.assertIn(("run saw cancel", cancels[-1][1], True), self.script.events)

    def test_newer_goal_replaces_the_running_one(self):
        first = ActionClientProxy("scripted", FollowPathAction)
        self.assertTrue(first.is_available(WAIT_S))
        first.send_goal(goal(WAIT))
        wait_until_active(first, WAIT_S)
        self.send(SUCCEED)
        self.assertTrue(first.wait_for_result(WAIT_S))
        self.assertEqual(first.state(), GoalStatus.PREEMPTED)
        self.assertEqual(first.result().code, FollowPathResult.PREEMPT)
        self.assertEqual(first.result().message, "replaced by a newer goal")
        self.assertEqual(self.result()[0], GoalStatus.SUCCEEDED)
        self.assertEqual([e for e in self.script.events if e[0] == "cancel"][-1][2], True)

    def test_back_to_back_goals_all_end_and_the_last_succeeds(self):
        handles = []
        # actionlib's client publishes goals with a drop-oldest queue of 10 (actionlib_client_pub_queue_size): in
        # CI (2026-12-07) the oldest 12 of this burst of 31 were never acknowledged, most likely dropped there
        # before they left this process (not reproduced locally); the queue holds the whole burst
        rospy.set_param("actionlib_client_pub_queue_size", BURST_GOALS + 1)
        self.addCleanup(rospy.delete_param, "actionlib_client_pub_queue_size")
        client = actionlib.ActionClient("scripted", FollowPathAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(WAIT_S)))
        for _ in range(BURST_GOALS):
            handles.append(client.send_goal(goal(WAIT)))
        handles.append(client.send_goal(goal(SUCCEED)))
        deadline = rospy.get_time() + WAIT_S
        while rospy.get_time() < deadline and any(h.get_comm_state() != actionlib.CommState.DONE for h in handles):
            rospy.sleep(0.02)
        states = [h.get_goal_status() for h in handles]
        self.assertTrue(all(h.get_comm_state() == actionlib.CommState.DONE for h in handles), states)
        self.assertEqual(states[-1], GoalStatus.SUCCEEDED)
        self.assertTrue(all(s in (GoalStatus.PREEMPTED, GoalStatus.RECALLED) for s in states[:-1]), states)


if __name__ == "__main__":
    init_node("test_goal_server", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_goal_server", TestGoalServer, sys.argv)
