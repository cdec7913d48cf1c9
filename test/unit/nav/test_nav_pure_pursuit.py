"""Regulated pure pursuit: regulations, rotate-to-heading, goal handling, collision check, bad input, closed loop."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.pure_pursuit import PurePursuitParams, PursuitStatus, RegulatedPurePursuit
from flex_nav.nav.costmap.costmap_grid import INSCRIBED, LETHAL, NO_INFORMATION, CostmapGeometry

DT = 0.05  # [s]


def straight(length=5.0, n=101, yaw=0.0):
    s = np.linspace(0.0, length, n)
    return np.column_stack([s, np.zeros(n), np.full(n, yaw)])


def controller(path=None, **kwargs):
    ctl = RegulatedPurePursuit(PurePursuitParams(**kwargs))
    ctl.set_path(straight() if path is None else path)
    return ctl


def free_costmap(width=80, height=80, res=0.05, ox=-2.0, oy=-2.0):
    return np.zeros((height, width), dtype=np.uint8), CostmapGeometry(width, height, res, ox, oy)


def test_straight_path_accelerates_within_limits():
    ctl = controller()
    cmd = ctl.step((0.0, 0.0, 0.0), (0.0, 0.0), DT)
    assert cmd.status is PursuitStatus.FOLLOWING and cmd.status.moving
    assert cmd.v == pytest.approx(2.5 * DT) and cmd.w == pytest.approx(0.0)
    assert cmd.carrot == pytest.approx((0.6, 0.0)) and cmd.lookahead == 0.6
    for _ in range(20):
        cmd = ctl.step((0.0, 0.0, 0.0), (cmd.v, cmd.w), DT)
    assert cmd.v == pytest.approx(0.5)  # desired speed, never above


def test_a_closed_loop_is_not_reached_at_its_start():
    """A patrol loop ending where it starts: the robot a hair nearer the closing segment drives the loop."""
    loop = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 0.0]])
    ctl = controller(loop, goal_dist_tol=0.1, use_final_heading=False)
    cmd = ctl.step((-0.003, 0.02, 0.0), (0.0, 0.0), DT)  # 0.003 m from the closing leg, 0.020 m from the first
    assert cmd.status is PursuitStatus.FOLLOWING, cmd.reason
    assert cmd.distance_to_goal == pytest.approx(8.0, abs=0.01)


def test_path_behind_rotates_in_place_towards_it():
    ctl = controller()
    cmd = ctl.step((1.0, 0.0, math.pi * 0.75), (0.0, 0.0), DT)  # facing back-left, path ahead along +x
    assert cmd.status is PursuitStatus.ROTATING_TO_PATH and cmd.v == 0.0
    assert cmd.w == pytest.approx(-3.2 * DT)  # clockwise, limited by max_angular_accel
    cmd = ctl.step((1.0, 0.0, -math.pi * 0.75), (0.0, 0.5), DT)
    assert cmd.w == pytest.approx(0.5 + 3.2 * DT)
    no_rotate = controller(use_rotate_to_heading=False).step((1.0, 0.0, math.pi * 0.75), (0.3, 0.0), DT)
    assert no_rotate.status is PursuitStatus.FOLLOWING


def test_a_spike_in_the_measured_turn_rate_never_lifts_the_command_beyond_max_angular_vel():
    ctl = controller(max_angular_vel=1.8)
    cmd = ctl.step((1.0, 0.0, math.pi * 0.75), (0.0, 3.0), DT)  # odometry says 3 rad/s (a glitch)
    assert cmd.status is PursuitStatus.ROTATING_TO_PATH
    assert abs(cmd.w) <= 1.8  # the rate limit around the measured 3 rad/s alone would give 2.84


def test_rotating_in_place_never_exceeds_max_angular_vel():
    ctl = controller(max_angular_vel=1.0)  # lowered alone: rotate_to_heading_angular_vel keeps its 1.8 default
    w = 0.0
    for _ in range(40):
        cmd = ctl.step((1.0, 0.0, math.pi * 0.75), (0.0, w), DT)
        w = cmd.w
        assert cmd.status is PursuitStatus.ROTATING_TO_PATH and abs(cmd.w) <= 1.0
    assert w == pytest.approx(-1.0)


def test_goal_rotation_then_reached():
    path = straight(yaw=1.0)
    ctl = controller(path, yaw_goal_tolerance=0.01)
    cmd = ctl.step((5.0, 0.05, 0.0), (0.0, 0.0), DT)
    assert cmd.status is PursuitStatus.ROTATING_TO_GOAL and cmd.v == 0.0 and cmd.w > 0.0
    cmd = ctl.step((5.0, 0.05, 0.97), (0.0, 1.0), DT)
    assert cmd.status is PursuitStatus.ROTATING_TO_GOAL and cmd.w == pytest.approx(0.03 / DT)
    cmd = ctl.step((5.0, 0.05, 0.995), (0.0, 0.0), DT)
    assert cmd.status is PursuitStatus.GOAL_REACHED and (cmd.v, cmd.w) == (0.0, 0.0)
    # without a final heading: reached as soon as the position is
    plain = controller(np.array([[0.0, 0.0], [2.0, 0.0]])).step((1.9, 0.1, 2.0), (0.0, 0.0), DT)
    assert plain.status is PursuitStatus.GOAL_REACHED


def test_goal_not_reached_when_near_end_point_but_far_along_path():
    # a loop whose end is next to its start: being at the start is not being at the goal
    path = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.1]])
    cmd = controller(path).step((0.0, 0.0, 0.0), (0.0, 0.0), DT)
    assert cmd.status is PursuitStatus.FOLLOWING


def test_curvature_regulation_slows_on_tight_turns():
    arc = np.array([[0.3 * math.sin(a), 0.3 * (1 - math.cos(a)), a] for a in np.linspace(0, math.pi, 60)])
    arc = np.vstack([arc, [[-2.0, 0.6, math.pi]]])
    tight = controller(arc, lookahead_dist=0.4).step((0.0, 0.0, 0.35), (0.5, 0.0), 1.0)
    loose = controller(lookahead_dist=0.4).step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0)
    assert tight.status is PursuitStatus.FOLLOWING and loose.v == pytest.approx(0.5)
    assert tight.v < 0.5 and tight.v >= 0.25  # floored at regulated_linear_scaling_min_speed
    off = controller(arc, lookahead_dist=0.4, use_regulated_linear_velocity_scaling=False)
    assert off.step((0.0, 0.0, 0.35), (0.5, 0.0), 1.0).v > tight.v


def test_cost_regulation_slows_near_obstacles():
    costs, geo = free_costmap()
    cell = geo.world_to_cell(1.0, 0.0)
    costs[cell] = 200  # about 0.28 m from an obstacle with k=3, r=0.2
    near = controller(regulated_linear_scaling_min_speed=0.0).step((1.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo)
    expected_d = -math.log(200 / 252) / 3.0 + 0.2
    assert near.v == pytest.approx(0.5 * expected_d / 0.6)
    far = controller().step((1.0, 0.0, 0.0), (0.5, 0.0), 1.0, *free_costmap())
    assert far.v == pytest.approx(0.5)


def test_approach_scaling_near_goal():
    ctl = controller()
    cmd = ctl.step((4.7, 0.0, 0.0), (0.5, 0.0), 1.0)
    assert cmd.v == pytest.approx(0.5 * 0.3 / 0.6)
    cmd = controller().step((4.74, 0.0, 0.0), (0.5, 0.0), 1.0)
    assert cmd.v == pytest.approx(max(0.5 * 0.26 / 0.6, 0.05))


def test_velocity_scaled_lookahead_is_clamped():
    ctl = controller(use_velocity_scaled_lookahead_dist=True)
    assert ctl.step((0.0, 0.0, 0.0), (0.0, 0.0), DT).lookahead == 0.3
    assert ctl.step((0.0, 0.0, 0.0), (0.4, 0.0), DT).lookahead == pytest.approx(0.6)
    assert ctl.step((0.0, 0.0, 0.0), (5.0, 0.0), DT).lookahead == 0.9


def test_collision_ahead_stops_the_robot():
    costs, geo = free_costmap()
    costs[geo.world_to_cell(0.45, 0.0)] = LETHAL
    cmd = controller().step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo)
    assert cmd.status is PursuitStatus.COLLISION_AHEAD and (cmd.v, cmd.w) == (0.0, 0.0)
    assert "collision" in cmd.reason and not cmd.status.moving
    # inscribed counts as collision for a circular robot; beyond the carrot it is not checked
    costs[...] = 0
    costs[geo.world_to_cell(0.3, 0.0)] = INSCRIBED
    assert controller().step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo).status is PursuitStatus.COLLISION_AHEAD
    costs[...] = 0
    costs[geo.world_to_cell(1.5, 0.0)] = LETHAL
    assert controller().step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo).status is PursuitStatus.FOLLOWING
    off = controller(use_collision_detection=False)
    costs[geo.world_to_cell(0.3, 0.0)] = LETHAL
    assert off.step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo).status is PursuitStatus.FOLLOWING


def test_robot_on_an_inscribed_cell_may_escape_through_inscribed_cells_only():
    """Right after a bumper contact the robot's own cell is inscribed; it may drive out through inscribed
    cells within collision_escape_dist, never into a lethal cell, and only when it starts inscribed."""
    costs, geo = free_costmap()
    row, col = geo.world_to_cell(0.0, 0.0)
    costs[row - 4 : row + 5, col - 4 : col + 8] = INSCRIBED  # around the robot and 0.35 m ahead
    assert controller().step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo).status is PursuitStatus.COLLISION_AHEAD
    escaping = controller(collision_escape_dist=0.5)
    cmd = escaping.step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo)
    assert cmd.status is PursuitStatus.FOLLOWING and cmd.v > 0.0
    # a lethal cell inside the escape distance still collides
    costs[geo.world_to_cell(0.2, 0.0)] = LETHAL
    assert controller(collision_escape_dist=0.5).step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs,
                                                      geo).status is PursuitStatus.COLLISION_AHEAD
    # inscribed cells beyond the escape distance collide again
    costs[geo.world_to_cell(0.2, 0.0)] = INSCRIBED
    assert controller(collision_escape_dist=0.1).step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs,
                                                      geo).status is PursuitStatus.COLLISION_AHEAD
    # from a free cell, inscribed cells ahead collide whatever the escape distance
    costs[row, col] = 0
    assert controller(collision_escape_dist=0.5).step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs,
                                                      geo).status is PursuitStatus.COLLISION_AHEAD


def test_nearer_carrot_when_the_far_arc_cuts_into_an_obstacle_beside_the_robot():
    """The baseline's trap at the lab's low step: facing north beside bumper contacts, the robot's own cell
    just outside the inscribed band, which starts one cell ahead. The plan first moves west, away from it,
    then north-west; the arc to the 0.6 m carrot starts north through the band. A nearer carrot on the
    clear path turns the robot towards the path instead of stopping for good."""
    costs, geo = free_costmap()
    row, col = geo.world_to_cell(0.0, 0.0)
    costs[row + 1 : row + 12, col : col + 6] = INSCRIBED  # the band: from one cell north of the robot, east
    costs[row + 1 : row + 12, col + 6] = LETHAL  # the contacts
    path = np.array([[0.0, 0.0], [-0.1, 0.0], [-0.4, 0.3], [-0.4, 1.0]])
    pose = (0.01, 0.01, math.pi / 2)
    assert costs[geo.world_to_cell(*pose[:2])] < INSCRIBED
    cmd = controller(path).step(pose, (0.0, 0.0), DT, costs, geo)
    assert cmd.status is PursuitStatus.ROTATING_TO_PATH and cmd.w > 0.0, cmd  # left, towards the path
    assert "lookahead shortened" in cmd.reason and cmd.lookahead < 0.6
    # facing the path's first leg, it drives it (the far arc would still cut the band's corner)
    cmd = controller(path).step((0.01, 0.01, math.radians(150)), (0.0, 0.0), DT, costs, geo)
    assert cmd.status is PursuitStatus.FOLLOWING and cmd.v > 0.0, cmd
    # with an obstacle on the path itself a nearer carrot would only hide it: the robot stops
    costs[geo.world_to_cell(-0.25, 0.15)] = LETHAL
    cmd = controller(path).step(pose, (0.0, 0.0), DT, costs, geo)
    assert cmd.status is PursuitStatus.COLLISION_AHEAD and (cmd.v, cmd.w) == (0.0, 0.0)


def test_unknown_ahead_is_a_collision_unless_allowed():
    costs, geo = free_costmap()
    costs[:, geo.world_to_cell(0.3, 0.0).col :] = NO_INFORMATION
    assert controller().step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo).status is PursuitStatus.COLLISION_AHEAD
    allowed = controller(allow_unknown=True).step((0.0, 0.0, 0.0), (0.5, 0.0), 1.0, costs, geo)
    assert allowed.status is PursuitStatus.FOLLOWING


@pytest.mark.parametrize(
    ("pose", "velocity", "dt", "needle"),
    [
        ((float("nan"), 0.0, 0.0), (0.0, 0.0), DT, "pose"),
        ((0.0, 0.0, float("inf")), (0.0, 0.0), DT, "pose"),
        ((0.0, 0.0, 0.0), (float("nan"), 0.0), DT, "velocity"),
        ((0.0, 0.0, 0.0), (0.0, 0.0), 0.0, "time step"),
        ((0.0, 0.0, 0.0), (0.0, 0.0), float("nan"), "time step"),
    ],
)
def test_invalid_input_gives_zero_command(pose, velocity, dt, needle):
    cmd = controller().step(pose, velocity, dt)
    assert cmd.status is PursuitStatus.INVALID_INPUT and (cmd.v, cmd.w) == (0.0, 0.0) and needle in cmd.reason


def test_no_path_and_half_costmap_are_invalid():
    ctl = RegulatedPurePursuit()
    assert ctl.step((0.0, 0.0, 0.0), (0.0, 0.0), DT).status is PursuitStatus.INVALID_INPUT
    costs, _ = free_costmap()
    assert controller().step((0, 0, 0), (0, 0), DT, costs, None).status is PursuitStatus.INVALID_INPUT
    with pytest.raises(ConfigError, match="empty"):
        ctl.set_path(np.zeros((0, 3)))
    with pytest.raises(ConfigError, match="non-finite"):
        ctl.set_path([[0.0, 0.0], [float("nan"), 0.0]])
    ctl.set_path(straight())
    ctl.clear()
    assert ctl.path is None and ctl.step((0.0, 0.0, 0.0), (0.0, 0.0), DT).status is PursuitStatus.INVALID_INPUT


def test_params_validation_and_from_mapping():
    params = PurePursuitParams.from_mapping({"desired_linear_vel": 1, "use_rotate_to_heading": False})
    assert params.desired_linear_vel == 1.0 and params.use_rotate_to_heading is False
    with pytest.raises(ConfigError, match=r"'desired_vel' is not valid \(valid: desired_linear_vel"):
        PurePursuitParams.from_mapping({"desired_vel": 1.0})
    for bad in (
        {"desired_linear_vel": 0.0},
        {"max_linear_accel": -1.0},
        {"lookahead_dist": float("nan")},
        {"use_rotate_to_heading": 1},
        {"min_lookahead_dist": 1.0, "max_lookahead_dist": 0.5},
        {"cost_scaling_gain": 1.5},
        {"goal_dist_tol": "0.2"},
    ):
        with pytest.raises(ConfigError):
            PurePursuitParams(**bad)


def test_closed_loop_follows_an_l_path_within_limits():
    path = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, math.pi / 2]])
    dense = np.vstack([np.linspace(path[i], path[i + 1], 40, endpoint=False) for i in range(2)] + [path[-1:]])
    dense[40:80, 2] = math.pi / 2
    params = PurePursuitParams()
    ctl = RegulatedPurePursuit(params)
    ctl.set_path(dense)
    x, y, yaw, v, w = 0.0, -0.1, 0.2, 0.0, 0.0
    worst_track = 0.0
    for _ in range(2000):
        cmd = ctl.step((x, y, yaw), (v, w), DT, *free_costmap(200, 200, 0.05, -3.0, -3.0))
        assert abs(cmd.v) <= params.desired_linear_vel + 1e-12 and abs(cmd.w) <= params.max_angular_vel + 1e-12
        assert cmd.v - v <= params.max_linear_accel * DT + 1e-9
        assert v - cmd.v <= params.max_linear_decel * DT + 1e-9 or cmd.status is not PursuitStatus.FOLLOWING
        if cmd.status is PursuitStatus.GOAL_REACHED:
            break
        assert cmd.status.moving, cmd.reason
        v, w = cmd.v, cmd.w
        yaw += w * DT
        x += v * math.cos(yaw) * DT
        y += v * math.sin(yaw) * DT
        worst_track = max(worst_track, cmd.cross_track)
    else:
        pytest.fail("goal not reached")
    assert math.hypot(x - 2.0, y - 2.0) <= params.goal_dist_tol
    assert abs(math.atan2(math.sin(yaw - math.pi / 2), math.cos(yaw - math.pi / 2))) <= params.yaw_goal_tolerance
    assert worst_track < 0.4


def test_closed_loop_turns_the_corner_of_a_sparse_path():
    """A planner's sparse path: a 2.7 m segment (longer than the search window) then a short dog-leg and a
    turn. The robot must take the turn, not turn back and forth at the end of the long segment."""
    path = np.array([[5.55, 0.53], [2.83, 0.53], [2.73, 0.58], [2.68, 0.58], [2.53, 0.73], [2.48, 0.93],
                     [2.43, 1.13], [2.43, 5.58]])
    params = PurePursuitParams(lookahead_dist=0.5, max_lookahead_dist=0.9, use_final_heading=False)
    ctl = RegulatedPurePursuit(params)
    ctl.set_path(path)
    x, y, yaw, v, w = 5.55, 0.53, math.pi, 0.0, 0.0
    for _ in range(2000):
        cmd = ctl.step((x, y, yaw), (v, w), DT)
        if cmd.status is PursuitStatus.GOAL_REACHED:
            break
        v, w = cmd.v, cmd.w
        yaw += w * DT
        x += v * math.cos(yaw) * DT
        y += v * math.sin(yaw) * DT
    else:
        pytest.fail(f"goal not reached; robot at ({x:.2f}, {y:.2f})")
    assert math.hypot(x - 2.43, y - 5.58) <= params.goal_dist_tol


def test_goal_heading_ignored_for_a_path_set_without_final_heading():
    # the same path with yaw: set_path(final_heading=False) makes the position enough; the next path counts again
    path = straight(yaw=1.0)
    ctl = controller(path, yaw_goal_tolerance=0.01)
    ctl.set_path(path, final_heading=False)
    cmd = ctl.step((5.0, 0.05, 0.0), (0.0, 0.0), DT)
    assert cmd.status is PursuitStatus.GOAL_REACHED and (cmd.v, cmd.w) == (0.0, 0.0)
    ctl.set_path(path)
    cmd = ctl.step((5.0, 0.05, 0.0), (0.0, 0.0), DT)
    assert cmd.status is PursuitStatus.ROTATING_TO_GOAL and cmd.w > 0.0
    # use_final_heading false in the parameters wins over a path that asks for it
    off = controller(path, yaw_goal_tolerance=0.01, use_final_heading=False)
    assert off.step((5.0, 0.05, 0.0), (0.0, 0.0), DT).status is PursuitStatus.GOAL_REACHED


def test_closed_loop_turns_to_a_goal_heading_behind_the_robot():
    """A goal facing back along the path (pi from the direction of travel) is reached within the tolerance,
    turning in place at the end (the shortest way) without leaving the goal position."""
    params = PurePursuitParams(desired_linear_vel=0.5, lookahead_dist=0.6, goal_dist_tol=0.15,
                               yaw_goal_tolerance=0.2, max_angular_vel=1.8, rotate_to_heading_angular_vel=1.5)
    ctl = RegulatedPurePursuit(params)
    path = straight(length=2.0, n=41, yaw=0.0)
    path[-1, 2] = -(math.pi - 0.3)  # 171 deg: clockwise is the short way
    ctl.set_path(path)
    x = y = yaw = v = w = 0.0
    turned_at = None
    for _ in range(1000):
        cmd = ctl.step((x, y, yaw), (v, w), DT)
        if cmd.status is PursuitStatus.GOAL_REACHED:
            break
        assert cmd.status.moving, cmd.reason
        if cmd.status is PursuitStatus.ROTATING_TO_GOAL:
            assert cmd.v == 0.0 and cmd.w < 0.0
            turned_at = (x, y) if turned_at is None else turned_at
        v, w = cmd.v, cmd.w
        yaw += w * DT
        x += v * math.cos(yaw) * DT
        y += v * math.sin(yaw) * DT
    else:
        pytest.fail("goal not reached in 1000 steps")
    assert turned_at is not None
    assert math.hypot(x - 2.0, y) <= params.goal_dist_tol
    assert abs(math.atan2(math.sin(path[-1, 2] - yaw), math.cos(path[-1, 2] - yaw))) <= params.yaw_goal_tolerance


@pytest.mark.parametrize("turn", [math.pi - 0.05, -(math.pi - 0.05), 1.0])
def test_the_final_turn_ends_within_tolerance_on_a_base_that_needs_time_to_stop(turn):
    """At the goal, facing away from its heading: the base stops at its own deceleration after the last command
    (a Kobuki: 5 rad/s²), not at once, so the turn must end with the robot standing within the tolerance, not
    merely pass through it."""
    base_accel = 5.0  # [rad/s²] the base's own limit (sim/robots/kobuki.yaml)
    params = PurePursuitParams(rotate_to_heading_angular_vel=1.8, max_angular_accel=3.2, yaw_goal_tolerance=0.2)
    ctl = controller(straight(length=1.0, yaw=0.0), **vars(params))
    x, yaw, w = 1.0, turn, 0.0  # at the end of the path, its heading 0
    for _ in range(400):
        cmd = ctl.step((x, 0.0, yaw), (0.0, w), DT)
        target = cmd.w if cmd.status is PursuitStatus.ROTATING_TO_GOAL else 0.0
        w += max(-base_accel * DT, min(base_accel * DT, target - w))
        yaw += w * DT
        if cmd.status is PursuitStatus.GOAL_REACHED and w == 0.0:
            break
    else:
        pytest.fail("the turn did not end")
    assert abs(math.atan2(math.sin(yaw), math.cos(yaw))) <= params.yaw_goal_tolerance
