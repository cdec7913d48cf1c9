"""What one simulation step reports: sensor readings and events, as plain data (no ROS types).

:meth:`flex_nav_sim.simulation.Simulation.step` returns a list of these; the ROS bridge turns each
kind into its message, tests inspect them directly. Stamps are simulated time [s].
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, NamedTuple, Tuple

import numpy as np


class Pose2D(NamedTuple):
    """A planar pose: x [m], y [m], yaw [rad]."""

    x: float
    y: float
    yaw: float


@dataclass(frozen=True)
class OdometryReading:
    """Wheel odometry (noisy, in the robot's odom frame), ground truth and the map -> odom transform."""

    robot: str
    stamp: float  # [s]
    odom_pose: Pose2D  # odom -> base_footprint, as the robot's odometry believes it
    linear: float  # [m/s] forward velocity reported by odometry
    angular: float  # [rad/s] yaw rate reported by odometry
    truth_pose: Pose2D  # map -> base_footprint, exact
    truth_linear: float  # [m/s] exact forward velocity
    truth_angular: float  # [rad/s] exact yaw rate
    map_to_odom: Pose2D  # makes map -> base_footprint equal the (optionally drifting) localization


@dataclass(frozen=True)
class ScanReading:
    """One lidar scan; ``ranges[i]`` belongs to bearing ``lidar.angle_min + i * lidar.angle_increment``."""

    robot: str
    stamp: float  # [s] time of the first beam
    ranges: np.ndarray  # [m] float32; +inf = no return within range_max


@dataclass(frozen=True)
class BumperReading:
    """State of every bumper zone (pressed if touched at any physics step since the previous reading)."""

    robot: str
    stamp: float  # [s]
    pressed: Dict[str, bool]  # zone name -> pressed
    changed: Tuple[str, ...]  # zones whose state differs from the previous reading


@dataclass(frozen=True)
class ImageReading:
    """One camera frame, row 0 at the top: the colour image and the depth image registered to it."""

    robot: str
    stamp: float  # [s]
    rgb: np.ndarray  # uint8 (height, width, 3)
    depth: np.ndarray  # float32 (height, width) [m] along the optical axis; +inf where nothing is in range


@dataclass(frozen=True)
class ContactReading:
    """A contact between a robot and something other than the floor began or ended."""

    robot: str
    stamp: float  # [s]
    begin: bool  # True: contact began; False: it ended
    other: str  # name of the other object
    other_kind: str  # wall, obstacle, door, box, person or robot
    zones: Tuple[str, ...]  # bumper zones the contact presses (empty: outside every zone, e.g. behind)
    point: Tuple[float, float, float]  # [m] contact point in the map frame (at the beginning)


@dataclass(frozen=True)
class WorldEventReading:
    """A scripted world event that was just applied."""

    stamp: float  # [s]
    action: str
    target: str
    detail: str


@dataclass(frozen=True)
class CommandNotice:
    """A velocity command was ignored (not finite), clamped to the profile's limits, or timed out."""

    robot: str
    stamp: float  # [s]
    kind: str  # "ignored", "clamped" or "timeout"
    detail: str
