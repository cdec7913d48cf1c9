"""Moving-obstacle tracking and the yield rule inside a controller node (ROS wiring only).

Built by ``pure_pursuit_path`` / ``pure_pursuit_topic`` when ``~yield_to_people`` is true. Subscribes the
scan (``~people_tracker/scan_topic``, "scan") and, unless ``~people_tracker/map_topic`` is "", the static map
(latched OccupancyGrid, "map"): scan points within ``~people_tracker/static_tolerance`` [m] (0.15) of a mapped
obstacle are not tracked. Scan points are carried by tf, at the scan's stamp, into the tracking frame
(``~people_tracker/tracking_frame``; "", the default, is the controller's global frame) and tracked there by
:class:`flex_nav.perception.moving_obstacles.MovingObstacleTracker` (its parameters by name under
``~people_tracker/``). The launch files name the robot's odometry frame: a localizer corrects ``map -> odom`` by
a centimetre or two at every scan, which in the global frame would look like 0.1-0.2 m/s of motion of
everything the scan sees; the static mask and the tracks handed to the controller are carried into the global
frame (the newest transform). The yield rule's parameters are :class:`flex_nav.nav.control.yielding.YieldParams`
by name under ``~yielding/``; ``robot_radius_m`` defaults to the local costmap's inscribed radius and
``speed_mps`` to pure pursuit's ``desired_linear_vel``. Publishes std_msgs/Bool ``~yielding``: True on every
control tick spent giving way, False once when that ends (for a progress monitor, see ``StuckMonitorState``), and,
when someone listens (the operator console's map), geometry_msgs/PoseArray ``~people``: the confirmed tracks at
each scan's stamp in the tracking frame, each facing its direction of motion. Unless
``~people_tracker/drop_boxes`` is false, a track standing on a cluster of the newest scan whose outline is a box's
(:func:`flex_nav.perception.lidar_shape.without_boxes`) is no person: neither handed to the controller nor shown.
Service ``~people_tracker/forget`` (flex_nav/ForgetTracks): forget every track and learnt walker lane and take no
scan stamped before the time given (so a run of a scripted world does not depend on when the node came up).
"""

from __future__ import annotations

import dataclasses
import math
import threading
from typing import List, Optional, Tuple

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import Pose, PoseArray, TransformStamped
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan as LaserScanMsg
from std_msgs.msg import Bool

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.nav.control.checked_yield import CheckedYield
from flex_nav.nav.control.social_distance import SocialDistanceRule, SocialLimit, SocialParams
from flex_nav.nav.control.space_time_yield import SpaceTimeYield
from flex_nav.nav.control.yielding import YieldDecision, YieldMode, YieldParams, YieldRule
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.perception.lidar_shape import BoxOutline, ShapeParams, box_outlines, without_boxes
from flex_nav.perception.moving_obstacles import MovingObstacleTracker, Track, TrackerParams
from flex_nav.perception.static_mask import StaticMask
from flex_nav.perception.walker_lanes import WalkerLanes
from flex_nav.ros.conversions import grid_map_of
from flex_nav.ros.frames import TF_ERRORS, lookup_bounded
from flex_nav.ros.latest_worker import LatestWorker
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.params import param_bool, param_float, param_str, reject_unknown
from flex_nav.ros.private_ns import private_name, private_namespace
from flex_nav.srv import ForgetTracks, ForgetTracksRequest, ForgetTracksResponse

