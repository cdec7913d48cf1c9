"""A small asymmetric room as an occupancy grid, scans ray-cast on it, and a robot driven through it with noisy
odometry: the world of the localization tests (no simulator, no ROS)."""

from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple

import numpy as np

from flex_nav.localization import GridMap, Localizer, ScanBeams
from flex_nav.nav.planar import Pose2D, compose_poses, inverse_pose

RESOLUTION = 0.05  # [m]
RANGE_MIN = 0.05  # [m]
RANGE_MAX = 6.0  # [m]
ANGLES = np.radians(np.arange(-135.0, 135.01, 1.0))  # 271 beams over 270 deg
LASER_POSE = (0.1, 0.0, 0.0)  # laser 10 cm ahead of the base


def asymmetric_room() -> GridMap:
    """An L-shaped room, 6 m x 4 m less its 2 m x 1.5 m north-east corner (walls one cell thick, unknown cells
    around), with a square pillar and a short wall stub: no two poses see the same."""
    cells_x, cells_y = int(7.0 / RESOLUTION), int(5.0 / RESOLUTION)
    occupancy = np.full((cells_y, cells_x), -1, dtype=np.int8)

    def fill(x0: float, y0: float, x1: float, y1: float, value: int) -> None:
        occupancy[round(y0 / RESOLUTION):round(y1 / RESOLUTION), round(x0 / RESOLUTION):round(x1 / RESOLUTION)] = value

    fill(0.5, 0.5, 6.5, 3.0, 0)  # free: the south part, 6 m wide ...
    fill(0.5, 3.0, 4.5, 4.5, 0)  # ... and the north-west part, 4 m wide
    fill(0.45, 0.45, 6.55, 0.5, 100)  # south wall
    fill(0.45, 0.45, 0.5, 4.55, 100)  # west wall
    fill(0.45, 4.5, 4.55, 4.55, 100)  # north wall
    fill(4.5, 2.95, 4.55, 4.55, 100)  # inner wall of the cut corner, north-south ...
    fill(4.5, 2.95, 6.55, 3.0, 100)  # ... and east-west
    fill(6.5, 0.45, 6.55, 3.0, 100)  # east wall
    fill(2.4, 1.6, 2.8, 2.0, 100)  # pillar
    fill(0.5, 3.6, 1.3, 3.7, 100)  # wall stub from the west
    return GridMap(occupancy, RESOLUTION, (0.0, 0.0, 0.0))


def symmetric_room(marker: bool = False) -> GridMap:
    """A 6 m x 4 m room (walls one cell thick) with a 2.4 m x 0.4 m island in its middle: the same under a half turn
    about the centre :data:`CENTRE`, cell for cell. ``marker`` adds a 30 cm pillar near the south-west corner that
    breaks the symmetry (seen from :data:`SOUTH`, not from its mirror)."""
    cells_x, cells_y = int(7.0 / RESOLUTION), int(5.0 / RESOLUTION)
    occupancy = np.full((cells_y, cells_x), -1, dtype=np.int8)

    def fill(x0: float, y0: float, x1: float, y1: float, value: int) -> None:
        occupancy[round(y0 / RESOLUTION):round(y1 / RESOLUTION), round(x0 / RESOLUTION):round(x1 / RESOLUTION)] = value

    fill(0.45, 0.45, 6.55, 4.55, 100)  # walls ...
    fill(0.5, 0.5, 6.5, 4.5, 0)  # ... around the free room
    fill(2.3, 2.3, 4.7, 2.7, 100)  # the island
    if marker:
        fill(1.0, 0.8, 1.3, 1.1, 100)
    return GridMap(occupancy, RESOLUTION, (0.0, 0.0, 0.0))


CENTRE = (3.5, 2.5)  # [m] of symmetric_room
SOUTH = (3.0, 1.6, math.pi / 2)  # between the island and the south wall, facing the island
NORTH = (4.0, 3.4, -math.pi / 2)  # its mirror image


