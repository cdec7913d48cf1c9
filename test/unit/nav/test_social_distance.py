"""The social-distance speed limit (slow down, stop 0.3 m from a person, never drive toward one) and whose doing a
contact was (no ROS)."""

from __future__ import annotations

import math
from typing import List, Tuple

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.social_distance import (
    SocialDistanceRule,
    SocialParams,
    contact_cause,
    footprint_distance,
)
from flex_nav.nav.footprint import circle_footprint
from flex_nav.perception.moving_obstacles import Track

ROUND = circle_footprint(0.171)  # TurtleBot 4
SQUARE = np.array([[0.2, 0.2], [-0.2, 0.2], [-0.2, -0.2], [0.2, -0.2]])
RULE = SocialDistanceRule(SocialParams())


def person(x: float, y: float, vx: float = 0.0, vy: float = 0.0, track_id: int = 1) -> Track:
    return Track(track_id, x, y, vx, vy, 0.2, 0.0, 5)


def test_nobody_near_leaves_the_command_alone() -> None:
    out = RULE.limit((0.0, 0.0, 0.0), ROUND, 0.3, 0.2, [person(10.0, 0.0)])
    assert (out.v, out.w, out.scale, out.limited_by) == (0.3, 0.2, 1.0, None)
    assert out.closest_m == math.inf and out.reason == "no person near"
    far_enough = RULE.limit((0.0, 0.0, 0.0), ROUND, 0.3, 0.0, [person(0.0, 3.0)])  # beside, far
    assert far_enough.scale == 1.0 and far_enough.closest_id == 1


def test_the_limit_falls_as_a_person_ahead_comes_closer_and_is_zero_at_the_distance() -> None:
    limits = []
    for gap in (2.0, 1.5, 1.0, 0.8, 0.6, 0.45, 0.35, 0.3, 0.25):
        centre = 0.171 + gap + 0.2  # the person's body `gap` in front of the footprint
        limits.append(RULE.limit((0.0, 0.0, 0.0), ROUND, 0.3, 0.0, [person(centre, 0.0)]).v)
    assert limits[0] == pytest.approx(0.3)
    assert all(a >= b for a, b in zip(limits, limits[1:]))
    assert limits[-2] == 0.0 and limits[-1] == 0.0  # at 0.3 m and inside: stopped
    assert 0.0 < limits[4] < 0.3


def test_it_never_drives_toward_a_person_inside_the_distance_but_may_leave() -> None:
    near = [person(0.171 + 0.2 + 0.2, 0.0)]  # 0.2 m in front
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, 0.2, 0.0, near).stopped
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, 0.05, 0.3, near).v == 0.0  # an arc toward them too
    back = RULE.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, near)
    assert back.v == -0.2 and back.scale == 1.0 and back.reason.startswith("nearest person #1")


def test_a_person_walking_toward_the_robot_stops_it_earlier() -> None:
    centre = 0.171 + 1.2 + 0.2  # 1.2 m ahead: outside the slowing zone
    speeds = [RULE.limit((0.0, 0.0, 0.0), ROUND, 0.3, 0.0, [person(centre, 0.0, vx=-u)]).v for u in (0.0, 1.0, 1.5)]
    assert speeds[0] == 0.3 and 0.0 < speeds[2] < speeds[1] < 0.3
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, 0.3, 0.0, [person(0.171 + 0.4 + 0.2, 0.0, vx=-2.0)]).stopped


def test_passing_close_beside_a_person_is_slowed_not_stopped() -> None:
    beside = [person(0.5, 0.171 + 0.2 + 0.5)]  # 0.5 m to the left, ahead: the robot drives past
    out = RULE.limit((0.0, 0.0, 0.0), ROUND, 0.3, 0.0, beside)
    assert 0.0 < out.v < 0.3 and "capped" in out.reason


def test_the_footprint_polygon_counts_and_a_turn_swings_its_corners() -> None:
    # a person 0.3 m in front of the square's front face, near its left corner
    people = [person(0.2 + 0.3 + 0.2, 0.15)]
    clockwise = RULE.limit((0.0, 0.0, 0.0), SQUARE, 0.0, -0.5, people)  # the front-left part swings toward them
    assert clockwise.w == 0.0 and clockwise.closest_m == pytest.approx(0.3)
    assert RULE.limit((0.0, 0.0, 0.0), SQUARE, 0.0, 0.5, people).w == 0.5  # swinging away is fine
    roomier = RULE.limit((0.0, 0.0, 0.0), ROUND, 0.0, -0.5, people)  # a round base turning takes no more room
    assert roomier.w == -0.5


def test_the_pose_places_the_footprint() -> None:
    ahead = [person(5.0 + 0.171 + 0.2 + 0.25, 2.0)]
    assert RULE.limit((5.0, 2.0, 0.0), ROUND, 0.3, 0.0, ahead).stopped
    assert RULE.limit((5.0, 2.0, math.pi), ROUND, 0.3, 0.0, ahead).scale == 1.0  # facing away


