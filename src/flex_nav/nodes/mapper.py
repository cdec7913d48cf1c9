"""``mapper`` node: 2D lidar graph SLAM with slam_toolbox's and gmapping's ROS interface.

``rosrun flex_nav mapper`` (in the robot's namespace; every name below is relative). The mapping is
:class:`flex_nav.mapping.slam.GraphSlam`; this node only converts messages and transforms.

Subscribes ``scan`` (sensor_msgs/LaserScan); the odometry comes from tf (``odom_frame`` -> ``base_frame`` at
the scan's stamp). Publishes ``map`` (nav_msgs/OccupancyGrid, latched, every ``map_update_interval`` [s] when it
changed), ``map_metadata`` (nav_msgs/MapMetaData, latched), ``pose`` (geometry_msgs/PoseWithCovarianceStamped,
the robot in the map frame at every scan used, as slam_toolbox's), tf ``map_frame`` -> ``odom_frame`` every
``transform_publish_period`` [s], post-dated by ``transform_tolerance`` [s], and ``~status`` (std_msgs/String,
latched: keyframes, loop closures). Services: ``dynamic_map`` (nav_msgs/GetMap), ``~save_map``
(flex_nav/MapFile: a map_server pair ``<path>.yaml`` + ``<path>.pgm``), ``~serialize_map`` (flex_nav/MapFile:
the pose graph with its scans as ``<path>.posegraph``, JSON) and ``~deserialize_map`` (flex_nav/MapFile: that
file; mapping goes on from it with the robot where the mapping stopped, within ``loop_search_space_dimension``).

Private parameters: the mapper's (:class:`flex_nav.mapping.slam.SlamParams`, slam_toolbox's names:
``minimum_travel_distance`` [m], ``minimum_travel_heading`` [rad], ``scan_buffer_size``,
``scan_buffer_maximum_scan_distance`` [m], ``correlation_search_space_dimension`` [m],
``coarse_search_angle_offset`` [rad], ``link_match_minimum_response_fine``, ``do_loop_closing``,
``loop_search_maximum_distance`` [m], ``loop_match_minimum_chain_size``, ``loop_search_space_dimension`` [m],
``loop_match_minimum_response_fine``, and flex_nav's ``odometry_sigma_per_meter``, ``odometry_sigma_yaw_per_radian``,
``loop_minimum_travel`` [m], ``loop_match_uniqueness_radius`` [m], ``loop_match_uniqueness_ratio``,
``loop_match_agreement_distance`` [m], ``loop_closure_cooldown``) and
  ~map_frame  str  map       ~odom_frame  str  odom       ~base_frame  str  base_footprint
  ~resolution           float  0.05 [m]   cell size of the map
  ~max_laser_range      float  5.0 [m]    a beam that saw nothing clears the map this far at most
  ~map_update_interval  float  2.0 [s]    how often the map is rebuilt and published
  ~transform_publish_period float 0.05 [s]  how often map -> odom is published (0: with every scan only)
  ~transform_tolerance  float  0.1 [s]    post-dating of map -> odom
  ~transform_timeout    float  0.2 [s]    bound on waiting for the odometry and laser transforms
  ~max_odometry_jump    float  1.0 [m]    odometry moving further between two scans is a jump
  ~map_start_pose       [x, y, yaw]  unset  [m, m, rad] where the robot's first pose is in the map frame (unset: at
                        its odometry pose), as slam_toolbox's: e.g. a known start, so that maps of two runs line up

Bad input is logged (throttled) naming the field, and the graph is kept: beams that are NaN, -inf or out of
range are dropped (+inf and max-range readings clear free space); a scan in a frame tf cannot place or without
odometry at its stamp is skipped; odometry that jumps (``max_odometry_jump``) or a scan stamped before the
previous one restarts the odometry reference (the next scans are placed by matching alone); a save path that
cannot be written gets ``ok: false`` and the reason.
"""

from __future__ import annotations

import dataclasses
import json
import math
import threading
from pathlib import Path
from typing import List, Optional, Union

import rospy
import tf2_ros
from geometry_msgs.msg import PoseWithCovarianceStamped
from nav_msgs.msg import MapMetaData, OccupancyGrid
from nav_msgs.srv import GetMap, GetMapRequest, GetMapResponse
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.mapping.occupancy import OccupancyParams
from flex_nav.mapping.slam import GraphSlam, SlamParams
from flex_nav.nav.costmap.map_io import save_map
from flex_nav.nav.planar import Pose2D, compose_poses
from flex_nav.ros.conversions import map_msg, pose_of_xy_yaw
from flex_nav.ros.node import run_node
from flex_nav.ros.params import param_float, param_str, reject_unknown
from flex_nav.ros.scan_input import Complaints, ScanInput, invalid_beams, transform_msg
from flex_nav.srv import MapFile, MapFileRequest, MapFileResponse

