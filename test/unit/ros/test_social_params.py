"""``~social_distance/`` of the controllers (no master: rospy.get_param replaced): off unless enabled, the
SocialParams fields by name, an unknown name or a bad value refused with the valid names."""

from __future__ import annotations

from typing import Any, Dict

import pytest
import rospy

from flex_nav.exceptions import ConfigError
from flex_nav.ros.moving_obstacles_ros import social_rule


def rule_from(monkeypatch: pytest.MonkeyPatch, raw: Any) -> Any:
    params: Dict[str, Any] = {"~social_distance": raw}
    monkeypatch.setattr(rospy, "get_param", lambda name, default=None: params.get(name, default))
    return social_rule()


def test_off_unless_enabled(monkeypatch: pytest.MonkeyPatch) -> None:
    assert rule_from(monkeypatch, {}) is None
    assert rule_from(monkeypatch, {"enabled": False, "min_distance_m": 0.5}) is None


def test_enabled_with_its_fields(monkeypatch: pytest.MonkeyPatch) -> None:
    rule = rule_from(monkeypatch, {"enabled": True, "min_distance_m": 0.4, "slow_distance_m": 1.5})
    assert rule is not None
    assert (rule.params.min_distance_m, rule.params.slow_distance_m) == (0.4, 1.5)
    assert rule.params.latency_s == 0.2  # the default


@pytest.mark.parametrize(("raw", "message"), [
    ({"enabled": True, "min_distance": 0.4}, r"'min_distance' is not valid \(valid: enabled, min_distance_m"),
    ({"enabled": "yes"}, "enabled = 'yes' is not true/false"),
    ({"enabled": True, "min_distance_m": "near"}, "social_distance"),
    ([0.3], "must be a dictionary"),
])
def test_bad_parameters_are_refused(monkeypatch: pytest.MonkeyPatch, raw: Any, message: str) -> None:
    with pytest.raises(ConfigError, match=message):
        rule_from(monkeypatch, raw)
