"""The parameter groups of the motion states: small frozen records, each validated once, when it is built.

The motion states (:mod:`~flex_nav_states.motion_base` and its subclasses) keep their flat keyword parameters --
the behavior files and the ``--`` docstrings use them -- and build these groups in their constructors, so a
group's rules (which topic may be empty, which number must be > 0, the speed sanity bounds) are written once,
here. A message names the state and its flat parameter: ``MoveDistanceState: odom_timeout_s must be > 0 [s], got 0``.
"""

from __future__ import annotations

from dataclasses import dataclass

from flex_nav_states import validation


def _store(record: object, **checked: float) -> None:
    """Keep the checked values (ints made floats) in a frozen record, from its ``__post_init__``."""
    for key, value in checked.items():
        object.__setattr__(record, key, value)


@dataclass(frozen=True)
class CommandOutput:
    """Velocity commands out: geometry_msgs/TwistStamped on ``cmd_topic``, stamped with ``frame_id``."""

    owner: str  # the state's class name, for messages
    topic: str  # cmd_topic: a legal ROS name
    frame_id: str  # frame_id of the commands (the robot's base frame; may be empty)

    def __post_init__(self) -> None:
        validation.name(self.owner, "cmd_topic", self.topic)
        validation.name(self.owner, "frame_id", self.frame_id, allow_empty=True)


@dataclass(frozen=True)
class OdometryInput:
    """nav_msgs/Odometry in, on ``odom_topic``; a sample counts while it is at most ``odom_timeout_s`` old."""

    owner: str  # the state's class name, for messages
    topic: str  # odom_topic: a legal ROS name, not empty
    timeout_s: float  # [s] odom_timeout_s (> 0): older samples do not count; none fresh for this long fails

    def __post_init__(self) -> None:
        validation.name(self.owner, "odom_topic", self.topic)
        _store(self, timeout_s=validation.number(self.owner, "odom_timeout_s", self.timeout_s, positive=True,
                                                 unit="[s]"))


@dataclass(frozen=True)
class RearCheck:
    """The look behind a robot backing up: no point of a fresh scan in the corridor it sweeps
    (:func:`flex_nav_states.rear_clearance.gap_behind_m`)."""

    owner: str  # the state's class name, for messages
    scan_topic: str  # sensor_msgs/LaserScan topic; "" for none (the robot backs up blind)
    robot_radius_m: float  # [m] radius of the base (> 0)
    clearance_m: float  # [m] margin kept to what is behind (>= 0)
    scan_max_age_s: float  # [s] backing up needs a scan at most this old (> 0)

    def __post_init__(self) -> None:
        owner = self.owner
        validation.name(owner, "scan_topic", self.scan_topic, allow_empty=True)
        _store(
            self,
            robot_radius_m=validation.number(owner, "robot_radius_m", self.robot_radius_m, positive=True, unit="[m]"),
            clearance_m=validation.number(owner, "clearance_m", self.clearance_m, minimum=0.0, unit="[m]"),
            scan_max_age_s=validation.number(owner, "scan_max_age_s", self.scan_max_age_s, positive=True,
                                             unit="[s]"),
        )

    @property
    def enabled(self) -> bool:
        """True when there is a scan to look at (``scan_topic`` set)."""
        return bool(self.scan_topic)


@dataclass(frozen=True)
class SpeedLimits:
    """Sanity bounds of the speeds a motion state may be told to command (defaults:
    :data:`~flex_nav_states.validation.MAX_LINEAR_MPS`, :data:`~flex_nav_states.validation.MAX_ANGULAR_RADPS`):
    far above what the supported bases drive, so a speed beyond them is a unit mistake, refused at load time."""

    linear_mps: float = validation.MAX_LINEAR_MPS  # [m/s] largest |forward speed|
    angular_radps: float = validation.MAX_ANGULAR_RADPS  # [rad/s] largest |yaw rate|

    def __post_init__(self) -> None:
        owner = type(self).__name__
        _store(
            self,
            linear_mps=validation.number(owner, "linear_mps", self.linear_mps, positive=True, unit="[m/s]"),
            angular_radps=validation.number(owner, "angular_radps", self.angular_radps, positive=True,
                                            unit="[rad/s]"),
        )

    def linear(self, owner: str, name: str, value: object, *, signed: bool = False) -> float:
        """[m/s] A forward speed: > 0 (``signed``: either sign), |value| <= ``linear_mps``."""
        return _speed(owner, name, value, self.linear_mps, signed=signed, unit="[m/s]")

    def angular(self, owner: str, name: str, value: object, *, signed: bool = False) -> float:
        """[rad/s] A yaw rate: > 0 (``signed``: either sign), |value| <= ``angular_radps``."""
        return _speed(owner, name, value, self.angular_radps, signed=signed, unit="[rad/s]")


def _speed(owner: str, name: str, value: object, limit: float, *, signed: bool, unit: str) -> float:
    if signed:
        return validation.number(owner, name, value, minimum=-limit, maximum=limit, unit=unit)
    return validation.number(owner, name, value, positive=True, maximum=limit, unit=unit)


SPEED_LIMITS = SpeedLimits()  # the bounds every motion state checks its speeds against
