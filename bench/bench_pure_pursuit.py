#!/usr/bin/env python3
"""Pure pursuit step benchmark: a closed loop along a planned path on a Nav2 benchmark map.

A unicycle robot follows the global plan (TurtleBot-like limits) with a rolling 4 m local costmap fed by
simulated 360-beam scans (costmap work is not timed). Timed: one ``RegulatedPurePursuit.step`` call with
the local costmap (pruning, lookahead, regulations, arc collision check).
Target: median <= 0.1 ms; the ratio printed is to that budget.
"""

from __future__ import annotations

import math
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))
sys.path.insert(0, str(REPO / "bench"))

from bench_costmap import INFLATION, simulate_scans  # noqa: E402

from flex_nav.nav.control.pure_pursuit import PurePursuitParams, PursuitStatus, RegulatedPurePursuit  # noqa: E402
from flex_nav.nav.costmap.layered import Costmap  # noqa: E402
from flex_nav.nav.costmap.map_io import load_map  # noqa: E402
from flex_nav.nav.costmap.obstacle_layer import ObstacleLayerParams  # noqa: E402
from flex_nav.nav.planning.planner import GridPlanner, PlannerParams  # noqa: E402

MAPS_DIR = Path(os.environ.get("FLEX_NAV_BENCH_MAPS", REPO.parent / "shared" / "maps"))
DT = 0.05  # [s] 20 Hz controller


def main() -> int:
    maps = sorted(MAPS_DIR.glob("*.yaml"))
    if not maps:
        print(f"no maps in {MAPS_DIR} (set FLEX_NAV_BENCH_MAPS)")
        return 2
    grid = load_map(maps[0])
    global_cm = Costmap.from_map(grid, inflation=INFLATION)
    plan = GridPlanner(PlannerParams(smooth=True)).plan(global_cm.costs, global_cm.geometry, (20.0, 20.0), (45.0, 40.0))
    if not plan.ok:
        print(f"planning failed: {plan.reason}")
        return 2
    # resample the smoothed plan every 5 cm, as a follow_path server would publish it
    seg = np.hypot(np.diff(plan.path[:, 0]), np.diff(plan.path[:, 1]))
    s = np.concatenate([[0.0], np.cumsum(seg)])
    samples = np.arange(0.0, s[-1], 0.05)
    path = np.column_stack(
        [np.interp(samples, s, plan.path[:, 0]), np.interp(samples, s, plan.path[:, 1]), np.zeros(len(samples))]
    )
    path[:-1, 2] = np.arctan2(np.diff(path[:, 1]), np.diff(path[:, 0]))
    path[-1, 2] = path[-2, 2]
    params = PurePursuitParams(
        desired_linear_vel=0.5, inscribed_radius=INFLATION.inscribed_radius, use_velocity_scaled_lookahead_dist=True
    )
    ctl = RegulatedPurePursuit(params)
    ctl.set_path(path)
    local = Costmap.rolling(4.0, 4.0, 0.05, obstacles=ObstacleLayerParams(), inflation=INFLATION)
    x, y, yaw = float(path[0, 0]), float(path[0, 1]), float(path[0, 2])
    v = w = 0.0
    t0 = time.perf_counter()
    ctl.step((x, y, yaw), (v, w), DT, local.costs, local.geometry)
    print(f"first step (numba compile or cache load): {1e3 * (time.perf_counter() - t0):.0f} ms")
    ctl.set_path(path)
    times = []
    statuses: dict = {}
    for _ in range(int(4 * s[-1] / (params.desired_linear_vel * DT))):
        scan = simulate_scans(grid.occupancy, grid.resolution, np.array([[x, y, yaw]]))[0]
        local.recentre(x, y)
        local.add_scan(scan)
        local.update()
        t = time.perf_counter()
        cmd = ctl.step((x, y, yaw), (v, w), DT, local.costs, local.geometry)
        times.append(time.perf_counter() - t)
        statuses[cmd.status.name] = statuses.get(cmd.status.name, 0) + 1
        if cmd.status is PursuitStatus.GOAL_REACHED or not cmd.status.moving:
            break
        v, w = cmd.v, cmd.w
        yaw += w * DT
        x += v * math.cos(yaw) * DT
        y += v * math.sin(yaw) * DT
    med = statistics.median(times)
    print(
        f"path {s[-1]:.1f} m ({len(path)} poses), {len(times)} steps, final status {cmd.status.name}, "
        f"distance to goal {math.hypot(x - path[-1, 0], y - path[-1, 1]):.3f} m; statuses {statuses}"
    )
    print(
        f"pure pursuit step: median {1e3 * med:.4f} ms, p95 {1e3 * float(np.percentile(times, 95)):.4f} ms, "
        f"max {1e3 * max(times):.4f} ms; ratio to the 0.1 ms budget {med / 1e-4:.2f}x"
    )
    ok = med <= 1e-4 and cmd.status is PursuitStatus.GOAL_REACHED
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
