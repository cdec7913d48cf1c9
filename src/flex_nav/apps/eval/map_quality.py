"""How good is a built map? Cell agreement with the ground truth, wall offsets, explored share of the reachable
free area, trajectory error (evo), and a picture. Pure (no ROS): the mapping benchmark and ``mapping_run`` use it.

The built map lives in the mapper's frame (its first pose's odometry frame); ``map_in_world`` (x [m], y [m],
yaw [rad]) places it in the world, whose ground-truth map the simulator's world file gives.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any, Dict, Optional, Sequence, Tuple

import cv2
import numpy as np

from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.planar import Pose2D, inverse_pose, transform_poses

GHOST_M = 0.15  # [m] a mapped wall cell this far from any true wall is a ghost (a doubled wall, a moved object)
OCCUPIED_MIN = 50  # cell values from this up count as occupied, 0..OCCUPIED_MIN-1 as free, -1 unknown


@dataclass(frozen=True)
class MapScore:
    agree: float  # [-] of the cells the truth calls free or occupied and the built map observed, the share that agree
    compared: int  # cells compared
    wall_median_cm: float  # [cm] built wall cells' distance to the nearest true wall, median
    wall_p95_cm: float  # [cm] ... 95th percentile
    ghost: float  # [-] share of built wall cells farther than GHOST_M from a true wall
    explored: float  # [-] share of the truth's reachable free cells the built map knows (free or occupied)

    def as_dict(self) -> Dict[str, Any]:
        return asdict(self)


def _transform(pose: Pose2D, xs: np.ndarray, ys: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    points = transform_poses(np.column_stack([xs, ys]), *pose)
    return points[:, 0], points[:, 1]


def _values_at(grid: GridMap, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """Cell values of ``grid`` at world points (-1 outside)."""
    rows, cols = grid.world_to_cells(xs, ys)
    inside = (rows >= 0) & (rows < grid.height) & (cols >= 0) & (cols < grid.width)
    values = np.full(xs.shape, -1, dtype=np.int16)
    values[inside] = grid.occupancy[rows[inside], cols[inside]]
    return values


def reachable_free(truth: GridMap, start_xy: Tuple[float, float], robot_radius: float) -> np.ndarray:
    """(H, W) bool: the truth's free cells the robot can reach from ``start_xy`` [m] with ``robot_radius`` [m] of
    clearance, plus the free cells within ``robot_radius`` of those (what it sweeps)."""
    free = (truth.occupancy >= 0) & (truth.occupancy < OCCUPIED_MIN)
    blocked = np.where(truth.occupancy >= OCCUPIED_MIN, 0, 255).astype(np.uint8)
    clearance = cv2.distanceTransform(blocked, cv2.DIST_L2, cv2.DIST_MASK_PRECISE) * truth.resolution
    passable = (free & (clearance > robot_radius)).astype(np.uint8)
    _count, labels = cv2.connectedComponents(passable, connectivity=8)
    row, col = truth.world_to_cell(*start_xy)
    if not truth.in_bounds((row, col)) or labels[row, col] == 0:
        return np.zeros(free.shape, dtype=bool)
    centres = (labels == labels[row, col]).astype(np.uint8)
    size = 2 * math.ceil(robot_radius / truth.resolution) + 1
    swept = cv2.dilate(centres, cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (size, size))) > 0
    return np.asarray(swept & free)


def score_map(built: GridMap, truth: GridMap, map_in_world: Pose2D, start_xy: Tuple[float, float],
              robot_radius: float) -> MapScore:
    """Compare ``built`` with ``truth`` cell by cell, at the truth's cell centres (see MapScore)."""
    rows, cols = np.nonzero(truth.occupancy >= 0)
    wx, wy = truth.cells_to_world(rows, cols)
    mx, my = _transform(inverse_pose(map_in_world), wx, wy)
    values = _values_at(built, mx, my)
    true_values = truth.occupancy[rows, cols]
    seen = values >= 0
    agree = (float(np.mean((values[seen] >= OCCUPIED_MIN) == (true_values[seen] >= OCCUPIED_MIN)))
             if seen.any() else math.nan)
    reachable = reachable_free(truth, start_xy, robot_radius)[rows, cols]
    explored = float(np.mean(seen[reachable])) if reachable.any() else math.nan
    no_walls = np.where(truth.occupancy >= OCCUPIED_MIN, 0, 255).astype(np.uint8)
    wall_distance = cv2.distanceTransform(no_walls, cv2.DIST_L2, cv2.DIST_MASK_PRECISE) * truth.resolution
    brows, bcols = np.nonzero(built.occupancy >= OCCUPIED_MIN)
    tx, ty = _transform(map_in_world, *built.cells_to_world(brows, bcols))
    trow, tcol = truth.world_to_cells(tx, ty)
    inside = (trow >= 0) & (trow < truth.height) & (tcol >= 0) & (tcol < truth.width)
    d = wall_distance[trow[inside], tcol[inside]]
    if d.size == 0:
        return MapScore(agree, int(seen.sum()), math.nan, math.nan, math.nan, explored)
    return MapScore(agree, int(seen.sum()), 100.0 * float(np.median(d)), 100.0 * float(np.percentile(d, 95)),
                    float(np.mean(d > GHOST_M)), explored)