TRACKER_NS = "~people_tracker/"
YIELD_NS = "~yielding"
TRACKER_FIELDS = tuple(f.name for f in dataclasses.fields(TrackerParams))
TRACKER_PARAMETERS = ("scan_topic", "map_topic", "static_tolerance", "tracking_frame", "drop_boxes", *TRACKER_FIELDS)
TF_WAIT_S = 0.1  # [s] wait for the scan's transform
LOCKSTEP_TF_WAIT_S = 1.0  # [s] lockstep: wait for the global frame's transform at a scan's stamp (_global_at)
STALE_GLOBAL_S = 1.0  # [s] a newest global-frame transform this much older than a scan is not waited on
MOVING_GAP_EXTRA_M = 0.1  # [m] the space-time planner keeps the social distance plus this (the predictions' error)
# [m] the checked rules' check keeps the social distance plus this while moving (issue 28, S6 and h6 seeds 0-4:
# 0.3 let h6 come within -0.03 m, 0.37 and 0.4 left S6 seed 0 or 1 unreached in 150 s; 0.35 kept >= 0.31 m in all)
CHECK_GAP_EXTRA_M = 0.05


def _carried(pose: Tuple[float, float, float], xs: np.ndarray, ys: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Points (xs, ys) [m] given in a frame whose pose is ``pose`` (x, y, yaw), in that pose's parent frame."""
    x, y, yaw = pose
    c, s = math.cos(yaw), math.sin(yaw)
    return x + c * xs - s * ys, y + s * xs + c * ys


def _planar_of(tf: TransformStamped) -> Tuple[float, float, float]:
    """(x [m], y [m], yaw [rad]) of a transform."""
    t, q = tf.transform.translation, tf.transform.rotation
    return (t.x, t.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))


def yield_rule(robot_radius_m: float, speed_mps: float, social: Optional[SocialDistanceRule] = None) -> YieldRule:
    """The YieldRule from ``~yielding/`` (defaults for the robot's radius and speed as given; with a ``social``
    distance rule, ``comfort_margin_m`` defaults to its ``min_distance_m``: a walker's way the robot would cross
    with less room is hurried across when that keeps it, the space-time planner's ``moving_gap_m`` to it plus
    ``MOVING_GAP_EXTRA_M`` and the checked rules' ``check_moving_gap_m`` to it plus ``CHECK_GAP_EXTRA_M``)."""
    raw = rospy.get_param(private_name(YIELD_NS), {})
    if not isinstance(raw, dict):
        raise ConfigError(
            f"parameter {rospy.resolve_name(private_name(YIELD_NS))} must be a dictionary, got {raw!r}")
    values = {"robot_radius_m": robot_radius_m, "speed_mps": speed_mps, **raw}
    if social is not None:
        values.setdefault("comfort_margin_m", social.params.min_distance_m)
        values.setdefault("moving_gap_m", social.params.min_distance_m + MOVING_GAP_EXTRA_M)
        values.setdefault("check_moving_gap_m", social.params.min_distance_m + CHECK_GAP_EXTRA_M)
    try:
        params = YieldParams.from_mapping(values)
        if params.planner == "checked":
            return CheckedYield(params)
        return SpaceTimeYield(params) if params.planner == "space_time" else YieldRule(params)
    except (ConfigError, TypeError) as err:
        raise ConfigError(f"{rospy.resolve_name(private_name(YIELD_NS))}: {err}") from err


SOCIAL_NS = "~social_distance"


def social_rule() -> Optional[SocialDistanceRule]:
    """The SocialDistanceRule from ``~social_distance/``: ``enabled`` (false) and the fields of
    :class:`~flex_nav.nav.control.social_distance.SocialParams` by name; None when not enabled."""
    name = rospy.resolve_name(private_name(SOCIAL_NS))
    raw = rospy.get_param(private_name(SOCIAL_NS), {})
    if not isinstance(raw, dict):
        raise ConfigError(f"parameter {name} must be a dictionary, got {raw!r}")
    values = dict(raw)
    enabled = values.pop("enabled", False)
    if not isinstance(enabled, bool):
        raise ConfigError(f"parameter {name}/enabled = {enabled!r} is not true/false")
    valid = [f.name for f in dataclasses.fields(SocialParams)]
    for key in values:
        if key not in valid:
            raise ConfigError(choices_message(f"parameter {name}: name", key, ["enabled", *valid]))
    try:
        rule = SocialDistanceRule(SocialParams(**{k: float(v) for k, v in values.items()}))
    except (ConfigError, TypeError, ValueError) as err:
        raise ConfigError(f"{name}: {err}") from err
    return rule if enabled else None


