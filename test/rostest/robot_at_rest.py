"""What the sensors of a robot standing still at the origin publish, for rostest nodes that fake them (imported from
this directory, not a test itself)."""

import math
from typing import Any

from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

BASE_FRAME = "base_footprint"
SCAN_BEAMS = 360  # over the full circle, the first straight behind


def identity_tf(parent: str, child: str, stamp: Any) -> TransformStamped:
    """The transform ``parent`` -> ``child`` with neither offset nor rotation."""
    tf = TransformStamped()
    tf.header.stamp = stamp
    tf.header.frame_id, tf.child_frame_id = parent, child
    tf.transform.rotation.w = 1.0
    return tf


def odom_at_rest(stamp: Any, frame_id: str = "odom") -> Odometry:
    """Odometry of the base standing at the origin of ``frame_id``."""
    odom = Odometry()
    odom.header.stamp = stamp
    odom.header.frame_id, odom.child_frame_id = frame_id, BASE_FRAME
    odom.pose.pose.orientation.w = 1.0
    return odom


def empty_scan(stamp: Any) -> LaserScan:
    """A scan of the base's SCAN_BEAMS beams (0.05 m to 3.5 m) that sees nothing: every range inf."""
    scan = LaserScan()
    scan.header.stamp = stamp
    scan.header.frame_id = BASE_FRAME
    scan.angle_min, scan.angle_increment = -math.pi, 2 * math.pi / SCAN_BEAMS
    scan.angle_max = scan.angle_min + (SCAN_BEAMS - 1) * scan.angle_increment
    scan.range_min, scan.range_max = 0.05, 3.5
    scan.ranges = [float("inf")] * SCAN_BEAMS
    return scan
