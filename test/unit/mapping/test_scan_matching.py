"""The correlative scan matcher (a known offset recovered on synthetic scans; a repeated scene shows a second
peak) and the occupancy grid (ray-traced free space, hits, thresholds, no doubled cells)."""

import math

import numpy as np
import pytest
from unit.localization.room import asymmetric_room, scan_at, wall_cells_near_truth

from flex_nav.exceptions import ConfigError
from flex_nav.localization import ScanBeams
from flex_nav.mapping.occupancy import FREE, OCCUPIED, UNKNOWN, OccupancyParams, rasterize, scan_rays
from flex_nav.mapping.scan_matcher import MatcherParams, ScanMatcher, Window, thin
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.planar import transform_poses

REFERENCE = (1.5, 1.2, 0.0)


def hits_at(grid, pose, rng=None):
    rays = scan_rays(scan_at(grid, pose, rng, 0.01 if rng is not None else 0.0), 5.0)
    return np.column_stack([rays.end_x[rays.hit], rays.end_y[rays.hit]])


def to_map(points, pose):
    return transform_poses(points, *pose)


@pytest.fixture(scope="module")
def room():
    return asymmetric_room()


@pytest.fixture(scope="module")
def reference(room):
    matcher = ScanMatcher(MatcherParams())
    return matcher, matcher.lookup(to_map(hits_at(room, REFERENCE, np.random.default_rng(0)), REFERENCE), 7.0)


@pytest.mark.parametrize("offset", [(0.13, -0.08, 0.12), (-0.2, 0.1, -0.25), (0.05, 0.25, 0.3)])
def test_the_matcher_recovers_a_known_offset(room, reference, offset):
    matcher, lookup = reference
    truth = (1.8, 1.3, 0.15)
    prior = (truth[0] + offset[0], truth[1] + offset[1], truth[2] + offset[2])
    match = matcher.match(lookup, hits_at(room, truth, np.random.default_rng(1)), Window(prior, 0.3, 0.35))
    assert match is not None
    assert math.hypot(match.pose[0] - truth[0], match.pose[1] - truth[1]) < 0.015, match.pose
    assert abs(wrap_angle(match.pose[2] - truth[2])) < math.radians(0.5)
    assert match.response > 0.7
    assert match.covariance.shape == (3, 3) and np.all(np.diag(match.covariance) > 0.0)


def test_an_offset_outside_the_window_is_not_found(room, reference):
    matcher, lookup = reference
    truth = (1.8, 1.3, 0.15)
    prior = (truth[0] + 0.6, truth[1], truth[2])  # 60 cm off, window 30 cm
    match = matcher.match(lookup, hits_at(room, truth), Window(prior, 0.3, 0.35))
    assert match is not None
    assert math.hypot(match.pose[0] - truth[0], match.pose[1] - truth[1]) > 0.25


def test_branch_and_bound_finds_what_the_exhaustive_search_finds(room, reference):
    matcher, lookup = reference
    points = thin(hits_at(room, (2.0, 1.0, -0.2), np.random.default_rng(2)), 200)
    window = Window((2.1, 0.95, -0.1), 0.15, 0.15)
    match = matcher.match(lookup, points, window)
    assert match is not None
    # exhaustive: every lattice pose of the window scored with the bilinear lookup
    step = matcher.params.resolution
    xs = window.prior[0] + step * np.arange(-6, 7)
    ys = window.prior[1] + step * np.arange(-6, 7)
    yaws = window.prior[2] + np.radians(np.arange(-8.0, 8.01, 0.5))
    poses = np.array([(x, y, a) for x in xs for y in ys for a in yaws])
    best = poses[int(np.argmax(lookup.scores(poses, points)))]
    assert math.hypot(match.pose[0] - best[0], match.pose[1] - best[1]) <= 1.5 * step
    assert match.response >= float(lookup.scores(best[None, :], points)[0]) - 0.01


def test_a_repeated_scene_has_a_second_peak_a_unique_one_not():
    """Two identical 'doors' (gaps in a wall) 2 m apart: the scan of one fits the other as well."""
    wall = [(x, 0.0) for x in np.arange(-3.0, 3.0, 0.02) if not (abs(x - 1.0) < 0.4 or abs(x + 1.0) < 0.4)]
    reference = np.array(wall)
    matcher = ScanMatcher(MatcherParams())
    lookup = matcher.lookup(reference, 4.0)
    # the robot 1 m in front of the door at x = -1, seeing 2.4 m of the wall
    robot = (-1.0, -1.0, math.pi / 2)
    seen = reference[np.abs(reference[:, 0] + 1.0) < 1.2]
    c, s = math.cos(-robot[2]), math.sin(-robot[2])
    local = np.column_stack([c * (seen[:, 0] - robot[0]) - s * (seen[:, 1] - robot[1]),
                             s * (seen[:, 0] - robot[0]) + c * (seen[:, 1] - robot[1])])
    window = Window((0.0, -1.0, math.pi / 2), 1.2, 0.1)
    best = matcher.match(lookup, local, window)
    assert best is not None
    second = matcher.match(lookup, local, window, exclude=(best.pose, 0.5, math.pi))
    assert second is not None
    assert {round(best.pose[0]), round(second.pose[0])} == {-1, 1}  # the two doors
    assert second.response > 0.9 * best.response


