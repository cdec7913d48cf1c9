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


def compose_poses(a: Pose2D, b: Pose2D) -> Pose2D:
    """The transform ``a * b``: pose ``b`` given in the frame whose pose is ``a``, expressed in ``a``'s parent."""
    c, s = math.cos(a[2]), math.sin(a[2])
    yaw = a[2] + b[2]
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], math.atan2(math.sin(yaw), math.cos(yaw)))


def inverse_pose(p: Pose2D) -> Pose2D:
    """The inverse transform of ``p``: ``compose_poses(p, inverse_pose(p))`` is the identity."""
    c, s = math.cos(p[2]), math.sin(p[2])
    return (-(c * p[0] + s * p[1]), -(-s * p[0] + c * p[1]), -p[2])
