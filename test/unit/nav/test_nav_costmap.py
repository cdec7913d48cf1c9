"""Layered costmap: values, inflation against a brute-force reference, layers, rolling window, bounded updates."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import (
    FREE,
    INSCRIBED,
    LETHAL,
    NO_INFORMATION,
    CostmapGeometry,
    costs_to_occupancy,
)
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.costmap.inflation import InflationParams, Inflator, cost_of_distance, inflate
from flex_nav.nav.costmap.layered import Costmap
from flex_nav.nav.costmap.obstacle_layer import LaserScan, ObstacleLayerParams, shifted
from flex_nav.nav.costmap.raytrace import line_cells, set_rays
from flex_nav.nav.costmap.static_layer import StaticLayerParams, occupancy_to_costs

RES = 0.05
PARAMS = InflationParams(inscribed_radius=0.12, inflation_radius=0.4, cost_scaling_factor=5.0)


def brute_force_inflation(costs, resolution, params):
    """Reference: distance from every cell centre to every lethal cell centre, costmap_2d's formula."""
    lethal = np.argwhere(costs == LETHAL)
    out = costs.copy()
    if len(lethal) == 0:
        return out
    radius_cells = math.ceil(params.inflation_radius / resolution - 1e-9)
    for (r, c), old in np.ndenumerate(costs):
        d = float(np.min(np.hypot(lethal[:, 0] - r, lethal[:, 1] - c)))
        if d > radius_cells:
            continue
        dm = d * resolution
        if d == 0:
            cost = LETHAL
        elif dm <= params.inscribed_radius:
            cost = INSCRIBED
        else:
            cost = int(252 * math.exp(-params.cost_scaling_factor * (dm - params.inscribed_radius)))
        if old == NO_INFORMATION:
            out[r, c] = cost if cost >= INSCRIBED else NO_INFORMATION
        else:
            out[r, c] = max(old, cost)
    return out


def test_occupancy_translation_matches_costmap_2d_publisher():
    costs = np.array([0, 1, 128, 252, 253, 254, 255], dtype=np.uint8)
    assert costs_to_occupancy(costs).tolist() == [0, 1, 50, 98, 99, 100, -1]
    with pytest.raises(ConfigError):
        costs_to_occupancy(costs.astype(np.int16))


def test_cost_function_values():
    assert cost_of_distance(0.0, PARAMS) == LETHAL
    assert cost_of_distance(0.12, PARAMS) == INSCRIBED
    assert cost_of_distance(0.2, PARAMS) == int(252 * math.exp(-5.0 * 0.08))


def test_inflation_single_obstacle_matches_brute_force():
    costs = np.zeros((31, 33), dtype=np.uint8)
    costs[15, 16] = LETHAL
    out = inflate(costs, RES, PARAMS)
    np.testing.assert_array_equal(out, brute_force_inflation(costs, RES, PARAMS))
    assert out[15, 16] == LETHAL and out[15, 18] == INSCRIBED  # 0.10 m <= 0.12 m
    assert out[15, 16 + 8] > 0 and out[15, 16 + 9] == 0  # radius ceil(0.4/0.05) = 8 cells


def test_inflation_many_obstacles_and_unknown_matches_brute_force():
    rng = np.random.default_rng(7)
    costs = np.zeros((40, 45), dtype=np.uint8)
    costs[rng.random(costs.shape) < 0.02] = LETHAL
    costs[5:12, 30:40] = NO_INFORMATION
    costs[20:25, 2:6] = 77
    out = inflate(costs, RES, PARAMS)
    np.testing.assert_array_equal(out, brute_force_inflation(costs, RES, PARAMS))


def test_inflate_unknown_option():
    costs = np.full((11, 11), NO_INFORMATION, dtype=np.uint8)
    costs[5, 5] = LETHAL
    params = InflationParams(0.05, 0.3, 3.0, inflate_unknown=True)
    out = inflate(costs, 0.05, params)
    assert out[5, 9] == cost_of_distance(0.2, params) and 0 < out[5, 9] < INSCRIBED
    plain = inflate(costs, 0.05, InflationParams(0.05, 0.3, 3.0))
    assert plain[5, 9] == NO_INFORMATION and plain[5, 6] == INSCRIBED


