"""A laser scan as the localizer takes it, and the choice of the beams one update uses.

Invalid beams (NaN, ±inf, shorter than ``range_min``, at or beyond ``range_max``) are dropped one by one:
a max-range reading says only that nothing was hit, which the likelihood field cannot score, so it is
skipped as amcl's likelihood-field model skips it. Of the valid beams, ``max_beams`` evenly spaced ones (by
index, first and last included) are kept. Dropping before thinning (amcl thins first) keeps ``max_beams``
beams in the update when part of the scan sees nothing, e.g. a robot facing an open doorway.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.planar import Pose2D


class ScanBeams(NamedTuple):
    """One scan: ranges and their directions, and where the laser sits on the robot."""

    ranges: np.ndarray  # (K,) [m] as received (may hold NaN/inf/out-of-range)
    angles: np.ndarray  # (K,) [rad] beam directions in the laser frame
    laser_pose: Pose2D  # pose of the laser in the robot base frame
    range_min: float  # [m]
    range_max: float  # [m]


class SelectedBeams(NamedTuple):
    """The beams an update uses, as end points in the robot frame for the range measured."""

    x: np.ndarray  # (M,) [m] end points in the robot base frame
    y: np.ndarray  # (M,) [m]
    dropped: int  # beams of the scan that were invalid


def select_beams(scan: ScanBeams, max_beams: int) -> SelectedBeams:
    """The valid beams of ``scan``, thinned to at most ``max_beams`` evenly spaced ones, as robot-frame end
    points. :class:`ConfigError` if ranges and angles differ in shape, a beam angle or the laser pose is not
    finite, or the range limits are not 0 <= range_min < range_max."""
    ranges = np.asarray(scan.ranges, dtype=np.float64).ravel()
    angles = np.asarray(scan.angles, dtype=np.float64).ravel()
    if ranges.shape != angles.shape:
        raise ConfigError(f"scan: {ranges.size} ranges but {angles.size} angles")
    if not np.isfinite(angles).all():
        raise ConfigError("scan: beam angles must be finite")
    if len(scan.laser_pose) != 3 or not np.isfinite(np.asarray(scan.laser_pose, dtype=np.float64)).all():
        raise ConfigError(f"scan: laser_pose must be a finite (x, y, yaw), got {scan.laser_pose!r}")
    range_min, range_max = float(scan.range_min), float(scan.range_max)
    if not (np.isfinite(range_min) and np.isfinite(range_max) and 0.0 <= range_min < range_max):
        raise ConfigError(f"scan: need 0 <= range_min < range_max (finite), got {range_min!r}, {range_max!r}")
    with np.errstate(invalid="ignore"):
        valid = np.isfinite(ranges) & (ranges >= range_min) & (ranges < range_max)
    index = np.flatnonzero(valid)
    dropped = int(ranges.size - index.size)
    if index.size > max_beams:
        index = index[np.rint(np.arange(max_beams) * ((index.size - 1) / (max_beams - 1))).astype(np.int64)]
    lx, ly, lyaw = (float(v) for v in scan.laser_pose)
    r = ranges[index]
    direction = lyaw + angles[index]
    return SelectedBeams(lx + r * np.cos(direction), ly + r * np.sin(direction), dropped)
