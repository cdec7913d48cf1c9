"""One headless run of a push-or-avoid scenario: ``python -m flex_nav.apps.scenario_run --world W --behavior B``.

Starts a private master (simulated time), the simulator with the robot's camera, the map server, the robot's
navigation and behavior runner (TurtleBot 4 profile) and the ``obstacle_classifier`` in the robot's
namespace; sets ``pure_pursuit_path``'s ``~blocked_distance`` (blocked-path detection, used by
push_or_avoid; move_base_like drives with ``pure_pursuit_topic``, which keeps it off) and its
``~yield_to_people`` (give way to moving people, :mod:`flex_nav.nav.control.yielding`; also push_or_avoid only;
``--yield-planner``, by default the rules checked by the space-time planner,
:mod:`flex_nav.nav.control.checked_yield`, and ``--yield-param KEY=VALUE`` for any of its ``~yielding/``
parameters) and its ``~social_distance`` (``--social-distance``, 0.3 m by default, 0: off;
:mod:`flex_nav.nav.control.social_distance`) and, for both behaviors, a bumper memory of 5 s in the costmaps (the
default 60 s would keep the contacts of a pushed box as obstacles in the door it was pushed through; no scenario
has obstacles only the bumper finds). Sends the world's
``goal`` once the behavior waits for one and records until the behavior is done with it or ``--sim-limit``
seconds of simulated time pass. ``--trips N`` drives from the start to the goal N times, back to the world's
``start`` between trips (untimed), in one system: what the robot learnt on a trip (the obstacle memory, with the
behavior parameter ``remember_heavy``) is there on the next; every trip's time is in ``trip_times_s``. With
``--clear-between-trips`` both costmaps are cleared (ClearCostmap) at the start before each further trip, as a
recovery, an operator or a restart does in a day's work: what the lidar marked is gone, the obstacle memory stays.
``--behavior-param KEY=VALUE`` overrides a behavior parameter (YAML value). Prints one ``RESULT {json}`` line
(see :class:`flex_nav.apps.eval.metrics.RunResult`) and writes ``run.png`` and logs to ``--out``. Exit 0 when the
run was recorded (reached or not), 2 when the system could not start.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import math
import shutil
import signal
import sys
import threading
import time
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Set, Tuple

import yaml

from flex_nav.apps.eval.metrics import RunResult, classify_contact, people_clearance
from flex_nav.apps.nav_demo import (
    DemoMonitor,
    RobotRun,
    add_localization_argument,
    add_separate_processes_argument,
    heading_error_deg,
    map_of_world,
    start_system,
    wait_until_ready,
    write_picture,
)
from flex_nav.exceptions import FlexNavError, choices_message
from flex_nav.nav.control.yielding import PLANNERS, YieldParams
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav.testing.process import ManagedProcess

PROFILE = "turtlebot4"
ROBOT = "robot1"
BLOCKED_DISTANCE_M = 0.7  # [m] pure_pursuit_path's blocked-path detection distance
STARTUP_TIMEOUT_S = 90.0  # [s] wall
# --yield-planner space_time: the follower's ~yielding/ (a horizon and range long enough to see a walker come back
# from a lane's end; the gaps are yielding's defaults) and its social slow-down only this far beyond the distance
SPACE_TIME_YIELDING = {"planner": "space_time", "horizon_s": 8.0, "max_range_m": 8.0}
SPACE_TIME_SLOW_EXTRA_M = 0.05  # [m]
SOCIAL_DISTANCE_M = 0.3  # [m] kept from tracked people while moving (issue 28), unless --social-distance says else
# push_or_avoid's follower's ~yielding/planner: the only one that keeps the social distance while moving in both S6
# and h6, seeds 0-4 (the rules alone come within 0.09 m in h6; docs/push_or_avoid.md, thirteenth session)
DEFAULT_YIELD_PLANNER = "checked"
HURRY_SPEED_MPS = 0.3  # [m/s] giving way: cross a walker's way at this speed when only that clears (max 0.306)
BUMPER_MEMORY_S = 5.0  # [s] bumper marks (both behaviors): a pushed box's contacts must not close the door
SETTLE_S = 2.0  # [s] simulated time between the behavior waiting for a goal and sending it
# lockstep: the world's script starts, and the goal goes out, at multiples of this [s] of simulated time (every
# sensor's period divides it: 20 Hz odometry, 5 Hz camera, 5.5 Hz lidar), with the simulation held there
START_GRID_S = 2.0
WORLD_LEAD_S = 4.0  # [s] lockstep: from the world's start to the goal (a multiple of START_GRID_S)
WORLD_START_S = 16.0  # [s] lockstep: the world's script starts here when the system is up by then (see start_at_grid)
START_WALL_WAIT_S = 0.2  # [s] wall: the simulation stays held this long after the goal, so the behavior has it
CLEAR_COSTMAPS = ("get_path_server/clear_costmap", "pure_pursuit_path/clear_costmap")  # --clear-between-trips
PEOPLE_TRACKERS = ("pure_pursuit_path", "pure_pursuit_topic")  # controllers that may track people (~people_tracker)
CLEAR_TIMEOUT_S = 10.0  # [s] ROS (simulated) time, per ClearCostmap goal
CLEAR_ATTEMPTS = 2  # a goal left without a result is sent once more (the CI once lost one under load)


def parse_args(argv: Optional[Sequence[str]] = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m flex_nav.apps.scenario_run", description=__doc__.split("\n\n")[0])
    parser.add_argument("--world", required=True, help="scenario world name in sim/worlds")
    parser.add_argument("--behavior", required=True, help="behavior name (move_base_like, push_or_avoid, ...)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--rtf", type=float, default=1.0, help="simulation real-time factor")
    parser.add_argument("--sim-limit", type=float, default=150.0, help="[s] simulated time bound of the goal")
    parser.add_argument("--timeout", type=float, default=600.0, help="[s] wall-time bound of the whole run")
    parser.add_argument("--out", type=Path, required=True, help="output directory")
    parser.add_argument("--bag", action="store_true", help="record run.bag (commands, odometry, plans, ...)")
    parser.add_argument("--keep-ros-logs", action="store_true",
                        help="keep the nodes' ROS logs (every level, rosout included) in OUT/ros_home/log")
    add_separate_processes_argument(parser)
    parser.add_argument("--lockstep", action=argparse.BooleanOptionalAction, default=True,
                        help="the simulator waits for the nodes' work (flex_nav_sim.lockstep), so a run ends the same "
                             "at any rtf and load (default); --no-lockstep: it keeps its rtf whatever the nodes do")
    parser.add_argument("--social-distance", type=float, default=SOCIAL_DISTANCE_M, metavar="M",
                        help="[m] keep this distance from tracked people while moving (push_or_avoid's follower; "
                             f"default {SOCIAL_DISTANCE_M:g}; 0: off)")
    parser.add_argument("--yield-planner", choices=PLANNERS, default=DEFAULT_YIELD_PLANNER,
                        help="how push_or_avoid's follower gives way to walkers: 'rules', 'space_time' (its speed "
                             "along the path planned around the walkers' learnt lanes) or 'checked' (the rules, each "
                             f"decision checked by that planner; the default, {DEFAULT_YIELD_PLANNER!r})")
    parser.add_argument("--yield-param", action="append", default=[], metavar="KEY=VALUE",
                        help="a parameter of push_or_avoid's follower's ~yielding/ (a YieldParams field, e.g. "
                             "check_moving_gap_m=0.3), after --yield-planner's; repeatable")
    parser.add_argument("--trips", type=int, default=1,
                        help="start -> goal this many times, driving back to the start between them (default 1)")
    parser.add_argument("--clear-between-trips", action="store_true",
                        help="clear both costmaps (ClearCostmap) at the start before each further trip")
    parser.add_argument("--behavior-param", action="append", default=[], metavar="KEY=VALUE",
                        help="behavior parameter override, a YAML value (e.g. remember_heavy=true); repeatable")
    add_localization_argument(parser)
    args = parser.parse_args(argv)
    if args.trips < 1:
        parser.error(f"--trips must be at least 1, got {args.trips}")
    args.behavior_params = key_values(parser, "--behavior-param", args.behavior_param)
    args.yield_params = key_values(parser, "--yield-param", args.yield_param)
    fields = sorted(f.name for f in dataclasses.fields(YieldParams))
    for key in args.yield_params:
        if key not in fields:
            parser.error(f"--yield-param: {choices_message('yield parameter', key, fields)}")
    return args


def key_values(parser: argparse.ArgumentParser, option: str, items: Sequence[str]) -> Dict[str, Any]:
    """``KEY=VALUE`` items (each VALUE a YAML value) by key; a malformed item is the parser's error."""
    values: Dict[str, Any] = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key:
            parser.error(f"{option} takes KEY=VALUE, got {item!r}")
        values[key] = yaml.safe_load(text)
    return values


