"""``localizer`` node: adaptive Monte Carlo localization on a known map, with amcl's ROS interface.

``rosrun flex_nav localizer`` (in the robot's namespace; every name below is relative). The filter is
:class:`flex_nav.localization.Localizer`; this node only converts messages and transforms.

Subscribes ``scan`` (sensor_msgs/LaserScan), ``map`` (nav_msgs/OccupancyGrid, latched; a new map rebuilds the
likelihood field), ``initialpose`` (geometry_msgs/PoseWithCovarianceStamped, RViz's "2D Pose Estimate").
Odometry comes from tf (``odom_frame_id`` -> ``base_frame_id`` at the scan's stamp), as amcl's does.
Publishes ``amcl_pose`` (PoseWithCovarianceStamped, after every filter update), ``particlecloud``
(geometry_msgs/PoseArray, when someone listens), tf ``global_frame_id`` -> ``odom_frame_id`` for every scan
while localized, post-dated by ``transform_tolerance``, and ``~status`` (std_msgs/String, latched:
``uninitialized: ...``, ``localized: ...`` or ``lost: ...``).
Services ``global_localization`` and ``request_nomotion_update`` (std_srvs/Empty).

The node never publishes a transform it does not believe: before an initial pose (``initialpose``,
``~initial_pose_*`` parameters or ``global_localization``) and while the filter reports itself lost (its
particle spread beyond ``~lost_std_xy``, or the scans no longer end on the map: fewer than ``~lost_match_fraction``
of the beams within ``~lost_match_distance`` over ``~lost_match_updates`` updates) it publishes no
``map -> odom``, so the controllers' ``localization_timeout`` stops the robot. With ``~lost_recovery`` ``global``
(the default) a lost filter spreads its particles over the free space and runs a sensor update on every scan
until it converges again.

Private parameters (amcl's names and units where the meaning is the same; see the README's "Localization"):
the filter's (:class:`flex_nav.localization.FilterParams`: ``min_particles``, ``max_particles``, ``kld_err``,
``kld_z``, ``odom_alpha1..4``, ``laser_z_hit``, ``laser_z_rand``, ``laser_sigma_hit`` [m],
``laser_likelihood_max_dist`` [m], ``laser_max_beams``, ``update_min_d`` [m], ``update_min_a`` [rad],
``resample_interval``, ``recovery_alpha_slow``, ``recovery_alpha_fast``, ``lost_std_xy`` [m],
``lost_match_distance`` [m], ``lost_match_fraction``, ``lost_match_updates``, ``converged_match_fraction``) and
  ~global_frame_id  str    map             ~odom_frame_id str  odom      ~base_frame_id str  base_footprint
  ~transform_tolerance  float  0.1 [s]      post-dating of map -> odom
  ~tf_broadcast      bool   true            publish map -> odom (false: estimate only, as amcl's)
  ~initial_pose_x, ~initial_pose_y [m], ~initial_pose_a [rad]   start there when any of them is set
  ~initial_cov_xx, ~initial_cov_yy [m^2], ~initial_cov_aa [rad^2]  (0.25, 0.25, (pi/12)^2)
  ~laser_min_range, ~laser_max_range  float  -1 [m]  (-1: the scan's own limits)
  ~lost_recovery     str    global          global | none
  ~seed              int    -1              random seed (-1: a fresh one each run); with a seed, every initial pose
                                             restarts the filter's generator from it (a run that starts from an
                                             initial pose is the same run whenever it starts)
  ~transform_timeout float  0.1 [s]         bound on waiting for the odometry and laser transforms

In a lockstep simulation (``/lockstep``) the node holds the simulation at every scan until it has weighed it, and
at every ``initialpose`` stamped after time 0 (the simulator's at a world start) until it has applied it.

Bad input is logged (throttled) with the field that is wrong and nothing wrong is published: beams that are NaN,
-inf or outside the range limits are dropped beam by beam (+inf, "no return" in REP 117, is skipped quietly); a
scan in a frame tf cannot place, a scan before the map or before an initial pose, an ``initialpose`` in another
frame or with a NaN or unnormalised quaternion or a covariance that is not positive semi-definite are ignored; a
scan stamped before the previous one (time went back: a restarted simulation or a looped bag) restarts the
odometry reference instead of applying a jump.
"""

from __future__ import annotations

import dataclasses
import math
import threading
from typing import List, Optional, Sequence, Tuple

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import PoseArray, PoseWithCovarianceStamped
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String
from std_srvs.srv import Empty, EmptyRequest, EmptyResponse