def test_large_radius_uses_wide_index_path():
    costs = np.zeros((61, 61), dtype=np.uint8)
    costs[30, 30] = LETHAL
    params = InflationParams(0.1, 1.4, 1.0)  # 28 cells: squared distances beyond 255
    out = inflate(costs, RES, params)
    np.testing.assert_array_equal(out, brute_force_inflation(costs, RES, params))


def test_no_lethal_cells_means_no_change():
    costs = np.full((5, 5), 17, dtype=np.uint8)
    np.testing.assert_array_equal(inflate(costs, RES, PARAMS), costs)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"inscribed_radius": -0.1},
        {"inflation_radius": float("nan")},
        {"cost_scaling_factor": "3"},
        {"inscribed_radius": 0.5, "inflation_radius": 0.4},
    ],
)
def test_bad_inflation_params(kwargs):
    with pytest.raises(ConfigError):
        InflationParams(**kwargs)


def test_inflator_rejects_bad_input():
    with pytest.raises(ConfigError):
        Inflator(PARAMS, 0.0)
    with pytest.raises(ConfigError):
        Inflator(PARAMS, RES).apply(np.zeros((3, 3), dtype=np.int16))


def test_static_layer_translation():
    occ = np.array([[-1, 0, 50, 99, 100]], dtype=np.int8)
    assert occupancy_to_costs(occ, StaticLayerParams()).tolist() == [[255, 0, 0, 0, 254]]
    scaled = occupancy_to_costs(occ, StaticLayerParams(track_unknown_space=False, trinary_costmap=False))
    assert scaled.tolist() == [[0, 0, 127, 251, 254]]
    assert occupancy_to_costs(occ, StaticLayerParams(lethal_threshold=50)).tolist() == [[255, 0, 254, 254, 254]]
    with pytest.raises(ConfigError, match="lethal_threshold"):
        StaticLayerParams(lethal_threshold=0)


def _scan(ranges, x=0.0, y=0.0, yaw=0.0, angle_min=0.0, inc=math.pi / 2, rmin=0.05, rmax=3.5):
    return LaserScan(np.asarray(ranges, dtype=float), angle_min, inc, rmin, rmax, x, y, yaw)


def test_raytrace_matches_reference_lines():
    assert line_cells(0, 0, 2, 5).tolist() == [[0, 0], [0, 1], [1, 2], [1, 3], [2, 4], [2, 5]]
    rng = np.random.default_rng(3)
    for _ in range(50):
        grid = np.zeros((30, 30), dtype=np.uint8)
        r0, c0 = rng.integers(0, 30, 2)
        r1, c1 = rng.integers(-10, 40, 2)
        skip_end = bool(rng.integers(0, 2))
        set_rays(grid, int(r0), int(c0), np.array([r1]), np.array([c1]), 7, np.array([skip_end]))
        expected = np.zeros_like(grid)
        cells = line_cells(int(r0), int(c0), int(r1), int(c1))
        for r, c in cells[:-1] if skip_end else cells:
            if not (0 <= r < 30 and 0 <= c < 30):
                break
            expected[r, c] = 7
        np.testing.assert_array_equal(grid, expected)
    grid = np.zeros((5, 5), dtype=np.uint8)
    assert set_rays(grid, -1, 0, np.array([3]), np.array([3]), 1, np.array([False])) == 0 and not grid.any()


