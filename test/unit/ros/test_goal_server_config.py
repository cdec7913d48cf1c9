"""GoalServer refuses a client timeout that is negative or not a number, naming it, before it touches actionlib
(no master needed); the watch itself is tested against a real master in controller_safety.test."""

import math

import pytest

from flex_nav.action_types import action_type
from flex_nav.exceptions import ConfigError
from flex_nav.ros.goal_server import GoalServer


@pytest.mark.parametrize("timeout_s", [-0.5, math.nan])
def test_bad_client_timeout_is_refused(timeout_s: float) -> None:
    with pytest.raises(ConfigError, match=r"client timeout .* is not valid \(valid: >= 0, 0 = off\)"):
        GoalServer("pp", action_type("FollowPath"), lambda _ticket: None, client_timeout_s=timeout_s)
