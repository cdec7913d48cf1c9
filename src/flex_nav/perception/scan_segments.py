"""Laser scan points grouped into segments (clusters) of small objects: where a leg, a person or a box is.

A planar scan sampled in beam order breaks into segments wherever two neighbouring hits lie farther apart
than a gap threshold. The threshold grows with range (neighbouring beams of one surface are
``range * angle_increment`` apart), so a far person is still one segment. A segment wider than
``max_width_m`` [m] is a wall or furniture, not something that walks: it is dropped.

Each kept segment gives the centre of the round body it is the visible front of: the beams see the near
half of a circle of radius r, whose mean point lies ``(1 - pi/4) r`` behind the nearest point, i.e.
``(pi/4) r`` in front of the centre; the centre is the mean point moved ``(pi/4) r`` away from the sensor.
A segment wider than ``split_width_m`` [m] (but not too wide) is taken for bodies side by side (two people
walking past each other) and cut into equal pieces, one body each.
r is half the segment's width plus one beam spacing (the visible chord of a circle seen from a distance
is its diameter, less up to one beam spacing at each edge).

Pure numpy, no ROS: the caller passes the scan's beam end points already in the tracking frame, in beam
order, NaN where a beam has no return (or its point was dropped): a NaN always separates segments.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError


@dataclass(frozen=True)
class SegmentParams:
    """How scan points are grouped; units in comments."""

    gap_m: float = 0.12  # [m] neighbouring hits closer than this belong together (at short range)
    gap_per_m: float = 0.04  # [m per m of range] added to ``gap_m``: far beams are farther apart
    min_points: int = 2  # fewer hits than this are noise
    max_width_m: float = 0.9  # [m] wider segments are walls or furniture (dropped)
    split_width_m: float = 0.55  # [m] wider segments are bodies side by side: cut into equal pieces
    min_radius_m: float = 0.1  # [m] smallest body radius reported
    max_radius_m: float = 0.4  # [m] largest body radius reported

    def __post_init__(self) -> None:
        for name in ("gap_m", "max_width_m", "split_width_m", "min_radius_m", "max_radius_m"):
            value = getattr(self, name)
            if not math.isfinite(value) or value <= 0.0:
                raise ConfigError(f"segment parameter {name} must be a finite number > 0 [m], got {value!r}")
        if not math.isfinite(self.gap_per_m) or self.gap_per_m < 0.0:
            raise ConfigError(f"segment parameter gap_per_m must be a finite number >= 0, got {self.gap_per_m!r}")
        if self.min_points < 1:
            raise ConfigError(f"segment parameter min_points must be >= 1, got {self.min_points!r}")
        if self.max_radius_m < self.min_radius_m:
            raise ConfigError(f"segment parameter max_radius_m ({self.max_radius_m!r}) must be >= "
                              f"min_radius_m ({self.min_radius_m!r})")


@dataclass(frozen=True)
class Segment:
    """One small object seen in a scan: estimated body centre (x, y) [m], radius [m], number of hits."""

    x: float
    y: float
    radius: float
    points: int


def split_points(xs: np.ndarray, ys: np.ndarray, ranges: np.ndarray, params: SegmentParams,
                 wrap: bool) -> List[np.ndarray]:
    """Index arrays of the runs of consecutive points (beam order) closer than the gap threshold.

    ``ranges`` [m] are the points' distances from the sensor (they set the threshold). With ``wrap`` (a
    360-degree scan) the last run joins the first when their end points are close.
    """
    count = len(xs)
    if count == 0:
        return []
    step = np.hypot(np.diff(xs), np.diff(ys))
    limit = params.gap_m + params.gap_per_m * np.maximum(ranges[:-1], ranges[1:])
    breaks = np.flatnonzero(step > limit) + 1
    runs = np.split(np.arange(count), breaks)
    if wrap and len(runs) > 1:
        gap = math.hypot(xs[0] - xs[-1], ys[0] - ys[-1])
        if gap <= params.gap_m + params.gap_per_m * max(ranges[0], ranges[-1]):
            runs = [np.concatenate((runs[-1], runs[0])), *runs[1:-1]]
    return runs


def segments(xs: np.ndarray, ys: np.ndarray, sensor: Tuple[float, float], params: SegmentParams, *,
             wrap: bool = True) -> List[Segment]:
    """The small objects in one scan's end points (``xs``, ``ys`` [m], beam order, tracking frame, NaN: no
    point) seen from the sensor at ``sensor`` (x, y) [m]; ``wrap``: the scan covers 360 degrees (its last beam
    neighbours its first). See the module docstring."""
    xs = np.asarray(xs, dtype=np.float64)
    ys = np.asarray(ys, dtype=np.float64)
    if xs.shape != ys.shape or xs.ndim != 1:
        raise ConfigError(f"scan points need two 1-D arrays of one length, got shapes {xs.shape} and {ys.shape}")
    finite = np.isfinite(xs) & np.isfinite(ys)
    if finite.all():
        return _segments_of_run(xs, ys, sensor, params, wrap)
    if wrap and finite.any():  # start at a gap so that no run straddles the scan's seam
        first_gap = int(np.flatnonzero(~finite)[0])
        xs, ys, finite = np.roll(xs, -first_gap), np.roll(ys, -first_gap), np.roll(finite, -first_gap)
    found: List[Segment] = []
    bounds = np.flatnonzero(np.diff(np.concatenate(([0], finite.astype(np.int8), [0]))))
    for start, stop in zip(bounds[::2], bounds[1::2]):
        found.extend(_segments_of_run(xs[start:stop], ys[start:stop], sensor, params, False))
    return found


def _segments_of_run(xs: np.ndarray, ys: np.ndarray, sensor: Tuple[float, float], params: SegmentParams,
                     wrap: bool) -> List[Segment]:
    sensor_x, sensor_y = sensor
    ranges = np.hypot(xs - sensor_x, ys - sensor_y)
    found: List[Segment] = []
    for run in split_points(xs, ys, ranges, params, wrap):
        if len(run) < params.min_points:
            continue
        px, py = xs[run], ys[run]
        width = math.hypot(px[-1] - px[0], py[-1] - py[0])
        spread = math.hypot(float(px.max() - px.min()), float(py.max() - py.min()))
        if max(width, spread) > params.max_width_m:
            continue
        pieces = max(1, math.ceil(width / params.split_width_m - 1e-9))
        if pieces > 1 and len(run) >= 2 * pieces:  # bodies side by side: equal pieces
            found.extend(_body(xs[piece], ys[piece], sensor, params) for piece in np.array_split(run, pieces))
        else:
            found.append(_body(px, py, sensor, params))
    return found


def _body(px: np.ndarray, py: np.ndarray, sensor: Tuple[float, float], params: SegmentParams) -> Segment:
    """The round body whose visible front is the points (``px``, ``py``); see the module docstring."""
    sensor_x, sensor_y = sensor
    width = math.hypot(px[-1] - px[0], py[-1] - py[0])
    spacing = width / (len(px) - 1) if len(px) > 1 else 0.0
    radius = min(max(0.5 * (width + spacing), params.min_radius_m), params.max_radius_m)
    mx, my = float(px.mean()), float(py.mean())
    dx, dy = mx - sensor_x, my - sensor_y
    dist = math.hypot(dx, dy)
    shift = (math.pi / 4.0) * radius
    if dist > 1e-9:
        mx, my = mx + shift * dx / dist, my + shift * dy / dist
    return Segment(mx, my, radius, len(px))
