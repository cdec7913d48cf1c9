"""The obstacle classifier's class as an RViz text marker (flex_nav.nodes.obstacle_class_marker): no master needed."""

from __future__ import annotations

import pytest
from visualization_msgs.msg import Marker

from flex_nav.msg import ObstacleClass
from flex_nav.nodes.obstacle_class_marker import (
    ABOVE_M,
    LABEL_COLOURS,
    LIFETIME_S,
    UNKNOWN_COLOUR,
    class_marker,
)


def obstacle_class(label: str, confidence: float, votes: int) -> ObstacleClass:
    msg = ObstacleClass(label=label, confidence=confidence, votes=votes, window=5)
    msg.header.frame_id = "robot1/camera_rgb_optical_frame"
    return msg


def test_text_above_the_robot_in_the_scans_frame() -> None:
    marker = class_marker(obstacle_class("movable", 0.934, 4), "robot1/laser")
    assert marker.type == Marker.TEXT_VIEW_FACING and marker.action == Marker.ADD
    assert marker.text == "movable 0.93 (4/5)"
    assert marker.header.frame_id == "robot1/laser" and marker.header.stamp.is_zero()  # newest transform
    assert marker.pose.position.z == pytest.approx(ABOVE_M) and marker.pose.orientation.w == 1.0
    assert (marker.color.r, marker.color.g, marker.color.b, marker.color.a) == pytest.approx(
        (*LABEL_COLOURS["movable"], 1.0))
    assert marker.lifetime.to_sec() == pytest.approx(LIFETIME_S) and marker.scale.z > 0.0


def test_before_a_scan_the_text_sits_at_the_camera_and_unknown_has_its_colour() -> None:
    marker = class_marker(obstacle_class("unknown", 0.0, 0), None)
    assert marker.header.frame_id == "robot1/camera_rgb_optical_frame"
    assert marker.pose.position.z == 0.0
    assert marker.text == "unknown 0.00 (0/5)"
    assert (marker.color.r, marker.color.g, marker.color.b) == pytest.approx(UNKNOWN_COLOUR)
    person = class_marker(obstacle_class("person", 0.8, 3), "robot1/laser")
    assert (person.color.r, person.color.g, person.color.b) == pytest.approx(LABEL_COLOURS["person"])
