"""flex_nav.mapping.frontiers on synthetic grids: where the frontiers are, how large, which are reachable by a robot
of a given radius, where their goals lie and which way they face, the documented cost and the choice."""

from __future__ import annotations

import math
from typing import Tuple

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.localization.free_space import FREE_MAX
from flex_nav.mapping.frontiers import (
    Frontier,
    FrontierParams,
    SearchStatus,
    choose_frontier,
    find_frontiers,
    wavefront,
)
from flex_nav.nav.costmap.grid_map import FREE, OCCUPIED, UNKNOWN, GridMap

RES = 0.05  # [m/cell]
ROWS, COLS = 60, 80  # a 4 m x 3 m room


def room(known_cols: int = COLS) -> np.ndarray:
    """A walled room whose columns ``< known_cols`` are known (walls on the known part only), the rest unknown."""
    occ = np.full((ROWS, COLS), UNKNOWN, dtype=np.int8)
    occ[:, :known_cols] = FREE
    occ[0, :known_cols] = occ[-1, :known_cols] = OCCUPIED
    occ[:, 0] = OCCUPIED
    if known_cols == COLS:
        occ[:, -1] = OCCUPIED
    return occ


def cell_of(grid: GridMap, x: float, y: float) -> Tuple[int, int]:
    cell = grid.world_to_cell(x, y)
    return int(cell.row), int(cell.col)


def angle_between(a: float, b: float) -> float:
    return abs(math.atan2(math.sin(a - b), math.cos(a - b)))


# --- where the frontiers are ------------------------------------------------------------------------------------


def test_a_half_known_room_has_one_frontier_on_the_boundary_with_a_reachable_goal_facing_the_unknown():
    known = 40
    grid = GridMap(room(known), RES)
    robot = (1.0, 1.5)
    search = find_frontiers(grid, robot, FrontierParams(robot_radius_m=0.2, min_frontier_size_m=0.3))
    assert search.status is SearchStatus.OK, search.reason
    assert len(search.frontiers) == 1 and search.unreachable == 0 and search.too_small == 0
    frontier = search.frontiers[0]
    # the free cells of the last known column between the two walls
    assert frontier.cell_count == ROWS - 2
    assert frontier.size_m == pytest.approx((ROWS - 2) * RES)
    boundary_x = known * RES
    assert frontier.centroid[0] == pytest.approx(boundary_x - RES / 2)
    assert frontier.centroid[1] == pytest.approx(ROWS * RES / 2)
    x, y, yaw = frontier.goal
    row, col = cell_of(grid, x, y)
    assert grid.occupancy[row, col] <= FREE_MAX  # a known free cell
    assert boundary_x - 2 * RES <= x < boundary_x  # on the boundary (the cluster or next to it)
    assert abs(y - frontier.centroid[1]) <= RES  # the reachable cell closest to the centroid
    assert angle_between(yaw, 0.0) < math.radians(10)  # facing the unknown half (+x)
    start_x, start_y = grid.cell_to_world(*cell_of(grid, *robot))  # paths run between cell centres
    straight = math.hypot(x - start_x, y - start_y)
    assert straight - 1e-9 <= frontier.path_length_m <= 1.09 * straight
    assert frontier.cost == pytest.approx(frontier.path_length_m - 1.0 * frontier.size_m)


@pytest.mark.parametrize(
    ("unknown_side", "expected_yaw"),
    [("east", 0.0), ("west", math.pi), ("north", math.pi / 2), ("south", -math.pi / 2)],
)
@pytest.mark.parametrize("origin_yaw", [0.0, 0.5])
def test_the_goal_faces_the_unknown_side_in_the_map_frame(unknown_side, expected_yaw, origin_yaw):
    occ = np.full((60, 60), FREE, dtype=np.int8)
    half = {"east": (slice(None), slice(40, None)), "west": (slice(None), slice(None, 20)),
            "north": (slice(40, None), slice(None)), "south": (slice(None, 20), slice(None))}[unknown_side]
    occ[half] = UNKNOWN
    grid = GridMap(occ, RES, (1.0, -2.0, origin_yaw))
    centre = grid.cell_to_world(30, 30)
    search = find_frontiers(grid, centre, FrontierParams())
    assert len(search.frontiers) == 1
    assert angle_between(search.frontiers[0].goal[2], expected_yaw + origin_yaw) < math.radians(10)


