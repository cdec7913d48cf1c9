"""Moving-obstacle tracking and the yield rule inside a controller node (ROS wiring only).

Built by ``pure_pursuit_path`` / ``pure_pursuit_topic`` when ``~yield_to_people`` is true. Subscribes the
scan (``~people_tracker/scan_topic``, "scan") and, unless ``~people_tracker/map_topic`` is "", the static map
(latched OccupancyGrid, "map"): scan points within ``~people_tracker/static_tolerance`` [m] (0.15) of a mapped
obstacle are not tracked. Scan points are carried into the controller's global frame by tf at the scan's
stamp, then tracked by :class:`flex_nav.perception.moving_obstacles.MovingObstacleTracker` (its parameters by
name under ``~people_tracker/``). The yield rule's parameters are :class:`flex_nav.nav.control.yielding.YieldParams`
by name under ``~yielding/``; ``robot_radius_m`` defaults to the local costmap's inscribed radius and
``speed_mps`` to pure pursuit's ``desired_linear_vel``. Publishes std_msgs/Bool ``~yielding``: True on every
control tick spent giving way, False once when that ends (for a progress monitor, see ``StuckMonitorState``).
"""

from __future__ import annotations

import dataclasses
import threading
from typing import List, Optional, Tuple

import numpy as np
import rospy
import tf2_ros
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan as LaserScanMsg
from std_msgs.msg import Bool

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.yielding import YieldDecision, YieldMode, YieldParams, YieldRule
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.perception.moving_obstacles import MovingObstacleTracker, Track, TrackerParams
from flex_nav.perception.static_mask import StaticMask
from flex_nav.ros.conversions import grid_map_of
from flex_nav.ros.params import param_float, param_str, reject_unknown

TRACKER_NS = "~people_tracker/"
YIELD_NS = "~yielding"
TRACKER_FIELDS = tuple(f.name for f in dataclasses.fields(TrackerParams))
TRACKER_PARAMETERS = ("scan_topic", "map_topic", "static_tolerance", *TRACKER_FIELDS)
TF_WAIT_S = 0.1  # [s] wait for the scan's transform


def yield_rule(robot_radius_m: float, speed_mps: float) -> YieldRule:
    """The YieldRule from ``~yielding/`` (defaults for the robot's radius and speed as given)."""
    raw = rospy.get_param(YIELD_NS, {})
    if not isinstance(raw, dict):
        raise ConfigError(f"parameter {rospy.resolve_name(YIELD_NS)} must be a dictionary, got {raw!r}")
    values = {"robot_radius_m": robot_radius_m, "speed_mps": speed_mps, **raw}
    try:
        return YieldRule(YieldParams.from_mapping(values))
    except (ConfigError, TypeError) as err:
        raise ConfigError(f"{rospy.resolve_name(YIELD_NS)}: {err}") from err


class MovingObstaclesROS:
    """Scan (+ map) -> tracks in ``global_frame``; :meth:`tracks` is safe to call from the control loop."""

    def __init__(self, tf_buffer: tf2_ros.Buffer, global_frame: str) -> None:
        reject_unknown(TRACKER_NS, TRACKER_PARAMETERS)
        self.tf_buffer = tf_buffer
        self.global_frame = global_frame
        self.static_tolerance_m = param_float(TRACKER_NS + "static_tolerance", 0.15, 0.0, 5.0)
        raw = {name: rospy.get_param(TRACKER_NS + name) for name in TRACKER_FIELDS
               if rospy.has_param(TRACKER_NS + name)}
        try:
            params = TrackerParams(**raw)
        except (ConfigError, TypeError) as err:
            raise ConfigError(f"{rospy.resolve_name(TRACKER_NS)}: {err}") from err
        self.lock = threading.Lock()
        self.tracker = MovingObstacleTracker(params)
        self._last_kind: Optional[Tuple[YieldMode, Optional[int]]] = None  # (mode, track) last logged
        self.yielding_publisher = rospy.Publisher("~yielding", Bool, queue_size=1)
        scan_topic = param_str(TRACKER_NS + "scan_topic", "scan")
        map_topic = param_str(TRACKER_NS + "map_topic", "map")
        self._subscribers = [rospy.Subscriber(scan_topic, LaserScanMsg, self._on_scan, queue_size=1)]
        if map_topic:
            self._subscribers.append(rospy.Subscriber(map_topic, OccupancyGrid, self._on_map, queue_size=1))

    def _on_map(self, msg: OccupancyGrid) -> None:
        if msg.header.frame_id.lstrip("/") not in ("", self.global_frame.lstrip("/")):
            rospy.logwarn_throttle(10.0, f"people tracker: map in frame {msg.header.frame_id!r}, not "
                                         f"{self.global_frame!r}: not used to drop static points")
            return
        try:
            mask = StaticMask(grid_map_of(msg), self.static_tolerance_m)
        except ConfigError as err:
            rospy.logwarn(f"people tracker: map ignored: {err}")
            return
        with self.lock:
            self.tracker.static_mask = mask

    def _on_scan(self, msg: LaserScanMsg) -> None:
        try:
            tf = self.tf_buffer.lookup_transform(self.global_frame, msg.header.frame_id, msg.header.stamp,
                                                 rospy.Duration(TF_WAIT_S))
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException) as err:
            rospy.logwarn_throttle(5.0, f"people tracker: scan ignored: no transform {self.global_frame} -> "
                                        f"{msg.header.frame_id}: {err}")
            return
        t, q = tf.transform.translation, tf.transform.rotation
        yaw = yaw_of_quaternion(q.x, q.y, q.z, q.w)
        ranges = np.asarray(msg.ranges, dtype=np.float64)
        angles = yaw + msg.angle_min + msg.angle_increment * np.arange(ranges.size)
        with np.errstate(invalid="ignore"):
            hit = (ranges >= msg.range_min) & (ranges < msg.range_max)
        dist = np.where(hit, ranges, np.nan)
        xs = t.x + dist * np.cos(angles)
        ys = t.y + dist * np.sin(angles)
        full_circle = abs(msg.angle_increment) * (ranges.size + 1) >= 2.0 * np.pi - 1e-6
        with self.lock:
            self.tracker.update_scan(xs, ys, (t.x, t.y), msg.header.stamp.to_sec(), wrap=bool(full_circle))

    def report(self, yielded: Optional[YieldDecision]) -> None:
        """One control tick's yield decision (None: not giving way): ``~yielding`` True while giving way (every
        tick, so it goes stale when the controller stops), False once when it ends; a log line when it starts,
        ends or changes mode or track."""
        kind = (yielded.mode, yielded.track_id) if yielded is not None else None
        if yielded is not None or self._last_kind is not None:
            self.yielding_publisher.publish(Bool(data=yielded is not None))
        if kind != self._last_kind:
            if yielded is not None:
                rospy.loginfo(f"{rospy.get_name()}: {yielded.reason}")
            else:
                rospy.loginfo(f"{rospy.get_name()}: yielding ended")
            self._last_kind = kind

    def tracks(self) -> List[Track]:
        """The confirmed tracks predicted to now (``rospy.get_time()``)."""
        now = rospy.get_time()
        with self.lock:
            return self.tracker.tracks(now)
