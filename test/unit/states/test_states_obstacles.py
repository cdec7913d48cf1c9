"""Push-or-avoid states: obstacle class, push (success, heavy-object stall, timeout, person never pushed),
waiting for the path to clear, and FollowPath's `blocked` outcome."""

from __future__ import annotations

import genpy
import pytest
from actionlib_msgs.msg import GoalStatus
from sensor_msgs.msg import LaserScan
from unit.states.states_testlib import Harness, KinematicRobot, passage_scan, path, twists, wall_scan

from flex_nav.behavior import LogLevel
from flex_nav.exceptions import ConfigError
from flex_nav.msg import FollowPathAction, FollowPathResult, ObstacleClass
from flex_nav_states.follow_until_blocked_state import FollowUntilBlockedState
from flex_nav_states.obstacle_class_state import ObstacleClassState
from flex_nav_states.push_state import PushState
from flex_nav_states.rear_clearance import walled_in
from flex_nav_states.wait_path_clear_state import WaitPathClearState

STEP_S = 0.05  # [s]


def class_msg(label: str, stamp_s: float, frame_label: str = "") -> ObstacleClass:
    msg = ObstacleClass(label=label, frame_label=frame_label or label, votes=5, window=5, confidence=0.9)
    msg.header.stamp = genpy.Time.from_sec(stamp_s)
    return msg


class Camera:
    """Publishes the class ``label`` (a callable of the time since start) on obstacle_class every step."""

    def __init__(self, h: Harness, label, frame_label=None) -> None:
        self.h = h
        self.sub = h.proxies.subscription("obstacle_class", ObstacleClass)
        self.start_s = h.clock.now()
        self.label = label if callable(label) else (lambda _t: label)
        self.frame_label = frame_label if callable(frame_label) or frame_label is None else (lambda _t: frame_label)
        self.publish()

    def publish(self) -> None:
        t = self.h.clock.now() - self.start_s
        label = self.label(t)
        if label is None:
            return
        frame = self.frame_label(t) if self.frame_label is not None else label
        self.sub.inject(class_msg(label, self.h.clock.now(), frame))


def run_timed(h: Harness, label, max_time_s: float, frame_label=None):
    """Start the harness and run it against a Camera showing ``label``; the result and the time it took [s]."""
    start = h.clock.now()
    result = run(h.start(), Camera(h, label, frame_label), max_time_s)
    return result, h.clock.now() - start


def run(h: Harness, camera: Camera, max_time_s: float, on_step=None):
    end = h.clock.now() + max_time_s
    while h.clock.now() <= end:
        if h.tick():
            return h.executor.result()
        h.advance(STEP_S)
        if on_step is not None:
            on_step(h.clock.now() - camera.start_s)
        camera.publish()
    raise AssertionError(f"still running after {max_time_s} s: {h.log_text()}")


# --- ObstacleClassState ---------------------------------------------------------------------------------


@pytest.mark.parametrize("label", ["person", "movable", "clear"])
def test_class_state_reports_the_decided_label(label):
    h = Harness(ObstacleClassState())
    result = run(h.start(), Camera(h, label), 3.0)
    assert result.outcome == label
    assert result.outputs["obstacle_class"] == label


def test_class_state_a_person_in_the_latest_frame_wins_over_the_vote():
    h = Harness(ObstacleClassState())
    assert run(h.start(), Camera(h, "movable", frame_label="person"), 3.0).outcome == "person"


def test_class_state_waits_for_a_decided_vote():
    h = Harness(ObstacleClassState(timeout_s=3.0))
    result, took_s = run_timed(h, lambda t: "unknown" if t < 1.0 else "movable", 5.0)
    assert result.outcome == "movable"
    assert took_s >= 1.0


@pytest.mark.parametrize("label", ["unknown", None])
def test_class_state_undecided_or_silent_is_unknown_after_the_timeout(label):
    h = Harness(ObstacleClassState(timeout_s=1.5))
    result, took_s = run_timed(h, label, 5.0)
    assert result.outcome == "unknown"
    assert 1.5 <= took_s <= 1.6
    assert any("unknown" in t for t in h.texts(LogLevel.WARN))


