#!/usr/bin/env python3
"""Global planner on random maps of rectangles, 500² to 4000² cells, against pyastar2d (C++ A*) in the same run.

Maps (seeded): obstacle rectangles 0.2-2.5 m a side at 0.05 m/cell covering about 12 % of the map, the
corners kept clear, inflated with flex_nav's costmap_2d-style inflation (Nav2's benchmark parameters:
inscribed 0.22 m, radius 0.55 m, k = 3.0 /m, as bench_costmap's INFLATION). Queries per map:

- long: the four corner-to-corner queries (top-left <-> bottom-right, top-right <-> bottom-left), start and
  goal the free cells nearest the corners 40 cells in;
- mid: random free pairs 30-60 % of the map's diagonal apart (reported, not a target).

The same two problems as bench_planner, on the same pairs, interleaved pair by pair:

A. flex_nav's default model (straight 1, diagonal √2, cell weight 50 + 0.8·cost) through ``GridPlanner.plan``
   against pyastar2d's C entry point on the weight grid of that model (weight / 50, inf where impassable);
B. the identical problem: flex_nav with ``diagonal_factor=1`` (``plan_cells``) against the same pyastar2d
   call; the optimal costs must agree.

Optimality of A is checked against an exact Dijkstra (scipy.sparse.csgraph on the whole map's graph) on
``FLEX_NAV_BENCH_DIJKSTRA_PAIRS`` pairs of the first map of each size (default 3: the two diagonals, top-left to
bottom-right and top-right to bottom-left, and the first mid pair; 0 skips it), up to
``FLEX_NAV_BENCH_DIJKSTRA_MAX`` cells (default 2000²; scipy needs about 8 GB for the 4000² graph).

Options: ``--sizes 500 1000`` (default 500 1000 2000 4000), ``--repeats N`` (each pair timed N times,
interleaved; default 1). Every call is timed by the wall clock and by the calling thread's CPU time (the
second is less disturbed by other jobs on a shared machine); the target is checked on both. The machine's
load average is printed before and after every size.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, List, Tuple, TypeVar

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

try:
    import pyastar2d.astar as pyastar_c
    from scipy.ndimage import label
except ImportError as err:  # bench-only references
    sys.exit(f"{err}: install the bench references first: bench/run.sh planner_random")

from bench_costmap import INFLATION  # noqa: E402
from bench_planner import dijkstra_costs, load, pyastar_cost_in_model  # noqa: E402

from flex_nav.nav.costmap.costmap_grid import LETHAL, CostmapGeometry  # noqa: E402
from flex_nav.nav.costmap.inflation import Inflator  # noqa: E402
from flex_nav.nav.planning.planner import GridPlanner, PlannerParams  # noqa: E402

Cell = Tuple[int, int]  # (row, col)
T = TypeVar("T")
RESOLUTION = 0.05  # [m/cell]
FILL = 0.12  # fraction of the map covered by obstacle rectangles (before inflation)
SIDE_M = (0.2, 2.5)  # [m] range of a rectangle's sides
CORNER_IN = 40  # [cells] start and goal this far in from the corners
MAPS = {500: 6, 1000: 4, 2000: 3, 4000: 2}  # maps per size
MID_PAIRS = 6  # per map
DIJKSTRA_PAIRS = int(os.environ.get("FLEX_NAV_BENCH_DIJKSTRA_PAIRS", "3"))
DIJKSTRA_MAX = int(os.environ.get("FLEX_NAV_BENCH_DIJKSTRA_MAX", str(2000 * 2000)))  # [cells]


def random_map(size: int, seed: int) -> np.ndarray:
    """Inflated uint8 costs (size x size) of random rectangles, corners clear."""
    rng = np.random.default_rng(seed)
    costs = np.zeros((size, size), dtype=np.uint8)
    lo, hi = (round(s / RESOLUTION) for s in SIDE_M)
    mean_area = ((lo + hi) / 2.0) ** 2
    for _ in range(int(FILL * size * size / mean_area)):
        h, w = rng.integers(lo, hi + 1, 2)
        r, c = rng.integers(0, size, 2)
        costs[r : r + h, c : c + w] = LETHAL
    clear = 2 * CORNER_IN
    for rows in (slice(0, clear), slice(size - clear, size)):
        for cols in (slice(0, clear), slice(size - clear, size)):
            costs[rows, cols] = 0
    Inflator(INFLATION, RESOLUTION).apply(costs)
    return costs


def free_near(costs: np.ndarray, cell: Cell, component: np.ndarray, which: int) -> Cell:
    """The cell of ``component == which`` with cost < 210 nearest ``cell``."""
    ok = (component == which) & (costs < 210)
    rows, cols = np.nonzero(ok)
    best = int(np.argmin((rows - cell[0]) ** 2 + (cols - cell[1]) ** 2))
    return int(rows[best]), int(cols[best])


def queries(costs: np.ndarray, seed: int) -> Tuple[List[Tuple[Cell, Cell]], List[Tuple[Cell, Cell]]]:
    """(long corner-to-corner pairs, mid-length pairs), all in the largest 8-connected passable region."""
    size = costs.shape[0]
    component, _ = label(costs < 253, structure=np.ones((3, 3), dtype=bool))
    counts = np.bincount(component.ravel())
    counts[0] = 0
    which = int(np.argmax(counts))
    a, b = CORNER_IN, size - 1 - CORNER_IN
    tl, tr, bl, br = (free_near(costs, c, component, which) for c in ((a, a), (a, b), (b, a), (b, b)))
    long_pairs = [(tl, br), (br, tl), (tr, bl), (bl, tr)]
    rng = np.random.default_rng(seed + 1000)
    free = np.argwhere((component == which) & (costs < 210))
    mid: List[Tuple[Cell, Cell]] = []
    diagonal = size * math.sqrt(2.0)
    while len(mid) < MID_PAIRS:
        i, j = rng.integers(0, len(free), 2)
        s, g = free[i], free[j]
        if 0.3 * diagonal <= math.hypot(*(s - g)) <= 0.6 * diagonal:
            mid.append(((int(s[0]), int(s[1])), (int(g[0]), int(g[1]))))
    return long_pairs, mid


def timed(call: Callable[..., T], *args: Any) -> Tuple[T, float, float]:
    """(what ``call(*args)`` returns, its wall time [s], this thread's CPU time [s] for it)."""
    wall, cpu = time.perf_counter(), time.thread_time()
    out = call(*args)
    return out, time.perf_counter() - wall, time.thread_time() - cpu


def ms(values: List[float]) -> str:
    return f"median {1e3 * statistics.median(values):8.2f} ms, mean {1e3 * statistics.mean(values):8.2f} ms"


def ratio(mine: List[float], ref: List[float]) -> Tuple[float, float]:
    """(median ratio, mean ratio)."""
    return statistics.median(mine) / statistics.median(ref), statistics.mean(mine) / statistics.mean(ref)


def run_size(size: int, repeats: int, planner: GridPlanner, same: GridPlanner) -> Dict[str, Tuple[float, float]]:
    geo = CostmapGeometry(size, size, RESOLUTION)
    names = [f"{k}_{q}" for k in ("mine_a", "py_a", "mine_b", "py_b") for q in ("long", "mid")]
    times: Dict[str, List[float]] = {name: [] for name in names}  # wall time [s]
    cpu: Dict[str, List[float]] = {name: [] for name in names}  # this thread's CPU time [s]

    def record(name: str, took: List[float]) -> None:
        times[name].append(took[0])
        cpu[name].append(took[1])

    equal_b = total_b = 0
    not_cheaper = True
    checked: List[Tuple[float, float]] = []
    print(f"\n{size}x{size} ({size * RESOLUTION:.0f} m), {MAPS[size]} maps; {load()}")
    for index in range(MAPS[size]):
        seed = 1000 * size + index
        costs = random_map(size, seed)
        long_pairs, mid_pairs = queries(costs, seed)
        flat = (planner.weights[costs] / planner.params.neutral_cost).astype(np.float32).ravel()
        found: Dict[Tuple[Cell, Cell], float] = {}  # flex_nav's A cost of each pair
        for kind, pairs in (("long", long_pairs), ("mid", mid_pairs)):
            for start, goal in pairs:
                s_idx, g_idx = start[0] * size + start[1], goal[0] * size + goal[1]
                sx, sy = geo.cell_to_world(*start)
                gx, gy = geo.cell_to_world(*goal)
                for _ in range(repeats):
                    result, *took = timed(planner.plan, costs, geo, (sx, sy), (gx, gy))
                    record(f"mine_a_{kind}", took)
                    py_path, *took = timed(pyastar_c.astar, flat, size, size, s_idx, g_idx, True, 0)
                    record(f"py_a_{kind}", took)
                    (cost_b, _, _), *took = timed(same.plan_cells, costs, start, goal)
                    record(f"mine_b_{kind}", took)
                    py_path_b, *took = timed(pyastar_c.astar, flat, size, size, s_idx, g_idx, True, 0)
                    record(f"py_b_{kind}", took)
                if not result.ok:
                    raise SystemExit(f"{size}² map {index}: {start}->{goal}: {result.status.name} {result.reason}")
                if pyastar_cost_in_model(planner, costs, py_path) < result.cost * (1 - 1e-9):
                    not_cheaper = False
                total_b += 1
                equal_b += math.isclose(cost_b, pyastar_cost_in_model(same, costs, py_path_b), rel_tol=1e-9)
                found[(start, goal)] = result.cost
        if index == 0 and DIJKSTRA_PAIRS > 0 and size * size <= DIJKSTRA_MAX:
            subset = (long_pairs[0::2] + mid_pairs)[:DIJKSTRA_PAIRS]  # the two diagonals, then mid pairs
            exact = dijkstra_costs(costs, planner, [p[0] for p in subset], [p[1] for p in subset])
            checked.extend(zip([found[p] for p in subset], exact))
    for kind in ("long", "mid"):
        for clock, table in (("wall", times), ("CPU", cpu)):
            mine, ref = table[f"mine_a_{kind}"], table[f"py_a_{kind}"]
            med_a, mean_a = ratio(mine, ref)
            med_b, mean_b = ratio(table[f"mine_b_{kind}"], table[f"py_b_{kind}"])
            print(f"  {kind:4s} {clock:4s} A ({len(mine)} timings): flex_nav {ms(mine)}; pyastar2d {ms(ref)}")
            print(
                f"            A ratio median {med_a:.2f}x, mean {mean_a:.2f}x;  "
                f"B (identical model) median {med_b:.2f}x, mean {mean_b:.2f}x"
            )
            print(f"            B flex_nav {ms(table[f'mine_b_{kind}'])}; pyastar2d {ms(table[f'py_b_{kind}'])}")
    agree = sum(math.isclose(c, e, rel_tol=1e-9) for c, e in checked)
    print(
        f"  B optimal costs equal to pyastar2d's: {equal_b}/{total_b}; "
        f"pyastar2d's A path never cheaper: {not_cheaper}"
    )
    print(
        f"  exact Dijkstra (scipy) == flex_nav A cost: {agree}/{len(checked)}"
        + "".join(f"\n    {c:.6f} vs {e:.6f}" for c, e in checked)
    )
    print(f"  {load()}")
    summary = {
        f"{model} {clock}": ratio(table[f"mine_{p}_long"], table[f"py_{p}_long"])
        for model, p in (("A", "a"), ("B", "b"))
        for clock, table in (("wall", times), ("CPU", cpu))
    }
    if agree != len(checked) or equal_b != total_b or not not_cheaper:
        summary["optimality"] = (math.inf, math.inf)
    return summary


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=sorted(MAPS), choices=sorted(MAPS))
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    planner = GridPlanner(PlannerParams())
    same = GridPlanner(PlannerParams(diagonal_factor=1.0))
    t0 = time.perf_counter()
    planner.plan(np.zeros((8, 8), dtype=np.uint8), CostmapGeometry(8, 8, RESOLUTION), (0.01, 0.01), (0.3, 0.3))
    same.plan_cells(np.zeros((8, 8), dtype=np.uint8), (0, 0), (7, 7))
    print(f"first plan() calls (numba compile or cache load): {(time.perf_counter() - t0) * 1e3:.0f} ms; {load()}")
    print(f"inflation: {INFLATION}; obstacles {FILL:.0%} of the map, sides {SIDE_M} m")
    results = {size: run_size(size, args.repeats, planner, same) for size in args.sizes}
    print("\nsummary, long queries (flex_nav / pyastar2d C, same run; target: median and mean <= 1.0x on A)")
    ok = True
    for size, summary in results.items():
        optimal = "optimality" not in summary
        ok = ok and optimal and all(max(summary[f"A {clock}"]) <= 1.0 for clock in ("wall", "CPU"))
        print(
            f"  {size}²: "
            + "; ".join(f"{k} median {summary[k][0]:.2f}x mean {summary[k][1]:.2f}x" for k in summary if k[0] in "AB")
            + f"; costs {'optimal' if optimal else 'NOT OPTIMAL'}"
        )
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
