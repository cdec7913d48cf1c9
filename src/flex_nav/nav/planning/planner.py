"""Global planner: optimal 8-connected A* on a costmap with a navfn-style cell cost.

Cost model (what "optimal" refers to): entering a cell of cost ``c`` costs
``step · (neutral_cost + cost_factor · c)``, ``step`` = 1 for a straight move and ``diagonal_factor``
(√2 by default) for a diagonal one. Cells with ``c >= lethal_cost`` (default 253: inscribed and lethal)
are impassable, and so are NO_INFORMATION cells unless ``allow_unknown`` (then they cost like
``unknown_cost``). A path's cost is the sum over its moves; the planner returns a path of minimum cost.

A goal on an impassable cell is moved to the nearest passable cell within ``goal_tolerance`` [m] (ties
go to the cheaper cell). Results are typed: :class:`PlanResult` with ``status`` SUCCESS and a path of at
least two poses, or a failure status with a reason and an empty path -- never a one-point path.

Optional post-processing: ``smooth`` (line-of-sight shortcuts that do not raise the path's cost by more
than ``smoothing_slack``) and ``simplify`` (drop poses on straight runs).

A :class:`GridPlanner` keeps work arrays sized to the last costmap; it is guarded by a lock, so one
instance can be shared, but calls on one instance run one at a time.
"""

from __future__ import annotations

import enum
import math
import threading
from dataclasses import dataclass, field
from typing import Optional, Sequence, Tuple

import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import LETHAL, NO_INFORMATION, CostmapGeometry
from flex_nav.nav.costmap.grid_map import Cell
from flex_nav.nav.planning import astar

_OWNER = "planner"  # in the messages of PlannerParams' checks


class PlanStatus(enum.Enum):
    """Outcome of a planning request."""

    SUCCESS = 0
    NO_PATH = 1  # start and goal are not connected through passable cells
    START_BLOCKED = 2  # the start cell is impassable
    GOAL_BLOCKED = 3  # the goal cell is impassable and no passable cell is within goal_tolerance
    OUT_OF_MAP = 4  # start or goal is outside the costmap
    INVALID_INPUT = 5  # NaN/inf coordinates, no costmap


@dataclass(frozen=True)
class PlannerParams:
    """Cost model and options of :class:`GridPlanner`."""

    neutral_cost: float = 50.0  # weight of a free cell (navfn's COST_NEUTRAL)
    cost_factor: float = 0.8  # weight added per unit of cell cost (navfn's COST_FACTOR)
    lethal_cost: int = 253  # cells with cost >= this are impassable (253 = inscribed, 254 = lethal only)
    allow_unknown: bool = False  # plan through NO_INFORMATION cells
    unknown_cost: int = 252  # cell cost used for NO_INFORMATION cells when allow_unknown
    diagonal_factor: float = math.sqrt(2.0)  # cost multiplier of a diagonal move (1..2)
    goal_tolerance: float = 0.0  # [m] move a blocked goal to a passable cell this close
    start_escape: float = 0.0  # [m] a start on an impassable, not lethal cell (e.g. inscribed, next to a bumper
    #   contact) may leave through such cells within this distance (move_base's planner clears the robot's cell)
    smooth: bool = False  # shortcut the grid path along straight lines where that costs no more
    smoothing_slack: float = 0.0  # shortcuts may cost this fraction more than the path they replace
    simplify: bool = False  # drop poses in the middle of straight runs

    def __post_init__(self) -> None:
        validation.number(_OWNER, "neutral_cost", self.neutral_cost, minimum=1e-9)
        validation.number(_OWNER, "cost_factor", self.cost_factor, minimum=0.0)
        validation.number(_OWNER, "goal_tolerance", self.goal_tolerance, minimum=0.0, unit="[m]")
        validation.number(_OWNER, "start_escape", self.start_escape, minimum=0.0, unit="[m]")
        validation.number(_OWNER, "smoothing_slack", self.smoothing_slack, minimum=0.0)
        validation.number(_OWNER, "diagonal_factor", self.diagonal_factor, minimum=1.0, maximum=2.0)
        validation.integer(_OWNER, "lethal_cost", self.lethal_cost, minimum=1, maximum=255)
        validation.integer(_OWNER, "unknown_cost", self.unknown_cost, minimum=0, maximum=254)

    def weight_table(self) -> np.ndarray:
        """float64[256]: the weight of entering a cell of each cost (inf = impassable)."""
        table = self.neutral_cost + self.cost_factor * np.arange(256, dtype=np.float64)
        table[self.lethal_cost :] = np.inf
        table[LETHAL] = np.inf
        table[NO_INFORMATION] = (
            self.neutral_cost + self.cost_factor * self.unknown_cost if self.allow_unknown else np.inf
        )
        return table


