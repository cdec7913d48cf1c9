"""Motion states: closed loop on odometry, stall and timeout detection, zero twist on every exit."""

from __future__ import annotations

import math

import pytest
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from unit.states.states_testlib import Harness, KinematicRobot, odometry, path, twists, wall_scan

from flex_nav.behavior import Autonomy, BehaviorStatus, LogLevel, ManualClock, StateMachine
from flex_nav.exceptions import ConfigError
from flex_nav.testing.fake_proxies import FakeProxies
from flex_nav_states.messages import message_age_s
from flex_nav_states.move_distance_state import MoveDistanceState
from flex_nav_states.pure_pursuit_state import PurePursuitState
from flex_nav_states.rear_clearance import gap_ahead_m, gap_behind_m
from flex_nav_states.rotate_angle_state import RotateAngleState
from flex_nav_states.timed_stop_state import TimedStopState
from flex_nav_states.timed_twist_state import TimedTwistState


def with_robot(state, inputs=None, **robot_kwargs):
    h = Harness(state, inputs=inputs)
    robot = KinematicRobot(h, **robot_kwargs)
    return h, robot


def last_twist(h):
    return twists(h)[-1]


def preempt_after(h, drive_s):
    """Start, drive for ``drive_s`` [s], preempt and tick once; the twist commanded just before the preempt."""
    h.start()
    h.run_for(drive_s)
    driving = last_twist(h)
    h.executor.preempt()
    h.tick()
    return driving


# --- MoveDistance -----------------------------------------------------------------------------------------


@pytest.mark.parametrize("distance", [0.25, -0.25, 1.0])
def test_move_distance_drives_the_distance_on_odometry(distance):
    h, robot = with_robot(MoveDistanceState(distance_m=distance, speed_mps=0.2), yaw=0.7)
    result = h.start().run(max_time_s=20.0)
    assert result.outcome == "done", h.log_text()
    along = robot.x * math.cos(0.7) + robot.y * math.sin(0.7)
    assert along == pytest.approx(distance, abs=0.02)
    assert last_twist(h) == (0.0, 0.0)
    signs = {math.copysign(1.0, v) for v, _ in twists(h) if v != 0.0}
    assert signs == {math.copysign(1.0, distance)}
    assert max(abs(v) for v, _ in twists(h)) <= 0.2 + 1e-9


def back_up_with_scan(wall_x, *, wall_from_s=0.0, scan=True):
    """Backs up 0.3 m with the way behind checked; a wall at ``wall_x`` appears at ``wall_from_s``."""
    h, robot = with_robot(MoveDistanceState(distance_m=-0.3, speed_mps=0.15, scan_topic="scan",
                                            robot_radius_m=0.2, clearance_m=0.05))
    sub = h.proxies.subscription("scan", LaserScan)
    h.start()
    start = h.clock.now()
    while h.clock.now() - start < 10.0:
        if scan:
            elapsed = h.clock.now() - start
            sub.inject(wall_scan(h.clock.now(), robot.x, wall_x if elapsed >= wall_from_s else None))
        if h.tick():
            return h, robot, h.executor.result()
        h.advance(0.05)
    raise AssertionError(h.log_text())


def test_backing_up_with_the_way_behind_free_drives_the_distance():
    h, robot, result = back_up_with_scan(wall_x=-0.6)  # the corridor swept ends 0.55 m behind the start
    assert result.outcome == "done", h.log_text()
    assert robot.x == pytest.approx(-0.3, abs=0.02)


def test_backing_up_toward_something_behind_does_not_start():
    h, robot, result = back_up_with_scan(wall_x=-0.45)
    assert result.outcome == "failed"
    assert all(v == 0.0 for v, _ in twists(h)) and robot.x == 0.0
    assert any("0.25 m behind the robot, in the way" in t for t in h.texts(LogLevel.ERROR)), h.log_text()


