#!/usr/bin/env python3
"""System scenario: at autonomy Low the Flex Planner waits for the operator before executing its plan; the
operator tool approves and the robot drives; a preempt mid-motion stops the robot.

Usage: operator_scenario.py OUT_DIR. Prints the measured figures and ``SCENARIO PASSED`` (exit 0), or the
check that failed (exit 1). Everything it starts is stopped on exit.
"""

from __future__ import annotations

import contextlib
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any, Callable, List, Optional, Tuple

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from flex_nav.apps import nav_demo
from flex_nav.msg import BehaviorActivity, BehaviorCommandFeedback, BehaviorStatus
from flex_nav.ros.node import init_node
from flex_nav_sim.world import load_world

WAIT_S = 60.0  # [s] wall bound of each wait
UNDER_WAY_MPS = 0.45  # [m/s] ground truth speed of a robot at cruise when preempted (turtlebot2 drives 0.5)
# Real test durations [s] wall: how long the scenario watches that nothing happens (not waits for something)
HELD_WATCH_S = 2.0  # the plan waits for approval: nothing moving is commanded
STOPPED_WATCH_S = 1.0  # after the preempt: nothing moving is commanded after the zero, then the robot stands
RUNNER = "/robot1/behavior_runner"


class ScenarioError(Exception):
    pass


def check(condition: bool, what: str) -> None:
    if not condition:
        raise ScenarioError(what)


def wait_for(predicate: Callable[[], bool], what: str, timeout_s: float = WAIT_S) -> None:
    deadline = time.monotonic() + timeout_s
    while not predicate():
        if time.monotonic() > deadline:
            raise ScenarioError(f"{what}: not within {timeout_s:.0f} s")
        time.sleep(0.02)


def operator(*args: str) -> Tuple[int, str]:
    proc = subprocess.run(["rosrun", "flex_nav", "operator", "--runner", RUNNER, *args],
                          capture_output=True, text=True, timeout=60, check=False)
    return proc.returncode, (proc.stdout + proc.stderr).strip()


