"""Progress along a goal path: lookahead by arc length, monotonic tracking, goal test, back-off."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.progress import PathProgress

L_PATH = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0]])  # 8 m, a left turn at (4, 0)


def test_lookahead_is_arc_length_not_straight_line():
    progress = PathProgress(L_PATH, lookahead_distance=2.0, goal_tolerance=0.2)
    p = progress.update(3.0, 0.1)
    assert p.travelled == pytest.approx(3.0)
    assert p.target[:2] == pytest.approx((4.0, 1.0))  # 1 m to the corner + 1 m up
    assert p.target[2] == pytest.approx(math.pi / 2)
    assert p.remaining == pytest.approx(5.0)
    assert p.cross_track == pytest.approx(0.1)
    assert not p.done and not p.target_is_end


def test_target_clamps_to_the_end_and_done_within_tolerance():
    progress = PathProgress(L_PATH, lookahead_distance=2.0, goal_tolerance=0.2)
    p = progress.update(3.9, 0.5)
    p = progress.update(4.0, 3.0)
    assert p.target == pytest.approx((4.0, 4.0, math.pi / 2))
    assert p.target_is_end and not p.done
    p = progress.update(4.1, 3.9)
    assert p.done
    assert p.distance_to_end == pytest.approx(math.hypot(0.1, 0.1))


def test_loop_path_is_not_done_at_its_start():
    loop = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.1]])
    progress = PathProgress(loop, lookahead_distance=1.0, goal_tolerance=0.3)
    p = progress.update(0.0, 0.0)
    assert not p.done  # 0.1 m from the end, but 7.9 m of path remain
    assert p.target[:2] == pytest.approx((1.0, 0.0))


def test_loop_path_closing_a_hair_nearer_than_its_start_is_not_done_at_its_start():
    """A closed patrol loop (end = start): the robot a few millimetres nearer the closing segment than the
    first one is still at the start, not at the end."""
    loop = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.0]])
    progress = PathProgress(loop, lookahead_distance=1.0, goal_tolerance=0.1)
    p = progress.update(-0.003, 0.02)  # 0.003 m from the closing segment, 0.020 m from the first
    assert not p.done
    assert p.travelled == pytest.approx(0.0)
    assert p.remaining == pytest.approx(8.0)


def test_tracking_is_monotonic_where_the_path_passes_close_by():
    # an S whose later part passes 0.4 m from the start region
    path = np.array([[0.0, 0.0], [5.0, 0.0], [5.0, 1.0], [1.0, 1.0], [1.0, 0.4], [6.0, 0.4]])
    progress = PathProgress(path, lookahead_distance=0.5, goal_tolerance=0.1)
    progress.update(0.0, 0.0)
    for x in np.arange(0.2, 3.0, 0.2):
        p = progress.update(float(x), 0.21)  # nearer the last leg (y 0.4) than the first (y 0) at y 0.21
        assert p.travelled < 5.0, f"jumped ahead at x={x}"


def test_back_off_keeps_target_inside():
    progress = PathProgress(L_PATH, lookahead_distance=3.0, goal_tolerance=0.2)
    p = progress.update(0.0, 0.0, inside=lambda x, y: x <= 2.0)
    assert p.target[0] == pytest.approx(2.0, abs=3.0 / 64 + 1e-9)
    assert p.target[0] <= 2.0
    p = progress.update(0.0, 0.0, inside=lambda x, y: False)
    assert p.target[:2] == pytest.approx((0.0, 0.0))


def test_xy_path_gets_headings_and_yaw_of_xyyaw_is_kept():
    p = PathProgress(np.array([[0.0, 0.0], [0.0, 1.0]]), 5.0, 0.1).update(0.0, 0.0)
    assert p.target == pytest.approx((0.0, 1.0, math.pi / 2))
    p = PathProgress(np.array([[0.0, 0.0, 0.0], [0.0, 1.0, 3.0]]), 5.0, 0.1).update(0.0, 0.0)
    assert p.target[2] == pytest.approx(3.0)


def test_single_pose_path():
    progress = PathProgress(np.array([[1.0, 1.0, 0.5]]), 1.0, 0.2)
    assert not progress.update(0.0, 0.0).done
    assert progress.update(1.1, 1.0).done


@pytest.mark.parametrize(
    ("args", "match"),
    [
        ((np.empty((0, 2)), 1.0, 0.1), "empty"),
        ((np.array([[0.0, math.nan]]), 1.0, 0.1), "non-finite"),
        ((L_PATH, 0.0, 0.1), "lookahead_distance"),
        ((L_PATH, 1.0, math.inf), "goal_tolerance"),
    ],
)
def test_bad_construction(args, match):
    with pytest.raises(ConfigError, match=match):
        PathProgress(*args)


def test_bad_position():
    with pytest.raises(ConfigError, match="finite"):
        PathProgress(L_PATH, 1.0, 0.1).update(math.nan, 0.0)


def test_done_waits_for_the_final_heading_when_it_counts():
    path = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, math.pi / 2]])  # ends facing +y
    progress = PathProgress(path, lookahead_distance=1.0, goal_tolerance=0.2, yaw_goal_tolerance=0.25)
    p = progress.update(1.95, 0.0, yaw=0.0)
    assert p.position_reached and not p.done
    assert p.heading_error == pytest.approx(math.pi / 2)
    assert p.target_is_end and p.target == pytest.approx((2.0, 0.0, math.pi / 2))  # plan to the end, its yaw
    p = progress.update(1.95, 0.0, yaw=math.pi / 2 - 0.2)
    assert p.done and p.heading_error == pytest.approx(0.2)
    p = progress.update(1.95, 0.0, yaw=-3.0 * math.pi / 2 + 0.3)  # the same heading, one turn further: wrapped
    assert not p.done and p.heading_error == pytest.approx(-0.3)
    p = progress.update(1.5, 0.0, yaw=math.pi / 2)  # facing right, but not there
    assert not p.done and not p.position_reached


def test_heading_ignored_without_a_yaw_tolerance():
    path = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, math.pi / 2]])
    p = PathProgress(path, lookahead_distance=1.0, goal_tolerance=0.2).update(1.95, 0.0)
    assert p.done and p.position_reached and math.isnan(p.heading_error)


@pytest.mark.parametrize("tolerance", [0.0, -0.1, math.nan, math.inf])
def test_bad_yaw_tolerance_is_refused(tolerance):
    with pytest.raises(ConfigError, match="yaw_goal_tolerance"):
        PathProgress(L_PATH, lookahead_distance=1.0, goal_tolerance=0.2, yaw_goal_tolerance=tolerance)


def test_yaw_is_needed_when_the_heading_counts():
    progress = PathProgress(L_PATH, lookahead_distance=1.0, goal_tolerance=0.2, yaw_goal_tolerance=0.25)
    with pytest.raises(ConfigError, match="yaw"):
        progress.update(1.0, 0.0)
    with pytest.raises(ConfigError, match="yaw"):
        progress.update(1.0, 0.0, yaw=math.nan)
