"""The yield rule: stop before a walking person's way, step out of it, never toward them; and SafeFollower with it."""

import dataclasses
import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.controller import Outcome, SafeFollower
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.control.yielding import YieldMode, YieldParams, YieldRule, arc_positions
from flex_nav.nav.costmap.costmap_grid import LETHAL, CostmapGeometry
from flex_nav.nav.path import cumulative_lengths
from flex_nav.perception.moving_obstacles import Track

PATH = np.array([[0.0, 0.0], [10.0, 0.0]])  # along +x
LENGTHS = cumulative_lengths(PATH)
PARAMS = YieldParams(robot_radius_m=0.17, speed_mps=0.26, margin_m=0.1, start_margin_m=0.05, resume_after_s=0.5)
R = 0.17 + 0.2 + 0.1  # robot radius + person radius + margin


def person(x, y, vx, vy, track_id=1, radius=0.2):
    return Track(track_id, x, y, vx, vy, radius, 0.0, 10)


def decide(rule, x, tracks, now_s=0.0, command=(0.26, 0.0), yaw=0.0, costs=None, geometry=None):
    return rule.decide(now_s, (x, 0.0, yaw), command, path=PATH, lengths=LENGTHS, s_robot=x, tracks=tracks,
                       costs=costs, geometry=geometry)


def test_no_people_or_people_far_from_the_way_leave_the_command_alone():
    rule = YieldRule(PARAMS)
    assert decide(rule, 1.0, []) .mode is YieldMode.FREE
    walking_away = person(3.0, -0.8, 0.0, -0.8)  # has crossed, walks away
    standing = person(2.0, 0.0, 0.05, 0.0)  # too slow: left to the costmap
    d = decide(rule, 1.0, [walking_away, standing])
    assert d.mode is YieldMode.FREE and (d.v, d.w) == (0.26, 0.0)


def test_a_person_about_to_cross_ahead_slows_the_robot_before_the_corridor():
    rule = YieldRule(PARAMS)
    crossing = person(3.0, -2.5, 0.0, 0.8)  # reaches the path at x = 3 in 3.1 s, as the robot would
    far = decide(rule, 1.0, [crossing])
    assert far.mode is YieldMode.FREE  # the person will have passed when the robot gets there
    d = decide(rule, 2.0, [crossing])
    assert d.mode is YieldMode.SLOW and d.track_id == 1
    # stopping distance at the capped speed ends before the corridor edge (3 - R from the crossing point)
    stop_at = 2.0 + d.v**2 / (2 * PARAMS.decel_mps2)
    assert stop_at < 3.0 - R + 1e-6
    near_x = 3.0 - R - 0.07
    near = decide(rule, near_x, [crossing])
    assert near.mode is YieldMode.SLOW and near.v < 0.26
    assert near_x + near.v**2 / (2 * PARAMS.decel_mps2) < 3.0 - R + 1e-6


def test_at_the_corridor_edge_the_robot_waits_and_only_turns_in_place():
    rule = YieldRule(PARAMS)
    crossing = person(3.0, -2.0, 0.0, 0.8)
    d = decide(rule, 3.0 - R - 0.02, [crossing], command=(0.26, 0.1))
    assert d.mode is YieldMode.WAIT and d.v == 0.0


def test_a_stopped_robot_resumes_only_after_the_way_stayed_clear():
    rule = YieldRule(PARAMS)
    waited = decide(rule, 2.5, [person(3.0, -1.0, 0.0, 0.8)], now_s=0.0)
    assert waited.mode is YieldMode.WAIT and waited.v == 0.0
    passed = [person(3.0, 1.5, 0.0, 0.8)]  # crossed and walking away
    held = decide(rule, 2.4, passed, now_s=0.2)
    assert held.mode is YieldMode.WAIT and held.v == 0.0 and "resuming" in held.reason
    assert decide(rule, 2.4, passed, now_s=0.8).mode is YieldMode.FREE
    rule.reset()
    assert decide(rule, 2.4, passed, now_s=0.81).mode is YieldMode.FREE


