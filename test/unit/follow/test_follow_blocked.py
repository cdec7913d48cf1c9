"""Blocked-path detection: obstacle_on_path, BlockedPathWatch and SafeFollower aborting with reason `blocked`."""

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.blocked import BlockedPathWatch, PathObstacle, obstacle_on_path
from flex_nav.nav.control.controller import Outcome, SafeFollower
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.costmap.costmap_grid import INSCRIBED, LETHAL, NO_INFORMATION, CostmapGeometry
from flex_nav.nav.path import cumulative_lengths

GEOMETRY = CostmapGeometry(100, 40, 0.05, -0.5, -1.0)  # x -0.5..4.5, y -1..1
STRAIGHT = np.array([[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]])  # sparse: two corners only
PARAMS = PurePursuitParams(desired_linear_vel=0.5, lookahead_dist=0.6, goal_dist_tol=0.1, use_final_heading=False,
                           use_collision_detection=False)


def on_path(path, s_from, costs, distance_m=2.0):
    return obstacle_on_path(path, cumulative_lengths(path), s_from, distance_m=distance_m, costs=costs,
                            geometry=GEOMETRY)


def costmap_with(x, y=0.0, cost=LETHAL, fill=0):
    costs = np.full(GEOMETRY.shape, fill, dtype=np.uint8)
    row, col = GEOMETRY.world_to_cell(x, y)
    costs[row, col] = cost
    return costs


def test_obstacle_between_sparse_path_points_is_found_with_its_distance():
    found = on_path(STRAIGHT, 0.5, costmap_with(1.8))
    assert found is not None
    assert found.ahead_m == pytest.approx(1.3, abs=0.06)
    assert found.x == pytest.approx(1.8, abs=0.05) and found.y == pytest.approx(0.0)


@pytest.mark.parametrize("x", [0.3, 2.6, 3.5])  # behind the robot, beyond the distance, beyond the distance
def test_obstacle_outside_the_watched_stretch_is_ignored(x):
    assert on_path(STRAIGHT, 0.5, costmap_with(x)) is None


@pytest.mark.parametrize("cost, blocks", [(INSCRIBED, True), (LETHAL, True), (INSCRIBED - 1, False),
                                          (NO_INFORMATION, False)])
def test_which_costs_block(cost, blocks):
    found = on_path(STRAIGHT, 0.0, costmap_with(1.0, cost=cost))
    assert (found is not None) is blocks


def test_unknown_cells_block_when_asked_to():  # pure pursuit without allow_unknown
    costs = costmap_with(1.0, cost=NO_INFORMATION)
    found = obstacle_on_path(STRAIGHT, cumulative_lengths(STRAIGHT), 0.0, distance_m=2.0, costs=costs,
                             geometry=GEOMETRY, unknown_blocks=True)
    assert found is not None and found.x == pytest.approx(1.0, abs=0.05)
    assert on_path(STRAIGHT, 0.0, costs) is None


def test_off_grid_path_is_not_blocked():
    far = np.array([[10.0, 10.0], [12.0, 10.0]])
    assert on_path(far, 0.0, costmap_with(1.0)) is None


def test_watch_needs_the_obstacle_for_the_timeout_without_a_gap():
    watch = BlockedPathWatch(1.0, 0.5)
    hit = PathObstacle(1.0, 0.0, 0.5)
    assert watch.update(hit, 0.0) is None
    assert watch.update(hit, 0.3) is None
    assert watch.update(None, 0.4) is None  # a free tick restarts the time
    assert watch.update(hit, 0.5) is None
    assert watch.update(hit, 0.9) is None
    reason = watch.update(hit, 1.0)
    assert reason is not None and reason.startswith("blocked") and "0.50 m ahead" in reason


@pytest.mark.parametrize("distance, timeout", [(-1.0, 0.5), (1.0, float("nan")), (float("inf"), 0.5)])
def test_watch_rejects_bad_parameters(distance, timeout):
    with pytest.raises(ConfigError, match="blocked_"):
        BlockedPathWatch(distance, timeout)


def follower(distance_m):
    return SafeFollower(PARAMS, sensors=("odom",), sensor_timeout_s=0.5, collision_timeout_s=2.0,
                        nominal_period_s=0.05, start_s=0.0, blocked_distance_m=distance_m, blocked_timeout_s=0.2)


def run(f, costs, ticks=10):
    decisions = []
    for k in range(ticks):
        now = 0.05 * (k + 1)
        f.watchdog.saw("odom", now)
        decisions.append(f.tick(now, lambda: (0.5, 0.0, 0.0), (0.3, 0.0), lambda: (costs, GEOMETRY)))
        if decisions[-1].outcome is not Outcome.RUNNING:
            break
    return decisions


def test_follower_aborts_blocked_and_stops_after_the_timeout():
    f = follower(1.0)
    f.set_path(STRAIGHT)
    decisions = run(f, costmap_with(1.2))
    last = decisions[-1]
    assert last.outcome is Outcome.ABORTED and last.stops
    assert last.reason.startswith("blocked: obstacle on the path 0.7")
    assert all(d.outcome is Outcome.RUNNING for d in decisions[:-1])
    assert 4 <= len(decisions) <= 6  # 0.2 s at 0.05 s per tick
    assert f.pursuit.path is None


def test_a_path_replaced_at_every_tick_still_ends_blocked_and_a_new_goal_starts_afresh():
    """FollowTopic replaces the path with every plan: that must not restart the blocked time (it would never
    reach the timeout), while a new goal after stop() must not inherit the old goal's time."""
    f = follower(1.0)
    costs = costmap_with(1.2)
    decisions = []
    for k in range(10):
        now = 0.05 * (k + 1)
        f.set_path(STRAIGHT)  # a new plan, the same way
        f.watchdog.saw("odom", now)
        decisions.append(f.tick(now, lambda: (0.5, 0.0, 0.0), (0.3, 0.0), lambda: (costs, GEOMETRY)))
        if decisions[-1].outcome is not Outcome.RUNNING:
            break
    assert decisions[-1].outcome is Outcome.ABORTED and decisions[-1].reason.startswith("blocked")
    assert 4 <= len(decisions) <= 6  # 0.2 s at 0.05 s per tick, as with one path

    f = follower(1.0)
    f.set_path(STRAIGHT)
    for k in range(3):  # 0.15 s blocked, less than the timeout
        f.watchdog.saw("odom", 0.05 * (k + 1))
        d = f.tick(0.05 * (k + 1), lambda: (0.5, 0.0, 0.0), (0.3, 0.0), lambda: (costs, GEOMETRY))
        assert d.outcome is Outcome.RUNNING
    f.stop()
    f.set_path(STRAIGHT)  # the next goal, 0.25 s after the first blocked tick: its own time starts now
    f.watchdog.saw("odom", 0.3)
    assert f.tick(0.3, lambda: (0.5, 0.0, 0.0), (0.0, 0.0), lambda: (costs, GEOMETRY)).outcome is Outcome.RUNNING


def test_follower_drives_on_when_the_obstacle_is_farther_than_the_distance():
    f = follower(1.0)
    f.set_path(STRAIGHT)
    decisions = run(f, costmap_with(2.0))
    assert all(d.outcome is Outcome.RUNNING for d in decisions)
    assert decisions[-1].v > 0.0


def test_follower_without_blocked_distance_never_aborts_blocked():
    f = follower(0.0)
    f.set_path(STRAIGHT)
    decisions = run(f, costmap_with(1.2))
    assert all(d.outcome is Outcome.RUNNING for d in decisions)