def trip_goals(goal: Tuple[float, float, float], start: Tuple[float, float, float],
               trips: int) -> List[Tuple[str, Tuple[float, float, float]]]:
    """The goals of ``trips`` trips: ``goal``, then (``start``, ``goal``) for every further trip."""
    return [("goal", goal)] + [("start", start), ("goal", goal)] * (trips - 1)


class ScenarioMonitor(DemoMonitor):
    """The demo monitor plus what the scenario table needs: pushes and contacts with people."""

    def __init__(self, runs: List[RobotRun], localizer: bool = True) -> None:
        super().__init__(runs, localizer)
        from flex_nav.msg import SimEvent  # noqa: PLC0415

        self.pushes_tried = 0
        self.pushes_succeeded = 0
        self.people_contacts: List[Tuple[float, str]] = []
        self.robot_caused_contacts = 0  # of people_contacts, the robot's doing (metrics.classify_contact)
        self.timed_trajectory: List[Tuple[float, float, float]] = []  # (sim s, x, y)
        # the newest ground truth: (x, y, yaw) [m, m, rad] and the twist (v [m/s], w [rad/s]) in the base frame
        self._truth: Optional[Tuple[Tuple[float, float, float], float, float]] = None
        self._event_lock = threading.Lock()
        from geometry_msgs.msg import Twist  # noqa: PLC0415

        self.commands: List[Tuple[float, float]] = []  # (sim s, v [m/s]) of the robot's velocity commands
        self.subs.append(self.rospy.Subscriber(f"/{ROBOT}/sim_events", SimEvent, self._on_sim_event, queue_size=50))
        self.subs.append(self.rospy.Subscriber(f"/{ROBOT}/cmd_vel", Twist, self._on_command, queue_size=50))

    def _on_command(self, msg: Any) -> None:
        with self._event_lock:
            self.commands.append((self.sim_s(), msg.linear.x))

    def command_log(self) -> List[Tuple[float, float]]:
        """The robot's velocity commands so far, (sim s, v [m/s]) in time order."""
        with self._event_lock:
            return sorted(self.commands)

    def _on_odom(self, msg: Any, run: RobotRun) -> None:
        super()._on_odom(msg, run)
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        yaw = yaw_of_quaternion(q.x, q.y, q.z, q.w)
        with self._event_lock:
            self.timed_trajectory.append((msg.header.stamp.to_sec(), p.x, p.y))
            self._truth = ((p.x, p.y, yaw), msg.twist.twist.linear.x, msg.twist.twist.angular.z)

    def _on_transition(self, msg: Any, run: RobotRun) -> None:
        super()._on_transition(msg, run)
        if msg.path.endswith("/Push"):
            with self._event_lock:
                self.pushes_tried += 1
                self.pushes_succeeded += msg.outcome == "done"

    def _on_sim_event(self, msg: Any) -> None:
        if msg.other_kind == "person" and msg.kind == msg.CONTACT_BEGIN:
            with self._event_lock:
                self.people_contacts.append((msg.header.stamp.to_sec(), msg.other))
                truth = self._truth
            cause = "counted as robot-caused: no ground truth of the robot yet to classify it by"
            robot_caused = True  # what cannot be classified counts against the robot
            if truth is not None:
                pose, v, w = truth
                try:
                    classified = classify_contact(pose, v, w, (msg.position.x, msg.position.y))
                except ValueError as err:
                    cause = f"counted as robot-caused: {err}"
                else:
                    robot_caused = classified.robot_caused
                    cause = ("robot-caused" if robot_caused else "person-caused") + f": {classified.reason}"
            with self._event_lock:
                self.robot_caused_contacts += robot_caused
            print(f"[sim {self.sim_s():7.1f} s] CONTACT with person {msg.other} ({cause})", flush=True)


