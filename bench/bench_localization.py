#!/usr/bin/env python3
"""Localization speed: one filter update of flex_nav.localization with 2000 particles and 60 beams, against the
same filter with the plain-numpy sensor model, measured in the same run.

The robot drives a path through the lab map (sim/worlds/maps/lab.yaml) in 6 cm steps (above update_min_d, so
every step is a full update: resampling of the previous weights, motion model, sensor model, estimate); its
scans (681 beams over 240 deg, 5.6 m, as the simulated Hokuyo) are ray-cast on the map beforehand and thinned
to 60 beams by the filter. Both filters get the same seed and inputs, interleaved step by step so that load
changes hit both alike; they must end at the same estimate.

Targets: median <= 2 ms; ratio to the numpy filter <= 0.25; printed too: the ratio to the 100 ms scan period
(10 Hz lidar) and the machine's load average (os.getloadavg) before and after.
"""

from __future__ import annotations

import math
import os
import statistics
import sys
import time
from pathlib import Path
from typing import List, Tuple

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

from flex_nav.localization import FilterParams, GridMap, Kernel, Localizer, ScanBeams  # noqa: E402
from flex_nav.localization.localizer import AMBIGUITY_MARGIN  # noqa: E402
from flex_nav.localization.pose_search import refine  # noqa: E402
from flex_nav.localization.scan import select_beams  # noqa: E402
from flex_nav.localization.sensor_model import beam_sums_numba, beam_sums_numpy  # noqa: E402
from flex_nav.nav.costmap.map_io import load_map  # noqa: E402
from flex_nav.nav.planar import Pose2D  # noqa: E402

PARTICLES = 2000
BEAMS = 60
STEP = 0.06  # [m] per update
SCAN_PERIOD = 0.1  # [s] 10 Hz lidar
ANGLES = np.radians(np.linspace(-119.53125, 119.53125, 681))
RANGE_MAX = 5.6  # [m]
WAYPOINTS = ((1.0, 1.0), (3.2, 1.0), (3.7, 1.85), (4.6, 1.85), (5.1, 1.1), (7.0, 1.0), (7.0, 5.0), (1.0, 5.0),
             (1.0, 1.0))
TARGET_MS = 2.0
TARGET_RATIO = 0.25


def path(step: float) -> List[Pose2D]:
    poses: List[Pose2D] = []
    for (x0, y0), (x1, y1) in zip(WAYPOINTS[:-1], WAYPOINTS[1:]):
        yaw = math.atan2(y1 - y0, x1 - x0)
        for s in np.arange(0.0, math.hypot(x1 - x0, y1 - y0), step):
            poses.append((x0 + s * math.cos(yaw), y0 + s * math.sin(yaw), yaw))
    return poses


def cast(grid: GridMap, pose: Pose2D, rng: np.random.Generator) -> np.ndarray:
    """Ranges [m] to the first occupied cell along each beam (quarter-cell steps), +inf if none, 1 cm noise."""
    steps = np.arange(1, int(RANGE_MAX / (grid.resolution / 4))) * (grid.resolution / 4)
    directions = pose[2] + ANGLES
    rows, cols = grid.world_to_cells(pose[0] + np.cos(directions)[:, None] * steps,
                                     pose[1] + np.sin(directions)[:, None] * steps)
    inside = (rows >= 0) & (rows < grid.height) & (cols >= 0) & (cols < grid.width)
    hit = np.zeros(rows.shape, dtype=bool)
    hit[inside] = grid.occupancy[rows[inside], cols[inside]] >= 65
    first = np.where(hit.any(axis=1), hit.argmax(axis=1), -1)
    ranges = np.where(first >= 0, steps[np.maximum(first, 0)], np.inf)
    return np.asarray(ranges + 0.01 * rng.standard_normal(ranges.shape))


def odometry(poses: List[Pose2D]) -> List[Pose2D]:
    """The true poses as odometry (the odom frame at the first pose)."""
    x0, y0, yaw0 = poses[0]
    c, s = math.cos(yaw0), math.sin(yaw0)
    return [(c * (x - x0) + s * (y - y0), -s * (x - x0) + c * (y - y0), yaw - yaw0) for x, y, yaw in poses]


def bench_updates(grid: GridMap) -> Tuple[List[float], List[float], float]:
    rng = np.random.default_rng(0)
    poses = path(STEP)
    scans = [ScanBeams(cast(grid, pose, rng), ANGLES, (0.0, 0.0, 0.0), 0.02, RANGE_MAX) for pose in poses]
    odom = odometry(poses)
    params = FilterParams(min_particles=PARTICLES, max_particles=PARTICLES, laser_max_beams=BEAMS)
    filters = {kernel: Localizer(params, grid, seed=1, kernel=kernel) for kernel in Kernel}
    times: dict = {kernel: [] for kernel in Kernel}
    for localizer in filters.values():
        localizer.update(odom[0], None)
        localizer.set_pose(poses[0], np.diag([0.05**2, 0.05**2, 0.03**2]))
    for index in range(1, len(poses)):
        for kernel, localizer in filters.items():
            t = time.perf_counter()
            updated = localizer.update(odom[index], scans[index])
            times[kernel].append(time.perf_counter() - t)
            assert updated, "every step must be a full update"
    numba_pose = filters[Kernel.NUMBA].estimate().pose
    numpy_pose = filters[Kernel.NUMPY].estimate().pose
    difference = max(abs(a - b) for a, b in zip(numba_pose, numpy_pose))
    x, y, _ = numba_pose
    error = math.hypot(x - poses[-1][0], y - poses[-1][1])
    print(f"  {len(poses) - 1} updates along a {STEP * (len(poses) - 1):.1f} m path; final error {100 * error:.1f} cm; "
          f"numba and numpy filters end {difference:.1e} apart")
    return times[Kernel.NUMBA][5:], times[Kernel.NUMPY][5:], difference


