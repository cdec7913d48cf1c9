"""``pure_pursuit_path`` / ``pure_pursuit_topic``: regulated pure pursuit controllers as action servers.

``pure_pursuit_path`` serves FollowPath (the path is in the goal); ``pure_pursuit_topic`` serves FollowTopic
(it follows the newest nav_msgs/Path on the topic named in the goal, e.g. a follow server's ``plan``).
Both publish geometry_msgs/TwistStamped on ``cmd_vel_stamped`` (see ``twist_relay`` for a Twist driver), and
the robot's footprint on ``footprint`` (geometry_msgs/PolygonStamped, latched and sent again every 0.2 s, in
``~robot_base_frame``: the circle of the local costmap's ``robot_radius``,
:func:`flex_nav.nav.footprint.circle_footprint`), for RViz.

Control ticks are synchronised to odometry: a tick runs as soon as a new ``odom`` message has arrived and
one period of ``~controller_frequency`` has passed since the previous tick (so the rate never exceeds it,
and odometry slower than it is answered at once), and at the latest two periods after the previous tick
even without odometry (so stale sensors are noticed). The robot pose is the odometry pose
carried into ``~global_frame`` by tf (``global_frame -> odom frame``); the path is carried into
``~global_frame`` when it arrives. The local costmap ``~local_costmap/`` (rolling window from ``scan`` by
default, see :mod:`flex_nav.ros.costmap_ros`) feeds pure pursuit's obstacle regulation and collision check.

Safety (see :class:`flex_nav.nav.control.controller.SafeFollower`): empty path, path in an unknown frame, bad pose,
stale ``odom`` or scan (``~sensor_timeout`` [s]; a zero twist at once, the goal aborted only if the sensor is not
fresh again within ``~sensor_grace`` [s] more, 0 by default), a global-frame transform older than
``~localization_timeout`` [s] (1.0; 0: off; static transforms have no age), an obstacle ahead for
``~collision_timeout`` [s], any exception in the control loop, the node that sent the goal gone for
``~client_timeout`` [s] (2.0; 0: off; see :mod:`flex_nav.ros.goal_server`), no heartbeat from the operator side for
``~heartbeat_timeout`` [s of wall time] (0: off, the default; :mod:`flex_nav.ros.heartbeat`), ROS time moving
backwards (a restarted simulation: nothing computed on the old timeline is executed) -> zero twist and the goal
aborted with the reason. ROS time standing still for ``~sensor_timeout`` of wall time (the simulator paused or
crashed) -> one zero twist, then no command until ROS time moves again (the goal goes on then). Control is paced on
ROS time (:class:`flex_nav.ros.ros_clock.RosClock`). In a lockstep simulation (``/lockstep``,
:mod:`flex_nav.ros.lockstep`) a goal's ticks hold the simulator at the first odometry stamped a period after the
previous tick, until the tick's command is out, and a standing ROS time is no stall. A cancel publishes a zero
twist from the cancel callback itself (before it returns), and no later command of that goal can follow it; a newer
goal replacing the current one also starts from a zero twist. A FollowTopic goal naming an illegal topic (empty,
``..``, blanks) aborts at once. At the end of a path the robot turns in place to the last pose's yaw
(``pure_pursuit/use_final_heading``, within ``pure_pursuit/yaw_goal_tolerance`` [rad]) unless the goal sets
``ignore_final_heading``.

Parameters (private): ``global_frame`` ("map"), ``robot_base_frame`` ("base_footprint"),
``controller_frequency`` [Hz] (20), ``sensor_timeout`` [s] (0.5), ``sensor_grace`` [s] (0),
``collision_timeout`` [s] (2.0),
``client_timeout`` [s] (2.0), ``localization_timeout`` [s] (1.0), ``transform_timeout`` [s] (0.2),
``topic_timeout`` [s] (2.0, FollowTopic: wait for the first Path), ``feedback_frequency`` [Hz] (5),
``heartbeat_timeout`` [s of wall time] (0: off),
``blocked_distance`` [m] (0: off; an obstacle on the path this far ahead aborts the goal with a reason starting
``blocked``), ``blocked_timeout`` [s] (0.5), ``yield_to_people`` (false; true: track moving obstacles in the
scan and give way to them, ``yielding/*`` and ``people_tracker/*``, see
:mod:`flex_nav.ros.moving_obstacles_ros`; the service ``~people_tracker/forget`` then makes the tracker start
afresh), ``pure_pursuit/*``
(:class:`flex_nav.nav.control.pure_pursuit.PurePursuitParams` by name; unknown names are rejected),
``social_distance/enabled`` (false; true: keep ``social_distance/min_distance_m`` (0.3 m) between the footprint
and every tracked person while moving, slowing from ``slow_distance_m``; the other fields of
:class:`flex_nav.nav.control.social_distance.SocialParams` by name; tracks people as ``yield_to_people`` does;
with both, ``yielding/comfort_margin_m`` defaults to ``min_distance_m``: a walker's way is hurried across rather
than crossed with less room).
"""

