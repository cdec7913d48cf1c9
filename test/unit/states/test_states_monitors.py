"""Monitors: bumper/cliff per robot profile, stuck detection, sensor freshness; GetPose drops stale goals."""

from __future__ import annotations

import genpy
import pytest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from unit.states.states_testlib import Harness, KinematicRobot, pose_stamped

from flex_nav.behavior import LogLevel, StateMachine
from flex_nav.exceptions import ConfigError
from flex_nav.msg import BumperEvent, BumperState, CreateBumper
from flex_nav_states.bumper_monitor_state import MAX_UNKNOWN_REPORTS, BumperMonitorState
from flex_nav_states.get_pose_state import GetPoseState
from flex_nav_states.sensor_freshness_state import SensorFreshnessState
from flex_nav_states.stuck_monitor_state import StuckMonitorState
from flex_nav_states.wait_state import WaitState

# --- BumperMonitor ------------------------------------------------------------------------------------------


def event(bumper: int, pressed: bool) -> BumperEvent:
    return BumperEvent(bumper=bumper, state=BumperEvent.PRESSED if pressed else BumperEvent.RELEASED)


def zones_msg(zones, pressed) -> BumperState:
    return BumperState(zones=list(zones), pressed=list(pressed))


def test_bumper_kobuki_profile_reads_bumper_events():
    h = Harness(BumperMonitorState(profile="kobuki")).start()
    sub = h.proxies.sub("events/bumper")
    assert sub.msg_type == BumperEvent  # (== not is: an `is` check would narrow the untyped message class)
    h.run_for(1.0)
    sub.inject(event(BumperEvent.RIGHT, True))
    result = h.run(max_time_s=1.0)
    assert result.outcome == "bumper"
    assert result.outputs["bumper_zones"] == ["right"]
    assert any("bumper pressed: right" in t for t in h.texts(LogLevel.WARN))


def test_bumper_kobuki_press_and_release_before_entry_does_not_fire():
    state = BumperMonitorState(profile="kobuki")
    h = Harness(state).start()
    sub = h.proxies.sub("events/bumper")
    sub.inject(event(BumperEvent.CENTER, True))
    sub.inject(event(BumperEvent.CENTER, False))  # released again before the monitor looked
    h.run_for(1.0)
    sub.inject(event(BumperEvent.LEFT, True))
    sub.inject(event(BumperEvent.CENTER, True))
    result = h.run(max_time_s=1.0)
    assert result.outputs["bumper_zones"] == ["left", "center"]


def test_bumper_kobuki_short_press_while_watching_fires():
    """A glancing contact: pressed and released between two ticks of the running monitor."""
    h = Harness(BumperMonitorState(profile="kobuki")).start()
    sub = h.proxies.sub("events/bumper")
    h.run_for(0.5)
    sub.inject(event(BumperEvent.CENTER, True))
    sub.inject(event(BumperEvent.CENTER, False))
    result = h.run(max_time_s=1.0)
    assert result.outcome == "bumper" and result.outputs["bumper_zones"] == ["center"]


def test_bumper_kobuki_monitors_of_one_behavior_each_see_every_event():
    """Two monitors on one topic (as move_base_like's copies of its navigate state): a release that arrives
    while the other one runs must still reach the first, or it reports the old press when entered again."""
    sm = StateMachine(outcomes=["finished"])
    sm.add("A", BumperMonitorState(profile="kobuki"), transitions={"bumper": "WaitA", "cliff": "finished"})
    sm.add("WaitA", WaitState(wait_time_s=1.0), transitions={"done": "B"})
    sm.add("B", BumperMonitorState(profile="kobuki"), transitions={"bumper": "WaitB", "cliff": "finished"})
    sm.add("WaitB", WaitState(wait_time_s=1.0), transitions={"done": "A"})
    h = Harness(sm).start()
    sub = h.proxies.sub("events/bumper")
    h.run_for(0.5)
    sub.inject(event(BumperEvent.CENTER, True))  # A fires
    h.run_for(0.5)
    sub.inject(event(BumperEvent.CENTER, False))  # released while waiting
    h.run_for(1.0)  # B runs
    sub.inject(event(BumperEvent.LEFT, True))  # B fires
    h.run_for(0.5)
    sub.inject(event(BumperEvent.LEFT, False))
    h.run_for(2.0)  # A runs again: nothing is pressed
    presses = [t for t in h.texts(LogLevel.WARN) if t.startswith("bumper pressed")]
    assert presses == ["bumper pressed: center (on events/bumper)", "bumper pressed: left (on events/bumper)"]


