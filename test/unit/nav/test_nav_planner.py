"""Global planner: optimality against an independent Dijkstra, typed failures, tolerance, smoothing."""

import heapq
import math
from typing import Tuple

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import INSCRIBED, LETHAL, NO_INFORMATION, CostmapGeometry
from flex_nav.nav.costmap.inflation import InflationParams, inflate
from flex_nav.nav.planning.astar import QueueStorage, line_cost
from flex_nav.nav.planning.planner import GridPlanner, PlannerParams, PlanStatus

RES = 0.1


def cell(row) -> Tuple[int, int]:
    """A (row, col) of np.argwhere's as a cell index."""
    return int(row[0]), int(row[1])


def two_free_cells(rng, free) -> Tuple[Tuple[int, int], Tuple[int, int]]:
    """Two different cells of ``free`` (np.argwhere's rows), drawn with ``rng``."""
    first, second = rng.choice(len(free), 2, replace=False)
    return cell(free[first]), cell(free[second])


def dijkstra(costs, start, goal, params):
    """Reference: textbook Dijkstra with heapq on the same graph, written from the cost model's definition."""
    height, width = costs.shape

    def weight(cost):
        if cost == NO_INFORMATION:
            return params.neutral_cost + params.cost_factor * params.unknown_cost if params.allow_unknown else None
        if cost >= params.lethal_cost or cost == LETHAL:
            return None
        return params.neutral_cost + params.cost_factor * cost

    dist = {start: 0.0}
    queue = [(0.0, start)]
    done = set()
    while queue:
        d, cell = heapq.heappop(queue)
        if cell in done:
            continue
        done.add(cell)
        if cell == goal:
            return d
        r, c = cell
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                if dr == 0 and dc == 0:
                    continue
                nr, nc = r + dr, c + dc
                if not (0 <= nr < height and 0 <= nc < width):
                    continue
                w = weight(int(costs[nr, nc]))
                if w is None:
                    continue
                step = w * (params.diagonal_factor if dr and dc else 1.0)
                if d + step < dist.get((nr, nc), math.inf):
                    dist[(nr, nc)] = d + step
                    heapq.heappush(queue, (d + step, (nr, nc)))
    return math.inf


def random_costs(rng, shape=(40, 50), lethal=0.2):
    costs = rng.integers(0, 253, shape).astype(np.uint8)
    costs[rng.random(shape) < 0.5] = 0
    costs[rng.random(shape) < lethal] = LETHAL
    costs[rng.random(shape) < 0.03] = INSCRIBED
    costs[rng.random(shape) < 0.03] = NO_INFORMATION
    return costs


def geometry_of(costs):
    return CostmapGeometry(costs.shape[1], costs.shape[0], RES, -1.0, 0.5)


def centre(geo, cell):
    return geo.cell_to_world(*cell)


@pytest.mark.parametrize(
    "params",
    [
        PlannerParams(),
        PlannerParams(diagonal_factor=1.0),
        PlannerParams(neutral_cost=1.0, cost_factor=3.0, allow_unknown=True, unknown_cost=100, lethal_cost=254),
    ],
)
def test_cost_equals_dijkstra_on_random_grids(params):
    rng = np.random.default_rng(12)
    planner = GridPlanner(params)
    found = 0
    for _ in range(25):
        costs = random_costs(rng)
        free = np.argwhere(np.isfinite(planner.weights[costs]))
        s, g = two_free_cells(rng, free)
        cost, cells, _ = planner.plan_cells(costs, s, g)
        expected = dijkstra(costs, s, g, params)
        if math.isinf(expected):
            assert math.isinf(cost) and len(cells) == 0
            continue
        found += 1
        assert cost == pytest.approx(expected, rel=1e-12, abs=1e-9)
        assert tuple(cells[0]) == s and tuple(cells[-1]) == g
        assert planner.path_cost(costs, cells) == pytest.approx(cost, rel=1e-12)
    assert found >= 10  # the grids are not all disconnected


def test_reused_work_arrays_give_same_answers_as_a_fresh_planner():
    rng = np.random.default_rng(2)
    costs = random_costs(rng, (60, 60), lethal=0.1)
    shared = GridPlanner()
    free = np.argwhere(np.isfinite(shared.weights[costs]))
    for _ in range(20):
        s, g = two_free_cells(rng, free)
        assert shared.plan_cells(costs, s, g)[0] == GridPlanner().plan_cells(costs, s, g)[0]
    shared._generation = 2**32 - 4  # next query wraps the stamps
    s, g = two_free_cells(rng, free)
    assert shared.plan_cells(costs, s, g)[0] == GridPlanner().plan_cells(costs, s, g)[0]
    assert shared._generation == 2


