"""Worlds as YAML: a validating loader into frozen dataclasses (no physics here).

A world file (``sim/worlds/<name>.yaml``) holds:

- ``rooms`` (rectangles of four walls), ``walls`` (segments) and ``wall_images`` (walls from a
  map image, map_server conventions), all static;
- ``doors``: a gap cut into the wall they sit on, with a panel that is there when ``closed``;
- ``obstacles``: static boxes and cylinders; one lower than ``map.min_height`` is a *low* obstacle,
  left out of the static map (the lidar does not see it, the bumper does);
- ``boxes``: movable boxes with ``mass`` [kg] and ``friction`` [-];
- ``people``: standing (one point) or walking along ``waypoints`` at ``speed`` [m/s], kinematic;
- ``events``: scripted changes at a simulated time (``remove``/``add`` a solid, ``open``/``close`` a
  door, ``start_walking``/``stop_walking`` a person, ``teleport`` a robot to ``pose``: the kidnapped robot,
  whose odometry does not see the jump);
- ``robots``: the default spawns (name = ROS namespace, profile, pose) and ``goals`` (named poses).

Poses are ``[x, y]`` or ``[x, y, yaw_deg]`` ([m], [m], [deg]). Every error names the file, the field
and the valid choices; unknown fields are errors. See ``docs`` in the world files for examples.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Mapping, Optional, Sequence, Tuple

import cv2
import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.nav.costmap.map_io import image_to_occupancy
from flex_nav_sim.geometry2d import Footprint, Point, project_on_segment, segment_footprint
from flex_nav_sim.profiles import PROFILE_DIR
from flex_nav_sim.yaml_fields import (
    Fields,
    PathLike,
    available_names,
    read_yaml_mapping,
    resolve_named_file,
)

WORLD_DIR = Path(__file__).resolve().parent / "worlds"
SHAPES = ("box", "cylinder")
SOLID_KINDS = ("wall", "obstacle", "door", "box")
ACTIONS = ("remove", "add", "open", "close", "start_walking", "stop_walking", "teleport")
ROBOT_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")  # a ROS namespace / frame prefix
Rgba = Tuple[float, float, float, float]

DEFAULT_COLORS: Dict[str, Rgba] = {
    "wall": (0.72, 0.72, 0.72, 1.0),
    "obstacle": (0.35, 0.45, 0.6, 1.0),
    "low_obstacle": (0.95, 0.8, 0.1, 1.0),
    "door": (0.55, 0.35, 0.15, 1.0),
    "box": (0.8, 0.6, 0.3, 1.0),
    "person": (0.85, 0.3, 0.3, 1.0),
}
SPAWN_CLEARANCE = 0.01  # [m] a robot must start at least this far from every solid, person and robot


@dataclass(frozen=True)
class Solid:
    """A rigid body of the world: static (``mass == 0``) or movable."""

    name: str
    kind: str  # one of SOLID_KINDS
    shape: str  # one of SHAPES
    size: Tuple[float, float, float]  # [m] box: extents x, y, z; cylinder: diameter, diameter, height
    pose: Tuple[float, float, float]  # (x [m], y [m], yaw [rad]) of the bottom centre
    color: Rgba
    mass: float = 0.0  # [kg] 0 = static
    friction: float = 0.6  # [-] sliding friction against the floor
    present: bool = True  # in the world at t = 0 (events may add or remove it)
    in_map: bool = True  # part of the static map (walls and obstacles the lidar sees)

    @property
    def height(self) -> float:
        return self.size[2]

    @property
    def radius(self) -> float:
        """Cylinder radius [m] (0 for boxes)."""
        return self.size[0] / 2.0 if self.shape == "cylinder" else 0.0

    @property
    def movable(self) -> bool:
        return self.mass > 0.0

    def footprint(self) -> Footprint:
        x, y, yaw = self.pose
        if self.shape == "cylinder":
            return Footprint(x, y, 0.0, 0.0, 0.0, radius=self.radius)
        return Footprint(x, y, yaw, self.size[0], self.size[1])


@dataclass(frozen=True)
class Person:
    """A kinematic person (a capsule) standing still or walking a polyline of waypoints."""

    name: str
    radius: float  # [m]
    height: float  # [m]
    waypoints: Tuple[Point, ...]  # [m]; one point = standing
    speed: float  # [m/s] walking speed
    loop: bool  # walk back to the first waypoint and repeat; else stop at the last one
    start_time: Optional[float]  # [s] when walking starts; None = only by a start_walking event
    yaw: float  # [rad] facing direction while standing
    color: Rgba

    @property
    def walks(self) -> bool:
        return len(self.waypoints) >= 2

    def path_length(self) -> float:
        """Length [m] of one lap (closed if ``loop``)."""
        pts = self._path()
        return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(pts, pts[1:]))

    def pose_after(self, walked_time: float) -> Tuple[float, float, float]:
        """(x, y, yaw) [m, m, rad] after walking for ``walked_time`` [s] from the first waypoint."""
        if not self.walks:
            return self.waypoints[0][0], self.waypoints[0][1], self.yaw
        pts = self._path()
        total = self.path_length()
        s = max(0.0, walked_time) * self.speed
        s = math.fmod(s, total) if self.loop else min(s, total)
        for a, b in zip(pts, pts[1:]):
            seg = math.hypot(b[0] - a[0], b[1] - a[1])
            if seg <= 0.0:
                continue
            heading = math.atan2(b[1] - a[1], b[0] - a[0])
            if s <= seg:
                f = s / seg
                return a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), heading
            s -= seg
        last, before = pts[-1], pts[-2]
        return last[0], last[1], math.atan2(last[1] - before[1], last[0] - before[0])

    def _path(self) -> List[Point]:
        pts = list(self.waypoints)
        if self.loop and pts[0] != pts[-1]:
            pts.append(pts[0])
        return pts


@dataclass(frozen=True)
class WorldEvent:
    """A scripted change at simulated time ``time`` [s]."""

    time: float  # [s]
    action: str  # one of ACTIONS
    target: str  # name of a solid, door, person or (teleport) robot
    pose: Optional[Tuple[float, float, float]] = None  # teleport only: (x [m], y [m], yaw [rad]) in the map frame


@dataclass(frozen=True)
class Spawn:
    """Where a robot starts: its name (ROS namespace and frame prefix), profile and pose."""

    name: str
    profile: str  # profile name or path (see flex_nav_sim.profiles.load_profile)
    pose: Tuple[float, float, float]  # (x [m], y [m], yaw [rad])


@dataclass(frozen=True)
class MapSettings:
    """How the static map is rasterised."""

    resolution: float  # [m/cell]
    min_height: float  # [m] solids lower than this are left out of the map (lidar cannot see them)
    padding: float  # [m] unknown-free border around the world's bounds


@dataclass(frozen=True)
class WorldSpec:
    """A validated world."""

    name: str
    description: str
    source: str
    map: MapSettings
    solids: Tuple[Solid, ...]
    people: Tuple[Person, ...]
    events: Tuple[WorldEvent, ...]  # sorted by time
    spawns: Tuple[Spawn, ...]
    goals: Mapping[str, Tuple[float, float, float]] = field(default_factory=dict)

    def solid(self, name: str) -> Solid:
        for s in self.solids:
            if s.name == name:
                return s
        raise ConfigError(choices_message(f"{self.source}: solid", name, [s.name for s in self.solids]))

    def bounds(self) -> Tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) [m] of every solid and person waypoint."""
        boxes = [s.footprint().bounds() for s in self.solids]
        for p in self.people:
            boxes.extend((x - p.radius, y - p.radius, x + p.radius, y + p.radius) for x, y in p.waypoints)
        if not boxes:
            return -1.0, -1.0, 1.0, 1.0
        xs0, ys0, xs1, ys1 = zip(*boxes)
        return min(xs0), min(ys0), max(xs1), max(ys1)