from flex_nav.exceptions import ConfigError
from flex_nav.localization import Estimate, FilterParams, Localizer, LocalizerStatus, ScanBeams
from flex_nav.nav.planar import Pose2D, compose_poses, inverse_pose
from flex_nav.nav.pose_checks import pose_problem, yaw_of_quaternion
from flex_nav.ros.conversions import grid_map_of, pose_of_xy_yaw
from flex_nav.ros.frames import TfSource
from flex_nav.ros.latest_worker import LatestWorker
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.node import run_node
from flex_nav.ros.params import param_bool, param_float, param_int, param_str, reject_unknown
from flex_nav.ros.private_ns import private_name
from flex_nav.ros.scan_input import Complaints, ScanInput, invalid_beams, transform_msg

NODE_NAME = "localizer"
TF_CACHE_S = 30.0  # [s] of transforms kept: scans are matched to odometry at their own stamps
FILTER_PARAMS = tuple(f.name for f in dataclasses.fields(FilterParams))
NODE_PARAMS = (
    "global_frame_id", "odom_frame_id", "base_frame_id", "transform_tolerance", "tf_broadcast",
    "initial_pose_x", "initial_pose_y", "initial_pose_a", "initial_cov_xx", "initial_cov_yy", "initial_cov_aa",
    "laser_min_range", "laser_max_range", "lost_recovery", "seed", "transform_timeout",
)
LOST_RECOVERY = ("global", "none")
COVARIANCE_INDEX = ((0, 1, 5), (6, 7, 11), (30, 31, 35))  # (x, y, yaw) rows of a 6x6 row-major pose covariance


def planar_covariance(flat: Sequence[float]) -> np.ndarray:
    """The (3, 3) x, y, yaw block of a geometry_msgs 6x6 row-major covariance."""
    return np.array([[flat[i] for i in row] for row in COVARIANCE_INDEX], dtype=np.float64)


