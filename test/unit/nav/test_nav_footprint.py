"""The footprint polygon drawn for a round base."""

import math

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.footprint import FOOTPRINT_SIDES, circle_footprint


def test_polygon_circumscribes_the_radius_counter_clockwise():
    corners = circle_footprint(0.177)
    assert corners.shape == (FOOTPRINT_SIDES, 2)
    assert corners[0] == pytest.approx((0.177 / math.cos(math.pi / FOOTPRINT_SIDES), 0.0))
    middles = (corners + np.roll(corners, -1, axis=0)) / 2.0
    assert np.hypot(middles[:, 0], middles[:, 1]) == pytest.approx(np.full(FOOTPRINT_SIDES, 0.177))  # sides touch it
    cross = corners[:, 0] * np.roll(corners[:, 1], -1) - np.roll(corners[:, 0], -1) * corners[:, 1]
    assert (cross > 0.0).all()  # counter-clockwise, convex
    assert circle_footprint(1.0, sides=4) == pytest.approx(np.array([[1, 0], [0, 1], [-1, 0], [0, -1]]) * math.sqrt(2))


@pytest.mark.parametrize(("radius", "sides"), [(0.0, 8), (-0.1, 8), (math.nan, 8), (0.2, 2), (0.2, 8.0)])
def test_bad_radius_or_sides_are_refused(radius, sides):
    with pytest.raises(ConfigError):
        circle_footprint(radius, sides)
