"""Every shipped behavior loads, validates and draws offline (no master): names, files and structure."""

from __future__ import annotations

from pathlib import Path

import pytest
from unit.behavior.behavior_testlib import child

from flex_nav.behavior.container import Container
from flex_nav.behavior.state_machine import StateMachine
from flex_nav.behavior.yaml_loader import list_behaviors, load_behavior
from flex_nav_states.move_distance_state import MoveDistanceState

BEHAVIORS = Path(__file__).resolve().parents[2] / "behaviors"
NAMES = sorted(p.stem for p in BEHAVIORS.glob("*.yaml"))


def test_the_issue_behaviors_are_shipped() -> None:
    assert {"flex_planner", "simple_recovery", "multi_level_planner", "create_flex_planner", "move_base_like"} <= set(
        NAMES
    )
    assert set(NAMES) <= set(list_behaviors([BEHAVIORS]))


@pytest.mark.parametrize("name", NAMES)
def test_behavior_loads_validates_and_draws(name: str) -> None:
    behavior = load_behavior(BEHAVIORS / f"{name}.yaml")
    behavior.validate()
    assert behavior.name == name
    dot = behavior.to_dot()
    assert dot.startswith("digraph") and dot.rstrip().endswith("}")


def test_flex_planner_navigate_is_pluggable_and_recovers_by_sub_behavior() -> None:
    for navigate, followers in (("flex_navigate", {"Planner", "Controller"}),
                                ("multi_level_navigate", {"MidLevel", "LowLevel", "Controller"}),
                                ("create_navigate", {"MidLevel", "LowLevel", "Controller", "Health"})):
        root = load_behavior("flex_planner", parameters={"navigate": navigate}, search_path=[BEHAVIORS]).root
        assert isinstance(root, StateMachine)
        concurrency = child(root, "Navigate", "Navigate")
        assert isinstance(concurrency, Container)
        assert followers <= set(concurrency.children)
        assert {"Bumper"} <= set(concurrency.children)
        assert root.transitions_of("Navigate") == {
            "arrived": "Arrived", "failed": "CountReplan", "bumper": "Recovery", "stuck": "CountReplan"
        }
    root = load_behavior("flex_planner", search_path=[BEHAVIORS]).root
    assert isinstance(root, StateMachine)
    assert root.transitions_of("Recovery") == {"done": "CountReplan", "failed": "failed"}
    recovery = child(root, "Recovery")
    assert isinstance(recovery, Container)
    assert set(recovery.children) == {"Stop", "BackUp", "BackUpFailed", "Clear"}


def test_backup_distance_is_a_behavior_parameter() -> None:
    root = load_behavior("flex_planner", parameters={"backup_offset_m": -0.05}, search_path=[BEHAVIORS]).root
    backup = child(root, "Recovery", "BackUp")
    assert isinstance(backup, MoveDistanceState)
    assert backup._distance_m == pytest.approx(-0.05)
