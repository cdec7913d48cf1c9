#!/usr/bin/env python3
"""rostest node for behavior_load_limits.test (issue 22): a start command gets "loading" at once and its final
answer within a bound, whatever the file; names never reach files outside the search path; a bad ~behavior file
ends the node with exit 2 and a clear message."""

import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest
from pathlib import Path

import rospy
import rostest
from operator_tool import run_operator
from refused_start import run_refused

from flex_nav.msg import BehaviorCommand, BehaviorCommandFeedback, BehaviorStatus
from flex_nav.ros.node import init_node

REPO = Path(__file__).resolve().parents[2]
RUNNER_SCRIPT = REPO / "scripts" / "behavior_runner"
HOSTILE = REPO / "test" / "data" / "hostile_behaviors"
RUNNER = "/load_runner"
WAIT_S = 20.0  # [s] bound on any wait for a message here
BOMB_ANSWERED_WITHIN_S = 2.0  # [s] from the "loading" answer to the refusal of the alias bomb (measured: ms)
SLOW_BUILD_S = 3.0  # [s] slow_load.yaml's constructor time
SECRET = "s3cret-token-0xC0FFEE"
STOP_GRACE_S = 10.0  # [s] for a runner started here to end after SIGINT


def operator(*args, runner=RUNNER, timeout_s=60.0):
    """Run the operator tool as a user would; returns (exit code, output)."""
    return run_operator(*args, runner=runner, timeout_s=timeout_s)