def drive(people: List[Tuple[float, float, float, float]], goal_x: float = 6.0, seconds: float = 30.0,
          dt: float = 0.05) -> Tuple[float, float]:
    """A robot driving along +x at up to 0.3 m/s (braking at most 0.5 m/s^2, one tick of latency) with the rule;
    people [(x0, y0, vx, vy)] walk at constant velocity (through the robot if it is in their way). Returns (the
    closest distance to a person ahead of the robot while it moved, its final x)."""
    x, speed = 0.0, 0.0
    closest = math.inf
    for step in range(int(seconds / dt)):
        t = step * dt
        tracks = [person(x0 + vx * t, y0 + vy * t, vx, vy, i) for i, (x0, y0, vx, vy) in enumerate(people)]
        wanted = 0.3 if x < goal_x else 0.0
        command = RULE.limit((x, 0.0, 0.0), ROUND, wanted, 0.0, tracks).v
        speed = max(command, speed - 0.5 * dt) if command < speed else min(command, speed + 0.5 * dt)
        x += speed * dt
        if speed > 0.02:
            polygon = ROUND + np.array([x, 0.0])
            for track in (t for t in tracks if t.x > x):  # behind it, a person walks into a robot driving away
                distance = footprint_distance(polygon, (track.x + track.vx * dt, track.y + track.vy * dt))[0]
                closest = min(closest, distance - track.radius)
    return closest, x


def test_driving_at_a_standing_person_stops_at_the_distance() -> None:
    closest, x = drive([(3.0, 0.0, 0.0, 0.0)])
    assert 0.3 - 0.02 <= closest <= 0.45, closest
    assert x < 3.0 - 0.2 - 0.171 - 0.28


def test_a_person_crossing_ahead_is_kept_at_the_distance_while_moving() -> None:
    for y0, vy in ((-3.0, 0.5), (2.5, -0.4), (-2.0, 0.8)):
        closest, _ = drive([(2.0, y0, 0.0, vy)])
        assert closest >= 0.3 - 0.02, (y0, vy, closest)


def test_a_person_walking_head_on_never_comes_closer_than_the_distance_while_the_robot_moves() -> None:
    closest, _ = drive([(4.0, 0.0, -0.5, 0.0)])
    assert closest >= 0.3 - 0.02


def test_contact_with_a_stopped_robot_is_not_its_doing() -> None:
    cause = contact_cause(0.0, 0.0, (0.17, 0.0))
    assert not cause.robot_caused and "stopped" in cause.reason


def test_contact_while_driving_into_the_person_is_its_doing() -> None:
    cause = contact_cause(0.2, 0.0, (0.17, 0.0))
    assert cause.robot_caused and cause.closing_mps == pytest.approx(0.2)
    assert contact_cause(0.0, -1.0, (0.2, 0.1), normal=(1.0, 0.0)).robot_caused  # a square's front swinging
    assert not contact_cause(0.0, 1.0, (0.2, 0.2), normal=(1.0, 1.0)).robot_caused  # a corner turning along


def test_contact_at_the_back_while_driving_away_is_not_its_doing() -> None:
    cause = contact_cause(0.2, 0.0, (-0.17, 0.0))
    assert not cause.robot_caused and "away or along" in cause.reason
    assert not contact_cause(0.2, 0.0, (0.0, 0.17)).robot_caused  # a person's side brushed while passing


def test_a_contact_without_direction_is_refused() -> None:
    with pytest.raises(ConfigError, match="normal"):
        contact_cause(0.2, 0.0, (0.0, 0.0))


def test_footprint_distance_inside_and_outside() -> None:
    assert footprint_distance(SQUARE, (0.0, 0.0))[0] == 0.0
    distance, nearest = footprint_distance(SQUARE, (1.0, 0.0))
    assert distance == pytest.approx(0.8) and np.allclose(nearest, [0.2, 0.0])


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"min_distance_m": 0.0}, "min_distance_m"),
    ({"slow_distance_m": 0.2}, "slow_distance_m"),
    ({"decel_mps2": -1.0}, "decel_mps2"),
    ({"latency_s": -0.1}, "latency_s"),
    ({"max_range_m": 0.5}, "max_range_m"),
])
def test_parameters_are_validated(kwargs: dict, match: str) -> None:
    with pytest.raises(ConfigError, match=match):
        SocialParams(**kwargs)


# issue 28 in S6: the yield rule's last-moment steps back from walkers passing 0.07-0.1 m away, at 0.2 m/s against
# their 0.9 m/s, were the closest approaches "while moving"; the robot now stands for them


def test_a_walker_who_passes_a_standing_robot_is_not_stepped_back_from_at_the_last_moment() -> None:
    walker = [person(0.171 + 0.2 + 0.5, 0.5, vx=-0.9)]  # ahead-left, to pass 0.13 m beside it at 0.9 m/s
    slowed = RULE.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, walker)  # backing away: slower, to stand in time
    assert 0.0 < slowed.scale < 1.0 and "closing in" in slowed.reason
    nearer = [person(0.3, 0.5, vx=-0.9)]
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, nearer).stopped  # too near to step back: stands
    slow = [person(0.171 + 0.2 + 0.5, 0.5, vx=-0.05)]  # barely moving: it may leave
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, slow).scale == 1.0


