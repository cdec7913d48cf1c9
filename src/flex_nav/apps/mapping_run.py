"""Map a simulated world from scratch: the explore behavior on flex_nav's mapper, headless, with a progress line,
then the map files, a picture and the metrics.

    python -m flex_nav.apps.mapping_run --world lab --out /tmp/lab_map

Starts a private master, the simulator (no map server, no oracle: the mapper publishes ``/map`` and
``map -> robot1/odom``), one robot's stack (flex_nav_robot.launch mapper:=true behavior:=explore) and follows the
behavior until it ends (it saves the map through the mapper's ``save_map`` and drives back to the start) or
``--timeout`` [s, wall] passes. Writes into ``--out``: ``map.yaml`` + ``map.pgm`` (saved by the behavior),
``map.posegraph`` (the mapper's graph), ``map.png`` (the built map over the world's true walls, the estimated
trajectory, the loop closures), ``metrics.json`` and ``logs/``. Exit status 0 when the behavior finished and the
map was saved, 1 otherwise, 2 when it could not start.

The metrics compare the built map with the world's ground-truth map (``sim/worlds/maps/<world>.yaml``), the map
frame placed in the world by the first pose estimate and the ground truth at its stamp (``map``), and placed by the
rigid alignment of the whole optimised trajectory with the ground truth (``map_aligned``: one pose's error does not
tilt the whole map): cells agreeing, walls' offsets, the share of the reachable free area known; and the ATE against
the ground truth computed with evo (SE(3)-aligned and as placed) of the trajectory after the last optimisation (the
keyframes' poses in the final graph, at their scans' stamps) and of the live pose estimates (``pose``, each as the
mapper knew it then, before later loop closures corrected it); plus the time, the distance driven and the bumper
contacts.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import signal
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

import yaml

from flex_nav.apps.eval.map_quality import aligned_placement, ate_rmse_cm, draw_map, score_map
from flex_nav.exceptions import ConfigError, FlexNavError
from flex_nav.nav.planar import Pose2D, compose_poses, inverse_pose
from flex_nav.resources import share_dir
from flex_nav.testing.private_master import PrivateMaster
from flex_nav.testing.process import ManagedProcess

REPO_ROOT = Path(__file__).resolve().parents[3]
ROBOT = "robot1"
PROFILES = {"kobuki": "kobuki", "turtlebot2": "kobuki", "create": "create2", "create2": "create2",
            "turtlebot4": "turtlebot4"}
NAV_CONFIG = {"kobuki": "turtlebot2", "create2": "create", "turtlebot4": "turtlebot4"}
PROGRESS_S = 10.0  # [s] wall between progress lines
PAIR_TOLERANCE_S = 0.05  # [s] a pose estimate and a ground-truth sample this close in time form a pair


def parse_args(argv: Optional[Sequence[str]] = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m flex_nav.apps.mapping_run", description=__doc__.split("\n\n")[0])
    parser.add_argument("--world", default="lab", help="a world of sim/worlds (lab, two_rooms, ...)")
    parser.add_argument("--out", type=Path, default=None, help="output folder (default out/mapping-<time>)")
    parser.add_argument("--profile", default="kobuki", choices=sorted(PROFILES))
    parser.add_argument("--rtf", type=float, default=2.0, help="simulation real-time factor")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--autonomy", default="full", choices=("off", "low", "high", "full"),
                        help="low: the operator approves every frontier (behavior_runner's operator interface)")
    parser.add_argument("--timeout", type=float, default=900.0, help="[s] wall-time bound on the whole run")
    parser.add_argument("--no-loop-closure", action="store_true", help="map without loop closing (for comparison)")
    parser.add_argument("--explore-param", action="append", default=[], metavar="NAME=VALUE",
                        help="an explore behavior parameter (behaviors/explore.yaml), e.g. size_weight=0.5; repeatable")
    return parser.parse_args(argv)


@dataclass
class Progress:
    """What the monitor has seen (guarded by ``lock``)."""

    lock: threading.Lock = field(default_factory=threading.Lock)
    truth: List[Tuple[float, Pose2D]] = field(default_factory=list)  # (stamp [s], pose) ground truth, world frame
    estimates: List[Tuple[float, Pose2D]] = field(default_factory=list)  # (stamp [s], pose) mapper, map frame
    distance_m: float = 0.0
    contacts: int = 0
    last_contact_s: float = -math.inf
    touched: Dict[str, int] = field(default_factory=dict)  # the simulator's contacts: object name -> count
    frontiers: int = 0
    outcome: Optional[str] = None
    reason: str = ""
    behavior_started_s: Optional[float] = None  # [s] sim time the runner reported the behavior running
    behavior_ended_s: Optional[float] = None  # [s] sim time it reported the end
    mapper_status: str = ""
    known_cells: int = 0


class MappingMonitor:
    """The run's ROS node: follows the robot, the mapper and the behavior."""

    def __init__(self, progress: Progress) -> None:
        import rospy  # noqa: PLC0415 - rospy only once the master is up
        from geometry_msgs.msg import PointStamped, PoseWithCovarianceStamped  # noqa: PLC0415
        from nav_msgs.msg import OccupancyGrid, Odometry  # noqa: PLC0415
        from std_msgs.msg import String  # noqa: PLC0415

        from flex_nav.msg import BehaviorStatus, BehaviorTransition, SimEvent  # noqa: PLC0415

        self.rospy = rospy
        self.progress = progress
        ns = f"/{ROBOT}"
        self.subs = [
            rospy.Subscriber(f"{ns}/ground_truth", Odometry, self._on_truth, queue_size=20),
            rospy.Subscriber(f"{ns}/pose", PoseWithCovarianceStamped, self._on_estimate, queue_size=20),
            rospy.Subscriber(f"{ns}/bumper_hits", PointStamped, self._on_bumper, queue_size=10),
            rospy.Subscriber(f"{ns}/behavior_runner/status", BehaviorStatus, self._on_status, queue_size=5),
            rospy.Subscriber(f"{ns}/behavior_runner/transitions", BehaviorTransition, self._on_transition,
                             queue_size=50),
            rospy.Subscriber(f"{ns}/mapper/status", String, self._on_mapper_status, queue_size=5),
            rospy.Subscriber("/map", OccupancyGrid, self._on_map, queue_size=1),
            rospy.Subscriber(f"{ns}/sim_events", SimEvent, self._on_sim_event, queue_size=50),
        ]

    def sim_s(self) -> float:
        return float(self.rospy.get_time())

    def say(self, text: str) -> None:
        print(f"[sim {self.sim_s():7.1f} s] {text}", flush=True)

    def _on_truth(self, msg: Any) -> None:
        pose = _planar(msg.pose.pose)
        with self.progress.lock:
            if self.progress.truth:
                self.progress.distance_m += math.dist(pose[:2], self.progress.truth[-1][1][:2])
            self.progress.truth.append((msg.header.stamp.to_sec(), pose))

    def _on_estimate(self, msg: Any) -> None:
        with self.progress.lock:
            self.progress.estimates.append((msg.header.stamp.to_sec(), _planar(msg.pose.pose)))

    def _on_bumper(self, _msg: Any) -> None:
        now = self.sim_s()
        with self.progress.lock:
            new_press = now - self.progress.last_contact_s > 0.5  # one press reports several contact points
            self.progress.last_contact_s = now
            self.progress.contacts += int(new_press)
        if new_press:
            self.say("BUMPER contact")

    def _on_sim_event(self, msg: Any) -> None:
        """What the robot touched, as the simulator knows it (the bumper cannot tell a wall from the low step)."""
        if msg.kind == msg.CONTACT_BEGIN:
            with self.progress.lock:
                self.progress.touched[msg.other] = self.progress.touched.get(msg.other, 0) + 1

    def _on_status(self, msg: Any) -> None:
        now = msg.header.stamp.to_sec() or self.sim_s()  # latched: the stamp says when it changed
        if msg.code == msg.RUNNING:
            with self.progress.lock:
                if self.progress.behavior_started_s is None:
                    self.progress.behavior_started_s = now
        if msg.code in (msg.FINISHED, msg.PREEMPTED, msg.FAILED):
            with self.progress.lock:
                self.progress.outcome = msg.outcome or ("failed" if msg.code == msg.FAILED else "preempted")
                self.progress.reason = msg.reason
                self.progress.behavior_ended_s = now

    def _on_transition(self, msg: Any) -> None:
        if msg.path.endswith("/FindFrontier") and msg.outcome == "found":
            with self.progress.lock:
                self.progress.frontiers += 1
        if not msg.path.count("/") > 2:  # the top level's transitions only: the rest is too chatty
            self.say(f"{msg.path} --{msg.outcome}--> {msg.target}")

    def _on_mapper_status(self, msg: Any) -> None:
        with self.progress.lock:
            self.progress.mapper_status = msg.data

    def _on_map(self, msg: Any) -> None:
        import numpy as np  # noqa: PLC0415

        known = int(np.count_nonzero(np.asarray(msg.data, dtype=np.int8) >= 0))
        with self.progress.lock:
            self.progress.known_cells = known


