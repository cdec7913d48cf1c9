"""The simulated navigation demo (``tools/demo.sh``): Flexible Navigation in the paper's obstacle course.

Starts a private master, the pybullet simulator (headless; GUI with ``--gui`` when a display exists), the
map server, and per robot the navigation servers, controllers, bumper relay and a behavior runner with the
Flex Planner behavior. It then acts as the operator of the paper's demonstration: whenever a robot's behavior
waits for a goal it sends the next of the world's intermediate goals (g1, g2, g3, then back to the start,
lap after lap), and prints state transitions and progress. A low step that the lidar cannot see lies on the
first leg: the bumper finds it and the behavior's recovery (stop, back up, clear costmaps, replan to the
original goal) handles it.

Each robot localizes with flex_nav's localizer on its scan and noisy odometry (``--localization oracle``: the
simulator's ground truth instead). At the end it prints ``goals reached: N/M, bumper recoveries: K, sim time: T s,
wall time: W s`` and, with the localizer, ``localization: median X cm, p95 Y cm, max Z cm`` (every amcl_pose
against the ground truth at its stamp), writes
``run.png`` (map, costmap, plans, trajectories, bumper hits) and ``run.bag`` to the output directory, and
exits 0 only if every goal was reached. Everything it started is stopped on exit and on Ctrl-C.

``--console PORT`` also starts the web operator console (``rosrun flex_nav console``, on 127.0.0.1:PORT) and prints
its URL; ``--hold`` keeps the whole stack up after the last goal (or the timeout) until Ctrl-C, so a person can go
on steering the robots from the console.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import shutil
import signal
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

from flex_nav.apps.eval.localization_error import LocalizationErrors, merged
from flex_nav.exceptions import ConfigError, FlexNavError, choices_message
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.testing.private_master import PrivateMaster
from flex_nav.testing.process import ManagedProcess

REPO_ROOT = Path(__file__).resolve().parents[3]
PROFILES = {"kobuki": "kobuki", "turtlebot2": "kobuki", "create": "create2", "create2": "create2",
            "turtlebot4": "turtlebot4"}
LAP = ("g1", "g2", "g3", "start")  # the paper's three intermediate goals, then home
STARTUP_TIMEOUT_S = 60.0  # [s] wall: every robot's behavior must be waiting for a goal by then
GOAL_TOPIC = "move_base_simple/goal"
GIVEN_UP = ("GiveUp", "NoPath", "Abort")  # labels of the behaviors' states that drop a goal
LOCALIZATION_SOURCES = ("localizer", "oracle")  # who publishes map -> odom (see --localization)


@dataclass
class RobotRun:
    """One robot of the demo: its goals and what it did."""

    name: str
    profile: str
    goals: List[Tuple[str, Tuple[float, float, float]]]  # (name, (x [m], y [m], yaw [rad]))
    next_goal: int = 0  # goals sent
    completed: int = 0  # goals the behavior is done with: reached or given up
    reached: int = 0
    recoveries: int = 0
    bumper_hits: List[Tuple[float, float]] = field(default_factory=list)
    trajectory: List[Tuple[float, float]] = field(default_factory=list)
    plans: List[Any] = field(default_factory=list)
    distance_m: float = 0.0
    waiting_for_goal: bool = False
    localized: bool = False  # its localizer said so (``localized: ...`` on localizer/status)
    pose: Optional[Tuple[float, float, float]] = None
    failed_reason: str = ""
    finished: bool = False
    goal_started_sim_s: float = 0.0
    goal_times_s: List[float] = field(default_factory=list)  # [s] simulated, per completed goal (nan: given up)
    last_bumper_sim_s: float = -math.inf


def parse_args(argv: Optional[Sequence[str]] = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="tools/demo.sh", description=__doc__.split("\n\n")[0])
    parser.add_argument("--profile", default="turtlebot2",
                        help="robot: " + ", ".join(PROFILES) + " (default %(default)s)")
    parser.add_argument("--profiles", default="",
                        help="one profile per robot, comma-separated (e.g. turtlebot2,turtlebot2,create)")
    parser.add_argument("--behavior", default="flex_planner",
                        help="behavior: flex_planner, multi_level_planner, create_flex_planner, move_base_like")
    parser.add_argument("--goals", default=",".join(LAP),
                        help="comma-separated goal names of the world, in order (default %(default)s)")
    parser.add_argument("--world", default="lab", help="world name in sim/worlds or a path (default %(default)s)")
    parser.add_argument("--map", type=Path, default=None,
                        help="map_server YAML to navigate on (default: the world's static map), e.g. a map the "
                             "mapper saved (python -m flex_nav.apps.mapping_run)")
    parser.add_argument("--robots", type=int, default=1, help="number of robots, 1..3 (default %(default)s)")
    parser.add_argument("--laps", type=int, default=1, help="laps of the goal loop (default %(default)s)")
    parser.add_argument("--goals-per-robot", type=int, default=0,
                        help="send each robot only its first N goals (0: all; default %(default)s)")
    parser.add_argument("--rtf", type=float, default=2.0, help="simulation real-time factor, 0 = as fast as possible")
    parser.add_argument("--autonomy", default="full", help="behavior autonomy: off, low, high, full")
    parser.add_argument("--timeout", type=float, default=900.0, help="[s] wall-time bound of the whole run")
    parser.add_argument("--seed", type=int, default=0)
    add_localization_argument(parser)
    add_separate_processes_argument(parser)
    parser.add_argument("--gui", action="store_true", help="pybullet window (needs a display)")
    parser.add_argument("--out", type=Path, default=None, help="output directory (default out/demo-<time>)")
    parser.add_argument("--console", type=int, default=0, metavar="PORT",
                        help="also serve the web operator console on http://127.0.0.1:PORT/ (default: none)")
    parser.add_argument("--hold", action="store_true",
                        help="after the last goal keep everything running until Ctrl-C (e.g. with --console)")
    args = parser.parse_args(argv)
    args.profile_list = [p for p in args.profiles.split(",") if p] or [args.profile] * args.robots
    if args.profiles:
        args.robots = len(args.profile_list)
    for profile in args.profile_list:
        if profile not in PROFILES:
            parser.error(choices_message("profile", profile, PROFILES))
    if not 1 <= args.robots <= 3:
        parser.error(f"--robots {args.robots} is not valid (valid: 1, 2, 3)")
    if args.laps < 1:
        parser.error(f"--laps {args.laps} must be >= 1")
    if args.console and not 1 <= args.console <= 65535:
        parser.error(f"--console {args.console} is not a TCP port (1..65535)")
    if args.gui and not os.environ.get("DISPLAY"):
        parser.error("--gui needs a display (DISPLAY is not set)")
    return args


def add_localization_argument(parser: argparse.ArgumentParser) -> None:
    """``--localization localizer|oracle`` (the demo's and the scenario runner's)."""
    parser.add_argument("--localization", choices=LOCALIZATION_SOURCES, default="localizer",
                        help="who publishes map -> odom: flex_nav's localizer on the scan (default) or the "
                             "simulator's ground truth (oracle, the figures before the localizer existed)")


def add_separate_processes_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--separate-processes", action="store_true",
                        help="run each navigation server and controller in a process of its own (default: all of "
                             "one robot's in one `navigation` process)")


def plan_robots(world: Any, profiles: Sequence[str], laps: int, lap: Sequence[str] = LAP) -> List[RobotRun]:
    """Robot k starts where goal k-1 of the lap ends (robot 1 at the world's first robot spawn or ``start``)
    and runs the lap from there, ``laps`` times."""
    missing = [n for n in lap if n not in world.goals]
    if missing or not lap:
        raise ConfigError(choices_message(f"world {world.name!r} goal", ", ".join(missing) or "(none)", world.goals))
    if len(profiles) > len(lap):
        raise ConfigError(f"{len(profiles)} robots need at least {len(profiles)} goals in the lap, got {len(lap)}")
    runs = []
    for index, profile in enumerate(profiles):
        order = list(lap[index:]) + list(lap[:index])
        goals = [(name, world.goals[name]) for _ in range(laps) for name in order]
        run = RobotRun(f"robot{index + 1}", PROFILES[profile], goals)
        if index == 0:
            run.pose = world.spawns[0].pose if world.spawns else world.goals.get("start", world.goals[lap[-1]])
        else:
            run.pose = world.goals[lap[index - 1]]
        runs.append(run)
    return runs


class DemoMonitor:
    """The demo's ROS node: sends goals, follows the behaviors and records what happens."""

    def __init__(self, runs: List[RobotRun], localizer: bool = True) -> None:
        """``localizer``: the robots run flex_nav's localizer, and a robot gets goals only once it is localized
        (False: the simulator's oracle publishes map -> odom from the start)."""
        import rospy  # noqa: PLC0415 - rospy only once the master is up
        from geometry_msgs.msg import PointStamped, PoseStamped, PoseWithCovarianceStamped  # noqa: PLC0415
        from nav_msgs.msg import Odometry  # noqa: PLC0415
        from nav_msgs.msg import Path as PathMsg  # noqa: PLC0415
        from std_msgs.msg import String  # noqa: PLC0415

        from flex_nav.msg import BehaviorActivity, BehaviorLog, BehaviorStatus, BehaviorTransition  # noqa: PLC0415

        self.rospy = rospy
        self.PoseStamped = PoseStamped
        self.runs = runs
        self.stopping = False  # set before the demo stops the nodes: their shutdown is not a failure
        self.lock = threading.Lock()
        self.goal_pubs = {}
        self.subs = []
        self.localization = {run.name: LocalizationErrors() for run in runs}
        for run in runs:
            ns = f"/{run.name}"
            run.localized = not localizer
            self.subs.append(rospy.Subscriber(f"{ns}/amcl_pose", PoseWithCovarianceStamped, self._on_estimate,
                                              callback_args=run, queue_size=10))
            self.subs.append(rospy.Subscriber(f"{ns}/localizer/status", String, self._on_localizer_status,
                                              callback_args=run, queue_size=10))
            self.goal_pubs[run.name] = rospy.Publisher(f"{ns}/{GOAL_TOPIC}", PoseStamped, queue_size=1)
            self.subs += [
                rospy.Subscriber(f"{ns}/ground_truth", Odometry, self._on_odom, callback_args=run, queue_size=5),
                rospy.Subscriber(f"{ns}/behavior_runner/activity", BehaviorActivity, self._on_activity,
                                 callback_args=run),
                rospy.Subscriber(f"{ns}/behavior_runner/transitions", BehaviorTransition, self._on_transition,
                                 callback_args=run, queue_size=50),
                rospy.Subscriber(f"{ns}/behavior_runner/status", BehaviorStatus, self._on_status, callback_args=run),
                rospy.Subscriber(f"{ns}/behavior_runner/log", BehaviorLog, self._on_log, callback_args=run,
                                 queue_size=50),
                rospy.Subscriber(f"{ns}/bumper_hits", PointStamped, self._on_bumper, callback_args=run),
                rospy.Subscriber(f"{ns}/get_path_server/plan", PathMsg, self._on_plan, callback_args=run),
            ]

    def sim_s(self) -> float:
        return float(self.rospy.get_time())

    def _say(self, run: RobotRun, text: str) -> None:
        print(f"[sim {self.sim_s():7.1f} s] {run.name}: {text}", flush=True)

    def _on_localizer_status(self, msg: Any, run: RobotRun) -> None:
        localized = msg.data.startswith("localized")
        with self.lock:
            changed, run.localized = localized != run.localized, localized
        if changed:
            self._say(run, f"localizer: {msg.data}")

    def _on_estimate(self, msg: Any, run: RobotRun) -> None:
        with self.lock:
            self.localization[run.name].add_estimate(msg.header.stamp.to_sec(), _planar_pose(msg.pose.pose))

    def _on_odom(self, msg: Any, run: RobotRun) -> None:
        p = msg.pose.pose.position
        yaw = _planar_pose(msg.pose.pose)[2]
        with self.lock:
            self.localization[run.name].add_truth(msg.header.stamp.to_sec(), (p.x, p.y, yaw))
            if run.trajectory:
                step = math.hypot(p.x - run.trajectory[-1][0], p.y - run.trajectory[-1][1])
                if step < 0.02:
                    run.pose = (p.x, p.y, yaw)
                    return
                run.distance_m += step
            run.trajectory.append((p.x, p.y))
            run.pose = (p.x, p.y, yaw)

    def _on_activity(self, msg: Any, run: RobotRun) -> None:
        with self.lock:
            run.waiting_for_goal = any(p.endswith("/ReceiveGoal") for p in msg.active_paths)
        for request in msg.requests:
            self._say(run, f"waits for the operator: {request.path} -> {request.outcome}")

    def _on_transition(self, msg: Any, run: RobotRun) -> None:
        self._say(run, f"{msg.path} --{msg.outcome}--> {msg.target}")
        with self.lock:
            if msg.target in ("Arrived", *GIVEN_UP) and run.next_goal > run.completed:
                name, goal = run.goals[run.completed]
                run.completed += 1
                run.goal_times_s.append(self.sim_s() - run.goal_started_sim_s if msg.target == "Arrived"
                                        else math.nan)
                if msg.target == "Arrived":
                    run.reached += 1
                    heading = ""
                    if run.pose is not None:
                        heading = f", heading off by {heading_error_deg(run.pose, goal):+.0f} deg"
                    self._say(run, f"goal {run.completed}/{len(run.goals)} ({name} at {goal[0]:.1f}, {goal[1]:.1f}) "
                                   f"reached after {self.sim_s() - run.goal_started_sim_s:.1f} s{heading}; "
                                   f"distance so far {run.distance_m:.1f} m")
                else:
                    self._say(run, f"goal {run.completed}/{len(run.goals)} ({name}) NOT reached: the behavior gave it "
                                   f"up ({msg.target})")
                if run.completed == len(run.goals):
                    run.finished = True
            if msg.path.endswith("/Recovery") and msg.outcome == "done":
                run.recoveries += 1
                self._say(run, f"bumper recovery {run.recoveries} done; replanning to the original goal")

    def _on_status(self, msg: Any, run: RobotRun) -> None:
        if msg.code in (msg.FINISHED, msg.PREEMPTED, msg.FAILED) and not self.stopping:
            with self.lock:
                run.failed_reason = run.failed_reason or f"behavior ended early: code {msg.code} {msg.reason}"

    def _on_log(self, msg: Any, run: RobotRun) -> None:
        if msg.level in (msg.WARN, msg.ERROR):
            self._say(run, f"[{'WARN' if msg.level == msg.WARN else 'ERROR'}] {msg.path}: {msg.text}")

    def _on_bumper(self, msg: Any, run: RobotRun) -> None:
        with self.lock:
            if run.pose is None:
                return
            x, y, yaw = run.pose
            px, py = msg.point.x, msg.point.y
            run.bumper_hits.append((x + math.cos(yaw) * px - math.sin(yaw) * py,
                                    y + math.sin(yaw) * px + math.cos(yaw) * py))
            new_press = self.sim_s() - run.last_bumper_sim_s > 0.5  # one press reports several contact points
            run.last_bumper_sim_s = self.sim_s()
        if new_press:
            self._say(run, "BUMPER hit: something the lidar does not see")

    def _on_plan(self, msg: Any, run: RobotRun) -> None:
        import numpy as np  # noqa: PLC0415

        points = np.array([(p.pose.position.x, p.pose.position.y) for p in msg.poses]).reshape(-1, 2)
        with self.lock:
            run.plans.append(points)

    def send_due_goals(self, stamp_s: Optional[float] = None) -> None:
        """Send each robot its next goal if it is due, stamped ``stamp_s`` [s] (None: now, as this node's clock
        reads it; a lockstep start gives the time it holds the simulation at, which that view may lag behind)."""
        for run in self.runs:
            with self.lock:
                due = run.waiting_for_goal and run.next_goal == run.completed and run.next_goal < len(run.goals)
                if due:
                    name, (x, y, yaw) = run.goals[run.next_goal]
                    run.next_goal += 1
                    run.waiting_for_goal = False
                    run.goal_started_sim_s = self.sim_s() if stamp_s is None else stamp_s
            if due:
                msg = self.PoseStamped()
                msg.header.frame_id = "map"
                msg.header.stamp = self.rospy.Time.now() if stamp_s is None else self.rospy.Time.from_sec(stamp_s)
                msg.pose.position.x, msg.pose.position.y = x, y
                msg.pose.orientation.z = math.sin(yaw / 2.0)
                msg.pose.orientation.w = math.cos(yaw / 2.0)
                self.goal_pubs[run.name].publish(msg)
                self._say(run, f"goal {run.next_goal}/{len(run.goals)}: {name} at "
                               f"({x:.1f}, {y:.1f}, {math.degrees(yaw):.0f} deg)")

    def all_waiting(self) -> bool:
        with self.lock:
            return all(run.waiting_for_goal and run.localized for run in self.runs)

    def done(self) -> bool:
        with self.lock:
            return all(run.finished or run.failed_reason for run in self.runs)


def _planar_pose(pose: Any) -> Tuple[float, float, float]:
    q = pose.orientation
    return (pose.position.x, pose.position.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))


