#!/usr/bin/env python3
"""Localization accuracy: flex_nav.localization on the simulated lab lap, against the simulator's ground truth.

Without ROS: :class:`flex_nav_sim.simulation.Simulation` runs the lab world (sim/worlds/lab.yaml) with one
robot of each profile (kobuki = TurtleBot 2, create2, turtlebot4), its noisy wheel odometry and its lidar
(pybullet ray casts with the profile's range noise; the boxes of the world are not in the map). The robot
drives the lap start -> g1 -> g2 -> g3 -> start along fixed way points that keep clear of the obstacles and of
the low step (turning on the spot to each goal's heading), steered on ground truth: what is measured is the
localizer, not a controller. The localizer gets every odometry reading and every scan, with the odometry
interpolated to the scan's stamp (what a node's tf lookup does); its pose between filter updates is the last
estimate moved by the odometry since (what a node publishes as map -> odom).

Measured, at every scan:
1. tracking (``set_pose`` at the true start pose, std 5 cm / 3 deg): position error median, p95, max [cm] and
   heading error median [deg] over the lap, per robot and seed. Targets (TurtleBot 2): median <= 3 cm,
   p95 <= 8 cm, heading median <= 1 deg.
2. convergence (kobuki): ``set_pose`` 1 m and 30 deg off the truth (four directions), with amcl's default
   initial covariance (std 0.5 m, 15 deg): seconds of driving until the error is within 5 cm (first time, and
   for good). Target <= 3 s.
3. global localization (kobuki): seconds until the filter reports LOCALIZED with the error within 10 cm, and
   until within 5 cm for good. Target <= 20 s.

``--param name=value`` overrides a FilterParams default (for tuning); exit status 1 if a target is missed.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

from flex_nav.localization import FilterParams, Localizer, LocalizerStatus, ScanBeams  # noqa: E402
from flex_nav.nav.angles import wrap_angle  # noqa: E402
from flex_nav.nav.costmap.map_io import load_map  # noqa: E402
from flex_nav.nav.planar import Pose2D, compose_poses, inverse_pose  # noqa: E402
from flex_nav_sim.profiles import load_profile  # noqa: E402
from flex_nav_sim.readings import OdometryReading, ScanReading  # noqa: E402
from flex_nav_sim.simulation import SensorOptions, Simulation  # noqa: E402
from flex_nav_sim.world import Spawn, load_world  # noqa: E402

ROBOTS = ("kobuki", "create2", "turtlebot4")
# The lap: (x [m], y [m], goal heading [deg] or None). Around the low step (4.0, 1.0) and bin_s on the south
# leg, straight up the east and west legs, under crate_n and over the chair on the north leg.
WAYPOINTS: Tuple[Tuple[float, float, Optional[float]], ...] = (
    (3.2, 1.0, None), (3.7, 1.85, None), (4.6, 1.85, None), (5.1, 1.1, None), (7.0, 1.0, 90.0),
    (7.0, 5.0, 180.0),
    (6.1, 4.9, None), (5.5, 4.15, None), (4.0, 4.15, None), (3.4, 5.0, None), (1.0, 5.0, -90.0),
    (1.0, 1.0, 0.0),
)
CRUISE = 0.5  # [m/s] at most (the demo's TurtleBot 2 speed); 90 % of a slower robot's limit
TURN_RATE = 1.2  # [rad/s] at most
REACHED = 0.12  # [m] a way point is passed this close
HEADING_DONE = math.radians(2.0)  # [rad]
TRACK_COV = np.diag([0.05**2, 0.05**2, math.radians(3.0) ** 2])
AMCL_INITIAL_COV = np.diag([0.25, 0.25, (math.pi / 12) ** 2])  # amcl's initial_cov_xx, _yy, _aa
OFFSETS = ((1.0, 0.0, 30.0), (0.0, 1.0, -30.0), (0.7071, 0.7071, 30.0), (0.7071, -0.7071, -30.0))  # [m, m, deg]
CONVERGED_CM = 5.0
GLOBAL_CM = 10.0
TARGETS = {"median": 3.0, "p95": 8.0, "heading": 1.0, "converge_s": 3.0, "global_s": 20.0}


@dataclass
class Trace:
    """One run: per scan, the time since the robot started driving and the errors of the published pose."""

    times: List[float] = field(default_factory=list)  # [s]
    error_xy: List[float] = field(default_factory=list)  # [m]
    error_yaw: List[float] = field(default_factory=list)  # [rad]
    localized: List[bool] = field(default_factory=list)
    particles: List[int] = field(default_factory=list)
    updates: int = 0
    update_s: float = 0.0  # [s] wall time in Localizer.update
    contacts: int = 0
    lap_done: bool = False


class LapDriver:
    """Steers along WAYPOINTS on ground truth: turn towards the next point, drive, turn to goal headings."""

    def __init__(self, cruise: float, turn_rate: float) -> None:
        self.cruise = cruise
        self.turn_rate = turn_rate
        self.index = 0
        self.turning_to: Optional[float] = None

    @property
    def done(self) -> bool:
        return self.index >= len(WAYPOINTS)

    def command(self, pose: Pose2D) -> Tuple[float, float]:
        if self.done:
            return 0.0, 0.0
        x, y, heading = WAYPOINTS[self.index]
        if self.turning_to is not None:
            error = wrap_angle(self.turning_to - pose[2])
            if abs(error) < HEADING_DONE:
                self.turning_to = None
                self.index += 1
                return 0.0, 0.0
            return 0.0, float(np.clip(2.0 * error, -self.turn_rate, self.turn_rate))
        dx, dy = x - pose[0], y - pose[1]
        if math.hypot(dx, dy) < REACHED:
            if heading is not None:
                self.turning_to = math.radians(heading)
            else:
                self.index += 1
            return self.command(pose)
        error = wrap_angle(math.atan2(dy, dx) - pose[2])
        turn = float(np.clip(2.5 * error, -self.turn_rate, self.turn_rate))
        if abs(error) > 0.6:
            return 0.0, turn
        return self.cruise * max(0.0, math.cos(error)) ** 2, turn


def interpolate(a: Tuple[float, Pose2D], b: Tuple[float, Pose2D], stamp: float) -> Pose2D:
    """Odometry pose at ``stamp`` between readings ``a`` and ``b`` ((stamp [s], pose))."""
    (ta, pa), (tb, pb) = a, b
    f = 0.0 if tb <= ta else min(max((stamp - ta) / (tb - ta), 0.0), 1.0)
    return (pa[0] + f * (pb[0] - pa[0]), pa[1] + f * (pb[1] - pa[1]), wrap_angle(pa[2] + f * wrap_angle(pb[2] - pa[2])))


def run(robot: str, start: str, params: FilterParams, seed: int, offset: Tuple[float, float, float] = (0, 0, 0),
        max_drive_s: float = 400.0) -> Trace:
    """Drive the lap with one robot; ``start`` is "truth", "offset" (with ``offset`` dx [m], dy [m], dyaw [deg])
    or "global"."""
    world = load_world("lab")
    profile = load_profile(robot)
    spawn_pose = world.goals["start"]
    grid = load_map(REPO / "sim" / "worlds" / "maps" / "lab.yaml")
    sensors = SensorOptions(odometry=True, lidar=True, bumpers=True, camera=False)
    localizer = Localizer(params, grid, seed=seed)
    drive = profile.drive
    driver = LapDriver(min(CRUISE, 0.9 * drive.max_linear_velocity), min(TURN_RATE, 0.9 * drive.max_angular_velocity))
    lidar = profile.lidar
    angles = lidar.beam_angles()
    laser_pose = (lidar.mount[0], lidar.mount[1], 0.0)
    trace = Trace()
    with Simulation(world, [Spawn("robot1", robot, spawn_pose)], seed=seed, sensors=sensors) as sim:
        truth0 = sim.truth_pose("robot1")
        if start == "truth":
            localizer.set_pose(truth0, TRACK_COV)
        elif start == "offset":
            dx, dy, dyaw = offset
            localizer.set_pose((truth0[0] + dx, truth0[1] + dy, truth0[2] + math.radians(dyaw)), AMCL_INITIAL_COV)
        else:
            localizer.global_localization()
        previous: Optional[Tuple[float, Pose2D]] = None
        pending: List[Tuple[float, np.ndarray, Pose2D]] = []
        filter_odom: Optional[Pose2D] = None
        filter_pose: Optional[Pose2D] = None
        started: Optional[float] = None
        while not driver.done and (started is None or sim.time - started < max_drive_s):
            for reading in sim.step():
                if isinstance(reading, OdometryReading):
                    current: Tuple[float, Pose2D] = (reading.stamp, reading.odom_pose)
                    if previous is None:
                        localizer.update(current[1], None)
                    for stamp, ranges, truth in pending:
                        odom = interpolate(previous or current, current, stamp)
                        scan = ScanBeams(ranges, angles, laser_pose, lidar.range_min, lidar.range_max)
                        t = time.perf_counter()
                        updated = localizer.update(odom, scan)
                        trace.update_s += time.perf_counter() - t
                        estimate = localizer.estimate()
                        if updated or filter_pose is None:
                            trace.updates += int(updated)
                            filter_odom, filter_pose = odom, estimate.pose
                        assert filter_odom is not None
                        published = compose_poses(filter_pose, compose_poses(inverse_pose(filter_odom), odom))
                        if started is not None:
                            trace.times.append(stamp - started)
                            trace.error_xy.append(math.hypot(published[0] - truth[0], published[1] - truth[1]))
                            trace.error_yaw.append(abs(wrap_angle(published[2] - truth[2])))
                            trace.localized.append(estimate.status is LocalizerStatus.LOCALIZED)
                            trace.particles.append(estimate.particle_count)
                    pending.clear()
                    previous = current
                    linear, angular = driver.command(reading.truth_pose)
                    if started is None and (linear or angular):
                        started = reading.stamp
                    sim.command("robot1", linear, angular)
                elif isinstance(reading, ScanReading):
                    pending.append((reading.stamp, reading.ranges, sim.truth_pose("robot1")))
                elif getattr(reading, "begin", False):
                    trace.contacts += 1
        trace.lap_done = driver.done
    return trace


def first_within(trace: Trace, limit_m: float, need_localized: bool = False) -> Tuple[float, float]:
    """(first time within ``limit_m``, time from which it stays within) [s]; inf if never."""
    first = math.inf
    for t, e, ok in zip(trace.times, trace.error_xy, trace.localized):
        if e <= limit_m and (ok or not need_localized):
            first = t
            break
    stays = math.inf
    for i in range(len(trace.times) - 1, -1, -1):
        if trace.error_xy[i] > limit_m or (need_localized and not trace.localized[i]):
            stays = trace.times[i + 1] if i + 1 < len(trace.times) else math.inf
            break
    else:
        stays = trace.times[0] if trace.times else math.inf
    return first, stays


def parse_params(items: Sequence[str]) -> FilterParams:
    values: Dict[str, object] = {}
    for item in items:
        name, _, text = item.partition("=")
        values[name] = int(text) if text.lstrip("-").isdigit() else float(text)
    return FilterParams.from_mapping(values, "bench")


def report_tracking(robots: Sequence[str], seeds: int, params: FilterParams) -> bool:
    print("1. tracking on the lab lap (error of the published pose at every scan)")
    ok = True
    for robot in robots:
        errors: List[float] = []
        headings: List[float] = []
        for seed in range(seeds):
            trace = run(robot, "truth", params, seed)
            e = np.array(trace.error_xy) * 100.0
            h = np.degrees(trace.error_yaw)
            print(f"  {robot:10s} seed {seed}: position median {np.median(e):.2f} cm, p95 "
                  f"{np.percentile(e, 95):.2f} cm, max {e.max():.2f} cm; heading median {np.median(h):.2f} deg, "
                  f"max {h.max():.2f} deg; {len(e)} scans, {trace.updates} updates "
                  f"({1e3 * trace.update_s / max(trace.updates, 1):.2f} ms each), particles "
                  f"{int(np.median(trace.particles))} median; not LOCALIZED at {trace.localized.count(False)} scans; "
                  f"lap {'done' if trace.lap_done else 'NOT DONE'}"
                  f"{f', {trace.contacts} CONTACTS' if trace.contacts else ''}")
            errors.extend(e)
            headings.extend(h)
        med, p95, worst = float(np.median(errors)), float(np.percentile(errors, 95)), float(max(errors))
        head = float(np.median(headings))
        print(f"  {robot:10s} all seeds: position median {med:.2f} cm, p95 {p95:.2f} cm, max {worst:.2f} cm; "
              f"heading median {head:.2f} deg")
        if robot == "kobuki":
            ok = med <= TARGETS["median"] and p95 <= TARGETS["p95"] and head <= TARGETS["heading"]
    return ok


def convergence(start: str, params: FilterParams, seed: int, offset: Tuple[float, float, float] = (0, 0, 0),
                max_drive_s: float = 20.0) -> Tuple[float, float, float]:
    """Driving times [s] of one kobuki run: until LOCALIZED within GLOBAL_CM, first within CONVERGED_CM, and
    within CONVERGED_CM for good."""
    trace = run("kobuki", start, params, seed, offset, max_drive_s)
    localized, _ = first_within(trace, GLOBAL_CM / 100.0, need_localized=True)
    return (localized, *first_within(trace, CONVERGED_CM / 100.0))


def report_convergence(seeds: int, params: FilterParams) -> bool:
    print(f"2. convergence from 1 m / 30 deg off (kobuki), amcl's initial covariance: driving time until within "
          f"{CONVERGED_CM:.0f} cm")
    worst = 0.0
    for seed, offset in ((seed, offset) for seed in range(seeds) for offset in OFFSETS):
        _, first, stays = convergence("offset", params, seed, offset)
        worst = max(worst, first)
        print(f"  seed {seed} offset ({offset[0]:+.2f} m, {offset[1]:+.2f} m, {offset[2]:+.0f} deg): first "
              f"{first:.1f} s, for good from {stays:.1f} s")
    print(f"  worst first time within {CONVERGED_CM:.0f} cm: {worst:.1f} s (target <= {TARGETS['converge_s']:.0f} s)")
    return worst <= TARGETS["converge_s"]


def report_global(seeds: int, params: FilterParams) -> bool:
    print("3. global localization (kobuki)")
    times = [convergence("global", params, seed, max_drive_s=40.0) for seed in range(seeds)]
    for seed, (localized, first, stays) in enumerate(times):
        print(f"  seed {seed}: LOCALIZED within {GLOBAL_CM:.0f} cm after {localized:.1f} s; within "
              f"{CONVERGED_CM:.0f} cm first {first:.1f} s, for good from {stays:.1f} s")
    worst = max(localized for localized, _, _ in times)
    print(f"  worst: {worst:.1f} s (target <= {TARGETS['global_s']:.0f} s)")
    return worst <= TARGETS["global_s"]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--robots", default=",".join(ROBOTS))
    parser.add_argument("--seeds", type=int, default=2, help="runs per robot and start (seeds 0..N-1; N+1 global)")
    parser.add_argument("--only", choices=("all", "lap", "offset", "global"), default="all")
    parser.add_argument("--param", action="append", default=[], help="FilterParams override name=value")
    args = parser.parse_args()
    params = parse_params(args.param)
    changed = {k: v for k, v in vars(params).items() if v != getattr(FilterParams(), k)}
    print(f"FilterParams: defaults{' with ' + str(changed) if changed else ''}")
    print(f"load average {', '.join(f'{v:.2f}' for v in os.getloadavg())}")
    ok = True
    if args.only in ("all", "lap"):
        ok &= report_tracking(args.robots.split(","), args.seeds, params)
    if args.only in ("all", "offset"):
        ok &= report_convergence(args.seeds, params)
    if args.only in ("all", "global"):
        ok &= report_global(args.seeds + 1, params)
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