def start(stack: contextlib.ExitStack, args: argparse.Namespace, run: RobotRun) -> List[ManagedProcess]:
    """The demo's system with the camera, the scenario parameters and the obstacle classifier."""
    params: Dict[str, object] = {
        f"/{ROBOT}/pure_pursuit_path/blocked_distance": BLOCKED_DISTANCE_M,
        f"/{ROBOT}/pure_pursuit_path/yield_to_people": True,  # push_or_avoid's follower
        f"/{ROBOT}/pure_pursuit_path/yielding/hurry_speed_mps": HURRY_SPEED_MPS,
    }
    if args.yield_planner == "space_time":  # the planner times its crossings itself (issue 28, h6)
        params.update({f"/{ROBOT}/pure_pursuit_path/yielding/{key}": value
                       for key, value in SPACE_TIME_YIELDING.items()})
    elif args.yield_planner == "checked":
        params[f"/{ROBOT}/pure_pursuit_path/yielding/planner"] = "checked"
    params.update({f"/{ROBOT}/pure_pursuit_path/yielding/{key}": value for key, value in args.yield_params.items()})
    if args.social_distance > 0.0:
        social: Dict[str, object] = {"enabled": True, "min_distance_m": args.social_distance}
        if args.yield_planner != "rules":  # its slow-down near people would break the plan's timing
            social["slow_distance_m"] = args.social_distance + SPACE_TIME_SLOW_EXTRA_M
        params[f"/{ROBOT}/pure_pursuit_path/social_distance"] = social
    if args.lockstep:
        params["/lockstep"] = True
        params["/sim/world_start"] = "on_request"  # start_at_grid starts the world's script with the goal
        params[f"/{ROBOT}/localizer/seed"] = args.seed  # and the initial pose then restarts the filter's generator
    if args.behavior_params:
        params[f"/{ROBOT}/behavior_runner/parameters"] = dict(args.behavior_params)
    for costmap in ("get_path_server/global_costmap", "pure_pursuit_path/local_costmap",
                    "pure_pursuit_topic/local_costmap"):
        params[f"/{ROBOT}/{costmap}/bumper_memory"] = BUMPER_MEMORY_S
    system = argparse.Namespace(world=args.world, rtf=args.rtf, seed=args.seed, gui=False, autonomy="full",
                                behavior=args.behavior, localization=args.localization, map=None,
                                separate_processes=args.separate_processes)
    processes, env = start_system(stack, system, [run], args.out, camera=True, params=params, bag=args.bag)
    classifier = ManagedProcess(["rosrun", "flex_nav", "obstacle_classifier", f"__ns:={ROBOT}", "_max_rate:=5.0"],
                                env=env, log_path=args.out / "logs" / "classifier.log")
    stack.callback(classifier.stop)
    return [*processes, classifier]


