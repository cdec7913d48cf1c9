from __future__ import annotations

import math

import pytest

from flex_nav.bumper_contacts import BumperContacts
from flex_nav.exceptions import ConfigError
from flex_nav_sim.profiles import load_profile


def test_kobuki_center_press_marks_a_point_ahead_once() -> None:
    contacts = BumperContacts(load_profile("kobuki"), margin_m=0.03)
    assert set(contacts.zone_names) == {"left", "center", "right"}
    hits = contacts.update({"left": False, "center": True, "right": False})
    assert len(hits) == 1
    zone, x, y = hits[0]
    assert zone == "center"
    assert x == pytest.approx(0.177 + 0.03) and y == pytest.approx(0.0, abs=1e-9)
    assert contacts.update({"center": True}) == []  # held: no new contact
    assert contacts.update({"center": False}) == []
    assert [h[0] for h in contacts.update({"center": True})] == ["center"]  # pressed again


def test_left_zone_point_is_on_the_left() -> None:
    contacts = BumperContacts(load_profile("kobuki"))
    (_, x, y), = contacts.update({"left": True})
    assert y > 0.0 and math.hypot(x, y) > 0.177


def test_unknown_zone_and_bad_lists_are_refused() -> None:
    contacts = BumperContacts(load_profile("create2"))
    with pytest.raises(ConfigError, match=r"bumper zone 'center' is not valid \(valid: left, right\)"):
        contacts.update({"center": True})
    with pytest.raises(ConfigError, match="differ in length"):
        contacts.update_lists(["left"], [True, False])
