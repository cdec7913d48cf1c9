"""ObstacleFusionState: the camera's class and the lidar's shape fused, bounded looks again, the camera-only mode
that behaves as ObstacleClassState."""

from __future__ import annotations

import math
from typing import Optional, Sequence

import genpy
import numpy as np
import pytest
from sensor_msgs.msg import LaserScan
from unit.perception.shape_synth import box_corners, ranges_of
from unit.states.states_testlib import Harness

from flex_nav.exceptions import ConfigError
from flex_nav.msg import ObstacleClass
from flex_nav.testing.state_harness import START_S
from flex_nav_states.obstacle_fusion_state import ObstacleFusionState

STEP_S = 0.05  # [s]
BOX = [box_corners(0.55 + 0.2, 0.0, 0.4, 0.4, math.radians(10.0))]  # a 0.4 m cube 0.55 m ahead
NOTHING: Sequence[np.ndarray] = []


def scan_msg(stamp_s: float, polygons: Sequence[np.ndarray] = (), circles: Sequence = ()) -> LaserScan:
    scan = LaserScan()
    scan.header.stamp = genpy.Time.from_sec(stamp_s)
    scan.angle_min, scan.angle_increment = -math.pi, math.radians(1.0)
    scan.range_min, scan.range_max = 0.1, 12.0
    angles = scan.angle_min + scan.angle_increment * np.arange(360)
    scan.ranges = [float(r) for r in ranges_of((0.0, 0.0), angles, polygons, circles)]
    return scan


def class_msg(label: str, stamp_s: float, confidence: float, frame_label: str = "") -> ObstacleClass:
    msg = ObstacleClass(label=label, frame_label=frame_label or label, votes=4, window=5, confidence=confidence,
                        frame_confidence=confidence)
    msg.header.stamp = genpy.Time.from_sec(stamp_s)
    return msg


def decide(state: ObstacleFusionState, label: Optional[str], confidence: float = 0.9, polygons=BOX,
           circles: Sequence = (), looks: float = 0.0, max_time_s: float = 5.0, frame_label: str = ""):
    """Run the state against a camera showing ``label`` (None: silent) and a lidar seeing the shapes."""
    h = Harness(state, inputs={"looks": looks}).start()
    camera = h.proxies.subscription("obstacle_class", ObstacleClass)
    lidar = h.proxies.subscription("scan", LaserScan)
    end = h.clock.now() + max_time_s
    while h.clock.now() <= end:
        if label is not None:
            camera.inject(class_msg(label, h.clock.now(), confidence, frame_label))
        shapes = polygons(h.clock.now() - START_S) if callable(polygons) else polygons
        lidar.inject(scan_msg(h.clock.now(), shapes, circles))
        if h.tick():
            return h.executor.result(), h
        h.advance(STEP_S)
    raise AssertionError(f"still running: {h.log_text()}")


def test_a_box_the_camera_calls_clear_is_looked_at_again_then_left_clear() -> None:
    result, h = decide(ObstacleFusionState(), "clear")
    assert result.outcome == "look_again" and result.outputs["looks"] == 1.0
    assert "row 4" in result.outputs["obstacle_fusion"] and "lidar box" in result.outputs["obstacle_fusion"]
    result, _ = decide(ObstacleFusionState(), "clear", looks=1.0)
    assert result.outcome == "look_again" and result.outputs["looks"] == 2.0
    result, h = decide(ObstacleFusionState(), "clear", looks=2.0)
    assert result.outcome == "clear" and result.outputs["looks"] == 0.0  # the camera's clear stands (fusion.py)
    assert any("fused clear (row 8" in text for text in h.texts())


def test_an_unsure_camera_looks_again() -> None:
    result, _ = decide(ObstacleFusionState(), "clear", confidence=0.52)
    assert result.outcome == "look_again"
    assert "camera unsure clear 0.52" in result.outputs["obstacle_fusion"]


