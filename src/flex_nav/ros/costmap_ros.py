"""A costmap owned by a node: parameters, sensor subscriptions, periodic update/publish, and clear_costmap.

Parameters (private, under ``~<name>/``; units in brackets):

- ``global_frame`` (str), ``robot_base_frame`` (str): default to the node's ``~global_frame`` ("map") and
  ``~robot_base_frame`` ("base_footprint"), so one pair of node parameters sets the frames of all its parts
- ``rolling_window`` (bool; the default is the owning node's: false for get_path's ``global_costmap``, true for
  the controllers' ``local_costmap`` and the follow servers'), ``width``/``height`` [m] (rolling window size,
  4.0), ``resolution`` [m/cell] (0.05; a static costmap takes the map's)
- ``static_map`` (bool; default: the owning node's, else not ``rolling_window`` — true for get_path and the
  follow servers, false for the controllers): static layer from ``map_topic`` (str, "map", latched
  OccupancyGrid)
- ``scan_topic`` (str, "scan"; "" for none), ``obstacle_range`` [m] (2.5), ``raytrace_range`` [m] (3.0)
- ``bumper_topic`` (str, "bumper_hits"; geometry_msgs/PointStamped contact points; "" for none) and
  ``bumper_memory`` [s] (60.0): contacts stay lethal this long, through lidar clearing and clear_costmap
- ``robot_radius`` [m] (inscribed radius, 0.18), ``inflation_radius`` [m] (0.5), ``cost_scaling_factor`` [1/m] (5.0)
- ``track_unknown_space`` (bool, false), ``update_frequency`` [Hz] (5.0), ``publish_frequency`` [Hz] (1.0; at
  most the update frequency: a publication follows an update on the same timer; 0: never)
- ``transform_tolerance`` [s] (0.5)

- ``obstacle_memory/enabled`` (bool, false; a static, not rolling, costmap only) and the fields of
  :class:`~flex_nav.nav.costmap.memory_layer.MemoryParams` (``memory_s`` [s] 600, ...): heavy obstacles the
  behavior found (geometry_msgs/PolygonStamped on ``obstacle_memory/mark``, placed by tf at its stamp) stay LETHAL
  until ``memory_s`` has passed, a scan sees through them, or the operator calls ``~<name>/clear_obstacle_memory``
  (std_srvs/Trigger); ClearCostmap keeps them. What is remembered is latched on ``~<name>/obstacle_memory``
  (visualization_msgs/MarkerArray of :func:`~flex_nav.ros.memory_markers.memory_markers`, in ``global_frame``) once
  the map has come and after every change (a mark, an expiry, a scan that saw one gone, the operator's clear, a new map)

Publishes the costmap as OccupancyGrid on ``~<name>/costmap``. The node serves ClearCostmap on
``<node>/clear_costmap`` (see :meth:`CostmapROS.serve_clear_costmap`). All access to the costmap goes through
:attr:`lock`.
"""

from __future__ import annotations

import dataclasses
import math
import threading
from typing import Optional, Tuple, Union

import actionlib
import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import PointStamped, PolygonStamped
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan as LaserScanMsg
from std_srvs.srv import Trigger, TriggerRequest, TriggerResponse
from visualization_msgs.msg import MarkerArray

from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.msg import ClearCostmapAction, ClearCostmapResult
from flex_nav.nav.costmap.costmap_grid import CostmapGeometry
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.costmap.inflation import InflationParams
from flex_nav.nav.costmap.layered import Costmap
from flex_nav.nav.costmap.memory_layer import MemoryParams
from flex_nav.nav.costmap.obstacle_layer import LaserScan, ObstacleLayerParams
from flex_nav.nav.planar import transform_poses
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.ros.conversions import grid_map_of, occupancy_grid_msg
from flex_nav.ros.frames import TF_ERRORS, lookup_bounded
from flex_nav.ros.latest_worker import LatestWorker
from flex_nav.ros.lockstep import LockstepParticipant, lockstep_enabled, server_accept_hold
from flex_nav.ros.memory_markers import memory_markers
from flex_nav.ros.params import param_bool, param_float, param_int, param_str, reject_unknown
from flex_nav.ros.private_ns import private_name
from flex_nav.ros.robot_pose import RobotPoseSource
from flex_nav.ros.ros_clock import LockstepTimer