def test_class_state_ignores_a_stale_message():
    h = Harness(ObstacleClassState(class_max_age_s=0.5, timeout_s=1.0))
    h.proxies.subscription("obstacle_class", ObstacleClass).inject(class_msg("clear", h.clock.now() - 3.0))
    assert run(h.start(), Camera(h, None), 3.0).outcome == "unknown"


# --- PushState ------------------------------------------------------------------------------------------


def push_harness(**params):
    h = Harness(PushState(**params))
    robot = KinematicRobot(h)
    return h, robot


def test_push_drives_the_distance_and_stops():
    h, robot = push_harness(distance_m=0.5, speed_mps=0.2)
    result = run(h.start(), Camera(h, "movable"), 10.0)
    assert result.outcome == "done", h.log_text()
    assert robot.x == pytest.approx(0.5, abs=0.03)
    assert twists(h)[-1] == (0.0, 0.0)
    assert max(v for v, _ in twists(h)) == pytest.approx(0.2)
    assert result.outputs["push_progress_m"] == pytest.approx(0.5, abs=0.03)


def test_push_against_a_heavy_object_fails_within_one_and_a_half_seconds():
    h, robot = push_harness(distance_m=1.0, speed_mps=0.2, stall_window_s=1.0)
    contact = {}

    def heavy(t):
        if t >= 0.5 and not robot.blocked:
            robot.blocked = True  # the box does not move: odometry shows no progress
            contact["s"] = h.clock.now()

    result = run(h.start(), Camera(h, "movable"), 10.0, on_step=heavy)
    assert result.outcome == "failed"
    assert h.clock.now() - contact["s"] < 1.5
    assert any("stalled" in t for t in h.texts(LogLevel.ERROR)), h.log_text()
    assert twists(h)[-1] == (0.0, 0.0)


def test_push_times_out_after_distance_over_speed_plus_margin():
    state = PushState(distance_m=0.5, speed_mps=0.25, margin_s=1.0, stall_distance_m=0.005)
    assert state.timeout_s == pytest.approx(3.0)
    h = Harness(state)
    robot = KinematicRobot(h)
    robot.forced_velocity = (0.01, 0.0)  # creeps: progress every window but far too slow
    result, took_s = run_timed(h, "movable", 10.0)
    assert result.outcome == "failed"
    assert 3.0 <= took_s <= 3.1
    assert any("timed out" in t for t in h.texts(LogLevel.ERROR)), h.log_text()


def test_a_push_that_times_out_after_most_of_the_distance_moved_the_object_and_is_done():
    # a hidden-variant box (h1) was pushed 1.91 of 2 m in the time and was remembered as heavy
    state = PushState(distance_m=0.5, speed_mps=0.25, margin_s=1.0, stall_distance_m=0.005, enough_fraction=0.75)
    h = Harness(state)
    robot = KinematicRobot(h)
    robot.forced_velocity = (0.14, 0.0)  # 0.42 m of 0.5 m in the 3 s
    result, took_s = run_timed(h, "movable", 10.0)
    assert result.outcome == "done", h.log_text()
    assert 3.0 <= took_s <= 3.1
    assert 0.375 <= result.outputs["push_progress_m"] < 0.5
    assert any("the object moved, counted as pushed" in t for t in h.texts(LogLevel.WARN)), h.log_text()
    assert twists(h)[-1] == (0.0, 0.0)


@pytest.mark.parametrize("label, frame_label", [("person", "person"), ("movable", "person"), (None, None)])
def test_push_never_moves_towards_a_person_or_without_a_class(label, frame_label):
    h, robot = push_harness(distance_m=0.5)
    result = run(h.start(), Camera(h, label, frame_label=frame_label), 3.0)
    assert result.outcome == "person"
    assert all(t == (0.0, 0.0) for t in twists(h))
    assert robot.x == 0.0


def test_push_stops_at_once_when_a_person_appears():
    h, robot = push_harness(distance_m=1.0, speed_mps=0.2)
    result = run(h.start(), Camera(h, lambda t: "movable" if t < 1.0 else "person"), 10.0)
    assert result.outcome == "person"
    assert twists(h)[-1] == (0.0, 0.0)
    assert robot.x == pytest.approx(0.2, abs=0.03)