from __future__ import annotations

import enum
import math
import threading
import time
from typing import Optional, Tuple

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import Point32, PolygonStamped, TwistStamped
from nav_msgs.msg import Odometry

from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.nav.control.clock_watch import ClockChange, ClockWatch
from flex_nav.nav.control.controller import Decision, LocalCostmap, Outcome, SafeFollower, no_tracks, warm_up
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.footprint import circle_footprint
from flex_nav.nav.planar import transform_poses
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.nodes.follow_base import FollowNode, GoalPath, GoalSource, Pose2D, bad_path
from flex_nav.ros.costmap_ros import CostmapROS
from flex_nav.ros.frames import TfSource, frame_pose, path_in_frame
from flex_nav.ros.goal_server import GoalOutcome, GoalTicket
from flex_nav.ros.heartbeat import HeartbeatListener
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.moving_obstacles_ros import MovingObstaclesROS, social_rule, yield_rule
from flex_nav.ros.params import param_bool, param_float, param_str
from flex_nav.ros.private_ns import private_name
from flex_nav.ros.proxies import SHUTDOWN_DRAIN_S, drain_publisher
from flex_nav.ros.ros_clock import RosClock
from flex_nav.ros.topic_path import TopicPath, TopicPaths

PARAMETERS = (
    "global_frame", "robot_base_frame", "controller_frequency", "sensor_timeout", "sensor_grace", "collision_timeout",
    "transform_timeout", "topic_timeout", "feedback_frequency", "local_costmap", "pure_pursuit",
    "blocked_distance", "blocked_timeout", "yield_to_people", "yielding", "people_tracker", "client_timeout",
    "localization_timeout", "heartbeat_timeout", "social_distance",
)
CLOCK_CHECK_PERIOD_S = 0.05  # [s] wall: longest wait in the control loop before ROS time is looked at again
TICK_SLACK_S = 1e-6  # [s] lockstep: odometry this much before a tick is due still starts it


class Wake(enum.Enum):
    """Why the control loop's wait ended."""

    TICK = "tick"
    CANCELLED = "cancelled"
    STALLED = "stalled"
    JUMPED_BACK = "jumped back"
    LINK_LOST = "link lost"


FOOTPRINT_PERIOD_S = 0.2  # [s] (ROS time) the footprint is published again this often, for RViz


def footprint_msg(radius_m: float, base_frame: str) -> PolygonStamped:
    """The footprint polygon of a round base of ``radius_m`` [m] in ``base_frame`` (stamp 0: valid at any time)."""
    msg = PolygonStamped()
    msg.header.frame_id = base_frame
    msg.polygon.points = [Point32(x=float(x), y=float(y), z=0.0) for x, y in circle_footprint(radius_m)]
    return msg