def test_scan_marks_hit_and_clears_old_marks():
    geo = CostmapGeometry(100, 100, RES, -2.5, -2.5)
    cm = Costmap(geo, obstacles=ObstacleLayerParams())
    cm.mark_obstacles(np.array([0.52, 1.0]), np.array([0.02, 1.0]))
    cm.update()
    assert cm.cost_at(0.52, 0.02) == LETHAL and cm.cost_at(1.0, 1.0) == LETHAL
    # beam along +x hitting at 1.5 m: the old mark at 0.52 m is cleared, the hit is marked
    cm.add_scan(_scan([1.5, float("nan"), 0.01, float("inf")], x=0.02, y=0.02))
    cm.update()
    assert cm.cost_at(0.52, 0.02) == FREE
    assert cm.cost_at(1.52, 0.02) == LETHAL
    assert cm.cost_at(1.0, 1.0) == LETHAL  # no beam went there


def test_far_hits_not_marked_and_no_return_clears():
    geo = CostmapGeometry(200, 200, RES, -5.0, -5.0)
    cm = Costmap(geo, obstacles=ObstacleLayerParams(obstacle_range=2.0, raytrace_range=3.0))
    cm.mark_obstacles(np.array([-2.0, -2.9]), np.array([0.0, 0.0]))
    cm.add_scan(_scan([2.4], angle_min=0.0))  # beyond obstacle_range: clears, no mark
    cm.add_scan(_scan([3.5], angle_min=math.pi))  # range_max: no return, clears to 3.0 m
    cm.update()
    assert cm.cost_at(2.41, 0.01) == FREE
    assert cm.cost_at(-2.0, 0.0) == FREE
    assert cm.cost_at(-2.9, 0.0) == FREE
    # a beam ending on an obstacle beyond obstacle_range does not mark it, nor clear a mark made from closer
    cm.mark_obstacles(np.array([2.41]), np.array([0.01]))
    cm.add_scan(_scan([2.41], angle_min=0.0))
    cm.update()
    assert cm.cost_at(2.41, 0.01) == LETHAL and cm.cost_at(1.5, 0.01) == FREE
    quiet = Costmap(geo, obstacles=ObstacleLayerParams(clear_on_no_return=False))
    quiet.mark_obstacles(np.array([-2.0]), np.array([0.0]))
    quiet.add_scan(_scan([float("inf")], angle_min=math.pi))
    quiet.update()
    assert quiet.cost_at(-2.0, 0.0) == LETHAL


def test_bad_scans_and_points_raise():
    geo = CostmapGeometry(20, 20, RES)
    cm = Costmap(geo, obstacles=ObstacleLayerParams())
    with pytest.raises(ConfigError, match="sensor_x"):
        cm.add_scan(_scan([1.0], x=float("nan")))
    with pytest.raises(ConfigError, match="range_min"):
        cm.add_scan(_scan([1.0], rmin=2.0, rmax=1.0))
    with pytest.raises(ConfigError, match="non-finite"):
        cm.mark_obstacles(np.array([float("inf")]), np.array([0.0]))
    with pytest.raises(ConfigError, match="as many"):
        cm.mark_obstacles(np.array([0.1, 0.2]), np.array([0.0]))
    with pytest.raises(ConfigError, match="no obstacle layer"):
        Costmap(geo).add_scan(_scan([1.0]))
    with pytest.raises(ConfigError, match="obstacle_range"):
        ObstacleLayerParams(obstacle_range=-1.0)


def test_sensor_off_grid_marks_but_does_not_clear():
    cm = Costmap(CostmapGeometry(20, 20, RES), obstacles=ObstacleLayerParams(obstacle_range=4.0, raytrace_range=5.0))
    cm.mark_obstacles(np.array([0.02]), np.array([0.52]))
    cm.update()
    before = cm.costs.copy()
    cm.add_scan(_scan([0.5], x=-3.0))  # hit at x=-2.5, off the grid too: nothing changes
    cm.update()
    np.testing.assert_array_equal(cm.costs, before)
    # from off the grid, a beam through the mark hitting behind it: the mark stays, the hit is marked
    cm.add_scan(_scan([3.32], x=-3.0, y=0.52))
    cm.update()
    assert cm.cost_at(0.02, 0.52) == LETHAL
    assert cm.cost_at(0.32, 0.52) == LETHAL


