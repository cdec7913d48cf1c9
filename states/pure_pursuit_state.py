"""PurePursuitState: follow the ``plan`` in userdata with regulated pure pursuit inside the behavior."""

from __future__ import annotations

import math
from typing import Any, Dict, Mapping, Optional, Tuple

import numpy as np
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped
from nav_msgs.msg import Odometry

from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.pure_pursuit import PurePursuitParams, PursuitStatus, RegulatedPurePursuit
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav_states import validation
from flex_nav_states.messages import describe, message_age_s
from flex_nav_states.motion_base import MotionBase
from flex_nav_states.motion_params import CommandOutput, OdometryInput
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of

POSE_TYPES: Dict[str, type] = {
    "odometry": Odometry,
    "pose_stamped": PoseStamped,
    "pose_with_covariance": PoseWithCovarianceStamped,
}


def plan_array(plan: Any) -> np.ndarray:
    """(N, 3) [x [m], y [m], yaw [rad]] of a nav_msgs/Path; ConfigError if it is empty."""
    poses = plan.poses
    if len(poses) == 0:
        raise ConfigError("plan is empty")
    out = np.empty((len(poses), 3))
    for i, stamped in enumerate(poses):
        p, q = stamped.pose.position, stamped.pose.orientation
        out[i] = (p.x, p.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))
    return out


def _pose_of(msg: Any) -> Tuple[float, float, float]:
    pose = msg.pose.pose if hasattr(msg.pose, "pose") else msg.pose  # Odometry/PoseWithCovarianceStamped vs PoseStamped
    p, q = pose.position, pose.orientation
    return float(p.x), float(p.y), yaw_of_quaternion(q.x, q.y, q.z, q.w)


