"""Lidar by batched ray casts and an RGB-D camera by offscreen rendering, for one robot.

Lidar rays start at the robot's body outline (never inside its own cylinder, so a robot does not see
itself) and end at ``range_max``; other robots, people, boxes and obstacles taller than the scan
plane are hit, low obstacles are not. Ranges get Gaussian noise ``noise_std + noise_fraction * r``;
no return within range gives +inf (REP 117).
"""

from __future__ import annotations

import math
from typing import Any, Tuple

import numpy as np
import pybullet

from flex_nav_sim.profiles import CameraSpec, LidarSpec
from flex_nav_sim.readings import Pose2D

BODY_MARGIN = 0.005  # [m] rays start this far outside the robot's own cylinder


class Lidar:
    """A planar scanner mounted on a robot; :meth:`scan` casts all beams in one ``rayTestBatch``."""

    def __init__(self, client: Any, spec: LidarSpec, body_radius: float, rng: np.random.Generator) -> None:
        self.client = client
        self.spec = spec
        self.rng = rng
        angles = spec.beam_angles()
        self._cos = np.cos(angles)
        self._sin = np.sin(angles)
        mx, my, _ = spec.mount
        # distance along each beam from the scan centre to just outside the body circle:
        # |m + s d| = R  ->  s = -(m.d) + sqrt((m.d)^2 - |m|^2 + R^2)
        md = mx * self._cos + my * self._sin
        radius = body_radius + BODY_MARGIN
        inside = max(0.0, radius * radius - (mx * mx + my * my))
        start = -md + np.sqrt(md * md + inside)
        self._start = np.maximum(start, 0.0)
        self._length = np.maximum(spec.range_max - self._start, 1e-3)

    def scan(self, pose: Pose2D) -> np.ndarray:
        """Ranges [m] (float32) for the robot at ``pose`` (map frame)."""
        spec = self.spec
        c, s = math.cos(pose.yaw), math.sin(pose.yaw)
        mx, my, mz = spec.mount
        ox = pose.x + c * mx - s * my
        oy = pose.y + s * mx + c * my
        dir_x = c * self._cos - s * self._sin
        dir_y = s * self._cos + c * self._sin
        n = dir_x.shape[0]
        starts = np.empty((n, 3))
        ends = np.empty((n, 3))
        starts[:, 0] = ox + dir_x * self._start
        starts[:, 1] = oy + dir_y * self._start
        starts[:, 2] = mz
        ends[:, 0] = ox + dir_x * spec.range_max
        ends[:, 1] = oy + dir_y * spec.range_max
        ends[:, 2] = mz
        results = self.client.rayTestBatch(starts, ends, numThreads=1)
        fractions = np.fromiter((r[2] for r in results), dtype=np.float64, count=n)
        hit = np.fromiter((r[0] >= 0 for r in results), dtype=bool, count=n)
        ranges = self._start + fractions * self._length
        sigma = spec.noise_std + spec.noise_fraction * ranges
        ranges = ranges + sigma * self.rng.standard_normal(n)
        ranges = np.where(hit, np.clip(ranges, spec.range_min, spec.range_max), np.inf)
        return ranges.astype(np.float32)


def depth_from_buffer(buffer: Any, width: int, height: int, near: float, far: float) -> np.ndarray:
    """Metric depth [m] (float32, height x width) from pybullet's OpenGL depth buffer (values 0..1).

    Depth along the optical axis as in a REP 118 depth image; pixels at the far plane (nothing rendered)
    are +inf, like a depth camera's "no return"."""
    d = np.asarray(buffer, dtype=np.float64).reshape(height, width)
    z = far * near / (far - (far - near) * d)
    return np.where(d >= 1.0, np.inf, z).astype(np.float32)


class Camera:
    """A forward-looking RGB-D camera rendered with ER_TINY_RENDERER (no display needed); the depth
    image is registered to the colour image (same pixels)."""

    def __init__(self, client: Any, spec: CameraSpec) -> None:
        self.client = client
        self.spec = spec
        self._projection = client.computeProjectionMatrixFOV(
            math.degrees(spec.vfov), spec.width / spec.height, spec.near, spec.far
        )

    def render(self, pose: Pose2D) -> Tuple[np.ndarray, np.ndarray]:
        """The RGB image uint8 (height, width, 3) and depth [m] float32 (height, width) seen from the
        robot at ``pose`` (map frame)."""
        spec = self.spec
        c, s = math.cos(pose.yaw), math.sin(pose.yaw)
        mx, my, mz = spec.mount
        eye = [pose.x + c * mx - s * my, pose.y + s * mx + c * my, mz]
        cp, sp = math.cos(spec.pitch), math.sin(spec.pitch)
        target = [eye[0] + c * cp, eye[1] + s * cp, mz - sp]
        up = [c * sp, s * sp, cp]
        view = self.client.computeViewMatrix(eye, target, up)
        _, _, rgba, depth, _ = self.client.getCameraImage(
            spec.width,
            spec.height,
            view,
            self._projection,
            renderer=pybullet.ER_TINY_RENDERER,
            flags=pybullet.ER_NO_SEGMENTATION_MASK,
            shadow=0,
        )
        image = np.asarray(rgba, dtype=np.uint8).reshape(spec.height, spec.width, 4)
        rgb = np.ascontiguousarray(image[:, :, :3])
        return rgb, depth_from_buffer(depth, spec.width, spec.height, spec.near, spec.far)