def start_system(stack: contextlib.ExitStack, args: argparse.Namespace, runs: List[RobotRun], out: Path, *,
                 camera: bool = False, params: Optional[Mapping[str, object]] = None, bag: bool = True,
                 ) -> Tuple[List[ManagedProcess], Dict[str, str]]:
    """Start a private master (use_sim_time and ``params``), the simulator (``args``: world, rtf, seed, gui;
    its camera when ``camera``), the map server, every robot's navigation and behavior runner (``args``:
    behavior, autonomy) and, with ``bag``, a rosbag recorder; ``stack`` stops them all (the recorder first).
    Sets this process's ROS environment to the master. Returns the processes whose death ends a run (not the
    recorder) and the environment for more nodes."""
    logs = out / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    master = stack.enter_context(PrivateMaster(ros_home=out / "ros_home"))
    env = master.env
    os.environ.update(env)
    import rosgraph  # noqa: PLC0415

    parameters = rosgraph.Master("/nav_demo", master_uri=master.uri)
    for name, value in {"/use_sim_time": True, **(params or {})}.items():
        parameters.setParam(name, value)
    map_yaml = args.map or map_of_world(args.world, out)
    oracle = getattr(args, "localization", "localizer") == "oracle"
    robots_param = ",".join(f"{r.name}:{r.profile}:{r.pose[0]}:{r.pose[1]}:{math.degrees(r.pose[2]):.1f}"
                            for r in runs if r.pose)
    processes = [
        ManagedProcess(["rosrun", "flex_nav", "sim", f"_world:={args.world}", f"_robots:={robots_param}",
                        f"_rtf:={args.rtf}", f"_seed:={args.seed}", f"_camera:={'true' if camera else 'false'}",
                        f"_gui:={'true' if getattr(args, 'gui', False) else 'false'}",
                        f"_publish_map_odom:={'true' if oracle else 'false'}"],
                       env=env, log_path=logs / "sim.log"),
        ManagedProcess(["rosrun", "flex_nav", "map_server", str(map_yaml)], env=env, log_path=logs / "map.log"),
    ]
    for run in runs:
        processes.append(ManagedProcess(
            ["roslaunch", "flex_nav", "flex_nav_robot.launch", f"robot:={run.name}", f"profile:={run.profile}",
             "twist_relay:=true", f"autonomy:={args.autonomy}", f"behavior:={args.behavior}",
             f"localizer:={'false' if oracle else 'true'}",
             f"combined_navigation:={'false' if getattr(args, 'separate_processes', False) else 'true'}"],
            env=env, log_path=logs / f"{run.name}.log"))
    for proc in processes:
        stack.callback(proc.stop)
    if bag:
        start_recorder(stack, out / "run.bag", [r.name for r in runs], env, logs / "rosbag.log")
    return processes, env


