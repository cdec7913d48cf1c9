"""behavior_runner's ``~robot_profile``: a behavior that declares a ``profile`` parameter gets the robot's
(flex_nav_robot.launch's ``profile``), so flex_planner's bumper monitor listens to the robot's own bumper topic;
an explicit override wins and a behavior without the parameter is left alone. No master needed."""

from pathlib import Path

import pytest

from flex_nav.behavior.yaml_loader import declared_parameter_names
from flex_nav.exceptions import BehaviorLoadError, ConfigError
from flex_nav.nodes.behavior_runner import PACKAGE_BEHAVIORS, with_robot_profile


def test_the_shipped_behaviors_that_watch_bumpers_declare_a_profile() -> None:
    assert "profile" in declared_parameter_names("flex_planner", [PACKAGE_BEHAVIORS])
    assert "profile" in declared_parameter_names(PACKAGE_BEHAVIORS / "push_or_avoid.yaml")
    assert "profile" not in declared_parameter_names("count_try", [PACKAGE_BEHAVIORS])


def test_declared_names_of_a_file_and_its_errors(tmp_path: Path) -> None:
    (tmp_path / "b.yaml").write_text("behavior: b\nparameters:\n  speed: {type: float, default: 0.1}\n  x: 1\n")
    assert declared_parameter_names("b", [tmp_path]) == frozenset({"speed", "x"})
    (tmp_path / "none.yaml").write_text("behavior: none\nstates: {}\n")
    assert declared_parameter_names(tmp_path / "none.yaml") == frozenset()
    (tmp_path / "bad.yaml").write_text("behavior: [unclosed\n")
    with pytest.raises(BehaviorLoadError, match=r"bad\.yaml"):
        declared_parameter_names(tmp_path / "bad.yaml")
    with pytest.raises(ConfigError, match="missing"):
        declared_parameter_names("missing", [tmp_path])


@pytest.mark.parametrize(("parameters", "declared", "robot_profile", "expected"), [
    ({}, frozenset({"profile"}), "turtlebot4", {"profile": "turtlebot4"}),
    ({"speed": 0.2}, frozenset({"profile", "speed"}), "create2", {"speed": 0.2, "profile": "create2"}),
    ({"profile": "kobuki"}, frozenset({"profile"}), "turtlebot4", {"profile": "kobuki"}),  # override wins
    ({}, frozenset({"speed"}), "turtlebot4", {}),  # not declared: an unknown parameter would stop the load
    ({}, frozenset({"profile"}), "", {}),  # no robot profile given: the behavior's default
])
def test_with_robot_profile(parameters: dict, declared: frozenset, robot_profile: str, expected: dict) -> None:
    given = dict(parameters)
    assert with_robot_profile(parameters, declared, robot_profile) == expected
    assert parameters == given  # the caller's dict is not changed
