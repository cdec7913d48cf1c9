"""``rosrun flex_nav console [_host:=127.0.0.1] [_port:=8080] [_token:=...]``: the web operator console.

Serves one page and a websocket (:mod:`flex_nav.console.server`, aiohttp) and connects them to every behavior
runner on the master: every ``discovery_period_s`` it asks the master for the topics of type
flex_nav/BehaviorStatus, so namespaced robots (``/robot1/behavior_runner``) are found as they come and go, and
subscribes each runner's ``status``, ``activity``, ``structure``, ``log``, ``transitions``,
``command_feedback`` and ``userdata``; commands validated by the server are published on its ``command`` topic.

The map view: the latched ``~map_topic`` (OccupancyGrid) and, in each runner's namespace (``/robot1`` for
``/robot1/behavior_runner``), ``get_path_server/plan`` and ``follow_path_server/plan`` (nav_msgs/Path),
``scan`` (LaserScan, carried into the map frame by tf), ``particlecloud`` (PoseArray, the localizer's) and the
controllers' tracked people (``pure_pursuit_path/people``, ``pure_pursuit_topic/people``, PoseArray); the
robot's pose is tf's ``map -> <ns>/base_footprint`` every ``pose_period_s`` and its footprint the polygon the
controller latches on ``<ns>/footprint`` (PolygonStamped in the base frame), else the circle of the namespace's
``robot_radius`` parameter. Goals placed on the page are published as PoseStamped on
``<ns>/<goal_topic>``, initial poses as PoseWithCovarianceStamped on ``<ns>/initialpose`` (RViz's covariance).

The obstacle memory: the heavy obstacles the robot's global costmap remembers, latched on
``<ns>/<memory_costmap>/obstacle_memory`` (visualization_msgs/MarkerArray, :mod:`flex_nav.ros.memory_markers`),
are drawn on the map (the newest at most every ``MIN_PERIOD_S["memory"]``, none lost); the page's "forget" calls
``<ns>/<memory_costmap>/clear_obstacle_memory`` (std_srvs/Trigger), waiting ``SERVICE_WAIT_S`` for it to exist.

Parameters (private; unknown names are refused):

- ``~host`` (str, "127.0.0.1"): address to bind. Any address other than a loopback one needs ``~token``.
- ``~port`` (int, 8080): TCP port.
- ``~token`` (str, ""): required on every request when set (open ``http://HOST:PORT/?token=TOKEN`` once); at
  least 16 characters. Anyone on the ROS graph can read parameters: the token guards the web port, not ROS.
- ``~discovery_period_s`` (float, 2.0): how often the master is asked for runners [s].
- ``~max_clients`` (int, 16): pages connected at once.
- ``~map_topic`` (str, "/map"): the occupancy grid shown; its frame is the map view's frame.
- ``~goal_topic`` (str, "move_base_simple/goal"): where a robot's goals go, in its namespace (flex_planner's
  ``goal_topic``).
- ``~pose_period_s`` (float, 0.1): how often each robot's pose is looked up [s].
- ``~memory_costmap`` (str, "get_path_server/global_costmap"): the costmap with the obstacle memory, in each robot's
  namespace.

A bad parameter, a missing token for a non-loopback host or a port that cannot be bound ends the node with
exit status 2 and the reason.
"""

from __future__ import annotations

import asyncio
import math
import os
import shutil
import sys
import threading
import time
import xmlrpc.client
from typing import Any, Callable, Dict, List, Sequence, Tuple

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import PolygonStamped, PoseArray, PoseStamped, PoseWithCovarianceStamped
from nav_msgs.msg import OccupancyGrid, Path
from rospy.numpy_msg import numpy_msg
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String
from std_srvs.srv import Trigger
from visualization_msgs.msg import MarkerArray

