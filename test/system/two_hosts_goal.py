#!/usr/bin/env python3
"""Operator-side goal sender of the two-host system test: one goal to a behavior runner, then its outcome.

Usage: two_hosts_goal.py ROBOT X Y YAW_DEG [TIMEOUT_S]. Waits until ROBOT's runner (/ROBOT/behavior_runner,
flex_planner) waits for a goal, publishes the goal on /ROBOT/move_base_simple/goal, and waits for the
behavior to be done with it. Prints one line per step with ``time.monotonic()`` (``SENT <wall>``,
``TAKEN <wall>``) and ends with ``ARRIVED <wall>`` (exit 0), ``GAVE UP <state> <wall>`` (exit 1) or the wait
that ran out (exit 2). Every wait is bounded by TIMEOUT_S [s of wall time] (default 90) in all.
"""

from __future__ import annotations

import math
import sys
import threading
import time
from typing import Callable, List

import rospy
from geometry_msgs.msg import PoseStamped

from flex_nav.msg import BehaviorActivity, BehaviorTransition
from flex_nav.ros.node import init_node

GIVEN_UP = ("GiveUp", "NoPath")  # flex_planner's states that drop a goal


def main() -> int:
    robot, x, y, yaw_deg = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
    deadline = time.monotonic() + (float(sys.argv[5]) if len(sys.argv) > 5 else 90.0)
    init_node("two_hosts_goal", anonymous=True)
    runner = f"/{robot}/behavior_runner"
    lock = threading.Lock()
    waiting = threading.Event()
    transitions: List[BehaviorTransition] = []

    def on_activity(msg: BehaviorActivity) -> None:
        if any(path.endswith("/ReceiveGoal") for path in msg.active_paths):
            waiting.set()
        else:
            waiting.clear()

    def on_transition(msg: BehaviorTransition) -> None:
        with lock:
            transitions.append(msg)

    subscribers = [rospy.Subscriber(f"{runner}/activity", BehaviorActivity, on_activity),
                   rospy.Subscriber(f"{runner}/transitions", BehaviorTransition, on_transition, queue_size=100)]
    publisher = rospy.Publisher(f"/{robot}/move_base_simple/goal", PoseStamped, queue_size=1, latch=False)

    def wait(predicate: Callable[[], bool], what: str) -> bool:
        while not predicate():
            if time.monotonic() > deadline or rospy.is_shutdown():
                print(f"NOT WITHIN TIMEOUT: {what}", flush=True)
                return False
            time.sleep(0.02)
        return True

    if not (wait(waiting.is_set, f"{runner} waiting for a goal")
            and wait(lambda: publisher.get_num_connections() > 0, f"{runner} subscribed to the goal topic")
            and wait(lambda: rospy.get_time() > 0.0, "/clock")):
        return 2
    with lock:
        transitions.clear()
    goal = PoseStamped()
    goal.header.frame_id = "map"
    goal.header.stamp = rospy.Time.now()
    goal.pose.position.x, goal.pose.position.y = x, y
    goal.pose.orientation.z = math.sin(math.radians(yaw_deg) / 2.0)
    goal.pose.orientation.w = math.cos(math.radians(yaw_deg) / 2.0)
    publisher.publish(goal)
    print(f"SENT {time.monotonic():.4f} goal ({x:.2f}, {y:.2f}, {yaw_deg:.0f} deg)", flush=True)

    def seen(*targets: str) -> List[BehaviorTransition]:
        with lock:
            return [t for t in transitions if t.target in targets]

    if not wait(lambda: bool(seen("ResetReplans")), "the runner taking the goal (ReceiveGoal -> ResetReplans)"):
        return 2
    print(f"TAKEN {time.monotonic():.4f}", flush=True)
    if not wait(lambda: bool(seen("Arrived", *GIVEN_UP)), "the goal reached or given up"):
        return 2
    outcome = seen("Arrived", *GIVEN_UP)[0]
    del subscribers
    if outcome.target == "Arrived":
        print(f"ARRIVED {time.monotonic():.4f}", flush=True)
        return 0
    print(f"GAVE UP {outcome.target} {time.monotonic():.4f}", flush=True)
    return 1


if __name__ == "__main__":
    sys.exit(main())