def test_bumper_kobuki_unknown_bumpers_are_reported_bounded_and_only_while_running():
    """A driver sending an unknown bumper id on a loop: a running monitor warns about at most
    MAX_UNKNOWN_REPORTS of them per tick; a monitor that was not running does not report them on entry."""
    sm = StateMachine(outcomes=["finished"])
    sm.add("A", BumperMonitorState(profile="kobuki"), transitions={"bumper": "WaitA", "cliff": "finished"})
    sm.add("WaitA", WaitState(wait_time_s=1.0), transitions={"done": "B"})
    sm.add("B", BumperMonitorState(profile="kobuki"), transitions={"bumper": "finished", "cliff": "finished"})
    h = Harness(sm).start()
    sub = h.proxies.sub("events/bumper")
    h.run_for(0.5)
    for _ in range(3 * MAX_UNKNOWN_REPORTS):
        sub.inject(event(7, True))  # seen by A (running) and by B (not running)
    h.run_for(0.2)
    sub.inject(event(BumperEvent.LEFT, True))  # A fires; B runs after WaitA
    sub.inject(event(BumperEvent.LEFT, False))
    h.run_for(2.0)
    unknown = [t for t in h.texts(LogLevel.WARN) if "unknown bumper 7" in t]
    assert len(unknown) == MAX_UNKNOWN_REPORTS, h.log_text()


def test_bumper_still_pressed_at_entry_fires_at_once():
    h = Harness(BumperMonitorState(profile="turtlebot4"))
    h.proxies.subscription("bumper_state", BumperState).inject(
        zones_msg(["bump_left", "bump_front_left", "bump_front_center"], [False, True, False])
    )
    result = h.start().run(max_time_s=1.0)
    assert result.outcome == "bumper"
    assert result.outputs["bumper_zones"] == ["bump_front_left"]


def test_bumper_watched_zones_filter():
    h = Harness(BumperMonitorState(profile="turtlebot4", zones=["bump_front_center"])).start()
    sub = h.proxies.sub("bumper_state")
    sub.inject(zones_msg(["bump_left", "bump_front_center"], [True, False]))
    h.run_for(1.0)  # a side zone that is not watched
    sub.inject(zones_msg(["bump_left", "bump_front_center"], [True, True]))
    result = h.run(max_time_s=1.0)
    assert result.outputs["bumper_zones"] == ["bump_front_center"]


def test_bumper_create_profile_reads_left_right_flags():
    h = Harness(BumperMonitorState(profile="create2")).start()
    sub = h.proxies.sub("bumper")
    assert sub.msg_type is CreateBumper
    sub.inject(CreateBumper(is_left_pressed=False, is_right_pressed=False))
    h.run_for(1.0)
    sub.inject(CreateBumper(is_left_pressed=True, is_right_pressed=True))
    result = h.run(max_time_s=1.0)
    assert result.outputs["bumper_zones"] == ["left", "right"]


def test_bumper_style_and_topic_override():
    h = Harness(BumperMonitorState(profile="kobuki", driver_style="zones", topic="sim/bumper_state")).start()
    sub = h.proxies.sub("sim/bumper_state")
    sub.inject(zones_msg(["left", "center", "right"], [False, False, True]))
    assert h.run(max_time_s=1.0).outputs["bumper_zones"] == ["right"]


def test_bumper_cliff():
    h = Harness(BumperMonitorState(profile="kobuki", cliff_topic="cliff_state")).start()
    h.run_for(0.5)
    h.proxies.sub("cliff_state").inject(zones_msg(["cliff_left", "cliff_right"], [False, True]))
    result = h.run(max_time_s=1.0)
    assert result.outcome == "cliff"
    assert result.outputs["bumper_zones"] == ["cliff_right"]


