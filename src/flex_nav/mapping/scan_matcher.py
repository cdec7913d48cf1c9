"""Correlative scan-to-map matching: where, within a window around a prior pose, does a scan fit a set of points
best? (The matcher of the Karto / slam_toolbox / Cartographer family, after Olson, "Real-time correlative scan
matching", ICRA 2009.)

The reference points (a submap: the hits of nearby keyframes, map frame) are drawn into a lookup grid of
``resolution`` [m] whose cells hold ``exp(-d² / (2 sigma²))``, ``d`` the distance to the nearest reference point
(an exact EDT, cv2). A candidate pose scores the mean of the lookup values under the scan's points: 1 when every
point lies on the reference, 0 when none is near. The search covers every pose of a lattice over the window:
headings ``prior ± search_yaw`` in steps that move the farthest point by at most one cell, positions
``prior ± search_xy`` in steps of one cell. Exhaustive search at full resolution costs
(headings x positions x points); the multi-resolution search (branch and bound) scores blocks of
``coarse_factor`` x ``coarse_factor`` positions first with a table whose cells hold the maximum of the fine cells
they cover, which bounds every position of the block from above, then descends only into the blocks whose bound
beats the best full-resolution score found so far: the same optimum, a fraction of the work.

The lattice optimum is then refined below the cell (:func:`refine_subcell`: bilinear lookup, halving steps), and
its covariance taken from the scores around it (how fast the fit falls off along x, y and the heading).

For loop closures the caller asks for the best pose *outside* a region as well (``exclude``): a second pose that
fits nearly as well means the scene repeats (a corridor of identical doors) and the closure is not to be trusted.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple, Optional, Tuple

import cv2
import numpy as np

from flex_nav import validation
from flex_nav.localization.jit import cached_njit
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.planar import Pose2D

_NO_EXCLUSION = (0.0, 0.0, -1.0, 0, -1)  # (x [cells], y [cells], radius [cells], heading index, heading radius)


@dataclass(frozen=True)
class MatcherParams:
    """The scan matcher's settings; validated at construction (ConfigError naming the field)."""

    resolution: float = 0.025  # [m] lookup cells and position steps (half a 5 cm map cell: 5 mm matches)
    sigma: float = 0.05  # [m] how far off a point still scores (the lookup's Gaussian)
    coarse_factor: int = 4  # positions per side of a coarse block
    max_points: int = 200  # scan points used at most (evenly thinned)
    min_yaw_step: float = 0.005  # [rad] the heading step at least (scans of only near points)

    def __post_init__(self) -> None:
        owner = "scan matcher"
        validation.number(owner, "resolution", self.resolution, positive=True, unit="[m]")
        validation.number(owner, "sigma", self.sigma, positive=True, unit="[m]")
        validation.integer(owner, "coarse_factor", self.coarse_factor, minimum=1)
        validation.integer(owner, "max_points", self.max_points, minimum=3)
        validation.number(owner, "min_yaw_step", self.min_yaw_step, positive=True, unit="[rad]")


class Window(NamedTuple):
    """Where to search: ``prior`` ± ``xy`` [m] in x and y, ± ``yaw`` [rad] in heading (map frame)."""

    prior: Pose2D
    xy: float
    yaw: float


class Match(NamedTuple):
    pose: Pose2D  # [m, m, rad] map frame: the robot pose at which the scan fits best
    response: float  # [-] mean lookup value under the points at ``pose``, 0..1
    covariance: np.ndarray  # (3, 3) over x [m], y [m], yaw [rad]