def test_a_robot_still_driving_when_the_way_clears_drives_on():
    rule = YieldRule(PARAMS)
    slowed = decide(rule, 2.2, [person(3.0, -2.0, 0.0, 0.8)], now_s=0.0)
    assert slowed.mode is YieldMode.SLOW and slowed.v > 0.05  # braking for the corridor, not yet stopped
    passed = [person(3.0, 1.5, 0.0, 0.8)]
    assert decide(rule, 2.2, passed, now_s=0.1).mode is YieldMode.FREE  # no stop for resume_after_s


def test_going_on_along_the_path_is_driven_at_the_speed_it_was_checked_at():
    rule = YieldRule(PARAMS)
    # a person comes up fast behind the robot; the controller has slowed near their costmap marks
    d = decide(rule, 3.0, [person(2.0, 0.0, 0.9, 0.0)], command=(0.1, 0.05))
    assert d.mode is YieldMode.ESCAPE and "along the path" in d.reason, d
    assert d.v == pytest.approx(PARAMS.speed_mps) and d.w == pytest.approx(0.05 * PARAMS.speed_mps / 0.1)


@pytest.mark.parametrize("x, y, vx, vy", [(3.4, -1.5, 0.0, 0.8), (6.0, 0.0, -0.8, 0.0), (4.0, -1.0, -0.55, 0.55)])
def test_standing_in_the_way_of_an_approaching_person_backs_away(x, y, vx, vy):
    rule = YieldRule(PARAMS)
    # the person's way runs through the robot (at x = 3) and just ahead of it: going on meets them too
    d = decide(rule, 3.0, [person(x, y, vx, vy)], command=(0.0, 0.0))
    assert d.mode is YieldMode.ESCAPE and d.v < 0.0, d
    # backing up is away from the person's way: its closest approach grows
    times = rule.times
    future = np.stack((x + vx * times, y + vy * times), axis=1)
    moved = arc_positions((3.0, 0.0, 0.0), d.v, d.w, times)
    assert np.min(np.hypot(*(moved - future).T)) > np.min(np.hypot(*(np.array([3.0, 0.0]) - future).T))


def test_never_toward_a_person_even_when_it_would_help_with_another():
    rule = YieldRule(PARAMS)
    # one person comes at the robot head-on along the path; another walks up slowly behind it
    ahead = person(4.5, 0.0, -0.8, 0.0, track_id=1)
    behind = person(2.0, -0.2, 0.3, 0.0, track_id=2)
    d = decide(rule, 3.0, [ahead, behind], command=(0.0, 0.0))
    assert d.v <= 0.0 or d.mode is not YieldMode.ESCAPE  # never forward into the person ahead
    moved = arc_positions((3.0, 0.0, 0.0), d.v, d.w, rule.times)
    walker = np.stack((2.0 + 0.3 * rule.times, np.full_like(rule.times, -0.2)), axis=1)
    gap_moving = np.hypot(*(moved - walker).T).min() - R
    gap_standing = np.hypot(*(np.array([3.0, 0.0]) - walker).T).min() - R
    assert gap_moving >= min(gap_standing, 0.0) - 1e-9  # nor back into the one behind


def test_going_on_is_an_escape_when_the_person_comes_from_behind():
    rule = YieldRule(PARAMS)
    # a person walks the path's direction fast, right behind the robot: backing up would be toward them
    d = decide(rule, 3.0, [person(2.0, 0.0, 0.9, 0.0)], command=(0.26, 0.0))
    assert d.v >= 0.0
    if d.mode is YieldMode.ESCAPE:
        assert "along the path" in d.reason or "forward" in d.reason


