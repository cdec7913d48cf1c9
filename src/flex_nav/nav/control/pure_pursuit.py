"""Regulated pure pursuit (after Nav2's RegulatedPurePursuitController), as a pure per-step function.

Each :meth:`RegulatedPurePursuit.step` takes the robot pose and velocity, the elapsed time and optionally
the local costmap (all in the path's frame) and returns a :class:`Command` ``(v [m/s], w [rad/s])`` with a
:class:`PursuitStatus`. In order:

1. goal: within ``goal_dist_tol`` [m] of the last pose the robot turns in place to the final heading
   until it is within ``yaw_goal_tolerance`` [rad] of it (``use_final_heading``, a path with yaw, and
   not ``set_path(..., final_heading=False)``) and then reports GOAL_REACHED with a zero command;
2. the path is pruned to the closest point ahead (a bounded, monotonic search);
3. the carrot is where the path leaves the lookahead circle (fixed ``lookahead_dist``, or
   ``|v|·lookahead_time`` clamped to [``min_lookahead_dist``, ``max_lookahead_dist``]);
4. if the carrot's bearing exceeds ``rotate_to_heading_min_angle`` the robot rotates in place;
5. otherwise ``v`` = ``desired_linear_vel`` regulated by curvature (turn radius below
   ``regulated_linear_scaling_min_radius``) and by obstacle proximity (distance to the nearest obstacle
   recovered from the costmap cost under ``cost_scaling_dist``), floored at
   ``regulated_linear_scaling_min_speed``, then scaled down within ``approach_velocity_scaling_dist`` of
   the goal (not below ``min_approach_linear_velocity``), then limited by the acceleration limits;
   ``w = v·curvature``, with ``v`` reduced so that ``|w| <= max_angular_vel``;
6. the arc the command would drive is projected ahead (up to the carrot, at most
   ``max_allowed_time_to_collision_up_to_carrot`` [s]) and checked cell by cell on the costmap: any cell
   at or above INSCRIBED (or unknown, unless ``allow_unknown``) gives COLLISION_AHEAD and a zero command.
   A robot that already stands on an INSCRIBED (not LETHAL) cell, e.g. right after a bumper contact was
   marked at its edge, may leave: for the first ``collision_escape_dist`` [m] of the arc only LETHAL cells
   count (the planner's ``start_escape`` lets its plans leave such a start the same way).
   When the arc collides but the path itself is clear for the lookahead distance, steps 3-6 are tried
   again with the lookahead halved (down to two costmap cells): a nearer carrot keeps the arc closer to
   the planned path, which avoids what the far carrot's arc would cut into (e.g. a path that first moves
   away from a bumper contact beside the robot). Otherwise, or when every arc collides: COLLISION_AHEAD.

Every failure returns a zero command. One instance per controller (it keeps the pruning index and the
previous command); :meth:`set_path` starts a new path.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, fields, replace
from typing import Any, Mapping, Optional, Tuple

import numpy as np
from numba import njit

from flex_nav import validation
from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.control.path_obstacle import obstacle_on_path
from flex_nav.nav.costmap.costmap_grid import INSCRIBED, LETHAL, MAX_NON_OBSTACLE, NO_INFORMATION, CostmapGeometry
from flex_nav.nav.path import PathPoint, as_path, closest_point, cumulative_lengths, lookahead_point


class PursuitStatus(enum.Enum):
    """What the controller is doing, or why it stopped."""

    FOLLOWING = 0
    ROTATING_TO_PATH = 1  # turning in place towards the carrot
    ROTATING_TO_GOAL = 2  # at the goal position, turning to the final heading
    GOAL_REACHED = 3  # zero command
    COLLISION_AHEAD = 4  # zero command: the projected arc hits an obstacle
    INVALID_INPUT = 5  # zero command: no path, NaN pose/velocity, bad time step

    @property
    def moving(self) -> bool:
        """True when the command drives the robot."""
        return self in (PursuitStatus.FOLLOWING, PursuitStatus.ROTATING_TO_PATH, PursuitStatus.ROTATING_TO_GOAL)


@dataclass(frozen=True)
class Command:
    """One controller output."""

    v: float  # [m/s] forward velocity
    w: float  # [rad/s] yaw rate, counter-clockwise positive
    status: PursuitStatus
    reason: str = ""
    carrot: Optional[Tuple[float, float]] = None  # (x [m], y [m]) in the path frame
    lookahead: float = 0.0  # [m] lookahead distance used
    distance_to_goal: float = math.inf  # [m] along the path
    cross_track: float = math.inf  # [m] distance from the robot to the path


_OWNER = "pure pursuit"  # in the messages of PurePursuitParams' checks
# every number is finite and >= 0; these are > 0, and these have a maximum
_POSITIVE = frozenset({
    "desired_linear_vel",
    "max_linear_accel",
    "max_linear_decel",
    "max_angular_vel",
    "max_angular_accel",
    "lookahead_dist",
    "min_lookahead_dist",
    "rotate_to_heading_angular_vel",
    "regulated_linear_scaling_min_radius",
    "cost_scaling_dist",
    "goal_dist_tol",
    "yaw_goal_tolerance",
})
_MAXIMUM = {"cost_scaling_gain": 1.0}


@dataclass(frozen=True)
class PurePursuitParams:
    """Parameters (Nav2's names; units in comments). Build from a ROS parameter dict with :meth:`from_mapping`."""

    desired_linear_vel: float = 0.5  # [m/s]
    max_linear_accel: float = 2.5  # [m/s²]
    max_linear_decel: float = 2.5  # [m/s²]
    max_angular_vel: float = 1.8  # [rad/s]
    max_angular_accel: float = 3.2  # [rad/s²]
    lookahead_dist: float = 0.6  # [m] used when not velocity-scaled
    use_velocity_scaled_lookahead_dist: bool = False
    min_lookahead_dist: float = 0.3  # [m]
    max_lookahead_dist: float = 0.9  # [m]
    lookahead_time: float = 1.5  # [s] lookahead = |v| · lookahead_time (velocity-scaled)
    use_rotate_to_heading: bool = True
    rotate_to_heading_angular_vel: float = 1.8  # [rad/s]
    rotate_to_heading_min_angle: float = 0.785  # [rad]
    use_regulated_linear_velocity_scaling: bool = True
    regulated_linear_scaling_min_radius: float = 0.9  # [m]
    regulated_linear_scaling_min_speed: float = 0.25  # [m/s]
    use_cost_regulated_linear_velocity_scaling: bool = True
    cost_scaling_dist: float = 0.6  # [m]
    cost_scaling_gain: float = 1.0  # [-] <= 1
    inflation_cost_scaling_factor: float = 3.0  # [1/m] must match the costmap's inflation
    inscribed_radius: float = 0.2  # [m] must match the costmap's inflation
    approach_velocity_scaling_dist: float = 0.6  # [m]
    min_approach_linear_velocity: float = 0.05  # [m/s]
    use_collision_detection: bool = True
    max_allowed_time_to_collision_up_to_carrot: float = 1.0  # [s]
    allow_unknown: bool = False  # unknown cells do not count as collisions
    collision_escape_dist: float = 0.0  # [m] from an inscribed start cell, only lethal cells collide this far
    goal_dist_tol: float = 0.25  # [m]
    yaw_goal_tolerance: float = 0.25  # [rad]
    use_final_heading: bool = True  # turn to the last pose's yaw at the goal

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if f.type in (bool, "bool"):
                validation.boolean(_OWNER, f.name, value)
            else:
                validation.number(_OWNER, f.name, value, minimum=0.0, positive=f.name in _POSITIVE,
                                  maximum=_MAXIMUM.get(f.name))
        if self.max_lookahead_dist < self.min_lookahead_dist:
            raise ConfigError(
                f"pure pursuit max_lookahead_dist ({self.max_lookahead_dist}) must be >= min_lookahead_dist "
                f"({self.min_lookahead_dist})"
            )

    @classmethod
    def from_mapping(cls, values: Mapping[str, Any]) -> PurePursuitParams:
        """Params from a dict (e.g. a ROS private namespace); unknown keys raise ConfigError naming the valid ones."""
        names = [f.name for f in fields(cls)]
        for key in values:
            if key not in names:
                raise ConfigError(choices_message("pure pursuit parameter", key, names))
        converted = {}
        for f in fields(cls):
            if f.name in values:
                value = values[f.name]
                if f.type not in (bool, "bool") and isinstance(value, int) and not isinstance(value, bool):
                    value = float(value)
                converted[f.name] = value
        return cls(**converted)


def _zero(status: PursuitStatus, reason: str, **extra: Any) -> Command:
    return Command(0.0, 0.0, status, reason, **extra)


class RegulatedPurePursuit:
    """Regulated pure pursuit controller state: the path, the pruning index and the last command."""

    def __init__(self, params: Optional[PurePursuitParams] = None) -> None:
        self.params = params if params is not None else PurePursuitParams()
        self._path: Optional[np.ndarray] = None
        self._lengths = np.zeros(1)
        self._index = 0
        self._fresh = True
        self._last_v = 0.0
        self._last_w = 0.0
        self._xy_reached = False
        self._final_heading = True  # this path's last yaw is a goal heading

    @property
    def path(self) -> Optional[np.ndarray]:
        """The path being followed (N, 2|3) or None."""
        return self._path

    def set_path(self, poses: object, final_heading: bool = True) -> None:
        """Start following a new path (validated: :class:`ConfigError` if empty or not finite). With
        ``final_heading`` False the last pose's yaw is no goal: reaching its position is enough."""
        path = as_path(poses)
        self._path = path
        self._final_heading = bool(final_heading)
        self._lengths = cumulative_lengths(path)
        self._index = 0
        self._fresh = True
        self._xy_reached = False

    def clear(self) -> None:
        """Forget the path and the previous command (e.g. on cancel)."""
        self._path = None
        self._index = 0
        self._last_v = self._last_w = 0.0
        self._xy_reached = False

    def override_last_command(self, v: float, w: float) -> None:
        """The command actually sent after :meth:`step` (v [m/s], w [rad/s]) when a rule above pursuit replaced
        or scaled it: the acceleration limits of the next step start from it, so a robot held still (or backing
        away) by such a rule speeds up from there, not from the speed pursuit would have reached meanwhile."""
        self._last_v, self._last_w = v, w

    def step(
        self,
        pose: Tuple[float, float, float],
        velocity: Tuple[float, float],
        dt: float,
        costs: Optional[np.ndarray] = None,
        geometry: Optional[CostmapGeometry] = None,
    ) -> Command:
        """One control step. ``pose`` (x [m], y [m], yaw [rad]) and ``velocity`` (v [m/s], w [rad/s]) of the
        robot, ``dt`` [s] since the last step; ``costs``/``geometry`` the local costmap (same frame) or None."""
        cmd = self._step(pose, velocity, dt, costs, geometry)
        self._last_v, self._last_w = cmd.v, cmd.w
        return cmd

    # ------------------------------------------------------------------ internals
    def _step(  # noqa: PLR0911, PLR0912 - one control law, read top to bottom
        self,
        pose: Tuple[float, float, float],
        velocity: Tuple[float, float],
        dt: float,
        costs: Optional[np.ndarray],
        geometry: Optional[CostmapGeometry],
    ) -> Command:
        p = self.params
        path = self._path
        if path is None:
            return _zero(PursuitStatus.INVALID_INPUT, "no path set")
        x, y, yaw = float(pose[0]), float(pose[1]), float(pose[2])
        v_now, w_now = float(velocity[0]), float(velocity[1])
        if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(yaw)):
            return _zero(PursuitStatus.INVALID_INPUT, f"robot pose is not finite: {tuple(pose)!r}")
        if not (math.isfinite(v_now) and math.isfinite(w_now)):
            return _zero(PursuitStatus.INVALID_INPUT, f"robot velocity is not finite: {tuple(velocity)!r}")
        if not (math.isfinite(dt) and dt > 0.0):
            return _zero(PursuitStatus.INVALID_INPUT, f"time step must be a finite number > 0 [s], got {dt!r}")
        if (costs is None) != (geometry is None):
            return _zero(PursuitStatus.INVALID_INPUT, "costs and geometry must be given together")

        lookahead = p.lookahead_dist
        if p.use_velocity_scaled_lookahead_dist:
            lookahead = min(max(abs(v_now) * p.lookahead_time, p.min_lookahead_dist), p.max_lookahead_dist)
        # first step on a path: search all of it; then a window ahead of the last point (monotonic, bounded)
        window = math.inf if self._fresh else 2.0 * max(lookahead, p.max_lookahead_dist)
        closest = closest_point(path, x, y, start_index=self._index, max_arc=window, lengths=self._lengths,
                                earliest_within=p.goal_dist_tol if self._fresh else 0.0)
        self._fresh = False
        self._index = closest.index
        remaining = float(self._lengths[-1] - closest.s)
        goal_x, goal_y = float(path[-1, 0]), float(path[-1, 1])
        to_goal = math.hypot(goal_x - x, goal_y - y)
        info: dict[str, Any] = {"distance_to_goal": remaining, "cross_track": closest.distance}

        # 1. goal position reached: final heading, then done
        if self._xy_reached or (to_goal <= p.goal_dist_tol and remaining <= p.goal_dist_tol + 1e-9):
            self._xy_reached = True
            if p.use_final_heading and self._final_heading and path.shape[1] == 3:
                error = wrap_angle(float(path[-1, 2]) - yaw)
                if abs(error) > p.yaw_goal_tolerance:
                    w = self._limited_rotation(math.copysign(p.rotate_to_heading_angular_vel, error), w_now, dt)
                    if abs(w) * dt > abs(error):  # do not turn past the heading in one step
                        w = error / dt
                    return Command(0.0, w, PursuitStatus.ROTATING_TO_GOAL, "turning to the goal heading", **info)
            return _zero(PursuitStatus.GOAL_REACHED, "goal reached", **info)

        # 2-6 with the lookahead, then with shorter ones while the arc collides (the carrot nearer on the path)
        cmd = self._towards_carrot(lookahead, x, y, yaw, dt, w_now, closest, remaining, costs, geometry, info)
        if cmd.status is not PursuitStatus.COLLISION_AHEAD or not self._path_clear(closest.s, lookahead, costs,
                                                                                    geometry):
            return cmd
        for carrot_dist in _shortened(lookahead, geometry):
            near = self._towards_carrot(carrot_dist, x, y, yaw, dt, w_now, closest, remaining, costs, geometry, info)
            if near.status is not PursuitStatus.COLLISION_AHEAD:
                return replace(near, reason=f"lookahead shortened to {carrot_dist:.2f} m ({cmd.reason})")
        return cmd

    def _path_clear(
        self, s_start: float, length: float, costs: Optional[np.ndarray], geometry: Optional[CostmapGeometry]
    ) -> bool:
        """True if the path from arc length ``s_start`` [m] on for ``length`` [m] meets no colliding cell: only
        then may a nearer carrot replace the far one (its shorter arc must not skip an obstacle on the path)."""
        if costs is None or geometry is None or self._path is None:
            return False
        return obstacle_on_path(self._path, self._lengths, s_start, distance_m=length, costs=costs,
                                geometry=geometry, unknown_blocks=not self.params.allow_unknown) is None

    def _towards_carrot(  # noqa: PLR0917 - one step's state, passed on from _step
        self,
        lookahead: float,
        x: float,
        y: float,
        yaw: float,
        dt: float,
        w_now: float,
        closest: PathPoint,
        remaining: float,
        costs: Optional[np.ndarray],
        geometry: Optional[CostmapGeometry],
        info: dict[str, Any],
    ) -> Command:
        """Steps 2-6 for one lookahead distance [m]: rotate towards the carrot, drive the arc to it, or
        COLLISION_AHEAD (zero command) when that arc meets an obstacle."""
        p = self.params
        path = self._path
        assert path is not None
        # 2-3. carrot on the lookahead circle, in the robot frame
        carrot = lookahead_point(path, x, y, lookahead, start=closest, lengths=self._lengths)
        cos_y, sin_y = math.cos(yaw), math.sin(yaw)
        dx, dy = carrot.x - x, carrot.y - y
        cx, cy = cos_y * dx + sin_y * dy, -sin_y * dx + cos_y * dy
        info = dict(info, carrot=(carrot.x, carrot.y), lookahead=lookahead)
        bearing = math.atan2(cy, cx)

        # 4. rotate in place towards the path
        if p.use_rotate_to_heading and abs(bearing) > p.rotate_to_heading_min_angle:
            w = self._limited_rotation(math.copysign(p.rotate_to_heading_angular_vel, bearing), w_now, dt)
            return Command(0.0, w, PursuitStatus.ROTATING_TO_PATH, "turning towards the path", **info)

        # 5. regulated linear velocity
        d2 = cx * cx + cy * cy
        curvature = 2.0 * cy / d2 if d2 > 1e-3 else 0.0
        v = self._regulated_speed(curvature=curvature, x=x, y=y, remaining=remaining, costs=costs, geometry=geometry)
        v = min(max(v, self._last_v - p.max_linear_decel * dt), self._last_v + p.max_linear_accel * dt)
        v = max(v, 0.0)
        w = v * curvature
        if abs(w) > p.max_angular_vel:
            w = math.copysign(p.max_angular_vel, w)
            v = abs(w / curvature)

        # 6. forward collision check of the commanded arc
        if p.use_collision_detection and costs is not None and geometry is not None and v > 0.0:
            horizon = min(p.max_allowed_time_to_collision_up_to_carrot, math.sqrt(d2) / v)
            hit = _arc_collision(x, y, yaw, v, w, horizon, costs, geometry, p.allow_unknown,
                                 p.collision_escape_dist)
            if hit is not None:
                return _zero(
                    PursuitStatus.COLLISION_AHEAD,
                    f"collision ahead at ({hit[0]:.2f}, {hit[1]:.2f}) within {horizon:.2f} s",
                    **info,
                )
        return Command(v, w, PursuitStatus.FOLLOWING, "", **info)

    def _regulated_speed(
        self,
        *,
        curvature: float,
        x: float,
        y: float,
        remaining: float,
        costs: Optional[np.ndarray],
        geometry: Optional[CostmapGeometry],
    ) -> float:
        p = self.params
        v = p.desired_linear_vel
        curvature_v = cost_v = v
        if p.use_regulated_linear_velocity_scaling and curvature != 0.0:
            radius = abs(1.0 / curvature)
            if radius < p.regulated_linear_scaling_min_radius:
                curvature_v = v * radius / p.regulated_linear_scaling_min_radius
        if p.use_cost_regulated_linear_velocity_scaling and costs is not None and geometry is not None:
            cell = geometry.world_to_cell(x, y)
            if geometry.in_bounds(cell):
                cost = int(costs[cell])
                if 0 < cost < NO_INFORMATION:
                    # distance to the nearest obstacle implied by the inflation cost function
                    if cost >= INSCRIBED:
                        distance = p.inscribed_radius
                    else:
                        distance = (
                            -math.log(cost / MAX_NON_OBSTACLE) / p.inflation_cost_scaling_factor + p.inscribed_radius
                            if p.inflation_cost_scaling_factor > 0
                            else p.inscribed_radius
                        )
                    if distance < p.cost_scaling_dist:
                        cost_v = v * p.cost_scaling_gain * distance / p.cost_scaling_dist
        v = max(min(curvature_v, cost_v), p.regulated_linear_scaling_min_speed)
        if remaining < p.approach_velocity_scaling_dist:
            v = max(v * remaining / p.approach_velocity_scaling_dist, p.min_approach_linear_velocity)
        return min(v, p.desired_linear_vel)

    def _limited_rotation(self, w_target: float, w_now: float, dt: float) -> float:
        """``w_target`` reached from the measured ``w_now`` at ``max_angular_accel``, never beyond
        ``max_angular_vel`` (a spike in the measured rate must not raise the command)."""
        p = self.params
        limit = p.max_angular_accel * dt
        w = min(max(w_target, w_now - limit), w_now + limit)
        return min(max(w, -p.max_angular_vel), p.max_angular_vel)


