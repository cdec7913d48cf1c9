"""Helpers for the state tests: :class:`Harness` (the package's StateHarness: one state in the behavior executor on a
ManualClock with fake proxies), a kinematic robot that turns the published twists into odometry, message builders."""

from __future__ import annotations

import math
from typing import List, Optional

import genpy
from geometry_msgs.msg import PoseStamped, TwistStamped
from nav_msgs.msg import Odometry, Path
from sensor_msgs.msg import LaserScan

from flex_nav.nav.pose_checks import quaternion_of_yaw
from flex_nav.testing.state_harness import START_S
from flex_nav.testing.state_harness import StateHarness as Harness


class KinematicRobot:
    """A unicycle that follows the newest TwistStamped on ``cmd_topic`` and publishes odometry on ``odom``.

    ``blocked``: commands are ignored (the robot stands, as against a wall); ``forced_velocity``: (v, w) it
    keeps regardless of commands (a robot that does not stop). ``odom_every``: publish odometry only every
    n-th step (0: never).
    """

    def __init__(self, harness: Harness, cmd_topic: str = "cmd_vel_stamped", odom_topic: str = "odom",
                 frame: str = "odom", x: float = 0.0, y: float = 0.0, yaw: float = 0.0) -> None:
        self.harness = harness
        self.cmd_topic = cmd_topic
        self.odom = harness.proxies.subscription(odom_topic, Odometry)
        self.frame = frame
        self.x, self.y, self.yaw = x, y, yaw
        self.v = self.w = 0.0
        self.blocked = False
        self.forced_velocity: Optional[tuple] = None
        self.odom_every = 1
        self._steps = 0
        self.traveled_m = 0.0
        harness.robot = self
        self.publish()

    def command(self) -> tuple:
        pub = self.harness.proxies.publishers.get(self.cmd_topic)
        msg: Optional[TwistStamped] = pub.last() if pub is not None else None
        if msg is None:
            return 0.0, 0.0
        return msg.twist.linear.x, msg.twist.angular.z

    def step(self, dt_s: float) -> None:
        if self.forced_velocity is not None:
            self.v, self.w = self.forced_velocity
        elif self.blocked:
            self.v = self.w = 0.0
        else:
            self.v, self.w = self.command()
        self.x += self.v * math.cos(self.yaw) * dt_s
        self.y += self.v * math.sin(self.yaw) * dt_s
        self.yaw = math.atan2(math.sin(self.yaw + self.w * dt_s), math.cos(self.yaw + self.w * dt_s))
        self.traveled_m += abs(self.v) * dt_s
        self._steps += 1
        if self.odom_every and self._steps % self.odom_every == 0:
            self.publish()

    def publish(self) -> None:
        self.odom.inject(odometry(self.x, self.y, self.yaw, self.v, self.w, self.harness.clock.now(), self.frame))


def odometry(x: float, y: float, yaw: float, v: float, w: float, stamp_s: float, frame: str = "odom") -> Odometry:
    msg = Odometry()
    msg.header.stamp = genpy.Time.from_sec(stamp_s)
    msg.header.frame_id = frame
    msg.child_frame_id = "base_footprint"
    msg.pose.pose.position.x, msg.pose.pose.position.y = x, y
    qx, qy, qz, qw = quaternion_of_yaw(yaw)
    o = msg.pose.pose.orientation
    o.x, o.y, o.z, o.w = qx, qy, qz, qw
    msg.twist.twist.linear.x = v
    msg.twist.twist.angular.z = w
    return msg


def pose_stamped(x: float, y: float, yaw: float = 0.0, stamp_s: float = 0.0, frame: str = "map") -> PoseStamped:
    msg = PoseStamped()
    msg.header.stamp = genpy.Time.from_sec(stamp_s)
    msg.header.frame_id = frame
    msg.pose.position.x, msg.pose.position.y = x, y
    qx, qy, qz, qw = quaternion_of_yaw(yaw)
    o = msg.pose.orientation
    o.x, o.y, o.z, o.w = qx, qy, qz, qw
    return msg


def path(points: List[tuple], frame: str = "map", stamp_s: float = START_S) -> Path:
    """A nav_msgs/Path through (x, y) points, each pose facing the next point."""
    msg = Path()
    msg.header.frame_id = frame
    msg.header.stamp = genpy.Time.from_sec(stamp_s)
    for i, (x, y) in enumerate(points):
        nx, ny = points[min(i + 1, len(points) - 1)]
        px, py = points[max(i - 1, 0)]
        yaw = math.atan2(ny - y, nx - x) if i + 1 < len(points) else math.atan2(y - py, x - px)
        msg.poses.append(pose_stamped(x, y, yaw, stamp_s, frame))
    return msg


def wall_scan(stamp_s: float, robot_x: float, wall_x: Optional[float] = None) -> LaserScan:
    """A 360-beam scan from a robot at ``robot_x`` facing +x: a wall across the world at x = ``wall_x`` (behind
    or ahead of it), or nothing at all (None)."""
    scan = LaserScan()
    scan.header.stamp = genpy.Time.from_sec(stamp_s)
    scan.angle_min, scan.angle_increment = -math.pi, 2.0 * math.pi / 360
    scan.range_min, scan.range_max = 0.1, 12.0
    cosines = [math.cos(scan.angle_min + i * scan.angle_increment) for i in range(360)]
    gap = wall_x - robot_x if wall_x is not None else 0.0  # [m] signed, along +x
    scan.ranges = [gap / c if wall_x is not None and abs(c) > 1e-6 and gap / c > 0.0 else math.inf for c in cosines]
    return scan


def passage_scan(stamp_s: float, robot_x: float, end_x: float, half_width_m: float = 0.6) -> LaserScan:
    """A 360-beam scan from a robot at ``robot_x`` facing +x on the centre line of a passage: walls at y =
    +-``half_width_m`` from far behind to x = ``end_x``, open beyond."""
    scan = wall_scan(stamp_s, robot_x)
    ranges = []
    for i in range(360):
        angle = scan.angle_min + i * scan.angle_increment
        s = math.sin(angle)
        r = half_width_m / abs(s) if abs(s) > 1e-6 else math.inf
        ranges.append(r if robot_x + r * math.cos(angle) <= end_x else math.inf)
    scan.ranges = ranges
    return scan


def twists(harness: Harness, topic: str = "cmd_vel_stamped") -> List[tuple]:
    """(v, w) of every twist published on ``topic``."""
    return [(m.twist.linear.x, m.twist.angular.z) for m in harness.proxies.pub(topic).messages]