def test_going_on_out_of_one_persons_way_stops_short_of_the_next_ones():
    rule = YieldRule(PARAMS)
    geometry = CostmapGeometry(100, 100, 0.05, 0.0, -2.5)
    costs = np.zeros(geometry.shape, dtype=np.uint8)
    rows, cols = geometry.world_to_cells(np.array([2.88, 2.88]), np.array([-0.5, 0.5]))
    costs[rows[0]:rows[1] + 1, cols[0]] = LETHAL  # a wall behind: no backing up
    coming = person(3.0, -2.5, 0.0, 0.7, track_id=1)  # walks through where the robot stands
    ahead = person(4.5, -3.3, 0.0, 0.6, track_id=2)  # crosses the path 1.5 m ahead as the robot would get there
    d = decide(rule, 3.0, [coming, ahead], command=(0.1, 0.0), costs=costs, geometry=geometry)
    assert d.mode is YieldMode.ESCAPE and "along the path" in d.reason and d.v > 0.0, d
    # the next tick out of the first person's way, the robot brakes before the second one's way
    later = decide(rule, 3.6, [person(3.0, -1.8, 0.0, 0.7, track_id=1), person(4.5, -2.7, 0.0, 0.6, track_id=2)],
                   now_s=1.0, costs=costs, geometry=geometry)
    assert later.mode in (YieldMode.SLOW, YieldMode.WAIT) and later.track_id == 2, later


def test_an_obstacle_behind_forbids_backing_up():
    rule = YieldRule(PARAMS)
    geometry = CostmapGeometry(100, 100, 0.05, 0.0, -2.5)
    costs = np.zeros(geometry.shape, dtype=np.uint8)
    rows, cols = geometry.world_to_cells(np.array([2.85, 2.85, 2.85]), np.array([-0.05, 0.0, 0.05]))
    costs[rows, cols] = LETHAL
    d = decide(rule, 3.0, [person(3.0, -2.5, 0.0, 0.8)], command=(0.0, 0.0), costs=costs, geometry=geometry)
    assert not (d.mode is YieldMode.ESCAPE and d.v < 0.0 and d.w == 0.0)


def test_parameters_are_validated_with_the_valid_names():
    with pytest.raises(ConfigError, match="horizon_s"):
        YieldParams(horizon_s=0.0)
    with pytest.raises(ConfigError, match=r"valid: .*margin_m"):
        YieldParams.from_mapping({"margins": 0.1})
    assert YieldParams.from_mapping({"horizon_s": 5}).horizon_s == 5.0


# ------------------------------------------------------------------ in SafeFollower
PURSUIT = PurePursuitParams(desired_linear_vel=0.26, lookahead_dist=0.5, goal_dist_tol=0.1, use_final_heading=False)


def follower(yielding):
    return SafeFollower(PURSUIT, sensors=("odom",), sensor_timeout_s=0.5, collision_timeout_s=1.0,
                        nominal_period_s=0.05, start_s=0.0, blocked_distance_m=0.7, yielding=yielding)


def test_safe_follower_gives_way_and_the_blocked_watch_stays_quiet():
    f = follower(YieldRule(PARAMS))
    f.set_path(np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]))
    crossing = [person(3.0, -1.5, 0.0, 0.8)]
    geometry = CostmapGeometry(60, 60, 0.05, 1.0, -1.5)
    costs = np.zeros(geometry.shape, dtype=np.uint8)
    rows, cols = geometry.world_to_cells(np.array([3.0]), np.array([0.0]))  # the person's marks on the path
    costs[rows[0] - 4:rows[0] + 5, cols[0] - 4:cols[0] + 5] = LETHAL
    for k in range(40):  # 2 s standing at the edge with the path "blocked" by the person's marks
        now = 0.05 * (k + 1)
        f.watchdog.saw("odom", now)
        d = f.tick(now, lambda: (2.52, 0.0, 0.0), (0.0, 0.0), lambda: (costs, geometry), lambda: crossing)
        assert d.outcome is Outcome.RUNNING and d.v == 0.0 and d.reason.startswith("yielding")


def test_after_giving_way_the_robot_speeds_up_from_standstill_within_the_acceleration_limit():
    """While the rule holds the robot, pursuit must not ramp up unseen: the first command after the way is clear
    is one acceleration step from the zero that was sent, not a jump to the cruising speed."""
    f = follower(YieldRule(PARAMS))
    f.set_path(np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]))
    crossing = [person(3.0, -1.5, 0.0, 0.8)]
    now, dt = 0.0, 0.05
    for k in range(120):  # 2 s held at the corridor's edge, then the walker is gone
        now = dt * (k + 1)
        f.watchdog.saw("odom", now)
        tracks = crossing if k < 40 else []
        d = f.tick(now, lambda: (2.52, 0.0, 0.0), (0.0, 0.0), lambda: None, lambda tracks=tracks: tracks)
        assert d.outcome is Outcome.RUNNING
        if k < 40:
            assert d.v == 0.0 and d.reason.startswith("yielding")
        elif d.v > 0.0:
            break
    assert not d.reason.startswith("yielding"), "the rule never let the robot go"
    assert d.v == pytest.approx(PURSUIT.max_linear_accel * dt)
    assert d.v < PURSUIT.desired_linear_vel