def test_success_path_shape_and_poses():
    costs = np.zeros((20, 30), dtype=np.uint8)
    costs[5:15, 15] = LETHAL
    geo = geometry_of(costs)
    result = GridPlanner().plan(costs, geo, (-0.7, 1.2), (1.5, 1.6, 0.3))
    assert result.ok and result.status is PlanStatus.SUCCESS
    assert result.path.shape[1] == 3 and len(result.path) >= 2
    assert tuple(result.path[0, :2]) == (-0.7, 1.2)
    assert tuple(result.path[-1]) == (1.5, 1.6, 0.3)
    # every pose faces the next one
    d = np.diff(result.path[:, :2], axis=0)
    np.testing.assert_allclose(result.path[:-1, 2], np.arctan2(d[:, 1], d[:, 0]))
    # steps are at most one diagonal cell apart, and no cell of the path is impassable
    assert np.abs(np.diff(result.cells, axis=0)).max() == 1
    assert (costs[result.cells[:, 0], result.cells[:, 1]] < INSCRIBED).all()


def test_start_and_goal_in_one_cell_gives_two_poses():
    costs = np.zeros((5, 5), dtype=np.uint8)
    geo = geometry_of(costs)
    x, y = centre(geo, (2, 2))
    result = GridPlanner().plan(costs, geo, (x, y), (x + 0.02, y + 0.01))
    assert result.ok and len(result.path) == 2 and result.cost == 0.0
    assert tuple(result.path[1, :2]) == (x + 0.02, y + 0.01)
    same = GridPlanner().plan(costs, geo, (x, y), (x, y, 1.0))
    assert same.ok and len(same.path) == 2 and (same.path[:, 2] == 1.0).all()


def test_no_path_when_walled_off():
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[:, 10] = LETHAL
    geo = geometry_of(costs)
    result = GridPlanner().plan(costs, geo, centre(geo, (5, 2)), centre(geo, (5, 18)))
    assert result.status is PlanStatus.NO_PATH and not result.ok
    assert len(result.path) == 0 and math.isinf(result.cost)
    assert "no path" in result.reason and result.expanded > 0


def across_a_wall(cost):
    """A 20 x 20 grid with a wall of ``cost`` down column 10, and a start and a goal on either side: plan's args."""
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[:, 10] = cost
    geo = geometry_of(costs)
    return costs, geo, centre(geo, (5, 2)), centre(geo, (5, 18))


def test_inscribed_wall_blocks_unless_lethal_cost_raised():
    args = across_a_wall(INSCRIBED)
    assert GridPlanner().plan(*args).status is PlanStatus.NO_PATH
    assert GridPlanner(PlannerParams(lethal_cost=254)).plan(*args).ok


def test_unknown_blocks_unless_allowed():
    args = across_a_wall(NO_INFORMATION)
    costs = args[0]
    assert GridPlanner().plan(*args).status is PlanStatus.NO_PATH
    result = GridPlanner(PlannerParams(allow_unknown=True)).plan(*args)
    assert result.ok and (costs[result.cells[:, 0], result.cells[:, 1]] == NO_INFORMATION).any()


def test_start_blocked_goal_blocked_out_of_map():
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[3, 3] = LETHAL
    costs[10:13, 10:13] = LETHAL
    geo = geometry_of(costs)
    planner = GridPlanner()
    blocked = planner.plan(costs, geo, centre(geo, (3, 3)), centre(geo, (8, 8)))
    assert blocked.status is PlanStatus.START_BLOCKED and "start" in blocked.reason and "254" in blocked.reason
    goal = planner.plan(costs, geo, centre(geo, (8, 8)), centre(geo, (11, 11)))
    assert goal.status is PlanStatus.GOAL_BLOCKED and "goal_tolerance" in goal.reason
    outside = planner.plan(costs, geo, centre(geo, (8, 8)), (100.0, 0.0))
    assert outside.status is PlanStatus.OUT_OF_MAP and "goal" in outside.reason
    outside = planner.plan(costs, geo, (-1.01, 0.6), centre(geo, (8, 8)))
    assert outside.status is PlanStatus.OUT_OF_MAP and "start" in outside.reason
    for r in (blocked, goal, outside):
        assert len(r.path) == 0


def test_goal_tolerance_moves_goal_to_nearest_passable_cell():
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[10:13, 10:13] = LETHAL
    geo = geometry_of(costs)
    goal = centre(geo, (11, 11))
    near = GridPlanner(PlannerParams(goal_tolerance=0.1)).plan(costs, geo, centre(geo, (2, 2)), goal)
    assert near.status is PlanStatus.GOAL_BLOCKED  # nearest free cell centre is 0.2 m away
    moved = GridPlanner(PlannerParams(goal_tolerance=0.25)).plan(costs, geo, centre(geo, (2, 2)), goal)
    assert moved.ok and "moved" in moved.reason
    assert moved.goal_cell is not None
    gr, gc = moved.goal_cell
    assert costs[gr, gc] == 0 and max(abs(gr - 11), abs(gc - 11)) == 2 and min(abs(gr - 11), abs(gc - 11)) == 0
    assert tuple(moved.path[-1, :2]) == pytest.approx(centre(geo, moved.goal_cell))