def start_recorder(stack: contextlib.ExitStack, bag: Path, robots: Sequence[str], env: Mapping[str, str],
                   log_path: Path) -> ManagedProcess:
    """Record what replays the run in RViz -- /clock, /tf, /tf_static, /map, each robot's scan, footprint, global
    and local plans and costmaps (published at their ``publish_frequency``, 1 Hz) -- and what evaluates it:
    ground truth, localization estimates and status, odometry, bumper hits, commands, behavior topics, the
    obstacle classifier's classes and fused lines, and the world's events; to ``bag``, registered on ``stack`` so
    that it stops before what was registered earlier. ``rosbag play run.bag`` then drives a use_sim_time RViz
    from the bag's own /clock (no ``--clock``)."""
    topics = [t for name in robots for t in (
        f"/{name}/ground_truth", f"/{name}/amcl_pose", f"/{name}/odom", f"/{name}/scan", f"/{name}/footprint",
        f"/{name}/get_path_server/plan", f"/{name}/follow_path_server/plan",
        f"/{name}/get_path_server/global_costmap/costmap", f"/{name}/pure_pursuit_path/local_costmap/costmap",
        f"/{name}/bumper_hits", f"/{name}/localizer/status",
        f"/{name}/cmd_vel", f"/{name}/behavior_runner/transitions", f"/{name}/behavior_runner/status",
        f"/{name}/obstacle_class", f"/{name}/obstacle_fusion")]
    # the recorder itself (not the rosbag wrapper script), so SIGINT reaches it and it closes the bag
    recorder = "/usr/lib/rosbag/record" if Path("/usr/lib/rosbag/record").is_file() else "rosbag"
    proc = ManagedProcess([recorder, *([] if recorder != "rosbag" else ["record"]), "-O", str(bag),
                           "/clock", "/tf", "/tf_static", "/map", "/sim_events", *topics], env=env, log_path=log_path)
    stack.callback(proc.stop, 10.0)  # stopped first (LIFO): SIGINT lets rosbag close the bag file
    return proc


