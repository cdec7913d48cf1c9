"""The fused classifier's held-out measurement (tools.perception.evaluate_fused), its pure parts: the lidar scan cast
on a scene's visual-only primitives (geometry of a known box, cylinder, a low object the scan plane misses), and the
scoring (no dataset, no model)."""

from __future__ import annotations

import json
import math
from typing import Iterator, Sequence, Tuple

import numpy as np
import pybullet
import pytest
from pybullet_utils import bullet_client
from unit.perception.shape_synth import box_corners, ranges_of

from flex_nav.exceptions import ConfigError
from flex_nav.perception.fusion import CameraCue, FusionParams
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON, Prediction
from flex_nav.perception.lidar_shape import BOX, NONE, ShapeCue, ShapeParams
from flex_nav.perception.lidar_shape import PERSON as LIDAR_PERSON
from flex_nav_sim.sensors import Lidar
from tools.perception.evaluate_fused import (
    CANDIDATES,
    HALF_WIDTH_M,
    REACH_M,
    VALIDATION,
    Candidate,
    CollidingClient,
    Records,
    camera_cue,
    choose,
    dump_header,
    dumped_cue,
    fused_labels,
    lidar_spec,
    rescore,
    scan_scene,
    scene_record,
    score,
    summary,
)
from tools.perception.render_dataset import SPLITS
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
    (CameraCue(CLEAR, 0.9, 1, 1, CLEAR, 0.9), lidar(BOX), CLEAR, True),  # disagree; the camera's clear stands
    (CameraCue(CLEAR, 0.5, 1, 1, CLEAR, 0.5), lidar(BOX), CLEAR, True),  # an unsure clear too
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


# ------------------------------------------------------------------------------------------ dump and rescore
def dumped_scene(split: str, truth: str, camera: str, confidence: float, ranges: np.ndarray,
                 model: str = "m") -> dict:
    prediction = Prediction(camera, confidence, {camera: confidence})
    return scene_record(split, 0, truth=truth, model=model, distance_m=0.6, prediction=prediction,
                        cue=ShapeCue(NONE, 1.0, "not used by rescore"), ranges=ranges)


def scan_of(polygons: Sequence[np.ndarray] = (), circles: Sequence[Tuple[float, float, float]] = ()) -> np.ndarray:
    """A 360-beam scan (1 degree from -180 degrees) of synthetic shapes, no noise."""
    return ranges_of((0.0, 0.0), np.radians(np.arange(-180.0, 180.0, 1.0)), polygons, circles)


HEADER = {"lidar": {"angle_min": -math.pi, "angle_increment": math.radians(1.0), "range_min": 0.15,
                    "range_max": 12.0}, "reach_m": REACH_M, "half_width_m": HALF_WIDTH_M}
BOX_SCAN = scan_of([box_corners(0.75, 0.0, 0.4, 0.4, 0.3)])  # a 0.4 m box, its corner 0.5 m ahead
BODY_SCAN = scan_of(circles=[(0.75, 0.0, 0.2)])  # a round body (or a drum) 0.55 m ahead


def test_a_scene_record_holds_both_cues_and_the_scan(client: CollidingClient) -> None:
    Scene(client, np.random.default_rng(0)).box((1.0, 0.0, 0.25), (0.2, 0.2, 0.25), GREY)
    lidar = lidar_on(client)
    ranges, cue = scan_scene(lidar)
    record = scene_record("val", 3, truth=MOVABLE, model="box", distance_m=1.0,
                          prediction=Prediction(CLEAR, 0.8, {CLEAR: 0.8, MOVABLE: 0.2}), cue=cue, ranges=ranges)
    record = json.loads(json.dumps(record))  # JSON as written (no NaN, no inf)
    assert (record["split"], record["index"], record["truth"], record["model"]) == ("val", 3, MOVABLE, "box")
    assert record["camera"] == {"label": CLEAR, "confidence": 0.8, "scores": {CLEAR: 0.8, MOVABLE: 0.2}}
    assert cue.features is not None
    assert record["lidar"]["label"] == BOX and record["lidar"]["features"]["points"] == cue.features.points
    assert len(record["ranges_m"]) == 360 and None in record["ranges_m"]
    header = json.loads(json.dumps(dump_header(ShapeParams(), FusionParams())))
    assert dumped_cue(record, header, ShapeParams()) == cue  # the cue recomputed from the dump is the same