def aligned_placement(estimates: Sequence[Pose2D], truths: Sequence[Pose2D]) -> Optional[Pose2D]:
    """The rigid placement of the map frame in the world that maps the estimated positions onto the true ones best
    (least squares: evo's Umeyama alignment, the one behind the aligned ATE), as (x [m], y [m], yaw [rad]); None
    with fewer than 3 pairs, without evo, or when the positions are degenerate (all on a line)."""
    if len(estimates) < 3 or len(estimates) != len(truths):
        return None
    try:
        from evo.core.geometry import GeometryException, umeyama_alignment  # noqa: PLC0415 - evaluation only
    except ImportError:
        return None
    source = np.array([(p[0], p[1], 0.0) for p in estimates]).T
    target = np.array([(p[0], p[1], 0.0) for p in truths]).T
    try:
        rotation, translation, _scale = umeyama_alignment(source, target, with_scale=False)
    except GeometryException:
        return None
    if not math.isclose(rotation[2, 2], 1.0, abs_tol=1e-6):  # a flip about an in-plane axis: positions on a line
        return None
    return float(translation[0]), float(translation[1]), math.atan2(rotation[1, 0], rotation[0, 0])


def ate_rmse_cm(estimates: Sequence[Pose2D], truths: Sequence[Pose2D], align: bool = True) -> Optional[float]:
    """Absolute trajectory error (translation RMSE) [cm] of ``estimates`` against ``truths`` (pairs taken at the same
    stamps) computed with evo: after an SE(3) Umeyama alignment when ``align``, else as given. None without evo or
    with fewer than 3 pairs."""
    if len(estimates) < 3 or len(estimates) != len(truths):
        return None
    try:
        from evo.core import metrics  # noqa: PLC0415 - evaluation only
        from evo.core.trajectory import PoseTrajectory3D  # noqa: PLC0415
    except ImportError:
        return None
    stamps = np.arange(len(estimates), dtype=float)

    def trajectory(poses: Sequence[Pose2D]) -> Any:
        xyz = np.array([(p[0], p[1], 0.0) for p in poses])
        wxyz = np.array([(math.cos(p[2] / 2.0), 0.0, 0.0, math.sin(p[2] / 2.0)) for p in poses])
        return PoseTrajectory3D(positions_xyz=xyz, orientations_quat_wxyz=wxyz, timestamps=stamps)

    reference, estimate = trajectory(truths), trajectory(estimates)
    if align:
        estimate.align(reference, correct_scale=False)
    ape = metrics.APE(metrics.PoseRelation.translation_part)
    ape.process_data((reference, estimate))
    return 100.0 * float(ape.get_statistic(metrics.StatisticsType.rmse))


def draw_map(built: GridMap, truth: GridMap, map_in_world: Pose2D, trajectory: Sequence[Tuple[float, float]] = (),
             closures: Sequence[Tuple[Tuple[float, float], Tuple[float, float]]] = (), *, scale: int = 3) -> np.ndarray:
    """A BGR picture in the built map's frame (up = +y), ``scale`` pixels per cell: the built map (grey unknown,
    white free, black occupied), the true walls over it (dark red where the built map has them too, bright red
    where it calls them free, pink where it never saw them: inside obstacles), ``trajectory`` (map frame [m]) in
    blue and the loop closures (pairs of map-frame points) in green."""
    built_walls = built.occupancy >= OCCUPIED_MIN
    image = np.full((*built.occupancy.shape, 3), 170, dtype=np.uint8)
    image[(built.occupancy >= 0) & (built.occupancy < OCCUPIED_MIN)] = (255, 255, 255)
    image[built_walls] = (0, 0, 0)
    rows, cols = np.nonzero(truth.occupancy >= OCCUPIED_MIN)
    brow, bcol = built.world_to_cells(*_transform(inverse_pose(map_in_world), *truth.cells_to_world(rows, cols)))
    inside = (brow >= 0) & (brow < built.height) & (bcol >= 0) & (bcol < built.width)
    true_walls = np.zeros(built_walls.shape, dtype=bool)
    true_walls[brow[inside], bcol[inside]] = True
    image[true_walls & built_walls] = (0, 0, 120)
    image[true_walls & (built.occupancy < 0)] = (200, 200, 255)
    image[true_walls & (built.occupancy >= 0) & ~built_walls] = (0, 0, 230)
    image = np.asarray(cv2.resize(image, None, fx=scale, fy=scale, interpolation=cv2.INTER_NEAREST), dtype=np.uint8)

    def pixels(xs: np.ndarray, ys: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        ox, oy, _ = built.origin
        return (((xs - ox) / built.resolution) * scale).astype(np.int64), \
            (((ys - oy) / built.resolution) * scale).astype(np.int64)

    if len(trajectory) > 1:
        tx, ty = pixels(np.array([p[0] for p in trajectory]), np.array([p[1] for p in trajectory]))
        cv2.polylines(image, [np.column_stack([tx, ty]).astype(np.int32)], False, (200, 80, 20), 1)
    for a, b in closures:
        ax, ay = pixels(np.array([a[0]]), np.array([a[1]]))
        bx, by = pixels(np.array([b[0]]), np.array([b[1]]))
        cv2.line(image, (int(ax[0]), int(ay[0])), (int(bx[0]), int(by[0])), (0, 180, 0), 1)
    return np.ascontiguousarray(np.flipud(image))
