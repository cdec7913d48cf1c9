"""The map of a world's static structure, "the map made with the room empty", in map_server format.

Occupied: walls, closed doors marked ``in_map`` and static obstacles at least ``map.min_height`` tall
(what a lidar sees) that are present at t = 0. Left out: movable boxes, people, low obstacles and
open doors. The grid covers the world's bounds plus ``map.padding``; every other cell is free.

Command line (writes ``OUT.yaml`` and ``OUT.pgm``)::

    python -m flex_nav_sim.static_map WORLD OUT.yaml
    python -m flex_nav_sim.static_map --shipped        # regenerate sim/worlds/maps/*.yaml for all worlds
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import List, Optional

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import FREE, OCCUPIED, GridMap
from flex_nav.nav.costmap.map_io import save_map
from flex_nav_sim.geometry2d import Footprint
from flex_nav_sim.world import WORLD_DIR, Solid, WorldSpec, available_worlds, load_world

MAP_DIR = WORLD_DIR / "maps"  # shipped maps of the shipped worlds (regenerated and checked by a test)
_EDGE = 1e-6  # [m] a cell centre exactly on a rectangle's edge counts as inside


def mapped_solids(world: WorldSpec) -> List[Solid]:
    """The solids that belong in the static map (see the module docstring)."""
    return [s for s in world.solids if s.present and s.in_map and s.mass == 0.0 and s.height >= world.map.min_height]


def static_map(world: WorldSpec) -> GridMap:
    """Rasterise the world's static structure into a GridMap (free everywhere else)."""
    res = world.map.resolution
    pad = world.map.padding
    x0, y0, x1, y1 = world.bounds()
    origin_x = round(math.floor((x0 - pad) / res) * res, 6)
    origin_y = round(math.floor((y0 - pad) / res) * res, 6)
    width = math.ceil((x1 + pad - origin_x) / res)
    height = math.ceil((y1 + pad - origin_y) / res)
    image = np.zeros((height, width), dtype=bool)  # row 0 = origin row (y up)
    for solid in mapped_solids(world):
        _fill(image, solid.footprint(), origin_x, origin_y, res)
    occupancy = np.where(image, OCCUPIED, FREE).astype(np.int8)
    return GridMap(occupancy, res, (origin_x, origin_y, 0.0))


def _fill(image: np.ndarray, fp: Footprint, origin_x: float, origin_y: float, res: float) -> None:
    """Mark the cells whose centre lies inside footprint ``fp``."""
    bx0, by0, bx1, by1 = fp.bounds()
    c0 = max(0, math.floor((bx0 - origin_x) / res))
    c1 = min(image.shape[1], math.ceil((bx1 - origin_x) / res) + 1)
    r0 = max(0, math.floor((by0 - origin_y) / res))
    r1 = min(image.shape[0], math.ceil((by1 - origin_y) / res) + 1)
    if c1 <= c0 or r1 <= r0:
        return
    xs = origin_x + (np.arange(c0, c1) + 0.5) * res
    ys = origin_y + (np.arange(r0, r1) + 0.5) * res
    dx = xs[None, :] - fp.x
    dy = ys[:, None] - fp.y
    if fp.is_circle:
        inside = dx * dx + dy * dy <= fp.radius * fp.radius
    else:
        c, s = math.cos(fp.yaw), math.sin(fp.yaw)
        inside = (np.abs(c * dx + s * dy) <= fp.size_x / 2.0 + _EDGE) & (
            np.abs(-s * dx + c * dy) <= fp.size_y / 2.0 + _EDGE
        )
    image[r0:r1, c0:c1] |= inside


def write_static_map(world: WorldSpec, yaml_path: Path) -> Path:
    """Write the world's static map as ``yaml_path`` + a PGM beside it; returns the YAML path."""
    save_map(static_map(world), yaml_path)
    return yaml_path


def shipped_map_path(world_name: str) -> Path:
    """Where the shipped map of a shipped world lives (``sim/worlds/maps/<name>.yaml``)."""
    return MAP_DIR / f"{world_name}.yaml"


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description="Write the static map of a flex_nav_sim world (map_server format).")
    parser.add_argument("world", nargs="?", help=f"world name ({', '.join(available_worlds())}) or path")
    parser.add_argument("out", nargs="?", help="output YAML path (a .pgm is written beside it)")
    parser.add_argument("--shipped", action="store_true", help="regenerate the shipped maps of all shipped worlds")
    args = parser.parse_args(argv)
    try:
        if args.shipped:
            MAP_DIR.mkdir(parents=True, exist_ok=True)
            for name in available_worlds():
                print(write_static_map(load_world(name), shipped_map_path(name)))
            return 0
        if not args.world or not args.out:
            parser.error("give WORLD and OUT.yaml, or --shipped")
        print(write_static_map(load_world(args.world), Path(args.out)))
    except ConfigError as err:
        print(f"ERROR: {err}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
