"""Where people walk: straight lanes learnt from the tracks, and each walker predicted along their lane.

A *lane* is a straight line people were seen to walk along, with the stretch of it they were seen on
(``low_m`` .. ``high_m`` [m] along its direction) and the directions they walked it in. It is learnt from the
tracker's tracks (:class:`~flex_nav.perception.moving_obstacles.Track`): each moving track's recent positions
(``leg_s`` [s]) that lie on a straight line (residual below ``straight_m``) and span at least ``min_leg_m``
make a lane, or join the lane they lie on (within ``line_tolerance_m`` of it and ``angle_tolerance_deg`` of
its direction; the line is refitted through the lane's points, the newest ``max_points``). A lane nobody
was seen on for ``forget_s`` [s] is forgotten.

:meth:`WalkerLanes.predict` gives a track's future positions at given times: a walker on a lane that was
walked both ways (someone turned on it) is predicted to walk on at their speed along the lane and to turn back
at the ends seen so far, again and again; on any other lane along it without turning; off every lane at
constant velocity. Seen ends are where people turned (or the farthest they were seen: a walker lost at the
end of the view is predicted to turn early, i.e. back sooner than they are).

Why: the constant-velocity prediction says nothing of a walker heading for a wall who will be back in a few
seconds, and its heading error (2-4 deg from the tracker) grows to tenths of a metre over a horizon of
seconds; walkers in a hospital's corridors, and the simulator's scripted ones, walk the same lines back and
forth (issue 28, the h6 variant).

Pure numpy, no ROS, no clock (times [s] are passed in); tracks in one planar frame.
"""

from __future__ import annotations

import math
import threading
from collections import deque
from dataclasses import dataclass, field
from typing import Deque, Dict, List, Optional, Sequence, Tuple

import numpy as np

from flex_nav import validation
from flex_nav.perception.moving_obstacles import Track

TURN_REACH_M = 0.6  # [m] a slow track this near a lane's end (along it) is turning there
DIRECTION_SEEN_MPS = 0.1  # [m/s] a walker this fast along a lane walks it in that direction


@dataclass(frozen=True)
class LaneParams:
    """Parameters of :class:`WalkerLanes`; units in comments."""

    min_speed_mps: float = 0.2  # [m/s] slower tracks are not walking (not learnt from, predicted standing)
    leg_s: float = 3.0  # [s] a track's positions this recent make its leg
    min_leg_m: float = 1.2  # [m] a leg this long (end to end) makes or joins a lane
    straight_m: float = 0.08  # [m] a leg's largest distance from its fitted line (straighter: a lane)
    line_tolerance_m: float = 0.3  # [m] a track this near a lane's line (and along it) is on the lane
    angle_tolerance_deg: float = 20.0  # [deg] between a track's (or leg's) direction and the lane's
    forget_s: float = 120.0  # [s] a lane nobody was seen on this long is forgotten
    max_points: int = 600  # the newest points a lane is fitted through

    def __post_init__(self) -> None:
        for name in ("min_speed_mps", "leg_s", "min_leg_m", "straight_m", "line_tolerance_m",
                     "angle_tolerance_deg", "forget_s"):
            validation.number("walker lanes", name, getattr(self, name), positive=True)
        validation.integer("walker lanes", "max_points", self.max_points, minimum=2)


@dataclass
class Lane:
    """A line people walk: ``origin`` (2,) [m] and unit ``direction`` (2,), seen from ``low_m`` to ``high_m``
    [m] along it, walked forward (along ``direction``) and/or backward, last seen at ``seen_s`` [s]."""

    origin: np.ndarray
    direction: np.ndarray
    low_m: float
    high_m: float
    forward: bool
    backward: bool
    seen_s: float
    points: Deque[Tuple[float, float]] = field(default_factory=deque)
    speed_sum_mps: float = 0.0  # [m/s] sum of the walkers' speeds along it (over speed_count ticks)
    speed_count: int = 0

    @property
    def speed_mps(self) -> float:
        """[m/s] The walkers' mean speed along the lane."""
        return self.speed_sum_mps / self.speed_count if self.speed_count else 0.0

    @property
    def turned(self) -> bool:
        """True when walked both ways: walkers turn at its ends."""
        return self.forward and self.backward

    def along(self, point: np.ndarray) -> float:
        """[m] ``point``'s position along the lane."""
        return float((np.asarray(point) - self.origin) @ self.direction)

    def off(self, point: np.ndarray) -> float:
        """[m] ``point``'s distance from the lane's line."""
        d = np.asarray(point) - self.origin
        return abs(float(d[0] * self.direction[1] - d[1] * self.direction[0]))