def _shortened(lookahead: float, geometry: Optional[CostmapGeometry]) -> Tuple[float, ...]:
    """Halves of the lookahead [m] down to two costmap cells (none without a costmap)."""
    if geometry is None:
        return ()
    distances = [lookahead / 2.0]
    while distances[-1] / 2.0 >= 2.0 * geometry.resolution:
        distances.append(distances[-1] / 2.0)
    return tuple(d for d in distances if d >= 2.0 * geometry.resolution)


def _arc_collision(  # noqa: PLR0917 - the arc's parameters, in the order of the formula
    x: float,
    y: float,
    yaw: float,
    v: float,
    w: float,
    horizon: float,
    costs: np.ndarray,
    geometry: CostmapGeometry,
    allow_unknown: bool,
    escape_dist: float = 0.0,
) -> Optional[Tuple[float, float]]:
    """First point of the arc driven at (v, w) for ``horizon`` [s] whose cell is in collision, or None.

    Sampled every half cell of travel; cells off the costmap are not checked (nothing is known there).
    When the robot's own cell is INSCRIBED (not LETHAL), the arc's first ``escape_dist`` [m] collide only
    on LETHAL cells.
    """
    steps = max(1, math.ceil(v * horizon / (0.5 * geometry.resolution)))
    escape_time = 0.0  # [s] of the arc during which inscribed cells are passable
    cell = geometry.world_to_cell(x, y)
    if escape_dist > 0.0 and geometry.in_bounds(cell) and INSCRIBED <= int(costs[cell]) < LETHAL:
        escape_time = escape_dist / v
    found, hx, hy = _arc_kernel(
        x, y, yaw, v, w, horizon, steps, costs, geometry.origin_x, geometry.origin_y, geometry.resolution,
        allow_unknown, escape_time,
    )
    return (hx, hy) if found else None