def test_a_frontier_behind_a_gap_narrower_than_the_robot_is_unreachable():
    def scene(gap_cells: int) -> GridMap:
        occ = room(60)  # rooms A (west) and B (east of the wall), the unknown beyond B
        occ[:, 30] = OCCUPIED  # the wall between them, with a gap in its middle
        top = ROWS // 2 - gap_cells // 2
        occ[top : top + gap_cells, 30] = FREE
        return GridMap(occ, RES)

    params = FrontierParams(robot_radius_m=0.2)
    narrow = find_frontiers(scene(3), (0.7, 1.5), params)  # 0.15 m gap, a 0.4 m wide robot
    assert narrow.status is SearchStatus.OK
    assert narrow.frontiers == () and narrow.unreachable == 1
    wide = find_frontiers(scene(12), (0.7, 1.5), params)  # 0.6 m gap: it passes
    assert len(wide.frontiers) == 1 and wide.unreachable == 0
    assert wide.frontiers[0].goal[0] > 30 * RES  # beyond the wall
    small_robot = find_frontiers(scene(3), (0.7, 1.5), FrontierParams(robot_radius_m=0.05))
    assert len(small_robot.frontiers) == 1


def test_frontier_clusters_smaller_than_min_frontier_size_are_dropped():
    occ = room()
    side = 2  # a 2 x 2 cell patch nobody saw, in the middle of a known room
    occ[30 : 30 + side, 50 : 50 + side] = UNKNOWN
    ring = (side + 2) ** 2 - side**2  # its 8-neighbours: the frontier cells around it
    grid = GridMap(occ, RES)
    dropped = find_frontiers(grid, (1.0, 1.5), FrontierParams(min_frontier_size_m=(ring + 1) * RES))
    assert dropped.frontiers == () and dropped.too_small == 1
    kept = find_frontiers(grid, (1.0, 1.5), FrontierParams(min_frontier_size_m=ring * RES))
    assert len(kept.frontiers) == 1 and kept.too_small == 0
    assert kept.frontiers[0].cell_count == ring


def test_an_all_known_map_has_no_frontier():
    search = find_frontiers(GridMap(room(), RES), (1.0, 1.5), FrontierParams())
    assert search.status is SearchStatus.OK
    assert search.frontiers == () and search.unreachable == 0 and search.too_small == 0
    assert choose_frontier(search.frontiers, [], FrontierParams()).frontier is None


def test_values_above_free_max_are_obstacles_and_below_are_free():
    occ = room(40)
    occ[1:-1, 1:39] = FREE_MAX  # still free
    assert len(find_frontiers(GridMap(occ, RES), (1.0, 1.5), FrontierParams()).frontiers) == 1
    occ[1:-1, 25] = FREE_MAX + 1  # a wall across the room: the boundary is behind it
    walled = find_frontiers(GridMap(occ, RES), (1.0, 1.5), FrontierParams())
    assert walled.frontiers == () and walled.unreachable == 1


def test_a_robot_in_its_own_unknown_footprint_is_not_walled_in_nor_a_frontier():
    occ = room(40)
    grid = GridMap(occ, RES)
    row, col = cell_of(grid, 1.0, 1.5)
    rows, cols = np.ogrid[:ROWS, :COLS]
    occ[(rows - row) ** 2 + (cols - col) ** 2 <= 3**2] = UNKNOWN  # a lidar's minimum range leaves it unseen
    search = find_frontiers(GridMap(occ, RES), (1.0, 1.5), FrontierParams(robot_radius_m=0.2))
    assert search.status is SearchStatus.OK
    assert len(search.frontiers) == 1
    assert search.frontiers[0].goal[0] > 1.5  # the boundary's, not one around the robot


