"""Planar (x, y, yaw) transforms of poses and paths; pure numpy."""

from __future__ import annotations

import math
from typing import Tuple

import numpy as np

Pose2D = Tuple[float, float, float]  # (x [m], y [m], yaw [rad]) in some planar frame


def transform_poses(poses: np.ndarray, x: float, y: float, yaw: float) -> np.ndarray:
    """(N, 3) poses [x, y, yaw] (or (N, 2) points) expressed in a frame whose pose is (x, y, yaw) -> parent frame."""
    poses = np.asarray(poses, dtype=np.float64)
    c, s = math.cos(yaw), math.sin(yaw)
    out = poses.copy()
    out[:, 0] = x + c * poses[:, 0] - s * poses[:, 1]
    out[:, 1] = y + s * poses[:, 0] + c * poses[:, 1]
    if poses.shape[1] > 2:
        out[:, 2] = np.arctan2(np.sin(poses[:, 2] + yaw), np.cos(poses[:, 2] + yaw))
    return out


def heading_along(points: np.ndarray) -> np.ndarray:
    """(N,) yaw [rad] along an (N, 2) polyline: each point faces the next distinct point; the points after the
    last distinct one keep the last segment's heading; 0 if all points coincide."""
    points = np.asarray(points, dtype=np.float64)
    count = len(points)
    yaw = np.zeros(count)
    seg = np.diff(points, axis=0)
    moving = (seg[:, 0] != 0.0) | (seg[:, 1] != 0.0)
    if not moving.any():
        return yaw
    seg_yaw = np.arctan2(seg[:, 1], seg[:, 0])
    last_index = int(np.flatnonzero(moving)[-1])
    following = seg_yaw[last_index]
    yaw[last_index + 1 :] = following
    for index in range(last_index, -1, -1):
        if moving[index]:
            following = seg_yaw[index]
        yaw[index] = following
    return yaw