def send_first_goal(monitor: ScenarioMonitor, lockstep: bool, wall_deadline: float) -> Tuple[Optional[str], float]:
    """Send the first goal SETTLE_S [s] of simulated time after the system is ready (odometry, scans and the first
    class votes flow); in lockstep by :func:`start_at_grid`. (The reason if it failed, else None; the simulated
    time [s] the world's script started at.)"""
    if lockstep:
        return start_at_grid(monitor, monitor.sim_s(), wall_deadline)
    settle_until = monitor.sim_s() + SETTLE_S
    while monitor.sim_s() < settle_until and time.monotonic() < wall_deadline:
        time.sleep(0.1)
    monitor.send_due_goals()
    return None, 0.0


def world_start_s(not_before_s: float, sim_s: float) -> float:
    """[s] Where the world's script starts: WORLD_START_S, the same simulated time in every run, so not only the
    sensors' schedule but every floating-point sum of absolute times agrees (a start 4 s later parted a run by
    1e-17 m at the first step, and after a walker's close pass by 6 s); when the simulation (at ``sim_s`` [s]) is
    nearly there or beyond, the first grid point from ``not_before_s`` [s] on that it has not nearly reached (half a
    grid ahead)."""
    grid_s = math.ceil(max(not_before_s, sim_s + START_GRID_S / 2.0) / START_GRID_S) * START_GRID_S
    return max(grid_s, WORLD_START_S)