NODE_NAME = "mapper"
SLAM_PARAMS = tuple(f.name for f in dataclasses.fields(SlamParams))
NODE_PARAMS = (
    "map_frame", "odom_frame", "base_frame", "resolution", "max_laser_range", "map_update_interval",
    "transform_publish_period", "transform_tolerance", "transform_timeout", "max_odometry_jump", "map_start_pose",
)
POSEGRAPH_SUFFIX = ".posegraph"
POSE_STD_XY = 0.05  # [m] the covariance published with ``pose`` (the map's scale of accuracy, not an estimate)
POSE_STD_YAW = 0.05  # [rad]


def slam_params_from_server() -> SlamParams:
    """SlamParams from the node's private parameters (defaults for the ones not set); ConfigError naming a bad one."""
    given = {name: rospy.get_param("~" + name) for name in SLAM_PARAMS if rospy.has_param("~" + name)}
    return validation.dataclass_from_mapping(SlamParams, given, owner=f"parameter {rospy.resolve_name('~')}")


class MapperNode:
    """Messages and transforms around one :class:`GraphSlam`; see the module docstring."""

    def __init__(self) -> None:
        reject_unknown("~", SLAM_PARAMS + NODE_PARAMS)
        self.params = slam_params_from_server()
        self.map_frame = param_str("~map_frame", "map").lstrip("/")
        self.odom_frame = param_str("~odom_frame", "odom").lstrip("/")
        self.base_frame = param_str("~base_frame", "base_footprint").lstrip("/")
        for name, frame in (("map_frame", self.map_frame), ("odom_frame", self.odom_frame),
                            ("base_frame", self.base_frame)):
            if not frame:
                raise ConfigError(f"parameter {rospy.resolve_name('~' + name)} must not be empty")
        self.occupancy = OccupancyParams(resolution=param_float("~resolution", 0.05, 0.005, 1.0),
                                         max_free_range=param_float("~max_laser_range", 5.0, 0.1, 100.0))
        self.map_update_interval = param_float("~map_update_interval", 2.0, 0.1, 3600.0)
        self.transform_period = param_float("~transform_publish_period", 0.05, 0.0, 10.0)
        self.tolerance = rospy.Duration.from_sec(param_float("~transform_tolerance", 0.1, 0.0, 10.0))
        timeout = rospy.Duration.from_sec(param_float("~transform_timeout", 0.2, 0.0, 10.0))
        self.max_jump = param_float("~max_odometry_jump", 1.0, 0.01, 100.0)

        self._lock = threading.Lock()
        start = rospy.get_param("~map_start_pose", None)
        try:
            self._slam = GraphSlam(self.params, self.occupancy, map_start_pose=start)
        except ConfigError as err:
            raise ConfigError(f"parameter {rospy.resolve_name('~map_start_pose')}: {err}") from err
        self._last_odom: Optional[Pose2D] = None
        self._last_stamp: Optional[rospy.Time] = None
        self._published_keyframes = -1  # keyframe count of the map last published
        self._published_closures = -1
        self._map_msg: Optional[OccupancyGrid] = None
        self._complain = Complaints(NODE_NAME)

        self.tf_buffer = tf2_ros.Buffer(cache_time=rospy.Duration(30.0))
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        self.tf_broadcaster = tf2_ros.TransformBroadcaster()
        self.scan_input = ScanInput(self.tf_buffer, self.odom_frame, self.base_frame, timeout, self._complain,
                                    laser_range=(-1.0, -1.0))
        self.pub_map = rospy.Publisher("map", OccupancyGrid, queue_size=1, latch=True)
        self.pub_metadata = rospy.Publisher("map_metadata", MapMetaData, queue_size=1, latch=True)
        self.pub_status = rospy.Publisher("~status", String, queue_size=2, latch=True)
        self.pub_pose = rospy.Publisher("pose", PoseWithCovarianceStamped, queue_size=2)
        self.pub_status.publish(String(data="waiting for the first scan"))
        self.services = [
            rospy.Service("dynamic_map", GetMap, self._on_dynamic_map),
            rospy.Service("~save_map", MapFile, self._on_save_map),
            rospy.Service("~serialize_map", MapFile, self._on_serialize_map),
            rospy.Service("~deserialize_map", MapFile, self._on_deserialize_map),
        ]
        self.timers = [rospy.Timer(rospy.Duration.from_sec(self.map_update_interval), self._on_map_timer)]
        if self.transform_period > 0.0:
            self.timers.append(rospy.Timer(rospy.Duration.from_sec(self.transform_period), self._on_tf_timer))
        self.sub_scan = rospy.Subscriber("scan", LaserScan, self._on_scan, queue_size=1, buff_size=2**20)
        rospy.loginfo("mapper: waiting for scans on %s (odometry %s -> %s)", self.sub_scan.resolved_name,
                      self.odom_frame, self.base_frame)

    # -- scans --------------------------------------------------------------------------------------------------
    def _on_scan(self, scan: LaserScan) -> None:
        laser_pose = self.scan_input.laser_pose(scan.header.frame_id)
        odom = self.scan_input.odom_pose(scan.header.stamp)
        if laser_pose is None or odom is None:
            return
        beams = self.scan_input.beams(scan, laser_pose)
        bad = invalid_beams(beams)
        if bad:
            self._complain("beams", f"scan: {bad} of {len(beams.ranges)} beams NaN, -inf or outside "
                                    f"[{beams.range_min:g}, {beams.range_max:g}] m: dropped")
        with self._lock:
            self._check_odometry(scan.header.stamp, odom)
            try:
                added = self._slam.add_scan(odom, beams, scan.header.stamp.to_sec())
            except ConfigError as err:
                self._complain("scan_bad", f"scan ignored: {err}")
                return
            if self._slam.reanchoring:
                self._complain("reanchor", "scan not placed: it does not fit the map where the mapping stopped "
                                           "(odometry restarted); drive back there, or the map stays as it is")
            if added:
                self._publish_transform(scan.header.stamp)
            first = added and len(self._slam.keyframes) == 1
            if self._slam.keyframes and not self._slam.reanchoring:
                self._publish_pose(scan.header.stamp, compose_poses(self._slam.map_to_odom(), odom))
        if first:  # a map at once, not a map_update_interval later: whoever waits for one can start
            self._publish_map()

    def _check_odometry(self, stamp: rospy.Time, odom: Pose2D) -> None:
        """(lock held) Restart the odometry reference when time went back or the odometry jumped."""
        if self._last_stamp is not None and stamp < self._last_stamp:
            self._complain("time_back", f"scan stamped {(self._last_stamp - stamp).to_sec():.2f} s before the "
                                        "previous one (time went back): odometry reference restarted", throttle=False)
            self._slam.restart_odometry()
        elif self._last_odom is not None:
            jump = math.hypot(odom[0] - self._last_odom[0], odom[1] - self._last_odom[1])
            if jump > self.max_jump:
                self._complain("jump", f"odometry jumped {jump:.2f} m between two scans (> ~max_odometry_jump "
                                       f"{self.max_jump:g} m): odometry reference restarted", throttle=False)
                self._slam.restart_odometry()
        self._last_stamp, self._last_odom = stamp, odom

    # -- outputs ------------------------------------------------------------------------------------------------
    def _publish_transform(self, stamp: rospy.Time) -> None:
        """(lock held) map -> odom, post-dated."""
        if not self._slam.keyframes:
            return
        self.tf_broadcaster.sendTransform(
            transform_msg(stamp + self.tolerance, self.map_frame, self.odom_frame, self._slam.map_to_odom()))

    def _publish_pose(self, stamp: rospy.Time, pose: Pose2D) -> None:
        msg = PoseWithCovarianceStamped()
        msg.header.stamp = stamp
        msg.header.frame_id = self.map_frame
        msg.pose.pose = pose_of_xy_yaw(*pose)
        covariance = [0.0] * 36
        covariance[0] = covariance[7] = POSE_STD_XY**2
        covariance[35] = POSE_STD_YAW**2
        msg.pose.covariance = covariance
        self.pub_pose.publish(msg)

    def _on_tf_timer(self, _event: rospy.timer.TimerEvent) -> None:
        with self._lock:
            self._publish_transform(rospy.Time.now())

    def _on_map_timer(self, _event: rospy.timer.TimerEvent) -> None:
        self._publish_map()

    def _publish_map(self) -> None:
        """Rebuild and publish the map if keyframes or loop closures came since it was last published."""
        with self._lock:
            count, closures = len(self._slam.keyframes), len(self._slam.loop_closures)
            if count == 0 or (count, closures) == (self._published_keyframes, self._published_closures):
                return
            grid = self._slam.occupancy_map()
            rejected = self._slam.rejected_loops
            reanchoring = self._slam.reanchoring
        msg = map_msg(grid, frame_id=self.map_frame, stamp=rospy.Time.now())
        self._map_msg = msg
        self.pub_metadata.publish(msg.info)
        self.pub_map.publish(msg)
        self._published_keyframes, self._published_closures = count, closures
        self.pub_status.publish(String(data=(
            f"mapping: {count} keyframes, {closures} loop closures ({rejected} candidates rejected), map "
            f"{grid.width}x{grid.height} cells" + ("; waiting to re-anchor" if reanchoring else ""))))

    # -- services -----------------------------------------------------------------------------------------------
    def _on_dynamic_map(self, _request: GetMapRequest) -> GetMapResponse:
        with self._lock:
            if not self._slam.keyframes:
                return GetMapResponse()  # map.info.width 0: nothing mapped yet
            grid = self._slam.occupancy_map()
        return GetMapResponse(map=map_msg(grid, frame_id=self.map_frame, stamp=rospy.Time.now()))

    def _on_save_map(self, request: MapFileRequest) -> MapFileResponse:
        path = _request_path(request)
        if isinstance(path, MapFileResponse):
            return path
        with self._lock:
            if not self._slam.keyframes:
                return MapFileResponse(ok=False, message="nothing mapped yet: no scan received")
            grid = self._slam.occupancy_map()
        yaml_path = path.with_name(path.name + ".yaml")
        try:
            image = save_map(grid, yaml_path)
        except (ConfigError, OSError) as err:
            rospy.logerr("mapper: save_map %s failed: %s", yaml_path, err)
            return MapFileResponse(ok=False, message=f"cannot write {yaml_path}: {err}")
        rospy.loginfo("mapper: map saved to %s and %s", yaml_path, image)
        return MapFileResponse(ok=True, message=f"wrote {yaml_path} and {image}")

    def _on_serialize_map(self, request: MapFileRequest) -> MapFileResponse:
        path = _request_path(request)
        if isinstance(path, MapFileResponse):
            return path
        with self._lock:
            data = self._slam.to_dict()
        target = path.with_name(path.name + POSEGRAPH_SUFFIX)
        try:
            target.write_text(json.dumps(data), encoding="utf-8")
        except OSError as err:
            rospy.logerr("mapper: serialize_map %s failed: %s", target, err)
            return MapFileResponse(ok=False, message=f"cannot write {target}: {err}")
        return MapFileResponse(ok=True, message=f"wrote {target} ({len(data['keyframes'])} keyframes)")

    def _on_deserialize_map(self, request: MapFileRequest) -> MapFileResponse:
        path = _request_path(request)
        if isinstance(path, MapFileResponse):
            return path
        source = path.with_name(path.name + POSEGRAPH_SUFFIX)
        try:
            data = json.loads(source.read_text(encoding="utf-8"))
            slam = GraphSlam.from_dict(data, self.params, self.occupancy)
        except (OSError, ValueError, ConfigError) as err:  # json.JSONDecodeError is a ValueError
            rospy.logerr("mapper: deserialize_map %s failed: %s", source, err)
            return MapFileResponse(ok=False, message=f"cannot read {source}: {err}; the current map is kept")
        slam.restart_odometry()
        with self._lock:
            self._slam = slam
            self._published_keyframes = -1
        rospy.loginfo("mapper: %d keyframes read from %s; mapping goes on where it stopped", len(slam.keyframes),
                      source)
        return MapFileResponse(ok=True, message=f"read {source} ({len(slam.keyframes)} keyframes)")


def _request_path(request: MapFileRequest) -> Union[Path, MapFileResponse]:
    """The path a MapFile request names (relative: from the working directory), or the refusal of an empty one or
    a folder."""
    text = request.path.strip()
    if not text or text.endswith("/"):
        return MapFileResponse(ok=False, message=f"path must name a file, without extension; got {request.path!r}")
    return Path(text).expanduser()


def main() -> int:
    return run_node(NODE_NAME, MapperNode)


__all__: List[str] = ["MapperNode", "main", "slam_params_from_server"]