def heading_error_deg(pose: Sequence[float], goal: Sequence[float]) -> float:
    """[deg] The robot's heading (``pose``: x, y, yaw [rad]) minus the goal's, wrapped to (-180, 180]."""
    return math.degrees(wrap_angle(pose[2] - goal[2]))


def start_console(stack: contextlib.ExitStack, port: int, env: Mapping[str, str], log_path: Path) -> ManagedProcess:
    """The web operator console on 127.0.0.1:``port`` (loopback: no token needed), stopped by ``stack``."""
    proc = ManagedProcess(["rosrun", "flex_nav", "console", "_host:=127.0.0.1", f"_port:={port}",
                           "_discovery_period_s:=1.0"], env=env, log_path=log_path)
    stack.callback(proc.stop)
    return proc


def hold(processes: Sequence[ManagedProcess], is_shutdown: Any) -> str:
    """Keep the stack up until Ctrl-C (or a process of it ends, or ROS shuts down); why it ended."""
    print("holding: everything stays up until Ctrl-C", flush=True)
    try:
        while not is_shutdown():
            dead = [p for p in processes if not p.running()]
            if dead:
                return f"{' '.join(dead[0].argv[:4])} exited (log {dead[0].log_path})"
            time.sleep(0.2)
    except KeyboardInterrupt:
        return "Ctrl-C"
    return "ROS shut down (Ctrl-C)"