from flex_nav.console.commands import RunnerCommand
from flex_nav.console.events import activity_event, feedback_event, log_event, status_event, transition_event
from flex_nav.console.graph import DOT_TIMEOUT_S
from flex_nav.console.mapview import (
    GoalRequest,
    GridGeometry,
    Throttle,
    memory_overlay,
    path_overlay,
    pose_overlay,
    poses_overlay,
    robot_namespace,
    scan_overlay,
)
from flex_nav.console.model import runner_names
from flex_nav.console.server import Console, ServerConfig, is_loopback, serve
from flex_nav.exceptions import ConfigError, FlexNavError, NotReadyError
from flex_nav.msg import (
    BehaviorActivity,
    BehaviorCommand,
    BehaviorCommandFeedback,
    BehaviorLog,
    BehaviorStatus,
    BehaviorTransition,
)
from flex_nav.nav.planar import transform_poses
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.ros.frames import TF_ERRORS
from flex_nav.ros.master_probe import MASTER_CALL_TIMEOUT_S, _TimeoutTransport
from flex_nav.ros.memory_markers import remembered_of_markers
from flex_nav.ros.node import init_node
from flex_nav.ros.params import param_float, param_int, param_str, reject_unknown

PARAMETERS = ("host", "port", "token", "discovery_period_s", "max_clients", "map_topic", "goal_topic",
              "pose_period_s", "memory_costmap")
SERVICE_WAIT_S = 2.0  # [s] how long the clear_obstacle_memory service may take to appear
DEFAULT_RADIUS_M = 0.2  # [m] footprint drawn when the namespace has no robot_radius parameter
INITIAL_POSE_COVARIANCE = (0.25, 0.25, 0.06853891945200942)  # [m^2, m^2, rad^2] x, y, yaw: RViz's 2D Pose Estimate


def published_topics(master_uri: str, caller_id: str, timeout_s: float = MASTER_CALL_TIMEOUT_S
                     ) -> List[Tuple[str, str]]:
    """The master's published ``(topic, type)`` pairs, the call bounded by ``timeout_s`` [s]; NotReadyError if the
    master does not answer."""
    proxy = xmlrpc.client.ServerProxy(master_uri, transport=_TimeoutTransport(timeout_s))
    try:
        reply: Any = proxy.getPublishedTopics(caller_id, "")
    except (OSError, xmlrpc.client.Error) as err:
        raise NotReadyError(f"the master at {master_uri} did not list its topics: {err}") from err
    if not (isinstance(reply, list) and len(reply) == 3 and reply[0] == 1 and isinstance(reply[2], list)):
        raise NotReadyError(f"the master at {master_uri} answered getPublishedTopics with {reply!r:.200}")
    return [(str(t[0]), str(t[1])) for t in reply[2] if isinstance(t, list) and len(t) == 2]


class RunnerLink:
    """The subscriptions to one runner's topics and the publisher of its commands."""

    def __init__(self, name: str, console: Console) -> None:
        self.name = name
        self.publisher = rospy.Publisher(f"{name}/command", BehaviorCommand, queue_size=10)

        def event(make: Callable[[str, Any], Dict[str, Any]]) -> Callable[[Any], None]:
            return lambda msg: console.submit_event(name, make(name, msg))

        topics: Sequence[Tuple[str, type, Callable[[Any], None], int]] = (
            ("status", BehaviorStatus, event(status_event), 10),
            ("activity", BehaviorActivity, event(activity_event), 10),
            ("transitions", BehaviorTransition, event(transition_event), 200),
            ("log", BehaviorLog, event(log_event), 200),
            ("command_feedback", BehaviorCommandFeedback, event(feedback_event), 50),
            ("structure", String, lambda msg: console.submit_structure(name, msg.data), 2),
            ("userdata", String, lambda msg: console.submit_userdata(name, msg.data), 2),
        )
        self.subscribers = [rospy.Subscriber(f"{name}/{topic}", kind, callback, queue_size=size)
                            for topic, kind, callback, size in topics]

    def send(self, command: RunnerCommand) -> None:
        if self.publisher.get_num_connections() == 0:
            raise NotReadyError(f"the runner {self.name} does not listen on {self.name}/command (yet); try again")
        self.publisher.publish(BehaviorCommand(command=command.command, args=list(command.args)))

    def close(self) -> None:
        for sub in self.subscribers:
            sub.unregister()
        self.publisher.unregister()


