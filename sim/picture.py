"""A top-down picture (PNG) of a world: the static map, movable boxes, low obstacles, doors, people
and their paths, goals, and the robots with their lidar rays, drawn with OpenCV.

Command line::

    python -m flex_nav_sim.picture WORLD OUT.png [--robots SPEC] [--seconds S] [--seed N] [--scale PX_PER_M]
    rosrun flex_nav sim_picture _world:=lab out.png

``--seconds`` runs the simulation first, the robots wandering (forward, turning away from whatever
their lidar sees within 0.6 m ahead), so the picture shows them somewhere other than their spawn.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
from dataclasses import replace
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import cv2
import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav_sim.readings import Pose2D, ScanReading
from flex_nav_sim.simulation import SensorOptions, Simulation
from flex_nav_sim.spawn_spec import resolve_spawns
from flex_nav_sim.static_map import static_map
from flex_nav_sim.world import Solid, available_worlds, load_world

Bgr = Tuple[int, int, int]
FREE_COLOR: Bgr = (250, 250, 250)
OCCUPIED_COLOR: Bgr = (40, 40, 40)
BOX_COLOR: Bgr = (60, 130, 200)
LOW_COLOR: Bgr = (0, 200, 240)
DOOR_COLOR: Bgr = (30, 80, 140)
PERSON_COLOR: Bgr = (60, 60, 220)
RAY_COLOR: Bgr = (80, 200, 80)
HIT_COLOR: Bgr = (0, 140, 0)
GOAL_COLOR: Bgr = (200, 80, 160)
ROBOT_COLORS: Tuple[Bgr, ...] = ((200, 90, 20), (30, 160, 230), (150, 60, 150), (40, 150, 40))
LEGEND_WIDTH = 760  # [px] the legend needs this much
RAY_STRIDE = 2  # draw every n-th beam
WANDER_BLOCKED = 0.6  # [m] turn away when something is this close ahead


class Canvas:
    """Map-frame drawing on an image whose pixels follow a GridMap scaled by ``scale`` px per cell."""

    def __init__(self, grid: GridMap, px_per_cell: int, margin_top: int, margin_bottom: int, min_width: int) -> None:
        self.grid = grid
        self.k = px_per_cell
        self.top = margin_top
        occupancy = np.flipud(grid.occupancy)  # image rows top-down (+y up)
        base = np.where(occupancy[..., None] >= 50, OCCUPIED_COLOR, FREE_COLOR).astype(np.uint8)
        base = np.repeat(np.repeat(base, px_per_cell, axis=0), px_per_cell, axis=1)
        width = max(base.shape[1], min_width)
        self.image = np.full((base.shape[0] + margin_top + margin_bottom, width, 3), 255, dtype=np.uint8)
        self.image[margin_top : margin_top + base.shape[0], : base.shape[1]] = base

    def px(self, x: float, y: float) -> Tuple[int, int]:
        gx, gy = self.grid.world_to_grid(x, y)
        return round(gx * self.k), round(self.top + (self.grid.height - gy) * self.k)

    def metres(self, length: float) -> int:
        return max(1, round(length / self.grid.resolution * self.k))

    def solid(self, solid: Solid, color: Bgr, filled: bool = True) -> None:
        fp = solid.footprint()
        if fp.is_circle:
            cv2.circle(self.image, self.px(fp.x, fp.y), self.metres(fp.radius), color, -1 if filled else 2, cv2.LINE_AA)
        else:
            poly = np.array([self.px(x, y) for x, y in fp.corners()], dtype=np.int32)
            if filled:
                cv2.fillPoly(self.image, [poly], color, cv2.LINE_AA)
            else:
                cv2.polylines(self.image, [poly], True, color, 2, cv2.LINE_AA)

    def text(self, label: str, at: Tuple[int, int], color: Bgr = (30, 30, 30), size: float = 0.45) -> None:
        cv2.putText(self.image, label, at, cv2.FONT_HERSHEY_SIMPLEX, size, color, 1, cv2.LINE_AA)


def wander_command(ranges: np.ndarray, angles: np.ndarray) -> Tuple[float, float]:
    """(v [m/s], w [rad/s]) of a simple wander: forward unless something is close ahead."""
    ahead = ranges[np.abs(angles) < math.radians(35.0)]
    if ahead.size and float(np.min(ahead)) < WANDER_BLOCKED:
        return 0.0, 1.0
    return 0.3, 0.0


def simulate(sim: Simulation, seconds: float) -> Dict[str, ScanReading]:
    """Run ``seconds`` [s] of wandering; return each robot's latest scan."""
    scans: Dict[str, ScanReading] = {}
    angles = {name: spec.beam_angles() for name in sim.robot_names if (spec := sim.lidar_spec_of(name)) is not None}
    while True:
        for reading in sim.step():
            if isinstance(reading, ScanReading):
                scans[reading.robot] = reading
                sim.command(reading.robot, *wander_command(reading.ranges, angles[reading.robot]))
        if sim.time >= seconds and len(scans) == len(angles):
            return scans