def scenario(out: Path) -> None:

    args = nav_demo.parse_args(["--autonomy", "low", "--goals", "g1", "--rtf", "1.0", "--out", str(out)])
    runs = nav_demo.plan_robots(load_world(args.world), args.profile_list, 1, ["g1"])
    with contextlib.ExitStack() as stack:
        processes, _env = nav_demo.start_system(stack, args, runs, out)
        init_node("operator_scenario")

        lock = threading.Lock()
        cmds: List[Tuple[float, float, float]] = []  # (sim time [s], v [m/s], w [rad/s]) as received
        statuses: List[Any] = []
        feedback: List[Any] = []
        activity: List[Any] = []
        speeds: List[float] = []  # [m/s] ground truth forward speed, as received

        def keep(into: List[Any], value: Any) -> None:
            with lock:
                into.append(value)

        rospy.Subscriber("/robot1/cmd_vel", Twist,
                         lambda m: keep(cmds, (rospy.get_time(), m.linear.x, m.angular.z)), queue_size=100)
        rospy.Subscriber(f"{RUNNER}/status", BehaviorStatus, lambda m: keep(statuses, m))
        rospy.Subscriber(f"{RUNNER}/command_feedback", BehaviorCommandFeedback, lambda m: keep(feedback, m))
        rospy.Subscriber(f"{RUNNER}/activity", BehaviorActivity, lambda m: keep(activity, m))
        rospy.Subscriber("/robot1/ground_truth", Odometry, lambda m: keep(speeds, m.twist.twist.linear.x))
        monitor = nav_demo.DemoMonitor(runs)
        problem = nav_demo.wait_until_ready(monitor, processes)
        check(problem is None, f"startup: {problem}")

        # 1. A goal is planned, and the plan waits for the operator (ApprovePlan needs autonomy High).
        monitor.send_due_goals()
        goal_sent_s = rospy.get_time()

        def approval_requested() -> bool:
            with lock:
                return bool(activity) and any(r.path == "/ApprovePlan" and r.outcome == "execute"
                                              for r in activity[-1].requests)

        wait_for(approval_requested, "request for approval of /ApprovePlan -> execute")
        time.sleep(HELD_WATCH_S)
        with lock:
            moving = [c for c in cmds if c[0] >= goal_sent_s and abs(c[1]) > 0.01]
            active = list(activity[-1].active_paths)
        check(not moving, f"the robot was commanded to move before the approval: {moving[:3]}")
        check("/ApprovePlan" in active, f"ApprovePlan should still be active, active: {active}")
        print("waits for approval: /ApprovePlan -> execute (robot not commanded)", flush=True)

        # 2. The operator tool approves; the robot drives.
        code, text = operator("approve-next", "--timeout", "10")
        check(code == 0, f"operator approve-next failed ({code}): {text}")
        print(f"operator: {text}", flush=True)
        wait_for(lambda: any(c[1] > 0.05 for c in list(cmds)), "forward motion after the approval")

        def driving_forward() -> bool:  # under way, not in a turn on the spot at the moment of the preempt
            with lock:
                return bool(cmds) and cmds[-1][1] > 0.05 and bool(speeds) and speeds[-1] >= UNDER_WAY_MPS

        # 3. Preempt mid-motion: zero command, nothing after it, the robot stands.
        wait_for(driving_forward, f"the robot driving forward (last command v > 0.05 m/s, ground truth >= "
                                  f"{UNDER_WAY_MPS} m/s) before the preempt")
        with lock:
            speed_before = speeds[-1]
        monitor.stopping = True
        sent_s = rospy.get_time()
        code, text = operator("preempt")
        check(code == 0, f"operator preempt failed ({code}): {text}")
        wait_for(lambda: any(s.code == BehaviorStatus.PREEMPTED for s in list(statuses)), "status PREEMPTED")
        with lock:
            preempt_s = next(f.header.stamp.to_sec() for f in feedback if f.command == "preempt")
            preempted_s = next(s.header.stamp.to_sec() for s in statuses if s.code == BehaviorStatus.PREEMPTED)
        time.sleep(STOPPED_WATCH_S)
        with lock:
            after = [c for c in cmds if c[0] >= sent_s]
        zeros = [c for c in after if c[1] == 0.0 and c[2] == 0.0]
        check(bool(zeros), "no zero command after the preempt")
        first_zero_s = zeros[0][0]
        late_moving = [c for c in after if c[0] > first_zero_s and (c[1] != 0.0 or c[2] != 0.0)]
        check(not late_moving, f"motion commanded after the stop: {late_moving[:3]}")
        check(after[-1][1] == 0.0 and after[-1][2] == 0.0, f"last command is not zero: {after[-1]}")
        period_s = 1.0 / 20.0
        print(f"preempt: behavior PREEMPTED at sim {preempted_s:.3f} s (operator's answer {preempt_s:.3f} s), first "
              f"zero command received at sim {first_zero_s:.3f} s ({(first_zero_s - preempted_s) * 1e3:+.0f} ms of "
              f"simulated time; control period {period_s * 1e3:.0f} ms); no motion command after it", flush=True)
        speed = _ground_truth_speed()
        check(speed is not None and speed < 0.02, f"robot still moving 1 s after the preempt: {speed} m/s")
        print(f"robot speed {speed_before:.2f} m/s at the preempt, 1 s after it: {speed:.4f} m/s", flush=True)


def _ground_truth_speed() -> Optional[float]:
    try:
        msg = rospy.wait_for_message("/robot1/ground_truth", Odometry, timeout=10.0)
    except rospy.ROSException:
        return None
    return float(abs(msg.twist.twist.linear.x))


def main() -> int:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out/operator_scenario")
    try:
        scenario(out)
    except ScenarioError as err:
        print(f"SCENARIO FAILED: {err}", flush=True)
        return 1
    print("SCENARIO PASSED", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
