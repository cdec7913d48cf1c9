"""The motion states' parameter groups (flex_nav_states.motion_params): each validated once when built, with the
state and the flat parameter in the message, and held by the states instead of loose attributes."""

from __future__ import annotations

import dataclasses

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav_states.motion_params import SPEED_LIMITS, CommandOutput, OdometryInput, RearCheck, SpeedLimits
from flex_nav_states.move_distance_state import MoveDistanceState
from flex_nav_states.pure_pursuit_state import PurePursuitState
from flex_nav_states.push_state import PushState
from flex_nav_states.rotate_angle_state import RotateAngleState
from flex_nav_states.timed_stop_state import TimedStopState
from flex_nav_states.timed_twist_state import TimedTwistState


def test_groups_keep_checked_values_and_are_frozen() -> None:
    odometry = OdometryInput("S", "odom", 1)
    assert odometry.timeout_s == 1.0 and isinstance(odometry.timeout_s, float)
    with pytest.raises(dataclasses.FrozenInstanceError):
        odometry.topic = "other"  # type: ignore[misc]
    rear = RearCheck("S", "", 0.2, 0, 0.5)
    assert not rear.enabled and rear.clearance_m == 0.0
    assert RearCheck("S", "scan", 0.2, 0.05, 0.5).enabled
    assert CommandOutput("S", "cmd_vel_stamped", "").frame_id == ""


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (lambda: OdometryInput("S", "", 0.5), "S: odom_topic must not be empty"),
        (lambda: OdometryInput("S", "odom", 0.0), r"S: odom_timeout_s must be > 0 \[s\], got 0.0"),
        (lambda: CommandOutput("S", "cmd vel", "base"), "S: cmd_topic must not contain blanks"),
        (lambda: CommandOutput("S", "cmd", "a//b"), "S: frame_id: 'a//b' is not a legal ROS name"),
        (lambda: RearCheck("S", "scan", 0.0, 0.05, 0.5), r"S: robot_radius_m must be > 0 \[m\]"),
        (lambda: RearCheck("S", "scan", 0.2, -0.1, 0.5), r"S: clearance_m must be >= 0.0 \[m\]"),
        (lambda: RearCheck("S", "scan", 0.2, 0.05, 0.0), r"S: scan_max_age_s must be > 0 \[s\]"),
        (lambda: RearCheck("S", "bad topic", 0.2, 0.05, 0.5), "S: scan_topic must not contain blanks"),
        (lambda: SpeedLimits(linear_mps=0.0), r"SpeedLimits: linear_mps must be > 0 \[m/s\]"),
    ],
)
def test_a_group_names_the_state_and_its_flat_parameter(build, message) -> None:
    with pytest.raises(ConfigError, match=message):
        build()


def test_speed_limits_refuse_unit_mistakes() -> None:
    assert SPEED_LIMITS.linear("S", "speed_mps", 0.3) == 0.3
    assert SPEED_LIMITS.angular("S", "w", -1.0, signed=True) == -1.0
    with pytest.raises(ConfigError, match=r"S: speed_mps must be <= 1.0 \[m/s\], got 20.0"):
        SPEED_LIMITS.linear("S", "speed_mps", 20.0)
    with pytest.raises(ConfigError, match=r"S: speed_mps must be > 0 \[m/s\]"):
        SPEED_LIMITS.linear("S", "speed_mps", -0.1)
    with pytest.raises(ConfigError, match=r"S: w must be >= -3.2 \[rad/s\], got -4.0"):
        SPEED_LIMITS.angular("S", "w", -4.0, signed=True)


@pytest.mark.parametrize(
    ("state", "odometry"),
    [
        (MoveDistanceState(distance_m=0.5, odom_topic="robot1/odom", odom_timeout_s=0.7, cmd_topic="c",
                           frame_id="f"), True),
        (RotateAngleState(angle_rad=1.0, odom_topic="robot1/odom", odom_timeout_s=0.7, cmd_topic="c",
                          frame_id="f"), True),
        (TimedStopState(odom_topic="robot1/odom", odom_timeout_s=0.7, cmd_topic="c", frame_id="f"), True),
        (PushState(distance_m=0.5, odom_topic="robot1/odom", odom_timeout_s=0.7, cmd_topic="c", frame_id="f"), True),
        (PurePursuitState(odom_topic="robot1/odom", odom_timeout_s=0.7, cmd_topic="c", frame_id="f"), True),
        (TimedTwistState(cmd_topic="c", frame_id="f"), False),
    ],
    ids=lambda v: type(v).__name__,
)
def test_motion_states_hold_the_groups_built_from_their_flat_parameters(state, odometry: bool) -> None:
    owner = type(state).__name__
    assert state._command_output == CommandOutput(owner, "c", "f")
    if odometry:
        assert state.odometry_input() == OdometryInput(owner, "robot1/odom", 0.7)
    else:
        with pytest.raises(ConfigError, match=f"{owner}: needs odometry but odom_topic is empty"):
            state.odometry_input()


def test_move_distance_holds_its_rear_check() -> None:
    state = MoveDistanceState(distance_m=-0.3, scan_topic="scan", robot_radius_m=0.18, clearance_m=0.1)
    assert state._rear == RearCheck("MoveDistanceState", "scan", 0.18, 0.1, 0.5)