def test_push_stops_when_the_classifier_goes_silent_mid_push():
    h, robot = push_harness(distance_m=1.0, speed_mps=0.2)
    result = run(h.start(), Camera(h, lambda t: "movable" if t < 1.0 else None), 10.0)
    assert result.outcome == "person"  # silence could hide a person
    assert twists(h)[-1] == (0.0, 0.0)
    assert robot.x < 0.2 + 0.2 * 1.0 + 0.03  # stopped within class_max_age_s (1 s) of the last class
    assert any("push stopped at" in t and "no fresh obstacle class" in t for t in h.texts(LogLevel.ERROR))


def test_with_person_frames_2_one_frame_said_person_stands_the_robot_then_the_push_goes_on():
    """h4 at contact: one frame said person (confidence 0.45), the next ones clear (the face fills the view)."""
    h, robot = push_harness(distance_m=0.6, speed_mps=0.2, person_frames=2, margin_s=0.5)
    single = Camera(h, "movable", frame_label=lambda t: "person" if 1.0 <= t < 1.0 + STEP_S else "clear")
    result = run(h.start(), single, 10.0)
    assert result.outcome == "done", h.log_text()
    assert result.outputs["push_progress_m"] >= 0.6 and robot.x >= 0.6
    stood = [i for i, (v, _) in enumerate(twists(h)) if v == 0.0]
    assert stood and stood[0] > 0 and stood[0] < len(twists(h)) - 1  # stood mid-push, then drove on
    texts = h.texts()
    assert any("a frame said person (" in t and "): standing" in t for t in texts), h.log_text()
    assert any("the next frame said clear: pushing on" in t for t in texts)


def test_with_person_frames_2_two_frames_in_a_row_end_the_push_having_stood_at_the_first():
    h, robot = push_harness(distance_m=1.0, speed_mps=0.2, person_frames=2)
    result = run(h.start(), Camera(h, "movable", frame_label=lambda t: "movable" if t < 1.0 else "person"), 10.0)
    assert result.outcome == "person"
    assert robot.x == pytest.approx(0.2, abs=0.03)  # not a step farther than with person_frames 1
    assert twists(h)[-2:] == [(0.0, 0.0), (0.0, 0.0)]


def test_with_person_frames_2_the_vote_said_person_ends_the_push_at_once():
    h, robot = push_harness(distance_m=1.0, speed_mps=0.2, person_frames=2)
    result = run(h.start(), Camera(h, lambda t: "movable" if t < 1.0 else "person", frame_label="movable"), 10.0)
    assert result.outcome == "person" and robot.x == pytest.approx(0.2, abs=0.03)


def push_with_scan(face_x, *, scan=True):
    """Pushes 1 m at 0.2 m/s with a 0.3 m/s approach; the object's face at x = ``face_x`` on the scan (None:
    nothing ahead); ``scan`` False: no scan at all. The harness and the result."""
    h, robot = push_harness(distance_m=1.0, speed_mps=0.2, approach_speed_mps=0.3, scan_topic="scan",
                            robot_radius_m=0.2, contact_slack_m=0.05)
    sub = h.proxies.subscription("scan", LaserScan)

    def scanned(_t):
        if scan:
            sub.inject(wall_scan(h.clock.now(), robot.x, face_x))

    scanned(0.0)
    result = run(h.start(), Camera(h, "movable"), 10.0, on_step=scanned)
    return h, result


def test_push_approaches_the_face_faster_then_pushes_at_its_speed():
    h, result = push_with_scan(face_x=0.5)  # 0.3 m from the front of a 0.2 m base
    assert result.outcome == "done", h.log_text()
    speeds = [v for v, _ in twists(h) if v > 0.0]
    assert speeds[0] == pytest.approx(0.3)
    first_push = speeds.index(pytest.approx(0.2))
    assert all(v == pytest.approx(0.3) for v in speeds[:first_push])
    assert all(v == pytest.approx(0.2) for v in speeds[first_push:])
    assert first_push * 0.3 * STEP_S == pytest.approx(0.25, abs=0.03)  # up to contact_slack_m before the face
    assert any("0.30 m ahead: 0.25 m at 0.3 m/s" in t for t in h.texts(LogLevel.INFO)), h.log_text()


