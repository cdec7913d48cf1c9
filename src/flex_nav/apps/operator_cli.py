"""``rosrun flex_nav operator``: watch a behavior runner and answer it from a terminal.

Usage::

    operator [--runner NAME] watch                      print status, active states, requests, log, transitions
    operator [--runner NAME] status                     print the current status and active states once
    operator [--runner NAME] approve-next [--timeout S] [--outcome O]
                                                        wait for the next outcome request and approve it
    operator [--runner NAME] COMMAND [ARGS...]          send a command and print the runner's answer:
        start NAME [autonomy=LEVEL] [PARAM=VALUE ...] | stop | autonomy LEVEL | approve PATH [OUTCOME]
        force PATH OUTCOME | pause | resume | preempt | lock PATH | unlock PATH

``--runner`` is the runner node's name (default ``behavior_runner``, resolved in the current namespace).
Exit status: 0 when the command was applied, 1 when the runner refused it, 2 when no answer came in time.
``start`` prints the runner's first answer ("ok: loading NAME ...") and waits for the final one (started or
refused), at most ``--timeout`` plus the runner's load bound (LOAD_TIMEOUT_S, 10 s).
"""

from __future__ import annotations

import argparse
import queue
import sys
import time
from typing import Any, List, Optional

import rospy

from flex_nav.msg import (
    BehaviorActivity,
    BehaviorCommand,
    BehaviorCommandFeedback,
    BehaviorLog,
    BehaviorStatus,
    BehaviorTransition,
)
from flex_nav.nodes.behavior_runner import LOAD_TIMEOUT_S, BehaviorRunner
from flex_nav.ros.node import init_node
from flex_nav.ros.operator_interface import status_name

ANSWER_TIMEOUT_S = 5.0  # [s] default wait for the runner's feedback
LEVEL_NAMES = ("Off", "Low", "High", "Full")
LOG_LEVELS = {0: "INFO", 1: "WARN", 2: "HINT", 3: "ERROR", 10: "DEBUG"}


def _latest(topic: str, msg_type: type, timeout_s: float) -> Optional[Any]:
    try:
        return rospy.wait_for_message(topic, msg_type, timeout=timeout_s)
    except rospy.ROSException:
        return None


def send_command(runner: str, command: str, args: List[str], timeout_s: float) -> int:
    """Send one command and print the runner's final answer. A ``start`` is answered twice: at once with
    ``pending`` true ("loading ..."), printed as it comes, then when the load ends; after the first answer the
    wait is extended by the runner's load bound (LOAD_TIMEOUT_S) so that the final answer is always awaited."""
    answers: queue.Queue[BehaviorCommandFeedback] = queue.Queue()

    def on_feedback(msg: BehaviorCommandFeedback) -> None:
        if msg.command == command and list(msg.args) == args:
            answers.put(msg)

    sub = rospy.Subscriber(f"{runner}/command_feedback", BehaviorCommandFeedback, on_feedback)
    pub = rospy.Publisher(f"{runner}/command", BehaviorCommand, queue_size=1)
    deadline = time.monotonic() + timeout_s
    while pub.get_num_connections() == 0 or sub.get_num_connections() == 0:
        if time.monotonic() > deadline:
            print(f"no behavior runner listens on {rospy.resolve_name(runner)}/command", file=sys.stderr)
            return 2
        time.sleep(0.02)
    pub.publish(BehaviorCommand(command=command, args=args))
    extended = False
    while True:
        try:
            msg = answers.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            print(f"no {'final ' if extended else ''}answer from {rospy.resolve_name(runner)} within "
                  f"{timeout_s + (LOAD_TIMEOUT_S if extended else 0.0):.1f} s", file=sys.stderr)
            return 2
        if not msg.pending:
            break
        print(f"{'ok' if msg.ok else 'refused'}: {msg.message}", flush=True)
        if not extended:  # the runner answers finally within its load bound
            deadline, extended = deadline + LOAD_TIMEOUT_S, True
    print(f"{'ok' if msg.ok else 'refused'}: {msg.message}")
    return 0 if msg.ok else 1


