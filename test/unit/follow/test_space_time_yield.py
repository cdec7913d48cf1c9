"""SpaceTimeYield: the speed along the path planned around walkers predicted along their lanes."""

import numpy as np
import pytest
from looping_walker import walker_on_lane

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.space_time_yield import SpaceTimeYield
from flex_nav.nav.control.yielding import YieldMode, YieldParams
from flex_nav.nav.path import cumulative_lengths
from flex_nav.perception.moving_obstacles import Track
from flex_nav.perception.walker_lanes import WalkerLanes

PATH = np.array([[0.0, 0.0], [10.0, 0.0]])  # along +x
LENGTHS = cumulative_lengths(PATH)
ROBOT_R, PERSON_R = 0.17, 0.2  # [m]
PARAMS = YieldParams(robot_radius_m=ROBOT_R, speed_mps=0.26, planner="space_time", horizon_s=8.0, max_range_m=8.0,
                     moving_gap_m=0.4, standing_gap_m=0.1)
LANE_X, LOW_Y, HIGH_Y, SPEED = 4.0, -3.0, 3.0, 0.7  # a walker going up and down x = 4 across the path


def walker_at(t):
    """The walker at time t [s] (at LOW_Y going up at t = 0)."""
    return walker_on_lane(t, LANE_X, LOW_Y, HIGH_Y, SPEED, radius=PERSON_R)


def learnt_lanes(until_s):
    lanes = WalkerLanes()
    for k in range(round(until_s / 0.1) + 1):
        lanes.update(k * 0.1, [walker_at(k * 0.1)])
    return lanes


def closest_while_moving(plan, start_s, step_s):
    """[m] the smallest gap between the plan's moving steps and the walker's true motion."""
    worst = np.inf
    for k in range(1, len(plan)):
        if np.hypot(*(plan[k] - plan[k - 1])) < 1e-9:
            continue
        for i in (k - 1, k):
            w = walker_at(start_s + i * step_s)
            worst = min(worst, float(np.hypot(plan[i, 0] - w.x, plan[i, 1] - w.y)) - ROBOT_R - PERSON_R)
    return worst


def plan_from(x, now_s, lanes):
    rule = SpaceTimeYield(PARAMS, lanes=lanes)
    now = walker_at(now_s)
    first, score, _who = rule.plan((x, 0.0, 0.0), PATH, LENGTHS, x, [now])
    return rule, first, score


# t = 13.0 s: the walker has just crossed the path walking down (y = -0.1), turns at the lane's end (y = -3) at
# t = 17.1 s and is back across the path at t = 21.4 s; the robot at x = 2.0, driving on, would be in the way
NOW_S, ROBOT_X = 13.0, 2.0


def test_with_the_lane_the_plan_keeps_the_distance_from_the_walker_coming_back():
    rule, _first, score = plan_from(ROBOT_X, NOW_S, learnt_lanes(NOW_S))
    assert score >= 0.0
    assert closest_while_moving(rule.last_plan, NOW_S, rule.step_s) >= PARAMS.moving_gap_m - 0.02
    assert rule.last_plan[-1, 0] > ROBOT_X  # and it gets on


def test_at_constant_velocity_the_plan_drives_into_the_walker_coming_back():
    cv = SpaceTimeYield(YieldParams(**{**PARAMS.__dict__, "lanes": False}))
    first, _score, _who = cv.plan((ROBOT_X, 0.0, 0.0), PATH, LENGTHS, ROBOT_X, [walker_at(NOW_S)])
    assert first > 0
    assert closest_while_moving(cv.last_plan, NOW_S, cv.step_s) < 0.3


def test_a_plan_backs_up_only_before_it_drives_forward():
    for now_s in np.arange(12.0, 20.0, 0.5):
        for x in (2.8, 3.4, 4.6):
            rule, _first, _score = plan_from(x, float(now_s), learnt_lanes(float(now_s)))
            steps = np.diff(rule.last_plan[:, 0])
            forward = np.flatnonzero(steps > 1e-9)
            if forward.size:
                assert (steps[forward[0]:] >= -1e-9).all(), (now_s, x, steps)


def test_a_walker_standing_at_the_lanes_end_is_planned_around():
    lanes = learnt_lanes(20.0)
    rule = SpaceTimeYield(PARAMS, lanes=lanes)
    standing = Track(1, LANE_X, LOW_Y, 0.0, 0.0, PERSON_R, 20.0, 10)
    assert rule.people((2.0, 0.0, 0.0), [standing]) == [standing]
    assert SpaceTimeYield(PARAMS, lanes=WalkerLanes()).people((2.0, 0.0, 0.0), [standing]) == []


def test_decide_is_free_without_people_and_waits_or_slows_before_a_crossing():
    rule = SpaceTimeYield(PARAMS, lanes=learnt_lanes(NOW_S))
    free = rule.decide(NOW_S, (ROBOT_X, 0.0, 0.0), (0.26, 0.0), path=PATH, lengths=LENGTHS, s_robot=ROBOT_X,
                       tracks=[])
    assert free.mode is YieldMode.FREE and free.v == 0.26
    near, turn_s = 3.5, 17.0  # the walker turns at the lane's end; at 3.5 m the robot is in the way it comes back
    d = rule.decide(turn_s, (near, 0.0, 0.0), (0.26, 0.0), path=PATH, lengths=LENGTHS, s_robot=near,
                    tracks=[walker_at(turn_s)])
    assert d.mode in (YieldMode.WAIT, YieldMode.SLOW, YieldMode.ESCAPE) and d.v < 0.26 and d.track_id == 1


@pytest.mark.parametrize("values, words", [({"planner": "astar"}, "rules, space_time"),
                                           ({"moving_gap_m": -0.1}, "moving_gap_m"),
                                           ({"plan_step_s": 0.0}, "plan_step_s"),
                                           ({"lanes": "yes"}, "lanes")])
def test_planner_parameters_are_validated_by_name(values, words):
    with pytest.raises(ConfigError, match=words):
        YieldParams(**values)
