#!/usr/bin/env python3
"""Test double of a differential-drive robot: integrates ``cmd_vel`` (Twist) into odometry and tf.

Publishes ``odom`` (nav_msgs/Odometry), tf ``odom_frame -> base_frame`` at ``~rate`` [Hz], a static
``map_frame -> odom_frame`` equal to the start pose (so odometry starts at zero), and a fake ``scan``
(sensor_msgs/LaserScan, ``~beams`` beams over 360 deg, ``~scan_range`` [m]) ray-marched through the map
file ``~map_yaml`` at ``~scan_rate`` [Hz]. The base stops when no command came for ``~cmd_timeout`` [s],
like a real driver. Motion is exact unicycle integration; walls do not stop it (tests check where it went).
"""

import math
import sys
import threading

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped, Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from flex_nav.nav.costmap.map_io import load_map
from flex_nav.ros.node import init_node


def transform(parent, child, stamp, x, y, yaw):
    msg = TransformStamped()
    msg.header.stamp = stamp
    msg.header.frame_id = parent
    msg.child_frame_id = child
    msg.transform.translation.x = x
    msg.transform.translation.y = y
    msg.transform.rotation.z = math.sin(yaw / 2.0)
    msg.transform.rotation.w = math.cos(yaw / 2.0)
    return msg


class KinematicRobot:
    def __init__(self):
        self.map_frame = rospy.get_param("~map_frame", "map")
        self.odom_frame = rospy.get_param("~odom_frame", "odom")
        self.base_frame = rospy.get_param("~base_frame", "base_footprint")
        self.start = (float(rospy.get_param("~x", 0.0)), float(rospy.get_param("~y", 0.0)),
                      float(rospy.get_param("~yaw", 0.0)))
        self.rate_hz = float(rospy.get_param("~rate", 50.0))
        self.cmd_timeout_s = float(rospy.get_param("~cmd_timeout", 0.5))
        self.scan_range = float(rospy.get_param("~scan_range", 3.5))
        self.beams = int(rospy.get_param("~beams", 360))
        map_yaml = rospy.get_param("~map_yaml", "")
        self.grid = load_map(map_yaml) if map_yaml else None
        self.lock = threading.Lock()
        self.pose = [0.0, 0.0, 0.0]  # in the odom frame
        self.cmd = (0.0, 0.0)
        self.cmd_time = rospy.get_time()
        self.odom_pub = rospy.Publisher("odom", Odometry, queue_size=5)
        self.scan_pub = rospy.Publisher("scan", LaserScan, queue_size=1)
        self.tf = tf2_ros.TransformBroadcaster()
        self.static_tf = tf2_ros.StaticTransformBroadcaster()
        self.static_tf.sendTransform(transform(self.map_frame, self.odom_frame, rospy.Time.now(), *self.start))
        rospy.Subscriber("cmd_vel", Twist, self.on_cmd, queue_size=1, tcp_nodelay=True)
        self.last_step = rospy.get_time()
        rospy.Timer(rospy.Duration(1.0 / self.rate_hz), quiet_at_shutdown(self.step))
        if self.grid is not None:
            scan_period_s = 1.0 / float(rospy.get_param("~scan_rate", 10.0))
            rospy.Timer(rospy.Duration(scan_period_s), quiet_at_shutdown(self.publish_scan))

    def on_cmd(self, msg):
        with self.lock:
            self.cmd = (msg.linear.x, msg.angular.z)
            self.cmd_time = rospy.get_time()

    def step(self, _event):
        now = rospy.get_time()
        with self.lock:
            dt = now - self.last_step
            self.last_step = now
            v, w = self.cmd if now - self.cmd_time <= self.cmd_timeout_s else (0.0, 0.0)
            x, y, yaw = self.pose
            if abs(w) > 1e-9:
                x += v / w * (math.sin(yaw + w * dt) - math.sin(yaw))
                y -= v / w * (math.cos(yaw + w * dt) - math.cos(yaw))
            else:
                x += v * dt * math.cos(yaw)
                y += v * dt * math.sin(yaw)
            yaw = math.atan2(math.sin(yaw + w * dt), math.cos(yaw + w * dt))
            self.pose = [x, y, yaw]
        stamp = rospy.Time.from_sec(now)
        self.tf.sendTransform(transform(self.odom_frame, self.base_frame, stamp, x, y, yaw))
        odom = Odometry()
        odom.header.stamp = stamp
        odom.header.frame_id = self.odom_frame
        odom.child_frame_id = self.base_frame
        odom.pose.pose.position.x, odom.pose.pose.position.y = x, y
        odom.pose.pose.orientation.z, odom.pose.pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
        odom.twist.twist.linear.x, odom.twist.twist.angular.z = v, w
        self.odom_pub.publish(odom)

    def map_pose(self):
        sx, sy, syaw = self.start
        with self.lock:
            x, y, yaw = self.pose
        return (sx + math.cos(syaw) * x - math.sin(syaw) * y, sy + math.sin(syaw) * x + math.cos(syaw) * y,
                syaw + yaw)

    def publish_scan(self, _event):
        stamp = rospy.Time.now()
        x, y, yaw = self.map_pose()
        grid = self.grid
        step = grid.resolution / 2.0
        angles = np.linspace(-math.pi, math.pi, self.beams, endpoint=False)
        dists = np.arange(step, self.scan_range, step)
        xs = x + np.cos(yaw + angles)[:, None] * dists[None, :]
        ys = y + np.sin(yaw + angles)[:, None] * dists[None, :]
        rows, cols = grid.world_to_cells(xs.ravel(), ys.ravel())
        inside = (rows >= 0) & (rows < grid.height) & (cols >= 0) & (cols < grid.width)
        hit = np.zeros(rows.shape, dtype=bool)
        hit[inside] = grid.occupancy[rows[inside], cols[inside]] >= 65
        hit = hit.reshape(xs.shape)
        first = np.where(hit.any(axis=1), hit.argmax(axis=1), -1)
        ranges = np.where(first >= 0, dists[np.maximum(first, 0)], np.inf)
        scan = LaserScan()
        scan.header.stamp = stamp
        scan.header.frame_id = self.base_frame
        scan.angle_min = float(angles[0])
        scan.angle_max = float(angles[-1])
        scan.angle_increment = float(angles[1] - angles[0])
        scan.scan_time = 0.1
        scan.range_min = 0.05
        scan.range_max = self.scan_range
        scan.ranges = ranges.astype(np.float32).tolist()
        self.scan_pub.publish(scan)


def quiet_at_shutdown(callback):
    """Timer callbacks may still fire while rospy closes the publishers: ignore that, not real errors."""

    def wrapped(event):
        try:
            callback(event)
        except rospy.ROSException:
            if not rospy.is_shutdown():
                raise

    return wrapped


if __name__ == "__main__":
    init_node("kinematic_robot")
    KinematicRobot()
    rospy.spin()
    sys.exit(0)