def _yaw(q: Any) -> float:
    return float(yaw_of_quaternion(q.x, q.y, q.z, q.w))


class MapLink:
    """The map view's subscriptions in one robot's namespace, and its goal and initial pose publishers."""

    def __init__(self, runner: str, console: Console, view: MapView) -> None:
        self.runner = runner
        self.view = view
        self.console = console
        ns = robot_namespace(runner)
        self.base_frame = f"{ns.strip('/')}/base_footprint" if ns else "base_footprint"
        radius = rospy.get_param(f"{ns}/robot_radius", DEFAULT_RADIUS_M)
        self.radius_m = float(radius) if isinstance(radius, (int, float)) else DEFAULT_RADIUS_M
        self.footprint: np.ndarray | None = None  # (x, y) rows [m] in the base frame, from <ns>/footprint
        self._memory_lock = threading.Lock()
        self._memory_pending: Dict[str, Any] | None = None  # the newest memory overlay not yet submitted
        self.goal_publisher = rospy.Publisher(f"{ns}/{view.goal_topic}", PoseStamped, queue_size=1)
        self.pose_publisher = rospy.Publisher(f"{ns}/initialpose", PoseWithCovarianceStamped, queue_size=1)
        self.subscribers = [
            rospy.Subscriber(f"{ns}/get_path_server/plan", Path, self._on_plan, callback_args="global_plan",
                             queue_size=1),
            rospy.Subscriber(f"{ns}/follow_path_server/plan", Path, self._on_plan, callback_args="local_plan",
                             queue_size=1),
            rospy.Subscriber(f"{ns}/scan", LaserScan, self._on_scan, queue_size=1),
            rospy.Subscriber(f"{ns}/footprint", PolygonStamped, self._on_footprint, queue_size=1),
            rospy.Subscriber(f"{ns}/particlecloud", PoseArray, self._on_poses, callback_args="particles",
                             queue_size=1),
            *(rospy.Subscriber(f"{ns}/{controller}/people", PoseArray, self._on_poses, callback_args="people",
                               queue_size=1) for controller in ("pure_pursuit_path", "pure_pursuit_topic")),
            rospy.Subscriber(f"{ns}/{view.memory_costmap}/obstacle_memory", MarkerArray, self._on_memory,
                             queue_size=1),
        ]

    def _due(self, kind: str) -> bool:
        return self.view.throttle_due(self.runner, kind)

    def _to_map(self, frame: str) -> Tuple[float, float, float] | None:
        try:
            t = self.view.tf.lookup_transform(self.view.frame, frame.lstrip("/"), rospy.Time(0)).transform
        except TF_ERRORS:
            return None
        return (t.translation.x, t.translation.y, _yaw(t.rotation))

    def _transformed(self, frame: str, rows: np.ndarray) -> np.ndarray | None:
        frame = frame.lstrip("/")
        if frame in ("", self.view.frame):
            return rows
        pose = self._to_map(frame)
        return None if pose is None else transform_poses(rows, *pose)

    def _on_plan(self, msg: Path, kind: str) -> None:
        if not self._due(kind):
            return
        rows = np.array([(p.pose.position.x, p.pose.position.y) for p in msg.poses], dtype=float).reshape(-1, 2)
        points = self._transformed(msg.header.frame_id, rows)
        if points is not None:
            self.console.submit_overlay(path_overlay(self.runner, kind, msg.header.stamp.to_sec(), points))

    def _on_footprint(self, msg: PolygonStamped) -> None:
        self.footprint = np.array([(p.x, p.y) for p in msg.polygon.points], dtype=float).reshape(-1, 2)

    def _on_scan(self, msg: LaserScan) -> None:
        if not self._due("scan"):
            return
        laser = self._to_map(msg.header.frame_id)
        if laser is not None:
            self.console.submit_overlay(scan_overlay(
                self.runner, msg.header.stamp.to_sec(), ranges=msg.ranges, angle_min=msg.angle_min,
                angle_increment=msg.angle_increment, range_min=msg.range_min, range_max=msg.range_max,
                laser_pose=laser))

    def _on_poses(self, msg: PoseArray, kind: str) -> None:
        if not self._due(kind):
            return
        rows = np.array([(p.position.x, p.position.y, _yaw(p.orientation)) for p in msg.poses],
                        dtype=float).reshape(-1, 3)
        points = self._transformed(msg.header.frame_id, rows)
        if points is not None:
            self.console.submit_overlay(poses_overlay(self.runner, kind, msg.header.stamp.to_sec(), points))

    def _on_memory(self, msg: MarkerArray) -> None:
        frame = msg.markers[0].header.frame_id if msg.markers else self.view.frame
        rows = remembered_of_markers(msg)
        shown = []
        for obstacle_id, footprint, text in rows:
            points = self._transformed(frame, footprint)
            if points is None:
                rospy.logwarn_throttle(30.0, f"console: remembered obstacles of {self.runner} not shown: no "
                                             f"transform {self.view.frame} -> {frame}")
                return
            shown.append((obstacle_id, points, text))
        with self._memory_lock:
            self._memory_pending = memory_overlay(self.runner, rospy.get_time(), shown)
        self.flush_memory()

    def flush_memory(self) -> None:
        """Submit the newest memory overlay if one waits and its kind is due (called again every pose period,
        so a change that came too soon after the last is shown late, never lost)."""
        with self._memory_lock:
            if self._memory_pending is None or not self._due("memory"):
                return
            event, self._memory_pending = self._memory_pending, None
        self.console.submit_overlay(event)

    def forget_memory(self) -> Tuple[bool, str]:
        """Call the robot's clear_obstacle_memory service: its (success, message); NotReadyError naming the service
        when it does not exist (the memory off) or fails."""
        name = f"{robot_namespace(self.runner)}/{self.view.memory_costmap}/clear_obstacle_memory"
        try:
            rospy.wait_for_service(name, timeout=SERVICE_WAIT_S)
        except rospy.ROSException as err:
            raise NotReadyError(f"no service {name} (within {SERVICE_WAIT_S:g} s): is the obstacle memory of "
                                f"{self.view.memory_costmap} off (obstacle_memory/enabled false)?") from err
        try:
            answer = rospy.ServiceProxy(name, Trigger)()
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise NotReadyError(f"{name} failed: {err}") from err
        return bool(answer.success), str(answer.message)

    def publish_pose(self) -> None:
        pose = self._to_map(self.base_frame)
        if pose is not None:
            self.console.submit_overlay(pose_overlay(self.runner, rospy.get_time(), pose, self.radius_m,
                                                     self.footprint))

    def send(self, request: GoalRequest) -> None:
        publisher = self.goal_publisher if request.kind == "goal" else self.pose_publisher
        if publisher.get_num_connections() == 0:
            raise NotReadyError(f"nothing listens on {publisher.resolved_name} (yet); try again")
        if request.kind == "goal":
            goal = PoseStamped()
            goal.header.frame_id, goal.header.stamp = self.view.frame, rospy.Time.now()
            _set_pose(goal.pose, request)
            self.goal_publisher.publish(goal)
            return
        initial = PoseWithCovarianceStamped()
        initial.header.frame_id, initial.header.stamp = self.view.frame, rospy.Time.now()
        _set_pose(initial.pose.pose, request)
        cov = [0.0] * 36
        cov[0], cov[7], cov[35] = INITIAL_POSE_COVARIANCE
        initial.pose.covariance = cov
        self.pose_publisher.publish(initial)

    def close(self) -> None:
        for sub in self.subscribers:
            sub.unregister()
        self.goal_publisher.unregister()
        self.pose_publisher.unregister()


