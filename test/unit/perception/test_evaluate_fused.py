"""The fused classifier's held-out measurement (tools.perception.evaluate_fused), its pure parts: the lidar scan cast
on a scene's visual-only primitives (geometry of a known box, cylinder, a low object the scan plane misses), and the
scoring (no dataset, no model)."""

from __future__ import annotations

import math
from typing import Iterator, Tuple

import numpy as np
import pybullet
import pytest
from pybullet_utils import bullet_client

from flex_nav.exceptions import ConfigError
from flex_nav.perception.fusion import CameraCue, FusionParams
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON, Prediction
from flex_nav.perception.lidar_shape import BOX, NONE, ShapeCue
from flex_nav.perception.lidar_shape import PERSON as LIDAR_PERSON
from flex_nav_sim.sensors import Lidar
from tools.perception.evaluate_fused import (
    CollidingClient,
    Records,
    camera_cue,
    fused_labels,
    lidar_spec,
    scan_scene,
    score,
)
from tools.perception.scene_base import Scene

GREY = (0.5, 0.5, 0.5, 1.0)


@pytest.fixture
def client() -> Iterator[CollidingClient]:
    raw = bullet_client.BulletClient(connection_mode=pybullet.DIRECT)
    try:
        yield CollidingClient(raw)
    finally:
        raw.disconnect()


def lidar_on(client: object, seed: int = 0) -> Lidar:
    spec, radius = lidar_spec()
    return Lidar(client, spec, radius, np.random.default_rng(seed))


def hits_ahead(ranges: np.ndarray, lidar: Lidar) -> Tuple[np.ndarray, np.ndarray]:
    """(bearings [rad], ranges [m]) of the beams with a return."""
    angles = lidar.spec.beam_angles()
    finite = np.isfinite(ranges)
    return angles[finite], ranges[finite].astype(np.float64)


def test_the_lidar_is_the_turtlebot4s() -> None:
    spec, radius = lidar_spec()
    assert spec.beam_count == 360
    assert spec.mount == pytest.approx((-0.04, 0.0, 0.20))
    assert math.degrees(spec.angle_increment) == pytest.approx(1.0)
    assert radius == pytest.approx(0.171)


def test_a_known_box_face_is_where_the_geometry_puts_it(client: CollidingClient) -> None:
    sc = Scene(client, np.random.default_rng(0))
    sc.box((1.0, 0.0, 0.25), (0.2, 0.2, 0.25), GREY)  # face at x = 0.8 m, 0.4 m wide, 0.5 m high
    lidar = lidar_on(client)
    ranges, cue = scan_scene(lidar)
    bearings, r = hits_ahead(ranges, lidar)
    lidar_x = lidar.spec.mount[0]
    # every return lies on the face x = 0.8 m, |y| <= 0.2 m (within 4 noise sigmas of its range)
    x = lidar_x + r * np.cos(bearings)
    y = r * np.sin(bearings)
    sigma = lidar.spec.noise_std + lidar.spec.noise_fraction * r
    assert np.all(np.abs(x - 0.8) <= 4.0 * sigma * np.abs(np.cos(bearings)) + 1e-6)
    assert np.all(np.abs(y) <= 0.2 + 0.01)
    half_angle = math.degrees(math.atan2(0.2, 0.8 - lidar_x))  # 13.4 deg: beams at -13 .. 13 deg
    assert len(bearings) == 2 * math.floor(half_angle) + 1
    assert cue.label == BOX, cue.describe()


def test_a_cylinder_is_hit_at_its_radius(client: CollidingClient) -> None:
    sc = Scene(client, np.random.default_rng(0))
    sc.cylinder((1.0, 0.5, 0.4), 0.15, 0.8, GREY)
    lidar = lidar_on(client)
    ranges, _ = scan_scene(lidar)
    bearings, r = hits_ahead(ranges, lidar)
    cx, cy = 1.0 - lidar.spec.mount[0], 0.5  # the centre in the lidar's frame
    distance = np.hypot(r * np.cos(bearings) - cx, r * np.sin(bearings) - cy)
    assert len(r) >= 5
    assert np.all(np.abs(distance - 0.15) < 0.02)