def bench_kernel(grid: GridMap) -> None:
    """For information: the sensor kernel alone (2000 particles x 60 beams)."""
    rng = np.random.default_rng(2)
    localizer = Localizer(FilterParams(min_particles=PARTICLES, max_particles=PARTICLES), grid, seed=3)
    localizer.set_pose((2.0, 1.0, 0.0), np.diag([0.01, 0.01, 0.01]))
    beams = select_beams(ScanBeams(cast(grid, (2.0, 1.0, 0.0), rng), ANGLES, (0.0, 0.0, 0.0), 0.02, RANGE_MAX),
                         BEAMS)
    model = localizer.sensor_model
    inputs = model.grid_inputs(np.array(localizer.particles), beams)
    table = model.table(RANGE_MAX, localizer.params.laser_sigma_hit)
    timed = {}
    for name, kernel in (("numba", beam_sums_numba), ("numpy", beam_sums_numpy)):
        runs = []
        for _ in range(50):
            t = time.perf_counter()
            kernel(*inputs, table, grid.height, grid.width)
            runs.append(time.perf_counter() - t)
        timed[name] = statistics.median(runs)
    print(f"  sensor kernel alone ({PARTICLES} x {beams.x.size} beams): numba {1e3 * timed['numba']:.3f} ms, "
          f"numpy {1e3 * timed['numpy']:.3f} ms, ratio {timed['numba'] / timed['numpy']:.3f}x")


def bench_pose_search(grid: GridMap) -> None:
    """For information: the search for rival poses a lost filter runs before it reports itself localized again
    (pose_search: the whole map's lattice, then the best distinct candidates refined), on one scan."""
    rng = np.random.default_rng(4)
    localizer = Localizer(FilterParams(), grid, seed=5)
    pose = (4.0, 1.9, math.pi / 2)
    beams = select_beams(ScanBeams(cast(grid, pose, rng), ANGLES, (0.0, 0.0, 0.0), 0.02, RANGE_MAX), BEAMS)
    estimate = refine(localizer.sensor_model, pose, beams, RANGE_MAX)
    runs = []
    for _ in range(5):
        t = time.perf_counter()
        localizer.pose_search.alternatives(beams, RANGE_MAX, estimate, AMBIGUITY_MARGIN)
        runs.append(time.perf_counter() - t)
    search = localizer.pose_search
    print(f"  rival-pose search ({search.pose_count} lattice poses x {beams.x.size} beams, {search.stride:.2f} m, "
          f"once per relocalization): median {1e3 * statistics.median(runs):.0f} ms")


def main() -> int:
    load_before = os.getloadavg()
    grid = load_map(REPO / "sim" / "worlds" / "maps" / "lab.yaml")
    t = time.perf_counter()
    warm = Localizer(FilterParams(), grid, seed=0)
    warm.set_pose((1.0, 1.0, 0.0), np.eye(3) * 0.01)
    warm.update((0.0, 0.0, 0.0), ScanBeams(np.ones(3), np.zeros(3), (0.0, 0.0, 0.0), 0.02, RANGE_MAX))
    warm.update((0.0, 0.0, 0.0), ScanBeams(np.ones(3), np.zeros(3), (0.0, 0.0, 0.0), 0.02, RANGE_MAX))
    print(f"first update (numba compile or cache load): {1e3 * (time.perf_counter() - t):.0f} ms")
    print(f"lab map {grid.width}x{grid.height} cells; {PARTICLES} particles, {BEAMS} of 681 beams")
    mine, reference, difference = bench_updates(grid)
    bench_kernel(grid)
    bench_pose_search(grid)
    load_after = os.getloadavg()
    median, ref_median = statistics.median(mine), statistics.median(reference)
    ratio = median / ref_median
    print(f"  one update (resampling + motion + sensor + estimate): median {1e3 * median:.3f} ms, p95 "
          f"{1e3 * float(np.percentile(mine, 95)):.3f} ms, max {1e3 * max(mine):.3f} ms (target <= {TARGET_MS} ms)")
    print(f"  plain-numpy filter: median {1e3 * ref_median:.3f} ms; ratio {ratio:.3f}x (target <= {TARGET_RATIO})")
    print(f"  ratio to the {1e3 * SCAN_PERIOD:.0f} ms scan period: {median / SCAN_PERIOD:.4f}x")
    print(f"  load average (1, 5, 15 min) before {', '.join(f'{v:.2f}' for v in load_before)}; after "
          f"{', '.join(f'{v:.2f}' for v in load_after)} ({os.cpu_count()} cores)")
    ok = median <= TARGET_MS * 1e-3 and ratio <= TARGET_RATIO and difference < 1e-6
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