class PurePursuitState(MotionBase):
    """Drives along the plan in userdata with regulated pure pursuit (no controller server needed).

    Runs :class:`flex_nav.nav.control.pure_pursuit.RegulatedPurePursuit` at the state's rate (20 Hz by default)
    without a costmap, so it does not avoid obstacles: run it beside a bumper/stuck monitor. The robot pose
    must be in the plan's frame: from ``pose_topic`` (e.g. a localization output in map), or from the
    odometry when ``pose_topic`` is empty (then the plan must be in the odometry frame). A frame mismatch
    fails the state; it never follows a plan in the wrong frame. The velocity comes from the odometry.

    -- pure_pursuit    dict   PurePursuitParams by name (unknown names are rejected); {} for the defaults.
    -- pose_topic      str    Robot pose topic in the plan's frame ("" for the odometry pose).
    -- pose_type       str    Message type on pose_topic: odometry, pose_stamped or pose_with_covariance.
    -- timeout_s       float  [s] Fail after this long (0: no limit).
    -- odom_topic      str    nav_msgs/Odometry topic (velocity, and pose when pose_topic is empty).
    -- odom_timeout_s  float  [s] Fail when no fresh odometry (or pose) for this long.
    -- cmd_topic       str    geometry_msgs/TwistStamped command topic.
    -- frame_id        str    frame_id of the commands (the robot's base frame).

    ># plan  Path  The path to follow (nav_msgs/Path with a frame_id, at least one pose).

    <= done    The goal was reached (position and, when configured, heading).
    <= failed  Bad plan, frame mismatch, stale odometry or pose, or timeout; the reason is logged.
    """

    def __init__(
        self,
        pure_pursuit: Optional[Mapping[str, Any]] = None,
        *,
        pose_topic: str = "",
        pose_type: str = "odometry",
        timeout_s: float = 0.0,
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
            input_keys=["plan"],
        )
        if pure_pursuit is not None and not isinstance(pure_pursuit, Mapping):
            raise ConfigError(f"{owner}: pure_pursuit must be a mapping of parameter names, got {pure_pursuit!r}")
        try:
            self._params = PurePursuitParams.from_mapping(dict(pure_pursuit or {}))
        except ConfigError as err:
            raise ConfigError(f"{owner}: {err}") from err
        self._pose_topic = validation.name(owner, "pose_topic", pose_topic, allow_empty=True)
        self._pose_type = POSE_TYPES[validation.choice(owner, "pose_type", pose_type, POSE_TYPES)]
        self._timeout_s = validation.number(owner, "timeout_s", timeout_s, minimum=0.0, unit="[s]")
        self._controller = RegulatedPurePursuit(self._params)
        self._pose_sub: Optional[SubscriptionLike] = None
        self._plan_frame = ""
        self._error = ""
        self._last_step_s: Optional[float] = None
        self._last_good_s = 0.0  # [s] when odometry and pose were last both fresh (entry and resume count)

    def on_start(self) -> None:
        super().on_start()
        if self._pose_topic:
            self._pose_sub = proxies_of(self).subscription(self._pose_topic, self._pose_type)

    def on_enter(self, userdata: UserDataView) -> None:
        super().on_enter(userdata)
        self._error = ""
        self._last_step_s = None
        self._last_good_s = self.now_s()
        plan = unwrap(userdata.plan)
        try:
            if not hasattr(plan, "poses") or not hasattr(plan, "header"):
                raise ConfigError(f"userdata plan must be a nav_msgs/Path, got {type(plan).__name__}")
            self._plan_frame = str(plan.header.frame_id).lstrip("/")
            if not self._plan_frame:
                raise ConfigError("plan has no frame_id")
            self._controller.set_path(plan_array(plan))
            self.log_info(f"following {describe(plan)}")
        except ConfigError as err:
            self._error = str(err)
            self._controller.clear()

    def on_resume(self, userdata: UserDataView) -> None:
        super().on_resume(userdata)
        self._last_step_s = None
        self._last_good_s = self.now_s()

    def execute(self, userdata: UserDataView) -> Optional[str]:  # noqa: PLR0911 - one control step, top to bottom
        if self._error:
            self.log_error(f"cannot follow the plan: {self._error}")
            return "failed"
        now = self.now_s()
        odom = self.odometry()
        pose = self._robot_pose(now) if odom is not None else None
        if odom is None or pose is None:
            if now - self._last_good_s > self.odometry_input().timeout_s:
                problem = self.odometry_problem() if odom is None else self._pose_problem(now)
                self.log_error(f"pure pursuit stopped: {problem}")
                return "failed"
            self.stop()
            return None
        self._last_good_s = now
        (x, y, yaw), frame = pose
        if frame != self._plan_frame:
            odom_topic = self.odometry_input().topic
            source = f"pose_topic {self._pose_topic}" if self._pose_topic else f"odometry on {odom_topic}"
            self.log_error(
                f"robot pose from {source} is in frame '{frame}' but the plan is in '{self._plan_frame}': set "
                "pose_topic to a pose in the plan's frame"
            )
            return "failed"
        period = 1.0 / self.rate_hz if math.isfinite(self.rate_hz) else 0.05
        dt = period if self._last_step_s is None or now <= self._last_step_s else now - self._last_step_s
        self._last_step_s = now
        cmd = self._controller.step((x, y, yaw), (odom.v, odom.w), dt)
        if cmd.status is PursuitStatus.GOAL_REACHED:
            self.log_info(f"goal reached at ({x:.2f}, {y:.2f}, {math.degrees(yaw):.0f} deg)")
            return "done"
        if not cmd.status.moving:
            self.log_error(f"pure pursuit stopped: {cmd.status.name}: {cmd.reason}")
            return "failed"
        if self._timeout_s > 0.0 and self.elapsed_s() > self._timeout_s:
            self.log_error(
                f"pure pursuit timed out after {self._timeout_s:g} s, {cmd.distance_to_goal:.2f} m from the goal"
            )
            return "failed"
        self.send(cmd.v, cmd.w)
        return None

    def _robot_pose(self, now: float) -> Optional[Tuple[Tuple[float, float, float], str]]:
        """((x, y, yaw), frame) of the robot from pose_topic or the odometry; None if not fresh and finite."""
        if self._pose_topic:
            sub = self._pose_sub
            if sub is None:
                sub = self._pose_sub = proxies_of(self).subscription(self._pose_topic, self._pose_type)
            msg = sub.last()
            if msg is None or message_age_s(msg, sub, now) > self.odometry_input().timeout_s:
                return None
        else:
            sub = self._odom
            msg = sub.last() if sub is not None else None
            if msg is None:
                return None
        pose = _pose_of(msg)
        if not all(math.isfinite(v) for v in pose):
            return None
        return pose, str(msg.header.frame_id).lstrip("/")

    def _pose_problem(self, now: float) -> str:
        sub = self._pose_sub
        msg = sub.last() if sub is not None else None
        if msg is None or sub is None:
            return f"no robot pose on {self._pose_topic} within {self.odometry_input().timeout_s:g} s"
        return f"robot pose on {self._pose_topic} is stale or invalid ({message_age_s(msg, sub, now):.2f} s old)"