def fit_line(points: np.ndarray) -> Tuple[np.ndarray, np.ndarray, float]:
    """(centroid (2,), unit direction (2,), largest distance [m] of a point from the line) of ``points`` (N, 2),
    N >= 2: the principal axis."""
    centroid = points.mean(axis=0)
    _, _, axes = np.linalg.svd(points - centroid, full_matrices=False)
    direction = axes[0] / float(np.hypot(*axes[0]))
    normal = np.array([-direction[1], direction[0]])
    return centroid, direction, float(np.abs((points - centroid) @ normal).max())


def bounce(start_m: np.ndarray, low_m: float, high_m: float) -> np.ndarray:
    """Positions [m] along a stretch ``low_m`` .. ``high_m`` of unbounded positions ``start_m`` (walked on
    past the ends): reflected at each end, back and forth."""
    span = high_m - low_m
    if span <= 0.0:
        return np.full_like(start_m, low_m)
    phase = np.mod(start_m - low_m, 2.0 * span)
    return low_m + np.where(phase <= span, phase, 2.0 * span - phase)


class WalkerLanes:
    """The lanes of the module docstring: :meth:`update` with every tick's tracks, :meth:`predict` a track."""

    def __init__(self, params: LaneParams = LaneParams()) -> None:
        self.params = params
        self.lanes: List[Lane] = []
        self._legs: Dict[int, Deque[Tuple[float, float, float]]] = {}
        self._lock = threading.RLock()  # one thread may learn (a tracker's scans) while another predicts

    def clear(self) -> None:
        """Forget every lane and every walker's leg."""
        with self._lock:
            self.lanes = []
            self._legs.clear()

    def update(self, now_s: float, tracks: Sequence[Track]) -> None:
        """Learn from ``tracks`` (as the tracker gives them at ``now_s`` [s])."""
        with self._lock:
            self._update(now_s, tracks)

    def _update(self, now_s: float, tracks: Sequence[Track]) -> None:
        p = self.params
        alive = set()
        for track in tracks:
            alive.add(track.track_id)
            leg = self._legs.setdefault(track.track_id, deque())
            if track.speed < p.min_speed_mps:
                leg.clear()
                continue
            leg.append((now_s, track.x, track.y))
            while leg and now_s - leg[0][0] > p.leg_s:
                leg.popleft()
            self._learn(now_s, track, leg)
        for track_id in list(self._legs):
            if track_id not in alive:
                del self._legs[track_id]
        self.lanes = [lane for lane in self.lanes if now_s - lane.seen_s <= p.forget_s]

    def _learn(self, now_s: float, track: Track, leg: Deque[Tuple[float, float, float]]) -> None:
        p = self.params
        velocity = np.array([track.vx, track.vy])
        lane = self.lane_of(track)
        if lane is None:
            if len(leg) < 3:
                return
            points = np.array([(x, y) for _t, x, y in leg])
            if float(np.hypot(*(points[-1] - points[0]))) < p.min_leg_m:
                return
            centroid, direction, worst = fit_line(points)
            if worst > p.straight_m or abs(float(direction @ velocity)) < track.speed * self._cos_tolerance:
                return
            if direction @ velocity < 0.0:
                direction = -direction
            lane = self._colinear(centroid, direction)
            if lane is not None:  # the leg lies on a lane the track was not matched to (its heading off)
                lane.points.extend(map(tuple, points))
                self._refit(lane, now_s, track)
                return
            along = (points - centroid) @ direction
            lane = Lane(centroid, direction, float(along.min()), float(along.max()), True, False, now_s,
                        deque(map(tuple, points), maxlen=p.max_points))
            self.lanes.append(lane)
            return
        lane.points.append((track.x, track.y))
        self._refit(lane, now_s, track)

    def _colinear(self, centroid: np.ndarray, direction: np.ndarray) -> Optional[Lane]:
        """The lane on whose line a leg (its centroid and direction) lies, None when on none."""
        for lane in self.lanes:
            if abs(float(direction @ lane.direction)) >= self._cos_tolerance \
                    and lane.off(centroid) <= self.params.line_tolerance_m:
                return lane
        return None

    def _refit(self, lane: Lane, now_s: float, track: Track) -> None:
        """The lane's line, stretch (its points hold the track's position), speed and directions, with ``track``."""
        velocity = np.array([track.vx, track.vy])
        lane.seen_s = now_s
        if len(lane.points) >= 3:
            centroid, direction, _worst = fit_line(np.array(lane.points))
            if direction @ lane.direction < 0.0:
                direction = -direction
            lane.origin, lane.direction = centroid, direction
            along = (np.array(lane.points) - centroid) @ direction
            lane.low_m, lane.high_m = float(along.min()), float(along.max())
        speed_along = float(velocity @ lane.direction)
        lane.speed_sum_mps += abs(speed_along)
        lane.speed_count += 1
        if speed_along > DIRECTION_SEEN_MPS:
            lane.forward = True
        elif speed_along < -DIRECTION_SEEN_MPS:
            lane.backward = True

    @property
    def _cos_tolerance(self) -> float:
        return math.cos(math.radians(self.params.angle_tolerance_deg))

    def lane_of(self, track: Track) -> Optional[Lane]:
        """The lane ``track`` walks on (the nearest within the tolerances), None when on none or not walking."""
        p = self.params
        if track.speed < p.min_speed_mps:
            return None
        position = np.array([track.x, track.y])
        velocity = np.array([track.vx, track.vy])
        best, best_off = None, math.inf
        with self._lock:
            lanes = list(self.lanes)
        for lane in lanes:
            off = lane.off(position)
            s = lane.along(position)
            if off > p.line_tolerance_m or abs(float(velocity @ lane.direction)) < track.speed * self._cos_tolerance:
                continue
            if s < lane.low_m - p.line_tolerance_m - p.min_leg_m or s > lane.high_m + p.line_tolerance_m + p.min_leg_m:
                continue  # a lane's own stretch (and a little beyond: it grows as walkers go farther)
            if off < best_off:
                best, best_off = lane, off
        return best

    def turning_at(self, track: Track) -> Optional[Tuple[Lane, float]]:
        """(lane, signed speed [m/s] along it) for a track within ``TURN_REACH_M`` of an end of a lane walked
        both ways (and within ``line_tolerance_m`` of its line) that is slow or walks toward that end: a walker
        turning there, about to walk back at the lane's speed (or their own, if faster); None otherwise."""
        return self._turning(track, self.lane_of(track))

    def _turning(self, track: Track, own: Optional[Lane]) -> Optional[Tuple[Lane, float]]:
        """:meth:`turning_at` for a track on lane ``own`` (None: on none; every lane is then looked at)."""
        p = self.params
        position = np.array([track.x, track.y])
        velocity = np.array([track.vx, track.vy])
        with self._lock:
            lanes = [own] if own is not None else list(self.lanes)
        for lane in lanes:
            if not lane.turned or lane.off(position) > p.line_tolerance_m:
                continue
            s = lane.along(position)
            u = float(velocity @ lane.direction)
            speed = max(lane.speed_mps, abs(u))
            if abs(s - lane.low_m) <= TURN_REACH_M and (track.speed < p.min_speed_mps or u < 0.0):
                return lane, speed
            if abs(s - lane.high_m) <= TURN_REACH_M and (track.speed < p.min_speed_mps or u > 0.0):
                return lane, -speed
        return None

    def predict(self, track: Track, times_s: np.ndarray) -> np.ndarray:
        """(K, 2) [m] positions of ``track`` at ``times_s`` (K,) [s] from its stamp on: see the module
        docstring."""
        with self._lock:
            return self._predict(track, np.asarray(times_s, dtype=np.float64))

    def _predict(self, track: Track, times: np.ndarray) -> np.ndarray:
        position = np.array([track.x, track.y])
        velocity = np.array([track.vx, track.vy])
        own = self.lane_of(track)
        turning = self._turning(track, own)
        lane = own if turning is None else turning[0]
        if lane is None:
            return np.asarray(position[None, :] + velocity[None, :] * times[:, None])
        s0 = lane.along(position)
        if turning is None:  # on a lane: at least the lane's walking speed (the tracker's lags after a turn)
            along = float(velocity @ lane.direction)
            u = math.copysign(max(abs(along), lane.speed_mps), along)
        else:
            u = turning[1]
        travelled = s0 + u * times
        inside = lane.low_m - self.params.line_tolerance_m <= s0 <= lane.high_m + self.params.line_tolerance_m
        s = bounce(travelled, min(lane.low_m, s0), max(lane.high_m, s0)) if lane.turned and inside else travelled
        return np.asarray(lane.origin[None, :] + s[:, None] * lane.direction[None, :])
