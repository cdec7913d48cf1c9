"""Tracking small objects seen by a laser scanner (people, in practice) with constant-velocity filters.

Each scan (hit points in the tracking frame, e.g. ``map``, in beam order) is cut into segments
(:mod:`flex_nav.perception.scan_segments`) after dropping the points the static map explains
(:class:`~flex_nav.perception.static_mask.StaticMask`, optional). Every track is a Kalman filter on
(x, y, vx, vy) with white-acceleration process noise; segments are matched to the tracks' predicted
positions greedily, nearest pair first, within a gate of ``gate_m + max_speed_mps * dt`` [m]. Unmatched
segments start tracks (velocity unknown: 1 m/s standard deviation); a track unseen for ``max_missed_s`` [s]
is dropped; a track is *confirmed* after ``confirm_hits`` matches. :meth:`MovingObstacleTracker.tracks`
gives every confirmed track predicted to a query time, with its position, velocity and radius.

Whether a track *moves* is the user's call (its speed against a threshold): a box is a track with a
velocity near zero. Pure numpy, no ROS, no clock of its own: scans carry their time stamps [s].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Set, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.perception.scan_segments import Segment, SegmentParams, segments
from flex_nav.perception.static_mask import StaticMask

INITIAL_SPEED_STD = 1.0  # [m/s] velocity uncertainty of a new track
CLOCK_JUMP_BACK_S = 1.0  # [s] a scan this much older than the last one means the clock was reset


@dataclass(frozen=True)
class TrackerParams:
    """Tracking parameters; units in comments."""

    gate_m: float = 0.5  # [m] match distance around a predicted position (plus max_speed_mps * dt)
    max_speed_mps: float = 1.5  # [m/s] fastest object followed (widens the gate after missed scans)
    accel_std_mps2: float = 1.5  # [m/s^2] process noise: how hard tracked objects change velocity
    measurement_std_m: float = 0.06  # [m] segment centre noise
    confirm_hits: int = 3  # matches before a track is reported
    max_missed_s: float = 0.8  # [s] a track unseen this long is dropped
    radius_smoothing: float = 0.3  # weight of a new radius measurement (exponential average)
    max_tracks: int = 64  # more tracks than this: the oldest unconfirmed ones are dropped

    def __post_init__(self) -> None:
        for name in ("gate_m", "max_speed_mps", "accel_std_mps2", "measurement_std_m", "max_missed_s"):
            value = getattr(self, name)
            if not math.isfinite(value) or value <= 0.0:
                raise ConfigError(f"tracker parameter {name} must be a finite number > 0, got {value!r}")
        if not 0.0 < self.radius_smoothing <= 1.0:
            raise ConfigError(f"tracker parameter radius_smoothing must be in (0, 1], got {self.radius_smoothing!r}")
        if self.confirm_hits < 1 or self.max_tracks < 1:
            raise ConfigError(f"tracker parameters confirm_hits and max_tracks must be >= 1, got "
                              f"{self.confirm_hits!r} and {self.max_tracks!r}")


@dataclass(frozen=True)
class Track:
    """A tracked object at ``stamp_s`` [s]: centre (x, y) [m], velocity (vx, vy) [m/s], radius [m]."""

    track_id: int
    x: float
    y: float
    vx: float
    vy: float
    radius: float
    stamp_s: float
    hits: int

    @property
    def speed(self) -> float:
        """[m/s]"""
        return math.hypot(self.vx, self.vy)


@dataclass
class _Filter:
    track_id: int
    state: np.ndarray  # (4,) x, y, vx, vy
    cov: np.ndarray  # (4, 4)
    radius: float
    stamp_s: float  # time of the state
    seen_s: float  # time of the last match
    hits: int = 1
    matched: bool = field(default=False, repr=False)


def _transition(dt: float) -> np.ndarray:
    f = np.eye(4)
    f[0, 2] = f[1, 3] = dt
    return f


def _process_noise(dt: float, accel_std: float) -> np.ndarray:
    q = accel_std * accel_std
    a, b, c = dt**4 / 4.0, dt**3 / 2.0, dt**2
    return q * np.array([[a, 0.0, b, 0.0], [0.0, a, 0.0, b], [b, 0.0, c, 0.0], [0.0, b, 0.0, c]])


class MovingObstacleTracker:
    """Tracks of the small objects in a stream of scans; see the module docstring. Not thread-safe: the
    caller serialises :meth:`update_scan` / :meth:`update` and :meth:`tracks`."""

    def __init__(self, params: Optional[TrackerParams] = None, segment_params: Optional[SegmentParams] = None,
                 static_mask: Optional[StaticMask] = None) -> None:
        self.params = params if params is not None else TrackerParams()
        self.segment_params = segment_params if segment_params is not None else SegmentParams()
        self.static_mask = static_mask
        self._filters: List[_Filter] = []
        self._next_id = 1
        self._last_stamp_s: Optional[float] = None
        r = self.params.measurement_std_m
        self._meas_cov = np.eye(2) * r * r

    def reset(self) -> None:
        """Forget every track (e.g. after a clock reset or a relocalisation)."""
        self._filters = []
        self._last_stamp_s = None

    def update_scan(self, xs: np.ndarray, ys: np.ndarray, sensor: Tuple[float, float], stamp_s: float, *,
                    wrap: bool = True) -> List[Segment]:
        """One scan's beam end points (tracking frame [m], beam order; NaN for a beam without a return), seen
        from ``sensor`` (x, y) [m] at ``stamp_s`` [s]; ``wrap``: the scan covers 360 degrees (its last
        beam neighbours its first). Returns the segments it was cut into (after the static mask)."""
        xs = np.asarray(xs, dtype=np.float64)
        ys = np.asarray(ys, dtype=np.float64)
        if self.static_mask is not None and xs.size:
            keep = ~self.static_mask.explained(xs, ys)
            # a dropped point is a gap (NaN): keep the beam order, never join points across it
            xs, ys = np.where(keep, xs, np.nan), np.where(keep, ys, np.nan)
        found = segments(xs, ys, sensor, self.segment_params, wrap=wrap)
        self.update(found, stamp_s)
        return found

    def update(self, found: Sequence[Segment], stamp_s: float) -> None:
        """Match ``found`` (segments of one scan at ``stamp_s`` [s]) to the tracks and update them."""
        if not math.isfinite(stamp_s):
            raise ConfigError(f"scan time stamp must be finite [s], got {stamp_s!r}")
        if self._last_stamp_s is not None and stamp_s < self._last_stamp_s:
            if stamp_s < self._last_stamp_s - CLOCK_JUMP_BACK_S:
                self.reset()
            else:
                return  # an old scan arriving late: the tracks are already past it
        self._last_stamp_s = stamp_s
        p = self.params
        for flt in self._filters:
            self._predict(flt, stamp_s)
            flt.matched = False
        used = self._associate(found, stamp_s)
        for j, seg in enumerate(found):
            if j not in used:
                self._start(seg, stamp_s)
        self._filters = [f for f in self._filters if stamp_s - f.seen_s <= p.max_missed_s]
        if len(self._filters) > p.max_tracks:
            self._filters.sort(key=lambda f: (f.hits >= p.confirm_hits, f.seen_s), reverse=True)
            del self._filters[p.max_tracks:]

    def tracks(self, now_s: float) -> List[Track]:
        """Every confirmed track, its position predicted to ``now_s`` [s] (never back in time)."""
        out = []
        for flt in self._filters:
            if flt.hits < self.params.confirm_hits:
                continue
            x, y, vx, vy = (float(v) for v in flt.state)
            dt = max(0.0, now_s - flt.stamp_s)
            out.append(Track(flt.track_id, x + vx * dt, y + vy * dt, vx, vy, flt.radius,
                             max(now_s, flt.stamp_s), flt.hits))
        return out

    # ------------------------------------------------------------------ filter steps
    def _associate(self, found: Sequence[Segment], stamp_s: float) -> Set[int]:
        """Greedy nearest-pair matching within the gates; corrects the matched tracks, returns the used segments."""
        p = self.params
        pairs = []
        for i, flt in enumerate(self._filters):
            gate = p.gate_m + p.max_speed_mps * max(0.0, stamp_s - flt.seen_s)
            for j, seg in enumerate(found):
                d = math.hypot(seg.x - flt.state[0], seg.y - flt.state[1])
                if d <= gate:
                    pairs.append((d, i, j))
        pairs.sort()
        used: Set[int] = set()
        for _d, i, j in pairs:
            flt = self._filters[i]
            if flt.matched or j in used:
                continue
            used.add(j)
            self._correct(flt, found[j], stamp_s)
        return used

    def _predict(self, flt: _Filter, stamp_s: float) -> None:
        dt = stamp_s - flt.stamp_s
        if dt <= 0.0:
            return
        f = _transition(dt)
        flt.state = f @ flt.state
        flt.cov = f @ flt.cov @ f.T + _process_noise(dt, self.params.accel_std_mps2)
        flt.stamp_s = stamp_s

    def _correct(self, flt: _Filter, seg: Segment, stamp_s: float) -> None:
        (a, b), (c, d) = (flt.cov[:2, :2] + self._meas_cov).tolist()
        det = a * d - b * c  # > 0: a covariance plus the measurement noise
        # the 2x2 inverse in closed form: np.linalg.inv's per-call overhead was 40 % of a controller's time in S4
        gain = flt.cov[:, :2] @ np.array([[d, -b], [-c, a]]) * (1.0 / det)
        innovation = np.array([seg.x, seg.y]) - flt.state[:2]
        flt.state = flt.state + gain @ innovation
        flt.cov = flt.cov - gain @ flt.cov[:2, :]
        speed = math.hypot(flt.state[2], flt.state[3])
        if speed > self.params.max_speed_mps:  # a wrong match must not fling a track across the room
            flt.state[2:] *= self.params.max_speed_mps / speed
        a = self.params.radius_smoothing
        flt.radius = (1.0 - a) * flt.radius + a * seg.radius
        flt.seen_s = stamp_s
        flt.hits += 1
        flt.matched = True

    def _start(self, seg: Segment, stamp_s: float) -> None:
        r = self.params.measurement_std_m
        cov = np.diag([r * r, r * r, INITIAL_SPEED_STD**2, INITIAL_SPEED_STD**2])
        self._filters.append(_Filter(self._next_id, np.array([seg.x, seg.y, 0.0, 0.0]), cov, seg.radius,
                                     stamp_s, stamp_s))
        self._next_id += 1