def _planar(pose: Any) -> Pose2D:
    from flex_nav.nav.pose_checks import yaw_of_quaternion  # noqa: PLC0415

    q = pose.orientation
    return (pose.position.x, pose.position.y, yaw_of_quaternion(q.x, q.y, q.z, q.w))


def start_system(stack: contextlib.ExitStack, args: argparse.Namespace, out: Path) -> List[ManagedProcess]:
    """The private master, the simulator (no map server, no oracle) and the robot's stack with the mapper and the
    explore behavior; ``stack`` stops them all."""
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    logs = out / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    master = stack.enter_context(PrivateMaster(ros_home=out / "ros_home"))
    os.environ.update(master.env)
    import rosgraph  # noqa: PLC0415

    world = load_world(args.world)
    x, y, yaw = world.spawns[0].pose
    parameters = rosgraph.Master("/mapping_run", master_uri=master.uri)
    parameters.setParam("/use_sim_time", True)
    # the map frame on the world's: the robot starts where the world file spawns it (as a robot started at a known
    # dock), so that the saved map and the world's goals line up
    parameters.setParam(f"/{ROBOT}/mapper/map_start_pose", [x, y, yaw])
    mapper_config = share_dir() / "config" / "mapper.yaml"
    if args.no_loop_closure:  # the launch file loads the config over any parameter set here: a copy, changed
        values = yaml.safe_load(mapper_config.read_text(encoding="utf-8"))
        values["do_loop_closing"] = False
        mapper_config = out / "mapper_no_loop_closure.yaml"
        mapper_config.write_text(yaml.safe_dump(values), encoding="utf-8")
    profile = PROFILES[args.profile]
    explore_parameters: Dict[str, Any] = {"map_path": str(out / "map"), "pose_topic": "pose",
                                          "pose_type": "pose_with_covariance", "profile": profile}
    for item in args.explore_param:
        name, separator, value = item.partition("=")
        if not separator or not name:
            raise ConfigError(f"--explore-param must be NAME=VALUE, got {item!r}")
        explore_parameters[name] = yaml.safe_load(value)  # a number, a word or a list, as YAML reads it
    behavior_parameters = json.dumps(explore_parameters)
    processes = [
        ManagedProcess(["rosrun", "flex_nav", "sim", f"_world:={args.world}",
                        f"_robots:={ROBOT}:{profile}:{x}:{y}:{math.degrees(yaw):.1f}", f"_rtf:={args.rtf}",
                        f"_seed:={args.seed}", "_camera:=false", "_publish_map_odom:=false",
                        "_publish_initial_pose:=false"],
                       env=master.env, log_path=logs / "sim.log"),
        ManagedProcess(["roslaunch", "flex_nav", "flex_nav_robot.launch", f"robot:={ROBOT}", f"profile:={profile}",
                        "twist_relay:=true", "mapper:=true", f"mapper_config:={mapper_config}", "behavior:=explore",
                        f"autonomy:={args.autonomy}",
                        f"behavior_parameters:={behavior_parameters}"],
                       env=master.env, log_path=logs / f"{ROBOT}.log"),
    ]
    for proc in processes:
        stack.callback(proc.stop)
    return processes