def test_a_walker_who_would_walk_into_a_standing_robot_may_be_escaped() -> None:
    head_on = [person(0.171 + 0.2 + 0.5, 0.0, vx=-0.9)]  # straight at it
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, head_on).scale == 1.0
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, 0.0, 0.0, head_on).scale == 1.0  # no motion: nothing to limit


def test_inside_the_distance_it_stands_for_a_walker_passing_until_they_are_past() -> None:
    abeam = [person(0.0, 0.171 + 0.2 + 0.15, vx=0.8)]  # 0.15 m to the left, walking past, not closing
    out = RULE.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, abeam)
    assert out.stopped and "walking past" in out.reason
    standing = [person(0.171 + 0.2 + 0.15, 0.0)]  # a person standing in front: the robot may back away
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, standing).scale == 1.0


def test_leaving_scale_is_the_largest_that_stands_before_the_gap_is_used() -> None:
    rule = SocialDistanceRule(SocialParams(latency_s=0.2, decel_mps2=0.5))
    assert rule.leaving_scale(0.5, -0.3, 0.3, 0.1) == 1.0  # leaves faster than they come
    assert rule.leaving_scale(0.1, -0.1, 0.2, 0.9) == 0.0  # their approach in the latency alone uses it up
    k = rule.leaving_scale(0.4, 0.0, 0.3, 0.6)  # passing along, a person coming at 0.6 m/s
    assert 0.0 < k < 1.0
    assert rule.gap_used(k, 0.0, 0.3, 0.6) == pytest.approx(0.4, abs=1e-6)
    assert rule.leaving_scale(-0.05, -0.2, 0.2, 0.0) == 1.0  # inside the distance, a standing person: may leave


def test_standing_miss_is_the_gap_a_walker_keeps_to_a_standing_robot() -> None:
    from flex_nav.nav.control.social_distance import standing_miss_m  # noqa: PLC0415

    assert standing_miss_m((0.0, 0.0, 0.0), 0.2, person(3.0, 1.0, vx=-1.0)) == pytest.approx(1.0 - 0.2 - 0.2)
    assert standing_miss_m((0.0, 0.0, 0.0), 0.2, person(3.0, 0.1, vx=-1.0)) < 0.0  # walks into it
    assert standing_miss_m((0.0, 0.0, 0.0), 0.2, person(3.0, 0.1, vx=1.0)) == pytest.approx(3.0 - 0.4, abs=0.01)


def test_a_robot_backing_from_walkers_keeps_the_distance_while_it_moves() -> None:
    """Closed loop: a robot asked to back up at 0.2 m/s the whole time while a walker passes 0.1-0.5 m beside it at
    0.9 m/s: whenever it moves, everyone is >= 0.3 m from its footprint (it stands while they pass)."""
    for lateral in (0.1, 0.3, 0.5):
        x, speed, closest = 0.0, 0.0, math.inf
        y0 = 0.171 + 0.2 + lateral
        dt = 0.05
        for step in range(200):
            t = step * dt
            walker = person(3.0 - 0.9 * t, y0, vx=-0.9)
            command = RULE.limit((x, 0.0, 0.0), ROUND, -0.2, 0.0, [walker]).v
            speed = max(command, speed - 0.5 * dt) if command < speed else min(command, speed + 0.5 * dt)
            x += speed * dt
            if abs(speed) > 0.02:
                gap = footprint_distance(ROUND + np.array([x, 0.0]), (walker.x - 0.9 * dt, walker.y))[0] - 0.2
                closest = min(closest, gap)
        assert closest >= 0.3 - 0.02, (lateral, closest)


def test_a_walker_predicted_to_pass_within_escape_miss_may_be_stepped_away_from() -> None:
    grazing = [person(0.6, 0.171 + 0.2 + 0.05, vx=-0.9)]  # to pass 0.05 m beside
    assert RULE.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, grazing).stopped  # default 0: it stands
    lenient = SocialDistanceRule(SocialParams(escape_miss_m=0.1))  # within the tracking error: may step away
    assert lenient.limit((0.0, 0.0, 0.0), ROUND, -0.2, 0.0, grazing).scale == 1.0


def test_stepping_aside_across_a_walkers_way_is_not_slowed_by_the_speed_cap() -> None:
    # a walker 0.43 m from the footprint coming straight at the robot's centre: standing, it would be walked into;
    # driving across their way (not toward them) goes at full speed, where a person standing there caps it
    walking_in = RULE.limit((0.0, 0.0, 0.0), ROUND, 0.26, 0.0, [person(0.0, -0.8, vy=0.7)])
    assert walking_in.scale == 1.0, walking_in.reason
    standing = RULE.limit((0.0, 0.0, 0.0), ROUND, 0.26, 0.0, [person(0.0, -0.8)])  # the same place, standing
    assert standing.scale < 0.5 and "capped" in standing.reason, standing.reason
