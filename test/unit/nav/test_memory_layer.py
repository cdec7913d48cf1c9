"""The obstacle memory layer: mark, decay, forget when the lidar sees the obstacle gone, operator clear, plans
around it (no ROS)."""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np
import pytest
from unit.perception.shape_synth import ranges_of

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import FREE, LETHAL, CostmapGeometry
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.costmap.inflation import InflationParams
from flex_nav.nav.costmap.layered import Costmap
from flex_nav.nav.costmap.memory_layer import (
    MemoryParams,
    ObstacleMemoryLayer,
    box_footprint,
    convex_footprint,
    ray_spans,
)
from flex_nav.nav.costmap.obstacle_layer import LaserScan, ObstacleLayerParams
from flex_nav.nav.planning.planner import GridPlanner

RES = 0.05  # [m]
BOX = box_footprint(3.0, 1.0, 0.5, 0.5)  # a heavy box on the straight way
MEMORY = MemoryParams(memory_s=300.0)
BEAMS = 720


def scan_of(sensor: Sequence[float], polygons: Sequence[np.ndarray]) -> LaserScan:
    """A 720-beam scan (no noise) from ``sensor`` (x, y) [m] in the costmap frame of the ``polygons``."""
    angles = -math.pi + 2.0 * math.pi * np.arange(BEAMS) / BEAMS
    ranges = ranges_of((sensor[0], sensor[1]), angles, polygons)
    return LaserScan(ranges, -math.pi, 2.0 * math.pi / BEAMS, 0.1, 12.0, sensor[0], sensor[1], 0.0)


def remembered(cm: Costmap) -> int:
    assert cm.memory_layer is not None
    return len(cm.memory_layer.obstacles)


def empty_costmap() -> Costmap:
    return Costmap(CostmapGeometry(120, 40, RES), obstacles=ObstacleLayerParams(), memory=MEMORY,
                   inflation=InflationParams(0.15, 0.3, 5.0))


def test_a_remembered_obstacle_is_lethal_where_its_footprint_is() -> None:
    cm = empty_costmap()
    entry = cm.remember_obstacle(BOX, now_s=10.0)
    cm.update()
    assert cm.cost_at(3.0, 1.0) == LETHAL and cm.cost_at(3.2, 0.8) == LETHAL  # centre and inside a corner
    assert LETHAL > cm.cost_at(3.0, 1.45) > FREE  # inflated around it
    assert cm.cost_at(1.0, 1.0) == FREE
    assert entry.describe() == "#1 heavy at (3.00, 1.00) m, 0.50 x 0.50 m, found at 10.0 s"
    cm.reset()  # a ClearCostmap keeps it (it is not a sensor observation)
    assert cm.cost_at(3.0, 1.0) == LETHAL


def test_it_decays_after_memory_s() -> None:
    cm = empty_costmap()
    cm.remember_obstacle(BOX, now_s=10.0)
    assert cm.expire_memory(310.0) == []  # exactly memory_s old: kept
    cm.update()
    assert cm.cost_at(3.0, 1.0) == LETHAL
    gone = cm.expire_memory(310.5)
    assert [g.obstacle_id for g in gone] == [1]
    cm.update()
    assert cm.cost_at(3.0, 1.0) == FREE
    assert remembered(cm) == 0


def test_a_clock_that_jumped_back_keeps_it() -> None:
    layer = ObstacleMemoryLayer(MEMORY)
    layer.remember(BOX, 500.0)
    assert layer.expire(0.0) == []


def test_a_scan_that_still_sees_it_keeps_it_and_one_that_sees_through_forgets_it_at_once() -> None:
    cm = empty_costmap()
    cm.remember_obstacle(BOX, now_s=10.0)
    cm.add_scan(scan_of((1.0, 1.0), [BOX]))  # the box is still there: beams end on its face
    cm.update()
    assert remembered(cm) == 1
    assert cm.cost_at(3.0, 1.0) == LETHAL
    cm.add_scan(scan_of((1.0, 1.0), []))  # moved away: the beams pass through the footprint
    cm.update()
    assert remembered(cm) == 0
    assert cm.cost_at(3.0, 1.0) == FREE


