"""Progress of a robot along a goal path, for the follow servers (mid-level planners).

The follow servers do not drive: at each replanning step they ask where the robot is along the goal path
and which point ``lookahead_distance`` [m] further along the path (arc length, not cells, not straight
line) they should plan to. The closest point is tracked monotonically inside a bounded window, so a path
that loops back near its start is not taken as finished when the robot starts, and a robot that drifts
does not jump to a far part of the path that passes nearby.

The goal's position counts as reached when the robot is within ``goal_tolerance`` [m] (straight line) of the
path's last pose and the tracked point is within ``goal_tolerance`` of the end along the path; the goal is
reached when, in addition, the robot's yaw is within ``yaw_goal_tolerance`` [rad] of the last pose's yaw
(move_base's goal check; ``yaw_goal_tolerance`` None: the position alone). Until then the target stays the
path's end, carrying its yaw, so a plan to it makes the controller turn in place there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Optional, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.path import as_path, closest_point, cumulative_lengths, point_at_arc
from flex_nav.nav.planar import heading_along

BACKOFF_STEPS = 64  # resolution of the search for a target inside the planning area


@dataclass(frozen=True)
class Progress:
    """Where the robot is along the path and where to plan to next."""

    done: bool  # the goal is reached: position and, when it counts, heading
    position_reached: bool  # within goal_tolerance of the path's end (the heading may still be off)
    heading_error: float  # [rad] the last pose's yaw minus the robot's, wrapped (nan when the heading is ignored)
    target: Tuple[float, float, float]  # (x [m], y [m], yaw [rad]) to plan to (the path's end when close)
    target_is_end: bool  # the target is the path's last pose
    travelled: float  # [m] arc length from the path's start to the robot's closest point
    remaining: float  # [m] arc length from there to the end
    distance_to_end: float  # [m] straight line from the robot to the last pose
    cross_track: float  # [m] from the robot to the path


class PathProgress:
    """Tracks one goal path; see the module docstring."""

    def __init__(self, poses: object, lookahead_distance: float, goal_tolerance: float,
                 yaw_goal_tolerance: Optional[float] = None) -> None:
        for name, value in (("lookahead_distance", lookahead_distance), ("goal_tolerance", goal_tolerance)):
            if not math.isfinite(value) or value <= 0.0:
                raise ConfigError(f"{name} must be a finite number > 0 [m], got {value!r}")
        if yaw_goal_tolerance is not None and not (math.isfinite(yaw_goal_tolerance) and yaw_goal_tolerance > 0.0):
            raise ConfigError(
                f"yaw_goal_tolerance must be None or a finite number > 0 [rad], got {yaw_goal_tolerance!r}")
        path = as_path(poses)
        if path.shape[1] == 2:
            path = np.column_stack([path, heading_along(path)])
        self.path = path
        self.lengths = cumulative_lengths(path)
        self.length = float(self.lengths[-1])
        self.lookahead_distance = lookahead_distance
        self.goal_tolerance = goal_tolerance
        self.yaw_goal_tolerance = yaw_goal_tolerance  # [rad] None: the final heading is no goal
        self._index = 0
        self._fresh = True

    def update(self, x: float, y: float, inside: Optional[Callable[[float, float], bool]] = None,
               yaw: Optional[float] = None) -> Progress:
        """Progress for the robot at (x [m], y [m]) facing ``yaw`` [rad] (needed when ``yaw_goal_tolerance`` is
        set). ``inside(x, y)`` (optional) says whether a point can be planned to (e.g. lies on a rolling
        costmap); the target backs off along the path until it does."""
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ConfigError(f"robot position must be finite, got ({x!r}, {y!r})")
        heading_error = math.nan
        if self.yaw_goal_tolerance is not None:
            if yaw is None or not math.isfinite(yaw):
                raise ConfigError(f"robot yaw must be finite when the final heading counts, got {yaw!r}")
            heading_error = wrap_angle(float(self.path[-1, 2]) - yaw)
        window = math.inf if self._fresh else 2.0 * self.lookahead_distance + self.goal_tolerance
        closest = closest_point(self.path, x, y, start_index=self._index, max_arc=window, lengths=self.lengths,
                                earliest_within=self.goal_tolerance if self._fresh else 0.0)
        self._fresh = False
        self._index = closest.index
        end_x, end_y = float(self.path[-1, 0]), float(self.path[-1, 1])
        to_end = math.hypot(end_x - x, end_y - y)
        remaining = self.length - closest.s
        position_reached = to_end <= self.goal_tolerance and remaining <= self.goal_tolerance + 1e-9
        done = position_reached and (self.yaw_goal_tolerance is None
                                     or abs(heading_error) <= self.yaw_goal_tolerance)
        target_s = min(closest.s + self.lookahead_distance, self.length)
        if inside is not None:
            target_s = self._inside_arc(closest.s, target_s, inside)
        target = self._pose_at(target_s)
        return Progress(
            done=done,
            position_reached=position_reached,
            heading_error=heading_error,
            target=target,
            target_is_end=target_s >= self.length,
            travelled=float(closest.s),
            remaining=float(remaining),
            distance_to_end=to_end,
            cross_track=closest.distance,
        )

    def _pose_at(self, s: float) -> Tuple[float, float, float]:
        if s >= self.length:
            return (float(self.path[-1, 0]), float(self.path[-1, 1]), float(self.path[-1, 2]))
        point = point_at_arc(self.path, s, self.lengths)
        return (point.x, point.y, float(self.path[point.index, 2]))

    def _inside_arc(self, s_from: float, s_to: float, inside: Callable[[float, float], bool]) -> float:
        """The largest arc length in [s_from, s_to] whose point is inside (checked in BACKOFF_STEPS steps)."""
        for k in range(BACKOFF_STEPS + 1):
            s = s_to - (s_to - s_from) * k / BACKOFF_STEPS
            x, y, _ = self._pose_at(s)
            if inside(x, y):
                return s
        return s_from