class LocalizerNode:
    """Messages and transforms around one :class:`Localizer`; see the module docstring."""

    def __init__(self, tf_buffer: Optional[tf2_ros.Buffer] = None) -> None:
        """``tf_buffer``: one shared with other components of the process, caching at least
        :data:`TF_CACHE_S` (None: a buffer of its own)."""
        reject_unknown("~", FILTER_PARAMS + NODE_PARAMS)
        given = {name: rospy.get_param(private_name("~" + name)) for name in FILTER_PARAMS
                 if rospy.has_param(private_name("~" + name))}
        self.params = FilterParams.from_mapping(given, owner=f"parameter {rospy.resolve_name(private_name('~'))}")
        self.global_frame = param_str("~global_frame_id", "map").lstrip("/")
        self.odom_frame = param_str("~odom_frame_id", "odom").lstrip("/")
        self.base_frame = param_str("~base_frame_id", "base_footprint").lstrip("/")
        for name, frame in (("global_frame_id", self.global_frame), ("odom_frame_id", self.odom_frame),
                            ("base_frame_id", self.base_frame)):
            if not frame:
                raise ConfigError(f"parameter {rospy.resolve_name(private_name('~' + name))} must not be empty")
        self.tolerance = rospy.Duration.from_sec(param_float("~transform_tolerance", 0.1, 0.0, 10.0))
        self.tf_broadcast = param_bool("~tf_broadcast", True)
        self.laser_min_range = param_float("~laser_min_range", -1.0, -1.0, 1e4)
        self.laser_max_range = param_float("~laser_max_range", -1.0, -1.0, 1e4)
        self.lost_recovery = param_str("~lost_recovery", "global", LOST_RECOVERY)
        seed = param_int("~seed", -1, -1)
        self.seed: Optional[int] = None if seed < 0 else seed
        self.transform_timeout = rospy.Duration.from_sec(param_float("~transform_timeout", 0.1, 0.0, 10.0))
        self.initial_pose = self._initial_pose_parameters()

        self._lock = threading.Lock()
        self._filter: Optional[Localizer] = None
        self._pending_pose: Optional[Tuple[Pose2D, np.ndarray]] = self.initial_pose
        self._pending_global = False
        self._last_scan_stamp: Optional[rospy.Time] = None
        self._map_to_odom: Optional[Pose2D] = None  # the transform last believed
        self._global_running = False  # global localization under way: a sensor update on every scan
        self._status = ""
        self._rivals_reported = 0  # rival poses last reported while relocalizing
        self._complain = Complaints(NODE_NAME)

        self.tf = TfSource(tf_buffer, cache_s=TF_CACHE_S)
        self.tf_buffer = self.tf.buffer
        self.scan_input = ScanInput(self.tf_buffer, self.odom_frame, self.base_frame, self.transform_timeout,
                                    self._complain, laser_range=(self.laser_min_range, self.laser_max_range))
        self.tf_broadcaster = tf2_ros.TransformBroadcaster()
        self.pub_pose = rospy.Publisher("amcl_pose", PoseWithCovarianceStamped, queue_size=2)
        self.pub_cloud = rospy.Publisher("particlecloud", PoseArray, queue_size=2)
        self.pub_status = rospy.Publisher(private_name("~status"), String, queue_size=2, latch=True)
        self._set_status("uninitialized: waiting for the map")
        self.services = [
            rospy.Service("global_localization", Empty, self._on_global_localization),
            rospy.Service("request_nomotion_update", Empty, self._on_nomotion_update),
        ]
        self.sub_map = rospy.Subscriber("map", OccupancyGrid, self._on_map, queue_size=1)
        self.sub_initial = rospy.Subscriber("initialpose", PoseWithCovarianceStamped, self._on_initial_pose,
                                            queue_size=1)
        # lockstep: a stamped initial pose (the simulator's at a world start) is applied before the simulation steps
        # on, so the first scan weighed from it is the same in every run (it raced the scans before)
        self.initial_hold = LockstepParticipant("initialpose")
        self.initial_hold.hold_topic(self.sub_initial.resolved_name, math.nextafter(0.0, math.inf))
        # the filter runs on a thread of its own (LatestWorker's docstring says why)
        self.scan_worker: LatestWorker[LaserScan] = LatestWorker(self._process_scan, "localizer scans")
        self.sub_scan = self.scan_worker.subscribe("scan", LaserScan, LockstepParticipant("scan"), buff_size=2**20)

    # -- inputs -----------------------------------------------------------------------------------------------
    def _initial_pose_parameters(self) -> Optional[Tuple[Pose2D, np.ndarray]]:
        names = ("~initial_pose_x", "~initial_pose_y", "~initial_pose_a")
        if not any(rospy.has_param(private_name(n)) for n in names):
            return None
        pose = (param_float(names[0], 0.0), param_float(names[1], 0.0), param_float(names[2], 0.0))
        cov = np.diag([param_float("~initial_cov_xx", 0.25, 0.0), param_float("~initial_cov_yy", 0.25, 0.0),
                       param_float("~initial_cov_aa", (math.pi / 12.0) ** 2, 0.0)])
        return pose, cov

    def _on_map(self, msg: OccupancyGrid) -> None:
        frame = msg.header.frame_id.lstrip("/")
        if frame != self.global_frame:
            self._complain("map_frame", f"map ignored: its header.frame_id '{msg.header.frame_id}' is not the "
                                        f"global frame '{self.global_frame}' (parameter ~global_frame_id)")
            return
        try:
            grid = grid_map_of(msg)
        except ConfigError as err:
            self._complain("map_bad", f"map ignored: {err}")
            return
        with self._lock:
            if self._filter is None:
                self._filter = Localizer(self.params, grid, seed=self.seed)
                rospy.loginfo("localizer: map %dx%d cells at %.3f m; likelihood field built", grid.occupancy.shape[1],
                              grid.occupancy.shape[0], grid.resolution)
            else:
                self._filter.set_map(grid)
                rospy.loginfo("localizer: new map %dx%d cells: likelihood field rebuilt, particles kept",
                              grid.occupancy.shape[1], grid.occupancy.shape[0])
            self._apply_pending_initialisation()
            if self._filter.estimate().status is LocalizerStatus.UNINITIALIZED:
                self._set_status("uninitialized: waiting for an initial pose (initialpose, ~initial_pose_x/y/a) "
                                 "or a global_localization call")

    def _on_initial_pose(self, msg: PoseWithCovarianceStamped) -> None:
        try:
            self._take_initial_pose(msg)
        finally:  # (lockstep) held for the next one, stamped after this
            stamp_s = max(msg.header.stamp.to_sec(), 0.0)
            self.initial_hold.hold_topic(self.sub_initial.resolved_name, math.nextafter(stamp_s, math.inf))

    def _take_initial_pose(self, msg: PoseWithCovarianceStamped) -> None:
        frame = msg.header.frame_id.lstrip("/")
        if frame != self.global_frame:
            self._complain("initial_frame", f"initialpose ignored: header.frame_id '{msg.header.frame_id}' is not "
                                            f"the global frame '{self.global_frame}'", throttle=False)
            return
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        problem = pose_problem((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
        cov = planar_covariance(msg.pose.covariance)
        if problem is None and not np.all(np.isfinite(cov)):
            problem = f"covariance {cov.tolist()} is not finite"
        if problem is not None:
            self._complain("initial_bad", f"initialpose ignored: pose.pose {problem}", throttle=False)
            return
        pose = (p.x, p.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))
        with self._lock:
            self._pending_pose, self._pending_global = (pose, cov), False
            self._apply_pending_initialisation()

    def _on_global_localization(self, _request: EmptyRequest) -> EmptyResponse:
        with self._lock:
            self._pending_pose, self._pending_global = None, True
            self._apply_pending_initialisation()
        return EmptyResponse()

    def _on_nomotion_update(self, _request: EmptyRequest) -> EmptyResponse:
        with self._lock:
            if self._filter is not None:
                self._filter.request_nomotion_update()
        return EmptyResponse()

    def _apply_pending_initialisation(self) -> None:
        """(lock held) Start the filter from a pending initial pose or global localization once a map exists."""
        if self._filter is None:
            return
        if self._pending_pose is not None:
            pose, cov = self._pending_pose
            self._pending_pose = None
            if self.seed is not None:
                self._filter.reseed(self.seed)
            try:
                self._filter.set_pose(pose, cov)
            except ConfigError as err:
                self._complain("initial_bad", f"initial pose ignored: {err}", throttle=False)
                return
            self._map_to_odom = None
            self._global_running = False
            self._set_status(f"localizing: initial pose ({pose[0]:.2f}, {pose[1]:.2f}, "
                             f"{math.degrees(pose[2]):.0f} deg)")
        elif self._pending_global:
            self._pending_global = False
            self._filter.global_localization()
            self._global_running = True
            self._map_to_odom = None
            self._set_status("localizing: global localization (particles over all free space)")

    # -- the filter ---------------------------------------------------------------------------------------------
    def _process_scan(self, scan: LaserScan) -> None:
        with self._lock:
            ready = self._filter is not None
        if not ready:
            self._complain("no_map", "scan ignored: no map yet on topic " + self.sub_map.resolved_name)
            return
        laser_pose = self.scan_input.laser_pose(scan.header.frame_id)
        odom = self.scan_input.odom_pose(scan.header.stamp)
        if laser_pose is None or odom is None:
            return
        beams = self.scan_input.beams(scan, laser_pose)
        with self._lock:
            self._update(scan.header.stamp, odom, beams)

    def _update(self, stamp: rospy.Time, odom: Pose2D, beams: ScanBeams) -> None:
        """(lock held) One scan through the filter, then the outputs."""
        localizer = self._filter
        assert localizer is not None
        if self._last_scan_stamp is not None and stamp < self._last_scan_stamp:
            back = (self._last_scan_stamp - stamp).to_sec()
            self._complain("time_back", f"scan stamped {back:.2f} s before the previous one (time went back): "
                                        "odometry reference restarted", throttle=False)
            localizer.restart_odometry()
        self._last_scan_stamp = stamp
        status = localizer.estimate().status
        if status is LocalizerStatus.UNINITIALIZED:
            self._complain("no_pose", "scan ignored: no initial pose yet (publish initialpose, e.g. RViz's "
                                      "2D Pose Estimate, or call global_localization)")
            return
        if self._global_running:  # converging from particles everywhere: every scan counts, moving or not
            localizer.request_nomotion_update()
        try:
            updated = localizer.update(odom, beams)
        except ConfigError as err:  # a malformed scan (e.g. range_min >= range_max)
            self._complain("scan_bad", f"scan ignored: {err}")
            return
        bad = invalid_beams(beams)
        if bad:
            self._complain("beams", f"scan: {bad} of {len(beams.ranges)} beams NaN, -inf or outside "
                                    f"[{beams.range_min:g}, {beams.range_max:g}] m: dropped")
        estimate = localizer.estimate()
        self._follow_status(estimate)
        if estimate.status is not LocalizerStatus.LOCALIZED:
            return
        if updated or self._map_to_odom is None:
            self._map_to_odom = compose_poses(estimate.pose, inverse_pose(odom))
            self._publish_estimate(stamp, estimate)
        if self.tf_broadcast:
            self._publish_transform(stamp + self.tolerance, self._map_to_odom)

    def _follow_status(self, estimate: Estimate) -> None:
        """(lock held) Log and publish changes of the filter's status; a newly lost filter starts global
        localization when ``~lost_recovery`` says so."""
        std_xy = math.sqrt(max(estimate.covariance[0, 0], estimate.covariance[1, 1], 0.0))
        if estimate.status is LocalizerStatus.LOCALIZED:
            self._global_running = False
            if not self._status.startswith("localized"):
                x, y, yaw = estimate.pose
                rospy.loginfo("localizer: localized at (%.2f, %.2f, %.0f deg), spread %.3f m", x, y,
                              math.degrees(yaw), std_xy)
                self._set_status(f"localized: ({x:.2f}, {y:.2f}, {math.degrees(yaw):.0f} deg), "
                                 f"spread {std_xy:.3f} m")
            return
        if estimate.status is LocalizerStatus.LOST and self._global_running:
            self._report_rivals()
            return
        if estimate.status is not LocalizerStatus.LOST:
            return
        recover = self.lost_recovery == "global"
        assert self._filter is not None
        why = self._lost_reason(std_xy, self._filter.match_fraction_mean)
        rospy.logerr("localizer: LOST: %s; map -> odom no longer published%s", why,
                     "; global localization" if recover else "")
        self._set_status(f"lost: {why}" + ("; global localization" if recover else ""))
        if recover:
            assert self._filter is not None
            self._filter.global_localization()
            self._global_running = True

    def _report_rivals(self) -> None:
        """(lock held, relocalizing) Log and publish it when the cloud has converged on a pose that other poses of
        the map rival (the filter stays lost until the scans tell them apart), and when that changes."""
        assert self._filter is not None
        rivals = self._filter.rivals
        if len(rivals) == self._rivals_reported:
            return
        self._rivals_reported = len(rivals)
        if not rivals:
            return
        poses = ", ".join(f"({r.pose[0]:.2f}, {r.pose[1]:.2f}, {math.degrees(r.pose[2]):.0f} deg)" for r in rivals)
        rospy.logwarn("localizer: %d poses fit the scans as well: %s; still lost until the scans tell them apart "
                      "(move the robot, or give it a pose)", len(rivals), poses)
        self._set_status(f"lost: ambiguous: {len(rivals)} poses fit the scans: {poses}; global localization")

    def _lost_reason(self, std_xy: float, match_mean: float) -> str:
        """Which rule declared the filter lost: the cloud's spread or scans that stopped matching the map."""
        p = self.params
        if std_xy > p.lost_std_xy:
            return f"particle spread {std_xy:.2f} m > {p.lost_std_xy:.2f} m (~lost_std_xy)"
        return (f"only {match_mean:.0%} of the beams end within {p.lost_match_distance:.2f} m of the map "
                f"(< {p.lost_match_fraction:.0%} over {p.lost_match_updates} updates, ~lost_match_fraction)")

    # -- outputs ------------------------------------------------------------------------------------------------
    def _publish_estimate(self, stamp: rospy.Time, estimate: Estimate) -> None:
        msg = PoseWithCovarianceStamped()
        msg.header.stamp = stamp
        msg.header.frame_id = self.global_frame
        msg.pose.pose = pose_of_xy_yaw(*estimate.pose)
        covariance = [0.0] * 36
        for i, row in enumerate(COVARIANCE_INDEX):
            for j, index in enumerate(row):
                covariance[index] = float(estimate.covariance[i, j])
        msg.pose.covariance = covariance
        self.pub_pose.publish(msg)
        if self.pub_cloud.get_num_connections() > 0:
            assert self._filter is not None
            cloud = PoseArray()
            cloud.header = msg.header
            cloud.poses = [pose_of_xy_yaw(x, y, yaw) for x, y, yaw in self._filter.particles.tolist()]
            self.pub_cloud.publish(cloud)

    def _publish_transform(self, stamp: rospy.Time, map_to_odom: Pose2D) -> None:
        self.tf_broadcaster.sendTransform(transform_msg(stamp, self.global_frame, self.odom_frame, map_to_odom))

    def _set_status(self, status: str) -> None:
        if status != self._status:
            self._status = status
            self.pub_status.publish(String(data=status))


def main() -> int:
    return run_node(NODE_NAME, LocalizerNode)


__all__: List[str] = ["LocalizerNode", "invalid_beams", "main", "planar_covariance"]