def _set_pose(pose: Any, request: GoalRequest) -> None:
    pose.position.x, pose.position.y = request.x, request.y
    pose.orientation.z, pose.orientation.w = math.sin(request.yaw / 2.0), math.cos(request.yaw / 2.0)


class MapView:
    """The map subscription, a tf buffer, and one :class:`MapLink` per runner (made and closed by the registry)."""

    def __init__(self, console: Console, map_topic: str, goal_topic: str,
                 memory_costmap: str = "get_path_server/global_costmap") -> None:
        self.console = console
        self.goal_topic = goal_topic
        self.memory_costmap = memory_costmap.strip("/")
        self.frame = "map"
        self.tf = tf2_ros.Buffer(cache_time=rospy.Duration(10.0))
        self._tf_listener = tf2_ros.TransformListener(self.tf)
        self._throttle = Throttle()
        self._throttle_lock = threading.Lock()
        # numpy_msg: the grid's int8[] read as one array (a 2000 x 2000 map as a tuple of ints costs ~0.3 s)
        self.map_subscriber = rospy.Subscriber(map_topic, numpy_msg(OccupancyGrid), self._on_map, queue_size=1,
                                               buff_size=2**24)

    def throttle_due(self, robot: str, kind: str) -> bool:
        with self._throttle_lock:
            return self._throttle.due(robot, kind)

    def _on_map(self, msg: OccupancyGrid) -> None:
        info = msg.info
        self.frame = msg.header.frame_id.lstrip("/") or "map"
        geometry = GridGeometry(self.frame, float(info.resolution), int(info.width), int(info.height),
                                (info.origin.position.x, info.origin.position.y, _yaw(info.origin.orientation)))
        try:
            self.console.submit_map(geometry, msg.data)
        except FlexNavError as err:
            rospy.logwarn_throttle(30.0, f"console: map on {self.map_subscriber.resolved_name} not shown: {err}")


