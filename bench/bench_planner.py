#!/usr/bin/env python3
"""Global planner benchmark on Nav2's planner benchmark maps, against pyastar2d (C++ A*) in the same run.

Protocol (Nav2 tools/planner_benchmarking): per map, 100 random start/goal pairs from
``random.seed(33)`` / ``randint``, a 100-cell border kept clear, start and goal >= 3 m apart, both on cells
with cost < 210 in the inflated costmap. Inflation: inscribed 0.22 m, radius 0.55 m, k = 3.0 /m.

Two problems are timed, each on the same pairs:

A. flex_nav's default model (straight step 1, diagonal step √2, cell weight 50 + 0.8·cost) against
   pyastar2d on the weight grid of that model (weight / 50, inf where impassable). pyastar2d cannot
   express √2 diagonals (every move costs the weight of the cell entered), so it solves a relaxed
   problem; both costs are reported, pyastar2d's path priced in flex_nav's model as well.
B. the identical problem: flex_nav with ``diagonal_factor=1`` -- the two optimal costs must agree.

pyastar2d is timed at its C entry point (``pyastar2d.astar.astar`` on a pre-flattened float32 grid), the
fastest way to call it; its Python wrapper (which also scans and copies the 4M-cell grid on every call) is
reported separately. flex_nav is timed through ``GridPlanner.plan`` (world coordinates in, world path out).

Optimality: on a subset of pairs the cost is compared with an exact Dijkstra (scipy.sparse.csgraph) on
the full graph of model A.
"""

from __future__ import annotations

import math
import os
import random
import statistics
import sys
import time
from pathlib import Path
from typing import Dict, List, Tuple

import numpy as np

Cell = Tuple[int, int]  # (row, col)

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

try:
    import pyastar2d
    import pyastar2d.astar as pyastar_c
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import dijkstra
except ImportError as err:  # bench-only references
    sys.exit(f"{err}: install the bench references first: bench/run.sh planner")

from bench_costmap import INFLATION, benchmark_maps  # noqa: E402

from flex_nav.nav.costmap.costmap_grid import CostmapGeometry  # noqa: E402
from flex_nav.nav.costmap.layered import Costmap  # noqa: E402
from flex_nav.nav.costmap.map_io import load_map  # noqa: E402
from flex_nav.nav.planning.planner import GridPlanner, PlannerParams  # noqa: E402

PAIRS = 100
DIJKSTRA_PAIRS = int(os.environ.get("FLEX_NAV_BENCH_DIJKSTRA_PAIRS", "4"))  # per map


def nav2_pairs(costs: np.ndarray, resolution: float, count: int = PAIRS) -> List[Tuple[Cell, Cell]]:
    """Start/goal cells (row, col) drawn as Nav2's planner benchmark does."""
    rng = random.Random(33)
    border, max_cost, min_dist = 100, 210, 3.0
    height, width = costs.shape

    def draw() -> Cell:
        while True:
            row = rng.randint(border, height - border)
            col = rng.randint(border, width - border)
            if costs[row, col] < max_cost:
                return row, col

    pairs: List[Tuple[Cell, Cell]] = []
    while len(pairs) < count:
        start, goal = draw(), draw()
        if math.hypot(start[0] - goal[0], start[1] - goal[1]) * resolution >= min_dist:
            pairs.append((start, goal))
    return pairs


def dijkstra_costs(costs: np.ndarray, planner: GridPlanner, sources: list, targets: list) -> list:
    """Exact shortest-path costs of the planner's graph by scipy's Dijkstra on an explicit sparse graph."""
    height, width = costs.shape
    weight = planner.weights[costs]
    rows, cols, data = [], [], []
    index = np.arange(height * width, dtype=np.int64).reshape(height, width)
    diag = planner.params.diagonal_factor
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            if dr == 0 and dc == 0:
                continue
            src = index[max(0, -dr) : height - max(0, dr), max(0, -dc) : width - max(0, dc)]
            dst = index[max(0, dr) : height + min(0, dr), max(0, dc) : width + min(0, dc)]
            w = weight[max(0, dr) : height + min(0, dr), max(0, dc) : width + min(0, dc)]
            ok = np.isfinite(w)
            rows.append(src[ok])
            cols.append(dst[ok])
            data.append(w[ok] * (diag if dr and dc else 1.0))
    graph = csr_matrix(
        (np.concatenate(data), (np.concatenate(rows), np.concatenate(cols))), shape=(height * width,) * 2
    )
    out = []
    for (sr, sc), (gr, gc) in zip(sources, targets):
        dist = dijkstra(graph, directed=True, indices=sr * width + sc)
        out.append(float(dist[gr * width + gc]))
    return out


def pyastar_cost_in_model(planner: GridPlanner, costs: np.ndarray, path: np.ndarray | None) -> float:
    if path is None or len(path) == 0:
        return math.inf
    return planner.path_cost(costs, np.asarray(path, dtype=np.int64))


def load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f} {five:.2f} {fifteen:.2f}"


def median_ms(values: list) -> float:
    return float(1e3 * statistics.median(values))