@dataclass(frozen=True)
class PlanResult:
    """A plan or a typed failure.

    ``path`` is (N, 3) float64 ``[x [m], y [m], yaw [rad]]`` in the costmap frame, N >= 2 on success
    and N == 0 on failure. ``cells`` are the grid path's (row, col) before smoothing. ``cost`` is the grid
    path's cost under the cost model (inf on failure).
    """

    status: PlanStatus
    reason: str = ""
    path: np.ndarray = field(default_factory=lambda: np.empty((0, 3)))
    cells: np.ndarray = field(default_factory=lambda: np.empty((0, 2), dtype=np.int64))
    cost: float = math.inf
    expanded: int = 0  # cells taken off the open list
    goal_cell: Optional[Tuple[int, int]] = None  # the goal cell actually used (after tolerance)

    @property
    def ok(self) -> bool:
        """True on SUCCESS."""
        return self.status is PlanStatus.SUCCESS


class GridPlanner:
    """Plans on uint8 costs with a :class:`CostmapGeometry`; see the module docstring for the cost model."""

    def __init__(self, params: Optional[PlannerParams] = None) -> None:
        params = params if params is not None else PlannerParams()
        self.params = params
        self.weights = params.weight_table()
        finite = self.weights[np.isfinite(self.weights)]
        self.heuristic_scale = float(finite.min()) if finite.size else 0.0
        self._lock = threading.Lock()
        self._shape: Tuple[int, int] = (0, 0)
        self._g = np.empty(0, dtype=np.float64)
        self._parent = np.empty(0, dtype=np.int32)
        self._state = np.empty(0, dtype=np.uint32)
        self._generation = 0
        self._queue = astar.QueueStorage()  # kept between queries, doubled when a search fills it

    def passable(self, cost: int) -> bool:
        """True if a cell of this cost can be entered."""
        return bool(np.isfinite(self.weights[cost]))

    def plan(
        self,
        costs: np.ndarray,
        geometry: CostmapGeometry,
        start: Sequence[float],
        goal: Sequence[float],
    ) -> PlanResult:
        """Plan from ``start`` (x, y[, yaw]) to ``goal`` (x, y[, yaw]) [m, rad] on ``costs`` (uint8 (H, W)).

        The last pose takes the goal's yaw when given, every other pose faces the next one.
        """
        failure = _check_request(costs, geometry, start, goal)
        if failure is not None:
            return failure
        start_cell = geometry.world_to_cell(start[0], start[1])
        goal_cell = geometry.world_to_cell(goal[0], goal[1])
        start_cost = int(costs[start_cell])
        if not self.passable(start_cost) and start_cost < LETHAL and self.params.start_escape > 0.0:
            costs = self._escape_costs(costs, geometry, start_cell)
            start_cost = int(costs[start_cell])
        if not self.passable(start_cost):
            return PlanResult(
                PlanStatus.START_BLOCKED,
                f"start ({start[0]:.3f}, {start[1]:.3f}) is on an impassable cell (cost {start_cost})",
            )
        goal_moved = False
        goal_cost = int(costs[goal_cell])
        if not self.passable(goal_cost):
            moved = self._nearest_passable(costs, geometry, goal[0], goal[1])
            if moved is None:
                return PlanResult(
                    PlanStatus.GOAL_BLOCKED,
                    f"goal ({goal[0]:.3f}, {goal[1]:.3f}) is on an impassable cell (cost {goal_cost}) and no "
                    f"passable cell is within goal_tolerance {self.params.goal_tolerance:.3f} m",
                )
            goal_cell, goal_moved = moved, True
        cost, cells, expanded = self.plan_cells(costs, start_cell, goal_cell)
        if not math.isfinite(cost):
            return PlanResult(
                PlanStatus.NO_PATH,
                f"no path from ({start[0]:.3f}, {start[1]:.3f}) to ({goal[0]:.3f}, {goal[1]:.3f}): "
                f"searched {expanded} cells",
                expanded=expanded,
                goal_cell=(int(goal_cell[0]), int(goal_cell[1])),
            )
        path = self._to_world(
            costs=costs, geometry=geometry, cells=cells, start=start, goal=goal, goal_moved=goal_moved
        )
        return PlanResult(
            PlanStatus.SUCCESS,
            "goal moved to the nearest passable cell" if goal_moved else "",
            path,
            cells,
            cost,
            expanded,
            (int(goal_cell[0]), int(goal_cell[1])),
        )

    def _escape_costs(self, costs: np.ndarray, geometry: CostmapGeometry, start: Tuple[int, int]) -> np.ndarray:
        """A copy of ``costs`` where the impassable, not lethal cells within ``start_escape`` of the start are
        made passable at the highest passable cost, so the path can leave them (costly, so it leaves them fast)."""
        radius = math.ceil(self.params.start_escape / geometry.resolution)
        rows = slice(max(0, start[0] - radius), min(costs.shape[0], start[0] + radius + 1))
        cols = slice(max(0, start[1] - radius), min(costs.shape[1], start[1] + radius + 1))
        rr, cc = np.mgrid[rows, cols]
        near = (rr - start[0]) ** 2 + (cc - start[1]) ** 2 <= radius * radius
        window = costs[rows, cols]
        blocked = near & (window >= self.params.lethal_cost) & (window < LETHAL)
        if not blocked.any():
            return costs
        escaped = costs.copy()
        escaped[rows, cols][blocked] = self.params.lethal_cost - 1
        return escaped

    def plan_cells(
        self, costs: np.ndarray, start: Tuple[int, int], goal: Tuple[int, int]
    ) -> Tuple[float, np.ndarray, int]:
        """The search alone: (cost or inf, (N, 2) cells start..goal or empty, expanded) between passable cells."""
        height, width = costs.shape
        flat = costs.reshape(-1)
        with self._lock:
            self._ensure_work(height, width)
            cost, expanded, self._generation = astar.search(
                flat,
                width,
                self.weights,
                self.params.diagonal_factor,
                self.heuristic_scale,
                int(start[0]) * width + int(start[1]),
                int(goal[0]) * width + int(goal[1]),
                self._g,
                self._parent,
                self._state,
                self._generation,
                self._queue,
            )
            if not math.isfinite(cost):
                return math.inf, np.empty((0, 2), dtype=np.int64), int(expanded)
            cells = astar.trace_back(self._parent, int(goal[0]) * width + int(goal[1]), width)
        return float(cost), cells, int(expanded)

    def path_cost(self, costs: np.ndarray, cells: np.ndarray) -> float:
        """Cost of an 8-connected cell path under this planner's model (inf if it enters an impassable cell)."""
        if len(cells) < 2:
            return 0.0
        steps = np.abs(np.diff(cells, axis=0))
        if (steps.max(axis=1) != 1).any():
            raise ConfigError("path_cost needs a path of 8-connected neighbouring cells")
        factor = np.where((steps == 1).all(axis=1), self.params.diagonal_factor, 1.0)
        entered = self.weights[costs[cells[1:, 0], cells[1:, 1]]]
        return float(np.sum(factor * entered))

    # ---------------------------------------------------------------- internals
    def _ensure_work(self, height: int, width: int) -> None:
        if self._shape != (height, width):
            size = height * width
            self._g = np.empty(size, dtype=np.float64)
            self._parent = np.empty(size, dtype=np.int32)
            self._state = np.zeros(size, dtype=np.uint32)
            self._shape = (height, width)
            self._generation = 0
        # each query owns two fresh stamps (open, closed); 0 is never used; a search that grows its queue
        # takes 2 more per try (a few at most: the arrays double)
        self._generation += 2
        if self._generation >= 2**32 - 256:
            self._state.fill(0)
            self._generation = 2

    def _nearest_passable(self, costs: np.ndarray, geometry: CostmapGeometry, x: float, y: float) -> Optional[Cell]:
        tolerance = self.params.goal_tolerance
        if tolerance <= 0.0:
            return None
        reach = math.ceil(tolerance / geometry.resolution) + 1
        row, col = geometry.world_to_cell(x, y)
        r0, r1 = max(0, row - reach), min(geometry.height, row + reach + 1)
        c0, c1 = max(0, col - reach), min(geometry.width, col + reach + 1)
        window = costs[r0:r1, c0:c1]
        rows, cols = np.mgrid[r0:r1, c0:c1]
        xs, ys = geometry.cells_to_world(rows, cols)
        dist = np.hypot(xs - x, ys - y)
        ok = np.isfinite(self.weights[window]) & (dist <= tolerance)
        if not ok.any():
            return None
        # nearest first, then cheapest
        order = np.lexsort((window[ok], dist[ok]))
        best = order[0]
        return Cell(int(rows[ok][best]), int(cols[ok][best]))

    def _to_world(
        self,
        *,
        costs: np.ndarray,
        geometry: CostmapGeometry,
        cells: np.ndarray,
        start: Sequence[float],
        goal: Sequence[float],
        goal_moved: bool,
    ) -> np.ndarray:
        keep = cells
        if self.params.smooth and len(cells) > 2:
            index = astar.shortcut(
                costs, self.weights, self.params.diagonal_factor, cells, float(self.params.smoothing_slack)
            )
            keep = cells[index]
        if self.params.simplify and len(keep) > 2:
            keep = keep[_corner_indices(keep)]
        if len(keep) == 1:  # start and goal in one cell: still two poses
            keep = np.concatenate([keep, keep])
        xs, ys = geometry.cells_to_world(keep[:, 0], keep[:, 1])
        points = np.stack([xs, ys], axis=1)
        points[0] = (start[0], start[1])
        if not goal_moved:
            points[-1] = (goal[0], goal[1])
        delta = np.diff(points, axis=0)
        yaw = np.empty(len(points))
        yaw[:-1] = np.arctan2(delta[:, 1], delta[:, 0])
        if len(goal) >= 3:
            yaw[-1] = float(goal[2])
        else:
            yaw[-1] = yaw[-2]
        still = (delta[:, 0] == 0.0) & (delta[:, 1] == 0.0)
        if still.any():  # zero-length segment (start == goal): face the final heading
            yaw[:-1][still] = yaw[-1]
        return np.column_stack([points, yaw])