class RunnerRegistry:
    """One :class:`RunnerLink` per runner on the master, kept up to date by a discovery thread."""

    def __init__(self, console: Console, master_uri: str, period_s: float) -> None:
        self.console = console
        self.master_uri = master_uri
        self.period_s = period_s
        self.links: Dict[str, RunnerLink] = {}
        self.map_links: Dict[str, MapLink] = {}
        self.map_view: MapView | None = None
        self.map_topics: Tuple[str, str] | None = None  # (map topic, goal topic): the map view made at start()
        self.memory_costmap = "get_path_server/global_costmap"  # in each robot's namespace
        self.pose_period_s = 0.1  # [s]
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="console discovery", daemon=True)

    def start(self) -> None:
        if self.map_topics is not None and self.map_view is None:
            self.map_view = MapView(self.console, *self.map_topics, self.memory_costmap)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread.ident is not None:  # started (a port that could not be bound never starts it)
            self._thread.join(MASTER_CALL_TIMEOUT_S + 1.0)
        with self._lock:
            links, self.links = list(self.links.values()), {}
        for link in links:
            link.close()
        with self._lock:
            map_links, self.map_links = list(self.map_links.values()), {}
        for map_link in map_links:
            map_link.close()

    def _run(self) -> None:
        next_discovery = 0.0
        while not self._stop.is_set() and not rospy.is_shutdown():
            if time.monotonic() >= next_discovery:
                next_discovery = time.monotonic() + self.period_s
                try:
                    self.discover_once()
                except NotReadyError as err:
                    rospy.logwarn_throttle(30.0, f"console: {err}")
            with self._lock:
                map_links = list(self.map_links.values())
            for link in map_links:
                link.publish_pose()
                link.flush_memory()
            self._stop.wait(min(self.pose_period_s, max(0.0, next_discovery - time.monotonic())))

    def discover_once(self) -> List[str]:
        """Ask the master once; drop the links of runners gone, tell the console, link the new ones (after the
        console knows them: their latched messages arrive as soon as they subscribe)."""
        names = runner_names(published_topics(self.master_uri, rospy.get_name()))
        with self._lock:
            gone = [self.links.pop(name) for name in list(self.links) if name not in names]
            gone_maps = [self.map_links.pop(name) for name in list(self.map_links) if name not in names]
        for link in gone:
            rospy.loginfo(f"console: behavior runner {link.name} is gone")
            link.close()
        for map_link in gone_maps:
            map_link.close()
        self.console.submit_robots(names)
        with self._lock:
            for name in names:
                if name not in self.links:
                    self.links[name] = RunnerLink(name, self.console)
                    rospy.loginfo(f"console: behavior runner {name} found")
                if self.map_view is not None and name not in self.map_links:
                    self.map_links[name] = MapLink(name, self.console, self.map_view)
        return names

    def send_goal(self, request: GoalRequest) -> None:
        with self._lock:
            link = self.map_links.get(request.robot)
        if link is None:
            raise NotReadyError(f"no map link to {request.robot} (yet)")
        link.send(request)

    def forget_memory(self, robot: str) -> Tuple[bool, str]:
        with self._lock:
            link = self.map_links.get(robot)
        if link is None:
            raise NotReadyError(f"no map link to {robot} (yet)")
        return link.forget_memory()

    def send(self, robot: str, command: RunnerCommand) -> None:
        with self._lock:
            link = self.links.get(robot)
        if link is None:
            raise NotReadyError(f"no behavior runner {robot} on the master")
        link.send(command)


