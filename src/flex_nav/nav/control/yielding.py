"""Giving way to moving people while following a path: stop before their way, step out of it, never toward them.

People walking across a robot's path do not avoid it (in the simulator they are scripted and blind; in a
hospital they may be busy). A costmap sees only where a person *is*, so a controller drives into the place
where the person is about to be. This rule looks a short ``horizon_s`` [s] ahead instead: every moving track
(speed >= ``min_track_speed_mps``, within ``max_range_m``; slower tracks are left to the costmap and the
planner) is predicted at constant velocity, and its *corridor* is the stretch it sweeps in the horizon,
widened by ``R = robot radius + track radius + margin``, growing by ``uncertainty_mps`` per second of
prediction (a velocity estimate a little off in direction puts a person far off after a few seconds). The
robot is predicted along its path, speeding up from its odometry speed to ``speed_mps`` at ``accel_mps2``.
Each control tick (:meth:`YieldRule.decide`):

1. the robot going on along its path stays farther than R from every predicted person -> FREE: the
   controller's command goes out unchanged (after yielding: only with ``start_margin_m`` [m] more, and a robot
   that had stopped starts again only after ``resume_after_s`` [s] without a conflict, so a wobbling estimate
   does not start and stop it; one still driving forward drives on);
   If only crossing at ``hurry_speed_mps`` (when > ``speed_mps``; off by default) clears everyone while the
   robot cruises along its path -> HURRY: that speed (the turn rate scaled with it); with a
   ``comfort_margin_m`` above ``margin_m`` (0: none), a way that is free by ``margin_m`` but not by the comfort
   margin is hurried across too when hurrying keeps the comfort margin (never waited for: the social distance's
   margin, :mod:`flex_nav.nav.control.social_distance`, as a larger margin_m kept the robot from ever crossing S6's
   walkers' ways);
2. otherwise, if standing still keeps R (less ``escape_tolerance_m``) to every predicted person: while
   the path ahead enters a conflicting person's corridor farther than ``stop_buffer_m`` [m] ahead -> SLOW:
   the speed is capped so the robot stops, at ``decel_mps2``, before the corridor (the turn rate is scaled
   with it: same curvature);
3. at the corridor's edge -> WAIT (no forward motion; the controller's turn in place is kept: a round robot
   turning takes no more room);
4. otherwise (standing still would be met) the robot is in an approaching person's way -> ESCAPE: of a
   few short motions (back up straight or on a gentle arc, go on along the path at ``speed_mps`` as far as
   the way of the next person that standing still keeps clear of) the one that keeps the
   largest predicted clearance (ties: the one that meets the person latest; the motion of the previous tick
   is preferred by a little, so the robot does not dither between two ways out) is commanded, but only a
   motion that never carries the robot toward a person: into the predicted way of anyone that standing
   still keeps clear of (toward a person's way is toward the person, even when it is away from where the
   person is now); it must keep more clearance than standing still, and its robot centres over ``check_s``
   [s] stay off the local costmap's obstacle cells (cells next to a moving track are its own marks and do
   not count). Without such a motion the robot waits.

Giving way is bounded: :class:`~flex_nav.nav.control.controller.SafeFollower` aborts the goal after ``patience_s`` [s]
(60) of giving way without a break, so a walker who never leaves the way (or a tracker artefact) cannot hold
the robot forever; the behavior then decides (push_or_avoid: pause and replan, bounded tries).

Pure: numpy, no ROS, no clock (times [s] are passed in); poses and tracks in the path's frame.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import INSCRIBED, NO_INFORMATION, CostmapGeometry
from flex_nav.nav.planar import Pose2D
from flex_nav.perception.moving_obstacles import Track

LATER_WEIGHT = 0.05  # [m/s] a later first violation is worth this much clearance per second (ties only)
COMMIT_BONUS_M = 0.05  # [m] the escape motion chosen on the previous tick is worth this much more
OWN_MARKS_MARGIN_M = 0.15  # [m] costmap cells this far beyond a moving track's body are its own marks
TRAIL_S = 0.5  # [s] a moving track's marks may lag this far behind it
PLANNERS = ("rules", "space_time", "checked")  # YieldParams.planner
DRIVING_MPS = 0.05  # [m/s] a decision sending more than this forward keeps the robot driving (no resume hold)


@dataclass(frozen=True)
class YieldParams:
    """Parameters of :class:`YieldRule`; units in comments."""

    robot_radius_m: float = 0.18  # [m]
    speed_mps: float = 0.26  # [m/s] the robot's speed along its path in the prediction
    hurry_speed_mps: float = 0.0  # [m/s] > speed_mps: cross at this speed when only that clears (0: never)
    accel_mps2: float = 0.9  # [m/s^2] the robot's acceleration to that speed in the prediction
    horizon_s: float = 6.0  # [s] prediction horizon (long enough to cross a person's way)
    time_step_s: float = 0.1  # [s] prediction step
    margin_m: float = 0.1  # [m] clearance kept beyond touching
    # [m] > margin_m: a crossing free by margin_m but not by this is hurried when hurrying keeps it (0: off). Not
    # a larger margin_m: with 0.3 m (S6 seeds 0-3) or 0.2 m (seeds 0-1) the robot never got across in 150 s
    comfort_margin_m: float = 0.0
    uncertainty_mps: float = 0.0  # [m/s] R grows by this per second of prediction (velocity error)
    min_track_speed_mps: float = 0.2  # [m/s] slower tracks are stationary (left to the costmap)
    max_range_m: float = 5.0  # [m] farther tracks are ignored
    decel_mps2: float = 0.5  # [m/s^2] braking before a corridor
    stop_buffer_m: float = 0.05  # [m] stop this far before a corridor
    escape_speed_mps: float = 0.2  # [m/s] speed of the escape motions
    escape_turn_radps: float = 0.3  # [rad/s] turn rate of the arc escapes
    check_s: float = 1.0  # [s] escape motions: costmap check and direction test over this time
    min_gain_m: float = 0.02  # [m] an escape must keep this much more clearance than standing still
    resume_after_s: float = 0.3  # [s] conflict-free time before the controller drives again
    escape_tolerance_m: float = 0.05  # [m] standing this far inside R still waits (no back-and-forth on noise)
    start_margin_m: float = 0.05  # [m] extra clearance the way must have to start again after yielding
    patience_s: float = 60.0  # [s] giving way this long without a break aborts the goal (0: no limit)
    # "rules": this module's rule; "space_time": the speed along the path planned in space and time
    # (:mod:`flex_nav.nav.control.space_time_yield`), with the six parameters below; "checked": this rule, each
    # decision checked by that planner (:mod:`flex_nav.nav.control.checked_yield`), with the four after them too
    planner: str = "rules"
    moving_gap_m: float = 0.4  # [m] space_time: predicted gap to every person kept while moving
    standing_gap_m: float = 0.1  # [m] space_time: predicted gap to every person kept while standing
    plan_step_s: float = 0.2  # [s] space_time: the plan's time step
    back_m: float = 0.5  # [m] space_time: how far behind the robot the plan may back up (0: never)
    score_cap_m: float = 0.3  # [m] space_time: more room than this buys nothing over progress
    lanes: bool = True  # space_time: predict walkers along the lanes they were seen to walk (False: straight on)
    plan_horizon_s: float = 8.0  # [s] checked: the planner's horizon (the rule keeps horizon_s)
    plan_range_m: float = 8.0  # [m] checked: the planner's range (the rule keeps max_range_m)
    check_standing_gap_m: float = 0.05  # [m] checked: predicted gap to every person the check keeps while standing
    check_moving_gap_m: float = 0.35  # [m] checked: predicted gap to every person the check keeps while moving

    def __post_init__(self) -> None:
        positive = ("robot_radius_m", "speed_mps", "accel_mps2", "horizon_s", "time_step_s", "min_track_speed_mps",
                    "max_range_m", "decel_mps2", "escape_speed_mps", "check_s", "plan_step_s", "score_cap_m",
                    "plan_horizon_s", "plan_range_m")
        for name in positive:
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value) \
                    or value <= 0.0:
                raise ConfigError(f"yield parameter {name} must be a finite number > 0, got {value!r}")
        for name in ("hurry_speed_mps", "margin_m", "comfort_margin_m", "uncertainty_mps", "stop_buffer_m",
                     "escape_turn_radps",
                     "min_gain_m", "resume_after_s", "start_margin_m", "escape_tolerance_m", "patience_s",
                     "moving_gap_m", "standing_gap_m", "back_m", "check_standing_gap_m", "check_moving_gap_m"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value) \
                    or value < 0.0:
                raise ConfigError(f"yield parameter {name} must be a finite number >= 0, got {value!r}")
        if not isinstance(self.lanes, bool):
            raise ConfigError(f"yield parameter lanes must be true or false, got {self.lanes!r}")
        if self.planner not in PLANNERS:
            raise ConfigError(f"yield parameter planner must be one of {', '.join(PLANNERS)}, got {self.planner!r}")
        if self.plan_step_s > self.horizon_s:
            raise ConfigError(f"yield parameter plan_step_s ({self.plan_step_s!r}) must not exceed horizon_s "
                              f"({self.horizon_s!r})")
        if self.planner == "checked" and self.plan_step_s > self.plan_horizon_s:
            raise ConfigError(f"yield parameter plan_step_s ({self.plan_step_s!r}) must not exceed plan_horizon_s "
                              f"({self.plan_horizon_s!r})")
        if self.time_step_s > self.horizon_s:
            raise ConfigError(f"yield parameter time_step_s ({self.time_step_s!r}) must not exceed horizon_s "
                              f"({self.horizon_s!r})")

    @classmethod
    def from_mapping(cls, values: dict) -> YieldParams:
        """From a parameter dictionary; unknown names are a ConfigError naming the valid ones."""
        valid = sorted(cls.__dataclass_fields__)
        unknown = sorted(set(values) - set(valid))
        if unknown:
            raise ConfigError(f"unknown yield parameter(s) {', '.join(unknown)} (valid: {', '.join(valid)})")
        converted: Dict[str, Any] = {k: float(v) if isinstance(v, int) and not isinstance(v, bool) else v
                                     for k, v in values.items()}
        return cls(**converted)


class YieldMode(enum.Enum):
    FREE = "free"  # no conflict: the controller's command unchanged
    SLOW = "slow"  # capped speed: stop before a person's corridor
    WAIT = "wait"  # standing: a person is about to cross
    ESCAPE = "escape"  # moving out of an approaching person's way
    HURRY = "hurry"  # crossing faster than usual: only that clears the people


@dataclass(frozen=True)
class YieldDecision:
    """The command (``v`` [m/s], ``w`` [rad/s]) after the rule, why, and for which track."""

    v: float
    w: float
    mode: YieldMode
    reason: str = ""
    track_id: Optional[int] = None

    @property
    def active(self) -> bool:
        """True when the rule changed or may have changed the command (anything but FREE)."""
        return self.mode is not YieldMode.FREE


class PredictedPeople:
    """The moving tracks predicted over the horizon: positions (M, K, 2) at times (K,), radii R (M,) growing by
    ``uncertainty_mps`` per second of prediction (``grown`` (M, K))."""

    def __init__(self, tracks: Sequence[Track], times: np.ndarray, params: YieldParams) -> None:
        self.tracks = list(tracks)
        pos = np.array([[t.x, t.y] for t in tracks], dtype=np.float64).reshape(-1, 2)
        vel = np.array([[t.vx, t.vy] for t in tracks], dtype=np.float64).reshape(-1, 2)
        self.now = pos
        self.velocity = vel
        self.future = pos[:, None, :] + vel[:, None, :] * times[None, :, None]
        self.reach = np.array([params.robot_radius_m + t.radius + params.margin_m for t in tracks])
        self.grown = self.reach[:, None] + params.uncertainty_mps * times[None, :]
        self.times = times

    def clearance(self, robot: np.ndarray) -> np.ndarray:
        """(M, K) predicted distance minus R (grown with the prediction time) for robot positions (K, 2)."""
        clearance: np.ndarray = np.hypot(*(self.future - robot[None, :, :]).transpose(2, 0, 1)) - self.grown
        return clearance


def _segment_closest(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """(distance [m], fraction along a-b in [0, 1]) of each point's closest point on the segment a-b."""
    ab = b - a
    denom = float(ab @ ab)
    if denom <= 1e-12:
        return np.hypot(points[:, 0] - a[0], points[:, 1] - a[1]), np.zeros(len(points))
    u = np.clip(((points - a) @ ab) / denom, 0.0, 1.0)
    closest = a[None, :] + u[:, None] * ab[None, :]
    return np.hypot(points[:, 0] - closest[:, 0], points[:, 1] - closest[:, 1]), u