def test_both_agree_on_a_movable_box() -> None:
    result, _ = decide(ObstacleFusionState(), "movable")
    assert result.outcome == "movable" and result.outputs["looks"] == 0.0


def test_a_static_round_body_on_the_lidar_leaves_the_decision_to_the_camera() -> None:
    # a static round body is unsure to the lidar by default (lidar_shape: a drum or a bin as often as a person)
    body = [(0.55 + 0.25, 0.0, 0.25)]
    result, h = decide(ObstacleFusionState(settle_s=1.0, timeout_s=3.0), "movable", polygons=NOTHING, circles=body)
    assert result.outcome == "movable" and result.outputs["obstacle_fusion"].startswith("fused movable (row 6")
    assert "lidar unsure" in result.outputs["obstacle_fusion"]
    assert h.clock.now() - START_S >= 1.0  # after the camera's settle_s


def test_a_box_shape_that_moves_is_a_person() -> None:
    def cart(t: float) -> list:  # something box-shaped wheeled across the way at 0.4 m/s
        return [box_corners(0.75, -0.2 + 0.4 * t, 0.4, 0.4, 0.0)]

    result, _ = decide(ObstacleFusionState(settle_s=1.0, timeout_s=3.0), "clear", polygons=cart)
    assert result.outcome == "person" and "(moves at 0.3" in result.outputs["obstacle_fusion"], result.outputs
    standing, _ = decide(ObstacleFusionState(settle_s=1.0, timeout_s=3.0, max_looks=0), "clear")
    assert standing.outcome == "clear" and "speed 0.0" in standing.outputs["obstacle_fusion"]  # measured: still


def test_a_person_in_the_cameras_latest_frame_is_a_person() -> None:
    result, _ = decide(ObstacleFusionState(), "movable", frame_label="person")
    assert result.outcome == "person" and "row 1" in result.outputs["obstacle_fusion"]


def test_a_silent_camera_and_a_box_decide_after_the_timeout_and_the_looks() -> None:
    result, _ = decide(ObstacleFusionState(timeout_s=1.0, max_looks=0), None)
    assert result.outcome == "movable"
    result, _ = decide(ObstacleFusionState(timeout_s=1.0, max_looks=0), None, polygons=NOTHING)
    assert result.outcome == "unknown"


def test_no_fresh_scan_is_an_unsure_lidar() -> None:
    h = Harness(ObstacleFusionState(max_looks=0), inputs={"looks": 0.0}).start()
    camera = h.proxies.subscription("obstacle_class", ObstacleClass)
    for _ in range(100):
        camera.inject(class_msg("clear", h.clock.now(), 0.9))
        if h.tick():
            break
        h.advance(STEP_S)
    result = h.executor.result()
    assert result.outcome == "clear" and "no scan on scan" in result.outputs["obstacle_fusion"]


@pytest.mark.parametrize("label", ["person", "movable", "clear"])
def test_camera_only_is_the_class_state(label: str) -> None:
    result, _ = decide(ObstacleFusionState(fuse_lidar=False), label, confidence=0.3)
    assert result.outcome == label and result.outputs["looks"] == 0.0


def test_camera_only_without_a_class_is_unknown_after_the_timeout() -> None:
    result, h = decide(ObstacleFusionState(fuse_lidar=False, timeout_s=1.0), None)
    assert result.outcome == "unknown" and any("no fresh message" in t for t in h.texts())


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"max_looks": 11}, "max_looks"),
    ({"settle_s": 3.0, "timeout_s": 2.0}, "timeout_s"),
    ({"camera_min_confidence": 2.0}, "camera_min_confidence"),
    ({"reach_m": 0.0}, "reach_m"),
    ({"scan_topic": "bad topic"}, "scan_topic"),
])
def test_parameters_are_validated(kwargs: dict, match: str) -> None:
    with pytest.raises(ConfigError, match=match):
        ObstacleFusionState(**kwargs)