def test_backing_up_stops_when_someone_steps_in_behind():
    h, robot, result = back_up_with_scan(wall_x=-0.5, wall_from_s=0.8)
    assert result.outcome == "failed"
    assert -0.2 < robot.x < -0.05  # it had started
    assert last_twist(h) == (0.0, 0.0)
    assert any("behind the robot" in t for t in h.texts(LogLevel.ERROR)), h.log_text()


def test_backing_up_without_a_scan_does_not_start():
    h, robot, result = back_up_with_scan(wall_x=-5.0, scan=False)
    assert result.outcome == "failed" and robot.x == 0.0
    assert any("no scan on scan newer than scan_max_age_s 0.5 s" in t for t in h.texts(LogLevel.ERROR))


def test_gap_behind_sees_only_the_corridor_swept():
    scan = LaserScan(angle_min=-math.pi, angle_increment=math.pi / 2, range_min=0.05, range_max=10.0,
                     ranges=[0.5, 0.3, 0.4, 0.3])  # behind, right, ahead, left
    assert gap_behind_m(scan, 0.2, 0.05, 0.3) == pytest.approx(0.3)
    assert gap_behind_m(scan, 0.2, 0.05, 0.0) is None  # 0.5 m behind the centre: beyond 0.25 m
    scan.ranges = [math.inf, 0.3, 0.4, 0.3]  # only beside and ahead: free behind
    assert gap_behind_m(scan, 0.2, 0.05, 1.0) is None
    scan.ranges = [0.04, 0.3, 0.4, 0.3]  # closer than range_min: no return
    assert gap_behind_m(scan, 0.2, 0.05, 1.0) is None


def test_gap_ahead_is_the_mirror_image():
    scan = LaserScan(angle_min=-math.pi, angle_increment=math.pi / 2, range_min=0.05, range_max=10.0,
                     ranges=[0.5, 0.3, 0.4, 0.3])  # behind, right, ahead, left
    assert gap_ahead_m(scan, 0.2, 0.05, 0.3) == pytest.approx(0.2)
    assert gap_ahead_m(scan, 0.2, 0.05, 0.0) is None  # 0.4 m ahead of the centre: beyond 0.25 m
    scan.ranges = [0.5, 0.3, math.inf, 0.3]
    assert gap_ahead_m(scan, 0.2, 0.05, 1.0) is None


def test_move_distance_holds_the_heading():
    h, robot = with_robot(MoveDistanceState(distance_m=1.0, speed_mps=0.2))
    h.start()
    h.run_for(1.0)
    robot.yaw = 0.2  # knocked sideways: the state steers back to the start heading
    result = h.run(max_time_s=20.0)
    assert result.outcome == "done"
    assert abs(robot.yaw) < 0.05
    assert any(w < 0.0 for _, w in twists(h))


def test_move_distance_stall_is_detected():
    h, robot = with_robot(MoveDistanceState(distance_m=0.5, speed_mps=0.2, stall_window_s=1.0))
    h.start()
    h.run_for(0.5)
    robot.blocked = True  # against a wall: commands have no effect
    start = h.clock.now()
    result = h.run(max_time_s=10.0)
    assert result.outcome == "failed"
    assert h.clock.now() - start <= 1.3
    assert any("stalled" in t for t in h.texts(LogLevel.ERROR)), h.log_text()
    assert last_twist(h) == (0.0, 0.0)


def test_move_distance_timeout_when_progress_is_too_slow():
    state = MoveDistanceState(distance_m=1.0, speed_mps=0.2, timeout_s=6.0, stall_distance_m=0.005)
    h, robot = with_robot(state)
    robot.forced_velocity = (0.01, 0.0)  # crawls: progress every window, but far too slow
    start = h.clock.now()
    result = h.start().run(max_time_s=20.0)
    assert result.outcome == "failed"
    assert 6.0 <= h.clock.now() - start <= 6.2
    assert any("timed out" in t for t in h.texts(LogLevel.ERROR)), h.log_text()


def test_move_distance_without_odometry_fails_and_never_drives():
    h = Harness(MoveDistanceState(distance_m=0.5, odom_timeout_s=0.5))
    result = h.start().run(max_time_s=5.0)
    assert result.outcome == "failed"
    assert all(t == (0.0, 0.0) for t in twists(h))
    assert any("no odometry on odom" in t for t in h.texts(LogLevel.ERROR))


