"""Do the scans fit the map where the filter puts the robot? The scan-consistency check behind LOST and its end.

The particle spread alone misses a kidnapped robot: resampling keeps the cloud tight wherever it is, and a tight
cloud in the wrong place tracks the odometry happily while no scan fits it. The check looks at the evidence
instead: after each sensor update, the **match fraction** is the share of the update's beams whose end point, seen
from the estimated pose, lies within ``lost_match_distance`` [m] of an obstacle's edge in the map (the likelihood
field's :attr:`~flex_nav.localization.likelihood_field.LikelihoodField.edge_distance`; end points in unknown cells
or outside the map do not match). On the right pose nearly every beam of a mapped scene matches; unmapped things
(a box, people) take away the beams they block, and a pose metres off matches only the beams that happen to end
near some wall.

:class:`MatchHistory` keeps the fractions of the last ``lost_match_updates`` updates. A LOCALIZED filter is LOST
when their mean is below ``lost_match_fraction``; a LOST one is LOCALIZED again only when the cloud is tight *and*
their mean reaches ``converged_match_fraction`` (higher, so that a cloud which settled near but not on the pose,
e.g. 25 cm off after a global localization standing still, does not count as converged). Updates while the cloud
is wide (the model's Gaussian annealed wider than laser_sigma_hit: the mean pose is then only a rough guess) clear
the history: only consecutive updates of a tight cloud are judged.

A standing robot can see a scene that does not pin its pose (a wall and little else: every pose along the wall
fits as well). Repeated no-motion updates then settle the cloud somewhere along the ambiguity, tight and matching.
So the return to LOCALIZED also asks that the estimate be **distinct** (:func:`distinct_fit`): the scan must fit it
better, by ``PROBE_MARGIN`` in the sensor model's log-likelihood, than it fits any of the poses ``PROBE_XY`` away
(four directions) or ``PROBE_YAW`` turned. An estimate that far from the truth has the truth, or a pose as good,
among its probes; an ambiguous pose stays LOST (the robot has to move to resolve it). And it asks that the rays be
**clear** (:func:`clear_fraction` at least ``CONVERGED_CLEAR_FRACTION``): the likelihood field scores an end point
by its distance to the nearest obstacle edge, whichever side of the obstacle it is on, so a pose a wall's thickness
too far fits the scan of a thin wall from behind it (measured in the lab, standing next to an unmapped box: 10.8 cm
north of the truth, 34 of 60 rays through the north wall; on the right poses of the lab lap and the push_or_avoid
worlds at least 78 % of the rays were clear, 92 % but for the TurtleBot 2 among people in s6).
"""

from __future__ import annotations

import math
from collections import deque
from typing import Deque, Tuple

import numpy as np

from flex_nav.localization.jit import Kernel
from flex_nav.localization.likelihood_field import LikelihoodField
from flex_nav.localization.scan import SelectedBeams
from flex_nav.localization.sensor_model import SensorModel
from flex_nav.nav.planar import Pose2D

PROBE_XY = 0.1  # [m] an estimate must fit the scan better than the poses this far away ...
PROBE_YAW = math.radians(5.0)  # [rad] ... and than the poses turned this far ...
PROBE_MARGIN = 3.0  # [-] ... by this much in the (tempered) log-likelihood of the scan, at laser_sigma_hit
CONVERGED_CLEAR_FRACTION = 0.75  # [-] share of the rays that must not cross a wall (clear_fraction) to converge


def match_fraction(field: LikelihoodField, pose: Pose2D, beams: SelectedBeams, match_distance: float) -> float:
    """Share of ``beams`` (end points in the robot frame) whose end point, with the robot at ``pose`` (map frame),
    lies in a known cell within ``match_distance`` [m] of an obstacle's edge; NaN for no beams."""
    if beams.x.size == 0:
        return float("nan")
    gx0, gy0, c, s, bx, by = _grid_frame(field, pose, beams)
    gx = gx0 + c * bx - s * by
    gy = gy0 + s * bx + c * by
    height, width = field.shape
    inside = (gx >= 0.0) & (gx < width) & (gy >= 0.0) & (gy < height)
    cols = np.where(inside, gx, 0.0).astype(np.int64)
    rows = np.where(inside, gy, 0.0).astype(np.int64)
    near = inside & field.known[rows, cols] & (field.edge_distance[rows, cols] <= match_distance)
    return float(np.count_nonzero(near)) / float(beams.x.size)