def test_giving_way_without_a_break_is_bounded_by_the_patience():
    """A walker who keeps crossing (a lingering track, a tracker artefact) must not hold the goal forever."""
    f = follower(YieldRule(dataclasses.replace(PARAMS, patience_s=3.0)))
    f.set_path(np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]))
    crossing = [person(3.0, -1.5, 0.0, 0.8)]
    for k in range(200):  # up to 10 s at the corridor's edge
        now = 0.05 * (k + 1)
        f.watchdog.saw("odom", now)
        d = f.tick(now, lambda: (2.52, 0.0, 0.0), (0.0, 0.0), lambda: None, lambda: crossing)
        if d.outcome is not Outcome.RUNNING:
            break
    assert d.outcome is Outcome.ABORTED and (d.v, d.w) == (0.0, 0.0)
    assert "gave way to people for 3 s" in d.reason and now == pytest.approx(3.05, abs=0.06)


def test_safe_follower_without_the_rule_ignores_tracks():
    f = follower(None)
    f.set_path(np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]))
    f.watchdog.saw("odom", 0.05)
    d = f.tick(0.05, lambda: (2.45, 0.0, 0.0), (0.26, 0.0), lambda: None, lambda: [person(3.0, -1.5, 0.0, 0.8)])
    assert d.outcome is Outcome.RUNNING and d.v > 0.0 and not d.reason.startswith("yielding")


def test_arc_positions_follow_a_circle():
    pos = arc_positions((0.0, 0.0, 0.0), 0.2, 0.4, np.array([0.0, math.pi / 0.4]))
    assert pos[1] == pytest.approx([0.0, 1.0], abs=1e-9)  # half a circle of radius 0.5


def test_an_obstacle_on_the_path_explained_by_a_walking_person_does_not_block():
    rule = YieldRule(PARAMS)
    walking, standing = person(3.0, 0.3, 0.0, 0.8), person(3.0, 0.0, 0.0, 0.0, track_id=2)
    assert rule.explains((3.0, 0.0), [walking])  # its marks, 0.3 m behind it
    assert not rule.explains((3.0, 0.0), [standing])  # a standing person is an obstacle for the behavior
    assert not rule.explains((3.0, -1.0), [walking])
    f = follower(rule)
    f.set_path(np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]))
    geometry = CostmapGeometry(60, 60, 0.05, 1.0, -1.5)
    costs = np.zeros(geometry.shape, dtype=np.uint8)
    rows, cols = geometry.world_to_cells(np.array([2.4]), np.array([0.0]))
    costs[rows[0] - 2:rows[0] + 3, cols[0] - 2:cols[0] + 3] = LETHAL  # marks 0.4 m ahead, on the path
    leaving = [person(2.4, 0.45, 0.0, 0.8)]  # the walker that left them, now beside the path, walking away
    outcomes = []
    for k in range(30):
        now = 0.05 * (k + 1)
        f.watchdog.saw("odom", now)
        outcomes.append(f.tick(now, lambda: (2.0, 0.0, 0.0), (0.0, 0.0), lambda: (costs, geometry),
                               lambda: leaving).outcome)
    assert set(outcomes) == {Outcome.RUNNING}
    still = follower(rule)  # the same marks with nobody walking: blocked
    still.set_path(np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]))
    for k in range(30):
        now = 0.05 * (k + 1)
        still.watchdog.saw("odom", now)
        end = still.tick(now, lambda: (2.0, 0.0, 0.0), (0.0, 0.0), lambda: (costs, geometry))
        if end.outcome is not Outcome.RUNNING:
            break
    assert end.outcome is Outcome.ABORTED and end.reason.startswith("blocked")