# --- cost and choice --------------------------------------------------------------------------------------------


def two_frontiers() -> GridMap:
    """A near short frontier (an opening in the west wall) and a far long one (the unknown east part)."""
    occ = room(70)
    occ[25:35, 0] = UNKNOWN  # 10 cells of the west wall nobody saw
    return GridMap(occ, RES)


def test_the_cost_is_path_length_minus_size_weight_times_size_and_the_cheapest_goes_first():
    grid = two_frontiers()
    robot = (0.6, 1.5)
    near_first = find_frontiers(grid, robot, FrontierParams(size_weight=0.0, robot_radius_m=0.1))
    assert len(near_first.frontiers) == 2
    near, far = near_first.frontiers
    assert near.path_length_m < far.path_length_m and near.size_m < far.size_m
    for f in near_first.frontiers:
        assert f.cost == pytest.approx(f.path_length_m)
    weight = 2.0 * (far.path_length_m - near.path_length_m) / (far.size_m - near.size_m)  # makes the large one cheaper
    large_first = find_frontiers(grid, robot, FrontierParams(size_weight=weight, robot_radius_m=0.1))
    assert [f.size_m for f in large_first.frontiers] == [far.size_m, near.size_m]
    for f in large_first.frontiers:
        assert f.cost == pytest.approx(f.path_length_m - weight * f.size_m)


def frontier_at(x: float, y: float, path_m: float) -> Frontier:
    return Frontier(goal=(x, y, 0.0), centroid=(x, y), size_m=1.0, path_length_m=path_m, cell_count=20,
                    cost=path_m - 1.0)


def test_choose_skips_frontiers_near_failed_goals_and_where_the_robot_stands():
    params = FrontierParams(failed_goal_radius_m=0.5, min_goal_distance_m=0.4)
    here, failed, good = frontier_at(0.1, 0.0, 0.1), frontier_at(2.0, 0.0, 2.0), frontier_at(3.0, 1.0, 3.2)
    choice = choose_frontier([here, failed, good], [(2.3, 0.2)], params)
    assert choice.frontier is good
    assert (choice.skipped_failed, choice.skipped_near) == (1, 1)
    assert choose_frontier([here, failed, good], [], params).frontier is failed
    assert choose_frontier([failed], [(2.3, 0.2)], params).frontier is None
    far_failure = choose_frontier([failed], [(2.6, 0.0)], params)  # 0.6 m from the goal: not the same one
    assert far_failure.frontier is failed


# --- the wavefront ------------------------------------------------------------------------------------------------


def test_wavefront_path_lengths_are_8_connected_and_stop_at_blocked_cells():
    passable = np.ones((20, 30), dtype=bool)
    passable[:, 15] = False  # a wall with one opening
    passable[10, 15] = True
    distance = wavefront(passable, (10, 2))
    assert distance[10, 2] == 0.0
    assert distance[10, 12] == pytest.approx(10.0)
    assert distance[4, 8] == pytest.approx(6 * math.sqrt(2.0))
    assert distance[10, 20] == pytest.approx(18.0)  # straight through the opening
    assert math.isinf(wavefront(~passable, (10, 2))[10, 12])  # only the wall is passable: nothing else is reached
    wider = np.ones((300, 300), dtype=bool)  # more open cells than the first queue holds: it grows
    assert wavefront(wider, (150, 150))[0, 0] == pytest.approx(150 * math.sqrt(2.0))


# --- the robot's position and the parameters ------------------------------------------------------------------------


