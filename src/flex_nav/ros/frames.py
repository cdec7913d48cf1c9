"""Poses and paths from messages into a node's frame via tf, with a bounded wait and a reason on failure."""

from __future__ import annotations

import math
import time
from typing import Optional

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import PoseStamped, Quaternion, TransformStamped
from nav_msgs.msg import Path

from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.nav.planar import heading_along, transform_poses
from flex_nav.nav.pose_checks import pose_problem, yaw_of_quaternion

TF_POLL_S = 0.002  # [s] wall: how often a bounded transform lookup looks again
TF_ERRORS = (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException)


def lookup_bounded(buffer: tf2_ros.Buffer, target_frame: str, source_frame: str, stamp: rospy.Time,
                   timeout_s: float, *, source_stamp: Optional[rospy.Time] = None,
                   fixed_frame: str = "") -> TransformStamped:
    """``buffer.lookup_transform`` waiting at most ``timeout_s`` [s] of ROS time, as tf2's own wait does -- or, while
    ROS time stands still, as much wall time since it last moved: tf2's wait would sleep forever when a lockstep
    simulation waits for this very node (:mod:`flex_nav.ros.lockstep`). Raises tf2's exception of the last try.
    With ``fixed_frame``: ``lookup_transform_full`` (target at ``stamp``, source at ``source_stamp``)."""
    start_s = seen_s = seen_wall_s = math.nan  # ROS time of the first miss; ROS time and when it last changed
    while True:
        try:
            if fixed_frame:
                return buffer.lookup_transform_full(target_frame, stamp, source_frame,
                                                    source_stamp if source_stamp is not None else stamp, fixed_frame)
            return buffer.lookup_transform(target_frame, source_frame, stamp)
        except TF_ERRORS:
            if timeout_s <= 0.0 or rospy.is_shutdown():
                raise
            now_s, wall_s = rospy.get_time(), time.monotonic()
            if math.isnan(start_s):
                start_s = now_s
            if now_s != seen_s:
                seen_s, seen_wall_s = now_s, wall_s
            if (now_s >= start_s + timeout_s or now_s < start_s  # the deadline, or time went back (a restarted sim)
                    or wall_s - seen_wall_s >= timeout_s):
                raise
        time.sleep(TF_POLL_S)


class TfSource:
    """A tf buffer with the listener that fills it: the one given (shared by the components of one process), or
    a buffer and listener of the caller's own when none is given."""

    def __init__(self, shared: Optional[tf2_ros.Buffer] = None, cache_s: float = 10.0) -> None:
        """``cache_s`` [s]: how long a buffer of its own keeps transforms (tf2's default 10 s)."""
        self.buffer: tf2_ros.Buffer = (shared if shared is not None
                                       else tf2_ros.Buffer(cache_time=rospy.Duration(cache_s)))
        self.listener: Optional[tf2_ros.TransformListener] = (
            None if shared is not None else tf2_ros.TransformListener(self.buffer))


def frame_pose(
    buffer: tf2_ros.Buffer, target_frame: str, source_frame: str, timeout_s: float, max_age_s: float = 0.0,
) -> tuple:
    """(x [m], y [m], yaw [rad]) of ``source_frame`` in ``target_frame`` (newest transform).

    With ``max_age_s`` > 0 a transform older than that [s] is a NotReadyError: a localization that has
    stopped publishing (map -> odom) is not taken for one that holds still. A chain of static transforms
    only (stamp 0, e.g. a robot on odometry alone) has no age."""
    if not source_frame:
        raise ConfigError(f"frame_id is empty (expected '{target_frame}' or a frame tf can transform into it)")
    if source_frame.lstrip("/") == target_frame.lstrip("/"):
        return (0.0, 0.0, 0.0)
    try:
        tf = lookup_bounded(buffer, target_frame.lstrip("/"), source_frame.lstrip("/"), rospy.Time(0), timeout_s)
    except TF_ERRORS as err:
        raise NotReadyError(f"frame '{source_frame}' cannot be transformed into '{target_frame}' "
                            f"within {timeout_s:.2f} s: {err}") from err
    if max_age_s > 0.0 and not tf.header.stamp.is_zero():
        age_s = (rospy.Time.now() - tf.header.stamp).to_sec()
        if age_s > max_age_s:
            raise NotReadyError(f"the newest transform '{target_frame}' -> '{source_frame}' is {age_s:.2f} s old "
                                f"(more than {max_age_s:.2f} s): is the localization publishing it?")
    t, q = tf.transform.translation, tf.transform.rotation
    return (t.x, t.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))


def goal_in_frame(buffer: tf2_ros.Buffer, goal: PoseStamped, target_frame: str, timeout_s: float) -> np.ndarray:
    """The goal as [x, y, yaw] in ``target_frame``; ConfigError for a bad pose, NotReadyError for a bad frame."""
    p, q = goal.pose.position, goal.pose.orientation
    problem = pose_problem((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
    if problem is not None:
        raise ConfigError(f"goal {problem}")
    pose = np.array([[p.x, p.y, yaw_of_quaternion(q.x, q.y, q.z, q.w)]])
    tx, ty, tyaw = frame_pose(buffer, target_frame, goal.header.frame_id, timeout_s)
    in_target: np.ndarray = transform_poses(pose, tx, ty, tyaw)[0]
    return in_target


def path_in_frame(buffer: tf2_ros.Buffer, path: Path, target_frame: str, timeout_s: float) -> np.ndarray:
    """The path's poses as (N, 3) [x, y, yaw] in ``target_frame``.

    ConfigError for an empty path or a bad pose (NaN/inf, unnormalised quaternion; the index is named),
    NotReadyError when the path's frame cannot be transformed. Each pose's own header is ignored: the
    path's header frame is used, as nav_msgs/Path users expect. An all-zero quaternion means "no
    orientation given" (common in generated paths): that pose faces along the path.
    """
    if not path.poses:
        raise ConfigError("the path is empty (no poses)")
    poses = np.empty((len(path.poses), 3))
    unoriented = np.zeros(len(path.poses), dtype=bool)
    for index, stamped in enumerate(path.poses):
        p, q = stamped.pose.position, stamped.pose.orientation
        if (q.x, q.y, q.z, q.w) == (0.0, 0.0, 0.0, 0.0):
            unoriented[index] = True
            q = Quaternion(w=1.0)
        problem = pose_problem((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
        if problem is not None:
            raise ConfigError(f"path pose {index}: {problem}")
        poses[index] = (p.x, p.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))
    if unoriented.any():
        poses[unoriented, 2] = heading_along(poses[:, :2])[unoriented]
    tx, ty, tyaw = frame_pose(buffer, target_frame, path.header.frame_id, timeout_s)
    return transform_poses(poses, tx, ty, tyaw)