def test_the_prediction_starts_from_the_measured_speed():
    # going on at full speed gets across before the person arrives; a robot still backing up does not
    crossing = [person(3.0, -2.0, 0.0, 0.8)]
    moving = YieldRule(PARAMS).decide(0.0, (2.9, 0.0, 0.0), (0.26, 0.0), path=PATH, lengths=LENGTHS, s_robot=2.9,
                                      tracks=crossing, speed=0.26)
    backing = YieldRule(PARAMS).decide(0.0, (2.9, 0.0, 0.0), (0.26, 0.0), path=PATH, lengths=LENGTHS, s_robot=2.9,
                                       tracks=crossing, speed=-0.2)
    assert moving.mode is YieldMode.FREE
    assert backing.mode is not YieldMode.FREE


def test_uncertainty_widens_the_way_with_the_prediction_time():
    passing = [person(3.6, -2.5, 0.0, 0.8)]  # its way runs 0.6 m ahead of a robot standing at x = 3
    sure = YieldRule(PARAMS)
    unsure = YieldRule(YieldParams(**{**PARAMS.__dict__, "uncertainty_mps": 0.1}))
    assert decide(sure, 3.0, passing, command=(0.0, 0.0)).v == 0.0  # waits: going on would meet
    assert decide(unsure, 3.0, passing, command=(0.0, 0.0)).mode is YieldMode.ESCAPE  # 0.6 m is not enough


def test_hurrying_across_only_when_enabled_and_only_that_clears():
    crossing = [person(3.0, -2.75, 0.0, 0.8)]  # at 0.26 m/s the robot would meet it, at 0.30 m/s it is across
    plain = decide(YieldRule(PARAMS), 2.5, crossing)
    assert plain.mode in (YieldMode.SLOW, YieldMode.WAIT) and plain.v <= 0.26
    hurried = YieldRule(YieldParams(**{**PARAMS.__dict__, "hurry_speed_mps": 0.3}))
    d = decide(hurried, 2.5, crossing, command=(0.26, 0.02))
    assert d.mode is YieldMode.HURRY and d.v == pytest.approx(0.3) and d.w == pytest.approx(0.02 * 0.3 / 0.26)
    assert decide(hurried, 2.5, crossing, command=(0.1, 0.0)).mode is not YieldMode.HURRY  # not cruising
    late = [person(3.0, -1.5, 0.0, 0.8)]  # too close for any speed: no hurry
    assert decide(YieldRule(hurried.params), 2.5, late).mode is not YieldMode.HURRY


def test_a_way_free_by_the_margin_but_not_the_comfort_margin_is_hurried_across_never_waited_for():
    comfort = YieldRule(YieldParams(**{**PARAMS.__dict__, "hurry_speed_mps": 0.3, "comfort_margin_m": 0.3}))
    tight = [person(3.0, -3.55, 0.0, 0.8)]  # at 0.26 m/s 0.15 m beyond the margin, at 0.30 m/s 0.31 m
    d = decide(comfort, 2.5, tight)
    assert d.mode is YieldMode.HURRY and d.v == pytest.approx(0.3)
    plain = YieldRule(YieldParams(**{**PARAMS.__dict__, "hurry_speed_mps": 0.3}))
    assert decide(plain, 2.5, tight).mode is YieldMode.FREE  # without the comfort margin the way is free
    closer = [person(3.0, -3.2, 0.0, 0.8)]  # hurrying keeps only 0.19 m beyond the margin: free, not waited for
    assert decide(YieldRule(comfort.params), 2.5, closer).mode is YieldMode.FREE
    roomy = [person(3.0, -3.8, 0.0, 0.8)]  # 0.23 m beyond the margin at cruise: the comfort margin is kept
    assert decide(YieldRule(comfort.params), 2.5, roomy).mode is YieldMode.FREE


def test_comfort_margin_is_validated():
    with pytest.raises(ConfigError, match="comfort_margin_m"):
        YieldParams(comfort_margin_m=-0.1)