def _static_grid(size=120, seed=5):
    rng = np.random.default_rng(seed)
    occ = np.zeros((size, size), dtype=np.int8)
    occ[rng.random(occ.shape) < 0.01] = 100
    occ[10:20, 10:30] = -1
    return GridMap(occ, RES, (-1.0, -2.0, 0.0))


def test_global_costmap_from_map_and_bounded_update_equals_full_rebuild():
    grid = _static_grid()
    params = InflationParams(0.1, 0.3, 4.0)
    cm = Costmap.from_map(grid, obstacles=ObstacleLayerParams(track_unknown_space=True), inflation=params)
    expected_static = inflate(occupancy_to_costs(grid.occupancy, StaticLayerParams()), RES, params)
    np.testing.assert_array_equal(cm.costs, expected_static)
    rng = np.random.default_rng(11)
    for _ in range(5):
        sx, sy = rng.uniform(0.0, 3.0, 2)
        cm.add_scan(_scan(rng.uniform(0.2, 4.0, 90), x=sx, y=sy, angle_min=-math.pi, inc=2 * math.pi / 90))
        box = cm.update()
        assert box is not None and box != (0, 120, 0, 120)  # bounded, not the whole map
    bounded = cm.costs.copy()
    cm._dirty = (0, 120, 0, 120)
    cm.update()
    np.testing.assert_array_equal(bounded, cm.costs)
    assert cm.update() is None  # nothing changed since


def test_obstacle_layer_without_unknown_tracking_frees_unknown_static_cells():
    # costmap_2d's updateWithMax: a FREE obstacle-layer cell overrides a NO_INFORMATION master cell
    grid = _static_grid()
    assert Costmap.from_map(grid).costs[15, 15] == NO_INFORMATION
    assert Costmap.from_map(grid, obstacles=ObstacleLayerParams()).costs[15, 15] == FREE


def test_reset_forgets_observations_keeps_static():
    grid = _static_grid()
    cm = Costmap.from_map(grid, obstacles=ObstacleLayerParams(), inflation=PARAMS)
    static_costs = cm.costs.copy()
    cm.mark_obstacles(np.array([1.0]), np.array([1.0]))
    cm.update()
    assert cm.cost_at(1.0, 1.0) == LETHAL
    cm.reset()
    np.testing.assert_array_equal(cm.costs, static_costs)


def test_rolling_window_recentres_and_keeps_what_it_saw():
    cm = Costmap.rolling(4.0, 4.0, RES, obstacles=ObstacleLayerParams(), inflation=PARAMS)
    assert cm.geometry.shape == (80, 80)
    assert cm.geometry.origin_x == pytest.approx(-2.0) and cm.geometry.origin_y == pytest.approx(-2.0)
    cm.mark_obstacles(np.array([1.01, -1.91]), np.array([0.51, 0.01]))
    cm.update()
    assert cm.cost_at(1.01, 0.51) == LETHAL
    cm.recentre(0.73, 0.21)
    cm.update()
    assert cm.geometry.origin_x == pytest.approx(-1.3) and cm.geometry.origin_y == pytest.approx(-1.8)
    assert cm.cost_at(1.01, 0.51) == LETHAL  # kept at the same world place
    assert cm.cost_at(-1.91, 0.01) == NO_INFORMATION  # now off the window
    cm.recentre(-0.5, 0.0)
    cm.update()
    assert cm.cost_at(-1.91, 0.01) == FREE  # it was dropped, not remembered
    assert cm.costs[cm.geometry.world_to_cell(1.01, 0.51)] == LETHAL
    cm.recentre(100.0, 100.0)
    cm.update()
    assert (cm.costs == FREE).all()
    with pytest.raises(ConfigError, match="finite"):
        cm.recentre(float("nan"), 0.0)
    with pytest.raises(ConfigError, match="rolling"):
        Costmap(CostmapGeometry(5, 5, RES)).recentre(0.0, 0.0)


