"""rviz/flex_nav.rviz and rviz/multi_robot.rviz: map frame, every robot's displays in its namespace, the
tools publishing into the namespaces (navigation_drive.test checks that the stack publishes these topics)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional, Tuple

import pytest
import yaml

REPO_ROOT = Path(__file__).resolve().parents[2]
# each robot's displays: class -> topic (or robot description) relative to the robot's namespace
ROBOT_TOPICS = {
    ("rviz/Map", "Global costmap"): "get_path_server/global_costmap/costmap",
    ("rviz/Map", "Local costmap"): "follow_path_server/local_costmap/costmap",
    ("rviz/Polygon", "Footprint"): "footprint",
    ("rviz/LaserScan", "Scan"): "scan",
    ("rviz/Path", "Global plan"): "get_path_server/plan",
    ("rviz/Path", "Local plan"): "follow_path_server/plan",
    ("rviz/Path", "move_base_like plan"): "move_base_like/plan",
    ("rviz/PoseArray", "Particles"): "particlecloud",
    ("rviz/PoseArray", "People"): "pure_pursuit_path/people",  # the controllers' tracked people
    ("rviz/PoseArray", "People (topic follower)"): "pure_pursuit_topic/people",
    ("rviz/PointStamped", "Bumper contacts"): "bumper_hits",  # bumper_relay's contact points
    ("rviz/Marker", "Obstacle class"): "obstacle_class_marker",  # obstacle_classifier's class as a text marker
    # the global costmap's remembered heavy obstacles (footprints and their describe() texts)
    ("rviz/MarkerArray", "Obstacle memory"): "get_path_server/global_costmap/obstacle_memory",
    ("rviz/Odometry", "Odometry"): "odom",
}


def rviz_config(name: str) -> Dict[str, Any]:
    loaded = yaml.safe_load((REPO_ROOT / "rviz" / name).read_text())
    assert isinstance(loaded, dict)
    return loaded


def leaves(displays: List[Dict[str, Any]]) -> Iterator[Dict[str, Any]]:
    for display in displays:
        if display["Class"] == "rviz/Group":
            yield from leaves(display["Displays"])
        else:
            yield display


@pytest.mark.parametrize(("name", "robots"), [("flex_nav.rviz", ["robot1"]),
                                               ("multi_robot.rviz", ["robot1", "robot2", "robot3"])])
def test_displays_and_tools_are_in_the_robots_namespaces(name: str, robots: List[str]) -> None:
    manager = rviz_config(name)["Visualization Manager"]
    assert manager["Global Options"]["Fixed Frame"] == "map"
    shown = [(d["Class"], d["Name"], d.get("Topic") or d.get("Marker Topic") or d.get("Robot Description"),
              d.get("TF Prefix")) for d in leaves(manager["Displays"])]
    expected: List[Tuple[str, str, str, Optional[str]]] = [("rviz/Map", "Map", "/map", None)]
    for ns in robots:
        expected += [(cls, label, f"/{ns}/{topic}", None) for (cls, label), topic in ROBOT_TOPICS.items()]
        expected.append(("rviz/RobotModel", "Robot model", f"{ns}/robot_description", ns))
    assert sorted(s for s in shown if s[0] != "rviz/Grid") == sorted(expected)
    tools = {(t["Class"], t.get("Topic")) for t in manager["Tools"]}
    for ns in robots:
        assert ("rviz/SetGoal", f"/{ns}/move_base_simple/goal") in tools  # the behaviors' default goal_topic
        assert ("rviz/SetInitialPose", f"/{ns}/initialpose") in tools  # the localizer's
    assert {cls for cls, _ in tools} >= {"rviz/Interact", "rviz/MoveCamera", "rviz/Measure"}