def approve_next(runner: str, outcome: Optional[str], timeout_s: float) -> int:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline and not rospy.is_shutdown():
        activity = _latest(f"{runner}/activity", BehaviorActivity, min(1.0, max(0.05, deadline - time.monotonic())))
        if activity is not None:
            for request in activity.requests:
                if outcome is None or request.outcome == outcome:
                    print(f"approving {request.path} -> {request.outcome} (needs {LEVEL_NAMES[request.required]})")
                    return send_command(runner, "approve", [request.path, request.outcome], ANSWER_TIMEOUT_S)
        time.sleep(0.05)
    print(f"no outcome request from {rospy.resolve_name(runner)} within {timeout_s:.1f} s", file=sys.stderr)
    return 2


def print_status(runner: str, timeout_s: float) -> int:
    status = _latest(f"{runner}/status", BehaviorStatus, timeout_s)
    if status is None:
        print(f"no status from {rospy.resolve_name(runner)} within {timeout_s:.1f} s", file=sys.stderr)
        return 2
    print(f"{status.behavior or '-'}: {status_name(status.code)} {status.outcome} {status.reason}".rstrip())
    activity = _latest(f"{runner}/activity", BehaviorActivity, 1.0)
    if activity is not None:
        print(f"autonomy {LEVEL_NAMES[min(activity.autonomy, 3)]}; active: {', '.join(activity.active_paths) or '-'}")
        for request in activity.requests:
            print(f"  waits for operator: {request.path} -> {request.outcome} ({request.reason})")
    return 0


def watch(runner: str) -> int:
    def on_status(msg: BehaviorStatus) -> None:
        print(f"[status] {msg.behavior or '-'} {status_name(msg.code)} {msg.outcome} {msg.reason}".rstrip())

    def on_activity(msg: BehaviorActivity) -> None:
        waits = "; ".join(f"{r.path} -> {r.outcome} waits ({r.reason})" for r in msg.requests)
        print(f"[active] {', '.join(msg.active_paths) or '-'}" + (f" | {waits}" if waits else ""))

    def on_log(msg: BehaviorLog) -> None:
        print(f"[{LOG_LEVELS.get(msg.level, msg.level)}] {msg.path}: {msg.text}")

    def on_transition(msg: BehaviorTransition) -> None:
        print(f"[transition] {msg.path} --{msg.outcome}--> {msg.target}{' (forced)' if msg.forced else ''}")

    subscribers = [
        rospy.Subscriber(f"{runner}/status", BehaviorStatus, on_status),
        rospy.Subscriber(f"{runner}/activity", BehaviorActivity, on_activity),
        rospy.Subscriber(f"{runner}/log", BehaviorLog, on_log),
        rospy.Subscriber(f"{runner}/transitions", BehaviorTransition, on_transition),
    ]
    rospy.spin()
    del subscribers
    return 0


def main(argv: Optional[List[str]] = None) -> int:
    argv = rospy.myargv(sys.argv)[1:] if argv is None else argv
    parser = argparse.ArgumentParser(prog="operator", description="Watch and command a flex_nav behavior runner.")
    parser.add_argument("--runner", default="behavior_runner", help="runner node name (default: %(default)s)")
    parser.add_argument("--timeout", type=float, default=ANSWER_TIMEOUT_S, help="[s] wait for an answer")
    parser.add_argument("--outcome", default=None, help="approve-next: only approve this outcome")
    choices = ("watch", "status", "approve-next", *BehaviorRunner.COMMANDS)
    parser.add_argument("command", choices=choices)
    parser.add_argument("args", nargs="*")
    options = parser.parse_args(argv)
    init_node("operator", anonymous=True)
    if options.command == "watch":
        return watch(options.runner)
    if options.command == "status":
        return print_status(options.runner, options.timeout)
    if options.command == "approve-next":
        return approve_next(options.runner, options.outcome, options.timeout)
    return send_command(options.runner, options.command, list(options.args), options.timeout)
