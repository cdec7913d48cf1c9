"""Path utilities for following: validation, length, closest point, lookahead by distance, pruning.

A path is an (N, 2) or (N, 3) float array of poses ``[x [m], y [m](, yaw [rad])]``, read as the
polyline through the points. Distances are in metres, never cells.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple

import numpy as np
from numba import njit

from flex_nav.exceptions import ConfigError


def as_path(poses: object, *, what: str = "path") -> np.ndarray:
    """``poses`` as a float64 (N, 2|3) array; :class:`ConfigError` if empty, misshapen or not finite."""
    try:
        path = np.array(poses, dtype=np.float64)
    except (TypeError, ValueError) as err:
        raise ConfigError(f"{what} must be an (N, 2) or (N, 3) array of numbers: {err}") from err
    if path.ndim != 2 or path.shape[1] not in (2, 3):
        raise ConfigError(f"{what} must be an (N, 2) or (N, 3) array, got shape {path.shape}")
    if path.shape[0] == 0:
        raise ConfigError(f"{what} is empty")
    if not np.isfinite(path).all():
        bad = int(np.flatnonzero(~np.isfinite(path).all(axis=1))[0])
        raise ConfigError(f"{what} has a non-finite value at pose {bad}: {path[bad].tolist()}")
    return path


def cumulative_lengths(path: np.ndarray) -> np.ndarray:
    """Arc length [m] from the first point to each point (length N, starts at 0)."""
    steps = np.hypot(np.diff(path[:, 0]), np.diff(path[:, 1]))
    return np.concatenate(([0.0], np.cumsum(steps)))


def path_length(path: np.ndarray) -> float:
    """Total length [m] of the polyline."""
    return float(cumulative_lengths(path)[-1])


@dataclass(frozen=True)
class PathPoint:
    """A point on a path: on segment ``index`` -> ``index + 1`` at fraction ``t``, ``s`` [m] from the start."""

    index: int  # segment start (0..N-1; N-1 means the last point itself)
    t: float  # 0..1 along the segment
    x: float  # [m]
    y: float  # [m]
    s: float  # [m] arc length from the path's first point
    distance: float = 0.0  # [m] from the query point (closest_point only)


def closest_point(
    path: np.ndarray,
    x: float,
    y: float,
    *,
    start_index: int = 0,
    max_arc: float = math.inf,
    lengths: np.ndarray | None = None,
    earliest_within: float = 0.0,
) -> PathPoint:
    """The point of the path nearest to (x, y) [m], searching segment ``start_index`` and the segments after
    it whose start lies less than ``max_arc`` [m] of arc beyond that segment's end (a bounded window keeps
    following monotonic and fast). Measured from the segment's end, not its start, so that a segment longer
    than the window (planners return sparse paths) never hides the next one.

    Ties go to the earliest segment. With ``earliest_within`` [m] > 0, the nearest point of the first pass of
    the path by (x, y) is taken, a pass being a run of consecutive segments at most that much farther than the
    nearest: a robot at the start of a path that loops back to it is at the start, even when the closing
    segment happens to pass a few millimetres nearer (a follower's first look at a new path).
    """
    lengths = cumulative_lengths(path) if lengths is None else lengths
    n = path.shape[0]
    start_index = min(max(int(start_index), 0), n - 1)
    if n == 1:
        return PathPoint(0, 0.0, float(path[0, 0]), float(path[0, 1]), 0.0, math.hypot(x - path[0, 0], y - path[0, 1]))
    window_end = lengths[min(start_index + 1, n - 1)] + max_arc
    stop = n - 1 if math.isinf(max_arc) else int(np.searchsorted(lengths, window_end, "left"))
    stop = min(max(stop, start_index + 1), n - 1)
    index, t, px, py, d2 = _closest_on_segments(path, start_index, stop, float(x), float(y))
    if earliest_within > 0.0 and index > start_index:
        near = _segment_distances(path[start_index:stop + 1], x, y) <= math.sqrt(d2) + earliest_within
        first = int(np.argmax(near))  # near[index - start_index] is True
        run_end = first + int(np.argmin(near[first:])) if not near[first:].all() else near.size
        if start_index + run_end <= index:  # an earlier pass of the path near (x, y): the nearest point of it
            index, t, px, py, d2 = _closest_on_segments(path, start_index + first, start_index + run_end,
                                                        float(x), float(y))
    seg = lengths[index + 1] - lengths[index]
    return PathPoint(index, t, px, py, float(lengths[index] + t * seg), math.sqrt(d2))


def _segment_distances(path: np.ndarray, x: float, y: float) -> np.ndarray:
    """[m] from (x, y) to each segment of ``path`` (N - 1 values)."""
    a, b = path[:-1, :2], path[1:, :2]
    ab = b - a
    denom = np.einsum("ij,ij->i", ab, ab)
    t = np.einsum("ij,ij->i", np.array([x, y]) - a, ab) / np.where(denom > 0.0, denom, 1.0)
    nearest = a + np.clip(t, 0.0, 1.0)[:, None] * ab
    distances: np.ndarray = np.hypot(nearest[:, 0] - x, nearest[:, 1] - y)
    return distances


@njit(cache=True, nogil=True)
def _closest_on_segments(
    path: np.ndarray, first: int, stop: int, x: float, y: float
) -> Tuple[int, float, float, float, float]:  # pragma: no cover - compiled
    # nearest point to (x, y) on segments first..stop-1 (segment i joins points i and i + 1)
    best = first
    best_t = 0.0
    best_x = path[first, 0]
    best_y = path[first, 1]
    best_d2 = np.inf
    for i in range(first, stop):
        ax = path[i, 0]
        ay = path[i, 1]
        abx = path[i + 1, 0] - ax
        aby = path[i + 1, 1] - ay
        denom = abx * abx + aby * aby
        t = ((x - ax) * abx + (y - ay) * aby) / denom if denom > 0.0 else 0.0
        t = min(max(t, 0.0), 1.0)
        px = ax + t * abx
        py = ay + t * aby
        d2 = (px - x) * (px - x) + (py - y) * (py - y)
        if d2 < best_d2:
            best, best_t, best_x, best_y, best_d2 = i, t, px, py, d2
    return best, best_t, best_x, best_y, best_d2


@njit(cache=True, nogil=True)
def _first_outside(path: np.ndarray, first: int, x: float, y: float, radius: float) -> int:  # pragma: no cover
    # index of the first point from ``first`` on at least ``radius`` from (x, y); -1 if none
    r2 = radius * radius
    for i in range(first, path.shape[0]):
        dx = path[i, 0] - x
        dy = path[i, 1] - y
        if dx * dx + dy * dy >= r2:
            return i
    return -1


def point_at_arc(path: np.ndarray, s: float, lengths: np.ndarray | None = None) -> PathPoint:
    """The point ``s`` [m] of arc length from the path's start (clamped to the ends)."""
    lengths = cumulative_lengths(path) if lengths is None else lengths
    n = path.shape[0]
    if n == 1 or s <= 0.0:
        return PathPoint(0, 0.0, float(path[0, 0]), float(path[0, 1]), 0.0)
    if s >= lengths[-1]:
        return PathPoint(n - 1, 0.0, float(path[-1, 0]), float(path[-1, 1]), float(lengths[-1]))
    index = int(np.searchsorted(lengths, s, "right")) - 1
    seg = lengths[index + 1] - lengths[index]
    t = (s - lengths[index]) / seg if seg > 0 else 0.0
    x = path[index, 0] + t * (path[index + 1, 0] - path[index, 0])
    y = path[index, 1] + t * (path[index + 1, 1] - path[index, 1])
    return PathPoint(index, float(t), float(x), float(y), float(s))


def lookahead_point(
    path: np.ndarray, x: float, y: float, distance: float, *, start: PathPoint, lengths: np.ndarray | None = None
) -> PathPoint:
    """Pure pursuit's carrot: the first point after ``start`` (a point on the path) that is ``distance`` [m]
    (straight line) from (x, y), interpolated where the path crosses that circle; the path's end if the
    whole rest of the path is inside the circle.
    """
    lengths = cumulative_lengths(path) if lengths is None else lengths
    n = path.shape[0]
    if n == 1:
        return PathPoint(0, 0.0, float(path[0, 0]), float(path[0, 1]), 0.0)
    j = _first_outside(path, start.index + 1, float(x), float(y), float(distance))  # first vertex on/outside
    if j < 0:
        return PathPoint(n - 1, 0.0, float(path[-1, 0]), float(path[-1, 1]), float(lengths[-1]))
    # the segment (j-1 -> j) crosses the circle; begin at the start point if it lies on that segment
    if j - 1 == start.index:
        ax, ay = start.x, start.y
    else:
        ax, ay = path[j - 1, 0], path[j - 1, 1]
    bx, by = path[j, 0], path[j, 1]
    t = _circle_exit(ax - x, ay - y, bx - ax, by - ay, distance)
    px, py = ax + t * (bx - ax), ay + t * (by - ay)
    seg = lengths[j] - lengths[j - 1]
    s_a = start.s if j - 1 == start.index else lengths[j - 1]
    s = s_a + t * math.hypot(bx - ax, by - ay)
    t_seg = (s - lengths[j - 1]) / seg if seg > 0 else 1.0
    return PathPoint(j - 1, float(min(max(t_seg, 0.0), 1.0)), float(px), float(py), float(s))


def _circle_exit(fx: float, fy: float, dx: float, dy: float, radius: float) -> float:
    # largest t in [0, 1] with |f + t·d| = radius, for f inside (or on) the circle and f + d outside/on it
    a = dx * dx + dy * dy
    if a == 0.0:
        return 1.0
    b = 2.0 * (fx * dx + fy * dy)
    c = fx * fx + fy * fy - radius * radius
    disc = max(b * b - 4.0 * a * c, 0.0)
    t = (-b + math.sqrt(disc)) / (2.0 * a)
    return min(max(t, 0.0), 1.0)


def prune_passed(
    path: np.ndarray, x: float, y: float, *, start_index: int = 0, max_arc: float = math.inf
) -> Tuple[np.ndarray, int]:
    """The rest of the path from the point closest to (x, y) (which becomes its first pose), and that
    point's segment index in the original path."""
    closest = closest_point(path, x, y, start_index=start_index, max_arc=max_arc)
    rest = path[closest.index + 1 :]
    first = path[closest.index].copy()
    first[0], first[1] = closest.x, closest.y
    if rest.shape[0] and rest[0, 0] == first[0] and rest[0, 1] == first[1]:
        return rest.copy(), closest.index  # the closest point is the next pose itself
    return np.vstack([first[None, :], rest]), closest.index


def detour_m(old: np.ndarray, new: np.ndarray) -> float:
    """[m] how much longer ``new`` (a replan from where the robot stands, its first point) is than the rest of
    ``old`` from the point of ``old`` nearest that start (negative: shorter). A path of one point is 0 m long."""
    if new.shape[0] == 0 or old.shape[0] == 0:
        raise ConfigError(f"detour_m needs two paths with points ({old.shape[0]} and {new.shape[0]} given)")
    lengths = cumulative_lengths(old)
    start = closest_point(old, float(new[0, 0]), float(new[0, 1]), lengths=lengths, earliest_within=0.1)
    return path_length(new) - (float(lengths[-1]) - start.s)