def pairs(progress: Progress) -> Tuple[List[Pose2D], List[Pose2D]]:
    """(estimates, truths) at the same stamps (within PAIR_TOLERANCE_S): the mapper's live ``pose`` estimates."""
    with progress.lock:
        truth = list(progress.truth)
        estimates = list(progress.estimates)
    return pair_with_truth(estimates, truth)


def pair_with_truth(stamped: Sequence[Tuple[float, Pose2D]], truth: Sequence[Tuple[float, Pose2D]],
                    ) -> Tuple[List[Pose2D], List[Pose2D]]:
    """(poses, truths) of the ``stamped`` poses (stamp [s], pose) with a ground-truth sample within
    PAIR_TOLERANCE_S of their stamp."""
    import numpy as np  # noqa: PLC0415

    if not truth or not stamped:
        return [], []
    stamps = np.array([t for t, _ in truth])
    out_e, out_t = [], []
    for stamp, pose in stamped:
        index = int(np.argmin(np.abs(stamps - stamp)))
        if abs(stamps[index] - stamp) <= PAIR_TOLERANCE_S:
            out_e.append(pose)
            out_t.append(truth[index][1])
    return out_e, out_t


def optimised_keyframes(graph: Dict[str, Any]) -> List[Tuple[float, Pose2D]]:
    """(stamp [s], optimised pose) of every stamped keyframe of a serialized graph (``~serialize_map``)."""
    poses = graph["graph"]["poses"]
    return [(float(k["stamp"]), (poses[i][0], poses[i][1], poses[i][2]))
            for i, k in enumerate(graph["keyframes"]) if k.get("stamp") is not None and i < len(poses)]