def forget_people(before_s: float) -> Optional[str]:
    """Ask every controller of the robot that tracks people (``~people_tracker/forget``) to forget its tracks and
    lanes and take no scan stamped before ``before_s`` [s] (the reason if one refused or failed, else None)."""
    import rosgraph  # noqa: PLC0415
    import rospy  # noqa: PLC0415

    from flex_nav.srv import ForgetTracks  # noqa: PLC0415

    served = {name for name, _providers in rosgraph.Master(rospy.get_name()).getSystemState()[2]}
    for controller in PEOPLE_TRACKERS:
        service = f"/{ROBOT}/{controller}/people_tracker/forget"
        if service not in served:
            continue
        try:
            answer = rospy.ServiceProxy(service, ForgetTracks)(rospy.Time.from_sec(before_s))
        except (rospy.ROSException, rospy.ServiceException) as err:
            return f"{service} failed: {err}"
        if not answer.ok:
            return f"{service} refused: {answer.message}"
    return None


def start_at_grid(monitor: ScenarioMonitor, not_before_s: float, wall_deadline: float) -> Tuple[Optional[str], float]:
    """Lockstep: hold the simulation at :func:`world_start_s` and start the world's script there
    (``/sim/start_world``); hold it again WORLD_LEAD_S later, send the goal, let go. So the run, its walkers and its
    noise begin at the same simulated time whatever the rtf or load, and the goal comes as long after the world's
    start as it did after t = 0 when the world started with the simulation (events such as "the person leaves at
    25 s" keep their meaning). The people trackers forget what they saw before the world's start
    (:func:`forget_people`): how many scans they took before it depends on when their node came up. (The reason
    if it failed, else None; the simulated time [s] the world's script started at.)"""
    import rospy  # noqa: PLC0415
    from std_srvs.srv import Trigger  # noqa: PLC0415

    from flex_nav.ros.lockstep import LockstepParticipant  # noqa: PLC0415

    hold = LockstepParticipant("start", enabled=True)

    def held_at(stamp_s: float) -> Optional[str]:
        hold.hold_clock(stamp_s)
        while monitor.sim_s() < stamp_s:
            if time.monotonic() > wall_deadline or rospy.is_shutdown():
                return f"simulated time did not reach {stamp_s:g} s"
            time.sleep(0.01)
        if monitor.sim_s() > stamp_s + START_GRID_S / 2.0:
            return f"the simulation passed {stamp_s:g} s before holding there (at {monitor.sim_s():.2f} s)"
        return None

    try:
        if not hold.wait_connected(max(0.0, wall_deadline - time.monotonic())):
            return "the simulator did not subscribe to the lockstep holds", not_before_s
        world_s = world_start_s(not_before_s, monitor.sim_s())
        if world_s > WORLD_START_S:
            print(f"scenario_run: the system was up only at {monitor.sim_s():.1f} s of simulated time: the world "
                  f"starts at {world_s:g} s, not at {WORLD_START_S:g} s (runs that start elsewhere may part)",
                  file=sys.stderr)
        problem = held_at(world_s) or forget_people(world_s)
        if problem is not None:
            return problem, world_s
        try:
            rospy.wait_for_service("/sim/start_world", timeout=CLEAR_TIMEOUT_S)
            answer = rospy.ServiceProxy("/sim/start_world", Trigger)()
        except (rospy.ROSException, rospy.ServiceException) as err:
            return f"/sim/start_world failed: {err}", world_s
        if not answer.success:
            return f"/sim/start_world refused: {answer.message}", world_s
        problem = held_at(world_s + WORLD_LEAD_S)
        if problem is not None:
            return problem, world_s
        monitor.send_due_goals(world_s + WORLD_LEAD_S)  # stamped where the simulation stands
        time.sleep(START_WALL_WAIT_S)
    finally:
        hold.release()
    return None, world_s