def test_a_box_moved_a_little_is_still_there() -> None:
    layer = ObstacleMemoryLayer(MEMORY)
    layer.remember(BOX, 0.0)
    moved = box_footprint(3.2, 1.0, 0.5, 0.5)  # pushed 0.2 m: still in most of its footprint
    assert layer.observe_scan(scan_of((1.0, 1.0), [moved])) == []


def test_what_the_scan_cannot_see_is_kept() -> None:
    layer = ObstacleMemoryLayer(MEMORY)
    layer.remember(BOX, 0.0)
    wall_in_front = box_footprint(2.0, 1.0, 0.1, 2.0)  # hides the footprint: beams end before it
    assert layer.observe_scan(scan_of((1.0, 1.0), [wall_in_front])) == []
    far = ObstacleMemoryLayer(MemoryParams(max_range_m=1.5))
    far.remember(BOX, 0.0)
    assert far.observe_scan(scan_of((1.0, 1.0), [])) == []  # 1.75 m away: not judged


def test_the_operator_clears_one_or_all() -> None:
    cm = empty_costmap()
    first = cm.remember_obstacle(BOX, 0.0)
    second = cm.remember_obstacle(box_footprint(5.0, 1.0, 0.4, 0.4), 1.0)
    assert [o.obstacle_id for o in cm.clear_memory(first.obstacle_id)] == [first.obstacle_id]
    cm.update()
    assert cm.cost_at(3.0, 1.0) == FREE and cm.cost_at(5.0, 1.0) == LETHAL
    with pytest.raises(ConfigError, match=r"no obstacle #1 \(remembered: 2\)"):
        cm.clear_memory(first.obstacle_id)
    assert [o.obstacle_id for o in cm.clear_memory()] == [second.obstacle_id]
    cm.update()
    assert cm.cost_at(5.0, 1.0) == FREE


def test_remembering_the_same_obstacle_again_replaces_it() -> None:
    layer = ObstacleMemoryLayer(MEMORY)
    layer.remember(BOX, 0.0)
    again = layer.remember(box_footprint(3.05, 1.0, 0.5, 0.5), 50.0)
    assert [(o.obstacle_id, o.found_s) for o in layer.obstacles] == [(again.obstacle_id, 50.0)]
    layer.remember(box_footprint(6.0, 1.0, 0.5, 0.5), 60.0)
    assert len(layer.obstacles) == 2


def test_a_full_memory_forgets_the_oldest() -> None:
    layer = ObstacleMemoryLayer(MemoryParams(memory_s=300.0, max_obstacles=2))
    first = layer.remember(box_footprint(1.0, 1.0, 0.5, 0.5), 30.0)
    layer.remember(box_footprint(3.0, 1.0, 0.5, 0.5), 10.0)  # found earlier (a mark that came late): the oldest
    third = layer.remember(box_footprint(5.0, 1.0, 0.5, 0.5), 40.0)
    assert [o.obstacle_id for o in layer.obstacles] == [first.obstacle_id, third.obstacle_id]


def test_a_replaced_or_forgotten_footprint_is_no_longer_lethal_in_the_costmap() -> None:
    cm = empty_costmap()
    cm.remember_obstacle(box_footprint(3.0, 1.0, 1.6, 0.8), now_s=0.0)  # the first mark: a long footprint
    cm.update()
    assert cm.cost_at(3.75, 1.0) == LETHAL
    cm.remember_obstacle(box_footprint(2.95, 1.0, 0.3, 0.3), now_s=5.0)  # the same box marked again, cut to it
    cm.update()
    assert remembered(cm) == 1
    assert cm.cost_at(2.95, 1.0) == LETHAL and cm.cost_at(3.75, 1.0) < LETHAL  # the old far end is free again