def test_bumper_malformed_state_message_is_ignored_with_a_warning():
    h = Harness(BumperMonitorState(profile="turtlebot4")).start()
    h.proxies.sub("bumper_state").inject(zones_msg(["bump_left", "bump_right"], [True]))
    h.run_for(0.5)
    assert any("2 zones but 1 flags" in t for t in h.texts(LogLevel.WARN))


@pytest.mark.parametrize(
    ("params", "match"),
    [
        ({"profile": "roomba9000"}, "roomba9000"),
        ({"profile": "kobuki", "zones": ["bump_front_left"]}, "bump_front_left"),
        ({"profile": "create2", "zones": ["center"]}, "center"),
        ({"profile": "kobuki", "driver_style": "hazard"}, "driver_style"),
        ({"profile": "kobuki", "zones": "left"}, "zones"),
    ],
)
def test_bumper_configuration_is_validated(params, match):
    with pytest.raises(ConfigError, match=match):
        BumperMonitorState(**params)


# --- StuckMonitor -------------------------------------------------------------------------------------------


def test_stuck_monitor_quiet_while_moving_fires_when_blocked():
    h = Harness(StuckMonitorState(window_s=3.0, min_distance_m=0.1))
    robot = KinematicRobot(h)
    robot.forced_velocity = (0.2, 0.0)
    h.start()
    h.run_for(10.0)
    robot.forced_velocity = None
    robot.blocked = True
    start = h.clock.now()
    result = h.run(max_time_s=10.0)
    assert result.outcome == "stuck"
    # the last progress (0.1 m steps at 0.2 m/s) was at most 0.5 s before the block
    assert 2.5 <= h.clock.now() - start <= 3.1
    assert any("robot stuck" in t for t in h.texts(LogLevel.WARN))


def test_stuck_monitor_counts_rotation_but_not_dithering():
    h = Harness(StuckMonitorState(window_s=2.0, min_rotation_rad=0.3))
    robot = KinematicRobot(h)
    robot.forced_velocity = (0.0, 0.5)  # turning in place is progress
    h.start()
    h.run_for(6.0)
    robot.forced_velocity = None
    # dithering: +-0.1 rad back and forth never reaches 0.3 rad net
    for _ in range(20):
        robot.forced_velocity = (0.0, 1.0)
        if h.tick():
            break
        h.advance(0.1)
        robot.forced_velocity = (0.0, -1.0)
        if h.tick():
            break
        h.advance(0.1)
    assert h.executor.result().outcome == "stuck"


def test_stuck_monitor_fails_without_odometry():
    h = Harness(StuckMonitorState(odom_timeout_s=1.0))
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert any("no fresh odometry" in t for t in h.texts(LogLevel.ERROR))


def test_stuck_monitor_pause_restarts_the_window():
    h = Harness(StuckMonitorState(window_s=2.0))
    robot = KinematicRobot(h)
    robot.blocked = True
    h.start()
    h.run_for(1.5)
    h.executor.pause()
    h.tick()
    h.advance(10.0)
    robot.publish()
    h.executor.resume()
    h.tick()
    resumed_s = h.clock.now()
    h.run_for(1.5)  # 1.5 s after resume: not stuck yet although 13 s passed since entry
    assert h.run(max_time_s=5.0).outcome == "stuck"  # and it still watches: stuck one window after resume
    assert h.clock.now() - resumed_s == pytest.approx(2.0, abs=0.2)


# --- SensorFreshness ----------------------------------------------------------------------------------------


def scan(stamp_s: float) -> LaserScan:
    msg = LaserScan()
    msg.header.stamp = genpy.Time.from_sec(stamp_s)
    return msg


SENSORS = [{"topic": "scan", "type": "LaserScan", "max_age_s": 0.5},
           {"topic": "odom", "type": "Odometry", "max_age_s": 0.2}]


def test_sensor_freshness_quiet_while_fresh_then_reports_the_stale_topic():
    h = Harness(SensorFreshnessState(sensors=SENSORS, startup_grace_s=1.0))
    robot = KinematicRobot(h)
    scans = h.proxies.subscription("scan", LaserScan)
    h.start()
    for _ in range(60):
        scans.inject(scan(h.clock.now()))
        assert not h.tick()
        h.advance(0.05)
    # scan stops; odometry goes on
    result = h.run(max_time_s=2.0)
    assert result.outcome == "stale"
    assert result.outputs["stale_topics"] == ["scan"]
    assert robot.odom.has_msg()
    assert any("scan" in t and "max_age_s 0.5" in t for t in h.texts(LogLevel.ERROR))


