"""The console's map view without ROS: the occupancy grid as PNG (once, then changed rectangles), the robots'
overlays as compact JSON, and the goals and initial poses a page places by clicking the map, checked.

Events to the page (the ROS side, :mod:`flex_nav.nodes.console`, converts messages into the plain values these
functions take):

``map``        frame, resolution [m/cell], width, height [cells], origin [x m, y m, yaw rad], png (base64 of a
               grayscale PNG, row 0 = the map's top, i.e. its largest y), version
``map_patch``  version, x, y, width, height [cells: the rectangle's top-left column and row in the PNG's rows], png
``overlay``    robot, kind (``pose``, ``global_plan``, ``local_plan``, ``scan``, ``particles``, ``people``,
               ``memory``), stamp [s] and ``pose``: x, y, yaw, radius [m, rad] and footprint ([[x, y], ...] in the
               robot's base frame, when the robot publishes one; else the circle of radius); ``memory``: obstacles
               [{id, footprint [[x, y], ...], text}] (the heavy obstacles its global costmap remembers, at most
               ``MAX_REMEMBERED``) and truncated (how many more were not sent); the others: points [[x, y], ...]
               (particles and tracked people [[x, y, yaw]]), in the map frame, rounded to millimetres and thinned to
               at most the kind's point budget

From a page: ``{"type": "goal", "id", "robot", "kind": "goal" | "initial_pose", "x", "y", "yaw"}`` in the map
frame; :func:`check_goal` refuses a robot not on the master, a non-finite number, a point off the map.
"""

from __future__ import annotations

import base64
import dataclasses
import math
import time
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import cv2
import numpy as np

from flex_nav.console.errors import CommandRefused, MapViewError

GOAL_KINDS = ("goal", "initial_pose")
OVERLAY_KINDS = ("pose", "global_plan", "local_plan", "scan", "particles", "people", "memory")
MAX_POINTS = {"global_plan": 2000, "local_plan": 500, "scan": 720, "particles": 500, "people": 100}  # per message
MIN_PERIOD_S = {"pose": 0.1, "global_plan": 0.2, "local_plan": 0.2, "scan": 0.2, "particles": 0.5,
                "people": 0.2, "memory": 0.5}  # [s]
MAX_FOOTPRINT_POINTS = 64
MAX_REMEMBERED = 200  # remembered obstacles of one robot sent to the pages
MAX_REMEMBERED_TEXT = 200  # [characters] of one remembered obstacle's text
MAX_MAP_CELLS = 25_000_000  # a 5000 x 5000 grid; a larger one is not shown
PNG_LEVEL = 6  # zlib level of the map's PNG (0-9)
# map_server's picture of a grid: free white, occupied black, unknown grey; costs in between shade linearly
FREE, OCCUPIED, UNKNOWN = 254, 0, 205


@dataclasses.dataclass(frozen=True)
class GridGeometry:
    """Where a grid lies: ``resolution`` [m/cell], ``width`` x ``height`` [cells], origin (x [m], y [m], yaw
    [rad]) of cell (0, 0)'s corner, in ``frame``."""

    frame: str
    resolution: float
    width: int
    height: int
    origin: Tuple[float, float, float]

    def contains(self, x: float, y: float) -> bool:
        """Whether the map-frame point (x, y) [m] lies on the grid."""
        ox, oy, yaw = self.origin
        dx, dy = x - ox, y - oy
        c, s = math.cos(yaw), math.sin(yaw)
        u, v = (c * dx + s * dy) / self.resolution, (-s * dx + c * dy) / self.resolution
        return 0.0 <= u < self.width and 0.0 <= v < self.height