def _not_ready(robot: str, command: RunnerCommand) -> None:
    raise NotReadyError("the console is still starting")


def read_config() -> ServerConfig:
    """The private parameters as a checked ServerConfig (ConfigError with the reason; the token never echoed)."""
    reject_unknown("~", PARAMETERS)
    token = rospy.get_param("~token", "")
    if not isinstance(token, str):
        raise ConfigError("parameter ~token must be a string (a token of digits only: quote it, "
                          "_token:=\"'0123...'\")")
    return ServerConfig(host=param_str("~host", "127.0.0.1"), port=param_int("~port", 8080, 1, 65535),
                        token=token, max_clients=param_int("~max_clients", 16, 1, 1000))


async def _serve(console: Console, registry: RunnerRegistry) -> None:
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()

    def on_shutdown() -> None:
        if not loop.is_closed():
            loop.call_soon_threadsafe(stop.set)

    rospy.on_shutdown(on_shutdown)
    config = console.config

    def ready() -> None:
        shown = f"[{config.host}]" if ":" in config.host else config.host
        url = f"http://{shown}:{config.port}/"
        how = f"open {url}?token=<your token> once" if config.token else f"open {url}"
        where = "" if is_loopback(config.host) else " (reachable from the network: the token guards it)"
        rospy.loginfo(f"console: serving on {url}{where}; {how}")
        print(f"[console] {how}", flush=True)
        registry.start()

    await serve(console, stop, ready)


def main() -> int:
    init_node("console")
    try:
        config = read_config()
        period_s = param_float("~discovery_period_s", 2.0, 0.1, 3600.0)
        pose_period_s = param_float("~pose_period_s", 0.1, 0.02, 60.0)
        map_topic = param_str("~map_topic", "/map")
        goal_topic = param_str("~goal_topic", "move_base_simple/goal")
        memory_costmap = param_str("~memory_costmap", "get_path_server/global_costmap")
        if not memory_costmap.strip("/"):
            raise ConfigError("~memory_costmap must name a costmap in the robots' namespaces, e.g. "
                              "get_path_server/global_costmap")
    except ConfigError as err:
        rospy.logfatal(f"console: {err}")
        print(f"[console] configuration error: {err}", file=sys.stderr)
        return 2
    console = Console(config, send=_not_ready)
    registry = RunnerRegistry(console, os.environ.get("ROS_MASTER_URI", ""), period_s)
    registry.pose_period_s = pose_period_s
    registry.map_topics = (map_topic, goal_topic)
    registry.memory_costmap = memory_costmap
    console.send = registry.send
    console.send_goal = registry.send_goal
    console.forget_memory = registry.forget_memory
    if shutil.which("dot") is None:
        rospy.logwarn(f"console: Graphviz's dot is not installed: behaviors will not be drawn (commands still work; "
                      f"install the Debian package graphviz; layouts are bounded by {DOT_TIMEOUT_S:g} s)")
    try:
        asyncio.run(_serve(console, registry))
    except FlexNavError as err:
        rospy.logfatal(f"console: {err}")
        print(f"[console] {err}", file=sys.stderr)
        return 2
    finally:
        registry.stop()
    return 0