def render(sim: Simulation, scans: Dict[str, ScanReading], px_per_cell: int = 4) -> np.ndarray:
    """The picture (BGR uint8) of ``sim`` in its current state with the given scans."""
    world = sim.world
    title = f"{world.name}: {world.description}  (t = {sim.time:.1f} s)"
    title_width = cv2.getTextSize(title, cv2.FONT_HERSHEY_SIMPLEX, 0.5, 1)[0][0] + 16
    canvas = Canvas(
        static_map(world), px_per_cell, margin_top=28, margin_bottom=30, min_width=max(LEGEND_WIDTH, title_width)
    )
    for solid in world.solids:
        pose = sim.object_pose(solid.name)
        if solid.kind == "door":
            canvas.solid(solid, DOOR_COLOR, filled=pose is not None)
        elif solid.kind == "box" and pose is not None:
            canvas.solid(replace(solid, pose=(pose.x, pose.y, pose.yaw)), BOX_COLOR)
            canvas.text(f"{solid.mass:g} kg", canvas.px(pose.x - solid.size[0] / 2, pose.y - solid.size[1] / 2 - 0.15))
        elif solid.kind == "obstacle" and not solid.in_map and pose is not None:
            canvas.solid(solid, LOW_COLOR)
            fp = solid.footprint()
            canvas.text("low", canvas.px(fp.x - 0.15, fp.y - fp.size_y / 2 - 0.15), (0, 120, 160))
    for person in world.people:
        if person.walks:
            pts = list(person.waypoints) + ([person.waypoints[0]] if person.loop else [])
            poly = np.array([canvas.px(x, y) for x, y in pts], dtype=np.int32)
            cv2.polylines(canvas.image, [poly], False, (170, 170, 235), 1, cv2.LINE_AA)
        pose = sim.object_pose(person.name)
        if pose is not None:
            cv2.circle(
                canvas.image, canvas.px(pose.x, pose.y), canvas.metres(person.radius), PERSON_COLOR, -1, cv2.LINE_AA
            )
            canvas.text(person.name, canvas.px(pose.x + person.radius, pose.y + person.radius), PERSON_COLOR)
    for name, (x, y, _) in world.goals.items():
        centre = canvas.px(x, y)
        cv2.drawMarker(canvas.image, centre, GOAL_COLOR, cv2.MARKER_TILTED_CROSS, 14, 2, cv2.LINE_AA)
        canvas.text(name, (centre[0] + 6, centre[1] - 6), GOAL_COLOR)
    for i, robot_name in enumerate(sim.robot_names):
        _draw_robot(canvas, sim, robot_name, scans.get(robot_name), ROBOT_COLORS[i % len(ROBOT_COLORS)])
    canvas.text(title, (8, 19), size=0.5)
    _legend(canvas)
    return canvas.image


def _legend(canvas: Canvas) -> None:
    y = canvas.image.shape[0] - 11
    x = 8
    items = (
        ("static map (walls, obstacles)", OCCUPIED_COLOR, "box"),
        ("movable box", BOX_COLOR, "box"),
        ("low obstacle (bumper only)", LOW_COLOR, "box"),
        ("person", PERSON_COLOR, "dot"),
        ("lidar rays", RAY_COLOR, "line"),
        ("goal", GOAL_COLOR, "cross"),
    )
    for label, color, mark in items:
        if mark == "box":
            cv2.rectangle(canvas.image, (x, y - 9), (x + 10, y + 1), color, -1)
        elif mark == "dot":
            cv2.circle(canvas.image, (x + 5, y - 4), 5, color, -1, cv2.LINE_AA)
        elif mark == "line":
            cv2.line(canvas.image, (x, y - 4), (x + 12, y - 4), color, 2, cv2.LINE_AA)
        else:
            cv2.drawMarker(canvas.image, (x + 5, y - 4), color, cv2.MARKER_TILTED_CROSS, 10, 2, cv2.LINE_AA)
        canvas.text(label, (x + 16, y), size=0.4)
        x += 16 + cv2.getTextSize(label, cv2.FONT_HERSHEY_SIMPLEX, 0.4, 1)[0][0] + 14


