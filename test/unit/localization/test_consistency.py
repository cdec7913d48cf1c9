"""Scan consistency: the match fraction of a scan seen from a pose, the distinct-fit probes, the history of
fractions the status is judged on."""

import math

import numpy as np
import pytest
from unit.localization.room import RANGE_MAX, asymmetric_room, scan_at

from flex_nav.localization import FilterParams, GridMap, Kernel
from flex_nav.localization.consistency import MatchHistory, clear_fraction, distinct_fit, match_fraction
from flex_nav.localization.likelihood_field import LikelihoodField
from flex_nav.localization.scan import SelectedBeams, select_beams
from flex_nav.localization.sensor_model import SensorModel

START = (1.5, 1.2, 0.0)


@pytest.fixture(scope="module")
def grid():
    return asymmetric_room()


@pytest.fixture(scope="module")
def field(grid):
    return LikelihoodField(grid, 2.0)


def beams_at(grid, pose, count=60):
    return select_beams(scan_at(grid, pose), count)


def test_all_beams_match_on_the_true_pose(grid, field):
    assert match_fraction(field, START, beams_at(grid, START), 0.1) == pytest.approx(1.0)


def test_few_beams_match_a_pose_a_metre_off(grid, field):
    beams = beams_at(grid, START)
    assert match_fraction(field, (START[0] + 1.0, START[1] + 0.5, 0.3), beams, 0.1) < 0.4


def test_blocked_beams_lower_the_fraction_by_their_share(grid, field):
    scan = scan_at(grid, START)
    ranges = scan.ranges.copy()
    ranges[:90] = 0.4  # a third of the beams end on something unmapped 40 cm away
    beams = select_beams(scan._replace(ranges=ranges), 271)
    assert match_fraction(field, START, beams, 0.1) == pytest.approx(1.0 - 90 / 271, abs=0.02)


def test_unknown_cells_and_outside_the_map_do_not_match(field):
    # end points: one on the south wall, one in the unknown cells around the room, one off the map
    beams = SelectedBeams(np.array([0.0, 0.0, 50.0]), np.array([-0.72, -0.9, 0.0]), 0)
    assert match_fraction(field, START, beams, 0.1) == pytest.approx(1.0 / 3.0)


def test_no_beams_is_nan(field):
    assert math.isnan(match_fraction(field, START, SelectedBeams(np.empty(0), np.empty(0), 3), 0.1))


def test_rotated_map_origin():
    occupancy = np.zeros((40, 40), dtype=np.int8)
    occupancy[:, 30] = 100  # a wall along the grid's rows: x = 1.5 m in grid coordinates
    field = LikelihoodField(GridMap(occupancy, 0.05, (0.0, 0.0, math.pi / 2)), 2.0)
    # the grid's x axis is the map's y axis, its y axis the map's -x: the wall is the line y = 1.5 m of the map,
    # the grid covers x in [-2, 0]
    beams = SelectedBeams(np.array([1.0]), np.array([0.0]), 0)
    assert match_fraction(field, (-1.0, 0.5, math.pi / 2), beams, 0.1) == 1.0
    assert match_fraction(field, (-1.0, 0.5, 0.0), beams, 0.1) == 0.0


def test_distinct_fit_on_the_true_pose_not_10_cm_off(grid, field):
    model = SensorModel(FilterParams(), field)
    beams = beams_at(grid, START)
    assert distinct_fit(model, START, beams, RANGE_MAX)
    assert not distinct_fit(model, (START[0] + 0.1, START[1], 0.0), beams, RANGE_MAX)
    assert not distinct_fit(model, (START[0], START[1], math.radians(5.0)), beams, RANGE_MAX, Kernel.NUMPY)
    assert not distinct_fit(model, START, SelectedBeams(np.empty(0), np.empty(0), 0), RANGE_MAX)


def test_distinct_fit_refuses_a_pose_a_corridor_does_not_pin():
    occupancy = np.zeros((40, 400), dtype=np.int8)
    occupancy[0, :] = occupancy[-1, :] = 100  # two walls 2 m apart, 20 m long: nothing fixes x
    corridor = GridMap(occupancy, 0.05)
    model = SensorModel(FilterParams(), LikelihoodField(corridor, 2.0))
    pose = (10.0, 1.0, 0.0)
    beams = beams_at(corridor, pose)
    assert match_fraction(model.field, pose, beams, 0.1) == pytest.approx(1.0)
    assert not distinct_fit(model, pose, beams, RANGE_MAX)


def test_rays_are_clear_on_the_true_pose_not_through_a_wall(grid, field):
    beams = beams_at(grid, START)
    assert clear_fraction(field, START, beams, 0.1) == pytest.approx(1.0)
    # 30 cm south: the beams that end on the south wall now end beyond it, their rays through it
    shifted = clear_fraction(field, (START[0], START[1] - 0.3, 0.0), beams, 0.1)
    assert 0.3 < shifted < 0.9
    assert math.isnan(clear_fraction(field, START, SelectedBeams(np.empty(0), np.empty(0), 0), 0.1))


def test_a_thin_wall_fits_from_behind_but_the_rays_cross_it():
    occupancy = np.zeros((60, 60), dtype=np.int8)
    occupancy[40, :] = 100  # a wall one cell thick along y = 2.0 .. 2.05 m, free on both sides
    thin = GridMap(occupancy, 0.05)
    field = LikelihoodField(thin, 2.0)
    truth = (1.5, 1.5, math.pi / 2)
    beams = beams_at(thin, truth)
    behind = (1.5, 1.6, math.pi / 2)  # the end points 10 cm further on: on the wall's far edge
    assert match_fraction(field, behind, beams, 0.1) == pytest.approx(1.0)
    assert clear_fraction(field, truth, beams, 0.1) == pytest.approx(1.0)
    assert clear_fraction(field, behind, beams, 0.1) < 0.75


def test_history_keeps_the_last_fractions():
    history = MatchHistory(3)
    assert math.isnan(history.mean())
    assert [is_full(history)] == [False]
    for fraction in (0.0, 0.9, 0.6, 0.3):
        history.add(fraction)
    assert [is_full(history)] == [True]
    assert history.mean() == pytest.approx(0.6)
    history.clear()
    assert [is_full(history)] == [False]
    assert math.isnan(history.mean())


def is_full(history: MatchHistory) -> bool:
    """``history.full`` read through a call, so that mypy does not carry one assertion's narrowing to the next."""
    return history.full