def test_an_object_below_the_scan_plane_gives_none(client: CollidingClient) -> None:
    sc = Scene(client, np.random.default_rng(0))
    sc.box((0.7, 0.0, 0.05), (0.3, 0.3, 0.05), GREY)  # 0.1 m high, the scan plane at 0.2 m
    ranges, cue = scan_scene(lidar_on(client))
    assert not np.isfinite(ranges).any()
    assert cue.label == NONE


def test_without_the_wrapper_visual_only_bodies_are_not_hit() -> None:
    raw = bullet_client.BulletClient(connection_mode=pybullet.DIRECT)
    try:
        Scene(raw, np.random.default_rng(0)).box((1.0, 0.0, 0.25), (0.2, 0.2, 0.25), GREY)
        ranges, _ = scan_scene(lidar_on(raw))
        assert not np.isfinite(ranges).any()
    finally:
        raw.disconnect()


def test_the_wrapper_does_not_change_the_camera_image(client: CollidingClient) -> None:
    raw = bullet_client.BulletClient(connection_mode=pybullet.DIRECT)
    try:
        images = []
        for c in (raw, client):
            sc = Scene(c, np.random.default_rng(3))
            sc.floor((0.7, 0.7, 0.7, 1.0))
            sc.box((1.0, 0.1, 0.2), (0.2, 0.15, 0.2), (0.8, 0.5, 0.2, 1.0), yaw=0.4)
            sc.capsule((1.4, -0.3, 0.6), 0.1, 0.8, (0.2, 0.3, 0.7, 1.0))
            view = c.computeViewMatrix([0.0, 0.0, 0.25], [1.0, 0.0, 0.2], [0.0, 0.0, 1.0])
            projection = c.computeProjectionMatrixFOV(50.0, 4.0 / 3.0, 0.05, 20.0)
            _, _, rgba, _, _ = c.getCameraImage(64, 48, view, projection, renderer=pybullet.ER_TINY_RENDERER)
            images.append(np.asarray(rgba, dtype=np.uint8))
        np.testing.assert_array_equal(images[0], images[1])
    finally:
        raw.disconnect()


def test_reset_forgets_the_shapes(client: CollidingClient) -> None:
    Scene(client, np.random.default_rng(0)).box((1.0, 0.0, 0.25), (0.2, 0.2, 0.25), GREY)
    client.resetSimulation()
    ranges, cue = scan_scene(lidar_on(client))
    assert not np.isfinite(ranges).any() and cue.label == NONE


# ------------------------------------------------------------------------------------------ scoring
def lidar(label: str, confidence: float = 0.9) -> ShapeCue:
    return ShapeCue(label, confidence, "test")


def test_camera_cue_is_one_frame_window() -> None:
    cue = camera_cue(Prediction(MOVABLE, 0.8, {MOVABLE: 0.8, PERSON: 0.1, CLEAR: 0.1}))
    assert cue == CameraCue(MOVABLE, 0.8, 1, 1, MOVABLE, 0.8)


@pytest.mark.parametrize("camera, shape, final, asked", [
    (CameraCue(CLEAR, 0.9, 1, 1, CLEAR, 0.9), lidar(BOX), MOVABLE, True),  # disagree; the box wins at the end
    (CameraCue(MOVABLE, 0.9, 1, 1, MOVABLE, 0.9), lidar(NONE), MOVABLE, True),  # nothing at lidar height
    (CameraCue(CLEAR, 0.5, 1, 1, CLEAR, 0.5), lidar(NONE), CLEAR, True),  # unsure camera, no box
    (CameraCue(PERSON, 0.9, 1, 1, PERSON, 0.9), lidar(BOX), PERSON, False),
    (CameraCue(MOVABLE, 0.9, 1, 1, MOVABLE, 0.9), lidar(LIDAR_PERSON, 0.5), PERSON, False),
    (CameraCue(MOVABLE, 0.9, 1, 1, MOVABLE, 0.9), lidar(BOX), MOVABLE, False),
])
def test_fused_labels_score_the_final_answer(camera: CameraCue, shape: ShapeCue, final: str, asked: bool) -> None:
    assert fused_labels(camera, shape, FusionParams()) == (final, asked)


