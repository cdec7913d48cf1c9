"""``sim`` node: the pybullet simulator (:mod:`flex_nav_sim`) behind the ROS interface of the real robots.

``rosrun flex_nav sim _world:=lab [_robots:=robot1,robot2:create2:3:1:90] [_seed:=0] [_rtf:=1.0]``

One thread steps the simulation and publishes what each step reports; ROS callbacks only queue
velocity commands for it. Everything is validated before anything is advertised: an unknown world
or profile, a malformed file, a robot inside a wall or two robots with one namespace make the node
log the reason and exit with status 2, with no topic advertised and no physics server left behind.

Private parameters:
  ~world         str    (required) world name (``sim/worlds/<name>.yaml``) or path
  ~robots        str|list  robots to spawn, default the world's (see :mod:`flex_nav_sim.spawn_spec`)
  ~seed          int    0      seed of the one random generator (noise): same seed, same run
  ~rtf           float  1.0    real-time factor to keep; 0 = as fast as possible
  ~physics_rate  float  240    [Hz] fixed physics step rate
  ~clock_rate    float  100    [Hz] /clock publication rate (in simulated time)
  ~lidar, ~camera, ~bumpers  bool  true  simulate these sensors (a camera renders only while its image or
                                          depth topic has a subscriber)
  ~gui           bool   false  pybullet GUI window (only if a display exists)
  ~drift_xy, ~drift_yaw, ~drift_tau  float  0, 0, 10  localization drift: [m], [rad], [s] (0 = exact)
  ~map_frame     str    map
  ~duration      float  0      [s] simulated time after which the node exits (0 = run until shutdown)
  ~publish_map_odom  bool  true  publish map -> NS/odom from ground truth (the oracle); false when a
                 localizer (``rosrun flex_nav localizer``) publishes it, as in every flex_nav launch file
  ~lockstep_timeout  float  5.0  [s of wall time] with the global ``/lockstep`` true (lockstep mode, see
                 :mod:`flex_nav_sim.lockstep`): the simulation steps no further than the nodes' holds on
                 ``/lockstep/holds`` (flex_nav/LockstepHold) allow; a hold that keeps it waiting this long is dropped
                 and logged; after each wait it pauses ``~lockstep_settle`` [s of wall time] (0.002) more, so
                 what a node sent just before it let go (a plan, a class) arrives before the next step; a scan
                 goes out after the step of the first odometry at or after its stamp. Velocity commands come from
                 NS/cmd_vel_stamped then (the controllers' own output, not twist_relay's NS/cmd_vel): a controller
                 says with its hold that it sent one, and the simulation steps on only once that command is in,
                 so a command computed at one step drives the robot from the next, whatever the load
  ~world_start  str  at_once  at_once: people walk and world events happen on the world's times from t = 0;
                 on_request: from the step after a call of ~start_world (a scenario's run starts there, the
                 same run at whatever time it starts)
  ~publish_initial_pose  bool  (not ~publish_map_odom)  publish NS/initialpose once, latched: the spawn pose
                 with a standard deviation of INITIAL_STD_XY_M / INITIAL_STD_YAW_RAD, as an operator's
                 "2D Pose Estimate" would give the localizer

Per robot ``NS`` (its name; frames are prefixed ``NS/``; an empty name is allowed for a single robot):
  publishes  NS/odom (nav_msgs/Odometry, NS/odom -> NS/base_footprint), NS/ground_truth (Odometry in
             map), NS/scan (LaserScan, NS/laser), NS/camera/rgb/image_raw + camera_info and
             NS/camera/depth/image_raw (32FC1 [m], registered: same frame, size and intrinsics) +
             camera_info (NS/camera_rgb_optical_frame), NS/bumper_state (BumperState, latched, on change),
             NS/events/bumper (kobuki profiles: BumperEvent), NS/bumper (create profiles: CreateBumper),
             NS/sim_events (SimEvent: contacts begin/end, ignored/clamped/timed-out commands)
  tf         map -> NS/odom -> NS/base_footprint; static NS/base_footprint -> NS/base_link, NS/laser,
             NS/camera_rgb_frame -> NS/camera_rgb_optical_frame
  subscribes NS/cmd_vel (geometry_msgs/Twist); in lockstep mode NS/cmd_vel_stamped (geometry_msgs/TwistStamped)
             instead, with twist_relay's rules: a command stamped before the newest one taken is dropped, at equal
             stamps a stop wins, a non-finite one stops the robot
  with ~publish_initial_pose: NS/initialpose (geometry_msgs/PoseWithCovarianceStamped, map frame, latched; stamped
             0 at the start, the world start's time at a world start: lockstep waits for a localizer to apply it)
Global: /clock (rosgraph_msgs/Clock; run every other node with use_sim_time), sim_events (world events).
Service ~start_world (std_srvs/Trigger, with ~world_start on_request): the world's script and fresh noise from the
seed start before the next step, and with ~publish_initial_pose every robot's initial pose goes out again (the
answer comes at once). Service ~teleport (flex_nav/Teleport): move a robot to a map pose at once, at rest, without
its odometry seeing it (the kidnapped robot); answered after the stepping thread has done it.
"""

