"""Closed loop without ROS: synthetic scans -> tracker -> SafeFollower with the yield rule -> a kinematic robot.

Blind people walk back and forth across a straight path, as in scenario S6; the robot must reach the end of
the path without ever touching one of them. Simulated time only (no timed assertions).
"""

import math
from functools import partial
from typing import Callable, Set

import numpy as np
import pytest
from unit.perception.scan_synth import ray_scan

from flex_nav.nav.control.controller import Outcome, SafeFollower
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.control.yielding import YieldParams, YieldRule
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.planar import Pose2D
from flex_nav.perception.moving_obstacles import MovingObstacleTracker
from flex_nav.perception.static_mask import StaticMask

ROBOT_RADIUS = 0.171  # [m] TurtleBot 4
PERSON_RADIUS = 0.2  # [m]
ROOM = (0.0, 0.0, 8.0, 8.0)
DT = 0.05  # [s] control period
SCAN_PERIOD = 1.0 / 5.5  # [s]
PURSUIT = PurePursuitParams(desired_linear_vel=0.26, max_linear_accel=0.9, max_linear_decel=0.9, lookahead_dist=0.5,
                            goal_dist_tol=0.15, use_final_heading=False, use_collision_detection=False)


def pose_now(x: float, y: float, yaw: float) -> Callable[[], Pose2D]:
    """The robot's pose callable of one tick (bound now, not to the loop's variables)."""
    return lambda: (x, y, yaw)


def walker(start, end, speed, t_s):
    """Position of a person walking start -> end -> start ... at ``speed`` [m/s], at time ``t_s``."""
    (x0, y0), (x1, y1) = start, end
    length = math.hypot(x1 - x0, y1 - y0)
    s = math.fmod(speed * t_s, 2.0 * length)
    f = (s if s <= length else 2.0 * length - s) / length
    return x0 + f * (x1 - x0), y0 + f * (y1 - y0)


PEOPLE = [  # (start, end, speed): two lanes across the path (y = 4) and a diagonal through the second crossing
    ((2.5, 0.8), (2.5, 7.2), 0.6),
    ((5.0, 7.2), (5.0, 0.8), 0.8),
    ((2.0, 7.0), (7.5, 1.5), 0.9),
]


def room_mask():
    res = 0.05
    occ = np.zeros((int(ROOM[3] / res), int(ROOM[2] / res)), dtype=np.int8)
    occ[0, :] = occ[-1, :] = occ[:, 0] = occ[:, -1] = 100
    return StaticMask(GridMap(occ, res, (0.0, 0.0, 0.0)), 0.15)


def run(start_s, limit_s=120.0):
    rule = YieldRule(YieldParams(robot_radius_m=ROBOT_RADIUS, speed_mps=0.26))
    follower = SafeFollower(PURSUIT, sensors=("odom",), sensor_timeout_s=0.5, collision_timeout_s=2.0,
                            nominal_period_s=DT, start_s=start_s, yielding=rule)
    follower.set_path(np.array([[0.5 + 0.25 * k, 4.0, 0.0] for k in range(27)]))  # 0.5 .. 7.0 m along y = 4
    tracker = MovingObstacleTracker(static_mask=room_mask())
    x, y, yaw, v, w = 0.5, 4.0, 0.0, 0.0, 0.0
    t, next_scan = start_s, start_s
    min_gap = math.inf
    reasons: Set[str] = set()
    while t < start_s + limit_s:
        people = [walker(a, b, speed, t) for a, b, speed in PEOPLE]
        min_gap = min(min_gap, *(math.hypot(px - x, py - y) - PERSON_RADIUS - ROBOT_RADIUS for px, py in people))
        if t >= next_scan:
            xs, ys = ray_scan((x, y), [(px, py, PERSON_RADIUS) for px, py in people], room=ROOM)
            tracker.update_scan(xs, ys, (x, y), t)
            next_scan += SCAN_PERIOD
        follower.watchdog.saw("odom", t)
        decision = follower.tick(t, pose_now(x, y, yaw), (v, w), lambda: None, partial(tracker.tracks, t))
        if decision.outcome is not Outcome.RUNNING:
            return decision, t - start_s, min_gap, reasons
        reasons.add(decision.reason.split(":")[0])
        v += max(-0.9 * DT, min(0.9 * DT, decision.v - v))  # base acceleration limits
        w += max(-4.0 * DT, min(4.0 * DT, decision.w - w))
        x, y, yaw = x + v * math.cos(yaw) * DT, y + v * math.sin(yaw) * DT, yaw + w * DT
        t += DT
    return None, limit_s, min_gap, reasons


@pytest.mark.parametrize("start_s", [0.0, 3.0, 11.0])
def test_robot_crosses_walking_people_without_touching_anyone(start_s):
    decision, _elapsed, min_gap, reasons = run(start_s)
    assert min_gap > 0.0, f"touched a person (gap {min_gap:.3f} m)"
    assert "yielding" in reasons  # it did have to give way
    assert decision is not None and decision.outcome is Outcome.SUCCEEDED, decision


def blind_min_gap(start_s):
    """Smallest robot-person gap [m] of the same robot following the path without the rule."""
    follower = SafeFollower(PURSUIT, sensors=("odom",), sensor_timeout_s=0.5, collision_timeout_s=2.0,
                            nominal_period_s=DT, start_s=start_s)
    follower.set_path(np.array([[0.5, 4.0, 0.0], [7.0, 4.0, 0.0]]))
    x, v, min_gap, t = 0.5, 0.0, math.inf, start_s
    while t < start_s + 40.0 and x < 6.9:
        min_gap = min(min_gap, *(math.hypot(px - x, py - 4.0) - PERSON_RADIUS - ROBOT_RADIUS
                                 for px, py in (walker(a, b, s, t) for a, b, s in PEOPLE)))
        follower.watchdog.saw("odom", t)
        v = follower.tick(t, pose_now(x, 4.0, 0.0), (v, 0.0), lambda: None).v
        x, t = x + v * DT, t + DT
    return min_gap


def test_without_the_rule_the_same_robot_walks_into_people():
    # the scene is a real test: for most of the starts above, blind people and a blind robot meet
    assert sum(blind_min_gap(start_s) < 0.0 for start_s in (0.0, 3.0, 7.0)) >= 2