def world_map(world_name: str) -> Path:
    """The static map (map_server YAML) the simulator's world ships (sim/worlds/maps/<world>.yaml)."""
    return REPO_ROOT / "sim" / "worlds" / "maps" / f"{world_name}.yaml"


def map_of_world(world: str, out: Path) -> Path:
    """The static map of ``world``: the shipped one for a shipped world's name; for a world file given by its path
    (a variant of one, or a world of the user's), the map of its static structure written to
    ``out/map/<file stem>.yaml``, so that a variant with other walls or doors is navigated on its own map."""
    if "/" not in world and not world.endswith(".yaml"):
        return world_map(world)
    from flex_nav_sim.static_map import write_static_map  # noqa: PLC0415
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    (out / "map").mkdir(parents=True, exist_ok=True)
    return write_static_map(load_world(world), out / "map" / f"{Path(world).stem}.yaml")


def wait_until_ready(monitor: DemoMonitor, processes: List[ManagedProcess], timeout_s: float = STARTUP_TIMEOUT_S
                     ) -> Optional[str]:
    """Wait until every robot's behavior waits for a goal and its localizer is localized; the reason if it did
    not happen, else None."""
    deadline = time.monotonic() + timeout_s
    while not monitor.all_waiting():
        dead = [p for p in processes if not p.running()]
        if dead:
            return f"{' '.join(dead[0].argv[:4])} exited (log {dead[0].log_path})"
        if time.monotonic() > deadline:
            with monitor.lock:
                late = [f"{r.name} ({'waits for a goal' if r.waiting_for_goal else 'behavior not ready'}, "
                        f"{'localized' if r.localized else 'not localized'})" for r in monitor.runs]
            return f"not ready after {timeout_s:.0f} s: {', '.join(late)}"
        time.sleep(0.2)
    return None