class Recorder:
    """Answers and statuses of the runner, and a publisher of raw commands."""

    def __init__(self):
        self.lock = threading.Lock()
        self.answers = []
        self.statuses = []
        rospy.Subscriber(f"{RUNNER}/command_feedback", BehaviorCommandFeedback, self._add, callback_args=self.answers)
        rospy.Subscriber(f"{RUNNER}/status", BehaviorStatus, self._add, callback_args=self.statuses)
        self.pub = rospy.Publisher(f"{RUNNER}/command", BehaviorCommand, queue_size=10)
        deadline = time.monotonic() + WAIT_S
        while self.pub.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.02)

    def _add(self, msg, into):
        with self.lock:
            into.append(msg)

    def mark(self):
        with self.lock:
            return len(self.answers)

    def send(self, command, *args):
        self.pub.publish(BehaviorCommand(command=command, args=list(args)))

    def answer(self, since, command, args, pending, timeout_s=WAIT_S):
        """The first answer to ``command args`` after answer number ``since`` with this ``pending`` flag."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            with self.lock:
                for msg in self.answers[since:]:
                    if msg.command == command and list(msg.args) == list(args) and msg.pending == pending:
                        return msg
            time.sleep(0.02)
        with self.lock:
            seen = [(m.command, list(m.args), m.pending, m.message) for m in self.answers[since:]]
        raise AssertionError(f"no answer to {command} {args} (pending {pending}) within {timeout_s} s; seen: {seen}")

    def wait_status(self, predicate, timeout_s=WAIT_S):
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            with self.lock:
                if any(predicate(m) for m in self.statuses):
                    return
            time.sleep(0.05)
        raise AssertionError(f"no matching status within {timeout_s} s")


class TestBehaviorLoadLimits(unittest.TestCase):
    rec = None

    @classmethod
    def setUpClass(cls):
        cls.rec = Recorder()

    def start_operator_test(self):
        """The runner still starts a good behavior (and it finishes by itself)."""
        code, out = operator("start", "operator_test", "autonomy=full", "wait_s=0.0", "hold_s=0.2")
        self.assertEqual(code, 0, out)
        self.assertIn("ok: loading behavior 'operator_test'", out)
        self.assertIn("ok: started behavior 'operator_test' at autonomy FULL", out)
        self.rec.wait_status(lambda m: m.behavior == "operator_test" and m.code == BehaviorStatus.FINISHED)

    def test_alias_bomb_is_answered_loading_then_refused_and_the_runner_still_answers(self):
        since = self.rec.mark()
        started = time.monotonic()
        code, out = operator("start", "alias_bomb")
        self.assertEqual(code, 1, out)
        self.assertIn("ok: loading behavior 'alias_bomb'", out)
        self.assertIn("refused: ", out)
        self.assertIn("alias_bomb.yaml", out)
        self.assertIn("limit max_yaml_nodes=50000", out)
        loading = self.rec.answer(since, "start", ["alias_bomb"], pending=True)
        final = self.rec.answer(since, "start", ["alias_bomb"], pending=False)
        self.assertTrue(loading.ok)
        self.assertFalse(final.ok)
        took_s = (final.header.stamp - loading.header.stamp).to_sec()
        print(f"alias bomb: refused {took_s * 1000:.1f} ms after the loading answer "
              f"(operator tool round trip {time.monotonic() - started:.1f} s)", flush=True)
        self.assertLess(took_s, BOMB_ANSWERED_WITHIN_S)
        self.start_operator_test()

    def test_a_non_utf8_file_on_the_search_path_is_refused(self):
        code, out = operator("start", "not_utf8")
        self.assertEqual(code, 1, out)
        self.assertIn("not_utf8.yaml:2: the file is not UTF-8 text", out)
        self.assertNotIn("Traceback", out)

    def test_a_second_start_while_loading_is_refused_and_stop_cancels_the_load(self):
        since = self.rec.mark()
        sent = time.monotonic()
        self.rec.send("start", "slow_load")
        loading = self.rec.answer(since, "start", ["slow_load"], pending=True)
        self.assertTrue(loading.ok, loading.message)
        self.rec.send("start", "operator_test")
        second = self.rec.answer(since, "start", ["operator_test"], pending=False)
        self.assertFalse(second.ok)
        self.assertIn("behavior 'slow_load' is still loading", second.message)
        self.rec.send("stop")
        stop = self.rec.answer(since, "stop", [], pending=False)
        self.assertTrue(stop.ok, stop.message)
        self.assertEqual(stop.message, "cancelled loading behavior 'slow_load'")
        final = self.rec.answer(since, "start", ["slow_load"], pending=False)
        self.assertFalse(final.ok)
        self.assertIn("loading 'slow_load' was cancelled: stopped by the operator", final.message)
        self.assertLess(time.monotonic() - sent, SLOW_BUILD_S, "the checks must run while slow_load still builds")
        time.sleep(max(0.0, sent + SLOW_BUILD_S + 1.0 - time.monotonic()))  # its build has ended meanwhile
        with self.rec.lock:
            started = [m for m in self.rec.statuses if m.behavior == "slow_load"]
        self.assertEqual(started, [], "a cancelled load must never start")
        self.start_operator_test()

    def test_a_start_command_never_reads_the_working_directory(self):
        with tempfile.TemporaryDirectory() as tmp:
            for name in ("notes", "notes.txt", "stolen.yaml"):
                Path(tmp, name).write_text(f"{SECRET}: 1\n")
            log = Path(tmp) / "runner.log"
            with open(log, "w") as out_file:
                proc = subprocess.Popen(
                    [str(RUNNER_SCRIPT), "__name:=cwd_runner", f"_behavior_path:=[{HOSTILE}]"],
                    cwd=tmp, env=dict(os.environ), stdout=out_file, stderr=subprocess.STDOUT,
                )
            try:
                answers = []
                for name in ("notes", "notes.txt", "stolen", "stolen.yaml", "./notes", "a" * 300):
                    code, out = operator("start", name, runner="/cwd_runner")
                    answers.append(out)
                    self.assertEqual(code, 1, out)
                    self.assertNotIn(SECRET, out)
                self.assertIn("'notes' is not valid (valid: alias_bomb, not_utf8, slow_load)", answers[0])
                self.assertIn("not a file or a class", answers[1])
                self.assertIn("300 characters long (at most 128)", answers[5])
            finally:
                proc.send_signal(signal.SIGINT)
                try:
                    proc.wait(STOP_GRACE_S)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait(STOP_GRACE_S)
            self.assertNotIn(SECRET, log.read_text())

    def test_a_non_utf8_behavior_parameter_exits_2_with_a_clear_message(self):
        stderr, _ = run_refused(self, RUNNER_SCRIPT, "bad_file_runner", f"_behavior:={HOSTILE / 'not_utf8.yaml'}")
        self.assertIn("behavior_runner: ", stderr)
        self.assertIn("not_utf8.yaml:2: the file is not UTF-8 text (invalid byte at offset", stderr)


if __name__ == "__main__":
    init_node("test_behavior_load_limits", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_behavior_load_limits", TestBehaviorLoadLimits, sys.argv)
