"""The robot's pose in a global frame from tf, with a bounded wait and a reason when it is not there."""

from __future__ import annotations

import math
from typing import Optional

import rospy
import tf2_ros
import yaml

from flex_nav.exceptions import NotReadyError
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.ros.frames import TF_ERRORS, lookup_bounded


class RobotPoseSource:
    """Looks up ``robot_base_frame`` in ``global_frame``; fails with NotReadyError when tf is missing or stale.

    ``transform_tolerance_s`` [s]: how old the newest transform may be (as move_base's parameter of that name).
    """

    def __init__(
        self,
        buffer: tf2_ros.Buffer,
        global_frame: str,
        robot_base_frame: str,
        transform_tolerance_s: float = 0.5,
    ) -> None:
        self.buffer = buffer
        self.global_frame = global_frame
        self.robot_base_frame = robot_base_frame
        self.transform_tolerance_s = transform_tolerance_s
        self._parent: Optional[str] = None  # the base frame's parent in tf, once known

    def _base_parent(self) -> Optional[str]:
        """The base frame's parent in tf (the odometry frame, or the global frame itself), once tf has the base
        frame (then kept: the tree does not change); None before."""
        if self._parent is None:
            try:
                frames = yaml.safe_load(self.buffer.all_frames_as_yaml()) or {}
            except yaml.YAMLError:
                return None
            parent = frames.get(self.robot_base_frame, {}).get("parent")
            self._parent = str(parent) if parent else None
        return self._parent

    def pose(self, timeout_s: float = 0.2, at_s: Optional[float] = None) -> tuple[float, float, float]:
        """(x [m], y [m], yaw [rad]) of the robot base in the global frame; waits at most ``timeout_s`` [s].

        ``at_s`` [s] (a lockstep simulation, where the odometry is stamped at that time: a planner's goal sent at a
        behavior's tick): the odometry at that time, waited for, not the newest this node happens to have received
        (one odometry message more or less, by a wall-time race, started the plan elsewhere), carried into the
        global frame by the newest transform of the odometry frame (a localizer's, which has come long before: it
        is sent a scan earlier); the newest pose when there is none at ``at_s``."""
        stamped = None
        parent = self._base_parent() if at_s is not None else None
        if at_s is not None and parent is not None:
            at = rospy.Time.from_sec(at_s)
            try:
                if parent == self.global_frame:  # (a costmap in the odometry frame)
                    stamped = lookup_bounded(self.buffer, self.global_frame, self.robot_base_frame, at, timeout_s)
                else:
                    stamped = lookup_bounded(self.buffer, self.global_frame, self.robot_base_frame, rospy.Time(0),
                                             timeout_s, source_stamp=at, fixed_frame=parent)
            except TF_ERRORS:
                stamped = None
        try:
            if stamped is None:
                stamped = lookup_bounded(self.buffer, self.global_frame, self.robot_base_frame, rospy.Time(0),
                                         timeout_s)
        except TF_ERRORS as err:
            raise NotReadyError(
                f"no transform {self.global_frame} -> {self.robot_base_frame} within {timeout_s:.2f} s: {err}"
            ) from err
        age_s = (rospy.Time.now() - stamped.header.stamp).to_sec()
        if stamped.header.stamp != rospy.Time(0) and age_s > self.transform_tolerance_s:
            raise NotReadyError(
                f"transform {self.global_frame} -> {self.robot_base_frame} is {age_s:.2f} s old "
                f"(tolerance {self.transform_tolerance_s:.2f} s)"
            )
        t = stamped.transform.translation
        q = stamped.transform.rotation
        yaw = yaw_of_quaternion(q.x, q.y, q.z, q.w)
        if not all(math.isfinite(v) for v in (t.x, t.y, yaw)):
            raise NotReadyError(f"transform {self.global_frame} -> {self.robot_base_frame} is not finite")
        return (t.x, t.y, yaw)