def test_sensor_freshness_grace_after_entry_then_no_message_is_stale():
    h = Harness(SensorFreshnessState(sensors=SENSORS, startup_grace_s=2.0))
    start = h.clock.now()
    result = h.start().run(max_time_s=5.0)
    assert result.outcome == "stale"
    assert 2.0 <= h.clock.now() - start <= 2.2
    assert sorted(result.outputs["stale_topics"]) == ["odom", "scan"]


def test_sensor_freshness_uses_stamps_not_arrival():
    h = Harness(SensorFreshnessState(sensors=SENSORS[:1], startup_grace_s=0.0))
    scans = h.proxies.subscription("scan", LaserScan)
    h.start()
    scans.inject(scan(h.clock.now() - 3.0))  # arrives now but was taken 3 s ago
    h.advance(0.6)
    assert h.run(max_time_s=1.0).outcome == "stale"


@pytest.mark.parametrize(
    ("sensors", "match"),
    [
        ([], "non-empty"),
        ({"topic": "scan"}, "list"),
        ([{"topic": "scan", "type": "Laser", "max_age_s": 1.0}], "type"),
        ([{"topic": "scan", "type": "LaserScan"}], "max_age_s"),
        ([{"topic": "scan", "type": "LaserScan", "max_age_s": 0.0}], "max_age_s"),
        ([{"topic": "scan", "type": "LaserScan", "max_age_s": 1.0, "qos": 1}], "qos"),
        ([{"topic": "scan", "type": "LaserScan", "max_age_s": 1.0}] * 2, "twice"),
    ],
)
def test_sensor_freshness_configuration_is_validated(sensors, match):
    with pytest.raises(ConfigError, match=match):
        SensorFreshnessState(sensors=sensors)


# --- GetPose ------------------------------------------------------------------------------------------------


def test_get_pose_outputs_a_fresh_goal():
    h = Harness(GetPoseState()).start()
    h.run_for(1.0)
    goal = pose_stamped(3.0, 4.0, 1.0, stamp_s=h.clock.now(), frame="map")
    h.proxies.sub("move_base_simple/goal").inject(goal)
    result = h.run(max_time_s=1.0)
    assert result.outcome == "received"
    assert result.outputs["goal"] is goal
    assert any("(3.00, 4.00, 57 deg) in map" in t for t in h.texts())


def test_get_pose_drops_a_stale_goal_and_takes_the_next():
    h = Harness(GetPoseState(max_age_s=1.0))
    sub = h.proxies.subscription("move_base_simple/goal", PoseStamped, buffer_size=10)
    h.start()
    old = pose_stamped(1.0, 1.0, stamp_s=h.clock.now() - 30.0)  # e.g. latched from an earlier run
    sub.inject(old)
    h.run_for(1.0)
    assert any("stale goal" in t for t in h.texts(LogLevel.WARN))
    new = pose_stamped(2.0, 2.0, stamp_s=h.clock.now())
    sub.inject(new)
    assert h.run(max_time_s=1.0).outputs["goal"] is new


def test_get_pose_refuses_a_goal_stamped_far_in_the_future_with_the_offset():
    # before: a goal stamped 100 s ahead was taken silently (its age came from its arrival)
    h = Harness(GetPoseState(max_age_s=5.0, timeout_s=1.0)).start()
    h.proxies.sub("move_base_simple/goal").inject(pose_stamped(1.0, 1.0, stamp_s=h.clock.now() + 100.0))
    assert h.run(max_time_s=2.0).outcome == "timeout"
    assert any("stamped 100.00 s ahead of the behavior's clock" in t for t in h.texts(LogLevel.WARN)), h.log_text()


def test_get_pose_takes_a_goal_slightly_ahead_and_warns_with_the_offset():
    h = Harness(GetPoseState(max_age_s=5.0)).start()
    goal = pose_stamped(1.0, 1.0, stamp_s=h.clock.now() + 2.0)  # another computer's clock, 2 s ahead
    h.proxies.sub("move_base_simple/goal").inject(goal)
    assert h.run(max_time_s=1.0).outputs["goal"] is goal
    assert any("2.00 s ahead" in t and "synchronised" in t for t in h.texts(LogLevel.WARN)), h.log_text()