@pytest.mark.parametrize("face_x, scan", [(None, True), (0.5, False)])
def test_push_without_a_face_on_a_fresh_scan_pushes_at_its_speed_all_the_way(face_x, scan):
    h, result = push_with_scan(face_x=face_x, scan=scan)
    assert result.outcome == "done", h.log_text()
    assert {round(v, 6) for v, _ in twists(h) if v > 0.0} == {0.2}
    assert scan or any("no faster approach" in t for t in h.texts(LogLevel.WARN)), h.log_text()


def push_in_passage(end_x, *, extra_m=1.0):
    """Pushes 1 m at 0.2 m/s with ``passage_extra_m`` ``extra_m`` along a passage (walls 0.6 m to each side)
    that ends at x = ``end_x``; the harness, the robot and the result."""
    h, robot = push_harness(distance_m=1.0, speed_mps=0.2, scan_topic="scan", passage_extra_m=extra_m,
                            passage_behind_m=0.4)
    sub = h.proxies.subscription("scan", LaserScan)

    def scanned(_t):
        sub.inject(passage_scan(h.clock.now(), robot.x, end_x))

    scanned(0.0)
    return h, robot, run(h.start(), Camera(h, "movable"), 20.0, on_step=scanned)


def test_a_push_in_a_passage_goes_on_until_a_side_opens_behind_the_robot():
    h, robot, result = push_in_passage(end_x=1.2)
    assert result.outcome == "done", h.log_text()
    assert robot.x == pytest.approx(1.2 + 0.4, abs=0.03)  # the walls end 0.4 m behind the centre
    assert result.outputs["push_progress_m"] == pytest.approx(1.6, abs=0.03)
    assert twists(h)[-1] == (0.0, 0.0)
    assert any("still in a passage" in t for t in h.texts(LogLevel.INFO)), h.log_text()


@pytest.mark.parametrize("end_x, extra_m, pushed_m", [(0.5, 1.0, 1.0), (5.0, 0.5, 1.5), (5.0, 0.0, 1.0)])
def test_a_push_past_its_distance_is_bounded_and_only_in_a_passage(end_x, extra_m, pushed_m):
    h, robot, result = push_in_passage(end_x=end_x, extra_m=extra_m)
    assert result.outcome == "done", h.log_text()
    assert robot.x == pytest.approx(pushed_m, abs=0.03)


def test_walled_in_needs_both_sides_beside_or_behind_the_centre():
    assert walled_in(passage_scan(0.0, 0.0, end_x=0.0), 0.8, 0.4)
    assert not walled_in(passage_scan(0.0, 0.0, end_x=-0.5), 0.8, 0.4)  # ends 0.5 m behind: open
    assert not walled_in(passage_scan(0.0, 0.0, end_x=5.0, half_width_m=0.9), 0.8, 0.4)  # wider than side_m
    ahead = wall_scan(0.0, 0.0, wall_x=0.3)  # an object ahead fills the view: no sides
    assert not walled_in(ahead, 0.8, 0.4)


@pytest.mark.parametrize("params, match", [
    ({"passage_extra_m": 0.5}, "passage_extra_m 0.5 m needs a scan_topic"),
    ({"passage_extra_m": -0.5, "scan_topic": "scan"}, "passage_extra_m"),
    ({"passage_side_m": 0.0, "scan_topic": "scan"}, "passage_side_m"),
    ({"approach_speed_mps": 0.1, "scan_topic": "scan"}, "approach_speed_mps 0.1 m/s must be 0 or at least"),
    ({"approach_speed_mps": 0.3}, "needs a scan_topic"),
    ({"approach_speed_mps": 9.0, "scan_topic": "scan"}, "approach_speed_mps"),
    ({"contact_slack_m": -0.1}, "contact_slack_m")])
def test_push_rejects_bad_approach_parameters(params, match):
    with pytest.raises(ConfigError, match=match):
        PushState(distance_m=0.5, speed_mps=0.2, **params)


