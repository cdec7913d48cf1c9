"""The best any robot keeping to its route could do in a scenario world: the earliest arrival of a speed profile
along the route that keeps a distance from every scripted person while it moves, knowing where they will walk.

A yardstick for the scenario table, not a navigator: the people's future comes from the world file (their
waypoints, speeds and events, as :mod:`flex_nav.apps.eval.metrics` replays them), which no robot knows. The
route (by default the straight line from the world's start to its goal) is cut into cells of ``speed_mps *
step_s / 3`` [m]; every ``step_s`` [s] the robot stands or drives one, two or three cells forward (a third, two
thirds or all of ``speed_mps``; it changes speed at once, so the bound is a little optimistic). Moving, the gap
(centre distance less both radii) to every person must be at least ``moving_gap_m`` [m] at every cell it
passes, at both ends of the step (the issue-28 metric: the closest approach while moving); standing, at least
``standing_gap_m`` [m] after the step (0: a person may pass a standing robot as close as they like, but not walk
through it). The set of cells reachable at each step is grown until the goal's cell is in it.

    python -m flex_nav.apps.eval.arrival_bound --world test/data/issue28/variants/h6_people_crossing.yaml

prints the earliest arrival [s] after the goal is sent (scenario_run sends it ``WORLD_LEAD_S`` after the
world's script starts), or how far along the route any admissible profile gets in ``limit_s``. Issue 28 used it to
show that h6's 0.3 m while moving is not ruled out by the walkers' geometry (docs/push_or_avoid.md).
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass
from typing import Any, List, Optional, Sequence, Tuple

import cv2
import numpy as np

from flex_nav.apps.eval.metrics import ROBOT_RADIUS_M, person_position, walking_intervals
from flex_nav.exceptions import ConfigError, FlexNavError
from flex_nav.nav.path import as_path, cumulative_lengths, path_length
from flex_nav.validation import number

MOVES = 3  # a step drives at most this many cells
OCCUPIED_THRESHOLD = 50  # occupancy above this is a wall


@dataclass(frozen=True)
class ArrivalBound:
    """``arrival_s`` [s] after the start (None: not within the limit), ``farthest_m`` [m] along the route that
    some admissible profile reached, and when it arrived one earliest profile (``profile_m``, every ``step_s``)."""

    arrival_s: Optional[float]
    farthest_m: float
    route_m: float
    profile_m: Tuple[float, ...] = ()  # [m] along the route at every step from the start (arrived: one such)

    def line(self, moving_gap_m: float) -> str:
        if self.arrival_s is not None:
            return (f"earliest arrival {self.arrival_s:.1f} s after the goal ({self.route_m:.2f} m route, "
                    f">= {moving_gap_m:g} m from every person while moving)")
        return (f"no speed profile keeps {moving_gap_m:g} m while moving to the goal: the farthest reachable is "
                f"{self.farthest_m:.2f} m of {self.route_m:.2f} m")


def earliest_arrival(world: Any, route: np.ndarray, *, start_world_s: float, moving_gap_m: float = 0.3,
                     standing_gap_m: float = 0.0, speed_mps: float = 0.26, robot_radius_m: float = ROBOT_RADIUS_M,
                     step_s: float = 0.1, limit_s: float = 150.0) -> ArrivalBound:
    """The search of the module docstring along ``route`` ((N >= 2, 2) [m]) for ``world``'s people, the robot
    starting at the first point at ``start_world_s`` [s] of the world's script."""
    for name, value in (("speed_mps", speed_mps), ("step_s", step_s), ("limit_s", limit_s)):
        number("arrival bound", name, value, positive=True)
    number("arrival bound", "robot_radius_m", robot_radius_m, minimum=0.0, unit="[m]")
    number("arrival bound", "standing_gap_m", standing_gap_m, minimum=0.0, unit="[m]")
    number("arrival bound", "moving_gap_m", moving_gap_m, minimum=0.0, unit="[m]")
    route = checked_route(route)
    length_m = path_length(route)
    arc = np.append(np.arange(0.0, length_m, speed_mps * step_s / MOVES), length_m)
    cells = _along(route, arc)
    intervals = [walking_intervals(p, world.events) for p in world.people]

    def gaps(world_s: float) -> np.ndarray:
        gap = np.full(len(cells), math.inf)
        for person, walking in zip(world.people, intervals):
            x, y = person_position(person, walking, world_s)
            gap = np.minimum(gap, np.hypot(cells[:, 0] - x, cells[:, 1] - y) - person.radius - robot_radius_m)
        return gap

    reached = np.zeros(len(cells), dtype=bool)
    reached[0] = True
    farthest_m = 0.0
    came_by: List[np.ndarray] = []  # per step: the move (cells) that reached each cell first (-1: not reached)
    now_gap = gaps(start_world_s)
    for k in range(1, math.ceil(limit_s / step_s) + 1):
        next_gap = gaps(start_world_s + k * step_s)
        move_into = np.where(reached & (next_gap >= standing_gap_m), 0, -1)
        passing = now_gap >= moving_gap_m  # cells the robot may be at while moving, at the step's start
        for move in range(1, MOVES + 1):
            # from cell i to i + move: every cell i..i + move clear at the start, the last one also at the end
            clear = passing[:len(cells) - move].copy()
            for between in range(1, move + 1):
                clear &= passing[between:len(cells) - move + between]
            arrive = reached[:-move] & clear & (next_gap[move:] >= moving_gap_m)
            move_into[move:] = np.where(arrive & (move_into[move:] < 0), move, move_into[move:])
        came_by.append(move_into)
        reached, now_gap = move_into >= 0, next_gap
        if reached[-1]:
            return ArrivalBound(k * step_s, length_m, length_m, _profile(came_by, arc, len(cells) - 1))
        if not reached.any():  # a person walks through every place the robot could be
            break
        farthest_m = max(farthest_m, float(arc[np.flatnonzero(reached).max()]))
    return ArrivalBound(None, farthest_m, length_m)


