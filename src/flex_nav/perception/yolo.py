"""YOLOv8-family detectors (ultralytics ONNX exports) as obstacle classifiers.

Two output layouts are decoded (``layout``):

``raw`` ``(1, 4 + nc, N)``: the plain ultralytics export (YOLOv8/v9/v11 ``Detect`` head): for each of
    N anchors ``cx, cy, w, h`` [model input px] then ``nc`` class scores (already sigmoid). Boxes
    with their best class score >= ``conf_threshold`` are kept, then class-wise greedy NMS at
    ``iou_threshold`` (boxes of different classes never suppress each other).
``end2end`` ``(1, K, 6)``: an export with NMS built in (``nms=True``, YOLOv10/YOLO26 end-to-end):
    rows ``x1, y1, x2, y2, score, class`` [model input px]; rows under ``conf_threshold`` are dropped,
    no NMS is applied again.
``auto`` picks ``raw`` when the middle dimension is ``4 + nc`` and ``end2end`` when the last is 6.

The image is letterboxed to the model input (:func:`flex_nav.perception.preprocess.letterbox`) and
boxes are mapped back to image pixels. Class names come from the configuration or, if not given,
from the ``names`` metadata ultralytics writes into the ONNX file; they map to person / movable /
ignore with :func:`flex_nav.perception.labels.class_roles`. A frame's label: ``person`` if a person
detection overlaps the region of interest by at least ``min_roi_overlap`` of its area, else
``movable`` if a movable one does, else ``clear`` (person first: never push what might be a person).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import yaml

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.perception.labels import CLEAR, IGNORE, MOVABLE, PERSON, Prediction, class_roles
from flex_nav.perception.onnx_model import image_input, make_session, metadata, static_size
from flex_nav.perception.preprocess import Letterbox, letterbox
from flex_nav.perception.roi import Roi

LAYOUTS = ("auto", "raw", "end2end")
DEFAULT_MAX_DETECTIONS = 300
MAX_NMS_CANDIDATES = 3000  # best-scoring boxes that enter NMS (ultralytics caps at 30000 with a C++ NMS)


@dataclass(frozen=True)
class Detections:
    """Boxes (N, 4) x1, y1, x2, y2 [px], scores (N,), class indices (N,), best first."""

    boxes: np.ndarray
    scores: np.ndarray
    classes: np.ndarray

    def __len__(self) -> int:
        return len(self.scores)

    def mapped(self, box: Letterbox) -> Detections:
        """The same detections with boxes in original image pixels."""
        return Detections(box.to_image(self.boxes), self.scores, self.classes)


def iou_one_to_many(box: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """Intersection over union of one x1, y1, x2, y2 box with each of (N, 4) boxes."""
    ix = np.clip(np.minimum(box[2], boxes[:, 2]) - np.maximum(box[0], boxes[:, 0]), 0.0, None)
    iy = np.clip(np.minimum(box[3], boxes[:, 3]) - np.maximum(box[1], boxes[:, 1]), 0.0, None)
    inter = ix * iy
    area = (box[2] - box[0]) * (box[3] - box[1])
    areas = (boxes[:, 2] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 1])
    union = area + areas - inter
    return np.where(union > 0.0, inter / np.where(union > 0.0, union, 1.0), 0.0)


def nms(boxes: np.ndarray, scores: np.ndarray, iou_threshold: float) -> np.ndarray:
    """Greedy non-maximum suppression: indices of the kept boxes, highest score first.

    A box is dropped when its IoU with an already kept box is > ``iou_threshold``.
    """
    order = np.argsort(-scores, kind="stable")
    keep: List[int] = []
    while order.size:
        best = int(order[0])
        keep.append(best)
        rest = order[1:]
        order = rest[iou_one_to_many(boxes[best], boxes[rest]) <= iou_threshold]
    return np.array(keep, dtype=np.int64)


def classwise_nms(boxes: np.ndarray, scores: np.ndarray, classes: np.ndarray, iou_threshold: float) -> np.ndarray:
    """NMS within each class only; kept indices sorted by score, highest first."""
    keep = [np.flatnonzero(classes == c)[nms(boxes[classes == c], scores[classes == c], iou_threshold)]
            for c in np.unique(classes)]
    if not keep:
        return np.zeros(0, dtype=np.int64)
    kept = np.concatenate(keep)
    ordered: np.ndarray = kept[np.argsort(-scores[kept], kind="stable")]
    return ordered


def resolve_layout(shape: Sequence[Any], num_classes: int, layout: str = "auto") -> str:
    """``raw`` or ``end2end`` for an output of ``shape``; ConfigError if it fits neither."""
    if layout not in LAYOUTS:
        raise ConfigError(choices_message("yolo layout", layout, LAYOUTS))
    dims = list(shape)
    if len(dims) != 3 or (dims[0] not in (1, None) and not isinstance(dims[0], str)):
        raise ConfigError(f"YOLO output shape {dims} is not (1, 4 + nc, N) or (1, K, 6)")
    raw_fits = dims[1] == 4 + num_classes
    e2e_fits = dims[2] == 6
    if (layout == "raw" and not raw_fits) or (layout == "end2end" and not e2e_fits):
        raise ConfigError(f"YOLO output shape {dims} does not fit layout {layout!r} with {num_classes} classes "
                          f"(raw: (1, {4 + num_classes}, N), end2end: (1, K, 6))")
    if layout != "auto":
        return layout
    if raw_fits:
        return "raw"
    if e2e_fits:
        return "end2end"
    raise ConfigError(f"YOLO output shape {dims} fits neither layout with {num_classes} classes: "
                      f"raw (1, {4 + num_classes}, N) or end2end (1, K, 6); check class_names")


def decode(
    output: np.ndarray,
    num_classes: int,
    layout: str,
    *,
    conf_threshold: float,
    iou_threshold: float,
    max_detections: int = DEFAULT_MAX_DETECTIONS,
) -> Detections:
    """Detections in model input pixels from one YOLO output (batch of one) in ``layout`` (raw | end2end)."""
    out = np.asarray(output, dtype=np.float32)
    if out.ndim != 3 or out.shape[0] != 1:
        raise ValueError(f"YOLO output of shape {out.shape}: a batch of one expected")
    if layout == "raw":
        if out.shape[1] != 4 + num_classes:
            raise ValueError(f"raw YOLO output {out.shape} needs {4 + num_classes} rows for {num_classes} classes")
        pred = out[0]
        class_scores = pred[4:]
        classes = class_scores.argmax(axis=0)
        scores = class_scores[classes, np.arange(pred.shape[1])]
        mask = scores >= conf_threshold
        cx, cy, w, h = pred[0, mask], pred[1, mask], pred[2, mask], pred[3, mask]
        boxes = np.stack([cx - w / 2.0, cy - h / 2.0, cx + w / 2.0, cy + h / 2.0], axis=1)
        scores, classes = scores[mask], classes[mask]
        if len(scores) > MAX_NMS_CANDIDATES:  # bound the NMS work on a degenerate output
            top = np.argsort(-scores, kind="stable")[:MAX_NMS_CANDIDATES]
            boxes, scores, classes = boxes[top], scores[top], classes[top]
        keep = classwise_nms(boxes, scores, classes, iou_threshold)[:max_detections]
    elif layout == "end2end":
        if out.shape[2] != 6:
            raise ValueError(f"end2end YOLO output {out.shape} needs 6 values per row")
        rows = out[0]
        mask = rows[:, 4] >= conf_threshold
        boxes, scores = rows[mask, :4], rows[mask, 4]
        classes = np.rint(rows[mask, 5]).astype(np.int64)
        valid = (classes >= 0) & (classes < num_classes)
        boxes, scores, classes = boxes[valid], scores[valid], classes[valid]
        keep = np.argsort(-scores, kind="stable")[:max_detections]
    else:
        raise ValueError(choices_message("layout", layout, ("raw", "end2end")))
    return Detections(boxes[keep].astype(np.float32), scores[keep].astype(np.float32),
                      classes[keep].astype(np.int64))


def parse_names(text: str) -> List[str]:
    """Class names from ultralytics' ``names`` metadata (``{0: 'person', 1: 'bicycle'}``), parsed as YAML."""
    try:
        value = yaml.safe_load(re.sub(r"(\d+):", r"\1: ", text))
    except yaml.YAMLError as err:
        raise ConfigError(f"model metadata 'names' is not a {{index: name}} mapping: {text[:80]!r}") from err
    if not isinstance(value, dict) or not value or sorted(value) != list(range(len(value))):
        raise ConfigError(f"model metadata 'names' is not a {{0: name, 1: name, ...}} mapping: {text[:80]!r}")
    return [str(value[i]) for i in range(len(value))]