@pytest.mark.parametrize("params, field", [({"distance_m": 0.0}, "distance_m"), ({"distance_m": -0.3}, "distance_m"),
                                           ({"distance_m": 0.5, "speed_mps": 5.0}, "speed_mps"),
                                           ({"distance_m": 0.5, "speed_mps": 0.1, "stall_distance_m": 0.2},
                                            "stall_distance_m"),
                                           ({"distance_m": 0.5, "enough_fraction": 1.5}, "enough_fraction"),
                                           ({"distance_m": 0.5, "person_frames": 0}, "person_frames")])
def test_push_rejects_bad_parameters(params, field):
    with pytest.raises(ConfigError, match=field):
        PushState(**params)


# --- WaitPathClearState ---------------------------------------------------------------------------------


def test_wait_returns_clear_once_the_person_walked_away():
    h = Harness(WaitPathClearState(patience_s=10.0, clear_for_s=1.0))
    result, took_s = run_timed(h, lambda t: "person" if t < 3.0 else "clear", 15.0)
    assert result.outcome == "clear"
    assert 4.0 <= took_s <= 4.2
    assert result.outputs["waited_s"] == pytest.approx(took_s, abs=0.11)


def test_wait_a_flicker_of_clear_does_not_count():
    h = Harness(WaitPathClearState(patience_s=3.0, clear_for_s=1.0))
    result = run(h.start(), Camera(h, lambda t: "clear" if int(t * 2) % 2 else "person"), 10.0)
    assert result.outcome == "still_blocked"


@pytest.mark.parametrize("label", ["person", None])
def test_wait_gives_up_after_its_patience(label):
    h = Harness(WaitPathClearState(patience_s=2.0, clear_for_s=0.5))
    result, took_s = run_timed(h, label, 10.0)
    assert result.outcome == "still_blocked"
    assert 2.0 <= took_s <= 2.1
    assert any("still blocked" in t for t in h.texts(LogLevel.WARN))


def test_wait_blocking_labels_are_configurable_and_validated():
    h = Harness(WaitPathClearState(patience_s=2.0, blocking=["person", "movable"]))
    assert run(h.start(), Camera(h, "movable"), 10.0).outcome == "still_blocked"
    with pytest.raises(ConfigError, match="blocking"):
        WaitPathClearState(blocking=["chair"])


# --- FollowUntilBlockedState ----------------------------------------------------------------------------


@pytest.mark.parametrize("status, code, message, outcome", [
    (GoalStatus.SUCCEEDED, FollowPathResult.SUCCESS, "goal reached", "done"),
    (GoalStatus.ABORTED, FollowPathResult.FAILURE, "blocked: obstacle on the path 0.60 m ahead", "blocked"),
    (GoalStatus.ABORTED, FollowPathResult.FAILURE, "stale odom: no message for 0.6 s", "failed"),
    (GoalStatus.PREEMPTED, FollowPathResult.PREEMPT, "replaced", "preempted"),
])
def test_follow_until_blocked_maps_the_blocked_reason(status, code, message, outcome):
    h = Harness(FollowUntilBlockedState(action_name="ctrl"), inputs={"plan": path([(0, 0), (1, 0)])})
    client = h.proxies.client("ctrl", FollowPathAction)
    client.respond(status, FollowPathResult(code=code, message=message), delay_s=0.5)
    assert h.start().run(max_time_s=5.0).outcome == outcome
    assert any(message in t for t in h.texts())


def test_class_state_settle_ignores_the_vote_taken_while_approaching():
    h = Harness(ObstacleClassState(settle_s=1.0, timeout_s=3.0))
    result, took_s = run_timed(h, lambda t: "clear" if t < 0.8 else "movable", 5.0)
    assert result.outcome == "movable"  # without settle_s it would be the approach's "clear"
    assert took_s >= 1.0


def test_class_state_settle_does_not_delay_a_person():
    h = Harness(ObstacleClassState(settle_s=1.0, timeout_s=3.0))
    result, took_s = run_timed(h, "movable", 5.0, frame_label="person")
    assert result.outcome == "person"
    assert took_s < 0.2


def test_class_state_timeout_must_exceed_settle():
    with pytest.raises(ConfigError, match="settle_s"):
        ObstacleClassState(settle_s=2.0, timeout_s=2.0)
