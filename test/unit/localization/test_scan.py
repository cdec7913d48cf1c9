"""Which beams an update uses: invalid ones dropped beam by beam, the rest thinned evenly, end points in the robot
frame; malformed scans refused."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.localization import ScanBeams
from flex_nav.localization.scan import select_beams


def scan(ranges, angles=None, laser_pose=(0.0, 0.0, 0.0), range_min=0.1, range_max=5.0):
    ranges = np.asarray(ranges, dtype=float)
    if angles is None:
        angles = np.linspace(-1.0, 1.0, ranges.size)
    return ScanBeams(ranges, np.asarray(angles, dtype=float), laser_pose, range_min, range_max)


def test_invalid_beams_are_dropped_and_counted():
    ranges = [1.0, math.nan, math.inf, -math.inf, 0.05, 5.0, 7.0, 2.0]  # 0.05 < min, 5.0 == max, 7.0 > max
    beams = select_beams(scan(ranges, angles=np.zeros(8)), max_beams=10)
    assert beams.dropped == 6
    np.testing.assert_allclose(beams.x, [1.0, 2.0])
    np.testing.assert_allclose(beams.y, [0.0, 0.0])


def test_valid_beams_are_thinned_evenly_first_and_last_kept():
    angles = np.radians(np.arange(100.0))
    beams = select_beams(scan(np.ones(100), angles), max_beams=12)
    used = np.degrees(np.arctan2(beams.y, beams.x))
    np.testing.assert_allclose(used, np.round(np.linspace(0, 99, 12)), atol=1e-9)
    assert beams.dropped == 0


def test_thinning_counts_only_valid_beams():
    ranges = np.ones(100)
    ranges[:50] = np.inf  # half the scan sees nothing
    beams = select_beams(scan(ranges, np.radians(np.arange(100.0))), max_beams=10)
    assert beams.x.size == 10 and beams.dropped == 50
    used = np.degrees(np.arctan2(beams.y, beams.x))
    assert used.min() == pytest.approx(50.0) and used.max() == pytest.approx(99.0)


def test_end_points_in_the_robot_frame_through_the_laser_mount():
    beams = select_beams(scan([2.0], angles=[0.0], laser_pose=(0.2, -0.1, math.pi / 2)), max_beams=5)
    assert beams.x[0] == pytest.approx(0.2)
    assert beams.y[0] == pytest.approx(1.9)


@pytest.mark.parametrize(
    ("bad", "message"),
    [
        ({"angles": np.zeros(3)}, "scan: 4 ranges but 3 angles"),
        ({"angles": [0.0, math.nan, 0.0, 0.0]}, "scan: beam angles must be finite"),
        ({"laser_pose": (0.0, math.inf, 0.0)}, "scan: laser_pose must be a finite"),
        ({"range_min": 5.0, "range_max": 5.0}, "scan: need 0 <= range_min < range_max"),
        ({"range_max": math.inf}, "scan: need 0 <= range_min < range_max"),
    ],
)
def test_malformed_scans_are_refused(bad, message):
    with pytest.raises(ConfigError, match=message.replace("(", r"\(")):
        select_beams(scan(np.ones(4), **bad), max_beams=5)
