"""RobotPoseState: the robot's pose from a pose topic into userdata (e.g. where exploring started), and
:class:`RobotPoseReader`, the reading it shares with the exploration states."""

from __future__ import annotations

from typing import Any, NamedTuple, Optional, Tuple

from geometry_msgs.msg import PoseStamped

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.nav.pose_checks import pose_problem, quaternion_of_yaw, yaw_of_quaternion
from flex_nav_states import validation
from flex_nav_states.messages import describe, message_age_s, stamp_s, to_stamp
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of
from flex_nav_states.pure_pursuit_state import POSE_TYPES


class RobotPose(NamedTuple):
    """The robot's planar pose in one message."""

    x: float  # [m]
    y: float  # [m]
    yaw: float  # [rad]
    frame_id: str  # without a leading "/"
    stamp_s: float  # [s] header stamp (0.0 if not stamped)


def planar_pose_stamped(x: float, y: float, yaw: float, frame_id: str, time_s: float) -> PoseStamped:
    """A geometry_msgs/PoseStamped at (``x``, ``y``) [m] facing ``yaw`` [rad], stamped ``time_s`` [s]."""
    msg = PoseStamped()
    msg.header.stamp = to_stamp(time_s)
    msg.header.frame_id = frame_id
    msg.pose.position.x, msg.pose.position.y = float(x), float(y)
    o = msg.pose.orientation
    o.x, o.y, o.z, o.w = quaternion_of_yaw(yaw)
    return msg


class RobotPoseReader:
    """The newest valid robot pose on one topic (a helper of the states, not a state)."""

    def __init__(self, owner: str, topic: str, pose_type: str, max_age_s: float) -> None:
        self.topic = validation.name(owner, "pose_topic", topic)
        self.msg_type = POSE_TYPES[validation.choice(owner, "pose_type", pose_type, POSE_TYPES)]
        self.max_age_s = validation.number(owner, "pose_max_age_s", max_age_s, minimum=0.0, unit="[s]")
        self._sub: Optional[SubscriptionLike] = None

    def start(self, state: State) -> None:
        self._sub = proxies_of(state).subscription(self.topic, self.msg_type)

    def read(self, state: State) -> Tuple[Optional[RobotPose], str]:
        """(the newest pose, "") if there is one, valid and at most max_age_s old (any age if 0); else (None, why)."""
        if self._sub is None:
            self.start(state)
        sub = self._sub
        assert sub is not None
        msg: Any = sub.last()
        if msg is None:
            return None, f"no robot pose on {self.topic} yet"
        age_s = message_age_s(msg, sub, state.now_s())
        if self.max_age_s > 0.0 and age_s > self.max_age_s:
            return None, f"the robot pose on {self.topic} is {age_s:.1f} s old (pose_max_age_s {self.max_age_s:g} s)"
        pose = msg.pose.pose if hasattr(msg.pose, "pose") else msg.pose  # Odometry, PoseWithCovarianceStamped
        p, q = pose.position, pose.orientation
        problem = pose_problem((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
        frame = str(msg.header.frame_id).lstrip("/")
        if problem is None and not frame:
            problem = "it has no frame_id"
        if problem is not None:
            return None, f"the robot pose on {self.topic} is not usable: {problem}"
        return RobotPose(float(p.x), float(p.y), yaw_of_quaternion(q.x, q.y, q.z, q.w), frame, stamp_s(msg)), ""


class RobotPoseState(State):
    """Writes the robot's current pose to userdata, from a pose topic (a localizer's or mapper's estimate).

    Takes the newest message on ``pose_topic`` that is valid (finite, normalised orientation, a frame_id) and not
    older than ``pose_max_age_s``; waits for one at most ``timeout_s`` after entry.

    -- pose_topic      str    Robot pose topic, relative to the behavior's namespace.
    -- pose_type       str    Message type on pose_topic: odometry, pose_stamped or pose_with_covariance.
    -- pose_max_age_s  float  [s] Largest accepted age of the pose (0: any age; a localizer publishes only when
                              its filter updates, which it does not while the robot stands).
    -- timeout_s       float  [s] Fail if there is no valid pose this long after entry (> 0).

    #> pose  PoseStamped  The robot's planar pose (x, y, heading) in the frame of the pose message.

    <= done    The pose was written to userdata.
    <= failed  No valid pose within timeout_s; the reason is logged.
    """

    def __init__(self, pose_topic: str = "amcl_pose", pose_type: str = "pose_with_covariance",
                 pose_max_age_s: float = 0.0, timeout_s: float = 5.0) -> None:
        super().__init__(outcomes=["done", "failed"], output_keys=["pose"])
        owner = type(self).__name__
        self._reader = RobotPoseReader(owner, pose_topic, pose_type, pose_max_age_s)
        self._timeout_s = validation.number(owner, "timeout_s", timeout_s, positive=True, unit="[s]")
        self._give_up_s = 0.0  # [s] on the behavior's clock

    def on_start(self) -> None:
        self._reader.start(self)

    def on_enter(self, userdata: UserDataView) -> None:
        self._give_up_s = self.now_s() + self._timeout_s

    def execute(self, userdata: UserDataView) -> Optional[str]:
        pose, problem = self._reader.read(self)
        if pose is not None:
            msg = planar_pose_stamped(pose.x, pose.y, pose.yaw, pose.frame_id, pose.stamp_s or self.now_s())
            userdata.pose = msg
            self.log_info(f"robot pose: {describe(msg)}")
            return "done"
        if self.now_s() >= self._give_up_s:
            self.log_error(f"no robot pose within {self._timeout_s:g} s: {problem}")
            return "failed"
        return None
