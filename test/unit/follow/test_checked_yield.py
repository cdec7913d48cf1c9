"""CheckedYield: the rules' decisions, each checked by the space-time planner."""

from dataclasses import replace

import numpy as np
import pytest
from looping_walker import walker_on_lane

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.checked_yield import CheckedYield
from flex_nav.nav.control.yielding import YieldMode, YieldParams, YieldRule
from flex_nav.nav.path import cumulative_lengths
from flex_nav.perception.walker_lanes import WalkerLanes

PATH = np.array([[0.0, 0.0], [10.0, 0.0]])  # along +x
LENGTHS = cumulative_lengths(PATH)
ROBOT_R, PERSON_R = 0.17, 0.2  # [m]
PARAMS = YieldParams(robot_radius_m=ROBOT_R, speed_mps=0.26, planner="checked", moving_gap_m=0.4,
                     standing_gap_m=0.1)
LANE_X, LOW_Y, HIGH_Y, SPEED = 4.0, -1.5, 3.0, 0.7  # a walker up and down x = 4 across the path, 12.9 s a loop
TICK_S = 0.1  # [s]
GOAL_X = 6.0  # [m] past the walker's lane


def walker_at(t):
    """The walker at time t [s] (at LOW_Y going up at t = 0)."""
    return walker_on_lane(t, LANE_X, LOW_Y, HIGH_Y, SPEED, radius=PERSON_R)


def learnt_lanes(until_s):
    lanes = WalkerLanes()
    for k in range(round(until_s / TICK_S) + 1):
        lanes.update(k * TICK_S, [walker_at(k * TICK_S)])
    return lanes


def decide(rule, now_s, x):
    return rule.decide(now_s, (x, 0.0, 0.0), (0.26, 0.0), path=PATH, lengths=LENGTHS, s_robot=x,
                       tracks=[walker_at(now_s)], speed=0.26)


def drive(rule, start_s, x=1.0, limit_s=40.0):
    """(time to GOAL_X [s] or None, closest gap [m] to the true walker while the robot moves) driving the
    rule's decisions from ``x`` [m] at ``start_s`` [s], the walker's lanes learnt from t = 0."""
    if rule.lanes is not None:
        for k in range(round(start_s / TICK_S) + 1):
            rule.lanes.update(k * TICK_S, [walker_at(k * TICK_S)])
    t, worst = start_s, np.inf
    while t < start_s + limit_s:
        if x >= GOAL_X:
            return t - start_s, worst
        walker = walker_at(t)
        v = decide(rule, t, x).v
        if abs(v) > 0.01:
            worst = min(worst, float(np.hypot(x - walker.x, walker.y)) - ROBOT_R - PERSON_R)
        x += v * TICK_S
        t += TICK_S
    return None, worst


class _Rules(YieldRule):
    lanes = None


def test_driven_by_the_checked_rules_the_robot_keeps_the_distance_and_gets_past():
    for start_s in (12.0, 14.0, 16.0, 18.0, 20.0):
        arrival_s, closest_m = drive(CheckedYield(PARAMS), start_s)
        assert arrival_s is not None and arrival_s < 30.0, start_s
        assert closest_m >= 0.3, (start_s, closest_m)


def test_driven_by_the_rules_alone_the_robot_comes_closer():
    closest = [drive(_Rules(PARAMS), start_s)[1] for start_s in (12.0, 14.0, 16.0, 18.0, 20.0)]
    assert min(closest) < 0.3  # so the check is what keeps the distance above


def test_the_rules_decide_when_a_plan_keeping_the_distance_follows_their_step():
    rule = CheckedYield(PARAMS, lanes=learnt_lanes(16.5))
    rules = decide(YieldRule(PARAMS), 16.5, 3.2)
    checked = decide(rule, 16.5, 3.2)
    assert rule.last_source == "rules"
    assert (checked.v, checked.mode) == (rules.v, rules.mode)


def test_the_check_keeps_its_own_moving_gap():
    # the scene above, where a plan after the rules' step keeps 0.4 m while moving: none keeps 1.5 m
    rule = CheckedYield(replace(PARAMS, check_moving_gap_m=1.5), lanes=learnt_lanes(16.5))
    rules = decide(YieldRule(PARAMS), 16.5, 3.2)
    after_rules = rule.planner.plan((3.2, 0.0, 0.0), PATH, LENGTHS, 3.2, [walker_at(16.5)],
                                    only_first=rule.planner.cells_per_step(rules.v),
                                    standing_gap_m=PARAMS.check_standing_gap_m, moving_gap_m=1.5)[1]
    assert after_rules < 0.0
    assert rule.planner.plan((3.2, 0.0, 0.0), PATH, LENGTHS, 3.2, [walker_at(16.5)])[1] >= 0.0  # its own keeps 0.4
    decide(rule, 16.5, 3.2)
    assert rule.last_source == "planner"  # (with the default check the rules decide here: the test above)


def test_the_planner_decides_when_the_walker_comes_back_before_the_rules_step_gets_across():
    # t = 18.75 s: the walker walks away up the lane (y = 2.6), turns at its end and is back on the path about
    # 4 s later; the rules, predicting straight on, drive into the lane
    rules = decide(YieldRule(PARAMS), 18.75, 3.6)
    assert rules.mode is YieldMode.FREE and rules.v > 0.0
    rule = CheckedYield(PARAMS, lanes=learnt_lanes(18.75))
    checked = decide(rule, 18.75, 3.6)
    assert rule.last_source == "planner"
    assert checked.v <= 0.0
    assert "no plan keeping the distance" in checked.reason
    _first, score, _who = rule.planner.plan((3.6, 0.0, 0.0), PATH, LENGTHS, 3.6, [walker_at(18.75)],
                                            only_first=rule.planner.cells_per_step(rules.v),
                                            standing_gap_m=PARAMS.check_standing_gap_m)
    assert score < 0.0


def test_the_planner_and_the_rules_keep_their_own_horizons():
    rule = CheckedYield(YieldParams(planner="checked", horizon_s=6.0, max_range_m=5.0, plan_horizon_s=8.0,
                                    plan_range_m=7.0))
    assert (rule.rules.params.horizon_s, rule.rules.params.max_range_m) == (6.0, 5.0)
    assert (rule.planner.params.horizon_s, rule.planner.params.max_range_m) == (8.0, 7.0)
    assert rule.planner.steps == 40


@pytest.mark.parametrize(("values", "words"), [
    ({"check_standing_gap_m": -0.1}, ["check_standing_gap_m", ">= 0"]),
    ({"check_moving_gap_m": float("inf")}, ["check_moving_gap_m", ">= 0"]),
    ({"plan_horizon_s": 0.0}, ["plan_horizon_s", "> 0"]),
    ({"plan_range_m": float("nan")}, ["plan_range_m"]),
    ({"planner": "checked", "plan_horizon_s": 0.1}, ["plan_step_s", "plan_horizon_s"]),
    ({"planner": "check"}, ["rules", "space_time", "checked"]),
])
def test_checked_parameters_are_validated_by_name(values, words):
    with pytest.raises(ConfigError) as err:
        YieldParams(**values)
    for word in words:
        assert word in str(err.value)
