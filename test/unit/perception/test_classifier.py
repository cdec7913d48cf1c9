"""ObstacleClassifier: metadata validation, a tiny known graph, and the shipped model on fresh simulator images."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml
from unit.perception.onnx_builder import mean_colour_classifier

from flex_nav.exceptions import ConfigError
from flex_nav.perception.classifier import DEFAULT_MODEL, ObstacleClassifier, load_metadata, metadata_path_for
from flex_nav.perception.image import to_rgb
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from flex_nav.perception.roi import Roi
from flex_nav_sim.readings import ImageReading
from flex_nav_sim.simulation import SensorOptions, Simulation
from flex_nav_sim.world import load_world

META = {
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
def sim_images(tmp_path_factory: pytest.TempPathFactory) -> dict[str, np.ndarray]:
    world_file = tmp_path_factory.mktemp("world") / "classifier_check.yaml"
    world_file.write_text(WORLD)
    images: dict[str, np.ndarray] = {}
    options = SensorOptions(odometry=False, lidar=False, bumpers=False, camera=True)
    with Simulation(load_world(world_file), seed=1, sensors=options) as sim:
        for reading in sim.step():
            if isinstance(reading, ImageReading):
                images[reading.robot] = reading.rgb
    return images


def test_shipped_model_is_small_and_described() -> None:
    assert DEFAULT_MODEL.is_file()
    assert DEFAULT_MODEL.stat().st_size < 2 * 1024 * 1024
    clf = ObstacleClassifier()
    assert clf.metadata.classes == (PERSON, MOVABLE, CLEAR)
    assert clf.roles == (PERSON, MOVABLE, "ignore")


@pytest.mark.parametrize("robot", sorted(EXPECTED))
def test_shipped_model_on_fresh_simulator_images(sim_images: dict[str, np.ndarray], robot: str) -> None:
    prediction = ObstacleClassifier().classify(sim_images[robot])
    assert prediction.label == EXPECTED[robot], f"{robot}: {prediction}"
    assert prediction.confidence > 0.5


def test_shipped_model_reads_bgr_through_the_image_path(sim_images: dict[str, np.ndarray]) -> None:
    rgb = sim_images["sees_person_tb4"]
    bgr_bytes = np.ascontiguousarray(rgb[:, :, ::-1]).tobytes()
    again = to_rgb(bgr_bytes, rgb.shape[1], rgb.shape[0], "bgr8")
    assert ObstacleClassifier().classify(again).label == PERSON