@pytest.mark.parametrize(
    ("start", "goal", "needle"),
    [
        ((float("nan"), 0.0), (1.0, 1.0), "start has a non-finite"),
        ((0.0, 1.0), (1.0, float("inf")), "goal has a non-finite"),
        ((0.0, 1.0), (1.0,), "goal must be"),
        ((0.0, 1.0), ("a", 1.0), "goal must be numbers"),
    ],
)
def test_invalid_input(start, goal, needle):
    costs = np.zeros((20, 20), dtype=np.uint8)
    result = GridPlanner().plan(costs, geometry_of(costs), start, goal)
    assert result.status is PlanStatus.INVALID_INPUT and needle in result.reason
    assert len(result.path) == 0


def test_wrong_costs_array_is_invalid_input():
    costs = np.zeros((20, 20), dtype=np.uint8)
    geo = geometry_of(costs)
    assert GridPlanner().plan(costs.astype(np.int16), geo, (0, 1), (0.5, 1)).status is PlanStatus.INVALID_INPUT
    assert GridPlanner().plan(costs[:10], geo, (0, 1), (0.5, 1)).status is PlanStatus.INVALID_INPUT


def test_smoothing_and_simplify_keep_cost_and_reduce_poses():
    rng = np.random.default_rng(5)
    costs = np.zeros((60, 60), dtype=np.uint8)
    costs[rng.random(costs.shape) < 0.05] = LETHAL
    costs[0:3, :] = 0
    costs[57:, :] = 0
    geo = geometry_of(costs)
    start, goal = centre(geo, (1, 1)), centre(geo, (58, 57))
    plain = GridPlanner().plan(costs, geo, start, goal)
    smooth = GridPlanner(PlannerParams(smooth=True)).plan(costs, geo, start, goal)
    simple = GridPlanner(PlannerParams(simplify=True)).plan(costs, geo, start, goal)
    assert plain.ok and smooth.ok and simple.ok
    assert len(smooth.path) < len(plain.path) and len(simple.path) < len(plain.path)
    assert smooth.cost == plain.cost  # the optimal grid cost is reported either way
    # each smoothed segment's Bresenham walk is passable and costs no more than the optimal path
    planner = GridPlanner()
    rows, cols = geo.world_to_cells(smooth.path[:, 0], smooth.path[:, 1])
    total = sum(
        line_cost(costs, planner.weights, math.sqrt(2), rows[i], cols[i], rows[i + 1], cols[i + 1])
        for i in range(len(rows) - 1)
    )
    assert total <= plain.cost + 1e-9
    # simplify keeps only the corners of the grid path: the removed poses lie on straight runs
    kept = {tuple(np.round(p, 9)) for p in simple.path[1:-1, :2]}
    xs, ys = geo.cells_to_world(plain.cells[:, 0], plain.cells[:, 1])
    assert kept <= {tuple(np.round((x, y), 9)) for x, y in zip(xs, ys)}


@pytest.mark.parametrize(
    "kwargs",
    [
        {"neutral_cost": 0.0},
        {"cost_factor": -1.0},
        {"diagonal_factor": 0.5},
        {"diagonal_factor": 3.0},
        {"lethal_cost": 0},
        {"lethal_cost": 300},
        {"unknown_cost": 255},
        {"goal_tolerance": float("nan")},
        {"smoothing_slack": -0.1},
    ],
)
def test_bad_params(kwargs):
    with pytest.raises(ConfigError):
        PlannerParams(**kwargs)


def test_path_cost_rejects_non_neighbour_paths():
    with pytest.raises(ConfigError):
        GridPlanner().path_cost(np.zeros((5, 5), dtype=np.uint8), np.array([[0, 0], [0, 2]]))


def test_full_queue_storage_is_grown_and_the_search_repeated():
    rng = np.random.default_rng(8)
    costs = random_costs(rng, (60, 60), lethal=0.1)
    planner = GridPlanner()
    planner._queue = QueueStorage(pool_rows=1, heap_rows=1, stack_size=1)
    free = np.argwhere(np.isfinite(planner.weights[costs]))
    s, g = cell(free[0]), cell(free[-1])
    cost, _, expanded = planner.plan_cells(costs, s, g)
    assert cost == GridPlanner().plan_cells(costs, s, g)[0] and expanded > 0
    queue = planner._queue
    assert len(queue.pool) > 1 and len(queue.heap) > 1 and len(queue.stack) > 1


