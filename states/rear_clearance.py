"""Is the way behind (or ahead of) the robot free? A laser scan's points in the corridor a robot driving
straight sweeps.

Used by :class:`~flex_nav_states.move_distance_state.MoveDistanceState` when it backs up with a ``scan_topic``,
and by :class:`~flex_nav_states.push_state.PushState` for the gap to the object it is about to push and whether
it is still in a passage.
The scan's frame is taken as the robot's base frame (x forward, y left): a lidar mounted near the centre of a
round base, as on the TurtleBot 2 and 4, within a few centimetres that the clearance covers.
"""

from __future__ import annotations

from typing import Any, Optional, Tuple

import numpy as np


def gap_behind_m(scan: Any, radius_m: float, clearance_m: float, reach_m: float) -> Optional[float]:
    """[m] from the robot's back to the nearest scan point in the corridor it sweeps backing up ``reach_m``
    [m] more (width: 2 x (``radius_m`` + ``clearance_m``), length: ``reach_m`` + ``radius_m`` +
    ``clearance_m`` behind the centre), or None when that corridor is free. Returns that are not finite or
    outside [range_min, range_max] are no points."""
    return _gap_m(scan, radius_m, clearance_m, reach_m, direction=-1.0)


def gap_ahead_m(scan: Any, radius_m: float, clearance_m: float, reach_m: float) -> Optional[float]:
    """[m] from the robot's front to the nearest scan point in the corridor it sweeps driving ``reach_m`` [m]
    forward; the mirror image of :func:`gap_behind_m`."""
    return _gap_m(scan, radius_m, clearance_m, reach_m, direction=1.0)


def _returns(scan: Any) -> Tuple[np.ndarray, np.ndarray]:
    """(x, y) [m] of the scan's returns in its frame; returns that are not finite or outside [range_min,
    range_max] are no points."""
    ranges = np.asarray(scan.ranges, dtype=np.float64)
    angles = scan.angle_min + scan.angle_increment * np.arange(ranges.size)
    valid = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges <= scan.range_max)
    r, a = ranges[valid], angles[valid]
    return r * np.cos(a), r * np.sin(a)


def _gap_m(scan: Any, radius_m: float, clearance_m: float, reach_m: float, direction: float) -> Optional[float]:
    """The gap along ``direction`` (+1 ahead, -1 behind) of :func:`gap_ahead_m` / :func:`gap_behind_m`."""
    x, y = _returns(scan)
    along = direction * x  # [m] the way the robot drives
    half_width = radius_m + clearance_m
    in_way = (along > 0.0) & (np.abs(y) <= half_width) & (along <= reach_m + half_width)
    if not in_way.any():
        return None
    return max(0.0, float(np.min(along[in_way])) - radius_m)


def walled_in(scan: Any, side_m: float, behind_m: float) -> bool:
    """True when the scan has a return on both sides of the robot (left: y > 0, right: y < 0) within ``side_m``
    [m] of its centre line, beside or behind its centre down to ``behind_m`` [m] (x in [-behind_m, 0]): the robot
    is in a passage. What is ahead of the centre (an object being pushed) does not count."""
    x, y = _returns(scan)
    beside = (x <= 0.0) & (x >= -behind_m) & (np.abs(y) <= side_m)
    return bool((beside & (y > 0.0)).any() and (beside & (y < 0.0)).any())