def write_results(out: Path, args: argparse.Namespace, progress: Progress, *, sim_s: float, wall_s: float,
                  graph: Optional[Dict[str, Any]]) -> Dict[str, Any]:
    """Score the saved map and the trajectory; write map.png and metrics.json; return the metrics."""
    import cv2  # noqa: PLC0415

    from flex_nav.nav.costmap.map_io import load_map  # noqa: PLC0415
    from flex_nav_sim.profiles import load_profile  # noqa: PLC0415
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    world = load_world(args.world)
    truth_map = load_map(REPO_ROOT / "sim" / "worlds" / "maps" / f"{world.name}.yaml")
    estimates, truths = pairs(progress)
    metrics: Dict[str, Any] = {
        "world": world.name, "profile": PROFILES[args.profile], "seed": args.seed, "rtf": args.rtf,
        "outcome": progress.outcome, "reason": progress.reason, "sim_time_s": sim_s, "wall_time_s": wall_s,
        "behavior_time_s": (None if progress.behavior_started_s is None or progress.behavior_ended_s is None
                            else progress.behavior_ended_s - progress.behavior_started_s),
        "distance_m": progress.distance_m, "bumper_contacts": progress.contacts, "touched": dict(progress.touched),
        "frontiers_visited": progress.frontiers,
        "loop_closure": not args.no_loop_closure, "mapper_status": progress.mapper_status,
        "load_average": os.getloadavg()[0],
    }
    saved = out / "map.yaml"
    if not saved.is_file() or not estimates:
        metrics["map_saved"] = saved.is_file()
        (out / "metrics.json").write_text(json.dumps(metrics, indent=2), encoding="utf-8")
        return metrics
    built = load_map(saved)
    map_in_world = compose_poses(truths[0], inverse_pose(estimates[0]))
    start = world.spawns[0].pose
    radius = load_profile(PROFILES[args.profile]).radius
    score = score_map(built, truth_map, map_in_world, (start[0], start[1]), radius)
    placed = [compose_poses(map_in_world, e) for e in estimates]
    metrics.update({
        "map_saved": True, "map": score.as_dict(),
        "ate_cm_aligned": ate_rmse_cm(estimates, truths, align=True),
        "ate_cm_placed": ate_rmse_cm(placed, truths, align=False),
        "pose_pairs": len(estimates),
    })
    closures = []
    if graph is not None:
        nodes = graph["graph"]["poses"]
        with progress.lock:
            truth = list(progress.truth)
        keyframes, keyframe_truths = pair_with_truth(optimised_keyframes(graph), truth)
        if keyframes:  # the trajectory after the last optimisation (the target), beside the live estimates
            aligned = aligned_placement(keyframes, keyframe_truths)
            if aligned is not None:  # the map placed by the whole trajectory, not by its first pose alone
                metrics["map_aligned"] = score_map(built, truth_map, aligned, (start[0], start[1]), radius).as_dict()
            metrics.update({
                "ate_optimised_cm_aligned": ate_rmse_cm(keyframes, keyframe_truths, align=True),
                "ate_optimised_cm_placed": ate_rmse_cm([compose_poses(map_in_world, k) for k in keyframes],
                                                       keyframe_truths, align=False),
                "keyframe_pairs": len(keyframes),
            })
        metrics["keyframes"] = len(graph["keyframes"])
        metrics["loop_closures"] = len(graph["loop_closures"])
        for old, new, *_rest in graph["loop_closures"]:
            if old < len(nodes) and new < len(nodes):
                closures.append(((nodes[old][0], nodes[old][1]), (nodes[new][0], nodes[new][1])))
    image = draw_map(built, truth_map, map_in_world, [(p[0], p[1]) for p in estimates], closures)
    cv2.imwrite(str(out / "map.png"), image)
    (out / "metrics.json").write_text(json.dumps(metrics, indent=2), encoding="utf-8")
    return metrics