def clear_fraction(field: LikelihoodField, pose: Pose2D, beams: SelectedBeams, skip: float) -> float:
    """Share of ``beams`` whose ray, from the robot at ``pose`` (its origin: the laser sits within a few cm) to
    ``skip`` [m] short of the end point, crosses no occupied cell (sampled every half cell); NaN for no beams. A pose
    that puts end points on the far side of a wall (a thin wall fits from either side) shows it here."""
    if beams.x.size == 0:
        return float("nan")
    gx0, gy0, c, s, bx, by = _grid_frame(field, pose, beams)
    length = np.hypot(bx, by)  # [cells]
    reach = np.maximum(length - skip / field.grid.resolution, 0.0) / np.maximum(length, 1e-9)  # [-] of each ray
    t = np.arange(0.0, float(length.max()) + 0.5, 0.5)[None, :] / np.maximum(length, 1e-9)[:, None]  # (M, S)
    inside_ray = t <= reach[:, None]
    ex, ey = c * bx - s * by, s * bx + c * by
    gx = gx0 + t * ex[:, None]
    gy = gy0 + t * ey[:, None]
    height, width = field.shape
    on_grid = inside_ray & (gx >= 0.0) & (gx < width) & (gy >= 0.0) & (gy < height)
    rows = np.where(on_grid, gy, 0.0).astype(np.int64)
    cols = np.where(on_grid, gx, 0.0).astype(np.int64)
    blocked = (on_grid & field.occupied[rows, cols]).any(axis=1)
    return 1.0 - float(np.count_nonzero(blocked)) / float(beams.x.size)


def _grid_frame(
    field: LikelihoodField, pose: Pose2D, beams: SelectedBeams
) -> Tuple[float, float, float, float, np.ndarray, np.ndarray]:
    """The robot's position in grid coordinates [cells], its heading's cosine and sine relative to the grid, and
    the beam end points in the robot frame in cells."""
    grid = field.grid
    ox, oy, oyaw = grid.origin
    x, y, yaw = pose
    co, so = math.cos(oyaw), math.sin(oyaw)
    gx0 = (co * (x - ox) + so * (y - oy)) / grid.resolution
    gy0 = (-so * (x - ox) + co * (y - oy)) / grid.resolution
    return (gx0, gy0, math.cos(yaw - oyaw), math.sin(yaw - oyaw), beams.x / grid.resolution,
            beams.y / grid.resolution)


def distinct_fit(
    model: SensorModel, pose: Pose2D, beams: SelectedBeams, range_max: float, kernel: Kernel = Kernel.NUMBA
) -> bool:
    """True when the scan (``beams``, ``range_max`` [m]) fits ``pose`` better by PROBE_MARGIN than every probe pose
    PROBE_XY [m] away along x or y or PROBE_YAW [rad] turned (see the module docstring)."""
    if beams.x.size == 0:
        return False
    x, y, yaw = pose
    poses = np.array([
        (x, y, yaw), (x + PROBE_XY, y, yaw), (x - PROBE_XY, y, yaw), (x, y + PROBE_XY, yaw), (x, y - PROBE_XY, yaw),
        (x, y, yaw + PROBE_YAW), (x, y, yaw - PROBE_YAW),
    ])
    scores = model.log_likelihoods(poses, beams, range_max, None, kernel)
    return bool(scores[0] - float(scores[1:].max()) >= PROBE_MARGIN)


class MatchHistory:
    """The match fractions of the last ``length`` judged updates."""

    def __init__(self, length: int) -> None:
        self._fractions: Deque[float] = deque(maxlen=length)

    def add(self, fraction: float) -> None:
        self._fractions.append(fraction)

    def clear(self) -> None:
        self._fractions.clear()

    @property
    def full(self) -> bool:
        return len(self._fractions) == self._fractions.maxlen

    def mean(self) -> float:
        """Mean of the fractions kept; NaN if none."""
        return float(np.mean(self._fractions)) if self._fractions else float("nan")
