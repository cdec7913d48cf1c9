"""Where a bumper touched something: contact points from bumper zone states, for any robot model.

A pressed zone means contact somewhere along its arc of the base, so the whole arc is reported: points
every ``ARC_STEP_RAD`` along it, just outside the base circle (one point at the middle would let the next
plan graze the rest of a wide obstacle and hit it again). Pure: no rospy.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav_sim.profiles import RobotProfile

CONTACT_MARGIN = 0.03  # [m] the contact points lie this far outside the base radius
ARC_STEP_RAD = math.radians(15.0)  # spacing of the contact points along a zone's arc


class BumperContacts:
    """Turns zone states into contact points (x [m], y [m]) in the robot's base frame, on each new press."""

    def __init__(self, profile: RobotProfile, margin_m: float = CONTACT_MARGIN) -> None:
        if not margin_m >= 0.0:
            raise ConfigError(f"bumper contact margin must be >= 0 [m], got {margin_m!r}")
        reach = profile.radius + margin_m
        self.points: dict[str, list[tuple[float, float]]] = {}
        for zone in profile.bumper.zones:
            count = 1 + math.ceil((zone.max_angle - zone.min_angle) / ARC_STEP_RAD - 1e-9)
            span = zone.max_angle - zone.min_angle
            bearings = [zone.min_angle + span * i / max(1, count - 1) for i in range(count)]
            self.points[zone.name] = [(reach * math.cos(b), reach * math.sin(b)) for b in bearings]
        self._pressed: dict[str, bool] = dict.fromkeys(self.points, False)

    @property
    def zone_names(self) -> tuple[str, ...]:
        return tuple(self.points)

    def update(self, states: Mapping[str, bool]) -> list[tuple[str, float, float]]:
        """Contact points of new presses among ``states`` (zone name -> pressed): [(zone, x, y)], several per zone.

        Unknown zones raise ConfigError.
        """
        touched: list[tuple[str, float, float]] = []
        for zone, pressed in states.items():
            if zone not in self._pressed:
                raise ConfigError(choices_message("bumper zone", zone, self.points))
            if pressed and not self._pressed[zone]:
                touched.extend((zone, x, y) for x, y in self.points[zone])
            self._pressed[zone] = bool(pressed)
        return touched

    def update_lists(self, zones: Sequence[str], pressed: Sequence[bool]) -> list[tuple[str, float, float]]:
        if len(zones) != len(pressed):
            raise ConfigError(f"bumper state lists differ in length: {len(zones)} zones, {len(pressed)} flags")
        return self.update(dict(zip(zones, pressed)))
