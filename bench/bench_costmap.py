#!/usr/bin/env python3
"""Costmap benchmark: full inflation of a 2000² map against a scipy-EDT inflation, and the rolling local
costmap update with a 360-beam scan, measured in the same run.

1. Full inflation (Nav2 benchmark maps, inscribed 0.22 m, radius 0.55 m, k = 3.0 /m): flex_nav's
   ``Inflator.apply`` (OpenCV exact L2 distance transform + cost table) against the same combination rule
   on ``scipy.ndimage.distance_transform_edt`` (the reference differs only in the distance transform, and
   its result must be identical). Target: ratio <= 0.35.
2. Rolling 4 m x 4 m local costmap (0.05 m) following a path across a benchmark map, one 360-beam scan
   (simulated on the map beforehand, 3.5 m range) per step: ``recentre`` + ``add_scan`` + ``update``.
   Target: median <= 2 ms (the ratio printed is to that budget).
3. For information: one scan into the 2000² global costmap with the bounded update.
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

try:
    from scipy.ndimage import distance_transform_edt
except ImportError as err:  # bench-only reference
    sys.exit(f"{err}: install the bench references first: bench/run.sh costmap")

from flex_nav.nav.costmap.costmap_grid import INSCRIBED, LETHAL, NO_INFORMATION, CostmapGeometry  # noqa: E402
from flex_nav.nav.costmap.grid_map import GridMap  # noqa: E402
from flex_nav.nav.costmap.inflation import InflationParams, Inflator  # noqa: E402
from flex_nav.nav.costmap.layered import Costmap  # noqa: E402
from flex_nav.nav.costmap.map_io import load_map  # noqa: E402
from flex_nav.nav.costmap.obstacle_layer import LaserScan, ObstacleLayerParams  # noqa: E402
from flex_nav.nav.planning.planner import GridPlanner  # noqa: E402

MAPS_DIR = Path(os.environ.get("FLEX_NAV_BENCH_MAPS", REPO.parent / "shared" / "maps"))  # Nav2's benchmark maps
INFLATION = InflationParams(inscribed_radius=0.22, inflation_radius=0.55, cost_scaling_factor=3.0)  # Nav2's
REPEATS = 7


def benchmark_maps() -> List[Path]:
    """The maps (.yaml) in MAPS_DIR, sorted; none: [] and a message naming the folder (bench_planner's too)."""
    maps = sorted(MAPS_DIR.glob("*.yaml"))
    if not maps:
        print(f"no maps in {MAPS_DIR} (set FLEX_NAV_BENCH_MAPS)")
    return maps


def scipy_inflation(costs: np.ndarray, inflator: Inflator) -> np.ndarray:
    """Reference: scipy's exact EDT, then the same cost table and costmap_2d combination rule."""
    out = costs.copy()
    dist = distance_transform_edt(costs != LETHAL)
    d2 = np.rint(np.minimum(dist, inflator.radius_cells + 1) ** 2).astype(np.intp)
    inflated = inflator.table[np.minimum(d2, len(inflator.table) - 1)]
    unknown = costs == NO_INFORMATION
    np.maximum(out, inflated, out=out)
    take = unknown & (inflated >= INSCRIBED)
    out[take] = inflated[take]
    return out


def bench_inflation(static_costs: np.ndarray, resolution: float) -> float:
    inflator = Inflator(INFLATION, resolution)
    mine, ref = [], []
    result = ref_result = static_costs
    for _ in range(REPEATS):
        work = static_costs.copy()
        t = time.perf_counter()
        inflator.apply(work)
        mine.append(time.perf_counter() - t)
        result = work
        t = time.perf_counter()
        ref_result = scipy_inflation(static_costs, inflator)
        ref.append(time.perf_counter() - t)
    ratio = statistics.median(mine) / statistics.median(ref)
    same = int((result != ref_result).sum())
    print(
        f"  full inflation {static_costs.shape[1]}x{static_costs.shape[0]}: flex_nav (OpenCV) median "
        f"{1e3 * statistics.median(mine):.1f} ms, scipy-EDT reference {1e3 * statistics.median(ref):.1f} ms, "
        f"ratio {ratio:.2f}x (target <= 0.35); cells differing: {same}"
    )
    return ratio


def simulate_scans(occupancy: np.ndarray, grid_resolution: float, poses: np.ndarray, beams: int = 360) -> list:
    """Ray-march 360-beam scans on the map (done before timing)."""
    angles = -math.pi + 2 * math.pi * np.arange(beams) / beams
    steps = np.arange(1, int(3.5 / (grid_resolution / 2)) + 1) * (grid_resolution / 2)
    occupied = occupancy >= 65
    scans = []
    for x, y, yaw in poses:
        a = yaw + angles
        xs = x + np.cos(a)[:, None] * steps[None, :]
        ys = y + np.sin(a)[:, None] * steps[None, :]
        cols = np.clip((xs / grid_resolution).astype(int), 0, occupancy.shape[1] - 1)
        rows = np.clip((ys / grid_resolution).astype(int), 0, occupancy.shape[0] - 1)
        hit = occupied[rows, cols]
        first = np.where(hit.any(axis=1), hit.argmax(axis=1), -1)
        ranges = np.where(first >= 0, steps[np.maximum(first, 0)], np.inf)
        scans.append(LaserScan(ranges, -math.pi, 2 * math.pi / beams, 0.12, 3.5, float(x), float(y), float(yaw)))
    return scans


def bench_rolling(grid: GridMap, global_costs: np.ndarray, geo: CostmapGeometry) -> float:
    # a robot pose every 5 cm along a planned path across the map
    planner = GridPlanner()
    result = planner.plan(global_costs, geo, (20.0, 20.0), (60.0, 55.0))
    if not result.ok:
        result = planner.plan(global_costs, geo, (30.0, 30.0), (50.0, 50.0))
    path = result.path
    seg = np.hypot(np.diff(path[:, 0]), np.diff(path[:, 1]))
    s = np.concatenate([[0.0], np.cumsum(seg)])
    samples = np.arange(0.0, min(s[-1], 40.0), 0.05)
    xs, ys = np.interp(samples, s, path[:, 0]), np.interp(samples, s, path[:, 1])
    yaws = np.interp(samples, s, np.unwrap(path[:, 2]))
    poses = np.column_stack([xs, ys, yaws])
    scans = simulate_scans(grid.occupancy, grid.resolution, poses)
    local = Costmap.rolling(4.0, 4.0, 0.05, obstacles=ObstacleLayerParams(), inflation=INFLATION, centre=(xs[0], ys[0]))
    times, convert = [], []
    for (x, y, _), scan in zip(poses, scans):
        t = time.perf_counter()
        local.recentre(x, y)
        local.add_scan(scan)
        local.update()
        times.append(time.perf_counter() - t)
        t = time.perf_counter()
        local.to_occupancy()
        convert.append(time.perf_counter() - t)
    times = times[5:]
    med = statistics.median(times)
    print(
        f"  rolling 4 m local costmap, {len(times)} updates with a 360-beam scan: median {1e3 * med:.3f} ms, "
        f"p95 {1e3 * float(np.percentile(times, 95)):.3f} ms, max {1e3 * max(times):.3f} ms; "
        f"ratio to the 2 ms budget {med / 2e-3:.2f}x; "
        f"OccupancyGrid conversion {1e6 * statistics.median(convert):.0f} us"
    )
    return med


def bench_global_scan(grid: GridMap, scans_pose: Tuple[float, float, float] = (50.0, 50.0, 0.0)) -> None:
    cm = Costmap.from_map(grid, obstacles=ObstacleLayerParams(track_unknown_space=True), inflation=INFLATION)
    scans = simulate_scans(grid.occupancy, grid.resolution, np.array([scans_pose]))
    times = []
    for _ in range(REPEATS):
        t = time.perf_counter()
        cm.add_scan(scans[0])
        box = cm.update()
        times.append(time.perf_counter() - t)
    print(
        f"  global 2000² costmap, one scan with bounded update (box {box}): median "
        f"{1e3 * statistics.median(times):.2f} ms"
    )


def main() -> int:
    maps = benchmark_maps()
    if not maps:
        return 2
    t = time.perf_counter()
    warm = Costmap.rolling(1.0, 1.0, 0.05, inflation=INFLATION)
    warm.add_scan(LaserScan(np.ones(4), 0.0, 1.0, 0.1, 3.0, 0.0, 0.0, 0.0))
    warm.update()
    print(f"first scan (numba compile or cache load): {1e3 * (time.perf_counter() - t):.0f} ms")
    ratios, rolling = [], []
    for yaml_path in maps:
        print(yaml_path.name)
        grid = load_map(yaml_path)
        static = Costmap.from_map(grid)
        ratios.append(bench_inflation(static.costs, grid.resolution))
        inflated = Costmap.from_map(grid, inflation=INFLATION)
        rolling.append(bench_rolling(grid, inflated.costs, inflated.geometry))
        bench_global_scan(grid)
    ok = max(ratios) <= 0.35 and max(rolling) <= 2e-3
    print(
        f"\nsummary: inflation ratio worst {max(ratios):.2f}x (target <= 0.35), "
        f"rolling update median worst {1e3 * max(rolling):.3f} ms (target <= 2 ms)"
    )
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