from __future__ import annotations

import math
import sys
import threading
import time
import warnings
from dataclasses import dataclass, replace
from typing import Any, Callable, Dict, List, Optional, Tuple

import genpy
import rospy
from geometry_msgs.msg import PoseWithCovarianceStamped, TransformStamped, Twist, TwistStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, LaserScan
from std_srvs.srv import Trigger, TriggerRequest, TriggerResponse
from tf2_msgs.msg import TFMessage

from flex_nav.exceptions import ConfigError
from flex_nav.msg import BumperEvent, BumperState, CreateBumper, LockstepHold, SimEvent
from flex_nav.nav.control.safety import CommandOrder, twist_problem
from flex_nav.ros.lockstep import HOLDS_QUEUE, HOLDS_TOPIC, lockstep_enabled
from flex_nav.ros.node import init_node
from flex_nav.ros.params import param_bool, param_float, param_int, param_str
from flex_nav.srv import Teleport, TeleportRequest, TeleportResponse
from flex_nav_sim.lockstep import CLOCK_TOPIC, LockstepBarrier
from flex_nav_sim.profiles import RobotProfile
from flex_nav_sim.readings import (
    BumperReading,
    CommandNotice,
    ContactReading,
    ImageReading,
    OdometryReading,
    Pose2D,
    ScanReading,
    WorldEventReading,
)
from flex_nav_sim.simulation import LocalizationDrift, SensorOptions, Simulation
from flex_nav_sim.spawn_spec import resolve_spawns
from flex_nav_sim.world import load_world

NODE_NAME = "sim"
KOBUKI_CODES = {"left": BumperEvent.LEFT, "center": BumperEvent.CENTER, "right": BumperEvent.RIGHT}
# Small high-rate messages (/clock, /tf, odom, ground truth) are written to the subscribers' sockets
# in the stepping thread: 7-11 us a message, against about 90 us through rospy's queued publisher
# (whose time.sleep(0) after every message hands the GIL to a writer thread). A subscriber that stops
# reading altogether stalls the simulation once its socket buffer is full: the clock then stops
# and every sim-time node with it. Scans, images and events go through queues.
PACE_SLACK_S = 0.002  # [s] sleep only when this far ahead of the real-time schedule
MAX_LAG_S = 0.25  # [s] further behind than this: re-anchor the schedule instead of bursting to catch up
STATS_PERIOD_S = 30.0  # [s] wall time between log lines with the achieved real-time factor
CAMERA_CHECK_PERIOD_S = 0.25  # [s] wall time between looks at whether anyone subscribes to a camera
# odometry covariance, diagonal [m^2, m^2, m^2, rad^2, rad^2, rad^2] (x, y, z, roll, pitch, yaw). The base is
# planar: z, roll and pitch are known to be 0, so their variances are small (not 0: an EKF needs them positive;
# not huge, as 1e6 once was: RViz's Odometry display draws the covariance to scale, over the whole view)
ODOM_COVARIANCE = (0.001, 0.001, 1e-6, 1e-6, 1e-6, 0.003)
INITIAL_STD_XY_M = 0.1  # [m] standard deviation of the published initial pose (an operator's click)
INITIAL_STD_YAW_RAD = 0.1  # [rad]
TELEPORT_WAIT_S = 5.0  # [s, wall] bound on waiting for the stepping thread to do a teleport