def grid_image(data: Sequence[int] | np.ndarray, width: int, height: int) -> np.ndarray:
    """The grayscale picture (uint8, ``height`` x ``width``, row 0 = largest y) of an OccupancyGrid's ``data``
    (row-major from the origin, -1 unknown, 0..100 occupancy)."""
    cells = np.frombuffer(data, dtype=np.int8) if isinstance(data, (bytes, bytearray)) else np.asarray(data)
    if cells.size != width * height:
        raise MapViewError(f"the map has {cells.size} cells, not width x height = {width} x {height}")
    values = cells.astype(np.int16).reshape(height, width)[::-1]
    shade = (FREE - (np.clip(values, 0, 100) * (FREE - OCCUPIED)) // 100).astype(np.uint8)
    shade[values < 0] = UNKNOWN
    return np.ascontiguousarray(shade)


def _png64(gray: np.ndarray) -> str:
    """Base64 of a grayscale 8-bit PNG of ``gray`` (rows x columns, uint8), encoded by OpenCV."""
    ok, encoded = cv2.imencode(".png", gray, [cv2.IMWRITE_PNG_COMPRESSION, PNG_LEVEL])
    if not ok:
        raise MapViewError(f"OpenCV could not encode a {gray.shape[1]} x {gray.shape[0]} map as PNG")
    return base64.b64encode(encoded.tobytes()).decode("ascii")


class MapPicture:
    """The map as the pages have it: :meth:`update` returns the event that brings them up to date (the whole map
    when it is new or its geometry changed, else the rectangle that changed, or None when nothing did);
    :meth:`whole_event` the whole map for a page that connects later (encoded only when asked for)."""

    def __init__(self) -> None:
        self.geometry: Optional[GridGeometry] = None
        self.image: Optional[np.ndarray] = None
        self.version = 0
        self._whole: Optional[Dict[str, Any]] = None  # the latest whole-map event made (of version _whole_version)

    def update(self, geometry: GridGeometry, data: Sequence[int] | np.ndarray) -> Optional[Dict[str, Any]]:
        if geometry.width < 1 or geometry.height < 1 or geometry.width * geometry.height > MAX_MAP_CELLS:
            raise MapViewError(f"a map of {geometry.width} x {geometry.height} cells is not shown "
                               f"(1 .. {MAX_MAP_CELLS} cells)")
        if not (math.isfinite(geometry.resolution) and geometry.resolution > 0):
            raise MapViewError(f"map resolution {geometry.resolution!r} is not a positive number")
        image = grid_image(data, geometry.width, geometry.height)
        old = self.image
        if geometry == self.geometry and old is not None:
            changed = np.nonzero(old != image)
            if changed[0].size == 0:
                return None
            self.version += 1
            self.image = image
            top, bottom = int(changed[0].min()), int(changed[0].max()) + 1
            left, right = int(changed[1].min()), int(changed[1].max()) + 1
            return {"type": "map_patch", "version": self.version, "x": left, "y": top, "width": right - left,
                    "height": bottom - top, "png": _png64(image[top:bottom, left:right])}
        self.version += 1
        self.geometry, self.image = geometry, image
        return self.whole_event()

    def whole_event(self) -> Optional[Dict[str, Any]]:
        """The whole map at its current version (None before the first map)."""
        if self.image is None or self.geometry is None:
            return None
        if self._whole is None or self._whole["version"] != self.version:
            g = self.geometry
            self._whole = {"type": "map", "frame": g.frame, "resolution": g.resolution, "width": g.width,
                           "height": g.height, "origin": [round(v, 6) for v in g.origin],
                           "png": _png64(self.image), "version": self.version}
        return self._whole


def _points(values: np.ndarray, budget: int) -> List[List[float]]:
    if len(values) > budget:
        values = values[np.linspace(0, len(values) - 1, budget).round().astype(int)]
    rows: List[List[float]] = np.round(values, 3).tolist()
    return rows


def pose_overlay(robot: str, stamp: float, pose: Tuple[float, float, float], radius: float,
                 footprint: Optional[np.ndarray] = None) -> Dict[str, Any]:
    """A robot's ``pose`` (x [m], y [m], yaw [rad]) in the map frame, the ``radius`` [m] of its round footprint and
    its ``footprint`` polygon ((x, y) rows [m] in its base frame; None: draw the circle)."""
    x, y, yaw = pose
    event = {"type": "overlay", "robot": robot, "kind": "pose", "stamp": stamp, "x": round(x, 3), "y": round(y, 3),
             "yaw": round(yaw, 4), "radius": round(radius, 3)}
    if footprint is not None and len(footprint) >= 3:
        event["footprint"] = _points(np.asarray(footprint, dtype=float).reshape(-1, 2), MAX_FOOTPRINT_POINTS)
    return event


def path_overlay(robot: str, kind: str, stamp: float, points: np.ndarray) -> Dict[str, Any]:
    """A plan (``global_plan`` or ``local_plan``): map-frame (x, y) rows [m], thinned to the kind's budget."""
    if kind not in ("global_plan", "local_plan"):
        raise MapViewError(f"overlay kind {kind!r} is not a plan (valid: global_plan, local_plan)")
    rows = np.asarray(points, dtype=float).reshape(-1, 2)
    return {"type": "overlay", "robot": robot, "kind": kind, "stamp": stamp, "points": _points(rows, MAX_POINTS[kind])}


def scan_overlay(robot: str, stamp: float, *, ranges: Sequence[float] | np.ndarray, angle_min: float,
                 angle_increment: float, range_min: float, range_max: float,
                 laser_pose: Tuple[float, float, float]) -> Dict[str, Any]:
    """The scan's end points in the map frame: ``laser_pose`` (x [m], y [m], yaw [rad]) of the laser in the map,
    readings outside [range_min, range_max] or not finite dropped."""
    r = np.asarray(ranges, dtype=float)
    angles = angle_min + angle_increment * np.arange(r.size)
    valid = np.isfinite(r) & (r >= range_min) & (r <= range_max)
    lx, ly, lyaw = laser_pose
    a = angles[valid] + lyaw
    rows = np.stack([lx + r[valid] * np.cos(a), ly + r[valid] * np.sin(a)], axis=1)
    return {"type": "overlay", "robot": robot, "kind": "scan", "stamp": stamp,
            "points": _points(rows, MAX_POINTS["scan"])}


def poses_overlay(robot: str, kind: str, stamp: float, poses: np.ndarray) -> Dict[str, Any]:
    """The localizer's ``particles`` or the tracked ``people``: (x [m], y [m], yaw [rad]) rows in the map frame."""
    if kind not in ("particles", "people"):
        raise MapViewError(f"overlay kind {kind!r} is not a set of poses (valid: particles, people)")
    rows = np.asarray(poses, dtype=float).reshape(-1, 3)
    return {"type": "overlay", "robot": robot, "kind": kind, "stamp": stamp, "points": _points(rows, MAX_POINTS[kind])}


def memory_overlay(robot: str, stamp: float, obstacles: Sequence[Tuple[int, np.ndarray, str]]) -> Dict[str, Any]:
    """The heavy obstacles a robot's global costmap remembers: (id, footprint (N >= 3, 2) [m] in the map frame,
    text) each, at most ``MAX_REMEMBERED`` (``truncated``: how many more), a footprint thinned to
    ``MAX_FOOTPRINT_POINTS`` corners, a text to ``MAX_REMEMBERED_TEXT`` characters; footprints with fewer than three
    corners or a corner that is not finite are left out."""
    shown: List[Dict[str, Any]] = []
    for obstacle_id, footprint, text in obstacles[:MAX_REMEMBERED]:
        rows = np.asarray(footprint, dtype=float).reshape(-1, 2)
        if len(rows) < 3 or not np.isfinite(rows).all():
            continue
        shown.append({"id": int(obstacle_id), "footprint": _points(rows, MAX_FOOTPRINT_POINTS),
                      "text": str(text)[:MAX_REMEMBERED_TEXT]})
    return {"type": "overlay", "robot": robot, "kind": "memory", "stamp": stamp, "obstacles": shown,
            "truncated": max(0, len(obstacles) - MAX_REMEMBERED)}


class Throttle:
    """At most one overlay of a kind per robot every ``MIN_PERIOD_S[kind]`` [s] (``clock``: seconds)."""

    def __init__(self, clock: Callable[[], float] = time.monotonic) -> None:
        self._clock = clock
        self._last: Dict[Tuple[str, str], float] = {}

    def due(self, robot: str, kind: str) -> bool:
        now = self._clock()
        last = self._last.get((robot, kind))
        if last is not None and now - last < MIN_PERIOD_S.get(kind, 0.0):
            return False
        self._last[(robot, kind)] = now
        return True


@dataclasses.dataclass(frozen=True)
class GoalRequest:
    """A checked goal or initial pose for ``robot`` (a runner's name), in the map frame."""

    robot: str
    kind: str
    x: float
    y: float
    yaw: float


def check_goal(data: Mapping[str, Any], robots: Sequence[str], geometry: Optional[GridGeometry]) -> GoalRequest:
    """The page's goal message as a GoalRequest, or CommandRefused with the reason and the field."""
    robot = data.get("robot")
    if not isinstance(robot, str) or robot not in robots:
        shown = repr(robot)[:100]
        raise CommandRefused(f"robot {shown} is not valid (valid: {', '.join(sorted(robots)) or 'none'})",
                             "robot", sorted(robots))
    kind = data.get("kind")
    if kind not in GOAL_KINDS:
        raise CommandRefused(f"kind {repr(kind)[:100]} is not valid (valid: {', '.join(GOAL_KINDS)})", "kind",
                             GOAL_KINDS)
    values = []
    for name in ("x", "y", "yaw"):
        value = data.get(name)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise CommandRefused(f"{kind}: {name} must be a finite number, got {repr(value)[:100]}", name)
        values.append(float(value))
    x, y, yaw = values
    if geometry is None:
        raise CommandRefused(f"{kind}: no map yet, so no point can be checked against it", "x")
    if not geometry.contains(x, y):
        raise CommandRefused(f"{kind}: ({x:.2f}, {y:.2f}) m is off the map", "x")
    return GoalRequest(robot, str(kind), x, y, math.atan2(math.sin(yaw), math.cos(yaw)))


def robot_namespace(runner: str) -> str:
    """The namespace of a runner's robot: ``/robot1/behavior_runner`` -> ``/robot1``, ``/behavior_runner`` -> ``""``."""
    return runner[: runner.rfind("/")] if "/" in runner else ""