def checked_route(route: object) -> np.ndarray:
    """``route`` as (N >= 2, 2) points [m]; ConfigError naming what is wrong otherwise."""
    points = as_path(route, what="arrival bound: route")[:, :2]
    if len(points) < 2:
        raise ConfigError(f"arrival bound: route needs at least 2 points, got {len(points)}")
    return points


def _along(route: np.ndarray, arc: np.ndarray) -> np.ndarray:
    """(K, 2) points [m] of ``route`` at arc lengths ``arc`` (K,) [m]."""
    lengths = cumulative_lengths(route)
    return np.stack((np.interp(arc, lengths, route[:, 0]), np.interp(arc, lengths, route[:, 1])), axis=1)


def _profile(came_by: Sequence[np.ndarray], arc: np.ndarray, goal: int) -> Tuple[float, ...]:
    """The arc lengths [m] of one earliest profile at every step (the start first), followed back from ``goal``."""
    cell, cells = goal, [goal]
    for moves in reversed(came_by):
        cell -= int(moves[cell])
        cells.append(cell)
    return tuple(float(arc[c]) for c in reversed(cells))


def _route(text: Optional[str], world: Any) -> np.ndarray:
    if text:
        try:
            return np.array([[float(v) for v in point.split(",")] for point in text.split(";")])
        except ValueError as err:
            raise ConfigError(f"arrival bound: --route must be 'x,y;x,y;...' [m], got {text!r}") from err
    start = world.spawns[0].pose if world.spawns else world.goals.get("start")
    goal = world.goals.get("goal")
    if start is None or goal is None:
        raise ConfigError(f"arrival bound: {world.source} has no start (robots or goals.start) and goals.goal: "
                          "give --route")
    return np.array([start[:2], goal[:2]], dtype=np.float64)


def check_route(grid: Any, route: np.ndarray, clearance_m: float) -> None:
    """ConfigError when a point of ``route`` ((N, 2) [m], sampled every half map cell) comes within
    ``clearance_m`` [m] of an occupied cell of ``grid`` (a GridMap: the world's static map); outside the map
    counts as free."""
    res = grid.resolution
    points = _along(route, np.arange(0.0, path_length(route) + 1e-9, res / 2.0))
    free = (grid.occupancy <= OCCUPIED_THRESHOLD).astype(np.uint8)
    # from each cell's centre to the nearest occupied centre, less half a cell: to the occupied square's edge
    to_wall_m = cv2.distanceTransform(free, cv2.DIST_L2, cv2.DIST_MASK_PRECISE) * res - res / 2.0
    cols = np.floor((points[:, 0] - grid.origin[0]) / res).astype(int)
    rows = np.floor((points[:, 1] - grid.origin[1]) / res).astype(int)
    inside = (rows >= 0) & (rows < free.shape[0]) & (cols >= 0) & (cols < free.shape[1])
    near = np.flatnonzero(inside)[to_wall_m[rows[inside], cols[inside]] < clearance_m]
    if near.size:
        x, y = points[near[0]]
        raise ConfigError(f"arrival bound: the route passes within {clearance_m:g} m of a wall at ({x:.2f}, "
                          f"{y:.2f}) m: give --route around it")


def main(argv: Optional[Sequence[str]] = None) -> int:
    from flex_nav.apps.scenario_run import WORLD_LEAD_S  # noqa: PLC0415  (when scenario_run sends the goal)
    from flex_nav_sim.static_map import static_map  # noqa: PLC0415
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    parser = argparse.ArgumentParser(prog="python -m flex_nav.apps.eval.arrival_bound",
                                     description=__doc__.split("\n")[0])
    parser.add_argument("--world", required=True, help="world name (sim/worlds) or path")
    parser.add_argument("--route", help="'x,y;x,y;...' [m] (default: the world's start to its goal, straight)")
    parser.add_argument("--moving-gap", type=float, default=0.3, help="[m] kept from every person while moving")
    parser.add_argument("--standing-gap", type=float, default=0.0, help="[m] kept from every person standing")
    parser.add_argument("--speed", type=float, default=0.26, help="[m/s] top speed along the route")
    parser.add_argument("--start-at", type=float, default=WORLD_LEAD_S,
                        help="[s] of the world's script when the robot starts (scenario_run: %(default)s)")
    parser.add_argument("--limit", type=float, default=150.0, help="[s] give up after this long")
    args = parser.parse_args(argv)
    try:
        world = load_world(args.world)
        route = checked_route(_route(args.route, world))
        check_route(static_map(world), route, ROBOT_RADIUS_M)
        result = earliest_arrival(world, route, start_world_s=args.start_at,
                                  moving_gap_m=args.moving_gap, standing_gap_m=args.standing_gap,
                                  speed_mps=args.speed, limit_s=args.limit)
    except FlexNavError as err:
        print(err, file=sys.stderr)
        return 2
    print(result.line(args.moving_gap))
    return 0 if result.arrival_s is not None else 1


if __name__ == "__main__":
    sys.exit(main())

