"""The robot's footprint as a polygon in its base frame, for display (RViz's Polygon display); pure numpy.

flex_nav's costmaps treat every supported base as a circle of ``robot_radius`` (its inscribed radius); the
polygon drawn is the regular polygon circumscribing that circle, so the outline never looks smaller than the
disc the planners and controllers keep clear.
"""

from __future__ import annotations

import math

import numpy as np

from flex_nav import validation

FOOTPRINT_SIDES = 24  # corners of the drawn circle: within 0.9 % of the radius at the middle of a side


def circle_footprint(radius_m: float, sides: int = FOOTPRINT_SIDES) -> np.ndarray:
    """(sides, 2) corners [m], counter-clockwise from +x, of the regular polygon around a circle of
    ``radius_m`` [m] centred on the base frame's origin (ConfigError for a radius <= 0 or fewer than 3 sides)."""
    validation.number("footprint", "radius_m", radius_m, minimum=0.0, positive=True, unit="[m]")
    validation.integer("footprint", "sides", sides, minimum=3)
    corner_m = radius_m / math.cos(math.pi / sides)  # the sides touch the circle at their middle
    angles = 2.0 * math.pi * np.arange(sides) / sides
    return np.column_stack([corner_m * np.cos(angles), corner_m * np.sin(angles)])