def test_rescore_recomputes_the_lidar_cue_per_candidate() -> None:
    dump = {"header": HEADER, "scenes": [
        dumped_scene("val", CLEAR, CLEAR, 0.9, BOX_SCAN, "fridge"),  # a sure clear and a box
        dumped_scene("val", MOVABLE, MOVABLE, 0.9, BODY_SCAN, "drum"),  # a movable drum, round to the lidar
        dumped_scene("val_extra", PERSON, CLEAR, 0.6, BOX_SCAN, "wheelchair"),  # an unsure clear on a person
    ]}
    body_on = ShapeParams(round_body_person=True)
    body_off = ShapeParams(round_body_person=False)
    candidates = [Candidate("always", "", body_on, FusionParams(box_beats_clear="always")),
                  Candidate("unsure", "", body_off, FusionParams(box_beats_clear="unsure")),
                  Candidate("never", "", body_off, FusionParams(box_beats_clear="never"))]
    results = rescore(dump, candidates)
    assert set(results) == {"always", "unsure", "never"} and set(results["never"]) == {"val", "val_extra"}
    for name, (val, val_extra, unsafe) in {"always": (0.0, 0.0, 1), "unsure": (1.0, 0.0, 1),
                                           "never": (1.0, 0.0, 0)}.items():
        assert results[name]["val"]["fused"]["accuracy"] == pytest.approx(val), name
        assert results[name]["val_extra"]["fused"]["accuracy"] == pytest.approx(val_extra), name
        assert results[name]["val_extra"]["fused"]["person_as_movable"] == unsafe, name
        assert results[name]["val"]["camera"]["accuracy"] == pytest.approx(1.0)
    assert results["always"]["val"]["lidar_by_truth"][MOVABLE][LIDAR_PERSON] == 1
    assert results["never"]["val"]["lidar_by_truth"][MOVABLE]["unsure"] == 1


def figures(fused: Tuple[float, ...], unsafe: Tuple[int, ...], asked: int, camera_unsafe: int = 1) -> dict:
    """Per-split results as :func:`score` gives them, for the criterion: fused accuracies, fused people taken for
    movable (the camera alone: 0.9 and ``camera_unsafe`` on each split), looks asked on the first split."""
    return {f"val{i}": {"camera": {"accuracy": 0.9, "person_as_movable": camera_unsafe},
                        "fused": {"accuracy": a, "person_as_movable": u}, "asked_again": asked if i == 0 else 0}
            for i, (a, u) in enumerate(zip(fused, unsafe))}


def test_summary_means_each_split_once_and_names_the_less_safe_ones() -> None:
    s = summary(figures((0.8, 1.0), (1, 2), asked=5))
    assert s["camera_mean"] == pytest.approx(0.9) and s["fused_mean"] == pytest.approx(0.9)
    assert (s["camera_person_as_movable"], s["fused_person_as_movable"]) == (2, 3)
    assert s["less_safe_splits"] == ["val1"] and s["asked_again"] == 5


def test_choose_follows_the_stated_criterion() -> None:
    results = {
        "unsafe_best": figures((1.0, 1.0), (0, 2), asked=0),  # more people for movable on one split: not eligible
        "good": figures((0.95, 0.93), (1, 0), asked=9),
        "good_fewer_looks": figures((0.93, 0.9504), (0, 1), asked=3),  # the same mean at 0.1 point, fewer looks
        "worse": figures((0.9, 0.9), (0, 0), asked=0),
    }
    order = list(results)
    assert choose(results, order) == "good_fewer_looks"
    results["good_fewer_looks"] = figures((0.93, 0.9504), (0, 1), asked=9)  # tie on looks too: the earlier
    assert choose(results, order) == "good"
    assert choose(results, ["unsafe_best", "worse"]) == "worse"
    assert choose({"unsafe_best": results["unsafe_best"]}, ["unsafe_best"]) is None


def test_the_candidates_are_distinct_and_fix_every_switch() -> None:
    names = [c.name for c in CANDIDATES]
    assert len(set(names)) == len(names) == 18
    assert len({(c.shape, c.fusion) for c in CANDIDATES}) == 18
    for candidate in CANDIDATES:  # a candidate's switches are its own, not the current defaults
        assert candidate.fusion.box_beats_clear == {"A": "always", "U": "unsure", "N": "never"}[candidate.name[-1]]
    assert tuple(s for s in SPLITS if s.startswith("val")) == VALIDATION and "val_extra8" in VALIDATION


def test_the_defaults_are_the_candidate_chosen_on_validation() -> None:
    """P5N (models/README.md, issue 28 second round): what the tool, the state and the node run by default."""
    chosen = next(c for c in CANDIDATES if c.name == "P5N")
    assert (chosen.shape, chosen.fusion) == (ShapeParams(), FusionParams())
    first = next(c for c in CANDIDATES if c.name == "P0A")  # the first run's rule
    assert first.shape != ShapeParams() and first.fusion != FusionParams()
