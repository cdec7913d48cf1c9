"""Message helpers shared by the states: stamps and ages, odometry samples, twists, short descriptions.

Pure functions on genpy message objects (no rospy). Times are seconds on the behavior's clock, which in a
ROS run is ROS time (simulated time included), the same time base as message stamps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional

import genpy
from geometry_msgs.msg import TwistStamped

from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav_states.proxy_types import SubscriptionLike

DESCRIBE_MAX_CHARS = 160  # longest description of a value in a log line
FUTURE_STAMP_TOLERANCE_S = 0.5  # [s] a stamp further ahead of the clock than this is not trusted


def stamp_s(msg: Any) -> float:
    """[s] ``msg.header.stamp``, or 0.0 for a message without a header (0.0 also means "not stamped")."""
    header = getattr(msg, "header", None)
    stamp = getattr(header, "stamp", None)
    return float(stamp.to_sec()) if stamp is not None else 0.0


def message_age_s(msg: Any, subscription: SubscriptionLike, now_s: float) -> float:
    """[s] how old ``msg`` is: ``now_s`` minus its header stamp, or the subscription's arrival age when it is not
    stamped or stamped more than ``FUTURE_STAMP_TOLERANCE_S`` ahead of the clock (a skewed clock on the sender
    would otherwise keep a message "fresh" long after its source stopped)."""
    stamp = stamp_s(msg)
    if stamp > 0.0 and now_s - stamp >= -FUTURE_STAMP_TOLERANCE_S:
        return now_s - stamp
    return subscription.age_s()


def to_stamp(time_s: float) -> genpy.Time:
    return genpy.Time.from_sec(max(time_s, 0.0))


@dataclass(frozen=True)
class OdomSample:
    """The planar state in one nav_msgs/Odometry message."""

    x: float  # [m] in the odometry frame
    y: float  # [m]
    yaw: float  # [rad]
    v: float  # [m/s] forward velocity (body frame)
    w: float  # [rad/s] yaw rate
    stamp_s: float  # [s] header stamp (0.0 if not stamped)
    frame_id: str


def odom_sample(msg: Any) -> OdomSample:
    """An :class:`OdomSample` of a nav_msgs/Odometry message."""
    p = msg.pose.pose.position
    q = msg.pose.pose.orientation
    t = msg.twist.twist
    return OdomSample(
        float(p.x),
        float(p.y),
        yaw_of_quaternion(q.x, q.y, q.z, q.w),
        float(t.linear.x),
        float(t.angular.z),
        stamp_s(msg),
        str(msg.header.frame_id),
    )


def sample_is_finite(sample: OdomSample) -> bool:
    return all(math.isfinite(v) for v in (sample.x, sample.y, sample.yaw, sample.v, sample.w))


def twist_stamped(v: float, w: float, frame_id: str, time_s: float) -> TwistStamped:
    """A geometry_msgs/TwistStamped with forward speed ``v`` [m/s] and yaw rate ``w`` [rad/s]."""
    msg = TwistStamped()
    msg.header.stamp = to_stamp(time_s)
    msg.header.frame_id = frame_id
    msg.twist.linear.x = float(v)
    msg.twist.angular.z = float(w)
    return msg


def describe(value: Any) -> str:
    """A short human-readable text for a log line: poses as (x, y, yaw), paths as length and size."""
    text = _describe(value)
    return text if len(text) <= DESCRIBE_MAX_CHARS else text[: DESCRIBE_MAX_CHARS - 3] + "..."


def _describe(value: Any) -> str:
    pose = _pose_of(value)
    if pose is not None:
        frame = getattr(getattr(value, "header", None), "frame_id", "")
        p, q = pose.position, pose.orientation
        yaw = yaw_of_quaternion(q.x, q.y, q.z, q.w)
        where = f" in {frame}" if frame else ""
        return f"({p.x:.2f}, {p.y:.2f}, {math.degrees(yaw):.0f} deg){where}"
    poses = getattr(value, "poses", None)
    if poses is not None and hasattr(value, "header"):
        length = 0.0
        for a, b in zip(poses, poses[1:]):
            length += math.hypot(b.pose.position.x - a.pose.position.x, b.pose.position.y - a.pose.position.y)
        return f"path of {len(poses)} poses, {length:.2f} m in {value.header.frame_id or '(no frame)'}"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def _pose_of(value: Any) -> Optional[Any]:
    """The geometry_msgs/Pose inside a Pose, PoseStamped or PoseWithCovarianceStamped, else None."""
    if hasattr(value, "position") and hasattr(value, "orientation"):
        return value
    inner = getattr(value, "pose", None)
    if inner is None:
        return None
    if hasattr(inner, "position") and hasattr(inner, "orientation"):
        return inner
    inner = getattr(inner, "pose", None)
    if inner is not None and hasattr(inner, "position") and hasattr(inner, "orientation"):
        return inner
    return None
