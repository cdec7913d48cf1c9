"""GraphSlam on the synthetic room: keyframes, a drifting loop closed, the map rebuilt on the optimised poses,
serialization, re-anchoring after the odometry broke off, and bad input."""

import math
from dataclasses import replace

import numpy as np
import pytest
from unit.localization.room import asymmetric_room, path_poses, scan_at, wall_cells_near_truth

from flex_nav.exceptions import ConfigError
from flex_nav.localization import ScanBeams
from flex_nav.mapping.slam import GraphSlam, SlamParams
from flex_nav.nav.planar import compose_poses, inverse_pose

LOOP = [(1.2, 1.2), (5.8, 1.2), (5.8, 2.4), (3.6, 2.4), (3.6, 3.9), (1.2, 3.9), (1.2, 1.2), (4.0, 1.2)]


@pytest.fixture(scope="module")
def room():
    return asymmetric_room()


def drive(slam, room, poses, seed=0, yaw_bias=0.02):
    """Feed the mapper a scan at every pose with odometry whose heading drifts ``yaw_bias`` [rad/m]; returns the true
    poses of the keyframes and the odometry poses given."""
    rng = np.random.default_rng(seed)
    odom = poses[0]
    truth_of_keyframes, odoms = [], []
    for index, after in enumerate(poses):
        if index:
            dx, dy, dyaw = compose_poses(inverse_pose(poses[index - 1]), after)
            odom = compose_poses(odom, (dx * (1 + 0.01 * rng.standard_normal()), dy,
                                        dyaw + yaw_bias * math.hypot(dx, dy) + 0.002 * rng.standard_normal()))
        odoms.append(odom)
        if slam.add_scan(odom, scan_at(room, after, rng, 0.01), stamp_s=SCAN_PERIOD_S * index):
            truth_of_keyframes.append(after)
    return truth_of_keyframes, odoms


SCAN_PERIOD_S = 0.1  # [s] the stamps drive() gives its scans


def reanchoring(slam):
    """Read through a call: mypy would carry one assertion's narrowing of the property into the next."""
    return slam.reanchoring


def rmse(slam, truth):
    poses = slam.poses()
    return math.sqrt(np.mean([(p[0] - t[0]) ** 2 + (p[1] - t[1]) ** 2 for p, t in zip(poses, truth)]))


@pytest.fixture(scope="module")
def closed_and_open(room):
    poses = path_poses(LOOP)
    results = {}
    for closing in (True, False):
        slam = GraphSlam(replace(SlamParams(), do_loop_closing=closing, loop_minimum_travel=8.0))
        truth, _ = drive(slam, room, poses)
        results[closing] = (slam, truth)
    return results


def test_keyframes_come_every_minimum_travel(room):
    slam = GraphSlam()
    step = 0.05  # [m] between scans
    poses = [(1.0 + step * i, 1.2, 0.0) for i in range(21)]  # 1 m
    truth, _ = drive(slam, room, poses, yaw_bias=0.0)
    assert len(slam.keyframes) == len(truth) >= 4
    gaps = np.diff([k.odom[0] for k in slam.keyframes])
    travel = SlamParams().minimum_travel_distance
    assert np.all(gaps >= travel - 0.01) and np.all(gaps <= travel + step + 1e-9), gaps


def test_a_drifting_loop_is_closed_and_the_error_falls(closed_and_open):
    slam, truth = closed_and_open[True]
    unclosed, _ = closed_and_open[False]
    assert slam.loop_closures, f"no loop closed ({slam.rejected_loops} candidates rejected)"
    assert rmse(slam, truth) < 0.03
    assert rmse(slam, truth) < 0.75 * rmse(unclosed, truth)


def test_the_map_is_rebuilt_on_the_optimised_poses(room, closed_and_open):
    slam, _truth = closed_and_open[True]
    # the map frame is the first keyframe's odometry frame, which the drive started at the true first pose
    count, near = wall_cells_near_truth(room, slam.occupancy_map())
    assert count > 300
    assert near > 0.97, near


def test_map_to_odom_places_the_last_keyframe(closed_and_open):
    slam, _ = closed_and_open[True]
    last = slam.keyframes[-1]
    placed = compose_poses(slam.map_to_odom(), last.odom)
    np.testing.assert_allclose(placed, slam.poses()[-1], atol=1e-9)


