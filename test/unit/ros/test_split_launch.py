"""flex_nav_robot.launch split over two computers (``part``), and the heartbeat parameters the launch files set.

Loaded with roslaunch's own loader (no master, nothing started): which nodes each part starts and which
parameters they get. The two-host system test (test_two_hosts_system.py) runs the split for real."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, List, Tuple

import pytest

REPO_ROOT = Path(__file__).resolve().parents[3]
ROBOT_NODES = ["bumper_relay", "follow_path_server", "follow_topic_server", "get_path_server", "localizer",
               "pure_pursuit_path", "pure_pursuit_topic"]


def load(launch: str, *args: str) -> Tuple[List[str], Dict[str, Any]]:
    """(sorted node names, parameters) of ``launch/<launch>`` with ``args``."""
    import roslaunch.config  # noqa: PLC0415 - ROS import only in the tests that need it

    config = roslaunch.config.load_config_default([(str(REPO_ROOT / "launch" / launch), ["roslaunch", *args])], None)
    return sorted(n.name for n in config.nodes), {name: p.value for name, p in config.params.items()}


@pytest.fixture(autouse=True)
def _package_path(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_PACKAGE_PATH", f"{REPO_ROOT}:/usr/share")


def test_all_on_one_computer_is_the_default_without_heartbeat() -> None:
    nodes, params = load("flex_nav_robot.launch")
    assert nodes == ["behavior_runner", "navigation"]
    assert sorted(params["/robot1/navigation/components"]) == ROBOT_NODES  # one process hosts them all
    assert params["/robot1/pure_pursuit_topic/heartbeat_timeout"] == 0.0
    nodes, params = load("flex_nav_robot.launch", "combined_navigation:=false")
    assert nodes == sorted([*ROBOT_NODES, "behavior_runner"])
    assert "/robot1/navigation/components" not in params
    assert params["/robot1/pure_pursuit_topic/heartbeat_timeout"] == 0.0


@pytest.mark.parametrize("combined", [True, False])
def test_the_robot_part_watches_the_heartbeat_and_runs_no_runner(combined: bool) -> None:
    nodes, params = load("flex_nav_robot.launch", "part:=robot", "twist_relay:=true",
                         f"combined_navigation:={str(combined).lower()}")
    if combined:
        assert nodes == ["navigation"]
        assert sorted(params["/robot1/navigation/components"]) == sorted([*ROBOT_NODES, "twist_relay"])
    else:
        assert nodes == sorted([*ROBOT_NODES, "twist_relay"])
    for node in ("pure_pursuit_path", "pure_pursuit_topic", "twist_relay"):
        assert params[f"/robot1/{node}/heartbeat_timeout"] == 0.5  # twist_relay's timeout (config)
    assert params["/robot1/twist_relay/timeout"] == 0.5
    assert params["/rosout_disable_topics_generation"] is True


def test_the_operator_part_is_the_runner_alone() -> None:
    nodes, params = load("flex_nav_robot.launch", "part:=operator", "behavior:=flex_planner")
    assert nodes == ["behavior_runner"]
    assert params["/robot1/behavior_runner/behavior"] == "flex_planner"
    assert not any(name.startswith("/robot1/pure_pursuit") for name in params)  # no navigation parameters


def test_an_unknown_part_is_refused() -> None:
    import roslaunch.core  # noqa: PLC0415

    with pytest.raises(roslaunch.core.RLException, match="part:=robots is not all, robot or operator"):
        load("flex_nav_robot.launch", "part:=robots")


def test_an_unknown_profile_is_refused_with_the_choices() -> None:
    import roslaunch.core  # noqa: PLC0415

    with pytest.raises(roslaunch.core.RLException,
                       match="profile:=kobuki2 is not a robot profile: kobuki, create2 or turtlebot4"):
        load("flex_nav_robot.launch", "profile:=kobuki2")


def test_the_simulators_twist_relay_takes_a_heartbeat_timeout() -> None:
    _nodes, params = load("sim.launch", "heartbeat_timeout:=0.5")
    assert params["/robot1/twist_relay/heartbeat_timeout"] == 0.5
    assert params["/rosout_disable_topics_generation"] is True
    _nodes, params = load("sim.launch")
    assert params["/robot1/twist_relay/heartbeat_timeout"] == 0.0


def test_the_robot_part_localizes_in_its_namespace_unless_told_not_to() -> None:
    nodes, params = load("flex_nav_robot.launch", "robot:=robot7", "part:=robot")
    assert "localizer" in params["/robot7/navigation/components"]
    nodes, params = load("flex_nav_robot.launch", "robot:=robot7", "part:=robot", "combined_navigation:=false")
    assert "localizer" in nodes
    assert params["/robot7/localizer/odom_frame_id"] == "robot7/odom"
    assert params["/robot7/localizer/base_frame_id"] == "robot7/base_footprint"
    assert params["/robot7/localizer/global_frame_id"] == "map"
    assert params["/robot7/localizer/recovery_alpha_fast"] == 0.1  # config/localizer.yaml
    for controller in ("pure_pursuit_path", "pure_pursuit_topic"):  # people are tracked in the smooth odom frame
        assert params[f"/robot7/{controller}/people_tracker/tracking_frame"] == "robot7/odom"
    nodes, params = load("flex_nav_robot.launch", "localizer:=false")
    assert "localizer" not in nodes
    assert "localizer" not in params["/robot1/navigation/components"]
    assert "/robot1/localizer/odom_frame_id" not in params


def test_the_simulator_launch_leaves_map_to_odom_to_the_localizer_unless_oracle() -> None:
    _nodes, params = load("sim.launch")
    assert params["/sim/publish_map_odom"] is False
    _nodes, params = load("sim.launch", "oracle:=true")
    assert params["/sim/publish_map_odom"] is True
    _nodes, params = load("sim_multi.launch")
    assert params["/sim/publish_map_odom"] is False


@pytest.mark.parametrize("profile", ["kobuki", "create2", "turtlebot4"])
def test_the_robot_part_sets_the_profiles_robot_description(profile: str) -> None:
    _, params = load("flex_nav_robot.launch", "robot:=robot2", f"profile:={profile}")
    assert params["/robot2/robot_description"] == (REPO_ROOT / "urdf" / f"{profile}.urdf").read_text()
    _, operator = load("flex_nav_robot.launch", "part:=operator", f"profile:={profile}")
    assert "/robot1/robot_description" not in operator  # the robot's side sets it, once


def test_the_navigation_process_hosts_the_components_asked_for() -> None:
    nodes, params = load("navigation.launch", "namespace:=robot7", "pure_pursuit_topic:=false", "follow_topic:=false")
    assert nodes == ["navigation"]
    assert params["/robot7/navigation/components"] == [
        "get_path_server", "follow_path_server", "pure_pursuit_path", "twist_relay"]
    assert params["/robot7/pure_pursuit_path/robot_base_frame"] == "base_footprint"  # where the component reads it
    assert "/robot7/pure_pursuit_topic/robot_base_frame" not in params
    nodes, _params = load("navigation.launch", "get_path:=false", "follow_path:=false", "follow_topic:=false",
                          "pure_pursuit_path:=false", "pure_pursuit_topic:=false", "twist_relay:=false")
    assert nodes == []  # nothing asked for: no process (an empty ~components would be refused)
