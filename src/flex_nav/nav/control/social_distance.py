"""Keeping a distance from people while moving: a speed limit that slows as a person comes closer and stops the
robot ``min_distance_m`` [m] from them, never driving toward a person; and whose doing a contact was.

The distance is measured from the robot's footprint (a polygon in its base frame, e.g.
:func:`flex_nav.nav.footprint.circle_footprint` or a rectangle) to each tracked person's body (a circle: the
tracker's centre and radius, :class:`~flex_nav.perception.moving_obstacles.Track`). Each control tick
(:meth:`SocialDistanceRule.limit`) the commanded twist (``v`` [m/s], ``w`` [rad/s]) is scaled by one factor
``k`` in [0, 1] (the same for both: the robot keeps its curvature), the smallest over the people within
``max_range_m``:

- the *closing speed* of the robot toward a person is the velocity of the footprint point nearest to them
  along the direction to them (a turn counts: the corners of a rectangular base swing toward people);
- a robot closing in (faster than ``stopped_speed_mps``) must be able to stop before the gap
  ``g = d - min_distance_m`` is used up, allowing ``latency_s`` [s] (L) of reaction and braking at
  ``decel_mps2`` [m/s^2] (a), while the person closes in at their own speed u until the robot stands: its
  closing speed c is at most the root of ``c * L + c^2 / (2 a) + u * (L + c / a) = g``; nothing once
  ``g <= u * L`` (it stops early and never drives toward a person inside the distance);
- inside ``slow_distance_m`` the robot's speed (not only its closing speed) is capped at ``max_speed_mps``
  scaled linearly from 1 at ``slow_distance_m`` to 0 at ``min_distance_m``, unless it is moving away
  from the person (closing speed below ``-stopped_speed_mps``): it slows down passing people, and may always
  leave.

A contact with a person is the robot's doing only when the robot was moving and the point that touched moved
toward the person (:func:`contact_cause`): a person who walks into a stopped robot, or into its back while it
drives away, is counted separately.

Pure numpy, no ROS, no clock; poses and tracks in one planar frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.nav.planar import Pose2D, transform_poses
from flex_nav.perception.moving_obstacles import Track

EPSILON_MPS = 1e-6  # [m/s] closing speeds smaller than this are no motion


@dataclass(frozen=True)
class SocialParams:
    """Parameters of :class:`SocialDistanceRule`; units in comments."""

    min_distance_m: float = 0.3  # [m] kept between the footprint and a person's body while moving
    slow_distance_m: float = 1.0  # [m] speed capped from here down to min_distance_m
    max_speed_mps: float = 0.31  # [m/s] the cap at slow_distance_m (TurtleBot 4's top speed 0.306 m/s)
    decel_mps2: float = 0.5  # [m/s^2] braking the limit counts on
    latency_s: float = 0.2  # [s] from a person's position measured to the robot braking
    stopped_speed_mps: float = 0.02  # [m/s] slower (at every footprint point) is standing still
    max_range_m: float = 4.0  # [m] people farther from the robot are ignored

    def __post_init__(self) -> None:
        for name in ("min_distance_m", "slow_distance_m", "max_speed_mps", "decel_mps2", "stopped_speed_mps",
                     "max_range_m"):
            validation.number("social distance", name, getattr(self, name), positive=True)
        validation.number("social distance", "latency_s", self.latency_s, minimum=0.0, unit="[s]")
        if self.slow_distance_m <= self.min_distance_m:
            raise ConfigError(
                f"social distance: slow_distance_m ({self.slow_distance_m!r}) must be > min_distance_m "
                f"({self.min_distance_m!r}) [m]")
        if self.max_range_m < self.slow_distance_m:
            raise ConfigError(
                f"social distance: max_range_m ({self.max_range_m!r}) must be >= slow_distance_m "
                f"({self.slow_distance_m!r}) [m]")


@dataclass(frozen=True)
class SocialLimit:
    """The command after the rule (``v`` [m/s], ``w`` [rad/s]), its scale, the nearest person's distance [m]
    (inf: nobody in range) and id, the person that limited it (None: not limited) and why."""

    v: float
    w: float
    scale: float
    closest_m: float
    closest_id: Optional[int]
    limited_by: Optional[int]
    reason: str

    @property
    def stopped(self) -> bool:
        """True when the rule stopped the robot (scale 0 on a command that moved)."""
        return self.scale == 0.0


def footprint_distance(polygon: np.ndarray, point: Tuple[float, float]) -> Tuple[float, np.ndarray]:
    """(distance [m], nearest point (2,)) from ``point`` to the closed ``polygon`` (N, 2) [m]; 0 and the point
    itself when inside."""
    a = polygon
    b = np.roll(polygon, -1, axis=0)
    p = np.asarray(point, dtype=np.float64)
    edge = b - a
    length_sq = np.maximum((edge * edge).sum(axis=1), 1e-18)
    t = np.clip(((p - a) * edge).sum(axis=1) / length_sq, 0.0, 1.0)
    nearest = a + t[:, None] * edge
    dist = np.hypot(nearest[:, 0] - p[0], nearest[:, 1] - p[1])
    best = int(np.argmin(dist))
    if _inside(polygon, p):
        return 0.0, p
    return float(dist[best]), nearest[best]


def _inside(polygon: np.ndarray, p: np.ndarray) -> bool:
    """Even-odd rule."""
    x, y = polygon[:, 0], polygon[:, 1]
    x2, y2 = np.roll(x, -1), np.roll(y, -1)
    crosses = (y > p[1]) != (y2 > p[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        at = x + (p[1] - y) * (x2 - x) / (y2 - y)
    return bool(np.count_nonzero(crosses & (p[0] < at)) % 2)


def point_velocity(pose: Pose2D, point: np.ndarray, v: float, w: float) -> np.ndarray:
    """Velocity (2,) [m/s] of a point (world [m]) fixed to a robot at ``pose`` driving at (v [m/s], w [rad/s])."""
    heading = np.array([math.cos(pose[2]), math.sin(pose[2])])
    arm = np.asarray(point, dtype=np.float64) - np.array([pose[0], pose[1]])
    return v * heading + w * np.array([-arm[1], arm[0]])


class SocialDistanceRule:
    """The speed limit around people; see the module docstring. Stateless: one call per control tick."""

    def __init__(self, params: SocialParams = SocialParams()) -> None:
        self.params = params

    def allowed_closing(self, gap_m: float, person_closing_mps: float = 0.0) -> float:
        """The robot's closing speed [m/s] from which it still stops before ``gap_m`` [m] is used up while the
        person closes in at ``person_closing_mps`` [m/s] (>= 0) until the robot stands: the largest ``c`` with
        ``c * L + c^2 / (2 a) + u * (L + c / a) <= gap`` (L latency, a deceleration, u the person's speed)."""
        p = self.params
        lat, a, u = p.latency_s, p.decel_mps2, max(0.0, person_closing_mps)
        room = gap_m - u * lat
        if room <= 0.0:
            return 0.0
        half_b = lat + u / a  # c^2 / (2 a) + c (L + u / a) - room = 0
        return a * (-half_b + math.sqrt(half_b * half_b + 2.0 * room / a))

    def limit(self, pose: Pose2D, footprint: np.ndarray, v: float, w: float,
              people: Sequence[Track]) -> SocialLimit:
        """The command (``v`` [m/s], ``w`` [rad/s]) of a robot at ``pose`` with ``footprint`` (N, 2) [m] in its
        base frame, limited for ``people`` (tracks predicted to now, same frame as ``pose``)."""
        p = self.params
        polygon = transform_poses(np.asarray(footprint, dtype=np.float64), *pose)
        scale, closest, closest_id, limited_by, reason = 1.0, math.inf, None, None, "no person near"
        for person in people:
            d_centre, nearest = footprint_distance(polygon, (person.x, person.y))
            distance = d_centre - person.radius
            if d_centre > p.max_range_m:
                continue
            if distance < closest:
                closest, closest_id = distance, person.track_id
            k, why = self._scale(pose, nearest, (person.x, person.y), (person.vx, person.vy), distance, v, w)
            if k < scale:
                scale, limited_by, reason = k, person.track_id, f"person #{person.track_id}: {why}"
        if limited_by is None and math.isfinite(closest):
            reason = f"nearest person #{closest_id} at {closest:.2f} m: no limit"
        return SocialLimit(scale * v, scale * w, scale, closest, closest_id, limited_by, reason)

    def _scale(self, pose: Pose2D, nearest: np.ndarray, centre: Tuple[float, float],  # noqa: PLR0917
               velocity: Tuple[float, float], distance: float, v: float, w: float) -> Tuple[float, str]:
        """(scale in [0, 1], why) for one person at ``distance`` [m] from the footprint point ``nearest``."""
        p = self.params
        toward = np.array(centre) - nearest
        norm = float(np.hypot(*toward))
        if norm < 1e-9:  # the person's centre on the footprint: every motion is toward them
            return (0.0, f"touching ({distance:.2f} m)") if abs(v) + abs(w) > 0.0 else (1.0, "")
        toward /= norm
        closing = float(point_velocity(pose, nearest, v, w) @ toward)
        person_closing = max(0.0, -float(np.array(velocity) @ toward))
        if closing < -p.stopped_speed_mps:
            return 1.0, "moving away"
        scale, why = 1.0, ""
        if closing > p.stopped_speed_mps:
            allowed = self.allowed_closing(distance - p.min_distance_m, person_closing)
            if allowed < closing:
                scale = allowed / closing
                why = (f"{distance:.2f} m away, closing {closing:.2f} m/s (person {person_closing:.2f} m/s): "
                       f"{allowed:.2f} m/s allowed")
        if distance < p.slow_distance_m and abs(v) > EPSILON_MPS:
            fraction = max(0.0, (distance - p.min_distance_m) / (p.slow_distance_m - p.min_distance_m))
            cap = p.max_speed_mps * fraction
            if cap < abs(v) * scale:
                scale = cap / abs(v)
                why = f"{distance:.2f} m away: speed capped at {cap:.2f} m/s"
        return scale, why


@dataclass(frozen=True)
class ContactCause:
    """Whether the robot caused a contact, the speed [m/s] of its touching point toward the person, and why."""

    robot_caused: bool
    closing_mps: float
    reason: str


def contact_cause(v: float, w: float, contact: Tuple[float, float], *, stopped_speed_mps: float = 0.02,
                  normal: Optional[Tuple[float, float]] = None) -> ContactCause:
    """Whose doing a contact was: the robot drove at (``v`` [m/s], ``w`` [rad/s]) when its footprint touched a
    person at ``contact`` (x, y) [m] in its base frame; ``normal``: the footprint's outward direction there
    (default: from the base's centre to the contact). The robot caused it if its touching point moved toward
    the person faster than ``stopped_speed_mps``; a stopped robot, or one whose touching point moved away or
    along, did not (the person walked into it)."""
    validation.number("contact", "stopped_speed_mps", stopped_speed_mps, positive=True, unit="[m/s]")
    cx, cy = float(contact[0]), float(contact[1])
    nx, ny = normal if normal is not None else (cx, cy)
    norm = math.hypot(nx, ny)
    if norm < 1e-9:
        raise ConfigError(f"contact: no direction at the contact point ({cx!r}, {cy!r}): give normal")
    closing = ((v - w * cy) * nx + (w * cx) * ny) / norm  # the touching point's velocity along the normal
    speed = math.hypot(v - w * cy, w * cx)
    if speed <= stopped_speed_mps:
        return ContactCause(False, closing, f"the robot was stopped ({speed:.3f} m/s at the contact): "
                                            "the person walked into it")
    if closing <= stopped_speed_mps:
        return ContactCause(False, closing, f"the robot's touching point moved away or along ({closing:+.3f} m/s "
                                            "toward the person): the person walked into it")
    return ContactCause(True, closing, f"the robot drove into the person at {closing:.3f} m/s")