def test_get_pose_drops_unstamped_goals_from_before_entry_but_takes_later_ones():
    h = Harness(GetPoseState())
    sub = h.proxies.subscription("move_base_simple/goal", PoseStamped, buffer_size=10)
    sub.inject(pose_stamped(1.0, 1.0, stamp_s=0.0))
    h.start()
    h.run_for(1.0)
    later = pose_stamped(2.0, 2.0, stamp_s=0.0)
    sub.inject(later)
    assert h.run(max_time_s=1.0).outputs["goal"] is later


def test_get_pose_keeps_a_recent_stamped_goal_sent_just_before_entry():
    h = Harness(GetPoseState(max_age_s=1.0))
    sub = h.proxies.subscription("move_base_simple/goal", PoseStamped, buffer_size=10)
    goal = pose_stamped(2.0, 2.0, stamp_s=h.clock.now() - 0.2)
    sub.inject(goal)
    assert h.start().run(max_time_s=1.0).outputs["goal"] is goal


@pytest.mark.parametrize(
    ("goal", "reason"),
    [
        (pose_stamped(float("nan"), 0.0, stamp_s=1000.0), "not finite"),
        (pose_stamped(1.0, 0.0, stamp_s=1000.0, frame=""), "without frame_id"),
    ],
)
def test_get_pose_drops_invalid_goals(goal, reason):
    h = Harness(GetPoseState(timeout_s=1.0)).start()
    h.proxies.sub("move_base_simple/goal").inject(goal)
    assert h.run(max_time_s=2.0).outcome == "timeout"
    assert any(reason in t for t in h.texts(LogLevel.WARN)), h.log_text()


def test_get_pose_unnormalised_orientation_is_dropped():
    goal = pose_stamped(1.0, 0.0, stamp_s=1000.0)
    goal.pose.orientation.w = 0.0
    h = Harness(GetPoseState(timeout_s=1.0)).start()
    h.proxies.sub("move_base_simple/goal").inject(goal)
    assert h.run(max_time_s=2.0).outcome == "timeout"
    assert any("not normalised" in t for t in h.texts(LogLevel.WARN))


def test_get_pose_timeout():
    h = Harness(GetPoseState(timeout_s=2.0))
    start = h.clock.now()
    assert h.start().run(max_time_s=5.0).outcome == "timeout"
    assert 2.0 <= h.clock.now() - start <= 2.2


def test_get_pose_uses_the_configured_topic():
    h = Harness(GetPoseState(topic="robot2/goal")).start()
    assert h.proxies.sub("robot2/goal").msg_type is PoseStamped
    assert "move_base_simple/goal" not in h.proxies.subscriptions


@pytest.mark.parametrize(("params", "match"), [({"topic": ""}, "topic"), ({"max_age_s": 0.0}, "max_age_s"),
                                               ({"timeout_s": -2.0}, "timeout_s")])
def test_get_pose_parameters_are_validated(params, match):
    with pytest.raises(ConfigError, match=match):
        GetPoseState(**params)


def test_odometry_type_is_the_one_states_subscribe():
    h = Harness(StuckMonitorState()).start()
    assert h.proxies.sub("odom").msg_type is Odometry


def test_stuck_monitor_waiting_on_purpose_restarts_the_window_while_fresh():
    from std_msgs.msg import Bool  # noqa: PLC0415

    h = Harness(StuckMonitorState(window_s=2.0, odom_timeout_s=1.0, waiting_topic="pure_pursuit_path/yielding"))
    robot = KinematicRobot(h)
    robot.blocked = True
    h.start()
    waiting = h.proxies.sub("pure_pursuit_path/yielding")
    for _ in range(50):  # 5 s standing still, giving way: not stuck
        waiting.inject(Bool(data=True))
        assert not h.tick()
        h.advance(0.1)
    waiting.inject(Bool(data=False))  # done giving way, still not moving: stuck after the window
    start = h.clock.now()
    assert h.run(max_time_s=5.0).outcome == "stuck"
    assert 1.9 <= h.clock.now() - start <= 2.3