def arc_positions(pose: Pose2D, v: float, w: float, times: np.ndarray) -> np.ndarray:
    """(K, 2) positions [m] of a differential-drive robot at ``pose`` driving (v [m/s], w [rad/s])."""
    x, y, yaw = pose
    if abs(w) < 1e-9:
        return np.stack((x + v * times * math.cos(yaw), y + v * times * math.sin(yaw)), axis=1)
    radius = v / w
    heading = yaw + w * times
    return np.stack((x + radius * (np.sin(heading) - math.sin(yaw)),
                     y - radius * (np.cos(heading) - math.cos(yaw))), axis=1)


class YieldRule:
    """The rule of the module docstring, with its one piece of memory (when the last conflict was)."""

    def __init__(self, params: YieldParams) -> None:
        self.params = params
        count = math.floor(params.horizon_s / params.time_step_s + 1e-9) + 1
        self.times = np.arange(count) * params.time_step_s
        self._last_conflict_s: Optional[float] = None
        self._last_escape = ""  # the escape motion of the previous tick ("" = none)
        self._last_v = 0.0  # [m/s] the speed the previous tick's decision sent

    def reset(self) -> None:
        """Forget the last conflict, escape and speed (a new goal starts free)."""
        self._last_conflict_s = None
        self._last_escape = ""
        self._last_v = 0.0

    def moving(self, pose: Pose2D, tracks: Sequence[Track]) -> List[Track]:
        """The tracks the rule gives way to: fast enough and near enough."""
        p = self.params
        return [t for t in tracks
                if t.speed >= p.min_track_speed_mps and math.hypot(t.x - pose[0], t.y - pose[1]) <= p.max_range_m]

    def explains(self, point: Tuple[float, float], tracks: Sequence[Track]) -> bool:
        """True when a moving track accounts for an obstacle at ``point`` (x, y) [m]: within its radius plus
        ``OWN_MARKS_MARGIN_M`` of where it is or was ``TRAIL_S`` [s] ago (a costmap keeps a walker's marks
        until a beam clears them)."""
        p = self.params
        x, y = point
        for t in tracks:
            if t.speed < p.min_track_speed_mps:
                continue
            a = np.array([t.x - t.vx * TRAIL_S, t.y - t.vy * TRAIL_S])
            b = np.array([t.x, t.y])
            if float(_segment_closest(np.array([[x, y]]), a, b)[0][0]) <= t.radius + OWN_MARKS_MARGIN_M:
                return True
        return False

    def decide(
        self,
        now_s: float,
        pose: Pose2D,
        command: Tuple[float, float],
        *,
        path: np.ndarray,
        lengths: np.ndarray,
        s_robot: float,
        tracks: Sequence[Track],
        costs: Optional[np.ndarray] = None,
        geometry: Optional[CostmapGeometry] = None,
        speed: Optional[float] = None,
    ) -> YieldDecision:
        """The command to send instead of the controller's ``command`` (v [m/s], w [rad/s]); ``path`` (N, 2|3)
        with cumulative ``lengths`` (N,), the robot at arc length ``s_robot`` [m], driving forward at ``speed``
        [m/s] (odometry; negative while backing up; None: the command's); see the module docstring."""
        p = self.params
        v_cmd, w_cmd = command
        people = PredictedPeople(self.moving(pose, tracks), self.times, p)
        if not people.tracks:
            return self._sent(self._free(now_s, v_cmd, w_cmd))
        v_now = v_cmd if speed is None else speed
        go = self._along_path(path, lengths, s_robot, v_now, p.speed_mps)
        go_clear = people.clearance(go).min(axis=1)  # (M,)
        needed = p.start_margin_m if self._last_conflict_s is not None else 0.0  # hysteresis
        conflicting = np.flatnonzero(go_clear < needed)
        if conflicting.size == 0:
            comfort = needed + p.comfort_margin_m - p.margin_m  # the clearance beyond margin_m it asks
            hurry = (self._hurry(people, path, lengths, s_robot, v_now, (v_cmd, w_cmd), comfort)
                     if p.comfort_margin_m > p.margin_m and float(go_clear.min()) < comfort else None)
            return self._sent(hurry if hurry is not None else self._free(now_s, v_cmd, w_cmd))
        hurry = self._hurry(people, path, lengths, s_robot, v_now, (v_cmd, w_cmd), needed)
        if hurry is not None:
            return self._sent(hurry)
        self._last_conflict_s = now_s
        worst = int(conflicting[np.argmin(go_clear[conflicting])])
        track = people.tracks[worst]
        entry = self._corridor_entry(path, lengths, s_robot, people, conflicting)
        ahead = entry - s_robot
        here = np.repeat(np.array([[pose[0], pose[1]]]), len(self.times), axis=0)
        stand_clear = people.clearance(here)
        standing_keeps_clear = float(stand_clear.min()) >= -p.escape_tolerance_m
        if standing_keeps_clear and ahead > p.stop_buffer_m:
            cap = math.sqrt(2.0 * p.decel_mps2 * (ahead - p.stop_buffer_m))
            v = min(v_cmd, cap)
            w = w_cmd * (v / v_cmd) if v_cmd > 1e-9 else w_cmd
            return self._sent(YieldDecision(
                v, w, YieldMode.SLOW, f"yielding: stopping {ahead:.2f} m ahead, before the way of track "
                f"{track.track_id} ({track.speed:.2f} m/s)", track.track_id))
        if standing_keeps_clear:
            self._last_escape = ""
            return self._sent(YieldDecision(
                0.0, w_cmd, YieldMode.WAIT, f"yielding: waiting for track {track.track_id} ({track.speed:.2f} m/s) "
                f"to pass", track.track_id))
        others = np.flatnonzero(stand_clear.min(axis=1) >= 0.0)  # the people standing still keeps clear of
        stop_s = (self._corridor_entry(path, lengths, s_robot, people, others) - p.stop_buffer_m if others.size
                  else math.inf)
        go_on = self._along_path(path, lengths, s_robot, v_now, p.speed_mps, stop_s=max(stop_s, s_robot))
        return self._sent(self._escape(pose, (v_cmd, w_cmd), go_on, people, stand_clear=stand_clear, costs=costs,
                                       geometry=geometry))

    # ------------------------------------------------------------------ pieces
    def _sent(self, decision: YieldDecision) -> YieldDecision:
        """``decision``, its speed remembered for the next tick's resume hold (see :meth:`_free`)."""
        self._last_v = decision.v
        return decision

    def _free(self, now_s: float, v_cmd: float, w_cmd: float) -> YieldDecision:
        """The controller's command; after a conflict a robot that had stopped (or was backing up) waits
        ``resume_after_s`` [s] first, one still driving forward (slowing before a corridor, hurrying, going on
        along its path) drives on: stopping it would only cost it the time it has to get across."""
        last = self._last_conflict_s
        if last is not None and self._last_v <= DRIVING_MPS and now_s - last < self.params.resume_after_s:
            return YieldDecision(0.0, w_cmd, YieldMode.WAIT,
                                 f"yielding: way clear for {now_s - last:.2f} s, resuming after "
                                 f"{self.params.resume_after_s:g} s")
        self._last_conflict_s = None
        return YieldDecision(v_cmd, w_cmd, YieldMode.FREE)

    def _hurry(self, people: PredictedPeople, path: np.ndarray, lengths: np.ndarray, s_robot: float,  # noqa: PLR0917
               v_now: float, command: Tuple[float, float], needed: float) -> Optional[YieldDecision]:
        """Crossing at ``hurry_speed_mps`` when the robot cruises along its path and only that speed clears
        everyone (None otherwise)."""
        p = self.params
        v_cmd, w_cmd = command
        if p.hurry_speed_mps <= p.speed_mps or v_cmd < 0.8 * p.speed_mps:
            return None
        fast = self._along_path(path, lengths, s_robot, v_now, p.hurry_speed_mps)
        if float(people.clearance(fast).min()) < needed:
            return None
        return YieldDecision(p.hurry_speed_mps, w_cmd * p.hurry_speed_mps / v_cmd, YieldMode.HURRY,
                             f"yielding: hurrying across at {p.hurry_speed_mps:.2f} m/s before the people come")

    def _along_path(self, path: np.ndarray, lengths: np.ndarray, s_robot: float, v_now: float,  # noqa: PLR0917
                    cruise: float, stop_s: float = math.inf) -> np.ndarray:
        """(K, 2) robot positions along the path, speeding up from ``v_now`` [m/s] (negative: backing up, it
        first has to stop) to ``cruise`` [m/s] at ``accel_mps2``, standing at arc length ``stop_s`` [m]."""
        p = self.params
        v0 = min(v_now, cruise)
        t_up = (cruise - v0) / p.accel_mps2
        t = self.times
        travelled = np.where(t < t_up, v0 * t + 0.5 * p.accel_mps2 * t * t,
                             v0 * t_up + 0.5 * p.accel_mps2 * t_up * t_up + cruise * (t - t_up))
        s = np.minimum(s_robot + travelled, min(float(lengths[-1]), stop_s))
        return np.stack((np.interp(s, lengths, path[:, 0]), np.interp(s, lengths, path[:, 1])), axis=1)

    def _corridor_entry(self, path: np.ndarray, lengths: np.ndarray, s_robot: float, people: PredictedPeople,
                        conflicting: np.ndarray) -> float:
        """Arc length [m] of the first path point (from the robot on) inside a conflicting corridor."""
        p = self.params
        end = min(float(lengths[-1]), s_robot + p.speed_mps * p.horizon_s + p.stop_buffer_m)
        samples = np.arange(s_robot, end + 1e-9, 0.05) if end > s_robot else np.array([s_robot])
        points = np.stack((np.interp(samples, lengths, path[:, 0]), np.interp(samples, lengths, path[:, 1])), axis=1)
        inside = np.zeros(len(samples), dtype=bool)
        for i in conflicting:
            a, b = people.future[i, 0], people.future[i, -1]
            dist, frac = _segment_closest(points, a, b)
            inside |= dist < people.reach[i] + p.uncertainty_mps * p.horizon_s * frac
        found = np.flatnonzero(inside)
        return float(samples[found[0]]) if found.size else end

    def _escape(self, pose: Pose2D, command: Tuple[float, float], go_on: np.ndarray, people: PredictedPeople, *,
                stand_clear: np.ndarray, costs: Optional[np.ndarray],
                geometry: Optional[CostmapGeometry]) -> YieldDecision:
        p = self.params
        stand_score = self._score(stand_clear)
        threatening = np.flatnonzero(stand_clear.min(axis=1) < 0.0)
        check = self.times <= p.check_s + 1e-9
        ve, we = p.escape_speed_mps, p.escape_turn_radps
        candidates: List[Tuple[str, float, float, np.ndarray]] = [
            (f"backing up at {ve:.2f} m/s", -ve, 0.0, arc_positions(pose, -ve, 0.0, self.times)),
            ("backing up, turning right", -ve, -we, arc_positions(pose, -ve, -we, self.times)),
            ("backing up, turning left", -ve, we, arc_positions(pose, -ve, we, self.times)),
            ("going on along the path", *self._at_cruise(command), go_on),
        ]
        stand_each = stand_clear.min(axis=1)  # (M,) per person
        best: Optional[Tuple[float, str, float, float]] = None
        for name, v, w, positions in candidates:
            if name == "going on along the path" and v <= 0.0:
                continue
            clearance = people.clearance(positions)
            each = clearance.min(axis=1)
            if np.any((each < 0.0) & (stand_each >= 0.0)):
                continue  # never toward a person: not into the way of anyone standing still keeps clear of
            if not self._free_of_obstacles(positions[check], people, costs, geometry):
                continue
            score = self._score(clearance)
            if name == self._last_escape:
                score += COMMIT_BONUS_M  # keep to one way out: dithering between two is the worst of both
            if score > stand_score + p.min_gain_m and (best is None or score > best[0]):
                best = (score, name, v, w)
        track = people.tracks[int(threatening[0])] if threatening.size else people.tracks[0]
        self._last_escape = best[1] if best is not None else ""
        if best is None:
            return YieldDecision(0.0, 0.0, YieldMode.WAIT,
                                 f"yielding: in the way of track {track.track_id} ({track.speed:.2f} m/s) "
                                 f"with no way out; standing", track.track_id)
        _score, name, v, w = best
        return YieldDecision(v, w, YieldMode.ESCAPE,
                             f"yielding: out of the way of track {track.track_id} ({track.speed:.2f} m/s): {name}",
                             track.track_id)

    def _at_cruise(self, command: Tuple[float, float]) -> Tuple[float, float]:
        """The controller's command (v [m/s], w [rad/s]) at least at ``speed_mps``, the speed the way along the
        path was predicted at (the controller slows near the walker's own costmap marks; an escape driven slower
        than it was checked is no escape), turning on the same arc; (0, w) when the controller does not drive
        forward (turning in place: no way along the path)."""
        v_cmd, w_cmd = command
        if v_cmd <= 0.0:
            return 0.0, w_cmd
        v = max(v_cmd, self.params.speed_mps)
        return v, w_cmd * v / v_cmd

    def _score(self, clearance: np.ndarray) -> float:
        """Smallest predicted clearance [m], plus a little for meeting later (ties between no-way-out motions)."""
        worst = clearance.min(axis=0)  # (K,)
        violated = np.flatnonzero(worst < 0.0)
        first_s = float(self.times[violated[0]]) if violated.size else float(self.times[-1])
        return float(worst.min()) + LATER_WEIGHT * first_s

    def _free_of_obstacles(self, positions: np.ndarray, people: PredictedPeople, costs: Optional[np.ndarray],
                           geometry: Optional[CostmapGeometry]) -> bool:
        if costs is None or geometry is None:
            return True
        rows, cols = geometry.world_to_cells(positions[:, 0], positions[:, 1])
        inside = (rows >= 0) & (rows < geometry.height) & (cols >= 0) & (cols < geometry.width)
        cell = np.full(len(positions), 0, dtype=np.int64)
        cell[inside] = costs[rows[inside], cols[inside]]
        blocked = (cell >= INSCRIBED) & (cell != NO_INFORMATION)
        if not blocked.any():
            return True
        gap = np.hypot(*(positions[None, :, :] - people.now[:, None, :]).transpose(2, 0, 1))  # (M, K)
        own = (gap <= (people.reach - self.params.margin_m + OWN_MARKS_MARGIN_M)[:, None]).any(axis=0)
        return not bool((blocked & ~own).any())