def _draw_robot(canvas: Canvas, sim: Simulation, name: str, scan: Optional[ScanReading], color: Bgr) -> None:
    profile = sim.robot(name).profile
    pose: Pose2D = sim.truth_pose(name)
    spec = sim.lidar_spec_of(name)
    if scan is not None and spec is not None:
        c, s = math.cos(pose.yaw), math.sin(pose.yaw)
        ox = pose.x + c * spec.mount[0] - s * spec.mount[1]
        oy = pose.y + s * spec.mount[0] + c * spec.mount[1]
        origin = canvas.px(ox, oy)
        overlay = canvas.image.copy()
        for angle, r in list(zip(spec.beam_angles(), scan.ranges.astype(float)))[::RAY_STRIDE]:
            hit = math.isfinite(r)
            length = r if hit else spec.range_max
            end = canvas.px(ox + length * math.cos(pose.yaw + angle), oy + length * math.sin(pose.yaw + angle))
            cv2.line(overlay, origin, end, RAY_COLOR, 1, cv2.LINE_AA)
            if hit:
                cv2.circle(overlay, end, 2, HIT_COLOR, -1)
        cv2.addWeighted(overlay, 0.55, canvas.image, 0.45, 0.0, canvas.image)
    centre = canvas.px(pose.x, pose.y)
    radius = canvas.metres(profile.radius)
    cv2.circle(canvas.image, centre, radius, color, -1, cv2.LINE_AA)
    tip = canvas.px(pose.x + profile.radius * math.cos(pose.yaw), pose.y + profile.radius * math.sin(pose.yaw))
    cv2.line(canvas.image, centre, tip, (255, 255, 255), 2, cv2.LINE_AA)
    canvas.text(f"{name or 'robot'} ({profile.name})", (centre[0] + radius + 2, centre[1] + radius + 10), color)


def picture(
    world_name: str, out: Path, *, robots: object = "", seconds: float = 0.0, seed: int = 0, px_per_cell: int = 4
) -> Path:
    """Write the PNG of ``world_name`` after ``seconds`` [s] of simulation; returns ``out``."""
    world = load_world(world_name)
    spawns = resolve_spawns(world, robots)
    with Simulation(world, spawns, seed=seed, sensors=SensorOptions(camera=False)) as sim:
        scans = simulate(sim, seconds)
        image = render(sim, scans, px_per_cell)
    if not cv2.imwrite(str(out), image, [cv2.IMWRITE_PNG_COMPRESSION, 9]):
        raise ConfigError(f"cannot write the picture to {out} (does the folder exist? valid suffixes: .png, .jpg)")
    return out


def _ros_style(argv: Sequence[str]) -> List[str]:
    """Accept rosrun-style ``_name:=value`` arguments as ``--name value`` (``_world`` is positional)."""
    out: List[str] = []
    for arg in argv:
        if arg.startswith("__") and ":=" in arg:  # roslaunch's __name:= / __log:=
            continue
        match = re.fullmatch(r"_([A-Za-z]\w*):=(.*)", arg)
        if match is None:
            out.append(arg)
        elif match.group(1) == "world":
            out.insert(0, match.group(2))
        else:
            out += [f"--{match.group(1)}", match.group(2)]
    return out


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description="Draw a flex_nav_sim world with robots, lidar rays and static map.")
    parser.add_argument("world", help=f"world name ({', '.join(available_worlds())}) or path")
    parser.add_argument("out", type=Path, help="output PNG")
    parser.add_argument("--robots", default="", help="robots (see flex_nav_sim.spawn_spec); default: the world's")
    parser.add_argument("--seconds", type=float, default=0.0, help="simulate this long [s] first (robots wander)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--scale", type=int, default=4, help="pixels per map cell (default 4: 80 px/m at 0.05 m)")
    args = parser.parse_args(_ros_style(sys.argv[1:] if argv is None else argv))
    if not (math.isfinite(args.seconds) and 0.0 <= args.seconds <= 3600.0) or not 1 <= args.scale <= 20:
        parser.error("--seconds must be 0..3600 and --scale 1..20")
    try:
        print(
            picture(
                args.world, args.out, robots=args.robots, seconds=args.seconds, seed=args.seed, px_per_cell=args.scale
            )
        )
    except ConfigError as err:
        print(f"ERROR: {err}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