def available_worlds() -> List[str]:
    """Names of the shipped worlds (``sim/worlds/*.yaml``)."""
    return available_names(WORLD_DIR)


def load_world(name_or_path: PathLike) -> WorldSpec:
    """Load and validate a world by name or path; ConfigError names the file, the field and valid values."""
    path = resolve_named_file(name_or_path, WORLD_DIR, "world")
    return _WorldReader(path).read()


def check_spawns(world: WorldSpec, spawns: Sequence[Spawn], radii: Mapping[str, float]) -> None:
    """Reject duplicate or invalid robot names and robots that overlap a solid, a person or each other.

    ``radii`` maps each spawn name to its robot radius [m]. Only solids present at t = 0 count.
    """
    names = [s.name for s in spawns]
    if not spawns:
        raise ConfigError(f"{world.source}: no robots to spawn (give robots in the world or the robots parameter)")
    for s in spawns:
        if s.name == "" and len(spawns) == 1:
            continue
        if not ROBOT_NAME.match(s.name):
            raise ConfigError(
                f"robot name {s.name!r} is not a valid ROS namespace (letters, digits, '_', starting with a letter; "
                "'' only for a single robot)"
            )
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise ConfigError(f"two robots share the namespace {duplicates[0]!r}: robot names must be unique (got {names})")
    for i, s in enumerate(spawns):
        x, y, _ = s.pose
        r = radii[s.name] + SPAWN_CLEARANCE
        for solid in world.solids:
            if solid.present and solid.footprint().distance_to(x, y) < r:
                raise ConfigError(
                    f"robot {s.name!r} spawned at ({x:.2f}, {y:.2f}) overlaps {solid.kind} {solid.name!r} of world "
                    f"{world.name} (robot radius {radii[s.name]:.3f} m); move it to free space"
                )
        for p in world.people:
            px, py, _ = p.pose_after(0.0)
            if math.hypot(px - x, py - y) < r + p.radius:
                raise ConfigError(f"robot {s.name!r} spawned at ({x:.2f}, {y:.2f}) overlaps person {p.name!r}")
        for other in spawns[:i]:
            if math.hypot(other.pose[0] - x, other.pose[1] - y) < r + radii[other.name]:
                raise ConfigError(f"robots {other.name!r} and {s.name!r} are spawned on top of each other")