def cast(grid: GridMap, pose: Pose2D, rng: Optional[np.random.Generator] = None, noise: float = 0.0) -> np.ndarray:
    """Ranges [m] of a scan from the robot at ``pose`` (map frame): the first occupied cell along each beam of
    :data:`ANGLES` (steps of a quarter cell), +inf if none within RANGE_MAX, plus Gaussian noise of std ``noise``."""
    lx, ly, _ = compose_poses(pose, LASER_POSE)
    steps = np.arange(1, int(RANGE_MAX / (RESOLUTION / 4))) * (RESOLUTION / 4)
    directions = pose[2] + ANGLES
    xs = lx + np.cos(directions)[:, None] * steps[None, :]
    ys = ly + np.sin(directions)[:, None] * steps[None, :]
    rows, cols = grid.world_to_cells(xs, ys)
    inside = (rows >= 0) & (rows < grid.height) & (cols >= 0) & (cols < grid.width)
    hit = np.zeros(xs.shape, dtype=bool)
    hit[inside] = grid.occupancy[rows[inside], cols[inside]] >= 65
    first = np.where(hit.any(axis=1), hit.argmax(axis=1), -1)
    ranges = np.where(first >= 0, steps[np.maximum(first, 0)], np.inf)
    if rng is not None and noise > 0.0:
        ranges = ranges + noise * rng.standard_normal(ranges.shape)
    return ranges


def scan_at(grid: GridMap, pose: Pose2D, rng: Optional[np.random.Generator] = None, noise: float = 0.0) -> ScanBeams:
    return ScanBeams(cast(grid, pose, rng, noise), ANGLES, LASER_POSE, RANGE_MIN, RANGE_MAX)


def wall_cells_near_truth(room: GridMap, built: GridMap) -> Tuple[int, float]:
    """How many occupied (100) cells ``built`` has, and the share of them within one cell of an occupied cell of
    ``room`` (both maps in the same frame)."""
    rows, cols = np.nonzero(built.occupancy == 100)
    xs, ys = built.cells_to_world(rows, cols)
    true_rows, true_cols = room.world_to_cells(xs, ys)
    near = np.zeros(rows.shape, dtype=bool)
    for d_row in (-1, 0, 1):
        for d_col in (-1, 0, 1):
            r = np.clip(true_rows + d_row, 0, room.height - 1)
            c = np.clip(true_cols + d_col, 0, room.width - 1)
            near |= room.occupancy[r, c] >= 65
    return int(rows.size), float(np.mean(near)) if rows.size else 0.0


def path_poses(waypoints: Sequence[Tuple[float, float]], step: float = 0.05, turn_step: float = 0.1) -> List[Pose2D]:
    """Poses every ``step`` [m] along straight legs through ``waypoints``, facing along each leg, turning on the
    spot between legs in steps of ``turn_step`` [rad]."""
    poses: List[Pose2D] = []
    for (x0, y0), (x1, y1) in zip(waypoints[:-1], waypoints[1:]):
        length = math.hypot(x1 - x0, y1 - y0)
        yaw = math.atan2(y1 - y0, x1 - x0)
        if poses:
            last = poses[-1][2]
            turn = math.atan2(math.sin(yaw - last), math.cos(yaw - last))
            for a in np.arange(turn_step, abs(turn), turn_step):
                poses.append((x0, y0, last + math.copysign(a, turn)))
        for s in np.arange(0.0, length, step):
            poses.append((x0 + s * math.cos(yaw), y0 + s * math.sin(yaw), yaw))
    return poses


def drive(
    localizer: Localizer, grid: GridMap, poses: Sequence[Pose2D], rng: np.random.Generator,
    odom_noise: float = 0.01, range_noise: float = 0.01,
) -> List[float]:
    """Drive the robot through ``poses`` (true, map frame), giving the localizer odometry with ``odom_noise``
    relative error per step and a scan at every pose; returns the position error [m] after each step of the pose
    a node would publish (the last estimate moved on by the odometry since that update)."""
    odom = (0.0, 0.0, 0.0)
    localizer.update(odom, None)
    estimate, odom_at_estimate = localizer.estimate().pose, odom
    errors = []
    for before, after in zip(poses[:-1], poses[1:]):
        dx, dy, dyaw = compose_poses(inverse_pose(before), after)
        scale = 1.0 + odom_noise * rng.standard_normal(3)
        odom = compose_poses(odom, (dx * scale[0], dy * scale[1], dyaw * scale[2]))
        if localizer.update(odom, scan_at(grid, after, rng, range_noise)):
            estimate, odom_at_estimate = localizer.estimate().pose, odom
        x, y, _ = compose_poses(estimate, compose_poses(inverse_pose(odom_at_estimate), odom))
        errors.append(math.hypot(x - after[0], y - after[1]))
    return errors