def write_picture(out: Path, map_yaml: Path, runs: List[RobotRun], title: str) -> Path:
    from flex_nav.apps.run_picture import RobotTrack, draw_run, write_png  # noqa: PLC0415
    from flex_nav.nav.costmap.map_io import load_map  # noqa: PLC0415

    grid = load_map(map_yaml)
    tracks = [RobotTrack(r.name, list(r.trajectory), list(r.plans), [(g[1][0], g[1][1]) for g in r.goals],
                         list(r.bumper_hits)) for r in runs]
    path = out / "run.png"
    write_png(path, draw_run(grid, tracks, title=title))
    return path


def main(argv: Optional[Sequence[str]] = None) -> int:  # noqa: PLR0915 - one linear script of the demo
    args = parse_args(argv)
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    started = time.monotonic()
    try:
        world = load_world(args.world)
        runs = plan_robots(world, args.profile_list, args.laps, [g for g in args.goals.split(",") if g])
        if args.goals_per_robot > 0:
            for run in runs:
                run.goals = run.goals[: args.goals_per_robot]
    except FlexNavError as err:
        print(f"demo: {err}", file=sys.stderr)
        return 2
    out = args.out or REPO_ROOT / "out" / time.strftime("demo-%Y%m%d-%H%M%S")
    out.mkdir(parents=True, exist_ok=True)
    map_yaml = args.map or map_of_world(args.world, out)
    robots = ", ".join(f"{r.name} ({r.profile})" for r in runs)
    lap_text = " -> ".join(g for g, _ in runs[0].goals[: max(1, len(runs[0].goals) // args.laps)])
    print(f"flex_nav demo: {args.behavior}, robots {robots} in world '{world.name}', {args.laps} lap(s) of "
          f"{lap_text}, autonomy {args.autonomy}; output in {out}", flush=True)

    with contextlib.ExitStack() as stack:
        signal.signal(signal.SIGTERM, _interrupt)
        processes, env = start_system(stack, args, runs, out)
        if args.console:
            processes.append(start_console(stack, args.console, env, out / "logs" / "console.log"))
            print(f"console: open http://127.0.0.1:{args.console}/ (log {out / 'logs' / 'console.log'})", flush=True)
        from flex_nav.ros.node import init_node  # noqa: PLC0415

        init_node("nav_demo")
        import rospy  # noqa: PLC0415

        monitor = DemoMonitor(runs, localizer=args.localization == "localizer")
        deadline = time.monotonic() + args.timeout
        try:
            problem = wait_until_ready(monitor, processes)
            if problem is not None:
                print(f"demo: startup failed: {problem}; logs in {out / 'logs'}", file=sys.stderr)
                return 2
            print(f"all robots wait for goals (wall {time.monotonic() - started:.1f} s)", flush=True)
            while not monitor.done() and time.monotonic() < deadline and not rospy.is_shutdown():
                monitor.send_due_goals()
                dead = [p for p in processes if not p.running()]
                if dead:
                    print(f"demo: {' '.join(dead[0].argv[:4])} exited; logs in {out / 'logs'}", file=sys.stderr)
                    break
                time.sleep(0.1)
            if args.hold and not rospy.is_shutdown():
                print(f"holding after the goals: {hold(processes, rospy.is_shutdown)}; stopping everything",
                      flush=True)
        except KeyboardInterrupt:
            print("interrupted: stopping everything", flush=True)
        monitor.stopping = True
        sim_s = rospy.get_time()
        with monitor.lock:
            localization = merged(list(monitor.localization.values())).summary()

    wall_s = time.monotonic() - started
    reached = sum(r.reached for r in runs)
    total = sum(len(r.goals) for r in runs)
    recoveries = sum(r.recoveries for r in runs)
    title = (f"{args.behavior}, {', '.join(r.profile for r in runs)} in {world.name}: {reached}/{total} goals, "
             f"{recoveries} bumper recoveries")
    picture = write_picture(out, map_yaml, runs, title)
    bag_file = out / "run.bag"
    for run in runs:
        if run.failed_reason:
            print(f"{run.name}: {run.failed_reason}")
    print(f"picture: {picture}; rosbag: {bag_file if bag_file.exists() else 'not written'}")
    shutil.rmtree(out / "ros_home", ignore_errors=True)
    print(f"goals reached: {reached}/{total}, bumper recoveries: {recoveries}, sim time: {sim_s:.1f} s, "
          f"wall time: {wall_s:.1f} s", flush=True)
    if args.localization == "localizer":
        print(localization.line(), flush=True)
    return 0 if reached == total else 1


def _interrupt(_signum: int, _frame: object) -> None:
    """SIGTERM is handled like Ctrl-C: unwind, stopping everything the demo started."""
    raise KeyboardInterrupt


if __name__ == "__main__":
    sys.exit(main())