def people_message(tracks: List[Track], frame: str, stamp: rospy.Time) -> PoseArray:
    """The tracks as a PoseArray in ``frame``: each at its centre, facing its velocity (yaw 0 when standing)."""
    msg = PoseArray()
    msg.header.frame_id, msg.header.stamp = frame, stamp
    for track in tracks:
        pose = Pose()
        pose.position.x, pose.position.y = track.x, track.y
        yaw = math.atan2(track.vy, track.vx) if track.speed > 0.0 else 0.0
        pose.orientation.z, pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
        msg.poses.append(pose)
    return msg


class MovingObstaclesROS:
    """Scan (+ map) -> tracks in ``global_frame``; :meth:`tracks` is safe to call from the control loop."""

    def __init__(self, tf_buffer: tf2_ros.Buffer, global_frame: str) -> None:
        reject_unknown(TRACKER_NS, TRACKER_PARAMETERS)
        self.name = private_namespace()  # the owning controller's name, for its log lines
        self.tf_buffer = tf_buffer
        self.global_frame = global_frame
        self.tracking_frame = param_str(TRACKER_NS + "tracking_frame", "").lstrip("/") or global_frame.lstrip("/")
        self.static_mask: Optional[StaticMask] = None  # in the global frame
        self.static_tolerance_m = param_float(TRACKER_NS + "static_tolerance", 0.15, 0.0, 5.0)
        self.drop_boxes = param_bool(TRACKER_NS + "drop_boxes", True)
        self.shape_params = ShapeParams()
        self._boxes: List[BoxOutline] = []  # the newest scan's box outlines (tracking frame)
        raw = {name: rospy.get_param(private_name(TRACKER_NS + name)) for name in TRACKER_FIELDS
               if rospy.has_param(private_name(TRACKER_NS + name))}
        try:
            params = TrackerParams(**raw)
        except (ConfigError, TypeError) as err:
            raise ConfigError(f"{rospy.resolve_name(private_name(TRACKER_NS))}: {err}") from err
        self.lock = threading.Lock()
        self.tracker = MovingObstacleTracker(params)
        self._forget_before_s = -math.inf  # [s] scans stamped before this are not taken (~people_tracker/forget)
        self._last_kind: Optional[Tuple[YieldMode, Optional[int]]] = None  # (mode, track) last logged
        self._last_social: Optional[int] = None  # the track the social distance limited the last tick for
        # the walkers' lanes a space-time yield rule predicts with (:meth:`share_lanes`), in the global frame
        self.lanes: Optional[WalkerLanes] = None
        self.yielding_publisher = rospy.Publisher(private_name("~yielding"), Bool, queue_size=1)
        self.people_publisher = rospy.Publisher(private_name("~people"), PoseArray, queue_size=1)
        scan_topic = param_str(TRACKER_NS + "scan_topic", "scan")
        map_topic = param_str(TRACKER_NS + "map_topic", "map")
        self.scan_worker: LatestWorker[LaserScanMsg] = LatestWorker(self._on_scan, "people tracker scans")
        tracker_scans = LockstepParticipant("people_tracker/scan")
        self.in_lockstep = tracker_scans.enabled
        self._subscribers = [self.scan_worker.subscribe(scan_topic, LaserScanMsg, tracker_scans)]
        if map_topic:
            self._subscribers.append(rospy.Subscriber(map_topic, OccupancyGrid, self._on_map, queue_size=1))
        self.forget_service = rospy.Service(private_name(TRACKER_NS + "forget"), ForgetTracks, self._on_forget)

    def share_lanes(self, rule: YieldRule) -> None:
        """Learn the lanes ``rule`` predicts with (a :class:`SpaceTimeYield` or :class:`CheckedYield` with lanes)
        from every scan's tracks, and not only while the rule decides (during goals)."""
        if isinstance(rule, (SpaceTimeYield, CheckedYield)) and rule.lanes is not None:
            self.lanes = rule.lanes
            rule.learns_in_decide = False

    def _on_forget(self, request: ForgetTracksRequest) -> ForgetTracksResponse:
        before_s = request.before.to_sec() if not request.before.is_zero() else rospy.get_time()
        if not math.isfinite(before_s):
            return ForgetTracksResponse(ok=False, message=f"before {before_s!r} s: not a finite time")
        with self.lock:
            forgotten = len(self.tracker.tracks(before_s))
            self.tracker = MovingObstacleTracker(self.tracker.params)  # track ids start again at 1
            self._boxes = []
            self._forget_before_s = before_s
            if self.lanes is not None:
                self.lanes.clear()
        message = f"forgot {forgotten} tracks; scans stamped before {before_s:.3f} s are not taken"
        rospy.loginfo(f"{self.name}: people tracker: {message}")
        return ForgetTracksResponse(ok=True, message=message)

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
            self.static_mask = mask

    def _on_scan(self, msg: LaserScanMsg) -> None:
        try:
            laser = self._planar(self.tracking_frame, msg.header.frame_id, msg.header.stamp)
            to_global = self._global_at(msg.header.stamp)
        except TF_ERRORS as err:
            rospy.logwarn_throttle(5.0, f"people tracker: scan ignored: no transform {self.global_frame} -> "
                                        f"{self.tracking_frame} -> {msg.header.frame_id}: {err}")
            return
        lx, ly, lyaw = laser
        ranges = np.asarray(msg.ranges, dtype=np.float64)
        angles = lyaw + msg.angle_min + msg.angle_increment * np.arange(ranges.size)
        with np.errstate(invalid="ignore"):
            hit = (ranges >= msg.range_min) & (ranges < msg.range_max)
        dist = np.where(hit, ranges, np.nan)
        xs = lx + dist * np.cos(angles)
        ys = ly + dist * np.sin(angles)
        full_circle = abs(msg.angle_increment) * (ranges.size + 1) >= 2.0 * np.pi - 1e-6
        with self.lock:
            mask = self.static_mask
        if mask is not None and xs.size:  # a dropped point is a gap (NaN): the beam order is kept
            gx, gy = _carried(to_global, xs, ys)
            keep = ~mask.explained(gx, gy)
            xs, ys = np.where(keep, xs, np.nan), np.where(keep, ys, np.nan)
        boxes = box_outlines(xs, ys, (lx, ly), self.shape_params, wrap=bool(full_circle)) if self.drop_boxes else []
        stamp_s = msg.header.stamp.to_sec()
        listened = self.people_publisher.get_num_connections() > 0
        with self.lock:
            if stamp_s < self._forget_before_s:
                return
            self.tracker.update_scan(xs, ys, (lx, ly), stamp_s, wrap=bool(full_circle))
            self._boxes = boxes
            people = self._people(stamp_s) if listened or self.lanes is not None else []
            if self.lanes is not None:  # learnt from every scan (also between goals) as the tracker sees it then
                self.lanes.update(stamp_s, self._carried_tracks(people, to_global))
        if listened:
            self.people_publisher.publish(people_message(people, self.tracking_frame, msg.header.stamp))

    def _global_at(self, stamp: rospy.Time) -> Tuple[float, float, float]:
        """The tracking frame in the global frame for a scan stamped ``stamp``: it drops the points the static map
        explains (within static_tolerance) and carries the tracks the lanes learn from. The newest transform, or,
        in lockstep, the one at the stamp: a localizer publishes ``map -> odom`` for a scan while this thread
        handles the same scan, so the newest would be the one before or after it as the threads happen to run
        (runs of one seed parted by 0.1 mm in a lane within 2 s). The wait for it is bounded, and skipped when the
        newest is older than STALE_GLOBAL_S (a lost localizer); waiting for it on a real robot would lose every
        scan the localizer is late for."""
        target, source = self.global_frame.lstrip("/"), self.tracking_frame
        if target == source:
            return (0.0, 0.0, 0.0)
        newest = lookup_bounded(self.tf_buffer, target, source, rospy.Time(0), 0.0)
        age_s = (stamp - newest.header.stamp).to_sec()
        if self.in_lockstep and not newest.header.stamp.is_zero() and age_s <= STALE_GLOBAL_S:
            try:
                return _planar_of(lookup_bounded(self.tf_buffer, target, source, stamp, LOCKSTEP_TF_WAIT_S))
            except TF_ERRORS:
                pass  # (late beyond the bound: the newest, as without lockstep)
        return _planar_of(newest)

    def _planar(self, target: str, source: str, stamp: rospy.Time) -> Tuple[float, float, float]:
        if target == source.lstrip("/"):
            return (0.0, 0.0, 0.0)
        return _planar_of(lookup_bounded(self.tf_buffer, target, source, stamp, TF_WAIT_S))

    def report(self, yielded: Optional[YieldDecision], social: Optional[SocialLimit] = None) -> None:
        """One control tick's yield decision (None: not giving way): ``~yielding`` True while giving way (every
        tick, so it goes stale when the controller stops), False once when it ends; a log line when it starts,
        ends or changes mode or track. ``social``: the social distance rule's limit of the tick (None: it did not
        slow the command): a log line when the person it slows the robot for changes."""
        limited_by = social.limited_by if social is not None else None
        if limited_by != self._last_social:
            if social is not None and limited_by is not None:
                rospy.loginfo(f"{self.name}: social distance: {social.reason} (command x{social.scale:.2f})")
            else:
                rospy.loginfo(f"{self.name}: social distance: no longer limiting")
            self._last_social = limited_by
        kind = (yielded.mode, yielded.track_id) if yielded is not None else None
        if yielded is not None or self._last_kind is not None:
            self.yielding_publisher.publish(Bool(data=yielded is not None))
        if kind != self._last_kind:
            if yielded is not None:
                rospy.loginfo(f"{self.name}: {yielded.reason}")
            else:
                rospy.loginfo(f"{self.name}: yielding ended")
            self._last_kind = kind

    def _people(self, now_s: float) -> List[Track]:
        """The tracker's tracks at ``now_s`` [s] less those standing on a box outline (tracking frame; under the
        lock)."""
        return without_boxes(self.tracker.tracks(now_s), self._boxes, self.shape_params.moving_speed_mps)

    def tracks(self) -> List[Track]:
        """The confirmed tracks predicted to now (``rospy.get_time()``), in the global frame (none while the newest
        transform from the tracking frame is missing)."""
        now = rospy.get_time()
        with self.lock:
            tracks = self._people(now)
        if not tracks or self.tracking_frame == self.global_frame.lstrip("/"):
            return tracks
        try:
            to_global = self._planar(self.global_frame, self.tracking_frame, rospy.Time(0))
        except TF_ERRORS:
            return []
        return self._carried_tracks(tracks, to_global)

    @staticmethod
    def _carried_tracks(tracks: List[Track], pose: Tuple[float, float, float]) -> List[Track]:
        """``tracks`` carried by the planar transform ``pose`` (x [m], y [m], yaw [rad]) of their frame."""
        if pose == (0.0, 0.0, 0.0) or not tracks:
            return tracks
        xs, ys = _carried(pose, np.array([t.x for t in tracks]), np.array([t.y for t in tracks]))
        vxs, vys = _carried((0.0, 0.0, pose[2]), np.array([t.vx for t in tracks]), np.array([t.vy for t in tracks]))
        return [dataclasses.replace(t, x=float(x), y=float(y), vx=float(vx), vy=float(vy))
                for t, x, y, vx, vy in zip(tracks, xs, ys, vxs, vys)]
