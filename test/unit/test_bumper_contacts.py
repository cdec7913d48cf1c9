from __future__ import annotations

import math

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.bumper_contacts import BumperContacts
from flex_nav_sim.profiles import load_profile


def test_kobuki_center_press_marks_a_point_ahead_once() -> None:
    contacts = BumperContacts(load_profile("kobuki"), margin_m=0.03)
    assert set(contacts.zone_names) == {"left", "center", "right"}
    hits = contacts.update({"left": False, "center": True, "right": False})
    assert {h[0] for h in hits} == {"center"}
    reach = 0.177 + 0.03
    bearings = sorted(math.degrees(math.atan2(y, x)) for _, x, y in hits)
    assert bearings[0] == pytest.approx(-30.0) and bearings[-1] == pytest.approx(30.0)  # the whole arc
    assert all(b - a <= 15.0 + 1e-9 for a, b in zip(bearings, bearings[1:]))
    assert all(math.hypot(x, y) == pytest.approx(reach) for _, x, y in hits)
    assert contacts.update({"center": True}) == []  # held: no new contact
    assert contacts.update({"center": False}) == []
    assert {h[0] for h in contacts.update({"center": True})} == {"center"}  # pressed again


def test_left_zone_point_is_on_the_left() -> None:
    contacts = BumperContacts(load_profile("kobuki"))
    hits = contacts.update({"left": True})
    assert hits and all(y > 0.0 and math.hypot(x, y) > 0.177 for _, x, y in hits)


def test_unknown_zone_and_bad_lists_are_refused() -> None:
    contacts = BumperContacts(load_profile("create2"))
    with pytest.raises(ConfigError, match=r"bumper zone 'center' is not valid \(valid: left, right\)"):
        contacts.update({"center": True})
    with pytest.raises(ConfigError, match="differ in length"):
        contacts.update_lists(["left"], [True, False])