def _check_request(
    costs: np.ndarray, geometry: CostmapGeometry, start: Sequence[float], goal: Sequence[float]
) -> Optional[PlanResult]:
    """The failure for a malformed request (bad array, NaN, off the map), or None."""
    if costs.dtype != np.uint8 or costs.shape != geometry.shape:
        return PlanResult(
            PlanStatus.INVALID_INPUT,
            f"costs must be uint8 of shape {geometry.shape}, got {costs.dtype} {costs.shape}",
        )
    bad = _bad_pose(start, "start") or _bad_pose(goal, "goal")
    if bad:
        return PlanResult(PlanStatus.INVALID_INPUT, bad)
    start_cell = geometry.world_to_cell(start[0], start[1])
    goal_cell = geometry.world_to_cell(goal[0], goal[1])
    for name, point, cell in (("start", start, start_cell), ("goal", goal, goal_cell)):
        if not geometry.in_bounds(cell):
            return PlanResult(
                PlanStatus.OUT_OF_MAP,
                f"{name} ({point[0]:.3f}, {point[1]:.3f}) is outside the costmap "
                f"(x {geometry.origin_x:.3f}..{geometry.origin_x + geometry.width * geometry.resolution:.3f}, "
                f"y {geometry.origin_y:.3f}..{geometry.origin_y + geometry.height * geometry.resolution:.3f})",
            )
    return None


def _corner_indices(cells: np.ndarray) -> np.ndarray:
    """Indices of the first, last and every cell where the direction of travel changes."""
    steps = np.diff(cells, axis=0)
    turn = np.any(steps[1:] != steps[:-1], axis=1)
    return np.concatenate([[0], np.flatnonzero(turn) + 1, [len(cells) - 1]])


def _bad_pose(pose: Sequence[float], name: str) -> str:
    try:
        values = [float(v) for v in pose]
    except (TypeError, ValueError):
        return f"{name} must be numbers (x, y[, yaw]), got {pose!r}"
    if len(values) not in (2, 3):
        return f"{name} must be (x, y) or (x, y, yaw), got {len(values)} values"
    if not all(math.isfinite(v) for v in values):
        return f"{name} has a non-finite value: {pose!r}"
    return ""