def test_move_distance_odometry_lost_midway_fails():
    h, robot = with_robot(MoveDistanceState(distance_m=1.0, odom_timeout_s=0.3))
    h.start()
    h.run_for(0.5)
    robot.odom_every = 0
    result = h.run(max_time_s=5.0)
    assert result.outcome == "failed"
    assert any("stale" in t for t in h.texts(LogLevel.ERROR)), h.log_text()
    assert last_twist(h) == (0.0, 0.0)


def test_move_distance_stale_stamped_odometry_is_not_used():
    h = Harness(MoveDistanceState(distance_m=0.5, odom_timeout_s=0.5))
    h.proxies.subscription("odom", type(odometry(0, 0, 0, 0, 0, 0))).inject(
        odometry(0.0, 0.0, 0.0, 0.0, 0.0, h.clock.now() - 5.0)
    )
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert all(t == (0.0, 0.0) for t in twists(h))


def test_move_distance_preempt_publishes_a_zero_twist():
    h, _robot = with_robot(MoveDistanceState(distance_m=2.0, speed_mps=0.3))
    assert preempt_after(h, 1.0)[0] > 0.1
    assert h.executor.status is BehaviorStatus.PREEMPTED
    assert last_twist(h) == (0.0, 0.0)


def test_move_distance_pause_stops_and_resume_finishes_the_same_distance():
    h, robot = with_robot(MoveDistanceState(distance_m=1.0, speed_mps=0.2, stall_window_s=1.0))
    h.start()
    h.run_for(2.0)
    h.executor.pause()
    h.tick()
    assert last_twist(h) == (0.0, 0.0)
    h.advance(5.0)  # longer than the stall window: paused time must not count as a stall
    h.executor.resume()
    result = h.run(max_time_s=20.0)
    assert result.outcome == "done", h.log_text()
    assert robot.x == pytest.approx(1.0, abs=0.02)


def test_move_distance_commands_carry_stamp_and_frame():
    h, _robot = with_robot(MoveDistanceState(distance_m=0.2, frame_id="robot1/base_footprint",
                                             cmd_topic="robot1/cmd_vel_stamped"), cmd_topic="robot1/cmd_vel_stamped")
    h.start().run(max_time_s=10.0)
    msgs = h.proxies.pub("robot1/cmd_vel_stamped").messages
    assert {m.header.frame_id for m in msgs} == {"robot1/base_footprint"}
    assert msgs[0].header.stamp.to_sec() == pytest.approx(1000.0)


@pytest.mark.parametrize(
    ("params", "match"),
    [
        ({"distance_m": 0.0}, "distance_m"),
        ({"distance_m": float("inf")}, "distance_m"),
        ({"distance_m": 0.5, "speed_mps": 0.0}, "speed_mps"),
        ({"distance_m": 0.5, "speed_mps": 0.1, "timeout_s": 1.0}, "timeout_s"),
        ({"distance_m": 0.5, "stall_distance_m": 0.2}, "stall_distance_m"),
        ({"distance_m": 0.5, "odom_topic": ""}, "odom_topic"),
        ({"distance_m": 0.5, "cmd_topic": "cmd vel"}, "cmd_topic"),
        ({"distance_m": True}, "distance_m"),
    ],
)
def test_move_distance_parameters_are_validated(params, match):
    with pytest.raises(ConfigError, match=match):
        MoveDistanceState(**params)


# --- RotateAngle --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("angle", [math.pi / 2, -math.pi / 2, 1.5 * math.pi, -2.5 * math.pi])
def test_rotate_angle_turns_the_angle_on_odometry(angle):
    h, robot = with_robot(RotateAngleState(angle_rad=angle, angular_speed_radps=1.0), yaw=3.0)
    result = h.start().run(max_time_s=30.0)
    assert result.outcome == "done", h.log_text()
    turned = math.atan2(math.sin(robot.yaw - 3.0), math.cos(robot.yaw - 3.0))
    expected = math.atan2(math.sin(angle), math.cos(angle))
    assert turned == pytest.approx(expected, abs=0.04)
    assert last_twist(h) == (0.0, 0.0)
    assert all(v == 0.0 for v, _ in twists(h))  # in place


