"""Path utilities: validation, length, closest point, arc-length points, lookahead circle, pruning."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.path import (
    as_path,
    closest_point,
    cumulative_lengths,
    lookahead_point,
    path_length,
    point_at_arc,
    prune_passed,
)

L_PATH = np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 4.0]])


@pytest.mark.parametrize(
    ("poses", "needle"),
    [
        ([], "shape|empty"),
        (np.zeros((0, 2)), "empty"),
        ([[1.0, 2.0, 3.0, 4.0]], "shape"),
        ([[0.0, 0.0], [float("nan"), 1.0]], "non-finite value at pose 1"),
        ([["a", "b"]], "numbers"),
    ],
)
def test_as_path_rejects_bad_input(poses, needle):
    with pytest.raises(ConfigError, match=needle):
        as_path(poses)


def test_lengths():
    assert path_length(L_PATH) == 7.0
    assert cumulative_lengths(L_PATH).tolist() == [0.0, 3.0, 7.0]
    assert path_length(np.array([[1.0, 1.0]])) == 0.0


def test_closest_point_prefers_the_earliest_segment_within_the_slack():
    loop = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.0]])
    nearest = closest_point(loop, -0.003, 0.02)
    assert nearest.index == 3 and nearest.distance == pytest.approx(0.003)  # the closing segment
    early = closest_point(loop, -0.003, 0.02, earliest_within=0.05)
    assert early.index == 0 and early.s == pytest.approx(0.0)
    assert early.distance == pytest.approx(math.hypot(0.003, 0.02))
    # a segment farther than the slack is not preferred
    assert closest_point(loop, -0.003, 0.02, earliest_within=0.01).index == 3
    # one pass: its nearest point, not the earliest segment within the slack
    line = np.column_stack([np.linspace(0.0, 5.0, 101), np.zeros(101)])
    assert closest_point(line, 2.0, 0.01, earliest_within=0.5).s == pytest.approx(2.0)


def test_closest_point_projects_on_segments():
    p = closest_point(L_PATH, 1.2, -0.5)
    assert (p.index, p.x, p.y, p.s) == (0, 1.2, 0.0, 1.2) and p.distance == pytest.approx(0.5)
    q = closest_point(L_PATH, 4.0, 2.0)
    assert q.index == 1 and (q.x, q.y) == (3.0, 2.0) and q.s == pytest.approx(5.0)
    # the search starts at start_index: earlier segments are ignored
    r = closest_point(L_PATH, 1.0, 0.1, start_index=1)
    assert r.index == 1 and (r.x, r.y) == (3.0, 0.1)
    # a bounded window does not see far segments (it ends max_arc beyond the start segment's end)
    long = np.column_stack([np.linspace(0, 10, 101), np.zeros(101)])
    w = closest_point(long, 9.0, 0.0, max_arc=1.0)
    assert w.x == pytest.approx(1.1)
    # ... but a segment longer than the window never hides the next one (sparse planner paths): a robot
    # past the corner of a 3 m segment finds the segment after it
    sparse = np.array([[5.0, 0.0], [2.0, 0.0], [1.9, 0.4], [1.9, 5.0]])
    c = closest_point(sparse, 1.95, 0.6, start_index=0, max_arc=1.0)
    assert c.index == 2 and c.x == pytest.approx(1.9) and c.y == pytest.approx(0.6)
    single = closest_point(np.array([[1.0, 1.0]]), 1.0, 2.0)
    assert single.distance == 1.0


def test_point_at_arc():
    assert point_at_arc(L_PATH, -1.0).s == 0.0
    mid = point_at_arc(L_PATH, 5.0)
    assert (mid.x, mid.y, mid.index) == (3.0, 2.0, 1)
    end = point_at_arc(L_PATH, 99.0)
    assert (end.x, end.y, end.index) == (3.0, 4.0, 2)


def test_lookahead_on_circle():
    start = closest_point(L_PATH, 1.0, 0.0)
    carrot = lookahead_point(L_PATH, 1.0, 0.0, 1.5, start=start)
    assert (carrot.x, carrot.y) == pytest.approx((2.5, 0.0))
    # around the corner: distance from the robot is exactly the lookahead
    carrot = lookahead_point(L_PATH, 2.0, 0.0, 2.0, start=closest_point(L_PATH, 2.0, 0.0))
    assert math.hypot(carrot.x - 2.0, carrot.y) == pytest.approx(2.0)
    assert carrot.x == pytest.approx(3.0) and carrot.index == 1
    assert carrot.s == pytest.approx(3.0 + carrot.y)
    # everything left is inside the circle: the end
    end = lookahead_point(L_PATH, 3.0, 3.0, 5.0, start=closest_point(L_PATH, 3.0, 3.0))
    assert (end.x, end.y) == (3.0, 4.0)
    # robot off the path: carrot still on the path at the lookahead distance
    off = lookahead_point(L_PATH, 1.0, 0.5, 1.0, start=closest_point(L_PATH, 1.0, 0.5))
    assert off.y == 0.0 and math.hypot(off.x - 1.0, 0.5) == pytest.approx(1.0)


def test_prune_passed():
    rest, index = prune_passed(L_PATH, 3.2, 1.0)
    assert index == 1
    assert rest.tolist() == [[3.0, 1.0], [3.0, 4.0]]
    last, index = prune_passed(L_PATH, 3.0, 5.0)
    assert last.tolist() == [[3.0, 4.0]] and index == 1
