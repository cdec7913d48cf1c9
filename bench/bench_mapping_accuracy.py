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
import math
import os
import statistics
import sys
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import cv2
import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))
sys.path.insert(0, str(REPO / "bench"))

from bench_localization_accuracy import CRUISE, TURN_RATE, LapDriver, Waypoint, interpolate  # noqa: E402

from flex_nav.localization import ScanBeams  # noqa: E402
from flex_nav.mapping.slam import GraphSlam, SlamParams  # noqa: E402
from flex_nav.nav.costmap.grid_map import GridMap  # noqa: E402
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
GHOST_M = 0.15  # [m] a mapped wall cell this far from any true wall is a ghost (a doubled wall)


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


def ate_cm(run: Run, slam: GraphSlam) -> float:
    offset = world_from_map(run)
    errors = [math.dist(compose_poses(offset, (float(p[0]), float(p[1]), float(p[2])))[:2], t[:2])
              for p, t in zip(slam.poses(), run.keyframes_truth)]
    return 100.0 * math.sqrt(statistics.fmean(e * e for e in errors))


def ate_evo_cm(run: Run, slam: GraphSlam) -> Optional[float]:
    """evo's APE (translation, RMSE) after SE(3) Umeyama alignment of the keyframes; None without evo."""
    try:
        from evo.core import metrics, sync  # noqa: F401, PLC0415
        from evo.core.trajectory import PoseTrajectory3D  # noqa: PLC0415
    except ImportError:
        return None
    stamps = np.arange(len(run.keyframes_truth), dtype=float)

    def trajectory(poses: Sequence[Sequence[float]]) -> PoseTrajectory3D:
        xyz = np.array([(p[0], p[1], 0.0) for p in poses])
        quat = np.array([(math.cos(p[2] / 2), 0.0, 0.0, math.sin(p[2] / 2)) for p in poses])  # w x y z
        return PoseTrajectory3D(positions_xyz=xyz, orientations_quat_wxyz=quat, timestamps=stamps)

    reference = trajectory(run.keyframes_truth)
    estimate = trajectory(slam.poses().tolist())
    estimate.align(reference, correct_scale=False)
    ape = metrics.APE(metrics.PoseRelation.translation_part)
    ape.process_data((reference, estimate))
    return 100.0 * float(ape.get_statistic(metrics.StatisticsType.rmse))


@dataclass
class MapScore:
    agree: float  # [-]
    compared: int  # cells
    wall_median_cm: float
    wall_p95_cm: float
    ghost: float  # [-] share of mapped wall cells farther than GHOST_M from a true wall


def score_map(built: GridMap, truth: GridMap, map_in_world: Pose2D) -> MapScore:
    """Compare ``built`` (map frame) with ``truth`` (world frame) cell by cell, at the truth's cell centres."""
    rows, cols = np.nonzero(truth.occupancy >= 0)
    wx, wy = truth.cells_to_world(rows, cols)
    inv = inverse_pose(map_in_world)
    c, s = math.cos(inv[2]), math.sin(inv[2])
    mx, my = inv[0] + c * wx - s * wy, inv[1] + s * wx + c * wy
    brow, bcol = built.world_to_cells(mx, my)
    inside = (brow >= 0) & (brow < built.height) & (bcol >= 0) & (bcol < built.width)
    values = np.full(rows.shape, -1, dtype=np.int16)
    values[inside] = built.occupancy[brow[inside], bcol[inside]]
    true_values = truth.occupancy[rows, cols]
    seen = values >= 0
    agree = float(np.mean((values[seen] >= 50) == (true_values[seen] >= 50))) if seen.any() else math.nan
    # walls: every built occupied cell's distance to the nearest true occupied cell
    free_of_walls = np.where(truth.occupancy >= 50, 0, 255).astype(np.uint8)
    distance = cv2.distanceTransform(free_of_walls, cv2.DIST_L2, cv2.DIST_MASK_PRECISE) * truth.resolution
    brows, bcols = np.nonzero(built.occupancy >= 50)
    bx, by = built.cells_to_world(brows, bcols)
    c, s = math.cos(map_in_world[2]), math.sin(map_in_world[2])
    tx, ty = map_in_world[0] + c * bx - s * by, map_in_world[1] + s * bx + c * by
    trow, tcol = truth.world_to_cells(tx, ty)
    ok = (trow >= 0) & (trow < truth.height) & (tcol >= 0) & (tcol < truth.width)
    d = distance[trow[ok], tcol[ok]]
    return MapScore(agree, int(seen.sum()), 100.0 * float(np.median(d)), 100.0 * float(np.percentile(d, 95)),
                    float(np.mean(d > GHOST_M)))


