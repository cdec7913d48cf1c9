"""A picture of a navigation run: map, costmap, planned paths, trajectories and where the bumpers hit.

Pure drawing with OpenCV on a :class:`~flex_nav.nav.costmap.grid_map.GridMap`; no ROS. Used by the demo
(``tools/demo.sh``) and the scenario evaluation to write one PNG per run.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import cv2
import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import GridMap

# BGR colours
ROBOT_COLOURS = ((200, 80, 20), (30, 150, 30), (150, 40, 170), (20, 120, 220))
PLAN_COLOUR = (0, 190, 255)
HIT_COLOUR = (0, 0, 230)
GOAL_COLOUR = (60, 60, 60)


@dataclass
class RobotTrack:
    """What one robot did: its trajectory, the plans it got, its goals and bumper contacts ([m] in the map frame)."""

    name: str
    trajectory: list[tuple[float, float]] = field(default_factory=list)
    plans: list[np.ndarray] = field(default_factory=list)  # (N, 2) each
    goals: list[tuple[float, float]] = field(default_factory=list)
    bumper_hits: list[tuple[float, float]] = field(default_factory=list)


def draw_run(
    grid: GridMap,
    tracks: Sequence[RobotTrack],
    costmap: Optional[np.ndarray] = None,
    px_per_cell: int = 4,
    title: str = "",
) -> np.ndarray:
    """BGR image (H, W, 3): map (black walls), costmap shading, plans, trajectories, goals, bumper hits.

    ``costmap`` is an OccupancyGrid-valued int8 array with the map's shape (0..100, -1 unknown), or None.
    """
    if px_per_cell < 1:
        raise ConfigError(f"px_per_cell must be >= 1, got {px_per_cell}")
    occ = grid.occupancy
    img = np.full((*occ.shape, 3), 255, dtype=np.uint8)
    img[occ < 0] = (205, 205, 205)
    if costmap is not None:
        if costmap.shape != occ.shape:
            raise ConfigError(f"costmap shape {costmap.shape} differs from the map's {occ.shape}")
        shade = np.clip(costmap.astype(np.int16), 0, 100)
        inflated = (shade > 0) & (occ < 50)
        strength = (shade[inflated] / 100.0)[:, None]  # 0..1: lighter to darker blue-grey
        img[inflated] = (np.array([255.0, 235.0, 225.0]) * (1.0 - 0.5 * strength)).astype(np.uint8)
    img[occ >= 50] = (0, 0, 0)
    upright = np.ascontiguousarray(img[::-1])  # row 0 of the map is at the bottom of the picture
    size = (occ.shape[1] * px_per_cell, occ.shape[0] * px_per_cell)
    img = np.asarray(cv2.resize(upright, size, interpolation=cv2.INTER_NEAREST), dtype=np.uint8)

    def pixel(x: float, y: float) -> tuple[int, int]:
        gx, gy = grid.world_to_grid(x, y)
        return int(gx * px_per_cell), int((occ.shape[0] - gy) * px_per_cell)

    for index, track in enumerate(tracks):
        colour = ROBOT_COLOURS[index % len(ROBOT_COLOURS)]
        for plan in track.plans:
            if len(plan) >= 2:
                pts = np.array([pixel(float(x), float(y)) for x, y in plan], dtype=np.int32)
                cv2.polylines(img, [pts], False, PLAN_COLOUR, 1, cv2.LINE_AA)
        if len(track.trajectory) >= 2:
            pts = np.array([pixel(x, y) for x, y in track.trajectory], dtype=np.int32)
            cv2.polylines(img, [pts], False, colour, 2, cv2.LINE_AA)
        for number, (x, y) in enumerate(track.goals, start=1):
            cv2.drawMarker(img, pixel(x, y), GOAL_COLOUR, cv2.MARKER_TILTED_CROSS, 14, 2)
            cv2.putText(img, str(number), (pixel(x, y)[0] + 6, pixel(x, y)[1] - 6), cv2.FONT_HERSHEY_SIMPLEX, 0.45,
                        GOAL_COLOUR, 1, cv2.LINE_AA)
        for x, y in track.bumper_hits:
            cv2.circle(img, pixel(x, y), 7, HIT_COLOUR, 2, cv2.LINE_AA)
        if track.trajectory:
            cv2.circle(img, pixel(*track.trajectory[0]), 5, colour, -1, cv2.LINE_AA)
    legend = [(name, ROBOT_COLOURS[i % len(ROBOT_COLOURS)]) for i, name in enumerate(t.name for t in tracks)]
    legend += [("plans", PLAN_COLOUR), ("bumper hit", HIT_COLOUR)]
    band = np.full((44, img.shape[1], 3), 255, dtype=np.uint8)  # title and legend above the map
    cv2.putText(band, title, (8, 16), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (0, 0, 0), 1, cv2.LINE_AA)
    x = 8
    for text, colour in legend:
        cv2.line(band, (x, 32), (x + 18, 32), colour, 3)
        cv2.putText(band, text, (x + 24, 37), cv2.FONT_HERSHEY_SIMPLEX, 0.45, (0, 0, 0), 1, cv2.LINE_AA)
        x += 34 + 9 * len(text)
    return np.vstack([band, img])


def write_png(path: Path, image: np.ndarray) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not cv2.imwrite(str(path), image):
        raise ConfigError(f"could not write the picture {path}")