@dataclass
class _Wall:
    name: str
    start: Point
    end: Point
    thickness: float
    height: float
    color: Rgba


class _WorldReader:
    """Reads one world file; collects walls first so doors can cut them."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.top = Fields(read_yaml_mapping(path, "world"), str(path))
        self.names: Dict[str, str] = {}  # name -> where it was defined

    def read(self) -> WorldSpec:
        top = self.top
        name = top.string("name")
        description = top.string("description", "")
        msettings = top.sub("map", default_empty=True)
        map_settings = MapSettings(
            resolution=msettings.positive("resolution", 0.05, unit="[m/cell]"),
            min_height=msettings.number("min_height", 0.12, minimum=0.0, unit="[m]"),
            padding=msettings.number("padding", 0.5, minimum=0.0, unit="[m]"),
        )
        msettings.done()
        defaults = top.sub("defaults", default_empty=True)
        wall_height = defaults.positive("wall_height", 0.6, unit="[m]")
        wall_thickness = defaults.positive("wall_thickness", 0.1, unit="[m]")
        defaults.done()

        walls = self._rooms(wall_height, wall_thickness) + self._walls(wall_height, wall_thickness)
        solids: List[Solid] = []
        solids.extend(self._doors(walls))
        solids[:0] = [self._wall_solid(w) for w in walls]
        solids.extend(self._wall_images(wall_height))
        solids.extend(self._obstacles(map_settings))
        solids.extend(self._boxes())
        people = self._people()
        events = self._events(solids, people)
        spawns = self._spawns()
        goals = self._goals()
        top.done()
        return WorldSpec(
            name=name,
            description=description,
            source=str(self.path),
            map=map_settings,
            solids=tuple(solids),
            people=tuple(people),
            events=tuple(events),
            spawns=tuple(spawns),
            goals=goals,
        )

    # -- naming ---------------------------------------------------------------------------------
    def _claim(self, name: str, where: str) -> str:
        if not name:
            raise ConfigError(f"{where} must be a non-empty name")
        if name in self.names:
            raise ConfigError(f"{where} {name!r} is already used by {self.names[name]}; names must be unique")
        self.names[name] = where
        return name

    def _color(self, f: Fields, kind: str) -> Rgba:
        if not f.has("color"):
            return DEFAULT_COLORS[kind]
        values = f.vector("color", 4, unit="[r, g, b, a] in 0..1")
        if not all(0.0 <= v <= 1.0 for v in values):
            raise ConfigError(f"{f.where('color')} values must be in 0..1, got {list(values)}")
        return values[0], values[1], values[2], values[3]

    # -- walls ----------------------------------------------------------------------------------
    def _rooms(self, height: float, thickness: float) -> List[_Wall]:
        walls = []
        for i, f in enumerate(self.top.sub_list("rooms")):
            name = self._claim(f.string("name", f"room{i}"), f.where("name"))
            x0, y0 = f.vector("min", 2, unit="[x, y] [m]")
            x1, y1 = f.vector("max", 2, unit="[x, y] [m]")
            if x1 <= x0 or y1 <= y0:
                raise ConfigError(
                    f"{f.where('max')} must lie above and right of min, got min {[x0, y0]} max {[x1, y1]}"
                )
            t = f.positive("thickness", thickness, unit="[m]")
            h = f.positive("height", height, unit="[m]")
            color = self._color(f, "wall")
            corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
            for side, a, b in zip(("south", "east", "north", "west"), corners, corners[1:] + corners[:1]):
                # extend each wall by half the thickness so the corners close
                dx, dy = b[0] - a[0], b[1] - a[1]
                n = math.hypot(dx, dy)
                ex, ey = dx / n * t / 2.0, dy / n * t / 2.0
                wname = self._claim(f"{name}_{side}", f.where("name"))
                walls.append(_Wall(wname, (a[0] - ex, a[1] - ey), (b[0] + ex, b[1] + ey), t, h, color))
            f.done()
        return walls

    def _walls(self, height: float, thickness: float) -> List[_Wall]:
        walls = []
        for i, f in enumerate(self.top.sub_list("walls")):
            name = self._claim(f.string("name", f"wall{i}"), f.where("name"))
            a = f.vector("from", 2, unit="[x, y] [m]")
            b = f.vector("to", 2, unit="[x, y] [m]")
            if math.hypot(b[0] - a[0], b[1] - a[1]) < 1e-3:
                raise ConfigError(f"{f.where('to')} must differ from 'from' (a wall needs a length)")
            walls.append(
                _Wall(
                    name,
                    (a[0], a[1]),
                    (b[0], b[1]),
                    f.positive("thickness", thickness, unit="[m]"),
                    f.positive("height", height, unit="[m]"),
                    self._color(f, "wall"),
                )
            )
            f.done()
        return walls

    def _wall_solid(self, w: _Wall) -> Solid:
        fp = segment_footprint(w.start, w.end, w.thickness)
        return Solid(w.name, "wall", "box", (fp.size_x, w.thickness, w.height), (fp.x, fp.y, fp.yaw), w.color)

    def _doors(self, walls: List[_Wall]) -> List[Solid]:
        """Cut a gap into the wall under each door; return the door panels."""
        panels = []
        for f in self.top.sub_list("doors"):
            name = self._claim(f.string("name"), f.where("name"))
            at = f.vector("at", 2, unit="[x, y] [m]")
            width = f.positive("width", 0.9, unit="[m]")
            state = f.choice("state", ("open", "closed"), "open")
            in_map = f.boolean("in_map", False)
            color = self._color(f, "door")
            f.done()
            hosts = []
            for w in walls:
                t, off = project_on_segment(w.start, w.end, (at[0], at[1]))
                length = math.hypot(w.end[0] - w.start[0], w.end[1] - w.start[1])
                if abs(off) <= w.thickness / 2.0 + 1e-6 and width / 2.0 < t < length - width / 2.0:
                    hosts.append((w, t, length))
            if not hosts:
                raise ConfigError(
                    f"{f.where('at')} {list(at)}: door {name!r} ({width} m wide) does not lie on any wall "
                    f"(walls: {', '.join(w.name for w in walls) or 'none'})"
                )
            for w, t, length in hosts:  # overlapping walls (two rooms sharing a side) are all cut
                ux, uy = (w.end[0] - w.start[0]) / length, (w.end[1] - w.start[1]) / length
                gap0 = (w.start[0] + ux * (t - width / 2.0), w.start[1] + uy * (t - width / 2.0))
                gap1 = (w.start[0] + ux * (t + width / 2.0), w.start[1] + uy * (t + width / 2.0))
                walls.remove(w)
                walls.append(
                    _Wall(self._claim(f"{w.name}_a", f.where("at")), w.start, gap0, w.thickness, w.height, w.color)
                )
                walls.append(
                    _Wall(self._claim(f"{w.name}_b", f.where("at")), gap1, w.end, w.thickness, w.height, w.color)
                )
            w, t, length = hosts[0]
            ux, uy = (w.end[0] - w.start[0]) / length, (w.end[1] - w.start[1]) / length
            yaw = math.atan2(uy, ux)
            cx, cy = w.start[0] + ux * t, w.start[1] + uy * t
            panels.append(
                Solid(
                    name,
                    "door",
                    "box",
                    (width, max(0.03, w.thickness / 2.0), w.height),
                    (cx, cy, yaw),
                    color,
                    present=state == "closed",
                    in_map=in_map,
                )
            )
        return panels

    def _wall_images(self, height: float) -> List[Solid]:
        """Walls from an occupancy image: occupied pixels merged into rectangles."""
        solids = []
        for i, f in enumerate(self.top.sub_list("wall_images")):
            file_name = f.string("file")
            image_path = Path(file_name) if Path(file_name).is_absolute() else self.path.parent / file_name
            resolution = f.positive("resolution", unit="[m/pixel]")
            ox, oy = f.vector("origin", 2, [0.0, 0.0], unit="[x, y] [m] of the lower-left pixel corner")
            h = f.positive("height", height, unit="[m]")
            negate = f.boolean("negate", False)
            occupied_thresh = f.number("occupied_thresh", 0.65, minimum=0.0, maximum=1.0)
            color = self._color(f, "wall")
            prefix = f.string("name", f"image{i}")
            f.done()
            pixels = cv2.imread(str(image_path), cv2.IMREAD_UNCHANGED)
            if pixels is None or pixels.dtype != np.uint8:
                raise ConfigError(f"{f.where('file')}: cannot read {image_path} as an 8-bit image (valid: PNG, PGM)")
            occ = image_to_occupancy(
                pixels, negate=negate, occupied_thresh=occupied_thresh, free_thresh=0.0, source=str(image_path)
            )
            for j, (r0, c0, r1, c1) in enumerate(occupied_rectangles(occ >= 100)):
                cx = ox + (c0 + c1) / 2.0 * resolution
                cy = oy + (r0 + r1) / 2.0 * resolution
                size = ((c1 - c0) * resolution, (r1 - r0) * resolution, h)
                solids.append(
                    Solid(self._claim(f"{prefix}_{j}", f.where("file")), "wall", "box", size, (cx, cy, 0.0), color)
                )
        return solids

    # -- obstacles, boxes, people ---------------------------------------------------------------
    def _shape(self, f: Fields) -> Tuple[str, Tuple[float, float, float]]:
        shape = f.choice("shape", SHAPES, "box")
        if shape == "box":
            sx, sy, sz = f.vector("size", 3, unit="[x, y, z] [m]")
            if min(sx, sy, sz) <= 0.0:
                raise ConfigError(f"{f.where('size')} extents must be > 0, got {[sx, sy, sz]}")
            return shape, (sx, sy, sz)
        radius = f.positive("radius", unit="[m]")
        return shape, (2.0 * radius, 2.0 * radius, f.positive("height", unit="[m]"))

    def _obstacles(self, ms: MapSettings) -> List[Solid]:
        solids = []
        for f in self.top.sub_list("obstacles"):
            name = self._claim(f.string("name"), f.where("name"))
            shape, size = self._shape(f)
            low = size[2] < ms.min_height
            solids.append(
                Solid(
                    name,
                    "obstacle",
                    shape,
                    size,
                    f.pose("pose"),
                    self._color(f, "low_obstacle" if low else "obstacle"),
                    friction=f.number("friction", 0.6, minimum=0.0, maximum=2.0),
                    present=f.boolean("present", True),
                    in_map=not low and f.boolean("in_map", True),
                )
            )
            f.done()
        return solids

    def _boxes(self) -> List[Solid]:
        solids = []
        for f in self.top.sub_list("boxes"):
            name = self._claim(f.string("name"), f.where("name"))
            shape, size = self._shape(f)
            solids.append(
                Solid(
                    name,
                    "box",
                    shape,
                    size,
                    f.pose("pose"),
                    self._color(f, "box"),
                    mass=f.positive("mass", unit="[kg]"),
                    friction=f.number("friction", 0.5, minimum=0.0, maximum=2.0),
                    present=f.boolean("present", True),
                    in_map=False,
                )
            )
            f.done()
        return solids

    def _people(self) -> List[Person]:
        people = []
        for f in self.top.sub_list("people"):
            name = self._claim(f.string("name"), f.where("name"))
            if f.has("waypoints") == f.has("pose"):
                raise ConfigError(
                    f"{f.where('pose')}: give either pose (standing) or waypoints (walking), not both/none"
                )
            if f.has("pose"):
                x, y, yaw = f.pose("pose")
                waypoints: Tuple[Point, ...] = ((x, y),)
            else:
                waypoints = tuple(f.points("waypoints", minimum=2))
                yaw = 0.0
            start = f.raw("start", 0.0)
            start_time: Optional[float] = None
            if start is not None:
                start_time = validation.number(f.source, f.dotted("start"), start, minimum=0.0, unit="[s]")
            people.append(
                Person(
                    name=name,
                    radius=f.positive("radius", 0.2, unit="[m]"),
                    height=f.positive("height", 1.7, unit="[m]"),
                    waypoints=waypoints,
                    speed=f.positive("speed", 1.0, unit="[m/s]"),
                    loop=f.boolean("loop", True),
                    start_time=start_time,
                    yaw=yaw,
                    color=self._color(f, "person"),
                )
            )
            f.done()
        return people

    def _events(self, solids: List[Solid], people: List[Person]) -> List[WorldEvent]:
        by_name = {s.name: s for s in solids}
        walkers = {p.name for p in people if p.walks}
        events = []
        for f in self.top.sub_list("events"):
            time = f.number("at", minimum=0.0, unit="[s]")
            action = f.choice("action", ACTIONS)
            target = f.string("target")
            if action in ("remove", "add"):
                valid = sorted(n for n, s in by_name.items() if s.kind != "wall")
            elif action in ("open", "close"):
                valid = sorted(n for n, s in by_name.items() if s.kind == "door")
            elif action == "teleport":  # the robot is checked when the simulation spawns its robots
                events.append(WorldEvent(time, action, target, f.pose("pose")))
                f.done()
                continue
            else:
                valid = sorted(walkers)
            if target not in valid:
                raise ConfigError(choices_message(f"{f.where('target')} for action {action}", target, valid))
            events.append(WorldEvent(time, action, target))
            f.done()
        return sorted(events, key=lambda e: e.time)

    def _spawns(self) -> List[Spawn]:
        spawns = []
        profiles = available_names(PROFILE_DIR)
        for f in self.top.sub_list("robots"):
            name = f.string("name")
            profile = f.string("profile")
            if profile not in profiles and not Path(profile).is_file():
                raise ConfigError(choices_message(f.where("profile"), profile, profiles))
            spawns.append(Spawn(name, profile, f.pose("pose")))
            f.done()
        return spawns

    def _goals(self) -> Dict[str, Tuple[float, float, float]]:
        goals_f = self.top.sub("goals", default_empty=True)
        goals = {str(key): goals_f.pose(str(key)) for key in list(goals_f.data)}
        goals_f.done()
        return goals


def occupied_rectangles(mask: np.ndarray) -> List[Tuple[int, int, int, int]]:
    """Cover the true cells of a boolean (rows, cols) mask with rectangles (r0, c0, r1, c1), ends exclusive.

    Runs of each row are merged with an identical run directly below them, so long walls become one
    rectangle and an image of N wall pixels gives far fewer than N bodies.
    """
    open_runs: Dict[Tuple[int, int], int] = {}  # (c0, c1) -> first row
    rects = []
    rows = mask.shape[0]
    for r in range(rows + 1):
        runs = set()
        if r < rows:
            row = np.concatenate(([False], mask[r].astype(bool), [False]))
            edges = np.flatnonzero(row[1:] != row[:-1])
            runs = {(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])}
        for run in list(open_runs):
            if run not in runs:
                rects.append((open_runs.pop(run), run[0], r, run[1]))
        for run in runs:
            open_runs.setdefault(run, r)
    return rects
