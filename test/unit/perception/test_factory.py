"""PerceptionConfig validation and building either model kind from it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from unit.perception.onnx_builder import constant_output_model

from flex_nav.exceptions import ConfigError
from flex_nav.perception.classifier import ObstacleClassifier
from flex_nav.perception.factory import PerceptionConfig, as_names, build
from flex_nav.perception.labels import PERSON
from flex_nav.perception.roi import Roi
from flex_nav.perception.yolo import YoloObstacleDetector


def test_default_config_builds_the_shipped_classifier() -> None:
    clf = build(PerceptionConfig())
    assert isinstance(clf, ObstacleClassifier)
    assert "obstacle_classifier.onnx" in clf.description


def test_roi_override_reaches_the_classifier() -> None:
    clf = build(PerceptionConfig(roi=Roi(0.1, 0.2, 0.9, 0.8)))
    assert isinstance(clf, ObstacleClassifier) and clf.roi == Roi(0.1, 0.2, 0.9, 0.8)


def test_yolo_config_builds_a_detector(tmp_path: Path) -> None:
    out = np.zeros((1, 6, 10), np.float32)
    out[0, :4, 0] = (32, 32, 20, 40)
    out[0, 4, 0] = 0.7
    path = constant_output_model(tmp_path / "y.onnx", out)
    det = build(PerceptionConfig(model_type="yolo", model=str(path), class_names=("legs", "box"),
                                 class_map={"legs": PERSON, "box": "movable"}, conf_threshold=0.5))
    assert isinstance(det, YoloObstacleDetector)
    assert det.classify(np.zeros((240, 320, 3), np.uint8)).label == PERSON
    assert "person: legs" in det.description and "movable: box" in det.description


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"model_type": "ssd"}, "model_type 'ssd' is not valid (valid: classifier, yolo)"),
        ({"model_type": "yolo"}, "model must be set"),
        ({"yolo_layout": "v5"}, "yolo_layout 'v5' is not valid"),
        ({"class_names": ("a",)}, "apply to model_type 'yolo' only"),
        ({"model_type": "yolo", "model": "x.onnx", "input_size": (4, 4)}, "input_size [4, 4]"),
    ],
)
def test_bad_config_is_rejected_naming_the_field(kwargs: dict, needle: str) -> None:
    with pytest.raises(ConfigError) as err:
        PerceptionConfig(**kwargs)
    assert needle in str(err.value)


def test_as_names() -> None:
    assert as_names(["a", "b"], "names") == ("a", "b")
    with pytest.raises(ConfigError, match="names = 'ab' must be a list"):
        as_names("ab", "names")
    with pytest.raises(ConfigError, match="non-empty strings"):
        as_names(["a", ""], "names")
