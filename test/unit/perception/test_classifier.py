"""ObstacleClassifier: metadata validation, a tiny known graph, and the shipped model on fresh simulator images."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict

import numpy as np
import pytest
import yaml
from unit.perception.onnx_builder import mean_colour_classifier

from flex_nav.exceptions import ConfigError
from flex_nav.perception.classifier import (
    DEFAULT_MODEL,
    MODELS_DIR,
    ObstacleClassifier,
    load_metadata,
    metadata_path_for,
)
from flex_nav.perception.image import to_depth, to_rgb
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from flex_nav.perception.roi import Roi
from flex_nav_sim.readings import ImageReading
from flex_nav_sim.simulation import SensorOptions, Simulation
from flex_nav_sim.world import load_world

META: Dict[str, Any] = {
    "format": "flex_nav_obstacle_classifier/1",
    "input": {"width": 8, "height": 8, "mean": [0.0, 0.0, 0.0], "std": [1.0, 1.0, 1.0]},
    "output": "probabilities",
    "classes": ["legs", "carton", "background"],
}


def _tiny(tmp_path: Path, meta: dict | None = None, softmax: bool = True) -> Path:
    """A classifier whose score k is 10 x the mean of colour channel k (red -> legs, green -> carton, blue -> bg)."""
    model = mean_colour_classifier(tmp_path / "tiny.onnx", 10.0 * np.eye(3), softmax=softmax)
    metadata_path_for(model).write_text(yaml.safe_dump(meta or META))
    return model


def _colour(rgb: tuple[int, int, int]) -> np.ndarray:
    img = np.zeros((240, 320, 3), np.uint8)
    img[:, 64:256] = rgb  # only the default roi is coloured; the borders stay black
    return img


def test_tiny_classifier_maps_classes_to_labels(tmp_path: Path) -> None:
    clf = ObstacleClassifier(_tiny(tmp_path), class_map={"legs": PERSON, "carton": MOVABLE, "background": "ignore"})
    assert clf.roles == (PERSON, MOVABLE, "ignore")
    red = clf.classify(_colour((255, 0, 0)))
    assert red.label == PERSON
    assert red.confidence == pytest.approx(np.exp(10) / (np.exp(10) + 2), rel=1e-4)
    assert clf.classify(_colour((0, 255, 0))).label == MOVABLE
    assert clf.classify(_colour((0, 0, 255))).label == CLEAR


def test_roi_override_changes_what_is_seen(tmp_path: Path) -> None:
    img = np.zeros((240, 320, 3), np.uint8)
    img[:, :160] = (255, 0, 0)
    img[:, 160:] = (0, 255, 0)
    class_map = {"legs": PERSON, "carton": MOVABLE}
    assert ObstacleClassifier(_tiny(tmp_path), roi=Roi(0.0, 0.0, 0.4, 1.0), class_map=class_map).classify(
        img).label == PERSON
    assert ObstacleClassifier(_tiny(tmp_path), roi=Roi(0.6, 0.0, 1.0, 1.0), class_map=class_map).classify(
        img).label == MOVABLE


def test_logits_output_gets_a_softmax(tmp_path: Path) -> None:
    meta = dict(META, output="logits")
    clf = ObstacleClassifier(_tiny(tmp_path, meta, softmax=False), class_map={"carton": MOVABLE})
    prediction = clf.classify(_colour((0, 255, 0)))
    assert prediction.label == MOVABLE
    assert sum(prediction.scores.values()) == pytest.approx(1.0)


@pytest.mark.parametrize(
    ("change", "needle"),
    [
        ({"format": "other/2"}, "field format = 'other/2'"),
        ({"input": {"width": 8, "height": 8, "mean": [0.0, 0.0], "std": [1.0, 1.0, 1.0]}}, "field input.mean"),
        ({"input": {"width": 2, "height": 8, "mean": [0, 0, 0], "std": [1, 1, 1]}}, "field input.width = 2"),
        ({"input": {"width": 8, "height": 8, "mean": [0, 0, 0], "std": [1, 0, 1]}}, "field input: std"),
        ({"output": "boxes"}, "field output 'boxes' is not valid (valid: probabilities, logits)"),
        ({"classes": ["only"]}, "field classes = ['only']"),
        ({"classes": None}, "field classes = None"),
        ({"roi": [0.5, 0, 0.4, 1]}, "field roi: roi"),
    ],
)
def test_bad_metadata_names_the_field(tmp_path: Path, change: dict, needle: str) -> None:
    path = tmp_path / "m.yaml"
    path.write_text(yaml.safe_dump({**META, **change}))
    with pytest.raises(ConfigError) as err:
        load_metadata(path)
    assert needle in str(err.value)
    assert str(path) in str(err.value)


def test_missing_field_and_files_are_named(tmp_path: Path) -> None:
    meta = {k: v for k, v in META.items() if k != "classes"}
    (tmp_path / "m.yaml").write_text(yaml.safe_dump(meta))
    with pytest.raises(ConfigError, match="field classes is missing"):
        load_metadata(tmp_path / "m.yaml")
    with pytest.raises(ConfigError, match="does not exist"):
        ObstacleClassifier(tmp_path / "none.onnx")
    model = _tiny(tmp_path)
    with pytest.raises(ConfigError, match="outputs 3 scores but its metadata lists 4 classes"):
        ObstacleClassifier(model, metadata=_write(tmp_path, dict(META, classes=["a", "b", "c", "d"])))
    with pytest.raises(ConfigError, match="takes 8x8 images but its metadata"):
        ObstacleClassifier(model, metadata=_write(tmp_path, dict(META, input=dict(META["input"], width=16))))


# -- RGB-D: a fourth input channel from the registered depth image ----------------------------------------
DEPTH_META = dict(META, input=dict(META["input"], depth={"max_range": 4.0, "mean": 1.0, "std": 0.1}))


def _tiny_rgbd(tmp_path: Path) -> Path:
    """Scores: legs = 10 x mean red, carton = -1 x mean depth channel = 10 - 2.5 x depth [m] (near -> high),
    background = 10 x mean blue."""
    weights = np.zeros((4, 3), np.float32)
    weights[0, 0] = 10.0
    weights[3, 1] = -1.0
    weights[2, 2] = 10.0
    model = mean_colour_classifier(tmp_path / "rgbd.onnx", weights)
    metadata_path_for(model).write_text(yaml.safe_dump(DEPTH_META))
    return model


def test_rgbd_model_reads_the_depth_channel(tmp_path: Path) -> None:
    clf = ObstacleClassifier(_tiny_rgbd(tmp_path), class_map={"legs": PERSON, "carton": MOVABLE})
    assert clf.uses_depth and clf.metadata.channels == 4 and "RGB-D" in clf.description
    grey = np.full((240, 320, 3), (0, 0, 60), np.uint8)  # background score 10 x 60 / 255
    depth = np.zeros((120, 160), np.float32)  # half the colour resolution: the ROI is taken by fractions
    depth[:, 32:128] = 0.2  # [m] inside the default ROI (x 0.2-0.8); outside: 0 = no return
    probabilities = clf.probabilities(clf.input_tensor(grey, depth))[0]
    scores = np.array([0.0, -(0.2 / 4.0 - 1.0) / 0.1, 10.0 * 60.0 / 255.0])
    assert probabilities == pytest.approx(np.exp(scores) / np.exp(scores).sum(), rel=1e-4)
    assert clf.classify(grey, depth).label == MOVABLE
    depth[:, 32:128] = 0.0  # no return counts as max_range: carton score 0
    assert clf.classify(grey, depth).label == CLEAR
    depth[:, 32:128] = np.inf  # REP 118's "nothing in range": the same
    assert clf.classify(grey, depth).label == CLEAR
    depth[:, 32:128] = 9.0  # beyond max_range: clipped to it
    assert clf.probabilities(clf.input_tensor(grey, depth))[0][1] == pytest.approx(
        1.0 / (2.0 + np.exp(scores[2])), rel=1e-4)
    with pytest.raises(ConfigError, match="a depth image is needed with every frame"):
        clf.classify(grey)


def test_rgbd_metadata_and_model_must_agree(tmp_path: Path) -> None:
    rgb_model = _tiny(tmp_path)
    with pytest.raises(ConfigError, match=r"N x 4 x H x W \(RGB \+ depth\) expected"):
        ObstacleClassifier(rgb_model, metadata=_write(tmp_path, DEPTH_META))
    with pytest.raises(ConfigError, match=r"N x 3 x H x W \(RGB\) expected"):
        ObstacleClassifier(_tiny_rgbd(tmp_path), metadata=_write(tmp_path, META))


@pytest.mark.parametrize(
    ("depth", "needle"),
    [
        ({"max_range": 4.0, "mean": 0.5}, "must map exactly max_range, mean, std"),
        ({"max_range": "far", "mean": 0.5, "std": 0.25}, "field input.depth.max_range = 'far' must be a number"),
        ({"max_range": -1.0, "mean": 0.5, "std": 0.25}, "depth max_range -1.0 must be a finite number of metres"),
        ({"max_range": 4.0, "mean": 0.5, "std": 0.0}, "depth std 0.0 must be finite and > 0"),
        ([4.0, 0.5, 0.25], "field input.depth = [4.0, 0.5, 0.25]"),
    ],
)
def test_bad_depth_metadata_names_the_field(tmp_path: Path, depth: object, needle: str) -> None:
    path = _write(tmp_path, dict(META, input=dict(META["input"], depth=depth)))
    with pytest.raises(ConfigError) as err:
        load_metadata(path)
    assert needle in str(err.value) and str(path) in str(err.value)


def _write(tmp_path: Path, meta: dict) -> Path:
    path = tmp_path / "other.yaml"
    path.write_text(yaml.safe_dump(meta))
    return path


# -- the shipped model on images rendered now by the simulator ------------------------------------------
WORLD = """
name: classifier_check
description: robots facing a person, a box or nothing, far enough apart not to see each other's targets
map: {resolution: 0.1, min_height: 0.12, padding: 0.5}
defaults: {wall_height: 0.8, wall_thickness: 0.1}
rooms:
  - {name: hall, min: [0.0, 0.0], max: [20.0, 24.0]}
