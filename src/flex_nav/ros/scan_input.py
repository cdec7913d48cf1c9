"""What a laser-based node (the localizer, the mapper) needs from each scan: the laser's pose on the robot, the
robot's odometry pose at the scan's stamp (tf, as amcl and slam_toolbox look them up), the scan as
:class:`~flex_nav.localization.ScanBeams`, and warnings about bad input that name the field and do not flood the log.
"""

from __future__ import annotations

import time
from typing import Dict, Optional, Tuple

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped
from sensor_msgs.msg import LaserScan

from flex_nav.localization import ScanBeams
from flex_nav.nav.planar import Pose2D
from flex_nav.nav.pose_checks import quaternion_of_yaw, yaw_of_quaternion
from flex_nav.ros.frames import TF_ERRORS, lookup_bounded

LOG_THROTTLE_S = 2.0  # [s] wall: one kind of complaint is logged at most this often


class Complaints:
    """Warnings about bad input, each kind logged at most every LOG_THROTTLE_S (unless asked not to throttle)."""

    def __init__(self, node: str) -> None:
        self.node = node
        self._logged_at: Dict[str, float] = {}

    def __call__(self, kind: str, message: str, throttle: bool = True) -> None:
        now = time.monotonic()
        if throttle and now - self._logged_at.get(kind, -LOG_THROTTLE_S) < LOG_THROTTLE_S:
            return
        self._logged_at[kind] = now
        rospy.logwarn("%s: %s", self.node, message)


class ScanInput:
    """tf lookups for scans: the laser frame in ``base_frame`` (static: cached) and ``odom_frame`` ->
    ``base_frame`` at a stamp, each waited for at most ``timeout``."""

    def __init__(self, buffer: tf2_ros.Buffer, odom_frame: str, base_frame: str, timeout: rospy.Duration,
                 complain: Complaints, *, laser_range: Tuple[float, float] = (-1.0, -1.0)) -> None:
        self.buffer = buffer
        self.odom_frame = odom_frame
        self.base_frame = base_frame
        self.timeout = timeout
        self.complain = complain
        self.laser_min_range, self.laser_max_range = laser_range  # [m] <= 0: the scan's own
        self._laser_poses: Dict[str, Pose2D] = {}  # laser frame -> its pose in the base frame

    def laser_pose(self, frame: str) -> Optional[Pose2D]:
        """The pose of laser ``frame`` in the base frame; None (and a warning) if tf cannot place it."""
        frame = frame.lstrip("/")
        known = self._laser_poses.get(frame)
        if known is not None:
            return known
        if not frame:
            self.complain("scan_frame", "scan ignored: its header.frame_id is empty")
            return None
        try:
            tf = lookup_bounded(self.buffer, self.base_frame, frame, rospy.Time(0), self.timeout.to_sec())
        except TF_ERRORS as err:
            self.complain("scan_frame", f"scan ignored: its frame '{frame}' cannot be placed in the base frame "
                                        f"'{self.base_frame}': {err}")
            return None
        pose = planar(tf)
        self._laser_poses[frame] = pose
        return pose

    def odom_pose(self, stamp: rospy.Time) -> Optional[Pose2D]:
        """The robot's odometry pose at ``stamp``; None (and a warning) if tf has none."""
        try:
            tf = lookup_bounded(self.buffer, self.odom_frame, self.base_frame, stamp, self.timeout.to_sec())
        except TF_ERRORS as err:
            self.complain("odom", f"scan ignored: no odometry '{self.odom_frame}' -> '{self.base_frame}' at the "
                                  f"scan's stamp {stamp.to_sec():.3f} s: {err}")
            return None
        return planar(tf)

    def beams(self, scan: LaserScan, laser_pose: Pose2D) -> ScanBeams:
        """``scan`` as ScanBeams (ranges as received; the range limits overridden where configured)."""
        ranges = np.asarray(scan.ranges, dtype=np.float64)
        angles = scan.angle_min + scan.angle_increment * np.arange(len(ranges), dtype=np.float64)
        range_min = self.laser_min_range if self.laser_min_range > 0.0 else float(scan.range_min)
        range_max = self.laser_max_range if self.laser_max_range > 0.0 else float(scan.range_max)
        return ScanBeams(ranges, angles, laser_pose, range_min, range_max)


def invalid_beams(beams: ScanBeams) -> int:
    """How many beams are NaN, -inf or a finite value outside [range_min, range_max]. A +inf beam ("no return
    within range", REP 117) and a max-range reading are not bad input."""
    ranges = beams.ranges
    with np.errstate(invalid="ignore"):
        good = (ranges == np.inf) | ((ranges >= beams.range_min) & (ranges <= beams.range_max))
    return int(ranges.size - np.count_nonzero(good))


def planar(tf: TransformStamped) -> Pose2D:
    """The x, y, yaw of a transform (z, roll and pitch dropped)."""
    t, q = tf.transform.translation, tf.transform.rotation
    return (t.x, t.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))


def transform_msg(stamp: rospy.Time, parent: str, child: str, pose: Pose2D) -> TransformStamped:
    """A TransformStamped ``parent`` -> ``child`` of the planar ``pose``."""
    tf = TransformStamped()
    tf.header.stamp = stamp
    tf.header.frame_id = parent
    tf.child_frame_id = child
    tf.transform.translation.x, tf.transform.translation.y = pose[0], pose[1]
    r = tf.transform.rotation
    r.x, r.y, r.z, r.w = quaternion_of_yaw(pose[2])
    return tf