def main() -> int:
    maps = benchmark_maps()  # and the inflation: the costmap bench's, Nav2's
    if not maps:
        return 2
    planner = GridPlanner(PlannerParams())
    same_planner = GridPlanner(PlannerParams(diagonal_factor=1.0))
    t0 = time.perf_counter()
    tiny = np.zeros((8, 8), dtype=np.uint8)
    planner.plan(tiny, CostmapGeometry(8, 8, 0.05), (0.01, 0.01), (0.3, 0.3))
    first_call_s = time.perf_counter() - t0
    print(f"first plan() call (numba compile or cache load): {first_call_s * 1e3:.0f} ms")
    print(f"inflation: {INFLATION}; {load()}")
    summary = []
    for yaml_path in maps:
        grid = load_map(yaml_path)
        costs = Costmap.from_map(grid, inflation=INFLATION).costs
        geo = Costmap.from_map(grid).geometry
        pairs = nav2_pairs(costs, grid.resolution)
        weights_a = (planner.weights[costs] / planner.params.neutral_cost).astype(np.float32)
        flat_a = weights_a.ravel()
        height, width = costs.shape

        rows: Dict[str, List[float]] = {"mine_a": [], "py_c": [], "py_wrap": [], "mine_b": [], "py_c_b": []}
        costs_a, py_costs_a, same_ok, expanded = [], [], 0, []
        for start, goal in pairs:
            sx, sy = geo.cell_to_world(*start)
            gx, gy = geo.cell_to_world(*goal)
            t = time.perf_counter()
            result = planner.plan(costs, geo, (sx, sy), (gx, gy))
            rows["mine_a"].append(time.perf_counter() - t)
            s_idx, g_idx = start[0] * width + start[1], goal[0] * width + goal[1]
            t = time.perf_counter()
            py_path = pyastar_c.astar(flat_a, height, width, s_idx, g_idx, True, 0)
            rows["py_c"].append(time.perf_counter() - t)
            t = time.perf_counter()
            pyastar2d.astar_path(weights_a, start, goal, allow_diagonal=True)
            rows["py_wrap"].append(time.perf_counter() - t)
            if not result.ok:
                print(f"  {yaml_path.name}: {start}->{goal}: {result.status.name} {result.reason}")
                continue
            costs_a.append(result.cost)
            expanded.append(result.expanded)
            py_costs_a.append(pyastar_cost_in_model(planner, costs, py_path))
            # B: the identical problem
            t = time.perf_counter()
            cost_b, _, _ = same_planner.plan_cells(costs, start, goal)
            rows["mine_b"].append(time.perf_counter() - t)
            t = time.perf_counter()
            py_path_b = pyastar_c.astar(flat_a, height, width, s_idx, g_idx, True, 0)
            rows["py_c_b"].append(time.perf_counter() - t)
            py_b = pyastar_cost_in_model(same_planner, costs, py_path_b)
            if math.isclose(cost_b, py_b, rel_tol=1e-9):
                same_ok += 1
        worse = [p / m - 1.0 for m, p in zip(costs_a, py_costs_a)]
        ratio_a = statistics.median(rows["mine_a"]) / statistics.median(rows["py_c"])
        mean_ratio_a = statistics.mean(rows["mine_a"]) / statistics.mean(rows["py_c"])
        ratio_b = statistics.median(rows["mine_b"]) / statistics.median(rows["py_c_b"])
        print(f"\n{yaml_path.name}: {len(pairs)} pairs, {len(costs_a)} planned")
        print(
            f"  A default model: flex_nav plan() median {median_ms(rows['mine_a']):.2f} ms "
            f"(mean {1e3 * statistics.mean(rows['mine_a']):.2f}, median expanded {statistics.median(expanded):.0f}); "
            f"pyastar2d C median {median_ms(rows['py_c']):.2f} ms (mean {1e3 * statistics.mean(rows['py_c']):.2f}, "
            f"wrapper median {median_ms(rows['py_wrap']):.2f} ms); "
            f"ratio median {ratio_a:.2f}x, mean {mean_ratio_a:.2f}x"
        )
        print(
            f"    cost: flex_nav optimal; pyastar2d's path priced in flex_nav's model is "
            f"{100 * statistics.median(worse):.2f} % more (median), {100 * max(worse):.2f} % (max), "
            f"never less: {min(worse) >= -1e-9}"
        )
        print(
            f"  B identical model (diagonal 1): flex_nav median {median_ms(rows['mine_b']):.2f} ms; pyastar2d C "
            f"{median_ms(rows['py_c_b']):.2f} ms; ratio {ratio_b:.2f}x; equal optimal costs {same_ok}/{len(costs_a)}"
        )
        if DIJKSTRA_PAIRS > 0:
            subset = list(zip(pairs[:DIJKSTRA_PAIRS], costs_a[:DIJKSTRA_PAIRS]))
            t = time.perf_counter()
            exact = dijkstra_costs(costs, planner, [p[0][0] for p in subset], [p[0][1] for p in subset])
            dt = time.perf_counter() - t
            agree = sum(math.isclose(c, e, rel_tol=1e-9) for (_, c), e in zip(subset, exact))
            print(
                f"  Dijkstra check (scipy, full graph, {dt:.1f} s incl. graph build): flex_nav cost == exact optimum "
                f"on {agree}/{len(subset)} pairs"
                + "".join(f"\n    {c:.6f} vs {e:.6f}" for (_, c), e in zip(subset, exact))
            )
        summary.append((yaml_path.name, ratio_a, mean_ratio_a, ratio_b))
    all_ok = all(a <= 1.0 and mean <= 1.0 for _, a, mean, _ in summary)
    print(f"\nsummary (plan time / pyastar2d C, median and mean, target <= 1.0x); {load()}:")
    for name, ratio_a, mean_ratio_a, ratio_b in summary:
        print(
            f"  {name}: default model median {ratio_a:.2f}x, mean {mean_ratio_a:.2f}x; "
            f"identical model median {ratio_b:.2f}x"
        )
    print("PASS" if all_ok else "FAIL")
    return 0 if all_ok else 1


if __name__ == "__main__":
    sys.exit(main())