def test_rotate_angle_is_closed_loop_not_timed():
    """A robot that turns at half the commanded rate still ends at the angle (it just takes longer)."""
    h, robot = with_robot(RotateAngleState(angle_rad=math.pi / 2, angular_speed_radps=0.5))
    h.start()
    while not h.tick():
        robot.forced_velocity = (0.0, 0.5 * robot.command()[1])
        h.advance(0.05)
    assert h.executor.result().outcome == "done"
    assert robot.yaw == pytest.approx(math.pi / 2, abs=0.04)


def test_rotate_angle_stall_is_detected():
    h, robot = with_robot(RotateAngleState(angle_rad=math.pi, stall_window_s=1.0))
    robot.blocked = True
    start = h.clock.now()
    assert h.start().run(max_time_s=10.0).outcome == "failed"
    assert h.clock.now() - start <= 1.3
    assert any("stalled" in t for t in h.texts(LogLevel.ERROR))
    assert last_twist(h) == (0.0, 0.0)


def test_rotate_angle_timeout():
    h, robot = with_robot(RotateAngleState(angle_rad=math.pi, angular_speed_radps=1.0, timeout_s=4.0,
                                           stall_angle_rad=0.01))
    robot.forced_velocity = (0.0, 0.05)
    assert h.start().run(max_time_s=10.0).outcome == "failed"
    assert any("timed out" in t for t in h.texts(LogLevel.ERROR))


def test_rotate_angle_preempt_publishes_a_zero_twist():
    h, _robot = with_robot(RotateAngleState(angle_rad=3.0))
    assert preempt_after(h, 1.0)[1] > 0.1
    assert last_twist(h) == (0.0, 0.0)


@pytest.mark.parametrize(
    ("params", "match"),
    [
        ({"angle_rad": 0.0}, "angle_rad"),
        ({"angle_rad": 1.0, "angular_speed_radps": -1.0}, "angular_speed_radps"),
        ({"angle_rad": 1.0, "stall_angle_rad": 1.0}, "stall_angle_rad"),
        ({"angle_rad": 3.0, "timeout_s": 1.0}, "timeout_s"),
    ],
)
def test_rotate_angle_parameters_are_validated(params, match):
    with pytest.raises(ConfigError, match=match):
        RotateAngleState(**params)


# --- TimedTwist / TimedStop ----------------------------------------------------------------------------------


def test_timed_twist_publishes_for_the_duration_then_zero():
    h = Harness(TimedTwistState(linear_mps=0.1, angular_radps=-0.2, duration_s=1.0))
    start = h.clock.now()
    assert h.start().run(max_time_s=5.0).outcome == "done"
    published = h.proxies.pub("cmd_vel_stamped").published
    moving = [t for t, m in published if m.twist.linear.x != 0.0]
    assert moving and min(moving) == start and max(moving) < start + 1.0
    assert all((m.twist.linear.x, m.twist.angular.z) == (0.1, -0.2) for t, m in published if t < start + 1.0)
    assert last_twist(h) == (0.0, 0.0)
    assert 19 <= len(moving) <= 21  # 20 Hz


def test_timed_twist_preempt_publishes_zero():
    h = Harness(TimedTwistState(linear_mps=0.1, duration_s=5.0))
    preempt_after(h, 1.0)
    assert last_twist(h) == (0.0, 0.0)


def test_timed_stop_done_when_the_robot_stands():
    h, robot = with_robot(TimedStopState(duration_s=0.5))
    robot.v = 0.3
    assert h.start().run(max_time_s=5.0).outcome == "done"
    assert set(twists(h)) == {(0.0, 0.0)}


