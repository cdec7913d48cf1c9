"""YOLOv8-family decoding: both ultralytics layouts, class-wise NMS, letterbox mapping, ROI decision.

The models are tiny ONNX graphs built here whose output is a known tensor, run by onnxruntime.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from unit.perception.onnx_builder import constant_output_model

from flex_nav.exceptions import ConfigError
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from flex_nav.perception.preprocess import Letterbox
from flex_nav.perception.yolo import (
    Detections,
    YoloObstacleDetector,
    classwise_nms,
    decode,
    nms,
    parse_names,
    resolve_layout,
)

NAMES = "{0: 'person', 1: 'box', 2: 'chair'}"


def raw_output(rows: list[tuple[float, float, float, float, int, float]], nc: int = 3, n: int = 20) -> np.ndarray:
    """(1, 4 + nc, n): each row (cx, cy, w, h, class, score) fills one anchor; other anchors score 0."""
    out = np.zeros((1, 4 + nc, n), np.float32)
    for i, (cx, cy, w, h, cls, score) in enumerate(rows):
        out[0, :4, i] = (cx, cy, w, h)
        out[0, 4 + cls, i] = score
        out[0, 4 + (cls + 1) % nc, i] = score / 2.0  # a lower second-best class must not win
    return out


def test_nms_keeps_the_best_of_overlapping_boxes() -> None:
    boxes = np.array([[0, 0, 10, 10], [1, 1, 11, 11], [50, 50, 60, 60]], np.float32)
    scores = np.array([0.6, 0.9, 0.5], np.float32)
    np.testing.assert_array_equal(nms(boxes, scores, 0.45), [1, 2])
    np.testing.assert_array_equal(nms(boxes, scores, 0.9), [1, 0, 2])  # IoU 0.68 <= 0.9: both kept


def test_classwise_nms_never_suppresses_across_classes() -> None:
    boxes = np.array([[0, 0, 10, 10], [1, 1, 11, 11], [0, 0, 10, 10]], np.float32)
    scores = np.array([0.6, 0.9, 0.7], np.float32)
    classes = np.array([0, 0, 1])
    np.testing.assert_array_equal(classwise_nms(boxes, scores, classes, 0.45), [1, 2])


def test_decode_raw_layout_thresholds_converts_and_suppresses() -> None:
    out = raw_output([
        (32, 32, 16, 16, 0, 0.9),   # person
        (33, 33, 16, 16, 0, 0.8),   # same person, lower: suppressed
        (33, 33, 16, 16, 1, 0.7),   # a box at the same place: other class, kept
        (10, 10, 4, 4, 2, 0.2),     # under the threshold
    ])
    found = decode(out, 3, "raw", conf_threshold=0.25, iou_threshold=0.45)
    assert len(found) == 2
    np.testing.assert_allclose(found.boxes[0], (24, 24, 40, 40))
    np.testing.assert_allclose(found.scores, (0.9, 0.7), rtol=1e-6)
    np.testing.assert_array_equal(found.classes, (0, 1))


def test_decode_end2end_layout_filters_by_score_and_class_range() -> None:
    rows = np.array([[[1, 2, 11, 12, 0.3, 1], [5, 5, 9, 9, 0.95, 0], [0, 0, 1, 1, 0.1, 2], [0, 0, 4, 4, 0.9, 7]]],
                    np.float32)
    found = decode(rows, 3, "end2end", conf_threshold=0.25, iou_threshold=0.45)
    np.testing.assert_allclose(found.boxes, [[5, 5, 9, 9], [1, 2, 11, 12]])
    np.testing.assert_array_equal(found.classes, (0, 1))  # class 7 does not exist: dropped


def test_layout_resolution() -> None:
    assert resolve_layout((1, 7, 8400), 3) == "raw"
    assert resolve_layout((1, 300, 6), 80) == "end2end"
    assert resolve_layout((1, 6, 8400), 2, "raw") == "raw"
    with pytest.raises(ConfigError, match="fits neither layout with 80 classes"):
        resolve_layout((1, 7, 8400), 80)
    with pytest.raises(ConfigError, match="does not fit layout 'end2end'"):
        resolve_layout((1, 7, 8400), 3, "end2end")
    with pytest.raises(ConfigError, match="yolo layout 'v5' is not valid"):
        resolve_layout((1, 7, 8400), 3, "v5")


def test_parse_ultralytics_names() -> None:
    assert parse_names("{0: 'person', 1: 'box', 2: 'traffic light'}") == ["person", "box", "traffic light"]
    assert parse_names("{0:'a',1:'b'}") == ["a", "b"]
    with pytest.raises(ConfigError, match="names"):
        parse_names("{1: 'a'}")
    with pytest.raises(ConfigError, match="names"):
        parse_names("[unclosed")


def _detector(path: Path, output: np.ndarray, **kwargs: object) -> YoloObstacleDetector:
    constant_output_model(path, output, metadata={"names": NAMES})
    return YoloObstacleDetector(path, **kwargs)  # type: ignore[arg-type]


def test_raw_model_end_to_end_maps_letterboxed_boxes_to_the_image(tmp_path: Path) -> None:
    # 320 x 240 image -> 64 x 64 input: scale 0.2, 8 px of padding above and below
    det = _detector(tmp_path / "raw.onnx", raw_output([(32, 32, 16, 16, 1, 0.8)]), class_map={"box": MOVABLE})
    assert det.layout == "raw" and det.class_names == ("person", "box", "chair")
    found = det.detect(np.zeros((240, 320, 3), np.uint8))
    np.testing.assert_allclose(found.boxes, [[120, 80, 200, 160]], atol=1e-4)
    prediction = det.classify(np.zeros((240, 320, 3), np.uint8))
    assert prediction.label == MOVABLE and prediction.confidence == pytest.approx(0.8)


def test_end2end_model_and_person_first(tmp_path: Path) -> None:
    rows = np.zeros((1, 10, 6), np.float32)
    rows[0, 0] = (20, 20, 44, 44, 0.95, 1)  # box, centre
    rows[0, 1] = (28, 20, 36, 56, 0.4, 0)  # person, centre, lower score
    det = _detector(tmp_path / "e2e.onnx", rows, class_map={"box": MOVABLE, "chair": "ignore"})
    assert det.layout == "end2end"
    prediction = det.classify(np.zeros((240, 320, 3), np.uint8))
    assert prediction.label == PERSON, "any person in the region wins: never push what may be a person"
    assert prediction.confidence == pytest.approx(0.4)
    assert prediction.scores[MOVABLE] == pytest.approx(0.95)


def test_detections_outside_the_roi_or_ignored_are_clear(tmp_path: Path) -> None:
    det = _detector(tmp_path / "raw.onnx", raw_output([(4, 32, 6, 20, 0, 0.9), (32, 32, 16, 16, 2, 0.9)]))
    # person at the left edge (outside the middle 60 %), chair (ignored by default) in the middle
    prediction = det.classify(np.zeros((240, 320, 3), np.uint8))
    assert prediction.label == CLEAR and prediction.confidence == pytest.approx(1.0)


def test_decide_uses_min_roi_overlap(tmp_path: Path) -> None:
    det = _detector(tmp_path / "raw.onnx", raw_output([(32, 32, 16, 16, 0, 0.9)]), min_roi_overlap=0.6)
    half_in = Detections(np.array([[0, 0, 128, 100]], np.float32), np.array([0.9], np.float32), np.array([0]))
    assert det.decide(half_in, 320, 240).label == CLEAR  # half of it inside (64..128 of 0..128)
    assert det.decide(half_in, 320, 240).scores[PERSON] == 0.0
    det.min_roi_overlap = 0.5
    assert det.decide(half_in, 320, 240).label == PERSON


def test_letterbox_mapping_of_detections() -> None:
    found = Detections(np.array([[24, 24, 40, 40]], np.float32), np.array([0.5], np.float32), np.array([0]))
    mapped = found.mapped(Letterbox(320, 240, 0.2, 0.0, 8.0))
    np.testing.assert_allclose(mapped.boxes, [[120, 80, 200, 160]])


def test_class_names_from_config_override_metadata(tmp_path: Path) -> None:
    path = constant_output_model(tmp_path / "m.onnx", raw_output([], nc=2))
    det = YoloObstacleDetector(path, class_names=["leg", "carton"], class_map={"leg": PERSON, "carton": MOVABLE})
    assert det.roles == (PERSON, MOVABLE)
    with pytest.raises(ConfigError, match="has no 'names' metadata: set class_names"):
        YoloObstacleDetector(path)


def test_bad_configuration_names_the_field(tmp_path: Path) -> None:
    path = constant_output_model(tmp_path / "m.onnx", raw_output([]), metadata={"names": NAMES})
    with pytest.raises(ConfigError, match="class_map: class 'sofa' is not valid \\(valid: person, box, chair\\)"):
        YoloObstacleDetector(path, class_map={"sofa": MOVABLE})
    with pytest.raises(ConfigError, match="role 'push' is not valid \\(valid: person, movable, ignore\\)"):
        YoloObstacleDetector(path, class_map={"box": "push"})
    with pytest.raises(ConfigError, match="maps none of the classes"):
        YoloObstacleDetector(path, class_map={"person": "ignore"})
    with pytest.raises(ConfigError, match=r"conf_threshold = 1\.5"):
        YoloObstacleDetector(path, conf_threshold=1.5)
    with pytest.raises(ConfigError, match="does not exist"):
        YoloObstacleDetector(tmp_path / "missing.onnx")
    (tmp_path / "junk.onnx").write_bytes(b"not a model")
    with pytest.raises(ConfigError, match="is not a loadable ONNX model"):
        YoloObstacleDetector(tmp_path / "junk.onnx")
    with pytest.raises(ConfigError, match="fits neither layout"):
        YoloObstacleDetector(path, class_names=["a", "b", "c", "d", "e"], class_map={"a": PERSON})


def test_dynamic_input_needs_input_size(tmp_path: Path) -> None:
    path = constant_output_model(tmp_path / "dyn.onnx", raw_output([(32, 32, 16, 16, 0, 0.9)]),
                                 input_shape=(1, 3, "height", "width"), metadata={"names": NAMES})
    with pytest.raises(ConfigError, match="dynamic input size"):
        YoloObstacleDetector(path)
    det = YoloObstacleDetector(path, input_size=(64, 64))
    assert det.classify(np.zeros((240, 320, 3), np.uint8)).label == PERSON


def test_decode_bounds_the_nms_work_and_the_detections() -> None:
    n = 5000  # more candidates than MAX_NMS_CANDIDATES, none overlapping
    out = np.zeros((1, 5, n), np.float32)
    out[0, 0] = np.arange(n) * 10.0
    out[0, 1], out[0, 2], out[0, 3] = 5.0, 4.0, 4.0
    out[0, 4] = np.linspace(0.3, 0.9, n)
    found = decode(out, 1, "raw", conf_threshold=0.25, iou_threshold=0.45, max_detections=300)
    assert len(found) == 300
    assert found.scores[0] == pytest.approx(0.9)
    assert (np.diff(found.scores) <= 0).all(), "best first"