def test_start_escape_leaves_an_inscribed_start_but_nothing_else_changes():
    # the robot backed off a bumper contact and stands on an inscribed cell, as in a bumper recovery
    geo = CostmapGeometry(40, 20, RES)
    costs = np.zeros((20, 40), dtype=np.uint8)
    costs[8:13, 8:13] = INSCRIBED  # around the start
    costs[10, 10] = INSCRIBED
    costs[:, 30] = INSCRIBED  # a wall of inscribed cells far from the start
    costs[5, 30] = 0  # with one free gap
    start, goal = (1.05, 1.05), (3.55, 1.05)
    strict = GridPlanner(PlannerParams())
    assert strict.plan(costs, geo, start, goal).status is PlanStatus.START_BLOCKED
    escaping = GridPlanner(PlannerParams(start_escape=0.3))
    result = escaping.plan(costs, geo, start, goal)
    assert result.status is PlanStatus.SUCCESS
    crossed = [tuple(c) for c in result.cells if costs[tuple(c)] >= INSCRIBED]
    assert crossed and all(math.hypot(r - 10, c - 10) <= 3.0 for r, c in crossed)  # only near the start
    assert (5, 30) in [tuple(c) for c in result.cells]  # the far wall is still only passable at its gap
    assert costs[10, 10] == INSCRIBED  # the caller's costmap is not modified
    lethal = costs.copy()
    lethal[10, 10] = LETHAL
    assert escaping.plan(lethal, geo, start, goal).status is PlanStatus.START_BLOCKED  # never out of a lethal cell
    with pytest.raises(ConfigError, match="start_escape"):
        PlannerParams(start_escape=-1.0)


def inflated_rectangles(rng, size=80):
    """Costs of a few random lethal rectangles inflated as costmap_2d does (0.05 m cells): long cost gradients."""
    costs = np.zeros((size, size), dtype=np.uint8)
    for _ in range(12):
        r, c = rng.integers(0, size, 2)
        h, w = rng.integers(2, 14, 2)
        costs[r : r + h, c : c + w] = LETHAL
    return inflate(costs, 0.05, InflationParams(inscribed_radius=0.1, inflation_radius=0.6, cost_scaling_factor=3.0))


@pytest.mark.parametrize("params", [PlannerParams(), PlannerParams(diagonal_factor=1.0)])
def test_cost_equals_dijkstra_on_inflated_rectangle_maps(params):
    # inflation gradients make many cells reachable first by a dearer diagonal and later by a cheaper way:
    # the queue's bucket ring, its drop of overtaken entries and the way in beside a diagonal are all used
    rng = np.random.default_rng(5)
    planner = GridPlanner(params)
    for _ in range(12):
        costs = inflated_rectangles(rng)
        free = np.argwhere(np.isfinite(planner.weights[costs]))
        s, g = two_free_cells(rng, free)
        cost, cells, _ = planner.plan_cells(costs, s, g)
        expected = dijkstra(costs, s, g, params)
        assert cost == pytest.approx(expected, rel=1e-12, abs=1e-9) or math.isinf(cost) == math.isinf(expected)
        if math.isfinite(expected):
            assert planner.path_cost(costs, cells) == pytest.approx(cost, rel=1e-12)


def test_open_space_search_expands_only_the_path():
    # the heuristic is exact in free space and equal-f successors are taken deepest first, so the search
    # runs straight to the goal: one expanded cell per path cell
    costs = np.zeros((300, 300), dtype=np.uint8)
    planner = GridPlanner()
    for goal in ((250, 100), (20, 290), (299, 299), (150, 0)):
        cost, cells, expanded = planner.plan_cells(costs, (10, 10), goal)
        assert expanded == len(cells)
        assert cost == pytest.approx(planner.heuristic_scale * octile((10, 10), goal), rel=1e-12)


def octile(a, b):
    d_row, d_col = abs(a[0] - b[0]), abs(a[1] - b[1])
    return max(d_row, d_col) + (math.sqrt(2.0) - 1.0) * min(d_row, d_col)


def test_unreachable_goal_expands_the_start_region_once():
    costs = np.zeros((40, 40), dtype=np.uint8)
    costs[10:20, 10] = costs[10:20, 20] = costs[10, 10:21] = costs[19, 10:21] = LETHAL  # a closed box
    costs[25:, :] = 30  # a cheaper-or-dearer mix outside: the search still closes every cell once
    costs[30:35, 5:35] = 120
    planner = GridPlanner()
    cost, cells, expanded = planner.plan_cells(costs, (2, 2), (15, 15))
    assert math.isinf(cost) and len(cells) == 0
    outside = 40 * 40 - 10 * 11  # every cell but the box and what it encloses
    assert expanded == outside
    cost, _, expanded = planner.plan_cells(costs, (15, 15), (2, 2))  # from inside: only the inside
    assert math.isinf(cost) and expanded == 8 * 9