boxes:
  - {name: light_box, size: [0.3, 0.3, 0.3], mass: 0.5, pose: [3.0, 10.0, 20]}
  - {name: heavy_box, size: [0.6, 0.6, 0.6], mass: 30.0, pose: [3.3, 14.0, 0]}
  - {name: blue_crate, size: [0.5, 0.4, 0.35], mass: 2.0, pose: [3.1, 22.0, 40], color: [0.3, 0.45, 0.75, 1.0]}
people:
  - {name: visitor, pose: [3.1, 2.0, 180]}
  - {name: nurse, pose: [3.3, 6.0, 90], color: [0.2, 0.5, 0.5, 1.0]}
robots:
  - {name: sees_person_tb4, profile: turtlebot4, pose: [2.0, 2.0, 0]}
  - {name: sees_person_kobuki, profile: kobuki, pose: [2.0, 6.0, 0]}
  - {name: sees_box_tb4, profile: turtlebot4, pose: [2.0, 10.0, 0]}
  - {name: sees_box_create, profile: create2, pose: [2.0, 14.0, 0]}
  - {name: sees_crate_tb4, profile: turtlebot4, pose: [2.0, 22.0, 0]}
  - {name: sees_floor_tb4, profile: turtlebot4, pose: [2.0, 18.0, 0]}
  - {name: sees_wall_kobuki, profile: kobuki, pose: [18.6, 10.0, 0]}