def test_serialization_round_trip(closed_and_open):
    slam, _ = closed_and_open[True]
    again = GraphSlam.from_dict(slam.to_dict())
    np.testing.assert_allclose(again.poses(), slam.poses(), atol=1e-9)
    assert len(again.keyframes) == len(slam.keyframes)
    assert again.loop_closures == slam.loop_closures
    np.testing.assert_array_equal(again.occupancy_map().occupancy, slam.occupancy_map().occupancy)
    assert [k.stamp for k in again.keyframes] == [k.stamp for k in slam.keyframes]


def test_keyframes_keep_their_scans_stamps_and_old_files_load_without(closed_and_open):
    slam, truth = closed_and_open[True]
    poses = path_poses(LOOP)
    for keyframe, true_pose in zip(slam.keyframes, truth):  # the stamp names the scan the keyframe was made of
        assert poses[round(keyframe.stamp / SCAN_PERIOD_S)] == true_pose
    data = slam.to_dict()
    for k in data["keyframes"]:
        del k["stamp"]  # a file from before stamps were kept
    assert all(math.isnan(k.stamp) for k in GraphSlam.from_dict(data).keyframes)


def test_a_bad_file_is_refused():
    with pytest.raises(ConfigError, match="not a flex_nav pose graph"):
        GraphSlam.from_dict({"keyframes": []})
    with pytest.raises(ConfigError, match="malformed"):
        GraphSlam.from_dict({"format": "flex_nav.mapping.posegraph/1", "keyframes": [{"odom": [0, 0]}]})


def test_after_an_odometry_break_scans_are_placed_by_matching(room):
    slam = GraphSlam()
    poses = path_poses([(1.2, 1.2), (3.0, 1.2)])
    drive(slam, room, poses, yaw_bias=0.0)
    count = len(slam.keyframes)
    slam.restart_odometry()
    assert reanchoring(slam)
    # the odometry restarted at zero, the robot 30 cm further on: placed where it is, not at the odometry's pose
    truth = (poses[-1][0] + 0.3, poses[-1][1], 0.0)
    assert slam.add_scan((0.0, 0.0, 0.0), scan_at(room, truth))
    assert not reanchoring(slam) and len(slam.keyframes) == count + 1
    assert math.dist(slam.poses()[-1][:2], truth[:2]) < 0.03
    # and the next scans follow the new odometry
    after = (truth[0] + 0.25, truth[1], 0.0)
    assert slam.add_scan((0.25, 0.0, 0.0), scan_at(room, after))
    assert math.dist(slam.poses()[-1][:2], after[:2]) < 0.03


def test_a_scan_that_fits_nowhere_near_is_not_placed_after_a_break(room):
    slam = GraphSlam()
    drive(slam, room, path_poses([(1.2, 1.2), (3.0, 1.2)]), yaw_bias=0.0)
    slam.restart_odometry()
    count = len(slam.keyframes)
    assert not slam.add_scan((0.0, 0.0, 0.0), scan_at(room, (2.0, 3.8, math.pi)))  # another room part
    assert reanchoring(slam) and len(slam.keyframes) == count


def test_bad_input_names_the_value_and_keeps_the_graph(room):
    slam = GraphSlam()
    assert slam.add_scan((1.2, 1.2, 0.0), scan_at(room, (1.2, 1.2, 0.0)))
    with pytest.raises(ConfigError, match="odometry pose"):
        slam.add_scan((math.nan, 0.0, 0.0), scan_at(room, (1.2, 1.2, 0.0)))
    with pytest.raises(ConfigError, match="range_min < range_max"):
        slam.add_scan((1.5, 1.2, 0.0), ScanBeams(np.ones(3), np.zeros(3), (0.0, 0.0, 0.0), 2.0, 1.0))
    with pytest.raises(ConfigError, match="3 ranges but 2 angles"):
        slam.add_scan((1.5, 1.2, 0.0), ScanBeams(np.ones(3), np.zeros(2), (0.0, 0.0, 0.0), 0.1, 5.0))
    assert len(slam.keyframes) == 1
    scan = scan_at(room, (1.5, 1.2, 0.0))
    ranges = scan.ranges.copy()
    ranges[::3] = np.nan
    assert slam.add_scan((1.5, 1.2, 0.0), scan._replace(ranges=ranges))  # NaN beams: dropped, the scan used
    assert len(slam.keyframes) == 2


def test_parameters_are_validated():
    with pytest.raises(ConfigError, match="loop_match_uniqueness_ratio"):
        SlamParams(loop_match_uniqueness_ratio=1.5)
    with pytest.raises(ConfigError, match="scan_buffer_size"):
        SlamParams(scan_buffer_size=0)
    with pytest.raises(ConfigError, match="do_loop_closing"):
        SlamParams(do_loop_closing="yes")  # type: ignore[arg-type]