def stamp_of(t: float) -> genpy.Time:
    """ROS time of simulated time ``t`` [s]."""
    nanoseconds = round(t * 1e9)
    return genpy.Time(nanoseconds // 1_000_000_000, nanoseconds % 1_000_000_000)


def synchronous_publisher(topic: str, msg_type: type) -> rospy.Publisher:
    """A publisher without a queue (see above); rospy's warning about the missing queue_size is silenced."""
    with warnings.catch_warnings():
        warnings.filterwarnings(
            "ignore", message="The publisher should be created with an explicit", category=SyntaxWarning
        )
        return rospy.Publisher(topic, msg_type, queue_size=None)


def set_yaw(q: Any, yaw: float) -> None:
    """Write a yaw-only rotation into geometry_msgs/Quaternion ``q``."""
    q.x = q.y = 0.0
    q.z = math.sin(yaw / 2.0)
    q.w = math.cos(yaw / 2.0)


def transform(parent: str, child: str, xyz: Tuple[float, float, float], quat: Tuple[float, ...]) -> TransformStamped:
    tf = TransformStamped()
    tf.header.frame_id = parent
    tf.child_frame_id = child
    tf.transform.translation.x, tf.transform.translation.y, tf.transform.translation.z = xyz
    r = tf.transform.rotation
    r.x, r.y, r.z, r.w = quat
    return tf


class RobotIO:
    """One robot's publishers, subscriber, frames and reusable messages."""

    def __init__(
        self, name: str, profile: RobotProfile, sim: Simulation, map_frame: str, queue_command: Callable,
        *, stamped_commands: bool = False,
    ) -> None:
        self.name = name
        self.profile = profile
        prefix = f"{name}/" if name else ""
        self.frame_odom = prefix + "odom"
        self.frame_base = prefix + "base_footprint"
        self.frame_laser = prefix + "laser"
        self.frame_camera = prefix + "camera_rgb_optical_frame"
        self.map_frame = map_frame

        def topic(t: str) -> str:
            return f"{name}/{t}" if name else t

        self.pub_odom = synchronous_publisher(topic("odom"), Odometry)
        self.pub_truth = synchronous_publisher(topic("ground_truth"), Odometry)
        self.lidar = sim.lidar_spec_of(name)
        self.pub_scan = rospy.Publisher(topic("scan"), LaserScan, queue_size=5) if self.lidar else None
        self.camera = sim.camera_spec_of(name)
        if self.camera is not None:
            self.pub_image: Optional[rospy.Publisher] = rospy.Publisher(
                topic("camera/rgb/image_raw"), Image, queue_size=2
            )
            self.pub_info: Optional[rospy.Publisher] = rospy.Publisher(
                topic("camera/rgb/camera_info"), CameraInfo, queue_size=10
            )
            self.pub_depth: Optional[rospy.Publisher] = rospy.Publisher(
                topic("camera/depth/image_raw"), Image, queue_size=2
            )
            self.pub_depth_info: Optional[rospy.Publisher] = rospy.Publisher(
                topic("camera/depth/camera_info"), CameraInfo, queue_size=10
            )
        else:
            self.pub_image = self.pub_info = self.pub_depth = self.pub_depth_info = None
        self.pub_state = rospy.Publisher(topic("bumper_state"), BumperState, queue_size=10, latch=True)
        style = profile.bumper.driver_style
        self.pub_kobuki = (
            rospy.Publisher(topic("events/bumper"), BumperEvent, queue_size=10) if style == "kobuki" else None
        )
        self.pub_create = rospy.Publisher(topic("bumper"), CreateBumper, queue_size=10) if style == "create" else None
        self.pub_events = rospy.Publisher(topic("sim_events"), SimEvent, queue_size=50)
        self.pub_initial_pose = rospy.Publisher(
            topic("initialpose"), PoseWithCovarianceStamped, queue_size=1, latch=True
        )
        # lockstep: the controllers' stamped commands (each waited for), not twist_relay's copies of them
        self.sub_cmd = rospy.Subscriber(
            topic("cmd_vel_stamped") if stamped_commands else topic("cmd_vel"),
            TwistStamped if stamped_commands else Twist,
            lambda msg: queue_command(name, msg), queue_size=10 if stamped_commands else 1, tcp_nodelay=True,
        )
        self._prepare_messages()

    def _prepare_messages(self) -> None:
        self.odom = Odometry()
        self.odom.header.frame_id = self.frame_odom
        self.odom.child_frame_id = self.frame_base
        for i, value in enumerate(ODOM_COVARIANCE):
            self.odom.pose.covariance[i * 7] = value
            self.odom.twist.covariance[i * 7] = value
        self.truth = Odometry()
        self.truth.header.frame_id = self.map_frame
        self.truth.child_frame_id = self.frame_base
        self.tf_map_odom = transform(self.map_frame, self.frame_odom, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
        self.tf_odom_base = transform(self.frame_odom, self.frame_base, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
        if self.lidar is not None:
            self.scan = LaserScan()
            self.scan.header.frame_id = self.frame_laser
            self.scan.angle_min = self.lidar.angle_min
            self.scan.angle_max = self.lidar.angle_max
            self.scan.angle_increment = self.lidar.angle_increment
            self.scan.scan_time = 1.0 / self.lidar.rate
            self.scan.time_increment = self.scan.scan_time / 360.0 * math.degrees(self.lidar.angle_increment)
            self.scan.range_min = self.lidar.range_min
            self.scan.range_max = self.lidar.range_max
        if self.camera is not None:
            cam = self.camera
            self.image = Image()
            self.image.header.frame_id = self.frame_camera
            self.image.height, self.image.width = cam.height, cam.width
            self.image.encoding = "rgb8"
            self.image.step = cam.width * 3
            self.depth = Image()
            self.depth.header.frame_id = self.frame_camera
            self.depth.height, self.depth.width = cam.height, cam.width
            self.depth.encoding = "32FC1"
            self.depth.is_bigendian = int(sys.byteorder == "big")
            self.depth.step = cam.width * 4
            self.info = CameraInfo()
            self.info.header.frame_id = self.frame_camera
            self.info.height, self.info.width = cam.height, cam.width
            self.info.distortion_model = "plumb_bob"
            self.info.D = [0.0] * 5
            # the renderer's optical axis passes through the middle of the image: (W - 1) / 2 with pixel centres
            # at integer coordinates, as CameraInfo counts them
            f, cx, cy = cam.focal_px, (cam.width - 1) / 2.0, (cam.height - 1) / 2.0
            self.info.K = [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0]
            self.info.R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
            self.info.P = [f, 0.0, cx, 0.0, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
        self.state = BumperState()
        self.state.zones = [z.name for z in self.profile.bumper.zones]
        self.state.pressed = [False] * len(self.state.zones)

    def publish_initial_pose(self, pose: Pose2D, stamp: Optional[genpy.Time] = None) -> None:
        """``pose`` (the spawn) on NS/initialpose, latched, with the covariance of an operator's estimate; stamped
        ``stamp`` (a world start's time; none: 0, the simulation's start)."""
        msg = PoseWithCovarianceStamped()
        msg.header.frame_id = self.map_frame
        msg.header.stamp = stamp if stamp is not None else genpy.Time()
        _set_pose(msg.pose.pose, pose)
        msg.pose.covariance[0] = msg.pose.covariance[7] = INITIAL_STD_XY_M**2
        msg.pose.covariance[35] = INITIAL_STD_YAW_RAD**2
        self.pub_initial_pose.publish(msg)

    def static_transforms(self) -> List[TransformStamped]:
        """base_footprint -> base_link, laser, camera frames (published once, latched)."""
        p = self.profile
        prefix = self.frame_base[: -len("base_footprint")]
        tfs = [
            transform(self.frame_base, prefix + "base_link", (0.0, 0.0, p.drive.wheel_radius), (0.0, 0.0, 0.0, 1.0)),
            transform(self.frame_base, self.frame_laser, p.lidar.mount, (0.0, 0.0, 0.0, 1.0)),
        ]
        if p.camera is not None:
            half = p.camera.pitch / 2.0
            tfs.append(
                transform(
                    self.frame_base,
                    prefix + "camera_rgb_frame",
                    p.camera.mount,
                    (0.0, math.sin(half), 0.0, math.cos(half)),
                )
            )
            # optical frame: z forward, x right, y down
            tfs.append(
                transform(prefix + "camera_rgb_frame", self.frame_camera, (0.0, 0.0, 0.0), (-0.5, 0.5, -0.5, 0.5))
            )
        return tfs


@dataclass(frozen=True)
class BridgeOptions:
    """How the bridge runs the simulation (from the node's parameters)."""

    rtf: float = 1.0  # real-time factor to keep; 0 = as fast as possible
    clock_rate: float = 100.0  # [Hz] /clock rate in simulated time
    map_frame: str = "map"
    duration: float = 0.0  # [s] simulated time to run (0 = until shutdown)
    publish_map_odom: bool = True  # map -> odom from ground truth (False: a localizer publishes it)
    publish_initial_pose: bool = False  # NS/initialpose once, latched, from the spawn pose
    lockstep: bool = False  # wait for the participants' holds (global /lockstep)
    lockstep_timeout_s: float = 5.0  # [s wall] longest wait for one hold
    lockstep_settle_s: float = 0.002  # [s wall] pause after a wait, for messages sent before a hold was replaced


class SimBridge:
    """Steps the simulation in one thread and publishes its readings."""

    def __init__(self, sim: Simulation, options: BridgeOptions) -> None:
        self.sim = sim
        self.rtf = options.rtf
        self.clock_period = 1.0 / options.clock_rate
        self.duration = options.duration
        self.publish_map_odom = options.publish_map_odom
        self.publish_initial_pose = options.publish_initial_pose
        map_frame = options.map_frame
        self._lock = threading.Lock()
        self._pending: Dict[str, Tuple[float, float]] = {}
        self._teleports: List[_TeleportRequest] = []  # from the service thread to the stepping thread
        self.pub_clock = synchronous_publisher("/clock", Clock)
        self.pub_tf = synchronous_publisher("/tf", TFMessage)
        self.pub_tf_static = rospy.Publisher("/tf_static", TFMessage, queue_size=10, latch=True)
        # latched: a node that subscribes late still learns the last world event (e.g. "box removed at 35 s")
        self.pub_world_events = rospy.Publisher("sim_events", SimEvent, queue_size=50, latch=True)
        self._command_order = {name: CommandOrder() for name in sim.robot_names}  # lockstep's stamped commands
        self.lockstep: Optional[LockstepBarrier] = None
        if options.lockstep:
            self.lockstep = LockstepBarrier(options.lockstep_timeout_s)
        self.robots = {
            name: RobotIO(name, sim.robot(name).profile, sim, map_frame, self._queue_command,
                          stamped_commands=options.lockstep)
            for name in sim.robot_names
        }
        if self.lockstep is not None:
            for io in self.robots.values():
                self.lockstep.subscribed(io.sub_cmd.resolved_name)
        self.publish_cost = 0.0  # [s] wall time spent building and publishing messages
        self.lag_resets = 0  # times the simulation fell more than MAX_LAG_S behind the requested rtf
        self._handlers: Dict[type, Callable] = {
            OdometryReading: self._on_odometry,
            ScanReading: self._on_scan,
            BumperReading: self._on_bumper,
            ImageReading: self._on_image,
            ContactReading: self._on_contact,
            WorldEventReading: self._on_world_event,
            CommandNotice: self._on_notice,
        }
        self._clock = Clock()
        self._clock_s = -math.inf  # [s] the newest /clock published
        self._tf = TFMessage()
        # lockstep: a scan goes out once the first odometry at or after its stamp is out and the nodes are done with
        # that step (the controllers' ticks on it), so its consumers find tf at its stamp without waiting for a step
        # that cannot come, and every controller tick sees the scans of the steps before its own, none of its own
        self._odom_stamp_s: Dict[str, float] = {}  # robot -> [s] newest odometry published
        self._scans_waiting: Dict[str, List[ScanReading]] = {}  # robot -> scans newer than its odometry
        self._scans_ready: List[ScanReading] = []  # to go out after this step's holds
        self.settle_s = options.lockstep_settle_s
        if self.lockstep is not None:
            self._holds_subscriber = rospy.Subscriber(HOLDS_TOPIC, LockstepHold, self._on_hold,
                                                      queue_size=HOLDS_QUEUE, tcp_nodelay=True)
        self.teleport_service = rospy.Service("~teleport", Teleport, self._on_teleport)
        self._start_world_requested = False  # from the service thread to the stepping thread
        self.start_world_service = rospy.Service("~start_world", Trigger, self._on_start_world)

    # -- commands and holds (ROS threads) ----------------------------------------------------------
    def _on_hold(self, msg: LockstepHold) -> None:
        if self.lockstep is None:
            return
        try:
            self.lockstep.update(msg.participant, msg.holding, msg.topic, msg.stamp_s, sent_topic=msg.sent_topic,
                                 sent_stamp_s=msg.sent_stamp_s, received_topic=msg.received_topic,
                                 received_stamp_s=msg.received_stamp_s)
        except ConfigError as err:
            rospy.logwarn_throttle(5.0, f"sim: lockstep hold ignored: {err}")

    def _queue_command(self, robot: str, msg: Any) -> None:
        """A Twist, or in lockstep mode a TwistStamped, which the barrier is told of once it is queued."""
        if not isinstance(msg, TwistStamped):
            with self._lock:
                self._pending[robot] = (msg.linear.x, msg.angular.z)
            return
        lin, ang = msg.twist.linear, msg.twist.angular
        problem = twist_problem((lin.x, lin.y, lin.z), (ang.x, ang.y, ang.z))
        v, w = (0.0, 0.0) if problem is not None else (lin.x, ang.z)
        stamp_s = msg.header.stamp.to_sec()
        with self._lock:
            if self._command_order[robot].admit(stamp_s, v != 0.0 or w != 0.0):
                self._pending[robot] = (v, w)
        if problem is not None:
            rospy.logerr_throttle(1.0, f"sim: {robot}: {problem}: the robot stops")
        io = self.robots.get(robot)  # (None only for a message during construction: no hold waits for it yet)
        if self.lockstep is not None and io is not None:
            self.lockstep.received(io.sub_cmd.resolved_name, stamp_s)

    def _on_teleport(self, request: TeleportRequest) -> TeleportResponse:
        """Service thread: queue the teleport for the stepping thread and wait (bounded) for its result."""
        job = _TeleportRequest(request.robot, Pose2D(request.x, request.y, request.yaw))
        with self._lock:
            self._teleports.append(job)
        if not job.done.wait(TELEPORT_WAIT_S):
            return TeleportResponse(ok=False, message=f"the simulation did not step within {TELEPORT_WAIT_S} s")
        if job.ok:
            rospy.loginfo("sim: t = %.2f s: %s", self.sim.time, job.message)
        else:
            rospy.logwarn("sim: teleport refused: %s", job.message)
        return TeleportResponse(ok=job.ok, message=job.message)

    def _on_start_world(self, _request: TriggerRequest) -> TriggerResponse:
        """Service thread: the stepping thread starts the world's script before its next step."""
        with self._lock:
            if self.sim.world_start_s is not None or self._start_world_requested:
                return TriggerResponse(success=False, message="the world's script has started already")
            self._start_world_requested = True
        return TriggerResponse(success=True, message=f"the world's script starts after t = {self.sim.time:.3f} s")

    def _apply_teleports(self) -> None:
        with self._lock:
            jobs, self._teleports = self._teleports, []
        for job in jobs:
            try:
                job.message, job.ok = self.sim.teleport(job.robot, job.pose), True
            except ConfigError as err:
                job.message = str(err)
            job.done.set()

    def _apply_commands(self) -> None:
        if self._start_world_requested:
            with self._lock:
                self._start_world_requested = False
            self.sim.start_world()
            rospy.loginfo(f"sim: t = {self.sim.time:.3f} s: the world's script starts (people, events, fresh noise)")
            if self.publish_initial_pose:  # the robots' initial poses again, as an operator gives them at a start
                stamp = stamp_of(self.sim.time)
                for name, io in self.robots.items():
                    io.publish_initial_pose(self.sim.truth_pose(name), stamp)
                    if self.lockstep is not None:  # a localizer holds until it has applied it
                        self.lockstep.published(io.pub_initial_pose.resolved_name, stamp.to_sec())
        if self._teleports:
            self._apply_teleports()
        if not self._pending:
            return
        with self._lock:
            pending, self._pending = self._pending, {}
        for robot, (v, w) in pending.items():
            notice = self.sim.command(robot, v, w)
            if notice is not None:
                self._on_notice(notice)

    def _render_cameras_watched(self) -> None:
        """A camera renders only while something subscribes to its image or depth topic."""
        for name, io in self.robots.items():
            if io.pub_image is not None and io.pub_depth is not None:
                watched = io.pub_image.get_num_connections() + io.pub_depth.get_num_connections() > 0
                self.sim.set_camera_wanted(name, watched)

    # -- main loop --------------------------------------------------------------------------------
    def run(self) -> None:
        """Step and publish until shutdown (or ``duration``); logs the achieved real-time factor."""
        static = [tf for io in self.robots.values() for tf in io.static_transforms()]
        self.pub_tf_static.publish(TFMessage(transforms=static))
        for name, io in self.robots.items():
            io.pub_state.publish(io.state)
            if self.publish_initial_pose:
                io.publish_initial_pose(self.sim.truth_pose(name))
        self._publish_clock(0.0)
        sim = self.sim
        next_clock = self.clock_period
        wall_start = anchor_wall = time.monotonic()
        anchor_sim = 0.0
        next_stats = wall_start + STATS_PERIOD_S
        next_camera_check = wall_start
        while not rospy.is_shutdown():
            self._apply_commands()
            if time.monotonic() >= next_camera_check:  # not every physics step: subscribers come and go slowly
                self._render_cameras_watched()
                next_camera_check = time.monotonic() + CAMERA_CHECK_PERIOD_S
            readings = sim.step()
            t = sim.time
            start = time.perf_counter()
            if t >= next_clock - 1e-9:
                self._publish_clock(t)
                next_clock += self.clock_period
            for reading in readings:
                self._handlers[type(reading)](reading)
            self.publish_cost += time.perf_counter() - start
            if self.lockstep is not None:
                self._wait_for_participants(t)  # the schedule catches up after a wait (up to MAX_LAG_S behind)
            if self.duration and t >= self.duration - 1e-9:
                break
            now = time.monotonic()
            if self.rtf > 0.0:
                ahead = anchor_wall + (t - anchor_sim) / self.rtf - now
                if ahead > PACE_SLACK_S:
                    time.sleep(ahead)
                elif ahead < -MAX_LAG_S:
                    anchor_wall, anchor_sim = now, t
                    self.lag_resets += 1
            if now >= next_stats:
                next_stats = now + STATS_PERIOD_S
                rospy.loginfo(self.stats(now - wall_start))
        rospy.loginfo(self.stats(time.monotonic() - wall_start))

    def stats(self, wall: float) -> str:
        """One line: simulated time, achieved real-time factor and where the wall time went."""
        costs = dict(self.sim.costs, ros_publishing=self.publish_cost)
        parts = ", ".join(f"{k} {v:.2f} s" for k, v in costs.items())
        rtf = self.sim.time / wall if wall > 0 else 0.0
        behind = f"; fell behind the requested rtf {self.lag_resets} times" if self.lag_resets else ""
        lockstep = f"; {self.lockstep.stats.line()}" if self.lockstep is not None else ""
        return (f"sim: t = {self.sim.time:.1f} s in {wall:.1f} s wall, real-time factor {rtf:.2f}; cost: {parts}"
                f"{behind}{lockstep}")

    def _wait_for_participants(self, t: float) -> None:
        """Lockstep, after a step's readings: wait for the holds that have come, then publish the scans that are
        ready and wait for their holds."""
        barrier = self.lockstep
        assert barrier is not None
        barrier.published(CLOCK_TOPIC, stamp_of(t).to_sec())  # as the nodes will read it
        self._wait_for_holds(barrier, t)
        if self._scans_ready:
            scans, self._scans_ready = self._scans_ready, []
            for scan in scans:
                self._publish_scan(scan)
            self._wait_for_holds(barrier, t)

    def _wait_for_holds(self, barrier: LockstepBarrier, t: float) -> None:
        """Once a hold has come, publish /clock at ``t`` (its node sees the time of what it waits for), wait until
        every such hold is replaced, then ``settle_s`` more (what the nodes sent before letting go lands first)."""
        if not barrier.blocking():
            return
        if self._clock_s < t:
            self._publish_clock(t)
        for hold in barrier.wait(rospy.is_shutdown):
            rospy.logwarn(f"sim: t = {t:.3f} s: lockstep hold of {hold.describe()} not replaced within "
                          f"{barrier.timeout_s:g} s of wall time: dropped, the simulation goes on")
        if self.settle_s > 0.0:
            time.sleep(self.settle_s)

    # -- publishing ---------------------------------------------------------------------------------
    def _publish_clock(self, t: float) -> None:
        self._clock.clock = stamp_of(t)
        self._clock_s = t
        self.pub_clock.publish(self._clock)

    def _on_odometry(self, r: OdometryReading) -> None:
        io = self.robots[r.robot]
        stamp = stamp_of(r.stamp)
        odom = io.odom
        odom.header.stamp = stamp
        _set_pose(odom.pose.pose, r.odom_pose)
        odom.twist.twist.linear.x = r.linear
        odom.twist.twist.angular.z = r.angular
        io.pub_odom.publish(odom)
        if self.lockstep is not None:
            self.lockstep.published(io.pub_odom.resolved_name, stamp.to_sec())
        truth = io.truth
        truth.header.stamp = stamp
        _set_pose(truth.pose.pose, r.truth_pose)
        truth.twist.twist.linear.x = r.truth_linear
        truth.twist.twist.angular.z = r.truth_angular
        io.pub_truth.publish(truth)
        frames = [(io.tf_odom_base, r.odom_pose)]
        if self.publish_map_odom:
            frames.insert(0, (io.tf_map_odom, r.map_to_odom))
        for tf, pose in frames:
            tf.header.stamp = stamp
            tf.transform.translation.x, tf.transform.translation.y = pose.x, pose.y
            set_yaw(tf.transform.rotation, pose.yaw)
        self._tf.transforms = [tf for tf, _ in frames]
        self.pub_tf.publish(self._tf)
        if self.lockstep is not None:
            self._odom_stamp_s[r.robot] = r.stamp
            self._scans_ready.extend(self._scans_waiting.pop(r.robot, []))

    def _on_scan(self, r: ScanReading) -> None:
        if self.lockstep is None:
            self._publish_scan(r)
        elif self._odom_stamp_s.get(r.robot, -math.inf) < r.stamp:
            self._scans_waiting.setdefault(r.robot, []).append(r)
        else:
            self._scans_ready.append(r)

    def _publish_scan(self, r: ScanReading) -> None:
        io = self.robots[r.robot]
        if io.pub_scan is None:
            return
        io.scan.header.stamp = stamp_of(r.stamp)
        io.scan.ranges = r.ranges.tolist()
        io.pub_scan.publish(io.scan)
        if self.lockstep is not None:
            self.lockstep.published(io.pub_scan.resolved_name, io.scan.header.stamp.to_sec())

    def _on_image(self, r: ImageReading) -> None:
        io = self.robots[r.robot]
        if io.pub_image is None or io.pub_info is None or io.pub_depth is None or io.pub_depth_info is None:
            return
        stamp = stamp_of(r.stamp)
        io.image.header.stamp = io.info.header.stamp = io.depth.header.stamp = stamp
        io.depth.data = r.depth.tobytes()  # float32 (ImageReading)
        io.pub_depth.publish(io.depth)
        io.pub_depth_info.publish(io.info)
        io.image.data = r.rgb.tobytes()
        io.pub_image.publish(io.image)
        io.pub_info.publish(io.info)
        if self.lockstep is not None:
            self.lockstep.published(io.pub_image.resolved_name, stamp.to_sec())
            self.lockstep.published(io.pub_depth.resolved_name, stamp.to_sec())

    def _on_bumper(self, r: BumperReading) -> None:
        io = self.robots[r.robot]
        if io.pub_create is not None:
            msg = CreateBumper()
            msg.header.stamp = stamp_of(r.stamp)
            msg.header.frame_id = io.frame_base
            msg.is_left_pressed = r.pressed["left"]
            msg.is_right_pressed = r.pressed["right"]
            io.pub_create.publish(msg)
        if not r.changed:
            return
        if io.pub_kobuki is not None:
            for zone in r.changed:
                event = BumperEvent(bumper=KOBUKI_CODES[zone], state=int(r.pressed[zone]))
                io.pub_kobuki.publish(event)
        io.state.header.stamp = stamp_of(r.stamp)
        io.state.header.frame_id = io.frame_base
        io.state.pressed = [r.pressed[z] for z in io.state.zones]
        io.pub_state.publish(io.state)
        if self.lockstep is not None:  # bumper_relay holds on it
            self.lockstep.published(io.pub_state.resolved_name, io.state.header.stamp.to_sec())

    def _on_contact(self, r: ContactReading) -> None:
        msg = SimEvent()
        msg.header.stamp = stamp_of(r.stamp)
        msg.header.frame_id = self.robots[r.robot].map_frame
        msg.kind = SimEvent.CONTACT_BEGIN if r.begin else SimEvent.CONTACT_END
        msg.robot, msg.other, msg.other_kind, msg.zones = r.robot, r.other, r.other_kind, list(r.zones)
        msg.position.x, msg.position.y, msg.position.z = r.point
        verb = "touches" if r.begin else "no longer touches"
        where = f" (bumper {', '.join(r.zones)})" if r.zones else ""
        msg.detail = f"{r.robot or 'robot'} {verb} {r.other_kind} {r.other}{where}"
        self.robots[r.robot].pub_events.publish(msg)

    def _on_world_event(self, r: WorldEventReading) -> None:
        msg = SimEvent(kind=SimEvent.WORLD_EVENT, other=r.target, other_kind=r.action, detail=r.detail)
        msg.header.stamp = stamp_of(r.stamp)
        msg.position.x = msg.position.y = msg.position.z = math.nan
        rospy.loginfo("sim: t = %.2f s: %s", r.stamp, r.detail)
        self.pub_world_events.publish(msg)

    def _on_notice(self, r: CommandNotice) -> None:
        log = rospy.loginfo if r.kind == "timeout" else rospy.logwarn
        log("sim: %s: %s", r.robot or "robot", r.detail)
        msg = SimEvent(kind=SimEvent.COMMAND, robot=r.robot, other_kind=r.kind, detail=r.detail)
        msg.header.stamp = stamp_of(r.stamp)
        msg.position.x = msg.position.y = msg.position.z = math.nan
        self.robots[r.robot].pub_events.publish(msg)


class _TeleportRequest:
    """One teleport asked through the service, done by the stepping thread."""

    def __init__(self, robot: str, pose: Pose2D) -> None:
        self.robot = robot
        self.pose = pose
        self.done = threading.Event()
        self.ok = False
        self.message = ""


def _set_pose(pose: Any, p: Pose2D) -> None:
    pose.position.x, pose.position.y = p.x, p.y
    set_yaw(pose.orientation, p.yaw)


def build_simulation() -> Tuple[Simulation, BridgeOptions]:
    """Read and validate every parameter, load the world and profiles, create the simulation."""
    world = load_world(param_str("~world"))
    spawns = resolve_spawns(world, rospy.get_param("~robots", ""))
    drift_xy = param_float("~drift_xy", 0.0, 0.0, 10.0)
    drift_yaw = param_float("~drift_yaw", 0.0, 0.0, math.pi)
    drift = (
        LocalizationDrift(drift_xy, drift_yaw, param_float("~drift_tau", 10.0, 0.01, 1e6))
        if drift_xy > 0.0 or drift_yaw > 0.0
        else None
    )
    options = BridgeOptions(
        rtf=param_float("~rtf", 1.0, 0.0, 1000.0),
        clock_rate=param_float("~clock_rate", 100.0, 1.0, 10000.0),
        map_frame=param_str("~map_frame", "map"),
        duration=param_float("~duration", 0.0, 0.0, 1e9),
        publish_map_odom=param_bool("~publish_map_odom", True),
        lockstep=lockstep_enabled(),
        lockstep_timeout_s=param_float("~lockstep_timeout", 5.0, 0.01, 3600.0),
        lockstep_settle_s=param_float("~lockstep_settle", 0.002, 0.0, 1.0),
    )
    options = replace(options, publish_initial_pose=param_bool("~publish_initial_pose", not options.publish_map_odom))
    if not options.map_frame:
        raise ConfigError("parameter ~map_frame must not be empty")
    sensors = SensorOptions(
        lidar=param_bool("~lidar", True), camera=param_bool("~camera", True), bumpers=param_bool("~bumpers", True)
    )
    gui = param_bool("~gui", False)
    world_start = param_str("~world_start", "at_once", choices=("at_once", "on_request"))
    sim = Simulation(
        world,
        spawns,
        seed=param_int("~seed", 0, 0),
        physics_rate=param_float("~physics_rate", 240.0, 30.0, 5000.0),
        sensors=sensors,
        drift=drift,
        gui=gui,
        world_started=world_start == "at_once",
    )
    if gui and not sim.gui_active:
        rospy.logwarn("sim: ~gui requested but no display (DISPLAY unset): running headless")
    return sim, options


def main() -> int:
    init_node(NODE_NAME)
    try:
        sim, options = build_simulation()
    except ConfigError as err:
        rospy.logfatal("sim: %s", err)
        print(f"[sim] ERROR: {err}", file=sys.stderr)
        return 2
    try:
        bridge = SimBridge(sim, options)
        names = ", ".join(f"{n or '(global)'} ({sim.robot(n).profile.name})" for n in sim.robot_names)
        rospy.loginfo("sim: world %s, robots %s, seed %d, rtf %s%s", sim.world.name, names, sim.seed, options.rtf,
                      ", lockstep" if options.lockstep else "")
        bridge.run()
    finally:
        sim.close()
    return 0