def test_a_robot_off_the_map_or_walled_in_is_a_status_never_no_frontiers():
    grid = GridMap(room(40), RES)
    outside = find_frontiers(grid, (-1.0, 1.5), FrontierParams())
    assert outside.status is SearchStatus.OUTSIDE_MAP and not outside.ok
    assert "outside the map" in outside.reason
    occ = room(40)
    row, col = cell_of(grid, 1.0, 1.5)
    occ[row - 2 : row + 3, col - 2 : col + 3] = OCCUPIED
    occ[row, col] = FREE
    walled = find_frontiers(GridMap(occ, RES), (1.0, 1.5), FrontierParams(robot_radius_m=0.0))
    assert walled.status is SearchStatus.START_BLOCKED and "no traversable cell" in walled.reason


@pytest.mark.parametrize(
    ("name", "value"),
    [("robot_radius_m", -0.1), ("min_frontier_size_m", math.nan), ("size_weight", -1.0),
     ("failed_goal_radius_m", math.inf), ("min_goal_distance_m", True), ("robot_radius_m", "0.2")],
)
def test_bad_parameters_are_refused_naming_them(name, value):
    with pytest.raises(ConfigError, match=name):
        FrontierParams(**{name: value})


def test_bad_inputs_are_refused():
    grid = GridMap(room(40), RES)
    with pytest.raises(ConfigError, match="robot position"):
        find_frontiers(grid, (math.nan, 1.0), FrontierParams())
    with pytest.raises(ConfigError, match="GridMap"):
        find_frontiers(room(40), (1.0, 1.0), FrontierParams())  # type: ignore[arg-type]


# --- stopping short of a frontier, in sight of it ----------------------------------------------------------------


def test_view_distance_stops_short_of_the_frontier_along_the_way_and_faces_it():
    grid = GridMap(room(70), RES)  # the frontier at x = 3.5 m
    robot = (0.5, 1.5)
    at_it = find_frontiers(grid, robot, FrontierParams(robot_radius_m=0.2)).frontiers[0]
    short = find_frontiers(grid, robot, FrontierParams(robot_radius_m=0.2, view_distance_m=1.0)).frontiers[0]
    assert short.path_length_m == pytest.approx(at_it.path_length_m - 1.0, abs=2 * RES)
    assert short.goal[0] == pytest.approx(at_it.goal[0] - 1.0, abs=2 * RES)
    assert angle_between(short.goal[2], 0.0) < math.radians(10.0)  # facing the frontier, east
    assert short.cost == pytest.approx(short.path_length_m - short.size_m)


def test_view_distance_keeps_the_frontier_in_sight_around_a_corner():
    occ = room(70)
    occ[1:45, 40] = OCCUPIED  # a wall from the south, with a gap in the north: the way goes round its end
    grid = GridMap(occ, RES)
    robot = (0.5, 0.5)
    params = FrontierParams(robot_radius_m=0.2, view_distance_m=3.0)
    short = find_frontiers(grid, robot, params).frontiers[0]
    at_it = find_frontiers(grid, robot, FrontierParams(robot_radius_m=0.2)).frontiers[0]
    assert short.path_length_m > at_it.path_length_m - 3.0 + 0.5  # not walked back round the corner
    a, b = cell_of(grid, *short.goal[:2]), cell_of(grid, *at_it.goal[:2])
    samples = np.linspace(0.0, 1.0, 200)
    rows = np.rint(a[0] + samples * (b[0] - a[0])).astype(int)
    cols = np.rint(a[1] + samples * (b[1] - a[1])).astype(int)
    assert not np.any(occ[rows, cols] == OCCUPIED)  # the frontier's cell in sight from the goal


def test_view_distance_never_brings_a_goal_nearer_than_min_goal_distance():
    grid = GridMap(room(40), RES)  # the frontier at x = 2.0 m
    robot = (1.5, 1.5)
    params = FrontierParams(robot_radius_m=0.2, view_distance_m=5.0, min_goal_distance_m=0.4)
    frontier = find_frontiers(grid, robot, params).frontiers[0]
    assert frontier.path_length_m >= 0.4 - RES
    assert choose_frontier([frontier], [], params).frontier == frontier