def test_timed_stop_fails_if_still_moving():
    h, robot = with_robot(TimedStopState(duration_s=0.5))
    robot.forced_velocity = (0.2, 0.0)  # ignores the stop
    start = h.clock.now()
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert h.clock.now() - start == pytest.approx(0.5, abs=0.06)
    assert any("still moving" in t for t in h.texts(LogLevel.ERROR))


def test_timed_stop_fails_if_still_turning():
    h, robot = with_robot(TimedStopState(duration_s=0.3))
    robot.forced_velocity = (0.0, 0.5)
    assert h.start().run(max_time_s=5.0).outcome == "failed"


def test_timed_stop_without_odometry_cannot_confirm():
    h = Harness(TimedStopState(duration_s=0.3))
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert any("cannot be confirmed" in t for t in h.texts(LogLevel.ERROR))


# --- PurePursuit --------------------------------------------------------------------------------------------

PP = {"desired_linear_vel": 0.3, "lookahead_dist": 0.4, "goal_dist_tol": 0.1, "use_final_heading": False}


def test_pure_pursuit_follows_the_plan_to_the_goal():
    plan = path([(0.0, 0.0), (1.0, 0.0), (2.0, 0.5), (2.5, 1.5)], frame="odom")
    h, robot = with_robot(PurePursuitState(pure_pursuit=PP), inputs={"plan": plan})
    result = h.start().run(max_time_s=40.0)
    assert result.outcome == "done", h.log_text()
    assert math.hypot(robot.x - 2.5, robot.y - 1.5) <= 0.15
    assert last_twist(h) == (0.0, 0.0)
    assert max(v for v, _ in twists(h)) <= 0.3 + 1e-9


def test_pure_pursuit_uses_the_pose_topic_in_the_plan_frame():
    plan = path([(5.0, 5.0), (6.0, 5.0)], frame="map")
    state = PurePursuitState(pure_pursuit=PP, pose_topic="ground_truth", pose_type="odometry")
    h, robot = with_robot(state, inputs={"plan": plan})
    truth = h.proxies.subscription("ground_truth", type(odometry(0, 0, 0, 0, 0, 0)))
    robot.x, robot.y = 5.0, 5.0

    def publish_truth():
        truth.inject(odometry(robot.x, robot.y, robot.yaw, robot.v, robot.w, h.clock.now(), frame="map"))

    h.start()
    while True:
        publish_truth()
        if h.tick():
            break
        h.advance(0.05)
    assert h.executor.result().outcome == "done", h.log_text()
    assert robot.x == pytest.approx(6.0, abs=0.12)


def test_pure_pursuit_refuses_a_plan_in_another_frame():
    plan = path([(0.0, 0.0), (1.0, 0.0)], frame="map")
    h, _robot = with_robot(PurePursuitState(pure_pursuit=PP), inputs={"plan": plan})
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert any("frame 'odom'" in t and "'map'" in t for t in h.texts(LogLevel.ERROR))
    assert all(t == (0.0, 0.0) for t in twists(h))


def test_pure_pursuit_empty_plan_fails():
    h, _robot = with_robot(PurePursuitState(), inputs={"plan": path([], frame="odom")})
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert any("empty" in t for t in h.texts(LogLevel.ERROR))


def test_pure_pursuit_stale_pose_topic_fails():
    plan = path([(0.0, 0.0), (3.0, 0.0)], frame="map")
    h, _robot = with_robot(PurePursuitState(pure_pursuit=PP, pose_topic="amcl_pose", pose_type="pose_with_covariance"),
                           inputs={"plan": plan})
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert any("amcl_pose" in t for t in h.texts(LogLevel.ERROR))


def test_pure_pursuit_preempt_publishes_zero():
    plan = path([(0.0, 0.0), (5.0, 0.0)], frame="odom")
    h, _robot = with_robot(PurePursuitState(pure_pursuit=PP), inputs={"plan": plan})
    assert preempt_after(h, 2.0)[0] > 0.1
    assert last_twist(h) == (0.0, 0.0)


