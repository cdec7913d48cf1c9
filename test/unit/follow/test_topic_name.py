"""topic_name_problem: illegal ROS names in a goal or a state parameter are refused with the reason."""

from __future__ import annotations

import pytest

from flex_nav.nav.control.topic_name import topic_name_problem


@pytest.mark.parametrize("name", ["plan", "/robot1/plan", "~plan", "follow_topic_server/plan", "a1_b2"])
def test_legal_names(name: str) -> None:
    assert topic_name_problem(name) is None


@pytest.mark.parametrize("name", ["..", "a/../b", "a b", " plan", "plan/", "a//b", "/", "1plan", "plan?", "~"])
def test_illegal_names(name: str) -> None:
    problem = topic_name_problem(name)
    assert problem is not None and repr(name) in problem


def test_empty_name() -> None:
    assert topic_name_problem("") == "the name is empty"
