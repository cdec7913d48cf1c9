"""Where a bumper touched something: contact points from bumper zone states, for any robot model.

A pressed zone means contact somewhere along its arc of the base; the contact point used to mark the
costmap is the middle of the arc, just outside the base circle. Pure: no rospy.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav_sim.profiles import RobotProfile

CONTACT_MARGIN = 0.03  # [m] the contact point lies this far outside the base radius


class BumperContacts:
    """Turns zone states into contact points (x [m], y [m]) in the robot's base frame, on each new press."""

    def __init__(self, profile: RobotProfile, margin_m: float = CONTACT_MARGIN) -> None:
        if not margin_m >= 0.0:
            raise ConfigError(f"bumper contact margin must be >= 0 [m], got {margin_m!r}")
        reach = profile.radius + margin_m
        self.points: dict[str, tuple[float, float]] = {
            zone.name: (reach * math.cos(zone.center), reach * math.sin(zone.center)) for zone in profile.bumper.zones
        }
        self._pressed: dict[str, bool] = dict.fromkeys(self.points, False)

    @property
    def zone_names(self) -> tuple[str, ...]:
        return tuple(self.points)

    def update(self, states: Mapping[str, bool]) -> list[tuple[str, float, float]]:
        """New presses among ``states`` (zone name -> pressed): [(zone, x, y)]; unknown zones raise ConfigError."""
        touched = []
        for zone, pressed in states.items():
            if zone not in self._pressed:
                raise ConfigError(choices_message("bumper zone", zone, self.points))
            if pressed and not self._pressed[zone]:
                touched.append((zone, *self.points[zone]))
            self._pressed[zone] = bool(pressed)
        return touched

    def update_lists(self, zones: Sequence[str], pressed: Sequence[bool]) -> list[tuple[str, float, float]]:
        if len(zones) != len(pressed):
            raise ConfigError(f"bumper state lists differ in length: {len(zones)} zones, {len(pressed)} flags")
        return self.update(dict(zip(zones, pressed)))
