"""The obstacle memory as RViz markers and back (flex_nav.ros.memory_markers): no master needed."""

from __future__ import annotations

import numpy as np
import rospy
from visualization_msgs.msg import Marker, MarkerArray

from flex_nav.nav.costmap.memory_layer import ObstacleMemoryLayer, box_footprint
from flex_nav.ros.memory_markers import (
    FOOTPRINT_NS,
    TEXT_ABOVE_M,
    TEXT_NS,
    memory_markers,
    remembered_of_markers,
)


def two_remembered() -> ObstacleMemoryLayer:
    layer = ObstacleMemoryLayer()
    layer.remember(box_footprint(5.6, 2.1, 0.5, 0.5), 41.2)
    layer.remember(box_footprint(1.0, -3.0, 0.8, 0.4, yaw=0.3), 50.0)
    return layer


def test_deleteall_first_then_a_closed_footprint_and_its_text_per_obstacle() -> None:
    layer = two_remembered()
    msg = memory_markers(layer.obstacles, "map", rospy.Time(12, 5))
    first, *rest = msg.markers
    assert first.action == Marker.DELETEALL and first.header.frame_id == "map"
    assert [(m.ns, m.id, m.type, m.action) for m in rest] == [
        (FOOTPRINT_NS, 1, Marker.LINE_STRIP, Marker.ADD), (TEXT_NS, 1, Marker.TEXT_VIEW_FACING, Marker.ADD),
        (FOOTPRINT_NS, 2, Marker.LINE_STRIP, Marker.ADD), (TEXT_NS, 2, Marker.TEXT_VIEW_FACING, Marker.ADD)]
    assert all(m.header.frame_id == "map" and m.header.stamp == rospy.Time(12, 5) for m in msg.markers)
    line, text = rest[0], rest[1]
    points = np.array([(p.x, p.y) for p in line.points])
    assert len(points) == 5 and np.allclose(points[0], points[-1])  # closed
    assert np.allclose(points[:4], layer.obstacles[0].footprint)
    assert line.scale.x > 0 and line.color.a == 1.0 and line.pose.orientation.w == 1.0
    assert text.text == layer.obstacles[0].describe() == "#1 heavy at (5.60, 2.10) m, 0.50 x 0.50 m, found at 41.2 s"
    assert (text.pose.position.x, text.pose.position.y, text.pose.position.z) == (5.6, 2.1, TEXT_ABOVE_M)
    assert text.scale.z > 0 and text.color.a == 1.0


def test_nothing_remembered_is_one_deleteall() -> None:
    msg = memory_markers((), "map", rospy.Time(1))
    assert [m.action for m in msg.markers] == [Marker.DELETEALL]
    assert remembered_of_markers(msg) == []


def test_read_back_gives_the_footprints_and_texts() -> None:
    layer = two_remembered()
    rows = remembered_of_markers(memory_markers(layer.obstacles, "map", rospy.Time(1)))
    assert [(i, text) for i, _, text in rows] == [(o.obstacle_id, o.describe()) for o in layer.obstacles]
    for (_, footprint, _), obstacle in zip(rows, layer.obstacles):
        assert np.allclose(footprint, obstacle.footprint)


def test_read_back_ignores_other_markers_and_follows_deletes() -> None:
    layer = two_remembered()
    msg = memory_markers(layer.obstacles, "map", rospy.Time(1))
    stray = Marker(ns="other", id=7, type=Marker.LINE_STRIP, action=Marker.ADD)
    stray.points = msg.markers[1].points
    short = Marker(ns=FOOTPRINT_NS, id=9, type=Marker.LINE_STRIP, action=Marker.ADD)
    short.points = msg.markers[1].points[:2]  # no area: dropped
    delete = Marker(ns=FOOTPRINT_NS, id=1, action=Marker.DELETE)
    rows = remembered_of_markers(MarkerArray(markers=[*msg.markers, stray, short, delete]))
    assert [i for i, _, _ in rows] == [2]
    untitled = MarkerArray(markers=[msg.markers[0], msg.markers[1]])  # a footprint without its text
    assert [text for _, _, text in remembered_of_markers(untitled)] == ["#1"]
    again = MarkerArray(markers=[*msg.markers, Marker(action=Marker.DELETEALL)])
    assert remembered_of_markers(again) == []
