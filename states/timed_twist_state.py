"""TimedTwistState: publish a constant velocity command for a fixed time (open loop)."""

from __future__ import annotations

from typing import Optional

from flex_nav.behavior.userdata import UserDataView
from flex_nav_states import validation
from flex_nav_states.motion_base import MotionBase
from flex_nav_states.motion_params import SPEED_LIMITS, CommandOutput


class TimedTwistState(MotionBase):
    """Publishes one velocity command repeatedly for a fixed time (open loop), then stops.

    Paused time does not count. For distances and angles that matter use MoveDistanceState or
    RotateAngleState, which are closed loop on odometry.

    -- linear_mps     float  [m/s] Forward velocity (negative: backwards).
    -- angular_radps  float  [rad/s] Yaw rate, counter-clockwise positive.
    -- duration_s     float  [s] How long to drive (> 0).
    -- cmd_topic      str    geometry_msgs/TwistStamped command topic.
    -- frame_id       str    frame_id of the commands (the robot's base frame).

    <= done  The time has passed; the robot was sent a zero twist.
    """

    def __init__(self, linear_mps: float = 0.0, angular_radps: float = 0.0, duration_s: float = 1.0,
                 cmd_topic: str = "cmd_vel_stamped", frame_id: str = "base_footprint") -> None:
        owner = type(self).__name__
        super().__init__(["done"], command=CommandOutput(owner, cmd_topic, frame_id), odometry=None)
        self._v = SPEED_LIMITS.linear(owner, "linear_mps", linear_mps, signed=True)
        self._w = SPEED_LIMITS.angular(owner, "angular_radps", angular_radps, signed=True)
        self._duration_s = validation.number(owner, "duration_s", duration_s, positive=True, unit="[s]")

    def execute(self, userdata: UserDataView) -> Optional[str]:
        if self.elapsed_s() >= self._duration_s:
            return "done"
        self.send(self._v, self._w)
        return None
