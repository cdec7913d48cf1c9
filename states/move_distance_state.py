"""MoveDistanceState: drive straight forward or backward by a distance, closed loop on odometry."""

from __future__ import annotations

import math
from typing import Optional

from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav_states import validation
from flex_nav_states.messages import OdomSample, wrap_angle
from flex_nav_states.motion_base import MotionBase, closed_loop_timeout, stall_watch

SLOWDOWN_GAIN = 1.5  # [1/s] commanded speed = gain x remaining distance near the end (capped at speed_mps)
MIN_SPEED_MPS = 0.05  # [m/s] slowest commanded speed (below this many bases do not move)
HEADING_GAIN = 1.0  # [1/s] yaw rate per radian of heading error (keeps the line straight)
MAX_HEADING_RATE = 0.5  # [rad/s] bound of the heading correction


class MoveDistanceState(MotionBase):
    """Drives straight by a signed distance (negative: backwards), closed loop on odometry.

    Progress is the odometry displacement projected on the heading at the start, so drift sideways does not
    count; the heading is held with a small yaw-rate correction and the speed ramps down near the end.
    The robot stops (zero twist) on every exit.

    -- distance_m        float  [m] Signed distance: > 0 forward, < 0 backward (not 0).
    -- speed_mps         float  [m/s] Cruise speed (> 0); the sign of distance_m gives the direction.
    -- tolerance_m       float  [m] Done when within this distance of the target (> 0).
    -- timeout_s         float  [s] Fail after this long (0: 2 x |distance_m| / speed_mps + 2 s).
    -- stall_window_s    float  [s] Fail when progress grew by less than stall_distance_m in this window.
    -- stall_distance_m  float  [m] Least progress per stall window (> 0).
    -- odom_topic        str    nav_msgs/Odometry topic.
    -- odom_timeout_s    float  [s] Fail when no fresh odometry for this long.
    -- cmd_topic         str    geometry_msgs/TwistStamped command topic.
    -- frame_id          str    frame_id of the commands (the robot's base frame).

    <= done    The distance was driven (within tolerance_m).
    <= failed  Stalled, timed out, or odometry was missing; the reason is logged.
    """

    def __init__(
        self,
        distance_m: float,
        speed_mps: float = 0.1,
        *,
        tolerance_m: float = 0.01,
        timeout_s: float = 0.0,
        stall_window_s: float = 1.0,
        stall_distance_m: float = 0.01,
        odom_topic: str = "odom",
        odom_timeout_s: float = 0.5,
        cmd_topic: str = "cmd_vel_stamped",
        frame_id: str = "base_footprint",
    ) -> None:
        super().__init__(
            ["done", "failed"],
            cmd_topic=cmd_topic,
            frame_id=frame_id,
            odom_topic=validation.name(type(self).__name__, "odom_topic", odom_topic),
            odom_timeout_s=odom_timeout_s,
        )
        owner = type(self).__name__
        self._distance_m = validation.number(owner, "distance_m", distance_m, unit="[m]")
        if self._distance_m == 0.0:
            raise ConfigError(f"{owner}: distance_m must not be 0 [m]")
        self._speed_mps = validation.number(owner, "speed_mps", speed_mps, positive=True,
                                             maximum=validation.MAX_LINEAR_MPS, unit="[m/s]")
        self._tolerance_m = validation.number(owner, "tolerance_m", tolerance_m, positive=True, unit="[m]")
        self._timeout_s = closed_loop_timeout(owner, timeout_s, amount=self._distance_m, amount_name="distance_m",
                                              speed=self._speed_mps, speed_name="speed_mps")
        self._stall = stall_watch(owner, stall_window_s, progress_name="stall_distance_m",
                                  min_progress=stall_distance_m, unit="m",
                                  slowest_speed=min(MIN_SPEED_MPS, self._speed_mps))
        self._start: Optional[OdomSample] = None
        self._progress_m = 0.0

    def on_enter(self, userdata: UserDataView) -> None:
        super().on_enter(userdata)
        self._start = None
        self._progress_m = 0.0

    def on_resume(self, userdata: UserDataView) -> None:
        super().on_resume(userdata)
        self._stall.restart_window(self.now_s())

    def execute(self, userdata: UserDataView) -> Optional[str]:
        now = self.now_s()
        sample = self.odometry()
        if sample is None:
            if self.odometry_lost():
                self.log_error(f"move {self._distance_m:+.3f} m: {self.odometry_problem()}")
                return "failed"
            self.stop()
            return None
        if self._start is None:
            self._start = sample
            self._stall.reset(0.0, now)
        start = self._start
        direction = math.copysign(1.0, self._distance_m)
        along = (sample.x - start.x) * math.cos(start.yaw) + (sample.y - start.y) * math.sin(start.yaw)
        self._progress_m = direction * along
        remaining = abs(self._distance_m) - self._progress_m
        if remaining <= self._tolerance_m:
            self.log_info(f"moved {direction * self._progress_m:+.3f} m (target {self._distance_m:+.3f} m)")
            return "done"
        if self.elapsed_s() > self._timeout_s:
            self.log_error(
                f"move {self._distance_m:+.3f} m timed out after {self._timeout_s:.1f} s at "
                f"{direction * self._progress_m:+.3f} m"
            )
            return "failed"
        if self._stall.stalled(self._progress_m, now):
            self.log_error(
                f"move {self._distance_m:+.3f} m stalled at {direction * self._progress_m:+.3f} m: less than "
                f"{self._stall.min_progress:g} m of progress in {self._stall.window_s:g} s"
            )
            return "failed"
        speed = min(self._speed_mps, max(MIN_SPEED_MPS, SLOWDOWN_GAIN * remaining))
        heading_error = wrap_angle(sample.yaw - start.yaw)
        w = max(-MAX_HEADING_RATE, min(MAX_HEADING_RATE, -HEADING_GAIN * heading_error))
        self.send(direction * speed, w)
        return None
