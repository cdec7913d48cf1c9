"""Scan segments, the static mask and the moving-obstacle tracker on synthetic scans (no ROS)."""

import math

import numpy as np
import pytest
from unit.perception.scan_synth import ray_scan

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.perception.moving_obstacles import MovingObstacleTracker, TrackerParams
from flex_nav.perception.scan_segments import SegmentParams, segments
from flex_nav.perception.static_mask import StaticMask


def test_a_round_body_gives_one_segment_at_its_centre():
    xs, ys = ray_scan((0.0, 0.0), [(2.0, 1.0, 0.2)])
    found = segments(xs, ys, (0.0, 0.0), SegmentParams(), wrap=True)
    assert len(found) == 1
    seg = found[0]
    assert math.hypot(seg.x - 2.0, seg.y - 1.0) < 0.05  # centre, not the visible front
    assert 0.12 <= seg.radius <= 0.25


def test_walls_are_too_wide_and_two_people_stay_apart():
    xs, ys = ray_scan((5.0, 5.0), [(6.0, 5.0, 0.2), (5.0, 3.5, 0.2)], room=(0.0, 0.0, 10.0, 10.0))
    found = segments(xs, ys, (5.0, 5.0), SegmentParams(), wrap=True)
    centres = sorted((round(s.x, 1), round(s.y, 1)) for s in found)
    assert centres == [(5.0, 3.5), (6.0, 5.0)]


def test_segment_parameters_are_validated():
    with pytest.raises(ConfigError, match="max_width_m"):
        SegmentParams(max_width_m=0.0)
    with pytest.raises(ConfigError, match="max_radius_m"):
        SegmentParams(min_radius_m=0.3, max_radius_m=0.2)


def room_grid():
    occ = np.zeros((200, 200), dtype=np.int8)  # 10 x 10 m at 0.05 m
    occ[0, :] = occ[-1, :] = occ[:, 0] = occ[:, -1] = 100
    return GridMap(occ, 0.05, (0.0, 0.0, 0.0))


def test_static_mask_explains_wall_points_only():
    mask = StaticMask(room_grid(), 0.15)
    assert mask.explained(np.array([0.1, 9.9, 5.0, 0.3]), np.array([5.0, 5.0, 5.0, 5.0])).tolist() == [
        True, True, False, False]
    assert not mask.explained(np.array([-3.0]), np.array([5.0]))[0]  # off the map
    with pytest.raises(ConfigError, match="tolerance"):
        StaticMask(room_grid(), -0.1)


def walk(tracker, sensor, people, times, room=None):
    """Feed scans of people [(x0, y0, vx, vy)] at ``times``; return the tracks at the last time."""
    for t in times:
        circles = [(x0 + vx * t, y0 + vy * t, 0.2) for x0, y0, vx, vy in people]
        xs, ys = ray_scan(sensor, circles, room)
        tracker.update_scan(xs, ys, sensor, t)
    return tracker.tracks(times[-1])


def test_tracks_a_walking_person_position_velocity_radius():
    tracker = MovingObstacleTracker()
    times = np.arange(0.0, 3.0, 1.0 / 5.5)
    tracks = walk(tracker, (1.0, 5.0), [(3.0, 2.0, 0.0, 0.8)], times)
    assert len(tracks) == 1
    tr = tracks[0]
    t_end = times[-1]
    assert math.hypot(tr.x - 3.0, tr.y - (2.0 + 0.8 * t_end)) < 0.1
    assert tr.vx == pytest.approx(0.0, abs=0.1) and tr.vy == pytest.approx(0.8, abs=0.1)
    assert 0.12 <= tr.radius <= 0.25


def test_a_standing_object_is_a_slow_track_and_walls_are_no_track():
    tracker = MovingObstacleTracker(static_mask=StaticMask(room_grid(), 0.15))
    times = np.arange(0.0, 2.0, 1.0 / 5.5)
    tracks = walk(tracker, (1.0, 5.0), [(4.0, 5.0, 0.0, 0.0), (6.0, 2.0, -0.5, 0.6)], times,
                  room=(0.0, 0.0, 10.0, 10.0))
    assert len(tracks) == 2
    standing = min(tracks, key=lambda t: t.speed)
    walking = max(tracks, key=lambda t: t.speed)
    assert standing.speed < 0.05 and math.hypot(standing.x - 4.0, standing.y - 5.0) < 0.05
    assert walking.vx == pytest.approx(-0.5, abs=0.1) and walking.vy == pytest.approx(0.6, abs=0.1)


def test_two_people_crossing_keep_their_identities():
    tracker = MovingObstacleTracker()
    # both pass x = 3 at t = 2.5 s, 1 m apart in y; the one going north stays the same track
    times = np.arange(0.0, 4.0, 1.0 / 5.5)
    walk(tracker, (0.0, 5.0), [(3.0, 3.0, 0.0, 0.8), (5.5, 6.0, -1.0, 0.0)], times[:3])
    first = {t.track_id: t for t in tracker.tracks(times[2])}
    north_id = min(first.values(), key=lambda t: abs(t.x - 3.0)).track_id
    tracks = walk(tracker, (0.0, 5.0), [(3.0, 3.0, 0.0, 0.8), (5.5, 6.0, -1.0, 0.0)], times[3:])
    north = [t for t in tracks if t.track_id == north_id]
    assert len(north) == 1 and north[0].vy == pytest.approx(0.8, abs=0.15)


def test_unseen_track_is_dropped_and_clock_reset_forgets():
    params = TrackerParams(max_missed_s=0.5)
    tracker = MovingObstacleTracker(params)
    times = np.arange(0.0, 1.0, 0.2)
    assert len(walk(tracker, (0.0, 0.0), [(2.0, 0.0, 0.0, 0.5)], times)) == 1
    empty = (np.full(360, np.nan), np.full(360, np.nan))
    tracker.update_scan(*empty, (0.0, 0.0), 1.2)
    assert len(tracker.tracks(1.2)) == 1  # coasting
    assert tracker.tracks(1.2)[0].y == pytest.approx(0.5 * 1.2, abs=0.1)
    tracker.update_scan(*empty, (0.0, 0.0), 1.6)
    assert tracker.tracks(1.6) == []
    walk(tracker, (0.0, 0.0), [(2.0, 0.0, 0.0, 0.5)], np.arange(2.0, 3.0, 0.2))
    assert len(tracker.tracks(3.0)) == 1
    walk(tracker, (0.0, 0.0), [(2.0, 0.0, 0.0, 0.5)], [0.0])  # the clock went back: start over
    assert tracker.tracks(0.0) == []


def test_tracker_parameters_are_validated():
    with pytest.raises(ConfigError, match="gate_m"):
        TrackerParams(gate_m=-1.0)
    with pytest.raises(ConfigError, match="confirm_hits"):
        TrackerParams(confirm_hits=0)
    with pytest.raises(ConfigError, match="finite"):
        MovingObstacleTracker().update([], math.nan)
