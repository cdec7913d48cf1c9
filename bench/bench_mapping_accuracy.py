#!/usr/bin/env python3
"""Mapping accuracy and speed: flex_nav.mapping.GraphSlam on a scripted tour of a simulated world, against the
world's ground-truth map and the simulator's ground-truth poses.

Without ROS: :class:`flex_nav_sim.simulation.Simulation` runs the world with one robot (its noisy wheel odometry,
its lidar; the boxes of the world are in the scans but not in the ground-truth map). The robot drives a tour of
way points, steered on ground truth (what is measured is the mapper, not a controller); the mapper gets every scan
with the odometry interpolated to its stamp, as the node does.

Printed, per world and seed, with loop closure on and off (the same drive):
- trajectory: ATE (RMSE of the keyframes' positions against ground truth, the map frame placed on the world by the
  first pose: no fitting) [cm], with evo's SE(2) Umeyama-aligned ATE beside it when evo is installed;
- map: of the cells the ground-truth map calls free or occupied and the mapper observed, the share that agree
  (target >= 97 %); the distance of every mapped wall cell to the true wall, median and p95 [cm] (target: median
  <= 5 cm), and the share farther than 15 cm (doubled or ghost walls);
- speed: per-scan processing (GraphSlam.add_scan) median and p95 [ms] (target: median <= 20 ms), the keyframes'
  processing alone, the loop closures accepted and rejected, and the machine's load.
Writes a PNG per run (``--png DIR``): the built map, the true walls and the trajectory.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Dict, List, Optional, Tuple

import cv2
import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))
sys.path.insert(0, str(REPO / "bench"))

from bench_localization_accuracy import CRUISE, TURN_RATE, LapDriver, Waypoint, interpolate  # noqa: E402

from flex_nav.apps.eval.map_quality import GHOST_M, ate_rmse_cm, draw_map, score_map  # noqa: E402
from flex_nav.localization import ScanBeams  # noqa: E402
from flex_nav.mapping.slam import GraphSlam, SlamParams  # noqa: E402
from flex_nav.nav.costmap.map_io import load_map  # noqa: E402
from flex_nav.nav.planar import Pose2D, compose_poses, inverse_pose  # noqa: E402
from flex_nav_sim.profiles import load_profile  # noqa: E402
from flex_nav_sim.readings import OdometryReading, ScanReading  # noqa: E402
from flex_nav_sim.simulation import SensorOptions, Simulation  # noqa: E402
from flex_nav_sim.world import Spawn, load_world  # noqa: E402

# Tours: the lab lap once and a half (the second pass closes loops on the first), and two_rooms out and back.
TOURS: Dict[str, Tuple[Waypoint, ...]] = {
    "lab": (
        (3.2, 1.0, None), (3.7, 1.85, None), (4.6, 1.85, None), (5.1, 1.1, None), (7.0, 1.0, None),
        (7.0, 5.0, None), (6.1, 4.9, None), (5.5, 4.15, None), (4.0, 4.15, None), (3.4, 5.0, None), (1.0, 5.0, None),
        (1.0, 1.0, None),
        (3.2, 1.0, None), (3.7, 1.85, None), (4.6, 1.85, None), (5.1, 1.1, None), (7.0, 1.0, None),
        (7.0, 5.0, None), (6.1, 4.9, None),
    ),
    # west room, through the door, around the east room (clear of the visitor at (8, 3.2)), back west
    "two_rooms": (
        (1.0, 1.0, None), (1.0, 3.0, None), (4.0, 2.0, None), (6.0, 2.0, None), (6.0, 0.8, None), (8.6, 0.8, None),
        (8.6, 2.2, None), (6.0, 2.2, None), (4.0, 2.0, None), (1.5, 1.2, None), (1.2, 2.6, None), (3.5, 2.3, None),
    ),
}
TARGET_AGREE = 0.97
TARGET_WALL_CM = 5.0
TARGET_SCAN_MS = 20.0
ROBOT_RADIUS = 0.177  # [m] TurtleBot 2 (sim/robots/kobuki.yaml): the clearance that makes free space reachable


@dataclass
class Run:
    keyframes_truth: List[Pose2D] = field(default_factory=list)
    scan_s: List[float] = field(default_factory=list)  # [s] per add_scan
    keyframe_s: List[float] = field(default_factory=list)  # [s] per add_scan that made a keyframe
    truth0: Optional[Pose2D] = None
    odom0: Optional[Pose2D] = None
    contacts: int = 0
    done: bool = False


def drive(world_name: str, robot: str, seed: int, slam: GraphSlam, max_s: float = 600.0) -> Run:
    world = load_world(world_name)
    profile = load_profile(robot)
    start = world.spawns[0].pose
    sensors = SensorOptions(odometry=True, lidar=True, bumpers=True, camera=False)
    drive_limits = profile.drive
    driver = LapDriver(min(CRUISE, 0.9 * drive_limits.max_linear_velocity),
                       min(TURN_RATE, 0.9 * drive_limits.max_angular_velocity), TOURS[world_name])
    lidar = profile.lidar
    angles = lidar.beam_angles()
    laser_pose = (lidar.mount[0], lidar.mount[1], 0.0)
    run = Run()
    with Simulation(world, [Spawn("robot1", robot, start)], seed=seed, sensors=sensors) as sim:
        previous: Optional[Tuple[float, Pose2D]] = None
        pending: List[Tuple[float, np.ndarray, Pose2D]] = []
        while not driver.done and sim.time < max_s:
            for reading in sim.step():
                if isinstance(reading, OdometryReading):
                    current: Tuple[float, Pose2D] = (reading.stamp, reading.odom_pose)
                    for stamp, ranges, truth in pending:
                        odom = interpolate(previous or current, current, stamp)
                        if run.odom0 is None:
                            run.odom0, run.truth0 = odom, truth
                        t = time.perf_counter()
                        made = slam.add_scan(odom, ScanBeams(ranges, angles, laser_pose, lidar.range_min,
                                                             lidar.range_max))
                        spent = time.perf_counter() - t
                        run.scan_s.append(spent)
                        if made:
                            run.keyframe_s.append(spent)
                            run.keyframes_truth.append(truth)
                    pending.clear()
                    previous = current
                    driver.time = reading.stamp
                    linear, angular = driver.command(reading.truth_pose)
                    sim.command("robot1", linear, angular)
                elif isinstance(reading, ScanReading):
                    pending.append((reading.stamp, reading.ranges, sim.truth_pose("robot1")))
                elif getattr(reading, "begin", False):
                    run.contacts += 1
        run.done = driver.done
    return run


def world_from_map(run: Run) -> Pose2D:
    """The map frame's pose in the world: the first scan's true pose composed with the inverse of its odometry."""
    assert run.truth0 is not None and run.odom0 is not None
    return compose_poses(run.truth0, inverse_pose(run.odom0))


def keyframe_pairs(run: Run, slam: GraphSlam) -> Tuple[List[Pose2D], List[Pose2D]]:
    """The keyframes' optimised poses placed in the world (first pose placed, no fitting) and their true poses."""
    offset = world_from_map(run)
    placed = [compose_poses(offset, (float(p[0]), float(p[1]), float(p[2]))) for p in slam.poses()]
    return placed, list(run.keyframes_truth)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--worlds", default="lab")
    parser.add_argument("--robot", default="kobuki")
    parser.add_argument("--seeds", type=int, default=1)
    parser.add_argument("--png", type=Path, default=None, help="write a PNG per run into this folder")
    args = parser.parse_args()
    print(f"load average {', '.join(f'{v:.2f}' for v in os.getloadavg())} ({os.cpu_count()} cores)")
    ok = True
    for world_name in args.worlds.split(","):
        truth_map = load_map(REPO / "sim" / "worlds" / "maps" / f"{world_name}.yaml")
        for seed in range(args.seeds):
            for closing in (True, False):
                slam = GraphSlam(replace(SlamParams(), do_loop_closing=closing))
                run = drive(world_name, args.robot, seed, slam)
                built = slam.occupancy_map()
                placed = world_from_map(run)
                world = load_world(world_name)
                start = world.spawns[0].pose
                score = score_map(built, truth_map, placed, (start[0], start[1]), ROBOT_RADIUS)
                estimates, truths = keyframe_pairs(run, slam)
                placed_cm = ate_rmse_cm(estimates, truths, align=False)
                evo_cm = ate_rmse_cm(estimates, truths, align=True)
                scan_ms = [1e3 * v for v in run.scan_s]
                key_ms = [1e3 * v for v in run.keyframe_s]
                label = "loop closure on " if closing else "loop closure off"
                print(f"{world_name} {args.robot} seed {seed}, {label}: {len(slam.keyframes)} keyframes, "
                      f"{len(slam.loop_closures)} closures ({slam.rejected_loops} rejected), tour "
                      f"{'done' if run.done else 'NOT done'}, {run.contacts} contacts")
                print(f"  ATE (evo, keyframes) {placed_cm:.1f} cm with the first pose placed, {evo_cm:.1f} cm "
                      f"SE(3)-aligned")
                print(f"  map: {100 * score.agree:.1f} % of {score.compared} observed cells agree; walls "
                      f"median {score.wall_median_cm:.1f} cm, p95 {score.wall_p95_cm:.1f} cm off; "
                      f"{100 * score.ghost:.1f} % of wall cells > {100 * GHOST_M:.0f} cm off")
                print(f"  per scan: median {statistics.median(scan_ms):.2f} ms, p95 "
                      f"{float(np.percentile(scan_ms, 95)):.2f} ms; per keyframe median "
                      f"{statistics.median(key_ms):.1f} ms, max {max(key_ms):.1f} ms; ratio of the median to the "
                      f"{TARGET_SCAN_MS:.0f} ms budget {statistics.median(scan_ms) / TARGET_SCAN_MS:.3f}")
                if args.png is not None:
                    args.png.mkdir(parents=True, exist_ok=True)
                    poses = slam.poses()
                    closures = [((poses[c.old][0], poses[c.old][1]), (poses[c.new][0], poses[c.new][1]))
                                for c in slam.loop_closures]
                    image = draw_map(built, truth_map, placed, [(p[0], p[1]) for p in poses], closures)
                    cv2.imwrite(str(args.png / f"{world_name}_{seed}_{'loops' if closing else 'noloops'}.png"), image)
                if closing:
                    ok &= (score.agree >= TARGET_AGREE and score.wall_median_cm <= TARGET_WALL_CM
                           and statistics.median(scan_ms) <= TARGET_SCAN_MS)
    print(f"load average {', '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
