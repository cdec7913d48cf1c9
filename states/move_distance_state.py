"""MoveDistanceState: drive straight forward or backward by a distance, closed loop on odometry."""

from __future__ import annotations

import math
from typing import Optional

from sensor_msgs.msg import LaserScan

from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.nav.angles import wrap_angle
from flex_nav_states import validation
from flex_nav_states.messages import OdomSample, message_age_s
from flex_nav_states.motion_base import MotionBase, closed_loop_timeout, stall_watch
from flex_nav_states.motion_params import SPEED_LIMITS, CommandOutput, OdometryInput, RearCheck
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of
from flex_nav_states.rear_clearance import gap_behind_m

# [1/s] commanded speed = gain x remaining distance near the end (capped at speed_mps); braking asked of the base:
# gain x speed (0.9 m/s^2 at 0.3 m/s). With 1.5 a 0.3 m back-off crept for over a second near its end
SLOWDOWN_GAIN = 3.0
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
    -- scan_topic        str    sensor_msgs/LaserScan topic: backing up, stop and fail when a point lies in the
                                way behind ("" for none: the robot backs up blind). Its frame is taken as the
                                base's (a lidar near the centre; see flex_nav_states.rear_clearance). A
                                scan that does not cover the back (a front-only lidar, a depth camera) shows
                                it free: the check is only as good as the scan's field of view.
    -- robot_radius_m    float  [m] Radius of the base, for the way behind (> 0).
    -- clearance_m       float  [m] Margin kept to what is behind (>= 0).
    -- scan_max_age_s    float  [s] Backing up needs a scan at most this old.

    <= done    The distance was driven (within tolerance_m).
    <= failed  Stalled, timed out, odometry was missing, or (with scan_topic) something was in the way behind
               or no fresh scan showed it free; the reason is logged.
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
        scan_topic: str = "",
        robot_radius_m: float = 0.2,
        clearance_m: float = 0.05,
        scan_max_age_s: float = 0.5,
    ) -> None:
        owner = type(self).__name__
        super().__init__(
            ["done", "failed"],
            odometry=OdometryInput(owner, odom_topic, odom_timeout_s),
            command=CommandOutput(owner, cmd_topic, frame_id),
        )
        self._distance_m = validation.number(owner, "distance_m", distance_m, unit="[m]")
        if self._distance_m == 0.0:
            raise ConfigError(f"{owner}: distance_m must not be 0 [m]")
        self._speed_mps = SPEED_LIMITS.linear(owner, "speed_mps", speed_mps)
        self._tolerance_m = validation.number(owner, "tolerance_m", tolerance_m, positive=True, unit="[m]")
        self._timeout_s = closed_loop_timeout(owner, timeout_s, amount=self._distance_m, amount_name="distance_m",
                                              speed=self._speed_mps, speed_name="speed_mps")
        self._stall = stall_watch(owner, stall_window_s, progress_name="stall_distance_m",
                                  min_progress=stall_distance_m, unit="m",
                                  slowest_speed=min(MIN_SPEED_MPS, self._speed_mps))
        self._rear = RearCheck(owner, scan_topic, robot_radius_m, clearance_m, scan_max_age_s)
        self._scan: Optional[SubscriptionLike] = None
        self._start: Optional[OdomSample] = None
        self._progress_m = 0.0

    def on_start(self) -> None:
        super().on_start()
        if self._rear.enabled and self._distance_m < 0.0:
            self._scan = proxies_of(self).subscription(self._rear.scan_topic, LaserScan)

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
        problem = self._problem(now, remaining)
        if problem is not None:
            self.stop()
            self.log_error(f"move {self._distance_m:+.3f} m {problem}")
            return "failed"
        speed = min(self._speed_mps, max(MIN_SPEED_MPS, SLOWDOWN_GAIN * remaining))
        heading_error = wrap_angle(sample.yaw - start.yaw)
        w = max(-MAX_HEADING_RATE, min(MAX_HEADING_RATE, -HEADING_GAIN * heading_error))
        self.send(direction * speed, w)
        return None

    def _problem(self, now: float, remaining_m: float) -> Optional[str]:
        """Why the move fails now (timed out, stalled, something behind), or None."""
        at = f"at {math.copysign(1.0, self._distance_m) * self._progress_m:+.3f} m"
        if self.elapsed_s() > self._timeout_s:
            return f"timed out after {self._timeout_s:.1f} s {at}"
        if self._stall.stalled(self._progress_m, now):
            return (f"stalled {at}: less than {self._stall.min_progress:g} m of progress in "
                    f"{self._stall.window_s:g} s")
        behind = self._way_behind_problem(remaining_m)
        return f"stopped {at}: {behind}" if behind is not None else None

    def _way_behind_problem(self, remaining_m: float) -> Optional[str]:
        """Why backing up on is not safe (something in the way, no fresh scan), or None (also when not checked)."""
        rear = self._rear
        if not rear.enabled or self._distance_m > 0.0:
            return None
        sub = self._scan
        if sub is None:
            sub = self._scan = proxies_of(self).subscription(rear.scan_topic, LaserScan)
        scan = sub.last()
        if scan is None or message_age_s(scan, sub, self.now_s()) > rear.scan_max_age_s:
            return f"no scan on {rear.scan_topic} newer than scan_max_age_s {rear.scan_max_age_s:g} s to see behind"
        gap = gap_behind_m(scan, rear.robot_radius_m, rear.clearance_m, remaining_m)
        if gap is None:
            return None
        return f"something is {gap:.2f} m behind the robot, in the way (clearance_m {rear.clearance_m:g} m)"