def fetch_graph(out: Path) -> Optional[Dict[str, Any]]:
    """Ask the mapper to serialize its graph to out/map.posegraph and read it back; None if that fails."""
    import rospy  # noqa: PLC0415

    from flex_nav.srv import MapFile  # noqa: PLC0415

    try:
        rospy.wait_for_service(f"/{ROBOT}/mapper/serialize_map", timeout=10.0)
        reply = rospy.ServiceProxy(f"/{ROBOT}/mapper/serialize_map", MapFile)(path=str(out / "map"))
    except (rospy.ROSException, rospy.ServiceException) as err:
        print(f"mapping_run: serialize_map failed: {err}", file=sys.stderr)
        return None
    if not reply.ok:
        print(f"mapping_run: serialize_map refused: {reply.message}", file=sys.stderr)
        return None
    data: Dict[str, Any] = json.loads((out / "map.posegraph").read_text(encoding="utf-8"))
    return data


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = parse_args(argv)
    out = (args.out or REPO_ROOT / "out" / time.strftime("mapping-%Y%m%d-%H%M%S")).resolve()
    out.mkdir(parents=True, exist_ok=True)
    print(f"flex_nav mapping run: explore in world '{args.world}' with a {args.profile}, rtf {args.rtf}, autonomy "
          f"{args.autonomy}{', loop closure off' if args.no_loop_closure else ''}; output in {out}", flush=True)
    started = time.monotonic()
    progress = Progress()
    graph: Optional[Dict[str, Any]] = None
    with contextlib.ExitStack() as stack:
        signal.signal(signal.SIGTERM, _interrupt)
        try:
            processes = start_system(stack, args, out)
        except FlexNavError as err:
            print(f"mapping_run: {err}", file=sys.stderr)
            return 2
        from flex_nav.ros.node import init_node  # noqa: PLC0415

        init_node("mapping_run")
        import rospy  # noqa: PLC0415

        monitor = MappingMonitor(progress)
        deadline = started + args.timeout
        next_line = started + PROGRESS_S
        try:
            while time.monotonic() < deadline and not rospy.is_shutdown():
                with progress.lock:
                    ended = progress.outcome is not None
                if ended:
                    break
                dead = [p for p in processes if not p.running()]
                if dead:
                    print(f"mapping_run: {' '.join(dead[0].argv[:4])} exited; logs in {out / 'logs'}", file=sys.stderr)
                    break
                if time.monotonic() >= next_line:
                    next_line += PROGRESS_S
                    with progress.lock:
                        line = (f"{progress.frontiers} frontiers, {progress.distance_m:.1f} m driven, "
                                f"{progress.known_cells} cells known, {progress.contacts} contacts; "
                                f"{progress.mapper_status}")
                    monitor.say(line)
                time.sleep(0.2)
        except KeyboardInterrupt:
            print("interrupted: stopping everything", flush=True)
        sim_s = monitor.sim_s()
        graph = fetch_graph(out)
    wall_s = time.monotonic() - started
    metrics = write_results(out, args, progress, sim_s=sim_s, wall_s=wall_s, graph=graph)
    _print_summary(metrics, out)
    return 0 if progress.outcome == "finished" and metrics.get("map_saved") else 1