def save_png(path: Path, built: GridMap, truth: GridMap, map_in_world: Pose2D, slam: GraphSlam) -> None:
    """The built map (grey: unknown, white: free, black: occupied) with the true walls in red and the keyframe
    trajectory in blue, loop closures in green (built map's frame, up = +y)."""
    image = np.full((*built.occupancy.shape, 3), 160, dtype=np.uint8)
    image[built.occupancy == 0] = (255, 255, 255)
    image[built.occupancy >= 50] = (0, 0, 0)
    rows, cols = np.nonzero(truth.occupancy >= 50)
    wx, wy = truth.cells_to_world(rows, cols)
    inv = inverse_pose(map_in_world)
    c, s = math.cos(inv[2]), math.sin(inv[2])
    brow, bcol = built.world_to_cells(inv[0] + c * wx - s * wy, inv[1] + s * wx + c * wy)
    inside = (brow >= 0) & (brow < built.height) & (bcol >= 0) & (bcol < built.width)
    image[brow[inside], bcol[inside]] = (0, 0, 255)
    poses = slam.poses()
    prow, pcol = built.world_to_cells(poses[:, 0], poses[:, 1])
    for a, b in zip(range(len(poses) - 1), range(1, len(poses))):
        cv2.line(image, (int(pcol[a]), int(prow[a])), (int(pcol[b]), int(prow[b])), (255, 0, 0), 1)
    for closure in slam.loop_closures:
        cv2.line(image, (int(pcol[closure.old]), int(prow[closure.old])),
                 (int(pcol[closure.new]), int(prow[closure.new])), (0, 200, 0), 1)
    cv2.imwrite(str(path), np.flipud(image))


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
                score = score_map(built, truth_map, placed)
                evo_cm = ate_evo_cm(run, slam)
                scan_ms = [1e3 * v for v in run.scan_s]
                key_ms = [1e3 * v for v in run.keyframe_s]
                label = "loop closure on " if closing else "loop closure off"
                print(f"{world_name} {args.robot} seed {seed}, {label}: {len(slam.keyframes)} keyframes, "
                      f"{len(slam.loop_closures)} closures ({slam.rejected_loops} rejected), tour "
                      f"{'done' if run.done else 'NOT done'}, {run.contacts} contacts")
                print(f"  ATE {ate_cm(run, slam):.1f} cm (first pose placed)"
                      + ("" if evo_cm is None else f", {evo_cm:.1f} cm (evo, SE(3) aligned)"))
                print(f"  map: {100 * score.agree:.1f} % of {score.compared} observed cells agree; walls "
                      f"median {score.wall_median_cm:.1f} cm, p95 {score.wall_p95_cm:.1f} cm off; "
                      f"{100 * score.ghost:.1f} % of wall cells > {100 * GHOST_M:.0f} cm off")
                print(f"  per scan: median {statistics.median(scan_ms):.2f} ms, p95 "
                      f"{float(np.percentile(scan_ms, 95)):.2f} ms; per keyframe median "
                      f"{statistics.median(key_ms):.1f} ms, max {max(key_ms):.1f} ms; ratio of the median to the "
                      f"{TARGET_SCAN_MS:.0f} ms budget {statistics.median(scan_ms) / TARGET_SCAN_MS:.3f}")
                if args.png is not None:
                    args.png.mkdir(parents=True, exist_ok=True)
                    save_png(args.png / f"{world_name}_{seed}_{'loops' if closing else 'noloops'}.png", built,
                             truth_map, placed, slam)
                if closing:
                    ok &= (score.agree >= TARGET_AGREE and score.wall_median_cm <= TARGET_WALL_CM
                           and statistics.median(scan_ms) <= TARGET_SCAN_MS)
    print(f"load average {', '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