def main(argv: Optional[Sequence[str]] = None) -> int:  # noqa: PLR0915 - one linear script of a run
    args = parse_args(argv)
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    try:
        world = load_world(args.world)
        goal = world.goals["goal"]
    except (FlexNavError, KeyError) as err:
        print(f"scenario_run: world {args.world!r}: {err}", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    start_pose = world.spawns[0].pose if world.spawns else world.goals["start"]
    run = RobotRun(ROBOT, PROFILE, trip_goals(goal, world.goals.get("start", start_pose), args.trips))
    run.pose = start_pose
    started = time.monotonic()
    result = RunResult(world=world.name, behavior=args.behavior, seed=args.seed)
    with contextlib.ExitStack() as stack:
        signal.signal(signal.SIGTERM, _interrupt)
        processes = start(stack, args, run)
        from flex_nav.ros.node import init_node  # noqa: PLC0415

        init_node("scenario_run")
        import rospy  # noqa: PLC0415

        monitor = ScenarioMonitor([run], localizer=args.localization == "localizer")
        problem = wait_until_ready(monitor, processes, STARTUP_TIMEOUT_S)
        if problem is not None:
            print(f"scenario_run: startup failed: {problem}; logs in {args.out / 'logs'}", file=sys.stderr)
            return 2
        wall_deadline = started + args.timeout
        problem, world_start_s = send_first_goal(monitor, args.lockstep, wall_deadline)
        if problem is not None:
            print(f"scenario_run: {problem}; logs in {args.out / 'logs'}", file=sys.stderr)
            return 2
        goal_sim_s = monitor.sim_s()
        cleared_before: Set[int] = set()  # goal indices before which the costmaps were cleared
        while not monitor.done() and not rospy.is_shutdown():
            with monitor.lock:
                back_at_start = run.completed % 2 == 0 and run.next_goal == run.completed > 0
            if args.clear_between_trips and back_at_start and run.completed not in cleared_before:
                cleared_before.add(run.completed)
                problem = clear_costmaps()
                print(f"[sim {monitor.sim_s():7.1f} s] costmaps cleared before trip {run.completed // 2 + 1}"
                      f"{': ' + problem if problem else ''}", flush=True)
            monitor.send_due_goals()  # the next trip's goal, once the behavior waits for it
            with monitor.lock:
                leg_started_s = run.goal_started_sim_s
            if monitor.sim_s() - leg_started_s > args.sim_limit:
                result.note = f"sim limit {args.sim_limit:g} s"
                break
            if time.monotonic() > wall_deadline:
                result.note = f"wall timeout {args.timeout:g} s"
                break
            dead = [p for p in processes if not p.running()]
            if dead:
                result.note = f"{' '.join(dead[0].argv[:4])} exited"
                break
            time.sleep(0.1)
        monitor.stopping = True
        with monitor.lock:
            result.success = run.reached == len(run.goals)
            first_reached = bool(run.goal_times_s) and math.isfinite(run.goal_times_s[0])
            result.time_s = run.goal_times_s[0] if first_reached else math.nan
            if args.trips > 1:  # the goals at even indices are the trips' goals; the rest drive back
                result.trip_times_s = [run.goal_times_s[i] if i < len(run.goal_times_s) else math.nan
                                       for i in range(0, len(run.goals), 2)]
            if result.success and run.pose is not None:
                result.heading_error_deg = heading_error_deg(run.pose, goal)
            result.path_m = run.distance_m
            result.pushes_tried = monitor.pushes_tried
            result.pushes_succeeded = monitor.pushes_succeeded
            result.people_contacts = len(monitor.people_contacts)
            result.people_contacts_robot_caused = monitor.robot_caused_contacts
            result.people_contacts_person_caused = result.people_contacts - monitor.robot_caused_contacts
            trajectory = [(t, x, y) for t, x, y in monitor.timed_trajectory if t >= goal_sim_s]
        commands = monitor.command_log()
        result.min_people_clearance_m = people_clearance(world, trajectory, world_start_s=world_start_s)
        result.min_people_clearance_moving_m = people_clearance(world, trajectory, moving_only=True,
                                                                commands=commands, world_start_s=world_start_s)
        if not result.note and not result.success:
            result.note = run.failed_reason or "goal given up"
    title = (f"{args.behavior} in {world.name} (seed {args.seed}): "
             f"{'reached' if result.success else 'NOT reached'}")
    picture = write_picture(args.out, map_of_world(args.world, args.out), [run], title)
    result.picture = str(picture)
    if not args.keep_ros_logs:
        shutil.rmtree(args.out / "ros_home", ignore_errors=True)
    print("RESULT " + json.dumps(result.to_dict()), flush=True)
    return 0


def clear_costmaps() -> str:
    """Clear the robot's global and controller costmaps (ClearCostmap, each bounded; a goal left without a result is
    sent once more, and that is printed); what went wrong, or ""."""
    import actionlib  # noqa: PLC0415
    import rospy  # noqa: PLC0415

    from flex_nav.msg import ClearCostmapAction, ClearCostmapGoal, ClearCostmapResult  # noqa: PLC0415

    problems = []
    for name in CLEAR_COSTMAPS:
        client = actionlib.SimpleActionClient(f"/{ROBOT}/{name}", ClearCostmapAction)
        if not client.wait_for_server(rospy.Duration(CLEAR_TIMEOUT_S)):
            problems.append(f"{name}: no server within {CLEAR_TIMEOUT_S:g} s")
            continue
        answered = False
        for attempt in range(1, CLEAR_ATTEMPTS + 1):
            client.send_goal(ClearCostmapGoal())
            answered = client.wait_for_result(rospy.Duration(CLEAR_TIMEOUT_S))
            if answered:
                break
            client.cancel_goal()
            print(f"scenario_run: {name}: no result within {CLEAR_TIMEOUT_S:g} s (attempt {attempt} of "
                  f"{CLEAR_ATTEMPTS})", flush=True)
        if not answered:
            problems.append(f"{name}: no result within {CLEAR_TIMEOUT_S:g} s, {CLEAR_ATTEMPTS} times")
            continue
        result = client.get_result()
        if result is None or result.code != ClearCostmapResult.SUCCESS:
            problems.append(f"{name}: {result.message if result is not None else 'no result'}")
    return "; ".join(problems)


def _interrupt(_signum: int, _frame: object) -> None:
    raise KeyboardInterrupt


if __name__ == "__main__":
    sys.exit(main())
