"""Building the frame classifier a node uses, from one validated configuration.

``model_type`` ``classifier`` loads :class:`ObstacleClassifier` (the shipped model by default),
``yolo`` loads :class:`YoloObstacleDetector` (a user's ultralytics export). Both answer
``classify(rgb, depth=None) -> Prediction``, say whether they need the depth image (``uses_depth``) and
carry a one-line ``description``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, Optional, Protocol, Sequence, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.perception.classifier import DEFAULT_MODEL, ObstacleClassifier
from flex_nav.perception.labels import Prediction
from flex_nav.perception.roi import Roi
from flex_nav.perception.yolo import LAYOUTS, YoloObstacleDetector

MODEL_TYPES = ("classifier", "yolo")


class FrameClassifier(Protocol):
    description: str

    @property
    def uses_depth(self) -> bool:
        """True if :meth:`classify` needs the depth image registered to the colour image."""

    def classify(self, rgb: np.ndarray, depth: Optional[np.ndarray] = None) -> Prediction: ...


@dataclass(frozen=True)
class PerceptionConfig:
    """What to load and how to decide; see the node's docstring for each field's meaning and default."""

    model_type: str = "classifier"
    model: str = ""  # '' = the shipped classifier (model_type classifier only)
    metadata: str = ""  # classifier metadata YAML; '' = beside the model
    class_map: Dict[str, str] = field(default_factory=dict)
    class_names: Tuple[str, ...] = ()  # yolo: '' = from the model's metadata
    roi: Optional[Roi] = None  # None = the model's (classifier) or the default Roi (yolo)
    conf_threshold: float = 0.25
    iou_threshold: float = 0.45
    min_roi_overlap: float = 0.3
    yolo_layout: str = "auto"
    input_size: Optional[Tuple[int, int]] = None  # yolo models with a dynamic input: (width, height) [px]

    def __post_init__(self) -> None:
        if self.model_type not in MODEL_TYPES:
            raise ConfigError(choices_message("model_type", self.model_type, MODEL_TYPES))
        if self.model_type == "yolo" and not self.model:
            raise ConfigError("model must be set to the ONNX file when model_type is 'yolo'")
        if self.yolo_layout not in LAYOUTS:
            raise ConfigError(choices_message("yolo_layout", self.yolo_layout, LAYOUTS))
        if self.model_type == "classifier" and (self.class_names or self.input_size):
            raise ConfigError("class_names and input_size apply to model_type 'yolo' only "
                              "(a classifier reads them from its metadata YAML)")
        if self.input_size is not None and (len(self.input_size) != 2 or min(self.input_size) < 8):
            raise ConfigError(f"input_size {list(self.input_size)} must be [width, height] >= 8 px")


def build(config: PerceptionConfig) -> FrameClassifier:
    """Load the configured model; ConfigError names the bad field (model path, metadata, class map, ...)."""
    if config.model_type == "classifier":
        return ObstacleClassifier(
            config.model or DEFAULT_MODEL,
            metadata=config.metadata or None,
            roi=config.roi,
            class_map=config.class_map or None,
        )
    return YoloObstacleDetector(
        config.model,
        class_map=config.class_map or None,
        class_names=list(config.class_names) or None,
        roi=config.roi,
        conf_threshold=config.conf_threshold,
        iou_threshold=config.iou_threshold,
        min_roi_overlap=config.min_roi_overlap,
        layout=config.yolo_layout,
        input_size=config.input_size,
    )


def as_names(values: Sequence[object], what: str) -> Tuple[str, ...]:
    """A tuple of non-empty strings; ConfigError naming ``what`` otherwise."""
    if isinstance(values, (str, bytes)) or not all(isinstance(v, str) and v for v in values):
        raise ConfigError(f"{what} = {values!r} must be a list of non-empty strings")
    return tuple(str(v) for v in values)
