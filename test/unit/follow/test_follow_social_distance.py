"""SafeFollower with the social distance rule: a standing person ahead slows the robot from slow_distance_m and
stops it min_distance_m from them; walking away and nobody near are not limited; the rule needs a footprint."""

from __future__ import annotations

from typing import Callable, List, Optional

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.controller import Decision, Outcome, SafeFollower
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.control.social_distance import SocialDistanceRule, SocialParams, footprint_distance
from flex_nav.nav.footprint import circle_footprint
from flex_nav.nav.planar import Pose2D
from flex_nav.perception.moving_obstacles import Track

RADIUS_M = 0.17  # [m] the robot's
SOCIAL = SocialParams(min_distance_m=0.3, slow_distance_m=1.0, max_speed_mps=0.31)
PURSUIT = PurePursuitParams(desired_linear_vel=0.3, lookahead_dist=0.5, goal_dist_tol=0.1, use_final_heading=False)


def follower(social: Optional[SocialDistanceRule]) -> SafeFollower:
    f = SafeFollower(PURSUIT, sensors=("odom",), sensor_timeout_s=0.5, collision_timeout_s=1.0, nominal_period_s=0.05,
                     start_s=0.0, social=social, footprint=circle_footprint(RADIUS_M) if social else None)
    f.set_path(np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]))
    return f


def standing(x: float, y: float = 0.0, radius: float = 0.2) -> Track:
    return Track(1, x, y, 0.0, 0.0, radius, 0.0, 10)


def pose_at(x: float) -> Callable[[], Pose2D]:
    return lambda: (x, 0.0, 0.0)


def drive(f: SafeFollower, people: List[Track], start_x: float = 0.0, seconds: float = 20.0) -> List[Decision]:
    """Closed loop on a kinematic robot along +x at 20 Hz; the decisions in order."""
    x, v, decisions = start_x, 0.0, []
    for k in range(int(seconds / 0.05)):
        now = 0.05 * (k + 1)
        f.watchdog.saw("odom", now)
        d = f.tick(now, pose_at(x), (v, 0.0), lambda: None, lambda: people)
        decisions.append(d)
        v = d.v
        x += v * 0.05
    return decisions


def test_a_standing_person_ahead_stops_the_robot_at_the_distance() -> None:
    person = standing(3.0)
    decisions = drive(follower(SocialDistanceRule(SOCIAL)), [person])
    assert all(d.outcome is Outcome.RUNNING for d in decisions)
    at = np.concatenate([[0.0], np.cumsum([0.05 * d.v for d in decisions])])  # x before each decision, and after
    gaps = [footprint_distance(circle_footprint(RADIUS_M) + np.array([x, 0.0]), (person.x, person.y))[0]
            - person.radius for x in at]
    assert min(gaps) >= SOCIAL.min_distance_m - 0.02  # kept while moving (the polygon's sides, 2 cm)
    assert decisions[-1].v == pytest.approx(0.0, abs=1e-3)  # stopped in front of them, not past them
    assert any(d.social is not None and d.social.limited_by == 1 for d in decisions)
    # inside slow_distance_m the cap falls linearly from max_speed_mps (0.31) to 0 at min_distance_m: below
    # 0.8 m it is under 0.23 m/s, the 0.3 m/s the controller asks
    near = [d for d, gap in zip(decisions, gaps[:-1]) if gap < 0.8 and d.v > 0.0]
    assert near and max(d.v for d in near) < 0.31 * (0.8 - 0.3) / 0.7 + 1e-6


def test_without_the_rule_the_robot_drives_into_the_person() -> None:
    person = standing(3.0)
    decisions = drive(follower(None), [person], seconds=15.0)
    xs = np.cumsum([0.05 * d.v for d in decisions])
    assert xs[-1] > 3.0  # nothing held it: the kinematic robot passed through the person's place


def test_nobody_near_and_people_behind_leave_the_command_alone() -> None:
    behind = standing(-1.5)  # the robot drives away from them
    for people in ([], [behind]):
        decisions = drive(follower(SocialDistanceRule(SOCIAL)), people, seconds=3.0)
        assert all(d.social is None for d in decisions)
        assert decisions[-1].v == pytest.approx(PURSUIT.desired_linear_vel, rel=0.05)


def test_the_rule_needs_a_footprint() -> None:
    with pytest.raises(ConfigError, match="footprint"):
        SafeFollower(PURSUIT, sensors=("odom",), sensor_timeout_s=0.5, collision_timeout_s=1.0,
                     nominal_period_s=0.05, start_s=0.0, social=SocialDistanceRule(SOCIAL))
    with pytest.raises(ConfigError, match="footprint"):
        SafeFollower(PURSUIT, sensors=("odom",), sensor_timeout_s=0.5, collision_timeout_s=1.0,
                     nominal_period_s=0.05, start_s=0.0, social=SocialDistanceRule(SOCIAL),
                     footprint=np.zeros((2, 2)))
