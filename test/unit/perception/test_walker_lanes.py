"""WalkerLanes: lanes learnt from tracks walking back and forth, and predictions along them."""

import math

import numpy as np
import pytest
from looping_walker import walker_on_lane

from flex_nav.exceptions import ConfigError
from flex_nav.perception.moving_obstacles import Track
from flex_nav.perception.walker_lanes import LaneParams, WalkerLanes, bounce, fit_line

DT = 0.1  # [s] tick
SPEED = 0.7  # [m/s]


def walker_at(t, y_low=1.0, y_high=6.0, x=4.0, speed=SPEED, track_id=1):
    """A walker going up and down x = ``x`` between the two ys, starting at y_low at t = 0 (velocity exact)."""
    return walker_on_lane(t, x, y_low, y_high, speed, track_id=track_id)


def learnt(until_s, **kwargs):
    lanes = WalkerLanes()
    for k in range(round(until_s / DT) + 1):
        lanes.update(k * DT, [walker_at(k * DT, **kwargs)])
    return lanes


def test_a_straight_leg_makes_one_lane_along_it():
    lanes = learnt(5.0)  # up from y = 1.0 to 4.5, no turn yet
    assert len(lanes.lanes) == 1
    lane = lanes.lanes[0]
    assert abs(abs(lane.direction[1]) - 1.0) < 1e-3
    assert lane.forward and not lane.backward and not lane.turned
    assert lane.off(np.array([4.0, 3.0])) < 1e-6


def test_walking_on_before_any_turn_is_predicted_straight_on():
    lanes = learnt(5.0)
    now = walker_at(5.0)
    future = lanes.predict(now, np.array([0.0, 2.0]))
    assert future[1] == pytest.approx([4.0, now.y + 2.0 * SPEED], abs=0.02)


def test_after_a_turn_the_walker_is_predicted_to_turn_again_at_the_far_end():
    lanes = learnt(16.0)  # up to 6.0 (7.1 s), down to 1.0 (14.3 s), up again
    assert len(lanes.lanes) == 1 and lanes.lanes[0].turned
    lane = lanes.lanes[0]
    ends = sorted(lane.origin[1] + np.array([lane.low_m, lane.high_m]) * lane.direction[1])
    assert ends == pytest.approx([1.0, 6.0], abs=0.1)
    now = walker_at(16.0)  # y = 2.2 going up
    times = np.arange(0.0, 12.0, 0.5)
    truth = np.array([[walker_at(16.0 + t).x, walker_at(16.0 + t).y] for t in times])
    assert np.abs(lanes.predict(now, times) - truth).max() < 0.15
    straight = now.y + SPEED * times  # what constant velocity says: through the wall at y = 6
    assert np.abs(straight - truth[:, 1]).max() > 3.0


def test_clear_forgets_the_lanes_and_the_legs_so_learning_starts_afresh():
    lanes = learnt(5.0)  # one straight leg up from y = 1.0: a lane
    assert len(lanes.lanes) == 1
    now = walker_at(5.0)
    lanes.clear()
    assert lanes.lanes == [] and lanes.lane_of(now) is None
    lanes.update(5.1, [walker_at(5.1)])  # a remembered leg would make the lane again at once; one point does not
    assert lanes.lanes == []
    assert learnt(5.1).lanes  # (as it would without the clear)


def test_a_walker_standing_at_a_lane_end_is_turning_and_walks_back_at_the_lanes_speed():
    lanes = learnt(16.0)
    standing = Track(1, 4.0, 6.0, 0.0, 0.0, 0.2, 16.0, 10)
    turning = lanes.turning_at(standing)
    assert turning is not None and turning[1] * turning[0].direction[1] < 0.0  # back down
    assert abs(turning[1]) == pytest.approx(SPEED, rel=0.05)
    assert lanes.predict(standing, np.array([2.0]))[0] == pytest.approx([4.0, 6.0 - 2.0 * SPEED], abs=0.1)
    elsewhere = Track(2, 4.0, 3.5, 0.0, 0.0, 0.2, 16.0, 10)  # standing mid-lane: not turning
    assert lanes.turning_at(elsewhere) is None


def test_a_track_off_the_lane_or_across_it_is_predicted_at_constant_velocity():
    lanes = learnt(16.0)
    across = Track(2, 3.0, 3.0, 0.8, 0.0, 0.2, 16.0, 10)
    assert lanes.lane_of(across) is None
    assert lanes.predict(across, np.array([1.0]))[0] == pytest.approx([3.8, 3.0])


def test_a_second_walker_on_the_same_line_joins_the_lane():
    lanes = WalkerLanes()
    for k in range(60):
        t = k * DT
        lanes.update(t, [walker_at(t), walker_at(t + 3.0, track_id=2)])
    assert len(lanes.lanes) == 1


def test_a_lane_nobody_walks_is_forgotten():
    lanes = WalkerLanes(LaneParams(forget_s=5.0))
    for k in range(40):
        lanes.update(k * DT, [walker_at(k * DT)])
    assert lanes.lanes
    lanes.update(10.0, [])
    assert not lanes.lanes


def test_bounce_reflects_between_the_ends():
    assert bounce(np.array([0.5, 1.5, 2.5, -0.5]), 0.0, 1.0) == pytest.approx([0.5, 0.5, 0.5, 0.5])
    assert bounce(np.array([3.0]), 2.0, 2.0) == pytest.approx([2.0])


def test_fit_line_gives_the_principal_axis_and_the_worst_residual():
    points = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [1.0, 1.2]])
    centre, direction, worst = fit_line(points)
    assert abs(abs(direction @ np.array([1.0, 1.0]) / math.sqrt(2.0)) - 1.0) < 0.01
    assert 0.1 < worst < 0.2 and centre == pytest.approx(points.mean(axis=0))


@pytest.mark.parametrize("field, value", [("min_leg_m", 0.0), ("leg_s", -1.0), ("max_points", 1),
                                          ("angle_tolerance_deg", math.nan)])
def test_parameters_are_validated_by_name(field, value):
    with pytest.raises(ConfigError, match=field):
        LaneParams(**{field: value})