class Lookup:
    """The reference points drawn into the fine table and its coarse (block-maximum) twin."""

    def __init__(self, points: np.ndarray, params: MatcherParams, margin: float) -> None:
        """``points``: (N, 2) [m] map frame; the table covers them plus ``margin`` [m] (the search window and the
        scan's reach, so that a candidate's points fall inside)."""
        self.params = params
        res = params.resolution
        pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        if pts.shape[0] == 0:
            pts = np.zeros((1, 2))
        low = pts.min(axis=0) - margin
        high = pts.max(axis=0) + margin
        self.origin = (math.floor(low[0] / res) * res, math.floor(low[1] / res) * res)  # [m] corner of cell (0, 0)
        width = math.ceil((high[0] - self.origin[0]) / res) + 1
        height = math.ceil((high[1] - self.origin[1]) / res) + 1
        cols = np.clip(((pts[:, 0] - self.origin[0]) / res).astype(np.int64), 0, width - 1)
        rows = np.clip(((pts[:, 1] - self.origin[1]) / res).astype(np.int64), 0, height - 1)
        empty = np.full((height, width), 255, dtype=np.uint8)
        empty[rows, cols] = 0
        distance = cv2.distanceTransform(empty, cv2.DIST_L2, cv2.DIST_MASK_PRECISE) * res  # [m] to the nearest point
        self.table = np.exp(-0.5 * (distance / params.sigma) ** 2).astype(np.float64)  # (H, W)
        self.coarse = _block_maximum(self.table, params.coarse_factor)

    def to_cells(self, x: np.ndarray, y: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """Map-frame coordinates [m] as fractional table coordinates [cells]."""
        res = self.params.resolution
        return (x - self.origin[0]) / res, (y - self.origin[1]) / res

    def scores(self, poses: np.ndarray, points: np.ndarray) -> np.ndarray:
        """(P,) mean bilinear lookup value of ``points`` ((M, 2) [m] robot frame) at each of ``poses`` ((P, 3))."""
        c, s = np.cos(poses[:, 2])[:, None], np.sin(poses[:, 2])[:, None]
        x = poses[:, 0:1] + c * points[None, :, 0] - s * points[None, :, 1]
        y = poses[:, 1:2] + s * points[None, :, 0] + c * points[None, :, 1]
        gx, gy = self.to_cells(x, y)
        return np.asarray(_bilinear(self.table, gx - 0.5, gy - 0.5).mean(axis=1))


def _block_maximum(table: np.ndarray, factor: int) -> np.ndarray:
    """``out[i, j] = max(table[i:i + factor, j:j + factor])`` (cells past the edge count as 0)."""
    height, width = table.shape
    padded = np.zeros((height + factor - 1, width + factor - 1))
    padded[:height, :width] = table
    out = np.zeros_like(table)
    for dy in range(factor):
        for dx in range(factor):
            np.maximum(out, padded[dy:dy + height, dx:dx + width], out=out)
    return out


def _bilinear(table: np.ndarray, gx: np.ndarray, gy: np.ndarray) -> np.ndarray:
    """Bilinear interpolation of ``table`` at cell-centre coordinates (0 = the centre of cell 0); 0 outside."""
    height, width = table.shape
    x0 = np.floor(gx).astype(np.int64)
    y0 = np.floor(gy).astype(np.int64)
    fx, fy = gx - x0, gy - y0
    out = np.zeros(gx.shape)
    for ox, oy, weight in ((0, 0, (1 - fx) * (1 - fy)), (1, 0, fx * (1 - fy)), (0, 1, (1 - fx) * fy), (1, 1, fx * fy)):
        cx, cy = x0 + ox, y0 + oy
        inside = (cx >= 0) & (cx < width) & (cy >= 0) & (cy < height)
        out += np.where(inside, table[np.where(inside, cy, 0), np.where(inside, cx, 0)], 0.0) * weight
    return out


@cached_njit
def _branch_and_bound(  # noqa: PLR0912, PLR0917 - a compiled kernel: plain positional arguments, flat loops
    table: np.ndarray, coarse: np.ndarray, cells_x: np.ndarray, cells_y: np.ndarray, reach: int, factor: int,
    exclusion: np.ndarray,
) -> Tuple[int, int, int, float]:  # pragma: no cover  (compiled)
    """The best (heading index, x offset, y offset [cells], summed score) over headings 0..K-1 (rows of
    ``cells_x``/``cells_y``: the points' integer cells at the prior position, per heading) and offsets
    -reach..reach, skipping the poses of ``exclusion`` (x, y [offset cells], radius [cells], heading index, heading
    radius; radius < 0: none)."""
    height, width = table.shape
    headings, count = cells_x.shape
    blocks = (2 * reach + factor) // factor
    bounds = np.empty(headings * blocks * blocks)
    for k in range(headings):
        for bi in range(blocks):
            for bj in range(blocks):
                ox0, oy0 = -reach + bj * factor, -reach + bi * factor
                total = 0.0
                for m in range(count):
                    cx, cy = cells_x[k, m] + ox0, cells_y[k, m] + oy0
                    if 0 <= cx < width and 0 <= cy < height:
                        total += coarse[cy, cx]
                bounds[(k * blocks + bi) * blocks + bj] = total
    order = np.argsort(-bounds)
    best = (-1, 0, 0, -1.0)
    ex_x, ex_y, ex_r, ex_k, ex_kr = exclusion[0], exclusion[1], exclusion[2], int(exclusion[3]), int(exclusion[4])
    for index in order:
        if bounds[index] <= best[3]:
            break
        k = index // (blocks * blocks)
        bi = (index // blocks) % blocks
        bj = index % blocks
        for oy in range(-reach + bi * factor, min(-reach + (bi + 1) * factor, reach + 1)):
            for ox in range(-reach + bj * factor, min(-reach + (bj + 1) * factor, reach + 1)):
                if ex_r >= 0.0 and abs(k - ex_k) <= ex_kr and (ox - ex_x) ** 2 + (oy - ex_y) ** 2 <= ex_r * ex_r:
                    continue
                total = 0.0
                for m in range(count):
                    cx, cy = cells_x[k, m] + ox, cells_y[k, m] + oy
                    if 0 <= cx < width and 0 <= cy < height:
                        total += table[cy, cx]
                if total > best[3]:
                    best = (k, ox, oy, total)
    return best


def thin(points: np.ndarray, max_points: int) -> np.ndarray:
    """At most ``max_points`` of ``points`` ((N, 2)), evenly spaced by index."""
    if points.shape[0] <= max_points:
        return points
    return np.asarray(points[np.rint(np.linspace(0, points.shape[0] - 1, max_points)).astype(np.int64)])


class ScanMatcher:
    """Matches scans (robot-frame points) against a :class:`Lookup`."""

    def __init__(self, params: MatcherParams) -> None:
        self.params = params

    def lookup(self, points: np.ndarray, margin: float) -> Lookup:
        return Lookup(points, self.params, margin)

    def match(
        self, lookup: Lookup, points: np.ndarray, window: Window,
        exclude: Optional[Tuple[Pose2D, float, float]] = None,
    ) -> Optional[Match]:
        """The best pose for ``points`` ((N, 2) [m], robot frame) within ``window``, refined below the cell, with
        its response and covariance; None for fewer than 3 points. ``exclude`` = (pose, radius [m], heading radius
        [rad]): poses that close to it are not candidates (the second-best fit, for a uniqueness check)."""
        p = self.params
        pts = thin(np.asarray(points, dtype=np.float64).reshape(-1, 2), p.max_points)
        if pts.shape[0] < 3:
            return None
        reach_m = float(np.hypot(pts[:, 0], pts[:, 1]).max())
        yaw_step = max(p.min_yaw_step, math.atan2(p.resolution, max(reach_m, p.resolution)))
        steps = math.ceil(window.yaw / yaw_step)
        headings = window.prior[2] + yaw_step * np.arange(-steps, steps + 1)
        c, s = np.cos(headings)[:, None], np.sin(headings)[:, None]
        gx, gy = lookup.to_cells(window.prior[0] + c * pts[None, :, 0] - s * pts[None, :, 1],
                                 window.prior[1] + s * pts[None, :, 0] + c * pts[None, :, 1])
        reach = math.ceil(window.xy / p.resolution)
        exclusion = np.array(_NO_EXCLUSION, dtype=np.float64)
        if exclude is not None:
            center, radius, yaw_radius = exclude
            exclusion[:] = ((center[0] - window.prior[0]) / p.resolution, (center[1] - window.prior[1]) / p.resolution,
                            radius / p.resolution, round(wrap_angle(center[2] - window.prior[2]) / yaw_step) + steps,
                            math.ceil(yaw_radius / yaw_step))
        k, ox, oy, total = _branch_and_bound(
            lookup.table, lookup.coarse, np.floor(gx).astype(np.int64), np.floor(gy).astype(np.int64), reach,
            p.coarse_factor, exclusion,
        )
        if k < 0:
            return None
        lattice = (window.prior[0] + ox * p.resolution, window.prior[1] + oy * p.resolution, float(headings[k]))
        pose = refine_subcell(lookup, pts, lattice, p.resolution, yaw_step)
        response = float(lookup.scores(np.array([pose]), pts)[0])
        if response < total / pts.shape[0]:  # the lattice pose fits better by the cell lookups: keep it
            pose, response = lattice, float(lookup.scores(np.array([lattice]), pts)[0])
        return Match((pose[0], pose[1], wrap_angle(pose[2])), response,
                     _covariance(lookup, pts, pose, p.resolution, yaw_step))


def refine_subcell(lookup: Lookup, points: np.ndarray, pose: Pose2D, step_xy: float, step_yaw: float) -> Pose2D:
    """Coordinate ascent on the bilinear score from ``pose``, steps halving from half a cell to 1/16 of one."""
    x, y, yaw = pose
    dxy, dyaw = step_xy / 2.0, step_yaw / 2.0
    for _ in range(4):
        for _ in range(8):
            probes = np.array([(x, y, yaw), (x + dxy, y, yaw), (x - dxy, y, yaw), (x, y + dxy, yaw),
                               (x, y - dxy, yaw), (x, y, yaw + dyaw), (x, y, yaw - dyaw)])
            scores = lookup.scores(probes, points)
            best = int(np.argmax(scores))
            if best == 0:
                break
            x, y, yaw = (float(v) for v in probes[best])
        dxy, dyaw = dxy / 2.0, dyaw / 2.0
    return x, y, yaw


def _covariance(lookup: Lookup, points: np.ndarray, pose: Pose2D, step_xy: float, step_yaw: float) -> np.ndarray:
    """A diagonal covariance from the curvature of the score at ``pose`` along x, y and the heading (a flat score
    along an axis, e.g. along a corridor, gives a large variance there); at least a tenth of a step squared."""
    x, y, yaw = pose
    probes = np.array([(x, y, yaw), (x + step_xy, y, yaw), (x - step_xy, y, yaw), (x, y + step_xy, yaw),
                       (x, y - step_xy, yaw), (x, y, yaw + step_yaw), (x, y, yaw - step_yaw)])
    s = lookup.scores(probes, points) * points.shape[0]  # summed score ~ log-likelihood up to a scale
    variances = []
    for index, step in ((1, step_xy), (3, step_xy), (5, step_yaw)):
        curvature = (2.0 * s[0] - s[index] - s[index + 1]) / step**2
        floor = (0.1 * step) ** 2
        variances.append(max(1.0 / curvature, floor) if curvature > 0.0 else 1e4 * floor)
    return np.diag(variances)