def test_score_counts_accuracy_and_people_taken_for_movable() -> None:
    records = Records()
    rows = [  # truth, camera, fused, lidar, model, asked again
        (PERSON, PERSON, PERSON, LIDAR_PERSON, "walker", False),
        (PERSON, MOVABLE, PERSON, LIDAR_PERSON, "walker", False),  # the lidar saves it
        (PERSON, CLEAR, MOVABLE, BOX, "sitter", True),  # fused: unsafe
        (MOVABLE, MOVABLE, MOVABLE, BOX, "box", False),
        (CLEAR, CLEAR, MOVABLE, BOX, "pillar", True),
        (CLEAR, CLEAR, CLEAR, NONE, "table", False),
    ]
    for truth, cam, fused, cue, model, asked in rows:
        records.add(truth, cam, fused, cue, model=model, asked_again=asked)
    result = score(records)
    assert result["camera"]["accuracy"] == pytest.approx(round(4 / 6, 4))
    assert result["fused"]["accuracy"] == pytest.approx(round(4 / 6, 4))
    assert result["camera"]["person_as_movable"] == 1
    assert result["fused"]["person_as_movable"] == 1
    assert result["fused"]["per_model_accuracy"] == {"box": 1.0, "pillar": 0.0, "sitter": 0.0, "table": 1.0,
                                                     "walker": 1.0}
    assert result["lidar_by_truth"][PERSON] == {BOX: 1, LIDAR_PERSON: 2, "unsure": 0, NONE: 0}
    assert result["asked_again"] == 2
    assert result["per_model"]["sitter"] == {"fused": {PERSON: 0, MOVABLE: 1, CLEAR: 0},
                                             "lidar": {BOX: 1, LIDAR_PERSON: 0, "unsure": 0, NONE: 0}}


def test_bad_labels_and_empty_records_are_refused() -> None:
    with pytest.raises(ConfigError, match="'chair'"):
        Records().add(CLEAR, "chair", CLEAR, NONE, model="m", asked_again=False)
    with pytest.raises(ConfigError, match="lidar label 'leg'"):
        Records().add(CLEAR, CLEAR, CLEAR, "leg", model="m", asked_again=False)
    with pytest.raises(ConfigError, match="no scenes"):
        score(Records())


def test_the_wrapper_takes_keywords_too(client: CollidingClient) -> None:
    visual = client.createVisualShape(pybullet.GEOM_SPHERE, radius=0.2, rgbaColor=list(GREY))
    client.createMultiBody(baseMass=0.0, baseVisualShapeIndex=visual, basePosition=[1.0, 0.0, 0.2])
    ranges, _ = scan_scene(lidar_on(client))
    assert np.isfinite(ranges).sum() >= 5


def test_score_slices_the_near_scenes() -> None:
    records = Records()
    records.add(CLEAR, CLEAR, MOVABLE, BOX, model="fridge", asked_again=True, distance_m=0.8)  # near, fused wrong
    records.add(PERSON, CLEAR, MOVABLE, BOX, model="sleeper", asked_again=True, distance_m=1.0)  # near, unsafe
    records.add(MOVABLE, MOVABLE, MOVABLE, NONE, model="box", asked_again=True, distance_m=1.5)  # far
    records.add(CLEAR, CLEAR, CLEAR, NONE, model="empty", asked_again=False, distance_m=0.0)  # empty: left out
    near = score(records, near_m=1.0)["near"]
    assert near["samples"] == 2
    assert near["camera"] == pytest.approx(0.5)
    assert near["fused"] == pytest.approx(0.0)
    assert (near["camera_person_as_movable"], near["fused_person_as_movable"]) == (0, 1)