def pursuit_params(raw: dict, costmap: CostmapROS) -> PurePursuitParams:
    """PurePursuitParams from ``~pure_pursuit``; ``inscribed_radius`` and ``inflation_cost_scaling_factor``
    come from the local costmap (they must describe its inflation), and a different value given for
    either is a ConfigError rather than a silently wrong obstacle regulation."""
    name = rospy.resolve_name(private_name("~pure_pursuit"))
    values = dict(raw)
    for key, own in (("inscribed_radius", costmap.inflation.inscribed_radius),
                     ("inflation_cost_scaling_factor", costmap.inflation.cost_scaling_factor)):
        given = values.setdefault(key, own)
        if isinstance(given, (int, float)) and not isinstance(given, bool) and abs(float(given) - own) > 1e-9:
            raise ConfigError(f"{name}/{key} = {given!r} differs from the local costmap's value {own!r}; "
                              f"leave it out (it is taken from ~local_costmap/)")
    try:
        return PurePursuitParams.from_mapping(values)
    except ConfigError as err:
        raise ConfigError(f"{name}: {err}") from err


class PurePursuitController(FollowNode):
    """One controller node, serving FollowPath or FollowTopic as ``source`` says."""

    def __init__(self, source: GoalSource, tf_buffer: Optional[tf2_ros.Buffer] = None) -> None:
        """``tf_buffer``: one shared with other components of the process (None: a buffer of its own)."""
        super().__init__(source, PARAMETERS)
        self.global_frame = param_str("~global_frame", "map")
        self.robot_base_frame = param_str("~robot_base_frame", "base_footprint")
        frequency = param_float("~controller_frequency", 20.0, 0.5, 1000.0)
        self.period_s = 1.0 / frequency
        self.transform_timeout_s = param_float("~transform_timeout", 0.2, 0.0, 10.0)
        self.localization_timeout_s = param_float("~localization_timeout", 1.0, 0.0, 600.0)
        self.topic_timeout_s = param_float("~topic_timeout", 2.0, 0.0, 600.0)
        self.feedback_period_s = 1.0 / param_float("~feedback_frequency", 5.0, 0.1, 1000.0)
        raw = rospy.get_param(private_name("~pure_pursuit"), {})
        if not isinstance(raw, dict):
            raise ConfigError(
                f"parameter {rospy.resolve_name(private_name('~pure_pursuit'))} must be a dictionary, got {raw!r}")
        self.tf = TfSource(tf_buffer)
        self.tf_buffer = self.tf.buffer
        self.costmap = CostmapROS("local_costmap", self.tf_buffer, rolling_default=True)
        params = pursuit_params(raw, self.costmap)
        warm_up(params)
        sensors = ["odom", "scan"] if self.costmap.scan_topic else ["odom"]
        yield_to_people = param_bool("~yield_to_people", False)
        social = social_rule()
        self.people = (MovingObstaclesROS(self.tf_buffer, self.global_frame)
                       if yield_to_people or social is not None else None)
        yielding = (yield_rule(self.costmap.inflation.inscribed_radius, params.desired_linear_vel, social)
                    if yield_to_people else None)
        if self.people is not None and yielding is not None:
            self.people.share_lanes(yielding)
        sensor_timeout_s = param_float("~sensor_timeout", 0.5, 0.01, 600.0)
        self.clock = RosClock(poll_s=min(self.period_s / 10.0, 0.005))
        self.lockstep = LockstepParticipant("control")  # a goal's ticks hold a lockstep simulation
        # the node's watch: jumps between goals count; in lockstep ROS time stands while the simulation waits for
        # some node on purpose, and the simulation (the robot) stands with it
        self.clock_watch = ClockWatch(stall_timeout_s=0.0 if self.lockstep.enabled else sensor_timeout_s)
        self.heartbeat = HeartbeatListener(param_float("~heartbeat_timeout", 0.0, 0.0, 3600.0))
        self.follower = SafeFollower(
            params,
            sensors=sensors,
            sensor_timeout_s=sensor_timeout_s,
            collision_timeout_s=param_float("~collision_timeout", 2.0, 0.0, 600.0),
            nominal_period_s=self.period_s,
            start_s=rospy.get_time(),
            blocked_distance_m=param_float("~blocked_distance", 0.0, 0.0, 100.0),
            blocked_timeout_s=param_float("~blocked_timeout", 0.5, 0.0, 600.0),
            yielding=yielding,
            sensor_grace_s=param_float("~sensor_grace", 0.0, 0.0, 600.0),
            social=social,
            footprint=(circle_footprint(self.costmap.inflation.inscribed_radius)
                       if social is not None and self.costmap.inflation.inscribed_radius > 0.0 else None),
        )
        self._odom: Optional[Odometry] = None
        self._odom_count = 0
        self._odom_stamp_s = -math.inf  # [s] the newest odometry's stamp
        self._publish_lock = threading.Lock()
        self._topics = TopicPaths(self._wake, self.clock, LockstepParticipant("paths"))  # reports each Path taken in
        self.cmd_publisher = rospy.Publisher("cmd_vel_stamped", TwistStamped, queue_size=1, tcp_nodelay=True)
        self.footprint_publisher = rospy.Publisher("footprint", PolygonStamped, queue_size=1, latch=True)
        if self.costmap.inflation.inscribed_radius > 0.0:  # a point robot (robot_radius 0) has no outline to draw
            footprint = footprint_msg(self.costmap.inflation.inscribed_radius, self.robot_base_frame)
            self.footprint_publisher.publish(footprint)
            # RViz's Polygon display places a polygon once, where its frame is when it arrives: sent once, the
            # footprint stayed where the robot started; sent again it follows the robot
            self._footprint_timer = rospy.Timer(rospy.Duration(FOOTPRINT_PERIOD_S),
                                                lambda _event: self.footprint_publisher.publish(footprint))
        self._shut_down = False  # set by the shutdown hook: no moving command after its zero twist
        rospy.on_shutdown(self._on_shutdown)
        self.odom_subscriber = rospy.Subscriber("odom", Odometry, self._on_odom, queue_size=1, tcp_nodelay=True)
        self.costmap.serve_clear_costmap(self.name + "/clear_costmap")
        spec = self._serve(on_error=self._on_error)
        rospy.loginfo(f"{self.name}: pure pursuit on {spec.name} goals at {frequency:.1f} Hz in '{self.global_frame}'")
        if social is not None:
            rospy.loginfo(f"{self.name}: social distance on: {social.params} (footprint: circle of "
                          f"{self.costmap.inflation.inscribed_radius:.3f} m)")

    # ------------------------------------------------------------------ inputs
    def _on_odom(self, msg: Odometry) -> None:
        with self._wake:
            self._odom = msg
            self._odom_count += 1
            self._odom_stamp_s = msg.header.stamp.to_sec()
            self.follower.watchdog.saw("odom", rospy.get_time())
            self._wake.notify_all()

    def _robot_pose(self) -> Pose2D:
        """Odometry pose carried into the global frame (raises NotReadyError without odometry or tf)."""
        odom = self._odom
        if odom is None:
            raise NotReadyError("robot pose unknown: no odometry received yet")
        p, q = odom.pose.pose.position, odom.pose.pose.orientation
        local = np.array([[p.x, p.y, yaw_of_quaternion(q.x, q.y, q.z, q.w)]])
        try:
            tx, ty, tyaw = frame_pose(self.tf_buffer, self.global_frame, odom.header.frame_id,
                                      self.transform_timeout_s, self.localization_timeout_s)
        except (ConfigError, NotReadyError) as err:
            raise NotReadyError(f"robot pose unknown: odometry frame: {err}") from err
        x, y, yaw = transform_poses(local, tx, ty, tyaw)[0]
        return (float(x), float(y), float(yaw))

    def _velocity(self) -> Tuple[float, float]:
        odom = self._odom
        if odom is None:
            return (0.0, 0.0)
        return (odom.twist.twist.linear.x, odom.twist.twist.angular.z)

    def _local_costmap(self) -> LocalCostmap:
        return self.costmap.snapshot()

    # ------------------------------------------------------------------ output
    def _publish(self, ticket: Optional[GoalTicket], v: float, w: float) -> bool:
        """Publish (v, w); a non-zero command only while ``ticket`` is the current goal. True if published."""
        with self._publish_lock:
            moving = v != 0.0 or w != 0.0
            if moving and (ticket is None or self._shut_down or not self.server.is_current(ticket)):
                return False
            msg = TwistStamped()
            msg.header.stamp = rospy.Time.now()
            msg.header.frame_id = self.robot_base_frame
            msg.twist.linear.x, msg.twist.angular.z = v, w
            self.cmd_publisher.publish(msg)
            self.lockstep.sent(self.cmd_publisher.resolved_name, msg.header.stamp.to_sec())
            return True

    def _on_shutdown(self) -> None:
        """The node is stopping: a zero twist, sent before rospy closes the connections; nothing moves after."""
        with self._publish_lock:
            self._shut_down = True
        self._publish(None, 0.0, 0.0)
        drain_publisher(self.cmd_publisher, time.monotonic() + SHUTDOWN_DRAIN_S)

    def _on_cancel(self, ticket: GoalTicket, replaced: bool) -> None:
        self._publish(None, 0.0, 0.0)
        super()._on_cancel(ticket, replaced)
        rospy.loginfo(f"{self.name}: {'replaced' if replaced else 'cancelled'}; zero twist published")

    def _on_error(self, _ticket: GoalTicket, _error: BaseException) -> None:
        self._publish(None, 0.0, 0.0)
        self.follower.stop()

    # ------------------------------------------------------------------ goals
    def _end(self, ticket: GoalTicket, outcome: GoalOutcome, reason: str, pose: Optional[Pose2D] = None) -> None:
        """Zero twist and the follower stopped first; without ``pose``, the result's is the odometry pose."""
        self._publish(None, 0.0, 0.0)
        self.follower.stop()
        if pose is None:
            try:
                pose = self._robot_pose()
            except NotReadyError:
                pose = None
        super()._end(ticket, outcome, reason, pose)

    def _pursue(self, ticket: GoalTicket, first: GoalPath) -> None:
        if first.topic is None:  # a goal's own path is taken now; a topic's Paths by the control loop
            try:
                self.follower.set_path(path_in_frame(self.tf_buffer, first.msg, self.global_frame,
                                                     self.transform_timeout_s),
                                       final_heading=not ticket.goal.ignore_final_heading)
            except (ConfigError, NotReadyError) as err:
                self._end(ticket, GoalOutcome.ABORTED, bad_path(first.topic, err))
                return
        try:
            self._control(ticket, first.topic)
        finally:
            self.lockstep.release()

    def _wait_for_tick(self, ticket: GoalTicket, next_due_s: float, used_odom: int) -> Wake:
        """Wait until a tick is due (``next_due_s`` [s ROS time] passed and new odometry, or one period later
        without), the goal is cancelled, or ROS time or the operator link fails. In lockstep the simulation holds
        at the first odometry stamped at or after ``next_due_s``, and the tick waits for that one."""
        latest_by_s = next_due_s + self.period_s
        self.lockstep.hold_topic(self.odom_subscriber.resolved_name, next_due_s)
        fresh_from_s = next_due_s if self.lockstep.enabled else -math.inf  # [s] the odometry a tick waits for
        with self._wake:
            while True:
                if ticket.cancelled.is_set() or rospy.is_shutdown():
                    return Wake.CANCELLED
                now_s = self.clock.now()
                change = self.clock_watch.observe(now_s, time.monotonic())
                if change is ClockChange.JUMPED_BACK:
                    return Wake.JUMPED_BACK
                if change is ClockChange.STALLED:
                    return Wake.STALLED
                if self.heartbeat.lost():
                    return Wake.LINK_LOST
                if not self.clock_watch.stalled and (
                        (now_s >= next_due_s and self._odom_count != used_odom
                         and self._odom_stamp_s >= fresh_from_s) or now_s >= latest_by_s):
                    return Wake.TICK
                deadline_s = next_due_s if now_s < next_due_s else latest_by_s
                self._wake.wait(min(self.clock.wall_wait_s(deadline_s, now_s), CLOCK_CHECK_PERIOD_S))

    def _control(self, ticket: GoalTicket, source: Optional[TopicPath]) -> None:
        used_odom = -1
        used_path = -1
        next_due_s = self.clock.now()
        if self.clock_watch.observe(next_due_s, time.monotonic()) is ClockChange.JUMPED_BACK:
            # time went back while no goal ran (a simulation restarted between goals): this goal is the new
            # timeline's (the goal server forgets the old one's); only the old sensor times go
            self.follower.watchdog.restart(next_due_s)
        last_feedback_s = -math.inf
        self.lockstep.hold_topic(self.odom_subscriber.resolved_name, next_due_s)
        self.server.release_accept(ticket)  # the goal holds on its own now
        while True:
            wake = self._wait_for_tick(ticket, next_due_s, used_odom)
            if wake is Wake.CANCELLED:
                self.follower.stop()
                return
            if wake is Wake.STALLED:
                self._publish(None, 0.0, 0.0)
                self.follower.hold()
                rospy.logerr(f"{self.name}: goal #{ticket.number}: ROS time has not advanced for "
                             f"{self.clock_watch.stall_timeout_s:.2f} s of wall time (simulator paused or gone?); "
                             "zero twist published, no command until it moves again")
                continue
            if wake is Wake.JUMPED_BACK:
                self.follower.watchdog.restart(self.clock.now())
                self._end(ticket, GoalOutcome.ABORTED, f"ROS time moved backwards by {self.clock_watch.jump_s:.2f} s "
                                                       "(a restarted simulation or a looped bag): goal dropped")
                return
            if wake is Wake.LINK_LOST:
                self._end(ticket, GoalOutcome.ABORTED, self.heartbeat.why_lost())
                return
            now_s = self.clock.now()
            with self._wake:
                used_odom = self._odom_count
                path_msg = None
                defer_same_step = self.lockstep.enabled and used_path >= 0  # the goal's first Path at once
                if source is not None and source.new_for_tick(used_path, now_s, defer_same_step):
                    path_msg, used_path = source.msg, source.count
            # from the tick itself: odometry arriving later starts the next one; in lockstep odometry stamped one
            # period on is due (to within TICK_SLACK_S: a stamp is not an exact sum of periods)
            next_due_s = now_s + self.period_s - (TICK_SLACK_S if self.lockstep.enabled else 0.0)
            if path_msg is not None:
                try:
                    self.follower.set_path(path_in_frame(self.tf_buffer, path_msg, self.global_frame,
                                                         self.transform_timeout_s),
                                           final_heading=not ticket.goal.ignore_final_heading)
                except (ConfigError, NotReadyError) as err:
                    self._end(ticket, GoalOutcome.ABORTED, bad_path(source, err))
                    return
            decision = self._tick()
            if decision.outcome is not Outcome.RUNNING:
                succeeded = decision.outcome is Outcome.SUCCEEDED
                self._end(ticket, GoalOutcome.SUCCEEDED if succeeded else GoalOutcome.ABORTED, decision.reason)
                return
            if not self._publish(ticket, decision.v, decision.w):
                self.follower.stop()
                return
            if now_s - last_feedback_s >= self.feedback_period_s:
                last_feedback_s = now_s
                self._report(ticket, decision, source)

    def _tick(self) -> Decision:
        scan_s = self.costmap.last_scan_received_s
        if scan_s is not None and self.costmap.scan_topic:
            self.follower.watchdog.saw("scan", scan_s)
        tracks = self.people.tracks if self.people is not None else no_tracks
        decision = self.follower.tick(rospy.get_time(), self._robot_pose, self._velocity(), self._local_costmap,
                                      tracks)
        if self.people is not None:
            self.people.report(decision.yielded, decision.social)
        return decision

    def _report(self, ticket: GoalTicket, decision: Decision, source: Optional[TopicPath]) -> None:
        """Feedback with the odometry pose (none while it is unknown) and the command just published."""
        try:
            pose = self._robot_pose()
        except NotReadyError:
            return
        self._feedback(ticket, pose, source, (decision.v, decision.w))