MEMORY_MARK_TOPIC = "obstacle_memory/mark"  # heavy obstacles' footprints (states/remember_obstacle_state.py)
MEMORY_TOPIC = "obstacle_memory"  # ~<name>/obstacle_memory: what is remembered, as latched markers
MAP_WAIT_S = 30.0  # [s] default bound on waiting for the first map
TF_WAIT_S = 0.1  # [s] wait for the transform of a scan or a bumper hit at its stamp
PARAMETERS = (
    "global_frame", "robot_base_frame", "rolling_window", "static_map", "map_topic", "width", "height",
    "resolution", "scan_topic", "bumper_topic", "obstacle_range", "raytrace_range", "track_unknown_space",
    "robot_radius", "inflation_radius", "cost_scaling_factor", "update_frequency", "publish_frequency",
    "transform_tolerance", "bumper_memory", "obstacle_memory",
)  # the names under ~<name>/ (anything else is a ConfigError)


class CostmapROS:
    """One costmap with its ROS inputs and outputs; ``name`` is its parameter namespace (e.g. "global_costmap")."""

    _memory_shown: Optional[Tuple[Tuple[int, float, bytes], ...]] = None  # the remembered obstacles last published

    def __init__(
        self,
        name: str,
        tf_buffer: tf2_ros.Buffer,
        *,
        rolling_default: bool = False,
        static_default: Optional[bool] = None,
    ) -> None:
        """``rolling_default``/``static_default``: defaults of ``rolling_window`` and ``static_map`` (None: a
        static layer unless rolling), so each node picks the usual kind of costmap for its job."""
        ns = f"~{name}/"
        reject_unknown(ns, PARAMETERS)
        self.name = name
        self.lock = threading.RLock()
        self.tf_buffer = tf_buffer
        self.global_frame = param_str(ns + "global_frame", param_str("~global_frame", "map"))
        self.robot_base_frame = param_str(ns + "robot_base_frame", param_str("~robot_base_frame", "base_footprint"))
        self.rolling_window = param_bool(ns + "rolling_window", rolling_default)
        self.use_static_map = param_bool(
            ns + "static_map", (not self.rolling_window) if static_default is None else static_default
        )
        self.map_topic = param_str(ns + "map_topic", "map")
        self.width_m = param_float(ns + "width", 4.0, 0.1, 1000.0)
        self.height_m = param_float(ns + "height", 4.0, 0.1, 1000.0)
        self.resolution = param_float(ns + "resolution", 0.05, 0.001, 10.0)
        scan_topic = param_str(ns + "scan_topic", "scan")
        self.scan_topic = scan_topic
        bumper_topic = param_str(ns + "bumper_topic", "bumper_hits")
        self.obstacles = ObstacleLayerParams(
            obstacle_range=param_float(ns + "obstacle_range", 2.5, 0.0, 100.0),
            raytrace_range=param_float(ns + "raytrace_range", 3.0, 0.0, 100.0),
            track_unknown_space=param_bool(ns + "track_unknown_space", False),
        )
        self.inflation = InflationParams(
            inscribed_radius=param_float(ns + "robot_radius", 0.18, 0.0, 10.0),
            inflation_radius=param_float(ns + "inflation_radius", 0.5, 0.0, 10.0),
            cost_scaling_factor=param_float(ns + "cost_scaling_factor", 5.0, 0.0, 1000.0),
        )
        self.track_unknown_space = param_bool(ns + "track_unknown_space", False)
        update_hz = param_float(ns + "update_frequency", 5.0, 0.1, 100.0)
        publish_hz = param_float(ns + "publish_frequency", 1.0, 0.0, 100.0)
        self.bumper_memory_s = param_float(ns + "bumper_memory", 60.0, 0.1, 1e6)
        self.robot_pose = RobotPoseSource(
            tf_buffer, self.global_frame, self.robot_base_frame, param_float(ns + "transform_tolerance", 0.5, 0.0, 10.0)
        )
        self.memory = self._memory_params(ns)
        if not self.use_static_map and not self.rolling_window:
            raise ConfigError(
                f"{rospy.resolve_name(private_name(ns))}: a costmap needs static_map: true or rolling_window: true")

        self.costmap: Optional[Costmap] = None
        self.last_scan_time: Optional[rospy.Time] = None  # header stamp of the newest scan used
        self.last_scan_received_s: Optional[float] = None  # [s] rospy.get_time() when it was used
        self._map_received = threading.Event()
        if self.rolling_window:
            self.costmap = Costmap.rolling(
                self.width_m, self.height_m, self.resolution, obstacles=self.obstacles, inflation=self.inflation,
                track_unknown_space=self.track_unknown_space, bumper_memory_s=self.bumper_memory_s,
            )
        self.publisher = rospy.Publisher(private_name(f"~{name}/costmap"), OccupancyGrid, queue_size=1, latch=True)
        self._memory_publisher = (rospy.Publisher(private_name(f"~{name}/{MEMORY_TOPIC}"), MarkerArray, queue_size=2,
                                                  latch=True) if self.memory is not None else None)
        self._subscribers = []
        if self.use_static_map:
            self._subscribers.append(rospy.Subscriber(self.map_topic, OccupancyGrid, self._on_map, queue_size=1))
        if scan_topic:
            # scans are placed (tf at their stamp) and added on a thread of the costmap's own (see LatestWorker)
            self.scan_worker: LatestWorker[LaserScanMsg] = LatestWorker(self._on_scan, f"{name} scans")
            self._subscribers.append(self.scan_worker.subscribe(scan_topic, LaserScanMsg,
                                                                LockstepParticipant(f"{name}/scan")))
        if bumper_topic:
            self._subscribers.append(rospy.Subscriber(bumper_topic, PointStamped, self._on_bumper_hit, queue_size=10))
        # reset=True: a timer whose ROS time jumps back (a restarted simulator, a looped bag) goes on
        # one timer thread for updating and publishing: every thread sleeping on ROS time is woken by every
        # /clock message (rospy), a real cost when several components share a process
        self._publish_period_s = 1.0 / publish_hz if publish_hz > 0 else math.inf  # [s] ROS time
        self._published_s = -math.inf  # [s] ROS time of the last publication
        if self.memory is not None:
            self._subscribers.append(rospy.Subscriber(MEMORY_MARK_TOPIC, PolygonStamped, self._on_memory_mark,
                                                      queue_size=10))
            self._memory_service = rospy.Service(private_name(f"~{name}/clear_obstacle_memory"), Trigger,
                                                 self._on_clear_memory)
        self._update_timer = self._start_update_timer(name, 1.0 / update_hz)
        self._clear_server: Optional[actionlib.SimpleActionServer] = None

    # ------------------------------------------------------------------ inputs
    def _on_map(self, msg: OccupancyGrid) -> None:
        try:
            grid = grid_map_of(msg)
        except ConfigError as err:
            rospy.logerr("%s: ignoring map: %s", self.name, err)
            return
        if msg.header.frame_id.lstrip("/") != self.global_frame.lstrip("/") and not self.rolling_window:
            rospy.logerr("%s: map frame '%s' is not global_frame '%s'; ignoring it",
                         self.name, msg.header.frame_id, self.global_frame)
            return
        with self.lock:
            if self.rolling_window:
                assert self.costmap is not None
                self.costmap.set_static_map(grid)
            else:
                self.costmap = self._static_costmap(grid)
            self._publish_memory()
        self._map_received.set()
        self.publish()

    def _memory_params(self, ns: str) -> Optional[MemoryParams]:
        """``obstacle_memory/`` (None: off)."""
        sub = ns + "obstacle_memory/"
        reject_unknown(sub, ["enabled", *(f.name for f in dataclasses.fields(MemoryParams))])
        if not param_bool(sub + "enabled", False):
            return None
        if self.rolling_window or not self.use_static_map:
            raise ConfigError(f"{rospy.resolve_name(private_name(sub))}enabled: an obstacle memory needs a static "
                              "costmap (static_map true, rolling_window false)")
        d = MemoryParams()
        try:
            return MemoryParams(
                memory_s=param_float(sub + "memory_s", d.memory_s),
                tolerance_m=param_float(sub + "tolerance_m", d.tolerance_m),
                min_free_beams=param_int(sub + "min_free_beams", d.min_free_beams),
                min_hits=param_int(sub + "min_hits", d.min_hits),
                max_range_m=param_float(sub + "max_range_m", d.max_range_m),
                max_obstacles=param_int(sub + "max_obstacles", d.max_obstacles),
            )  # MemoryParams checks the ranges
        except ConfigError as err:
            raise ConfigError(f"{rospy.resolve_name(private_name(sub))}: {err}") from err

    def _on_memory_mark(self, msg: PolygonStamped) -> None:
        """A heavy obstacle's footprint: into the global frame at its stamp, then remembered."""
        points = np.array([[p.x, p.y] for p in msg.polygon.points], dtype=np.float64).reshape(-1, 2)
        try:
            x, y, yaw = self._frame_pose_at(msg.header.frame_id, msg.header.stamp)
            footprint = transform_poses(points, x, y, yaw)
            with self.lock:
                if self.costmap is None:
                    raise NotReadyError("no map yet")
                entry = self.costmap.remember_obstacle(footprint, msg.header.stamp.to_sec())
                layer = self.costmap.memory_layer
                held = f"{len(layer.obstacles)} of at most {layer.params.max_obstacles}" if layer is not None else ""
                self._publish_memory()
        except (NotReadyError, ConfigError) as err:
            rospy.logwarn(f"{self.name}: obstacle memory: footprint ignored: {err}")
            return
        rospy.loginfo(f"{self.name}: obstacle memory: {entry.describe()} ({held} remembered)")

    def _on_clear_memory(self, _request: TriggerRequest) -> TriggerResponse:
        with self.lock:
            forgotten = self.costmap.clear_memory() if self.costmap is not None else []
            self._publish_memory()
        rospy.loginfo(f"{self.name}: obstacle memory cleared by request ({len(forgotten)} forgotten)")
        return TriggerResponse(success=True, message=f"{len(forgotten)} remembered obstacle(s) forgotten")

    def _publish_memory(self) -> None:
        """Latch the remembered obstacles on ``~<name>/obstacle_memory`` if they changed since last published (the
        caller holds :attr:`lock`, so publications follow the changes in order)."""
        if self._memory_publisher is None or self.costmap is None or self.costmap.memory_layer is None:
            return
        obstacles = self.costmap.memory_layer.obstacles
        shown = tuple((o.obstacle_id, o.found_s, o.footprint.tobytes()) for o in obstacles)
        if shown == self._memory_shown:
            return
        self._memory_shown = shown
        self._memory_publisher.publish(memory_markers(obstacles, self.global_frame, rospy.Time.now()))

    def _static_costmap(self, grid: GridMap) -> Costmap:
        if grid.origin[2] != 0.0:
            raise ConfigError(f"{self.name}: map origin yaw must be 0, got {grid.origin[2]}")
        remembered = (self.costmap.memory_layer.obstacles if self.costmap is not None
                      and self.costmap.memory_layer is not None else ())
        costmap = self._new_static_costmap(grid)
        for obstacle in remembered:  # a new map (the mapper's, say) keeps what was found heavy
            costmap.remember_obstacle(obstacle.footprint, obstacle.found_s, obstacle.what)
        return costmap

    def _new_static_costmap(self, grid: GridMap) -> Costmap:
        return Costmap(
            CostmapGeometry(grid.width, grid.height, grid.resolution, grid.origin[0], grid.origin[1]),
            static_map=grid,
            obstacles=self.obstacles,
            inflation=self.inflation,
            track_unknown_space=self.track_unknown_space,
            bumper_memory_s=self.bumper_memory_s,
            memory=self.memory,
        )

    def _frame_pose_at(self, frame_id: str, stamp: rospy.Time) -> tuple[float, float, float]:
        try:
            tf = lookup_bounded(self.tf_buffer, self.global_frame, frame_id, stamp, TF_WAIT_S)
        except TF_ERRORS as err:
            raise NotReadyError(f"no transform {self.global_frame} -> {frame_id}: {err}") from err
        t, q = tf.transform.translation, tf.transform.rotation
        return (t.x, t.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))

    def _on_scan(self, msg: LaserScanMsg) -> None:
        try:
            x, y, yaw = self._frame_pose_at(msg.header.frame_id, msg.header.stamp)
            # a rolling window follows the robot base (as the update timer does), not the sensor: centred on
            # the lidar it would move a cell back and forth between a scan and the next timer tick
            base = self._frame_pose_at(self.robot_base_frame, msg.header.stamp) if self.rolling_window else None
            scan = LaserScan(
                ranges=np.asarray(msg.ranges, dtype=np.float64), angle_min=msg.angle_min,
                angle_increment=msg.angle_increment, range_min=msg.range_min, range_max=msg.range_max,
                sensor_x=x, sensor_y=y, sensor_yaw=yaw,
            )
            scan.validate()
        except (NotReadyError, ConfigError) as err:
            rospy.logwarn_throttle(5.0, f"{self.name}: scan ignored: {err}")
            return
        with self.lock:
            if self.costmap is not None:
                if base is not None:
                    self.costmap.recentre(base[0], base[1])
                self.costmap.add_scan(scan)  # may forget a remembered obstacle: the update timer publishes that
            # only a scan that reached the obstacle layer counts as fresh: one add_scan rejected keeps aging
            self.last_scan_time = msg.header.stamp
            self.last_scan_received_s = rospy.get_time()

    def _on_bumper_hit(self, msg: PointStamped) -> None:
        try:
            tf = lookup_bounded(self.tf_buffer, self.global_frame, msg.header.frame_id, msg.header.stamp, TF_WAIT_S)
        except TF_ERRORS as err:
            rospy.logwarn(f"{self.name}: bumper hit ignored, no transform: {err}")
            return
        t, q = tf.transform.translation, tf.transform.rotation
        yaw = yaw_of_quaternion(q.x, q.y, q.z, q.w)
        px, py = msg.point.x, msg.point.y
        x = t.x + math.cos(yaw) * px - math.sin(yaw) * py
        y = t.y + math.sin(yaw) * px + math.cos(yaw) * py
        with self.lock:
            if self.costmap is not None:
                self.costmap.add_bumper_hits(np.array([x]), np.array([y]), now_s=rospy.get_time())
                self.costmap.update()
        rospy.loginfo(f"{self.name}: bumper hit marked at ({x:.2f}, {y:.2f}) in {self.global_frame}")

    # ------------------------------------------------------------------ upkeep
    def _start_update_timer(self, name: str, period_s: float) -> Union[rospy.Timer, LockstepTimer]:
        """A rospy.Timer; in a lockstep simulation one that holds it for each update (so the rolling window moves
        at the same steps in every run)."""
        if lockstep_enabled():
            return LockstepTimer(period_s, lambda now_s: self._on_update_timer(now_s, at_tick=True),
                                 LockstepParticipant(f"{name}/update"), f"{name} updates")
        return rospy.Timer(rospy.Duration(period_s), lambda event: self._on_update_timer(event.current_real.to_sec()),
                           reset=True)

    def _on_update_timer(self, now_s: float, at_tick: bool = False) -> None:
        """Update at ROS time ``now_s`` [s]; publish if due. ``at_tick`` (lockstep): the rolling window moves to the
        pose at ``now_s`` (see RobotPoseSource.pose), not the newest."""
        try:
            self._update(now_s if at_tick else None)
        except Exception as err:  # an exception would end rospy's timer thread: the costmap would freeze
            rospy.logerr_throttle(5.0, f"{self.name}: costmap update failed: {err!r}")
        if now_s < self._published_s:  # ROS time went back (a restarted simulation): publish on the new timeline
            self._published_s = -math.inf
        if now_s - self._published_s < self._publish_period_s - 1e-6:
            return
        self._published_s = now_s
        try:
            self.publish()
        except Exception as err:  # as above: the next tick tries again
            rospy.logerr_throttle(5.0, f"{self.name}: costmap publish failed: {err!r}")

    def _update(self, at_s: Optional[float] = None) -> None:
        """The upkeep of one update tick: the rolling window follows the robot (its pose at ``at_s`` [s] if given,
        else the newest), bumper hits and remembered obstacles expire."""
        centre = None
        if self.rolling_window:
            try:  # outside the lock: a tf wait must not hold up the users of the costmap
                centre = self.robot_pose.pose(timeout_s=0.05, at_s=at_s)
            except NotReadyError:
                return
        with self.lock:
            if self.costmap is None:
                return
            self.costmap.expire_bumper_hits(rospy.get_time())
            if self.costmap.memory_layer is not None:
                for gone in self.costmap.expire_memory(rospy.get_time()):
                    rospy.loginfo(f"{self.name}: obstacle memory: forgotten after memory_s: {gone.describe()}")
                self._publish_memory()
            if centre is not None:
                self.costmap.recentre(centre[0], centre[1])
            self.costmap.update()

    def publish(self) -> None:
        with self.lock:
            if self.costmap is None:
                return
            self.costmap.update()
            geo = self.costmap.geometry
            msg = occupancy_grid_msg(
                self.costmap.to_occupancy(), geo.resolution, geo.origin_x, geo.origin_y,
                frame_id=self.global_frame, stamp=rospy.Time.now(),
            )
        self.publisher.publish(msg)

    def snapshot(self) -> Optional[Tuple[np.ndarray, CostmapGeometry]]:
        """A copy of the current costs and geometry (for planning or checking outside the lock), or None.

        The master costs are brought up to date first: a scan moves the window and marks the obstacle layer,
        and costs copied before the next timer update would be placed by the new geometry but hold the old
        window's contents (every obstacle out of place by the robot's motion since)."""
        with self.lock:
            if self.costmap is None:
                return None
            self.costmap.update()
            return self.costmap.costs.copy(), dataclasses.replace(self.costmap.geometry)

    def wait_for_map(self, timeout_s: float = MAP_WAIT_S) -> bool:
        """True once a static costmap has a map (immediately for a rolling window without a static layer)."""
        if not self.use_static_map:
            return True
        return self._map_received.wait(timeout_s)

    def clear(self) -> None:
        """Forget every observation (the static map stays)."""
        with self.lock:
            if self.costmap is not None:
                self.costmap.reset()
        self.publish()

    def serve_clear_costmap(self, action_name: str) -> None:
        """Serve ClearCostmap on ``action_name`` (a node's ``<node>/clear_costmap``)."""
        server = actionlib.SimpleActionServer(action_name, ClearCostmapAction, auto_start=False)
        # lockstep: a client's hold stands from its send until the costmap is cleared (accept_hold_name)
        accept = server_accept_hold(rospy.resolve_name(action_name))

        def on_goal() -> None:
            server.accept_new_goal()
            stamp_s = server.current_goal.get_goal_id().stamp.to_sec()  # its client's hold is stamped up to it
            result = ClearCostmapResult()
            try:
                if self.costmap is None:
                    result.code, result.message = ClearCostmapResult.FAILURE, f"{self.name} has no map yet"
                    server.set_aborted(result, result.message)
                    return
                self.clear()
                result.code, result.message = ClearCostmapResult.SUCCESS, f"{self.name} cleared"
                server.set_succeeded(result, result.message)
            finally:
                accept.release(through_s=stamp_s)

        server.register_goal_callback(on_goal)
        server.start()
        self._clear_server = server
