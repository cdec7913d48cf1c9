"""RememberObstacleState: the footprint of the object ahead published for the costmap's obstacle memory."""

from __future__ import annotations

import math

import genpy
import numpy as np
import pytest
from geometry_msgs.msg import PolygonStamped
from sensor_msgs.msg import LaserScan
from unit.perception.shape_synth import box_corners, ranges_of
from unit.states.states_testlib import Harness

from flex_nav.exceptions import ConfigError
from flex_nav_states.remember_obstacle_state import RememberObstacleState


def scan_of_box(stamp_s: float, face_m: float = 0.85) -> LaserScan:
    scan = LaserScan()
    scan.header.stamp = genpy.Time.from_sec(stamp_s)
    scan.header.frame_id = "robot1/base_laser"
    scan.angle_min, scan.angle_increment = -math.pi, math.radians(1.0)
    scan.range_min, scan.range_max = 0.1, 12.0
    angles = scan.angle_min + scan.angle_increment * np.arange(360)
    scan.ranges = [float(r) for r in ranges_of((0.0, 0.0), angles, [box_corners(face_m + 0.25, 0.0, 0.5, 0.5, 0.0)])]
    return scan


def test_the_footprint_of_the_box_ahead_is_published_in_the_scans_frame() -> None:
    h = Harness(RememberObstacleState(), inputs={})
    h.proxies.subscription("scan", LaserScan).inject(scan_of_box(h.clock.now()))
    result = h.start().run(5.0)
    assert result.outcome == "done"
    (msg,) = h.proxies.pub("obstacle_memory/mark").messages
    assert isinstance(msg, PolygonStamped) and msg.header.frame_id == "robot1/base_laser"
    xs = [p.x for p in msg.polygon.points]
    ys = [p.y for p in msg.polygon.points]
    assert abs(min(xs) - 0.85) < 0.02 and max(xs) > 1.3 and min(ys) < -0.22 and max(ys) > 0.22
    assert len(result.outputs["obstacle_footprint"]) == len(xs)
    assert "obstacle cannot be pushed: planning around it" in h.texts()


def test_without_a_fresh_scan_or_an_object_nothing_is_published_and_it_goes_on() -> None:
    h = Harness(RememberObstacleState(scan_max_age_s=0.5), inputs={})
    h.proxies.subscription("scan", LaserScan).inject(scan_of_box(h.clock.now() - 2.0))
    assert h.start().run(5.0).outcome == "done"
    assert h.proxies.pub("obstacle_memory/mark").messages == []
    assert any("no scan on scan" in t for t in h.texts())
    far = Harness(RememberObstacleState(reach_m=0.5), inputs={})
    far.proxies.subscription("scan", LaserScan).inject(scan_of_box(far.clock.now()))
    assert far.start().run(5.0).outputs["obstacle_footprint"] == []
    assert any("nothing within 0.5 m ahead" in t for t in far.texts())


def test_publish_off_is_a_log_state() -> None:
    h = Harness(RememberObstacleState(publish=False), inputs={})
    result = h.start().run(5.0)
    assert result.outcome == "done" and result.outputs["obstacle_footprint"] == []
    assert h.texts() == ["obstacle cannot be pushed: planning around it"]


@pytest.mark.parametrize(("kwargs", "match"), [({"reach_m": 0.0}, "reach_m"), ({"depth_m": -1.0}, "depth_m"),
                                              ({"topic": "a b"}, "topic")])
def test_parameters_are_validated(kwargs: dict, match: str) -> None:
    with pytest.raises(ConfigError, match=match):
        RememberObstacleState(**kwargs)