@pytest.mark.parametrize(
    ("params", "match"),
    [({"pure_pursuit": {"lookahead": 1.0}}, "lookahead"), ({"pose_type": "tf"}, "pose_type"),
     ({"pure_pursuit": [1, 2]}, "pure_pursuit"), ({"timeout_s": -1.0}, "timeout_s")],
)
def test_pure_pursuit_parameters_are_validated(params, match):
    with pytest.raises(ConfigError, match=match):
        PurePursuitState(**params)


def test_closed_loop_limits_are_checked_at_construction():
    with pytest.raises(ConfigError, match=r"timeout_s 5 s is shorter than \|distance_m\| / speed_mps = 10.00 s"):
        MoveDistanceState(distance_m=1.0, speed_mps=0.1, timeout_s=5.0)
    with pytest.raises(ConfigError, match=r"stall_distance_m 1 m cannot be made in stall_window_s 1 s"):
        MoveDistanceState(distance_m=1.0, stall_distance_m=1.0)
    with pytest.raises(ConfigError, match=r"stall_angle_rad 2 rad cannot be made"):
        RotateAngleState(angle_rad=1.0, stall_angle_rad=2.0)
    assert MoveDistanceState(distance_m=-0.5, speed_mps=0.25)._timeout_s == pytest.approx(2.0 * 2.0 + 2.0)


def test_a_motion_state_whose_outcome_waits_for_the_operator_stops_the_robot():
    """A stalled move whose 'failed' needs approval: the last command must be a stop while the operator
    decides, not the push it was sending when the stall was detected."""
    sm = StateMachine(outcomes=["finished", "failed"])
    sm.add("Move", MoveDistanceState(distance_m=1.0, speed_mps=0.2),
           transitions={"done": "finished", "failed": "failed"}, autonomy={"failed": Autonomy.HIGH})
    h = Harness(sm, autonomy=Autonomy.LOW)
    robot = KinematicRobot(h)
    robot.blocked = True
    h.start()
    for _ in range(200):  # 10 s at 20 Hz: the stall shows after about 1 s
        h.tick()
        h.advance(0.05)
        if h.executor.requested_outcomes():
            break
    assert [(r.path, r.outcome) for r in h.executor.requested_outcomes()] == [("/Move", "failed")]
    assert any(v > 0.0 for v, _ in twists(h))  # it did drive before the stall
    assert last_twist(h) == (0.0, 0.0)
    sent = len(twists(h))
    h.run_for(2.0)  # waiting: nothing more is sent, the stop stands
    assert len(twists(h)) == sent


@pytest.mark.parametrize(("cls", "params", "field"), [
    (MoveDistanceState, {"distance_m": 1.0, "speed_mps": 20.0}, "speed_mps"),  # cm/s given as m/s
    (RotateAngleState, {"angle_rad": 1.0, "angular_speed_radps": 90.0}, "angular_speed_radps"),  # deg/s
    (TimedTwistState, {"linear_mps": -1.5}, "linear_mps"),
    (TimedTwistState, {"angular_radps": 4.0}, "angular_radps"),
])
def test_speeds_beyond_any_supported_base_are_refused_at_load_time(cls, params, field):
    with pytest.raises(ConfigError, match=rf"{field} must be (<=|>=) -?[0-9.]+ \["):
        cls(**params)


def test_a_message_stamped_ahead_of_the_clock_ages_by_its_arrival():
    """A sender whose clock runs 10 s ahead: its last odometry must go stale when it stops, not 10 s later."""
    clock = ManualClock(1000.0)
    sub = FakeProxies(clock).subscription("odom", Odometry)
    sub.inject(odometry(0.0, 0.0, 0.0, 0.0, 0.0, stamp_s=1010.0))
    clock.advance(1.0)
    assert message_age_s(sub.last(), sub, clock.now()) == pytest.approx(1.0)  # by arrival, not -9 s
    sub.inject(odometry(0.0, 0.0, 0.0, 0.0, 0.0, stamp_s=1001.3))  # slightly ahead (within the tolerance): the stamp
    assert message_age_s(sub.last(), sub, clock.now()) == pytest.approx(-0.3)