def _cm(value: Optional[float]) -> str:
    return "n/a" if value is None else f"{value:.1f}"


def _s(value: Optional[float]) -> str:
    return "n/a" if value is None else f"{value:.1f} s"


def _print_summary(metrics: Dict[str, Any], out: Path) -> None:
    print(f"behavior: {metrics['outcome']} {metrics['reason']}".rstrip(), flush=True)
    print(f"time: sim {metrics['sim_time_s']:.1f} s (the behavior {_s(metrics['behavior_time_s'])}), wall "
          f"{metrics['wall_time_s']:.1f} s; driven "
          f"{metrics['distance_m']:.1f} m; frontiers {metrics['frontiers_visited']}; bumper contacts "
          f"{metrics['bumper_contacts']}; touched (simulator) "
          f"{', '.join(f'{name} x{n}' for name, n in sorted(metrics['touched'].items())) or 'nothing'}", flush=True)
    score = metrics.get("map")
    if score:
        print(f"map: {100 * score['agree']:.1f} % of {score['compared']} observed cells agree with the ground truth; "
              f"walls median {score['wall_median_cm']:.1f} cm off (p95 {score['wall_p95_cm']:.1f}); "
              f"{100 * score['explored']:.1f} % of the reachable free area known (map placed by the first pose)",
              flush=True)
        aligned_score = metrics.get("map_aligned")
        if aligned_score:
            print(f"map placed by the optimised trajectory's alignment: {100 * aligned_score['agree']:.1f} % agree; "
                  f"walls median {aligned_score['wall_median_cm']:.1f} cm off (p95 "
                  f"{aligned_score['wall_p95_cm']:.1f})", flush=True)
        print(f"trajectory (evo ATE, SE(3)-aligned / as placed): optimised keyframes "
              f"{_cm(metrics.get('ate_optimised_cm_aligned'))} / {_cm(metrics.get('ate_optimised_cm_placed'))} cm, "
              f"live pose estimates {_cm(metrics.get('ate_cm_aligned'))} / {_cm(metrics.get('ate_cm_placed'))} cm; "
              f"{metrics.get('keyframes')} keyframes, {metrics.get('loop_closures')} loop closures", flush=True)
    print(f"files: {out / 'map.yaml'}, {out / 'map.png'}, {out / 'metrics.json'}", flush=True)


def _interrupt(_signum: int, _frame: object) -> None:
    raise KeyboardInterrupt


if __name__ == "__main__":
    sys.exit(main())
