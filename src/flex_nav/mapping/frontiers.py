"""Frontier exploration on an occupancy grid: where the known free space meets the unknown, which of those places
the robot can reach, and which to visit next. numpy and OpenCV, plus the global planner's compiled search; no ROS.

Values as in nav_msgs/OccupancyGrid (:class:`~flex_nav.nav.costmap.grid_map.GridMap`): -1 unknown, 0..100 [%].

- **free** cells hold 0..``FREE_MAX`` (19, map_server's free_thresh); every other known value (20..100) is an
  **obstacle**: a cell not known to be free is never driven through, and the robot keeps its distance from it.
- The robot's **footprint** (the disk of ``robot_radius_m`` around its position, at least its own cell) counts as
  free where it is unknown: the robot stands there (in a fresh map a lidar's minimum range leaves it unknown).
- A **frontier cell** is a free cell with an unknown cell among its 8 neighbours (cells outside the grid are not
  unknown: a mapper grows its grid where it sees more). A **frontier** is an 8-connected cluster of them; its
  **size** [m] is its cell count times the resolution (the length of a one-cell-wide frontier along a grid axis;
  a diagonal one counts 1/sqrt(2) of its length). Frontiers smaller than ``min_frontier_size_m`` are dropped
  (noise, gaps between the rays of a scan).
- **Traversable** cells are free cells whose centre lies at least ``robot_radius_m`` from the centre of every
  obstacle cell (exact Euclidean distance transform); unknown cells are not traversable. Free cells of the
  footprint are traversable whatever their clearance, so a robot standing close to a wall can leave it (as the
  planner's ``start_escape``).
- **Reachability** and **path length**: Dijkstra's wavefront from the robot's cell over traversable cells,
  8-connected with steps of 1 and sqrt(2) cells (:func:`wavefront`). A path length is at least the straight-line
  distance and at most about 8 % longer than the shortest path in the plane.
- Each frontier's **goal** is, among its cells and their 8 neighbours, the reached cell closest to the frontier's
  centroid (ties: the shorter path), facing the unknown: the heading is the mean direction from the goal to the
  unknown cells within ``VIEW_RADIUS_CELLS`` (or ``robot_radius_m``, if larger) of it. A frontier without a
  reached cell there is **unreachable**.
- **Cost** of a frontier: ``path_length_m - size_weight * size_m``; the lowest cost is visited first, so a near
  frontier goes first and a large one is worth ``size_weight`` metres of driving per metre of frontier.
  :func:`choose_frontier` takes the cheapest one whose goal is neither within ``failed_goal_radius_m`` of a goal
  that failed before nor closer to the robot than ``min_goal_distance_m`` along the path (the robot stands at a
  frontier it cannot resolve: going there again would change nothing).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import cv2
import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.localization.free_space import FREE_MAX
from flex_nav.nav.costmap.costmap_grid import LETHAL
from flex_nav.nav.costmap.grid_map import UNKNOWN, GridMap
from flex_nav.nav.planar import Pose2D
from flex_nav.nav.planning import astar

_OWNER = "frontiers"  # in the messages of FrontierParams' checks
VIEW_RADIUS_CELLS = 3  # [cells] a goal faces the unknown cells this close (at least; robot_radius_m if larger)
_EIGHT = np.ones((3, 3), dtype=np.uint8)  # the 8-neighbourhood (and the cell itself) as a morphology kernel
_NO_GOAL = -1  # a flat index no cell has: the search never stops early, it reaches every cell it can


@dataclass(frozen=True)
class FrontierParams:
    """What :func:`find_frontiers` and :func:`choose_frontier` need; validated when made (ConfigError)."""

    robot_radius_m: float = 0.2  # [m] clearance from obstacle cells; also the footprint's radius
    min_frontier_size_m: float = 0.3  # [m] smaller frontiers are dropped
    size_weight: float = 1.0  # [m/m] metres of path a metre of frontier is worth (cost = path - weight * size)
    failed_goal_radius_m: float = 0.5  # [m] a frontier whose goal is this close to a failed goal is skipped
    min_goal_distance_m: float = 0.4  # [m] a frontier whose goal is a shorter path away is skipped
    view_distance_m: float = 0.0  # [m] stop this much path short of the frontier where it stays in sight (0: at it)

    def __post_init__(self) -> None:
        validation.number(_OWNER, "robot_radius_m", self.robot_radius_m, minimum=0.0, unit="[m]")
        validation.number(_OWNER, "min_frontier_size_m", self.min_frontier_size_m, minimum=0.0, unit="[m]")
        validation.number(_OWNER, "size_weight", self.size_weight, minimum=0.0, unit="[m/m]")
        validation.number(_OWNER, "failed_goal_radius_m", self.failed_goal_radius_m, minimum=0.0, unit="[m]")
        validation.number(_OWNER, "min_goal_distance_m", self.min_goal_distance_m, minimum=0.0, unit="[m]")
        validation.number(_OWNER, "view_distance_m", self.view_distance_m, minimum=0.0, unit="[m]")


@dataclass(frozen=True)
class Frontier:
    """One reachable frontier: where to go to see it and what it is worth."""

    goal: Pose2D  # (x [m], y [m], yaw [rad]) in the map frame: the goal cell's centre, facing the unknown
    centroid: Tuple[float, float]  # (x [m], y [m]) of the frontier's cells
    size_m: float  # [m] cell count times the resolution
    path_length_m: float  # [m] wavefront path from the robot to the goal
    cell_count: int  # frontier cells in the cluster
    cost: float  # [m] path_length_m - size_weight * size_m (lower goes first)


class SearchStatus(enum.Enum):
    """Whether :func:`find_frontiers` could search at all (its ``reason`` says why not)."""

    OK = "ok"
    OUTSIDE_MAP = "outside map"  # the robot's position is not on the grid
    START_BLOCKED = "start blocked"  # no traversable cell next to the robot's cell (walled in, or on a bad pose)


@dataclass(frozen=True)
class FrontierSearch:
    """The result of one search: the reachable frontiers, cheapest first, and what was left out."""

    status: SearchStatus
    reason: str = ""
    frontiers: Tuple[Frontier, ...] = ()  # reachable, by cost (then path length)
    unreachable: int = 0  # frontiers large enough but without a reached goal cell
    too_small: int = 0  # clusters of frontier cells smaller than min_frontier_size_m

    @property
    def ok(self) -> bool:
        return self.status is SearchStatus.OK


@dataclass(frozen=True)
class FrontierChoice:
    """The frontier to visit next (None: none is left) and how many were passed over, and why."""

    frontier: Optional[Frontier]
    skipped_failed: int = 0  # goal within failed_goal_radius_m of a failed goal
    skipped_near: int = 0  # goal closer than min_goal_distance_m along the path


def find_frontiers(grid: GridMap, robot_xy: Tuple[float, float], params: FrontierParams) -> FrontierSearch:
    """The reachable frontiers of ``grid`` seen from the robot at ``robot_xy`` (x [m], y [m] in the map frame).

    ConfigError for a robot position that is not finite or a ``grid`` that is not a GridMap; a robot off the grid
    or without a traversable cell next to it is a status (the search cannot say anything about the frontiers then:
    never read it as "no frontier left").
    """
    if not isinstance(grid, GridMap):
        raise ConfigError(f"{_OWNER}: the map must be a GridMap, got {type(grid).__name__}")
    if len(robot_xy) != 2 or not all(isinstance(v, (int, float)) and math.isfinite(v) for v in robot_xy):
        raise ConfigError(f"{_OWNER}: the robot position must be finite (x [m], y [m]), got {robot_xy!r}")
    start = grid.world_to_cell(float(robot_xy[0]), float(robot_xy[1]))
    if not grid.in_bounds(start):
        return FrontierSearch(
            SearchStatus.OUTSIDE_MAP,
            f"the robot at ({robot_xy[0]:.2f}, {robot_xy[1]:.2f}) is outside the map "
            f"({grid.width} x {grid.height} cells of {grid.resolution:g} m from ({grid.origin[0]:.2f}, "
            f"{grid.origin[1]:.2f}))",
        )
    radius_cells = params.robot_radius_m / grid.resolution
    footprint = _disk_mask(grid.height, grid.width, start, radius_cells)
    occupancy = grid.occupancy
    unknown = (occupancy == UNKNOWN) & ~footprint
    free = ((occupancy >= 0) & (occupancy <= FREE_MAX)) | (footprint & (occupancy == UNKNOWN))
    obstacle = ~free & ~unknown
    clearance = cv2.distanceTransform((~obstacle).view(np.uint8), cv2.DIST_L2, cv2.DIST_MASK_PRECISE)
    traversable = free & ((clearance >= radius_cells - 1e-6) | footprint)
    distance = wavefront(traversable, (int(start[0]), int(start[1])))
    if int(np.count_nonzero(np.isfinite(distance))) <= 1:
        return FrontierSearch(
            SearchStatus.START_BLOCKED,
            f"no traversable cell next to the robot's cell {tuple(start)} (obstacles closer than "
            f"robot_radius_m {params.robot_radius_m:g} m all around)",
        )
    near_unknown = cv2.dilate(unknown.view(np.uint8), _EIGHT) > 0
    return _cluster(grid, free & near_unknown, unknown, distance, params=params,
                    view_radius=max(float(VIEW_RADIUS_CELLS), radius_cells), obstacle=obstacle)


def choose_frontier(
    frontiers: Sequence[Frontier], failed_goals: Sequence[Tuple[float, float]], params: FrontierParams
) -> FrontierChoice:
    """The cheapest of ``frontiers`` (cheapest first, as :func:`find_frontiers` orders them) whose goal is not within
    ``failed_goal_radius_m`` of one of ``failed_goals`` ((x [m], y [m])) and not nearer than ``min_goal_distance_m``."""
    failed = np.asarray(failed_goals, dtype=np.float64).reshape(-1, 2)
    skipped_failed = skipped_near = 0
    for frontier in frontiers:
        x, y, _ = frontier.goal
        if failed.size and float(np.min(np.hypot(failed[:, 0] - x, failed[:, 1] - y))) <= params.failed_goal_radius_m:
            skipped_failed += 1
        elif frontier.path_length_m < params.min_goal_distance_m:
            skipped_near += 1
        else:
            return FrontierChoice(frontier, skipped_failed, skipped_near)
    return FrontierChoice(None, skipped_failed, skipped_near)


def wavefront(passable: np.ndarray, start: Tuple[int, int]) -> np.ndarray:
    """Path lengths [cells] from ``start`` (row, col) to every cell reached through ``passable`` cells (bool (H, W)),
    8-connected with steps of 1 and sqrt(2); inf where not reached. The start itself need not be passable.

    Dijkstra's algorithm: the planner's A* kernel with a zero heuristic and a goal no cell has, so it expands every
    cell it can reach; each cell is then closed with its shortest path length.
    """
    height, width = passable.shape
    costs = np.where(passable, 0, LETHAL).astype(np.uint8).reshape(-1)
    weights = np.full(256, np.inf)
    weights[0] = 1.0
    g = np.empty(height * width, dtype=np.float64)
    parent = np.empty(height * width, dtype=np.int32)
    state = np.zeros(height * width, dtype=np.uint32)
    # open cells are marked 2, closed ones 3 (0: never seen); a search that grows its queue takes 2 more
    _, _, generation = astar.search(
        costs, width, weights, math.sqrt(2.0), 0.0, start[0] * width + start[1], _NO_GOAL,
        g, parent, state, 2, astar.QueueStorage(),
    )  # fmt: skip
    distance = np.full(height * width, np.inf)
    closed = state == generation + 1
    distance[closed] = g[closed]
    return distance.reshape(height, width)


def _cluster(
    grid: GridMap,
    frontier_cells: np.ndarray,
    unknown: np.ndarray,
    distance: np.ndarray,
    *,
    params: FrontierParams,
    view_radius: float,
    obstacle: np.ndarray,
) -> FrontierSearch:
    """The frontiers of the ``frontier_cells`` mask: clusters, sizes, goals, costs."""
    count, labels, stats, centroids = cv2.connectedComponentsWithStats(frontier_cells.view(np.uint8), connectivity=8)
    found = []
    unreachable = too_small = 0
    for label in range(1, count):  # 0 is the background
        cells = int(stats[label, cv2.CC_STAT_AREA])
        size_m = cells * grid.resolution
        if size_m < params.min_frontier_size_m - 1e-9:
            too_small += 1
            continue
        centre_col, centre_row = float(centroids[label, 0]), float(centroids[label, 1])
        goal = _goal_cell(labels, label, stats[label], distance, (centre_row, centre_col))
        if goal is None:
            unreachable += 1
            continue
        yaw = _facing_unknown(grid, unknown, goal, view_radius)
        keep_m = max(float(distance[goal]) * grid.resolution - params.view_distance_m, params.min_goal_distance_m)
        viewpoint = _viewpoint(distance, obstacle, goal, keep_m / grid.resolution)
        if viewpoint != goal:  # face the frontier from there
            yaw = math.atan2(goal[0] - viewpoint[0], goal[1] - viewpoint[1]) + grid.origin[2]
            yaw = math.atan2(math.sin(yaw), math.cos(yaw))
            goal = viewpoint
        x, y = grid.cell_to_world(*goal)
        path_m = float(distance[goal]) * grid.resolution
        found.append(Frontier(
            goal=(x, y, yaw),
            centroid=grid.grid_to_world(centre_col + 0.5, centre_row + 0.5),
            size_m=size_m,
            path_length_m=path_m,
            cell_count=cells,
            cost=path_m - params.size_weight * size_m,
        ))
    found.sort(key=lambda f: (f.cost, f.path_length_m))
    return FrontierSearch(SearchStatus.OK, "", tuple(found), unreachable, too_small)


def _goal_cell(
    labels: np.ndarray, label: int, stat: np.ndarray, distance: np.ndarray, centre: Tuple[float, float]
) -> Optional[Tuple[int, int]]:
    """The reached cell among the cluster's cells and their 8 neighbours closest to ``centre`` (row, col), ties to
    the shorter path; None if none is reached."""
    height, width = labels.shape
    row0 = max(0, int(stat[cv2.CC_STAT_TOP]) - 1)
    col0 = max(0, int(stat[cv2.CC_STAT_LEFT]) - 1)
    row1 = min(height, int(stat[cv2.CC_STAT_TOP] + stat[cv2.CC_STAT_HEIGHT]) + 1)
    col1 = min(width, int(stat[cv2.CC_STAT_LEFT] + stat[cv2.CC_STAT_WIDTH]) + 1)
    near = cv2.dilate((labels[row0:row1, col0:col1] == label).view(np.uint8), _EIGHT) > 0
    window = distance[row0:row1, col0:col1]
    rows, cols = np.nonzero(near & np.isfinite(window))
    if rows.size == 0:
        return None
    off_centre = np.hypot(rows + row0 - centre[0], cols + col0 - centre[1])
    best = int(np.lexsort((window[rows, cols], off_centre))[0])
    return int(rows[best]) + row0, int(cols[best]) + col0


def _viewpoint(distance: np.ndarray, obstacle: np.ndarray, goal: Tuple[int, int], keep: float) -> Tuple[int, int]:
    """The cell on the shortest way back from ``goal`` towards the robot (down the wavefront ``distance``) where the
    path left is about ``keep`` [cells] long, or the last one before that from which ``goal`` is still in sight
    (no obstacle cell on the straight line); ``goal`` itself when it is no farther than ``keep``."""
    height, width = distance.shape
    cell = goal
    while float(distance[cell]) > keep:
        row, col = cell
        best = cell
        for d_row in (-1, 0, 1):
            for d_col in (-1, 0, 1):
                r, c = row + d_row, col + d_col
                if 0 <= r < height and 0 <= c < width and distance[r, c] < distance[best]:
                    best = (r, c)
        if best == cell or not _in_sight(obstacle, best, goal):
            break
        cell = best
    return cell


def _in_sight(obstacle: np.ndarray, a: Tuple[int, int], b: Tuple[int, int]) -> bool:
    """True when no obstacle cell lies on the segment between the centres of cells ``a`` and ``b``."""
    steps = max(2, 2 * max(abs(a[0] - b[0]), abs(a[1] - b[1])) + 1)
    rows = np.rint(np.linspace(a[0], b[0], steps)).astype(np.int64)
    cols = np.rint(np.linspace(a[1], b[1], steps)).astype(np.int64)
    return not bool(np.any(obstacle[rows, cols]))


def _facing_unknown(grid: GridMap, unknown: np.ndarray, goal: Tuple[int, int], radius: float) -> float:
    """[rad] map-frame heading from the goal cell towards the unknown cells within ``radius`` [cells] (the mean of
    the unit vectors to them); the grid's +x axis if they surround it evenly."""
    reach = math.ceil(radius)
    row0, col0 = max(0, goal[0] - reach), max(0, goal[1] - reach)
    rows, cols = np.nonzero(unknown[row0 : goal[0] + reach + 1, col0 : goal[1] + reach + 1])
    d_row = (rows + row0 - goal[0]).astype(np.float64)
    d_col = (cols + col0 - goal[1]).astype(np.float64)
    length = np.hypot(d_row, d_col)
    keep = (length > 0.0) & (length <= radius)
    sum_row = float(np.sum(d_row[keep] / length[keep]))
    sum_col = float(np.sum(d_col[keep] / length[keep]))
    local = math.atan2(sum_row, sum_col) if abs(sum_row) + abs(sum_col) > 1e-9 else 0.0
    yaw = local + grid.origin[2]
    return math.atan2(math.sin(yaw), math.cos(yaw))


def _disk_mask(height: int, width: int, centre: Tuple[int, int], radius_cells: float) -> np.ndarray:
    """bool (height, width): the cells whose centre lies within ``radius_cells`` of cell ``centre``'s (at least it)."""
    reach = math.floor(radius_cells)
    mask = np.zeros((height, width), dtype=bool)
    row0, row1 = max(0, centre[0] - reach), min(height, centre[0] + reach + 1)
    col0, col1 = max(0, centre[1] - reach), min(width, centre[1] + reach + 1)
    rows, cols = np.ogrid[row0:row1, col0:col1]
    mask[row0:row1, col0:col1] = (rows - centre[0]) ** 2 + (cols - centre[1]) ** 2 <= radius_cells**2 + 1e-9
    return mask


__all__ = [
    "VIEW_RADIUS_CELLS",
    "Frontier",
    "FrontierChoice",
    "FrontierParams",
    "FrontierSearch",
    "SearchStatus",
    "choose_frontier",
    "find_frontiers",
    "wavefront",
]
