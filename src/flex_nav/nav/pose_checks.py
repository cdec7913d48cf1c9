"""Checks of poses and paths received from outside (goals, paths), before any algorithm sees them.

Each check returns ``None`` when the input is acceptable, or a human-readable reason that a server puts in
its result ``message``. Pure functions on plain numbers; no rospy.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

QUATERNION_NORM_TOLERANCE = 1e-2  # |‖q‖ − 1| above this counts as not normalised (RViz sends ‖q‖ = 1 ± 1e-7)


def pose_problem(position: Sequence[float], orientation: Sequence[float]) -> str | None:
    """Why the pose (x, y, z) [m], quaternion (x, y, z, w) is unusable, or ``None`` if it is fine."""
    if not all(math.isfinite(v) for v in position):
        return f"position {tuple(position)} is not finite"
    if not all(math.isfinite(v) for v in orientation):
        return f"orientation {tuple(orientation)} is not finite"
    norm = math.sqrt(sum(v * v for v in orientation))
    if abs(norm - 1.0) > QUATERNION_NORM_TOLERANCE:
        return f"orientation quaternion {tuple(orientation)} is not normalised (norm {norm:.4f}, expected 1)"
    return None


def frame_problem(frame_id: str, expected_frame: str) -> str | None:
    """Why ``frame_id`` is not usable where ``expected_frame`` is required (a leading '/' is tolerated)."""
    if not frame_id:
        return f"frame_id is empty (expected '{expected_frame}')"
    if frame_id.lstrip("/") != expected_frame.lstrip("/"):
        return f"frame_id '{frame_id}' is not the planning frame '{expected_frame}'"
    return None


def yaw_of_quaternion(x: float, y: float, z: float, w: float) -> float:
    """Yaw [rad] in (−π, π] of a quaternion (rotation about z of its ZYX Euler decomposition)."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def quaternion_of_yaw(yaw: float) -> tuple[float, float, float, float]:
    """Quaternion (x, y, z, w) of a rotation by ``yaw`` [rad] about z."""
    return (0.0, 0.0, math.sin(0.5 * yaw), math.cos(0.5 * yaw))
