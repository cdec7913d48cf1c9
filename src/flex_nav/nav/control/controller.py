"""One goal of a path-following controller, with its safety rules, around regulated pure pursuit.

:class:`SafeFollower` turns each control tick into a :class:`Decision`: the velocity to publish and whether
the goal goes on, succeeded or must be aborted. Every decision other than RUNNING carries a zero command,
and so does every failure:

- stale sensors (no message for ``sensor_timeout`` [s], see :class:`~flex_nav.nav.control.safety.SensorWatchdog`)
  -> a zero command at once; ABORTED with the sensor named unless it is fresh again within ``sensor_grace_s``
  [s] more (0, the default, aborts at once), so a scan that arrives late on a loaded computer stops the robot
  for a moment instead of ending the goal;
- the robot pose cannot be had (``pose()`` raises a FlexNavError, e.g. NotReadyError) -> ABORTED with its
  message;
- pure pursuit reports INVALID_INPUT -> ABORTED; GOAL_REACHED -> SUCCEEDED;
- an obstacle on the path within ``blocked_distance_m`` [m] ahead for ``blocked_timeout_s`` [s] ->
  ABORTED with a reason starting ``blocked`` (off when ``blocked_distance_m`` is 0; see
  :mod:`flex_nav.nav.control.blocked`), so a behavior can classify the obstacle instead of waiting it out;
- COLLISION_AHEAD -> zero command while blocked; ABORTED once blocked for ``collision_timeout`` [s]
  (0 aborts at once), so a person walking past does not end the goal but a wall does;
- a non-finite command, or any exception raised while computing the tick -> ABORTED
  ("internal error ..."), so a bug stops the robot instead of leaving it on its last command;
- with a ``yielding`` rule (off by default; :mod:`flex_nav.nav.control.yielding`) and the moving tracks passed
  to :meth:`SafeFollower.tick`, people walking into the path are given way to: while the rule is active its
  command replaces the controller's, and neither the blocked-path watch nor the collision timeout runs
  (a person crossing is waited for, not reported as a blocked path); nor does an obstacle on the path
  that a walking person explains (see :meth:`YieldRule.explains`) count as blocking it;
- with a ``social`` distance rule (off by default; :mod:`flex_nav.nav.control.social_distance`) and the robot's
  ``footprint``, every moving command (the controller's or the yield rule's) is scaled down so the footprint
  keeps ``min_distance_m`` from every tracked person: slower near people, stopped early, never toward one.

Pure: the node passes times (one clock, [s]) and callables for the pose and the local costmap.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, replace
from typing import Callable, List, Optional, Sequence, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError, FlexNavError
from flex_nav.nav.control.blocked import BlockedPathWatch, obstacle_on_path
from flex_nav.nav.control.pure_pursuit import Command, PurePursuitParams, PursuitStatus, RegulatedPurePursuit
from flex_nav.nav.control.safety import SensorWatchdog
from flex_nav.nav.control.social_distance import SocialDistanceRule, SocialLimit
from flex_nav.nav.control.yielding import YieldDecision, YieldRule
from flex_nav.nav.costmap.costmap_grid import CostmapGeometry
from flex_nav.nav.path import as_path, cumulative_lengths
from flex_nav.nav.planar import Pose2D
from flex_nav.perception.moving_obstacles import Track

LocalCostmap = Optional[Tuple[np.ndarray, CostmapGeometry]]


def no_tracks() -> List[Track]:
    """The tracks of a follower without a moving-obstacle tracker: none."""
    return []


class Outcome(enum.Enum):
    RUNNING = 0
    SUCCEEDED = 1
    ABORTED = 2


@dataclass(frozen=True)
class Decision:
    """What to publish now (``v`` [m/s], ``w`` [rad/s]) and what becomes of the goal."""

    v: float
    w: float
    outcome: Outcome
    reason: str = ""
    command: Optional[Command] = None  # pure pursuit's output, when it ran
    yielded: Optional[YieldDecision] = None  # the yield rule's decision, when it replaced the command
    social: Optional[SocialLimit] = None  # the social distance rule's limit, when it slowed the command

    @property
    def stops(self) -> bool:
        return self.v == 0.0 and self.w == 0.0


def _stop(outcome: Outcome, reason: str, command: Optional[Command] = None) -> Decision:
    return Decision(0.0, 0.0, outcome, reason, command)


class SafeFollower:
    """Safety rules around one :class:`RegulatedPurePursuit`; see the module docstring."""

    def __init__(
        self,
        params: PurePursuitParams,
        *,
        sensors: Sequence[str],
        sensor_timeout_s: float,
        collision_timeout_s: float,
        nominal_period_s: float,
        start_s: float,
        blocked_distance_m: float = 0.0,
        blocked_timeout_s: float = 0.5,
        yielding: Optional[YieldRule] = None,
        sensor_grace_s: float = 0.0,
        social: Optional[SocialDistanceRule] = None,
        footprint: Optional[np.ndarray] = None,
    ) -> None:
        """``social`` needs ``footprint``: the robot's outline, (N, 2) [m] in its base frame."""
        for name, value in (("collision_timeout_s", collision_timeout_s), ("nominal_period_s", nominal_period_s),
                            ("sensor_grace_s", sensor_grace_s)):
            if not math.isfinite(value) or value < 0.0:
                raise ConfigError(f"{name} must be a finite number >= 0 [s], got {value!r}")
        if nominal_period_s <= 0.0:
            raise ConfigError(f"nominal_period_s must be > 0 [s], got {nominal_period_s!r}")
        self.pursuit = RegulatedPurePursuit(params)
        self.watchdog = SensorWatchdog(sensors, sensor_timeout_s, start_s)
        self.sensor_grace_s = sensor_grace_s
        self._stale_since_s: Optional[float] = None  # [s] a sensor has been stale without a break since then
        self.collision_timeout_s = collision_timeout_s
        self.nominal_period_s = nominal_period_s
        self._last_tick_s: Optional[float] = None
        self._blocked_since_s: Optional[float] = None
        self._yielding_since_s: Optional[float] = None  # [s] giving way to people without a break since then
        self.blocked = BlockedPathWatch(blocked_distance_m, blocked_timeout_s)
        self.yielding = yielding  # give way to moving tracks (None: off)
        if social is not None and (footprint is None or np.asarray(footprint).ndim != 2
                                   or np.asarray(footprint).shape[0] < 3 or np.asarray(footprint).shape[1] != 2):
            raise ConfigError(f"a social distance rule needs the footprint as (N >= 3, 2) corners [m], got "
                              f"{None if footprint is None else np.asarray(footprint).shape}")
        self.social = social  # keep a distance from tracked people (None: off)
        self.footprint = None if footprint is None else np.asarray(footprint, dtype=np.float64)
        # the last guard's limits: max_angular_vel [rad/s]; desired_linear_vel or the hurry speed [m/s]
        self._w_max = params.max_angular_vel
        self._v_max = max(params.desired_linear_vel, yielding.params.hurry_speed_mps if yielding else 0.0)
        self._path: Optional[np.ndarray] = None
        self._lengths = np.zeros(1)

    def set_path(self, poses: object, final_heading: bool = True) -> None:
        """Follow ``poses`` ((N, 2|3) in the controller's frame); ConfigError if empty or not finite.

        The previous command is kept, so a replaced path continues smoothly. So are the time the robot has
        been held by a collision ahead and the time an obstacle has sat on the path: a planner that replaces
        the path every second must not keep a robot standing in front of an obstacle from ever reaching
        ``collision_timeout`` or ``blocked_timeout`` (a new path that avoids the obstacle ends the latter at
        the next tick). Both start afresh with the first path after :meth:`stop`. ``final_heading`` False:
        the last pose's yaw is no goal (see :meth:`RegulatedPurePursuit.set_path`).
        """
        self.pursuit.set_path(poses, final_heading)
        self._path = as_path(poses)
        self._lengths = cumulative_lengths(self._path)

    def stop(self) -> None:
        """The goal ended (or the robot was stopped): forget the path and the previous command."""
        self.pursuit.clear()
        self._last_tick_s = None
        self._blocked_since_s = None
        self._yielding_since_s = None
        self._stale_since_s = None
        self._path = None
        self.blocked.reset()
        if self.yielding is not None:
            self.yielding.reset()

    def hold(self) -> None:
        """The robot was stopped outside the control law (ROS time stood still): the next step ramps up from a
        zero command and measures its interval afresh; the path and the goal are kept."""
        self.pursuit.override_last_command(0.0, 0.0)
        self._last_tick_s = None

    def tick(
        self,
        now_s: float,
        pose: Callable[[], Pose2D],
        velocity: Tuple[float, float],
        local_costmap: Callable[[], LocalCostmap],
        tracks: Callable[[], Sequence[Track]] = no_tracks,
    ) -> Decision:
        """One control step at ``now_s``; never raises (an exception becomes an ABORTED decision).
        ``tracks``: the moving-obstacle tracks in the path's frame, used only with a ``yielding`` rule."""
        try:
            decision = self._tick(now_s, pose, velocity, local_costmap, tracks)
        except FlexNavError as err:  # an expected failure with its own reason (no transform, bad input)
            decision = _stop(Outcome.ABORTED, str(err))
        except Exception as err:
            decision = _stop(Outcome.ABORTED, f"internal error in the control step: {err!r}")
        if decision.outcome is not Outcome.RUNNING:
            self.stop()
            return decision
        decision = self._within_limits(decision)
        self.pursuit.override_last_command(decision.v, decision.w)  # the next step ramps from what was sent
        return decision

    def _within_limits(self, decision: Decision) -> Decision:
        """The last guard: no command beyond the configured speeds — ``max_angular_vel`` [rad/s], and
        ``desired_linear_vel`` or the yield rule's ``hurry_speed_mps`` [m/s], forwards or backwards. Both are
        scaled by the same factor, so the robot keeps the arc that was checked for collisions, only slower."""
        scale = min(1.0, self._v_max / abs(decision.v) if decision.v else 1.0,
                    self._w_max / abs(decision.w) if decision.w else 1.0)
        if scale == 1.0:
            return decision
        return replace(decision, v=decision.v * scale, w=decision.w * scale)

    def _stale_sensor(self, now_s: float) -> Optional[Decision]:
        """A stopping decision while a sensor is stale: RUNNING within ``sensor_grace_s`` of the moment it went
        stale, ABORTED after; None while every sensor is fresh."""
        problem = self.watchdog.problem(now_s)
        if problem is None:
            self._stale_since_s = None
            return None
        if self._stale_since_s is None:
            self._stale_since_s = now_s
        if now_s - self._stale_since_s < self.sensor_grace_s:
            self._last_tick_s = None  # the next moving tick measures its interval afresh
            return _stop(Outcome.RUNNING, f"{problem}: stopped, waiting up to {self.sensor_grace_s:g} s for it")
        waited = f" (stopped {self.sensor_grace_s:g} s waiting for it)" if self.sensor_grace_s > 0.0 else ""
        return _stop(Outcome.ABORTED, problem + waited)

    def _tick(  # noqa: PLR0911 - one return per way a tick can end, read top to bottom
        self,
        now_s: float,
        pose: Callable[[], Pose2D],
        velocity: Tuple[float, float],
        local_costmap: Callable[[], LocalCostmap],
        tracks: Callable[[], Sequence[Track]],
    ) -> Decision:
        stale = self._stale_sensor(now_s)
        if stale is not None:
            return stale
        robot = pose()
        dt = self.nominal_period_s if self._last_tick_s is None else now_s - self._last_tick_s
        if dt <= 0.0:
            dt = self.nominal_period_s
        self._last_tick_s = now_s
        costmap = local_costmap()
        costs, geometry = costmap if costmap is not None else (None, None)
        command = self.pursuit.step(robot, velocity, dt, costs, geometry)
        status = command.status
        if status is PursuitStatus.GOAL_REACHED:
            return _stop(Outcome.SUCCEEDED, "goal reached", command)
        if status is PursuitStatus.INVALID_INPUT:
            return _stop(Outcome.ABORTED, command.reason, command)
        moving = list(tracks()) if self.yielding is not None or self.social is not None else []
        s_robot = float(self._lengths[-1]) - command.distance_to_goal  # [m] along the path (nan: unknown)
        given_way = self._give_way(now_s, robot, command, moving, costmap, velocity[0], s_robot)
        if given_way is not None:
            return self._keep_distance(given_way, robot, moving)
        if self.blocked.enabled and costs is not None and geometry is not None and self._path is not None:
            obstacle = (obstacle_on_path(self._path, self._lengths, s_robot, distance_m=self.blocked.distance_m,
                                         costs=costs, geometry=geometry)
                        if math.isfinite(s_robot) else None)
            if obstacle is not None and self.yielding is not None and self.yielding.explains(
                    (obstacle.x, obstacle.y), moving):
                obstacle = None  # a person walking: the yield rule gives way, nothing to classify
            reason = self.blocked.update(obstacle, now_s)
            if reason is not None:
                return _stop(Outcome.ABORTED, reason, command)
        if status is PursuitStatus.COLLISION_AHEAD:
            if self._blocked_since_s is None:
                self._blocked_since_s = now_s
            blocked_s = now_s - self._blocked_since_s
            if blocked_s >= self.collision_timeout_s:
                return _stop(Outcome.ABORTED, f"{command.reason}; blocked for {blocked_s:.2f} s", command)
            return _stop(Outcome.RUNNING, command.reason, command)
        self._blocked_since_s = None
        if not (math.isfinite(command.v) and math.isfinite(command.w)):
            return _stop(Outcome.ABORTED, f"internal error: non-finite command ({command.v}, {command.w})", command)
        return self._keep_distance(Decision(command.v, command.w, Outcome.RUNNING, command.reason, command), robot,
                                   moving)

    def _keep_distance(self, decision: Decision, robot: Pose2D, people: Sequence[Track]) -> Decision:
        """``decision`` with its command scaled by the social distance rule (unchanged when the rule is off, the
        robot stands, or nobody limits it)."""
        if self.social is None or self.footprint is None or decision.stops or not people:
            return decision
        limit = self.social.limit(robot, self.footprint, decision.v, decision.w, people)
        if limit.scale >= 1.0:
            return decision
        return replace(decision, v=limit.v, w=limit.w, reason=f"{decision.reason}; {limit.reason}", social=limit)

    def _give_way(self, now_s: float, robot: Pose2D, command: Command, tracks: Sequence[Track],  # noqa: PLR0917
                  costmap: LocalCostmap, speed: float, s_robot: float) -> Optional[Decision]:
        """The yield rule's decision while it is active (people to give way to), else None (also when off)."""
        if self.yielding is None or self._path is None or not math.isfinite(s_robot):
            return None
        costs, geometry = costmap if costmap is not None else (None, None)
        given_way = self.yielding.decide(
            now_s, robot, (command.v, command.w), path=self._path, lengths=self._lengths,
            s_robot=s_robot, tracks=tracks, costs=costs, geometry=geometry, speed=speed)
        if not given_way.active:
            self._yielding_since_s = None
            return None
        self.blocked.reset()  # a person crossing is waited for, not a blocked path
        self._blocked_since_s = None
        if self._yielding_since_s is None:
            self._yielding_since_s = now_s
        patience_s = self.yielding.params.patience_s
        if patience_s > 0.0 and now_s - self._yielding_since_s >= patience_s:
            return _stop(Outcome.ABORTED, f"gave way to people for {now_s - self._yielding_since_s:.0f} s without a "
                                          f"break (yielding/patience_s {patience_s:g} s)", command)
        if not (math.isfinite(given_way.v) and math.isfinite(given_way.w)):
            return _stop(Outcome.ABORTED, f"internal error: non-finite yield command ({given_way.v}, {given_way.w})",
                         command)
        return Decision(given_way.v, given_way.w, Outcome.RUNNING, given_way.reason, command, given_way)


def warm_up(params: PurePursuitParams) -> None:
    """Run pure pursuit once on a small made-up scene so its compiled kernels (closest point, arc collision
    check) are loaded before the first goal, not during the first control period."""
    geometry = CostmapGeometry(20, 20, 0.05, -0.5, -0.5)
    pursuit = RegulatedPurePursuit(params)
    pursuit.set_path(np.array([[0.0, 0.0, 0.0], [0.4, 0.0, 0.0], [0.8, 0.1, 0.0]]))
    pursuit.step((0.0, 0.0, 0.0), (0.2, 0.0), 0.05, np.zeros(geometry.shape, dtype=np.uint8), geometry)
