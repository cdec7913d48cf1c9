"""Angles: the one wrap used by the controllers, the motion states and the simulator."""

from __future__ import annotations

import math


def wrap_angle(angle: float) -> float:
    """``angle`` [rad] wrapped into (−π, π]."""
    return math.atan2(math.sin(angle), math.cos(angle))