"""
EXPECTED = {
    "sees_person_tb4": PERSON,
    "sees_person_kobuki": PERSON,
    "sees_box_tb4": MOVABLE,
    "sees_box_create": MOVABLE,
    "sees_crate_tb4": MOVABLE,
    "sees_floor_tb4": CLEAR,
    "sees_wall_kobuki": CLEAR,
}


@pytest.fixture(scope="module")
def sim_images(tmp_path_factory: pytest.TempPathFactory) -> dict[str, ImageReading]:
    world_file = tmp_path_factory.mktemp("world") / "classifier_check.yaml"
    world_file.write_text(WORLD)
    images: dict[str, ImageReading] = {}
    options = SensorOptions(odometry=False, lidar=False, bumpers=False, camera=True)
    with Simulation(load_world(world_file), seed=1, sensors=options) as sim:
        for reading in sim.step():
            if isinstance(reading, ImageReading):
                images[reading.robot] = reading
    return images


RGB_MODEL = MODELS_DIR / "obstacle_classifier_rgb.onnx"  # the colour-only model, for cameras without depth


@pytest.mark.parametrize(("model", "uses_depth"), [(DEFAULT_MODEL, True), (RGB_MODEL, False)])
def test_shipped_models_are_small_and_described(model: Path, uses_depth: bool) -> None:
    assert model.is_file()
    assert model.stat().st_size < 2 * 1024 * 1024
    clf = ObstacleClassifier(model)
    assert clf.metadata.classes == (PERSON, MOVABLE, CLEAR)
    assert clf.roles == (PERSON, MOVABLE, "ignore")
    assert clf.uses_depth is uses_depth


@pytest.mark.parametrize("robot", sorted(EXPECTED))
def test_shipped_model_on_fresh_simulator_images(sim_images: dict[str, ImageReading], robot: str) -> None:
    frame = sim_images[robot]
    prediction = ObstacleClassifier().classify(frame.rgb, frame.depth)
    assert prediction.label == EXPECTED[robot], f"{robot}: {prediction}"
    assert prediction.confidence > 0.5


@pytest.mark.parametrize("robot", sorted(EXPECTED))
def test_colour_only_model_on_fresh_simulator_images(sim_images: dict[str, ImageReading], robot: str) -> None:
    prediction = ObstacleClassifier(RGB_MODEL).classify(sim_images[robot].rgb)
    assert prediction.label == EXPECTED[robot], f"{robot}: {prediction}"


def test_shipped_model_reads_bgr_and_millimetres_through_the_image_path(sim_images: dict[str, ImageReading]) -> None:
    frame = sim_images["sees_person_tb4"]
    rgb = frame.rgb
    bgr_bytes = np.ascontiguousarray(rgb[:, :, ::-1]).tobytes()
    again = to_rgb(bgr_bytes, rgb.shape[1], rgb.shape[0], "bgr8")
    millimetres = np.where(np.isfinite(frame.depth), np.round(frame.depth * 1000.0), 0).astype(np.uint16)
    depth = to_depth(millimetres.tobytes(), rgb.shape[1], rgb.shape[0], "16UC1")
    assert ObstacleClassifier().classify(again, depth).label == PERSON