def test_rolling_window_with_static_map_samples_it():
    grid = _static_grid()
    cm = Costmap.rolling(1.0, 1.0, RES, static_map=grid, centre=(1.0, 1.0))
    rows, cols = np.nonzero(cm.costs == LETHAL)
    assert len(rows) > 0, "the window over the map's wall must hold lethal cells"
    xs, ys = cm.geometry.cells_to_world(rows, cols)
    for x, y in zip(xs, ys):
        assert grid.occupancy[grid.world_to_cell(float(x), float(y))] == 100


def test_shifted_moves_content():
    a = np.arange(12, dtype=np.uint8).reshape(3, 4)
    b = shifted(a, 1, -1, 99)
    assert b.tolist() == [[99, 4, 5, 6], [99, 8, 9, 10], [99, 99, 99, 99]]
    assert (shifted(a, 5, 0, 0) == 0).all()


def test_bad_geometry():
    with pytest.raises(ConfigError):
        CostmapGeometry(0, 5, RES)
    with pytest.raises(ConfigError):
        CostmapGeometry(5, 5, -1.0)
    with pytest.raises(ConfigError):
        Costmap.rolling(float("nan"), 4.0, RES)
    with pytest.raises(ConfigError, match="yaw"):
        Costmap.from_map(GridMap(np.zeros((3, 3), dtype=np.int8), RES, (0.0, 0.0, 0.3)))


def test_to_occupancy_of_costmap():
    cm = Costmap(CostmapGeometry(10, 10, RES), obstacles=ObstacleLayerParams(), inflation=PARAMS)
    cm.mark_obstacles(np.array([0.26]), np.array([0.26]))
    cm.update()
    occ = cm.to_occupancy()
    assert occ.dtype == np.int8 and occ[5, 5] == 100 and occ[5, 6] == 99


def test_bumper_contacts_survive_lidar_clearing_and_reset_until_they_expire():
    geo = CostmapGeometry(100, 100, RES, -2.5, -2.5)
    cm = Costmap(geo, obstacles=ObstacleLayerParams(), inflation=PARAMS, bumper_memory_s=30.0)
    cm.add_bumper_hits(np.array([0.52]), np.array([0.02]), now_s=100.0)
    cm.update()
    assert cm.cost_at(0.52, 0.02) == LETHAL
    assert cm.cost_at(0.52 + PARAMS.inscribed_radius * 0.9, 0.02) == INSCRIBED  # inflated like any obstacle
    cm.add_scan(_scan([1.5], x=0.02, y=0.02))  # a beam over the low obstacle: an obstacle mark would go
    cm.update()
    assert cm.cost_at(0.52, 0.02) == LETHAL
    cm.reset()  # ClearCostmap keeps what the bumper felt
    assert cm.cost_at(0.52, 0.02) == LETHAL
    assert cm.expire_bumper_hits(now_s=129.0) == 0
    assert cm.expire_bumper_hits(now_s=131.0) == 1
    cm.update()
    assert cm.cost_at(0.52, 0.02) == FREE
    cm.add_bumper_hits(np.array([0.52]), np.array([0.02]), now_s=200.0)
    cm.reset(forget_contacts=True)
    assert cm.cost_at(0.52, 0.02) == FREE


def test_bumper_contacts_stay_at_their_world_place_in_a_rolling_window():
    cm = Costmap.rolling(4.0, 4.0, RES, obstacles=ObstacleLayerParams())
    cm.add_bumper_hits(np.array([1.01]), np.array([0.51]), now_s=0.0)
    cm.recentre(5.0, 5.0)
    cm.update()
    assert cm.cost_at(1.01, 0.51) == NO_INFORMATION  # off the window
    cm.recentre(0.5, 0.5)
    cm.update()
    assert cm.cost_at(1.01, 0.51) == LETHAL  # back in view: still remembered
    with pytest.raises(ConfigError, match="memory_s"):
        Costmap.rolling(4.0, 4.0, RES, bumper_memory_s=0.0)
