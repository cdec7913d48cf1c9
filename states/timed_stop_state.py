"""TimedStopState: command a stop for a time, then check on odometry that the robot really stands still."""

from __future__ import annotations

from typing import Optional

from flex_nav.behavior.userdata import UserDataView
from flex_nav_states import validation
from flex_nav_states.motion_base import MotionBase
from flex_nav_states.motion_params import CommandOutput, OdometryInput


class TimedStopState(MotionBase):
    """Publishes zero twists for a time, then fails unless odometry shows the robot standing still.

    -- duration_s                 float  [s] How long to command the stop (> 0).
    -- linear_tolerance_mps       float  [m/s] Largest |forward velocity| that counts as stopped.
    -- angular_tolerance_radps    float  [rad/s] Largest |yaw rate| that counts as stopped.
    -- odom_topic                 str    nav_msgs/Odometry topic.
    -- odom_timeout_s             float  [s] Largest age of the odometry used for the check.
    -- cmd_topic                  str    geometry_msgs/TwistStamped command topic.
    -- frame_id                   str    frame_id of the commands (the robot's base frame).

    <= done    The robot stands still after duration_s.
    <= failed  It is still moving after duration_s, or there is no fresh odometry to tell; the reason is logged.
    """

    def __init__(
        self,
        duration_s: float = 0.5,
        *,
        linear_tolerance_mps: float = 0.01,
        angular_tolerance_radps: float = 0.02,
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
        self._duration_s = validation.number(owner, "duration_s", duration_s, positive=True, unit="[s]")
        self._lin_tol = validation.number(owner, "linear_tolerance_mps", linear_tolerance_mps, positive=True,
                                          unit="[m/s]")
        self._ang_tol = validation.number(owner, "angular_tolerance_radps", angular_tolerance_radps, positive=True,
                                          unit="[rad/s]")

    def execute(self, userdata: UserDataView) -> Optional[str]:
        self.stop()
        if self.elapsed_s() < self._duration_s:
            return None
        sample = self.odometry()
        if sample is None:
            self.log_error(f"stop after {self._duration_s:g} s cannot be confirmed: {self.odometry_problem()}")
            return "failed"
        if abs(sample.v) > self._lin_tol or abs(sample.w) > self._ang_tol:
            self.log_error(
                f"robot still moving {self._duration_s:g} s after the stop command: v={sample.v:+.3f} m/s, "
                f"w={sample.w:+.3f} rad/s (tolerances {self._lin_tol:g} m/s, {self._ang_tol:g} rad/s)"
            )
            return "failed"
        self.log_info(f"robot stopped (v={sample.v:+.3f} m/s, w={sample.w:+.3f} rad/s)")
        return "done"
