"""RotateAngleState: turn in place by an angle, closed loop on the odometry yaw (not timed)."""

from __future__ import annotations

import math
from typing import Optional

from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.nav.angles import wrap_angle
from flex_nav_states import validation
from flex_nav_states.motion_base import MotionBase, closed_loop_timeout, stall_watch
from flex_nav_states.motion_params import SPEED_LIMITS, CommandOutput, OdometryInput

SLOWDOWN_GAIN = 1.5  # [1/s] commanded yaw rate = gain x remaining angle near the end (capped)
MIN_RATE_RADPS = 0.15  # [rad/s] slowest commanded yaw rate (static friction)


class RotateAngleState(MotionBase):
    """Turns in place by a signed angle, closed loop on odometry yaw (more than a full turn is allowed).

    The turned angle is the sum of the wrapped yaw changes between odometry samples, so it keeps counting
    past +-pi. The yaw rate ramps down near the end; the robot stops (zero twist) on every exit.

    -- angle_rad            float  [rad] Signed angle: > 0 counter-clockwise (not 0).
    -- angular_speed_radps  float  [rad/s] Cruise yaw rate (> 0); the sign of angle_rad gives the direction.
    -- tolerance_rad        float  [rad] Done when within this angle of the target (> 0).
    -- timeout_s            float  [s] Fail after this long (0: 2 x |angle_rad| / angular_speed_radps + 2 s).
    -- stall_window_s       float  [s] Fail when the turned angle grew by less than stall_angle_rad in this window.
    -- stall_angle_rad      float  [rad] Least progress per stall window (> 0).
    -- odom_topic           str    nav_msgs/Odometry topic.
    -- odom_timeout_s       float  [s] Fail when no fresh odometry for this long.
    -- cmd_topic            str    geometry_msgs/TwistStamped command topic.
    -- frame_id             str    frame_id of the commands (the robot's base frame).

    <= done    The angle was turned (within tolerance_rad).
    <= failed  Stalled, timed out, or odometry was missing; the reason is logged.
    """

    def __init__(
        self,
        angle_rad: float,
        angular_speed_radps: float = 0.5,
        *,
        tolerance_rad: float = 0.03,
        timeout_s: float = 0.0,
        stall_window_s: float = 1.0,
        stall_angle_rad: float = 0.02,
        odom_topic: str = "odom",
        odom_timeout_s: float = 0.5,
        cmd_topic: str = "cmd_vel_stamped",
        frame_id: str = "base_footprint",
    ) -> None:
        owner = type(self).__name__
        super().__init__(
            ["done", "failed"],
            odometry=OdometryInput(owner, odom_topic, odom_timeout_s),
            command=CommandOutput(owner, cmd_topic, frame_id),
        )
        self._angle_rad = validation.number(owner, "angle_rad", angle_rad, unit="[rad]")
        if self._angle_rad == 0.0:
            raise ConfigError(f"{owner}: angle_rad must not be 0 [rad]")
        self._speed = SPEED_LIMITS.angular(owner, "angular_speed_radps", angular_speed_radps)
        self._tolerance_rad = validation.number(owner, "tolerance_rad", tolerance_rad, positive=True, unit="[rad]")
        self._timeout_s = closed_loop_timeout(owner, timeout_s, amount=self._angle_rad, amount_name="angle_rad",
                                              speed=self._speed, speed_name="angular_speed_radps")
        self._stall = stall_watch(owner, stall_window_s, progress_name="stall_angle_rad",
                                  min_progress=stall_angle_rad, unit="rad",
                                  slowest_speed=min(MIN_RATE_RADPS, self._speed))
        self._last_yaw: Optional[float] = None
        self._turned_rad = 0.0

    def on_enter(self, userdata: UserDataView) -> None:
        super().on_enter(userdata)
        self._last_yaw = None
        self._turned_rad = 0.0

    def on_resume(self, userdata: UserDataView) -> None:
        super().on_resume(userdata)
        self._stall.restart_window(self.now_s())

    def execute(self, userdata: UserDataView) -> Optional[str]:
        now = self.now_s()
        sample = self.odometry()
        if sample is None:
            if self.odometry_lost():
                self.log_error(f"rotate {math.degrees(self._angle_rad):+.1f} deg: {self.odometry_problem()}")
                return "failed"
            self.stop()
            return None
        if self._last_yaw is None:
            self._stall.reset(0.0, now)
        else:
            self._turned_rad += wrap_angle(sample.yaw - self._last_yaw)
        self._last_yaw = sample.yaw
        direction = math.copysign(1.0, self._angle_rad)
        progress = direction * self._turned_rad
        remaining = abs(self._angle_rad) - progress
        turned_deg = math.degrees(self._turned_rad)
        target_deg = math.degrees(self._angle_rad)
        if remaining <= self._tolerance_rad:
            self.log_info(f"turned {turned_deg:+.1f} deg (target {target_deg:+.1f} deg)")
            return "done"
        if self.elapsed_s() > self._timeout_s:
            self.log_error(
                f"rotate {target_deg:+.1f} deg timed out after {self._timeout_s:.1f} s at {turned_deg:+.1f} deg"
            )
            return "failed"
        if self._stall.stalled(progress, now):
            self.log_error(
                f"rotate {target_deg:+.1f} deg stalled at {turned_deg:+.1f} deg: less than "
                f"{math.degrees(self._stall.min_progress):.1f} deg of progress in {self._stall.window_s:g} s"
            )
            return "failed"
        rate = min(self._speed, max(MIN_RATE_RADPS, SLOWDOWN_GAIN * remaining))
        self.send(0.0, direction * rate)
        return None