def corridor_map() -> GridMap:
    """8 x 4 m: a wall along y = 2 m from x = 1 to 7 m; the way along y = 1 m is short, around the wall long."""
    occ = np.zeros((80, 160), dtype=np.int8)
    occ[0, :] = occ[-1, :] = occ[:, 0] = occ[:, -1] = 100
    occ[38:42, 20:140] = 100  # the wall (y 1.9-2.1 m, x 1-7 m)
    return GridMap(occ, RES, (0.0, 0.0, 0.0))


def test_plans_route_around_a_remembered_obstacle_and_back_when_it_is_forgotten() -> None:
    cm = Costmap.from_map(corridor_map(), obstacles=ObstacleLayerParams(), inflation=InflationParams(0.15, 0.3, 5.0),
                          memory=MEMORY)
    box = box_footprint(4.0, 1.0, 0.5, 1.8)  # fills the lower way from y = 0.1 to 1.9 m
    planner = GridPlanner()
    start, goal = (0.5, 1.0), (7.5, 1.0)
    straight = planner.plan(cm.costs, cm.geometry, start, goal)
    assert straight.ok and straight.path[:, 1].max() < 1.9
    cm.remember_obstacle(box, now_s=0.0)
    cm.update()
    around = planner.plan(cm.costs, cm.geometry, start, goal)
    assert around.ok
    assert around.path[:, 1].max() > 2.1  # over the wall's end: the upper way
    xs, ys = around.path[:, 0], around.path[:, 1]
    assert not ((np.abs(xs - 4.0) <= 0.25) & (np.abs(ys - 1.0) <= 0.9)).any()  # never through the footprint
    assert len(around.path) > len(straight.path)
    cm.clear_memory()
    cm.update()
    assert planner.plan(cm.costs, cm.geometry, start, goal).path[:, 1].max() < 1.9


def test_ray_spans_enter_and_leave_a_footprint() -> None:
    directions = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]])
    t_in, t_out = ray_spans(BOX, 1.0, 1.0, directions)  # along +x through the box, along +y and -x past it
    assert t_in[0] == pytest.approx(1.75) and t_out[0] == pytest.approx(2.25)
    assert t_in[1] > t_out[1]  # parallel to two faces, beside the box: misses
    assert t_out[2] < 0.0  # the box is behind


def test_footprints_are_checked_and_turned_counter_clockwise() -> None:
    clockwise = BOX[::-1]
    assert np.allclose(convex_footprint(clockwise), BOX[::-1][::-1])
    with pytest.raises(ConfigError, match="convex"):
        convex_footprint(np.array([[0.0, 0.0], [2.0, 0.0], [1.0, 0.5], [2.0, 2.0], [0.0, 2.0]]))
    with pytest.raises(ConfigError, match="one line"):
        convex_footprint(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]))
    with pytest.raises(ConfigError, match=">= 3"):
        convex_footprint(np.zeros((2, 2)))
    with pytest.raises(ConfigError, match="finite"):
        convex_footprint(np.array([[0.0, 0.0], [1.0, np.nan], [0.0, 1.0]]))


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"memory_s": 0.0}, "memory_s"),
    ({"tolerance_m": -0.1}, "tolerance_m"),
    ({"min_free_beams": 0}, "min_free_beams"),
    ({"min_hits": 0}, "min_hits"),
    ({"max_range_m": math.inf}, "max_range_m"),
    ({"max_obstacles": 0}, "max_obstacles"),
])
def test_parameters_are_validated(kwargs: dict, match: str) -> None:
    with pytest.raises(ConfigError, match=match):
        MemoryParams(**kwargs)


def test_a_costmap_without_memory_says_so() -> None:
    cm = Costmap(CostmapGeometry(10, 10, RES), obstacles=ObstacleLayerParams())
    with pytest.raises(ConfigError, match="no obstacle memory"):
        cm.remember_obstacle(BOX, 0.0)
