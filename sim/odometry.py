"""Wheel odometry that tells the truth about the motion actually achieved, plus realistic error.

Each update takes the robot's true pose change since the previous update (expressed in the robot's
previous frame, so it is exactly what the wheels rolled), scales it by a per-run calibration error and
adds zero-mean noise whose *variance* grows with the distance driven and the angle turned. Variance
proportional to the motion (not to its square) makes the accumulated error independent of the
update rate. A stalled robot has no pose change, so its odometry reports no motion at all.
"""

from __future__ import annotations

import math
from typing import Tuple

import numpy as np

from flex_nav_sim.profiles import OdometrySpec
from flex_nav_sim.readings import Pose2D


def relative_motion(before: Pose2D, after: Pose2D) -> Tuple[float, float, float]:
    """(dx [m], dy [m], dyaw [rad]) of ``after`` in the frame of ``before``."""
    c, s = math.cos(before.yaw), math.sin(before.yaw)
    wx, wy = after.x - before.x, after.y - before.y
    dyaw = math.atan2(math.sin(after.yaw - before.yaw), math.cos(after.yaw - before.yaw))
    return c * wx + s * wy, -s * wx + c * wy, dyaw


def compose(pose: Pose2D, dx: float, dy: float, dyaw: float) -> Pose2D:
    """``pose`` moved by (dx, dy, dyaw) given in its own frame."""
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    yaw = pose.yaw + dyaw
    return Pose2D(pose.x + c * dx - s * dy, pose.y + s * dx + c * dy, math.atan2(math.sin(yaw), math.cos(yaw)))


def inverse(pose: Pose2D) -> Pose2D:
    """The inverse transform of ``pose``."""
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    return Pose2D(-(c * pose.x + s * pose.y), -(-s * pose.x + c * pose.y), -pose.yaw)


def multiply(a: Pose2D, b: Pose2D) -> Pose2D:
    """Transform composition ``a * b``."""
    return compose(a, b.x, b.y, b.yaw)


class OdometryIntegrator:
    """Integrates true motion increments into a noisy odometry pose (odom frame starts at the spawn)."""

    def __init__(self, spec: OdometrySpec, rng: np.random.Generator) -> None:
        self.spec = spec
        self.rng = rng
        # systematic calibration errors, fixed for the run
        self.trans_scale = 1.0 + spec.scale_error_std * float(rng.standard_normal())
        self.rot_scale = 1.0 + spec.scale_error_std * float(rng.standard_normal())
        self.pose = Pose2D(0.0, 0.0, 0.0)
        self.linear = 0.0  # [m/s] last reported
        self.angular = 0.0  # [rad/s]

    def update(self, before: Pose2D, after: Pose2D, dt: float) -> Pose2D:
        """Add the true motion from ``before`` to ``after`` (map frame) over ``dt`` [s]; return the odom pose."""
        dx, dy, dyaw = relative_motion(before, after)
        dist = math.hypot(dx, dy)
        noise_t, noise_r = self.rng.standard_normal(2)
        spec = self.spec
        sigma_t = math.sqrt(spec.trans_var_per_m * dist + spec.trans_var_per_rad * abs(dyaw))
        sigma_r = math.sqrt(spec.rot_var_per_rad * abs(dyaw) + spec.rot_var_per_m * dist)
        if dt > 0.0:  # reported velocities: calibration error only (the random walk is in the pose)
            self.linear = math.copysign(dist, dx) * self.trans_scale / dt
            self.angular = dyaw * self.rot_scale / dt
        if dist > 0.0:
            factor = self.trans_scale + sigma_t * float(noise_t) / dist
            dx, dy = dx * factor, dy * factor
        dyaw = dyaw * self.rot_scale + sigma_r * float(noise_r)
        self.pose = compose(self.pose, dx, dy, dyaw)
        return self.pose
