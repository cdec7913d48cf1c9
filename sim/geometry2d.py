"""Planar geometry of world footprints: oriented rectangles and circles in the map frame.

Used before any physics exists (spawn checks at load time), to rasterise the static map and to draw
pictures, so it is plain math with no pybullet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Tuple

Point = Tuple[float, float]


@dataclass(frozen=True)
class Footprint:
    """The floor outline of a solid: an oriented rectangle (``radius == 0``) or a circle (``radius > 0``)."""

    x: float  # [m] centre
    y: float  # [m]
    yaw: float  # [rad] rectangle orientation
    size_x: float  # [m] rectangle extent along its own x (0 for circles)
    size_y: float  # [m]
    radius: float = 0.0  # [m] circle radius (0 for rectangles)

    @property
    def is_circle(self) -> bool:
        return self.radius > 0.0

    def corners(self) -> List[Point]:
        """Rectangle corners counter-clockwise (map frame) [m]; for a circle, its bounding square."""
        hx = self.radius if self.is_circle else self.size_x / 2.0
        hy = self.radius if self.is_circle else self.size_y / 2.0
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        local = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
        return [(self.x + c * px - s * py, self.y + s * px + c * py) for px, py in local]

    def distance_to(self, px: float, py: float) -> float:
        """Distance [m] from point (px, py) to the footprint's outline; 0 if the point is inside."""
        if self.is_circle:
            return max(0.0, math.hypot(px - self.x, py - self.y) - self.radius)
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        dx, dy = px - self.x, py - self.y
        lx, ly = c * dx + s * dy, -s * dx + c * dy
        ox = max(0.0, abs(lx) - self.size_x / 2.0)
        oy = max(0.0, abs(ly) - self.size_y / 2.0)
        return math.hypot(ox, oy)

    def bounds(self) -> Tuple[float, float, float, float]:
        """Axis-aligned bounding box (xmin, ymin, xmax, ymax) [m]."""
        if self.is_circle:
            r = self.radius
            return self.x - r, self.y - r, self.x + r, self.y + r
        xs, ys = zip(*self.corners())
        return min(xs), min(ys), max(xs), max(ys)


def segment_footprint(start: Point, end: Point, thickness: float) -> Footprint:
    """The rectangle of a wall segment from ``start`` to ``end`` [m], ``thickness`` [m] wide."""
    dx, dy = end[0] - start[0], end[1] - start[1]
    return Footprint(
        x=(start[0] + end[0]) / 2.0,
        y=(start[1] + end[1]) / 2.0,
        yaw=math.atan2(dy, dx),
        size_x=math.hypot(dx, dy),
        size_y=thickness,
    )


def project_on_segment(start: Point, end: Point, p: Point) -> Tuple[float, float]:
    """(t along the segment [m] from ``start``, signed perpendicular distance [m]) of point ``p``."""
    dx, dy = end[0] - start[0], end[1] - start[1]
    length = math.hypot(dx, dy)
    ux, uy = dx / length, dy / length
    qx, qy = p[0] - start[0], p[1] - start[1]
    return qx * ux + qy * uy, -qx * uy + qy * ux


