"""The four actions: generated classes import, fields and result codes are those of the issue."""

from __future__ import annotations

import pytest

from flex_nav.action_types import ACTION_TYPES, action_type
from flex_nav.exceptions import ConfigError


def test_result_codes() -> None:
    assert action_type("GetPath").result_codes == {"EMPTY": 1, "FAILURE": 2, "SUCCESS": 0}
    assert action_type("FollowPath").result_codes == {"FAILURE": 1, "PREEMPT": 2, "SUCCESS": 0}
    assert action_type("FollowTopic").result_codes == {"FAILURE": 1, "PREEMPT": 2, "SUCCESS": 0}
    assert action_type("ClearCostmap").result_codes == {"FAILURE": 1, "SUCCESS": 0}


def test_fields_and_types() -> None:
    expected = {
        "GetPath": (["pose"], ["code", "plan", "message"], ["location", "goal"]),
        "FollowPath": (["path", "ignore_final_heading"], ["code", "pose", "message"], ["twist", "pose"]),
        "FollowTopic": (["topic", "newer_than", "ignore_final_heading"], ["code", "pose", "message"], ["path", "pose"]),
        "ClearCostmap": ([], ["code", "message"], []),
    }
    for name, (goal, result, feedback) in expected.items():
        spec = ACTION_TYPES[name]
        assert list(spec.goal.__slots__) == goal
        assert list(spec.result.__slots__) == result
        assert list(spec.feedback.__slots__) == feedback
    assert ACTION_TYPES["GetPath"].goal._slot_types == ["geometry_msgs/PoseStamped"]
    assert ACTION_TYPES["FollowTopic"].goal._slot_types == ["std_msgs/String", "time", "bool"]
    assert ACTION_TYPES["FollowPath"].goal._slot_types == ["nav_msgs/Path", "bool"]
    assert ACTION_TYPES["GetPath"].result._slot_types == ["uint8", "nav_msgs/Path", "string"]


def test_code_name() -> None:
    assert action_type("GetPath").code_name(1) == "EMPTY"
    assert action_type("GetPath").code_name(9) == "UNKNOWN(9)"


def test_unknown_action_names_choices() -> None:
    with pytest.raises(ConfigError, match=r"action 'GetPlan' is not valid \(valid: GetPath, FollowPath"):
        action_type("GetPlan")
