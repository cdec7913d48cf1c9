"""The robots' URDFs: generated from the profiles, committed up to date, matching the simulator's frames."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import List

import pytest

from flex_nav_sim.profiles import available_profiles, load_profile
from flex_nav_sim.urdf import robot_urdf

REPO_ROOT = Path(__file__).resolve().parents[3]


def test_every_profile_has_a_committed_urdf_as_generated() -> None:
    # tools/gen_urdf.py writes these files; a profile changed without regenerating them fails here
    assert available_profiles() == ["create2", "kobuki", "turtlebot4"]
    for name in available_profiles():
        path = REPO_ROOT / "urdf" / f"{name}.urdf"
        assert path.read_text() == robot_urdf(load_profile(name)), f"{path} is stale: run tools/gen_urdf.py"


@pytest.mark.parametrize("name", ["create2", "kobuki", "turtlebot4"])
def test_links_and_joints_are_the_simulators_frames(name: str) -> None:
    profile = load_profile(name)
    robot = ET.fromstring(robot_urdf(profile))
    assert robot.get("name") == name
    links = [link.get("name") for link in robot.findall("link")]
    assert links[0] == "base_footprint" and {"base_link", "laser"} <= set(links)
    assert ("camera_rgb_frame" in links) is (profile.camera is not None)
    joints = {attribute(joint, "child", "link"): joint for joint in robot.findall("joint")}
    assert set(joints) == set(links) - {"base_footprint"}
    for joint in joints.values():  # a tree of fixed joints from base_footprint, as the static transforms
        assert joint.get("type") == "fixed" and attribute(joint, "parent", "link") == "base_footprint"

    def origin(child: str) -> List[float]:
        return numbers(joints[child], "origin", "xyz") + numbers(joints[child], "origin", "rpy")

    assert origin("laser") == pytest.approx([*profile.lidar.mount, 0.0, 0.0, 0.0], abs=1e-4)
    assert origin("base_link") == pytest.approx([0.0, 0.0, profile.drive.wheel_radius, 0.0, 0.0, 0.0], abs=1e-4)
    if profile.camera is not None:
        assert origin("camera_rgb_frame") == pytest.approx([*profile.camera.mount, 0.0, profile.camera.pitch, 0.0],
                                                           abs=1e-4)
    body = "link[@name='base_link']/visual"
    assert numbers(robot, f"{body}/geometry/cylinder", "radius") == pytest.approx([profile.base.radius])
    assert numbers(robot, f"{body}/geometry/cylinder", "length") == pytest.approx([profile.base.height])
    bottom = numbers(robot, f"{body}/origin", "xyz")[2] - profile.base.height / 2.0 + profile.drive.wheel_radius
    assert math.isclose(bottom, 0.0, abs_tol=1e-4)  # the body stands on the floor


def attribute(element: ET.Element, path: str, name: str) -> str:
    """The attribute ``name`` of the element at ``path`` below ``element`` (a missing one fails the test)."""
    found = element.find(path)
    assert found is not None, f"no {path}"
    value = found.get(name)
    assert value is not None, f"{path} has no {name}"
    return value


def numbers(element: ET.Element, path: str, name: str) -> List[float]:
    return [float(v) for v in attribute(element, path, name).split()]
