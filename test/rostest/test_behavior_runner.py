#!/usr/bin/env python3
"""rostest node: a behavior run by behavior_runner at autonomy Low waits for the operator; the operator tool
approves it, preempts it, starts it again by name, and the status / activity / transition topics report it."""

import sys
import time
import unittest

import rospy
import rostest
from message_log import MessageLog
from operator_tool import run_operator

from flex_nav.msg import BehaviorActivity, BehaviorStatus, BehaviorTransition
from flex_nav.ros.node import init_node

WAIT_S = 20.0  # [s]
STATUS_ATTEMPTS = 3  # `operator status` runs before its output must show the pending request
RUNNER = "/behavior_runner"


def operator(*args, timeout_s=30.0):
    """Run the operator tool as a user would; returns (exit code, output)."""
    return run_operator(*args, runner=RUNNER, timeout_s=timeout_s)


class Recorder:
    """What the runner publishes: its status, activity and transitions (waits of at most WAIT_S)."""

    def __init__(self):
        self.status = MessageLog(f"{RUNNER}/status", BehaviorStatus, queue_size=None, wait_s=WAIT_S)
        self.activity = MessageLog(f"{RUNNER}/activity", BehaviorActivity, queue_size=None, wait_s=WAIT_S)
        self.transitions = MessageLog(f"{RUNNER}/transitions", BehaviorTransition, queue_size=None, wait_s=WAIT_S)


class TestBehaviorRunner(unittest.TestCase):
    def test_operator_approves_preempts_and_restarts(self):
        rec = Recorder()
        # 1. At autonomy Low, /Ask's transition (needs High) waits for the operator; /Hold is not entered.
        activity = rec.activity.newest(lambda m: any(r.path == "/Ask" for r in m.requests))
        request = next(r for r in activity.requests if r.path == "/Ask")
        self.assertEqual((request.outcome, request.required, request.reason), ("done", 2, "autonomy"))
        self.assertNotIn("/Hold", activity.active_paths)
        # `operator status` waits only 1 s for the latched activity message: ask again if it came too late
        for _attempt in range(STATUS_ATTEMPTS):
            code, out = operator("status")
            if code == 0 and "waits for operator: /Ask -> done" in out:
                break
        self.assertEqual(code, 0, out)
        self.assertIn("waits for operator: /Ask -> done", out)

        # 2. A wrong command is refused with the valid choices; nothing changes.
        code, out = operator("approve", "/Nowhere")
        self.assertEqual(code, 1, out)
        self.assertIn("refused", out)

        # 3. The operator tool approves: the transition fires and /Hold becomes active.
        code, out = operator("approve-next", "--timeout", "10")
        self.assertEqual(code, 0, out)
        transition = rec.transitions.newest(lambda m: m.path == "/Ask")
        self.assertEqual((transition.outcome, transition.target), ("done", "Hold"))
        rec.activity.newest(lambda m: "/Hold" in m.active_paths)

        # 4. Preempt: status PREEMPTED.
        code, out = operator("preempt")
        self.assertEqual(code, 0, out)
        status = rec.status.newest(lambda m: m.code == BehaviorStatus.PREEMPTED)
        self.assertEqual(status.behavior, "operator_test")
        code, out = operator("pause")
        self.assertEqual(code, 1, out)
        self.assertIn("no behavior is running", out)

        # 5. Start it again by name at runtime (full autonomy, short hold): it finishes by itself.
        code, out = operator("start", "../operator_test.yaml")
        self.assertEqual(code, 1, out)
        self.assertIn("not a file", out)
        code, out = operator("start", "operator_test", "hold_s")
        self.assertEqual(code, 1, out)
        self.assertIn("is not KEY=VALUE", out)
        code, out = operator("start", "operator_test", "no_such_parameter=1")
        self.assertEqual(code, 1, out)
        self.assertIn("no_such_parameter", out)
        code, out = operator("start", "operator_test", "autonomy=full", "hold_s=0.2")
        self.assertEqual(code, 0, out)
        status = rec.status.newest(lambda m: m.code == BehaviorStatus.FINISHED)
        self.assertEqual(status.outcome, "finished")
        codes = [m.code for m in rec.status.since(0)]
        self.assertIn(BehaviorStatus.RUNNING, codes)


class TestFlexBEBehaviorClass(unittest.TestCase):
    def test_flexbe_behavior_class_runs_to_its_outcome(self):
        statuses = []
        rospy.Subscriber("/flexbe/behavior_runner/status", BehaviorStatus, statuses.append)
        deadline = time.monotonic() + WAIT_S
        while time.monotonic() < deadline and not any(m.code == BehaviorStatus.FINISHED for m in list(statuses)):
            time.sleep(0.05)
        finished = [m for m in list(statuses) if m.code == BehaviorStatus.FINISHED]
        self.assertTrue(finished, f"no FINISHED status; got {[(m.behavior, m.code, m.reason) for m in statuses]}")
        self.assertEqual((finished[-1].behavior, finished[-1].outcome), ("Count", "finished"))

    def test_remote_start_of_a_python_class_is_refused(self):
        code, out = operator("start", "py:os:system")
        self.assertEqual(code, 1, out)
        self.assertIn("not a file", out)


class AllRunnerTests(TestBehaviorRunner, TestFlexBEBehaviorClass):
    """Both groups in one rostest node (rostest.rosrun takes one TestCase class)."""


if __name__ == "__main__":
    init_node("test_behavior_runner", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_behavior_runner", AllRunnerTests, sys.argv)
