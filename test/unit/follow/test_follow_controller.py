"""SafeFollower: every way a controller goal ends, and that each non-running decision stops the robot."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.nav.control.controller import Decision, Outcome, SafeFollower
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.costmap.costmap_grid import LETHAL, CostmapGeometry

STRAIGHT = np.array([[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]])
PARAMS = PurePursuitParams(desired_linear_vel=0.5, lookahead_dist=0.6, goal_dist_tol=0.1, use_final_heading=False)


def follower(collision_timeout_s=1.0, sensors=("odom", "scan")):
    f = SafeFollower(PARAMS, sensors=sensors, sensor_timeout_s=0.5, collision_timeout_s=collision_timeout_s,
                     nominal_period_s=0.05, start_s=0.0)
    return f


def following(collision_timeout_s=1.0):
    """A follower given the STRAIGHT path."""
    f = follower(collision_timeout_s)
    f.set_path(STRAIGHT)
    return f


def fresh(f, now_s):
    for name in ("odom", "scan"):
        f.watchdog.saw(name, now_s)


def tick_fresh(f, now_s, pose, velocity, costmap):
    """One tick at ``now_s`` with both sensors just seen."""
    fresh(f, now_s)
    return f.tick(now_s, pose, velocity, costmap)


def at(x, y=0.0, yaw=0.0):
    return lambda: (x, y, yaw)


def no_costmap():
    return None


def test_drives_forward_along_the_path():
    f = following()
    v = 0.0
    for k in range(10):
        now = 0.05 * (k + 1)
        d = tick_fresh(f, now, at(0.5), (v, 0.0), no_costmap)
        assert d.outcome is Outcome.RUNNING
        assert d.w == pytest.approx(0.0, abs=1e-9)
        assert d.v > v or d.v == pytest.approx(0.5)
        v = d.v
    assert v == pytest.approx(0.5)


def test_goal_reached_succeeds_with_zero():
    f = following()
    d = tick_fresh(f, 1.0, at(2.95), (0.2, 0.0), no_costmap)
    assert d.outcome is Outcome.SUCCEEDED and d.stops and d.reason == "goal reached"
    assert f.pursuit.path is None  # forgotten after the goal ended


@pytest.mark.parametrize("stale", ["odom", "scan"])
def test_stale_sensor_aborts_with_zero_and_names_it(stale):
    f = following()
    fresh(f, 1.0)
    assert f.tick(1.2, at(0.5), (0.3, 0.0), no_costmap).outcome is Outcome.RUNNING
    f.watchdog.saw("odom" if stale == "scan" else "scan", 1.6)
    d = f.tick(1.6, at(0.5), (0.3, 0.0), no_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops
    assert d.reason.startswith(f"stale {stale}")


def with_grace(grace_s):
    f = SafeFollower(PARAMS, sensors=("odom", "scan"), sensor_timeout_s=0.5, collision_timeout_s=1.0,
                     nominal_period_s=0.05, start_s=0.0, sensor_grace_s=grace_s)
    f.set_path(STRAIGHT)
    return f


def test_a_late_scan_within_the_grace_stops_the_robot_and_the_goal_goes_on():
    f = with_grace(1.5)
    fresh(f, 1.0)
    assert f.tick(1.2, at(0.5), (0.3, 0.0), no_costmap).v > 0.0
    f.watchdog.saw("odom", 1.6)  # the scan is 0.6 s old: stale
    held = f.tick(1.6, at(0.5), (0.3, 0.0), no_costmap)
    assert held.outcome is Outcome.RUNNING and held.stops  # a zero command at once, the goal kept
    assert held.reason.startswith("stale scan") and "waiting up to 1.5 s" in held.reason
    fresh(f, 2.0)  # it came back
    again = f.tick(2.0, at(0.5), (0.0, 0.0), no_costmap)
    assert again.outcome is Outcome.RUNNING and 0.0 < again.v <= 2.5 * 0.05 + 1e-9  # ramps up from the stop
    f.watchdog.saw("odom", 3.0)  # stale again: the grace starts afresh
    assert f.tick(3.0, at(0.6), (0.0, 0.0), no_costmap).outcome is Outcome.RUNNING


def test_a_sensor_stale_beyond_the_grace_aborts_and_says_how_long_it_waited():
    f = with_grace(1.5)
    fresh(f, 1.0)
    for now_s in (1.6, 2.5, 3.0):
        f.watchdog.saw("odom", now_s)
        assert f.tick(now_s, at(0.5), (0.0, 0.0), no_costmap).outcome is Outcome.RUNNING
    f.watchdog.saw("odom", 3.1)
    ended = f.tick(3.1, at(0.5), (0.0, 0.0), no_costmap)  # 1.5 s after it went stale at 1.6
    assert ended.outcome is Outcome.ABORTED and ended.stops
    assert ended.reason.startswith("stale scan") and ended.reason.endswith("(stopped 1.5 s waiting for it)")


def test_a_negative_grace_is_refused():
    with pytest.raises(ConfigError, match="sensor_grace_s"):
        with_grace(-1.0)


def test_sensor_never_seen_aborts_after_grace():
    f = following()
    d = f.tick(0.6, at(0.5), (0.0, 0.0), no_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops and "since start" in d.reason


def test_pose_failure_aborts_with_reason():
    f = following()
    fresh(f, 1.0)

    def no_pose():
        raise NotReadyError("no transform map -> base_footprint")

    d = f.tick(1.0, no_pose, (0.0, 0.0), no_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops
    assert "no transform map -> base_footprint" in d.reason


def test_any_exception_aborts_with_zero():
    f = following()
    fresh(f, 1.0)

    def broken_costmap():
        raise ZeroDivisionError("bug")

    d = f.tick(1.0, at(0.5), (0.3, 0.0), broken_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops
    assert d.reason.startswith("internal error in the control step: ZeroDivisionError")


def test_without_path_aborts():
    f = follower()
    d = tick_fresh(f, 1.0, at(0.5), (0.0, 0.0), no_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops and "no path" in d.reason


def test_nan_pose_aborts():
    f = following()
    d = tick_fresh(f, 1.0, at(math.nan), (0.0, 0.0), no_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops and "not finite" in d.reason


def blocked_costmap():
    geometry = CostmapGeometry(80, 40, 0.05, -1.0, -1.0)
    costs = np.zeros(geometry.shape, dtype=np.uint8)
    _row, col = geometry.world_to_cell(0.6, 0.0)
    costs[:, col : col + 2] = LETHAL  # a wall across the path 0.1 m ahead of x = 0.5 (one step's reach)
    return costs, geometry


def test_collision_waits_then_aborts():
    f = following(collision_timeout_s=1.0)
    d = tick_fresh(f, 1.0, at(0.5), (0.3, 0.0), blocked_costmap)
    assert d.outcome is Outcome.RUNNING and d.stops and "collision ahead" in d.reason
    assert tick_fresh(f, 1.5, at(0.5), (0.0, 0.0), blocked_costmap).outcome is Outcome.RUNNING
    d = tick_fresh(f, 2.0, at(0.5), (0.0, 0.0), blocked_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops and "blocked for 1.00 s" in d.reason


def test_collision_clears_and_resets_patience():
    f = following(collision_timeout_s=1.0)
    assert tick_fresh(f, 1.0, at(0.5), (0.0, 0.0), blocked_costmap).stops
    d = tick_fresh(f, 1.9, at(0.5), (0.0, 0.0), no_costmap)
    assert d.outcome is Outcome.RUNNING and d.v > 0.0
    assert tick_fresh(f, 2.5, at(0.5), (0.0, 0.0), blocked_costmap).outcome is Outcome.RUNNING  # patience restarted


def test_replaced_path_does_not_restart_collision_patience():
    """A planner replacing the path every second must not keep a blocked robot waiting forever."""
    f = following(collision_timeout_s=1.0)
    assert tick_fresh(f, 1.0, at(0.5), (0.3, 0.0), blocked_costmap).outcome is Outcome.RUNNING
    f.set_path(STRAIGHT)
    assert tick_fresh(f, 1.5, at(0.5), (0.0, 0.0), blocked_costmap).outcome is Outcome.RUNNING
    f.set_path(STRAIGHT)
    d = tick_fresh(f, 2.0, at(0.5), (0.0, 0.0), blocked_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops and "blocked for 1.00 s" in d.reason


def test_zero_collision_timeout_aborts_at_once():
    f = following(collision_timeout_s=0.0)
    d = tick_fresh(f, 1.0, at(0.5), (0.3, 0.0), blocked_costmap)
    assert d.outcome is Outcome.ABORTED and d.stops


def test_bad_path_and_parameters_raise():
    f = follower()
    with pytest.raises(ConfigError, match="empty"):
        f.set_path(np.empty((0, 3)))
    with pytest.raises(ConfigError, match="collision_timeout_s"):
        follower(collision_timeout_s=-1.0)
    with pytest.raises(ConfigError, match="sensor timeout"):
        SafeFollower(PARAMS, sensors=["odom"], sensor_timeout_s=0.0, collision_timeout_s=1.0,
                     nominal_period_s=0.05, start_s=0.0)


def test_no_running_command_leaves_beyond_the_configured_speeds():
    """The last guard of every step: max_angular_vel and desired_linear_vel (or a yield rule's hurry speed)."""
    f = follower()
    limited = f._within_limits(Decision(2.0, -9.0, Outcome.RUNNING, "too fast"))
    assert limited.w == pytest.approx(-PARAMS.max_angular_vel)  # the binding limit here
    assert limited.v / limited.w == pytest.approx(2.0 / -9.0)  # same arc, only slower
    assert (limited.outcome, limited.reason) == (Outcome.RUNNING, "too fast")
    fast = f._within_limits(Decision(-2.0, 0.1, Outcome.RUNNING))
    assert (fast.v, fast.w) == pytest.approx((-0.5, 0.025))
    inside = Decision(-0.3, 0.4, Outcome.RUNNING)
    assert f._within_limits(inside) is inside