def test_matcher_parameters_are_validated():
    with pytest.raises(ConfigError, match="resolution"):
        MatcherParams(resolution=0.0)
    with pytest.raises(ConfigError, match="coarse_factor"):
        MatcherParams(coarse_factor=0)


def test_too_few_points_give_no_match(reference):
    matcher, lookup = reference
    assert matcher.match(lookup, np.zeros((2, 2)), Window(REFERENCE, 0.3, 0.3)) is None


# --- occupancy ---------------------------------------------------------------------------------------------


def test_a_beam_clears_the_cells_it_passes_and_marks_the_one_it_hits():
    params = OccupancyParams(resolution=0.1, padding=0.0)
    scan = ScanBeams(np.array([1.97, np.inf]), np.array([0.0, math.pi / 2]), (0.0, 0.0, 0.0), 0.05, 3.0)
    grid = rasterize(params, [(0.05, 0.05, 0.0)], [scan_rays(scan, 1.0)]).to_grid_map()
    row, col = grid.world_to_cell(2.05, 0.05)  # the surface at x = 2.02: its cell
    assert grid.occupancy[row, col] == OCCUPIED
    for x in np.arange(0.05, 2.0, 0.1):  # along the hit beam
        assert grid.occupancy[grid.world_to_cell(x, 0.05)] == FREE, x
    for y in np.arange(0.15, 1.0, 0.1):  # the beam that saw nothing: free up to max_free_range (1 m), no hit
        assert grid.occupancy[grid.world_to_cell(0.05, y)] == FREE, y
    assert np.count_nonzero(grid.occupancy == OCCUPIED) == 1
    assert np.any(grid.occupancy == UNKNOWN)


def test_a_cell_seen_free_more_often_than_hit_turns_free():
    params = OccupancyParams(resolution=0.1, padding=0.5)
    # the hit ends in the cell [1.0, 1.1): 0.05 + 0.98 + half a cell
    hit_once = scan_rays(ScanBeams(np.array([0.98]), np.array([0.0]), (0.0, 0.0, 0.0), 0.05, 3.0), 3.0)
    passed = scan_rays(ScanBeams(np.array([2.0]), np.array([0.0]), (0.0, 0.0, 0.0), 0.05, 3.0), 3.0)
    pose = (0.05, 0.05, 0.0)
    grid = rasterize(params, [pose] * 4, [hit_once] + [passed] * 3).to_grid_map()
    assert grid.occupancy[grid.world_to_cell(1.05, 0.05)] == FREE  # a door that opened
    grid = rasterize(params, [pose] * 2, [hit_once, hit_once]).to_grid_map()
    assert grid.occupancy[grid.world_to_cell(1.05, 0.05)] == OCCUPIED


def test_rasterized_room_walls_land_on_the_true_walls(room):
    rng = np.random.default_rng(3)
    poses = [(1.5, 1.2, 0.0), (3.0, 2.0, 1.0), (5.5, 1.5, 3.0), (2.0, 3.8, -1.5)]
    rays = [scan_rays(scan_at(room, p, rng, 0.01), 5.0) for p in poses]
    built = rasterize(OccupancyParams(), poses, rays).to_grid_map()
    count, near = wall_cells_near_truth(room, built)
    assert count > 200
    assert near > 0.98  # every mapped wall cell within a cell of a true one


def test_occupancy_parameters_are_validated():
    with pytest.raises(ConfigError, match="log_odds_free"):
        OccupancyParams(log_odds_free=0.5)
    with pytest.raises(ConfigError, match="resolution"):
        OccupancyParams(resolution=-1.0)


def test_scan_rays_drop_short_ranges_and_cap_no_returns():
    scan = ScanBeams(np.array([0.01, np.nan, 2.0, 9.0]), np.array([0.0, 0.5, 1.0, 1.5]), (0.1, 0.0, 0.0), 0.05, 5.0)
    rays = scan_rays(scan, 3.0)
    assert rays.hit.tolist() == [False, True, False]  # NaN: nothing seen; 2.0: a hit; 9.0 >= range_max: nothing
    lengths = np.hypot(rays.end_x - 0.1, rays.end_y)
    np.testing.assert_allclose(lengths, [3.0, 2.0, 3.0])