class YoloObstacleDetector:
    """A user's YOLOv8-family ONNX model answering person / movable / clear for the region of interest."""

    def __init__(
        self,
        model: Union[str, Path],
        *,
        class_map: Optional[Mapping[str, str]] = None,
        class_names: Optional[Sequence[str]] = None,
        roi: Optional[Roi] = None,
        conf_threshold: float = 0.25,
        iou_threshold: float = 0.45,
        min_roi_overlap: float = 0.3,
        layout: str = "auto",
        input_size: Optional[Tuple[int, int]] = None,
        max_detections: int = DEFAULT_MAX_DETECTIONS,
    ) -> None:
        for name, value in (("conf_threshold", conf_threshold), ("iou_threshold", iou_threshold),
                            ("min_roi_overlap", min_roi_overlap)):
            if not 0.0 <= value <= 1.0:
                raise ConfigError(f"{name} = {value!r} must be in [0, 1]")
        if layout not in LAYOUTS:
            raise ConfigError(choices_message("yolo layout", layout, LAYOUTS))
        self.path = Path(model)
        self.session = make_session(self.path, "YOLO model")
        self.input_name, shape = image_input(self.session, f"YOLO model {self.path}")
        size = static_size(shape) or input_size
        if size is None:
            raise ConfigError(
                f"YOLO model {self.path} has a dynamic input size {shape}: set input_size [width, height]"
            )
        if input_size is not None and static_size(shape) not in (None, tuple(input_size)):
            raise ConfigError(f"input_size {list(input_size)} differs from YOLO model {self.path} input {shape}")
        self.width, self.height = int(size[0]), int(size[1])
        if class_names is None or len(class_names) == 0:
            names_text = metadata(self.session).get("names")
            if names_text is None:
                raise ConfigError(f"YOLO model {self.path} has no 'names' metadata: set class_names")
            class_names = parse_names(names_text)
        self.class_names = tuple(str(n) for n in class_names)
        self.roles = class_roles(self.class_names, class_map, "class_map")
        outputs = self.session.get_outputs()
        if len(outputs) != 1:
            raise ConfigError(f"YOLO model {self.path} must have one output, it has {len(outputs)}")
        self._layout_request = layout
        self.layout: Optional[str] = None
        if all(isinstance(d, int) for d in outputs[0].shape):
            self.layout = resolve_layout(outputs[0].shape, len(self.class_names), layout)
        self.roi = roi if roi is not None else Roi()
        self.conf_threshold = conf_threshold
        self.iou_threshold = iou_threshold
        self.min_roi_overlap = min_roi_overlap
        self.max_detections = max_detections
        person = [n for n, r in zip(self.class_names, self.roles) if r == PERSON]
        movable = [n for n, r in zip(self.class_names, self.roles) if r == MOVABLE]
        if not person and not movable:
            listed = ", ".join(self.class_names[:20]) + (" ..." if len(self.class_names) > 20 else "")
            raise ConfigError(
                f"class_map maps none of the classes of YOLO model {self.path} to person or movable (classes: {listed})"
            )
        self.description = (f"YOLO {self.path.name} ({self.width}x{self.height}; person: {', '.join(person) or '-'}; "
                            f"movable: {', '.join(movable) or '-'})")

    def detect(self, rgb: np.ndarray) -> Detections:
        """Detections in ``rgb`` (H, W, 3) uint8, boxes in its pixels."""
        tensor, box = letterbox(rgb, self.width, self.height)
        output = np.asarray(self.session.run(None, {self.input_name: tensor})[0])
        if self.layout is None:
            self.layout = resolve_layout(output.shape, len(self.class_names), self._layout_request)
        found = decode(output, len(self.class_names), self.layout, conf_threshold=self.conf_threshold,
                       iou_threshold=self.iou_threshold, max_detections=self.max_detections)
        return found.mapped(box)

    uses_depth = False  # a detector on colour images only

    def classify(self, rgb: np.ndarray, depth: Optional[np.ndarray] = None) -> Prediction:
        """The frame label from the detections in ``rgb`` (``depth`` is not used)."""
        return self.decide(self.detect(rgb), rgb.shape[1], rgb.shape[0])

    def decide(self, found: Detections, width: int, height: int) -> Prediction:
        """The frame label from detections in image pixels (see the module docstring)."""
        best: Dict[str, float] = {PERSON: 0.0, MOVABLE: 0.0}
        for box, score, cls in zip(found.boxes, found.scores, found.classes):
            role = self.roles[int(cls)]
            if role == IGNORE:
                continue
            x1, y1, x2, y2 = (float(v) for v in box)
            if self.roi.overlap((x1, y1, x2, y2), width, height) < self.min_roi_overlap:
                continue
            best[role] = max(best[role], float(score))
        scores = {PERSON: best[PERSON], MOVABLE: best[MOVABLE], CLEAR: 1.0 - max(best.values())}
        if best[PERSON] > 0.0:
            return Prediction(PERSON, best[PERSON], scores)
        if best[MOVABLE] > 0.0:
            return Prediction(MOVABLE, best[MOVABLE], scores)
        return Prediction(CLEAR, scores[CLEAR], scores)