@njit(cache=True, nogil=True)
def _arc_kernel(  # noqa: PLR0917 - compiled kernel
    x: float,
    y: float,
    yaw: float,
    v: float,
    w: float,
    horizon: float,
    steps: int,
    costs: np.ndarray,
    origin_x: float,
    origin_y: float,
    resolution: float,
    allow_unknown: bool,
    escape_time: float,
) -> Tuple[bool, float, float]:  # pragma: no cover - compiled
    height, width = costs.shape
    cos_y = math.cos(yaw)
    sin_y = math.sin(yaw)
    for k in range(1, steps + 1):
        t = horizon * k / steps
        if abs(w) < 1e-9:
            lx = v * t
            ly = 0.0
        else:
            lx = (v / w) * math.sin(w * t)
            ly = (v / w) * (1.0 - math.cos(w * t))
        px = x + cos_y * lx - sin_y * ly
        py = y + sin_y * lx + cos_y * ly
        col = math.floor((px - origin_x) / resolution)
        row = math.floor((py - origin_y) / resolution)
        if row < 0 or row >= height or col < 0 or col >= width:
            continue
        cost = costs[row, col]
        if cost == NO_INFORMATION:
            if not allow_unknown:
                return True, px, py
        elif cost >= LETHAL or (cost >= INSCRIBED and t > escape_time):
            return True, px, py
    return False, 0.0, 0.0


