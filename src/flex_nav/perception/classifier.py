""":class:`ObstacleClassifier`: a whole-ROI image classifier (the project's own CNN, or a user's) on onnxruntime.

A classifier model comes with a metadata YAML beside it (same name, ``.yaml``) that says how to feed
it; ``models/obstacle_classifier.yaml`` is the shipped example::

    format: flex_nav_obstacle_classifier/1
    input: {width: 64, height: 64, mean: [0.5, 0.5, 0.5], std: [0.25, 0.25, 0.25],   # RGB, pixel/255
            depth: {max_range: 4.0, mean: 0.5, std: 0.25}}   # optional: a 4th channel, depth [m] / max_range
    output: probabilities          # or logits (softmax applied here)
    classes: [person, movable, clear]
    roi: [0.2, 0.0, 0.8, 1.0]      # the region the model was trained on (the node may override it)

A model with ``input.depth`` takes N x 4 x H x W (R, G, B, depth) and needs the depth image registered
to the colour image with every frame (:func:`flex_nav.perception.preprocess.depth_patch`); without it,
N x 3 x H x W. Everything is checked when loading: a missing or malformed field raises ConfigError naming the file
and the field. The class names map to person / movable / ignore (= clear) as in
:func:`flex_nav.perception.labels.class_roles`; a frame's label is the role with the highest summed
probability.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, Mapping, Optional, Tuple, Union

import numpy as np
import yaml

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.perception.labels import LABELS, Prediction, class_roles, label_of_role
from flex_nav.perception.onnx_model import image_input, make_session, static_size
from flex_nav.perception.preprocess import DepthScaling, Normaliser, depth_patch, roi_patch
from flex_nav.perception.roi import Roi
from flex_nav.resources import models_dir

FORMAT = "flex_nav_obstacle_classifier/1"
OUTPUTS = ("probabilities", "logits")
MODELS_DIR = models_dir()  # the package's models/ (flex_nav.resources)
DEFAULT_MODEL = MODELS_DIR / "obstacle_classifier.onnx"
PathLike = Union[str, Path]


@dataclass(frozen=True)
class ClassifierMetadata:
    """How to feed a classifier model and read its output (from the YAML beside it)."""

    source: str
    width: int  # [px] model input
    height: int  # [px]
    mean: Tuple[float, float, float]  # per channel, on pixel / 255
    std: Tuple[float, float, float]
    output: str  # one of OUTPUTS
    classes: Tuple[str, ...]
    roi: Roi
    depth: Optional[DepthScaling] = None  # None: a colour-only model

    @property
    def channels(self) -> int:
        return 3 if self.depth is None else 4


def metadata_path_for(model: PathLike) -> Path:
    """The metadata file that belongs to a model: same directory and name, suffix ``.yaml``."""
    return Path(model).with_suffix(".yaml")


def load_metadata(path: PathLike) -> ClassifierMetadata:
    """Read and validate a classifier metadata YAML; ConfigError names the file and the field."""
    file = Path(path)
    if not file.is_file():
        raise ConfigError(f"classifier metadata {str(path)!r} does not exist (a model needs its .yaml beside it)")
    try:
        top = yaml.safe_load(file.read_text())
    except yaml.YAMLError as err:
        raise ConfigError(f"classifier metadata {file}: not valid YAML: {err}") from err
    if not isinstance(top, dict):
        raise ConfigError(f"classifier metadata {file}: a mapping expected at the top level")

    def field(name: str, container: Mapping[str, Any] = top, where: str = "") -> Any:
        if name not in container:
            raise ConfigError(f"classifier metadata {file}: field {where}{name} is missing")
        return container[name]

    if field("format") != FORMAT:
        raise ConfigError(f"classifier metadata {file}: field format = {top['format']!r}, expected {FORMAT!r}")
    (width, height), mean, std, depth = _input_section(file, field("input"))
    output = field("output")
    if output not in OUTPUTS:
        raise ConfigError(choices_message(f"classifier metadata {file}: field output", output, OUTPUTS))
    classes = field("classes")
    if not isinstance(classes, list) or len(classes) < 2 or not all(isinstance(c, str) and c for c in classes):
        raise ConfigError(f"classifier metadata {file}: field classes = {classes!r} must list >= 2 class names")
    if len(set(classes)) != len(classes):
        raise ConfigError(f"classifier metadata {file}: field classes = {classes!r} has duplicates")
    roi = Roi.from_sequence(top["roi"], f"classifier metadata {file}: field roi") if "roi" in top else Roi()
    return ClassifierMetadata(str(file), width, height, mean, std, output, tuple(classes), roi, depth)


Triple = Tuple[float, float, float]


def _input_section(file: Path, inp: Any) -> Tuple[Tuple[int, int], Triple, Triple, Optional[DepthScaling]]:
    """(width, height), mean, std, depth scaling (None: colour only) from the metadata's ``input`` mapping."""
    if not isinstance(inp, dict):
        raise ConfigError(f"classifier metadata {file}: field input must be a mapping")
    size = []
    for name in ("width", "height"):
        value = inp.get(name)
        if isinstance(value, bool) or not isinstance(value, int) or value < 4:
            raise ConfigError(f"classifier metadata {file}: field input.{name} = {value!r} must be an integer >= 4")
        size.append(value)
    norm = []
    for name in ("mean", "std"):
        value = inp.get(name)
        if not isinstance(value, list) or len(value) != 3 or not all(isinstance(v, (int, float)) for v in value):
            raise ConfigError(f"classifier metadata {file}: field input.{name} = {value!r} must be 3 numbers (R, G, B)")
        norm.append((float(value[0]), float(value[1]), float(value[2])))
    try:
        Normaliser(norm[0], norm[1])
    except ConfigError as err:
        raise ConfigError(f"classifier metadata {file}: field input: {err}") from err
    return (size[0], size[1]), norm[0], norm[1], _depth_section(file, inp.get("depth"))


def _depth_section(file: Path, depth: Any) -> Optional[DepthScaling]:
    """The optional ``input.depth`` mapping: ``max_range`` [m], ``mean``, ``std``."""
    if depth is None:
        return None
    keys = ("max_range", "mean", "std")
    if not isinstance(depth, dict) or sorted(depth) != sorted(keys):
        raise ConfigError(f"classifier metadata {file}: field input.depth = {depth!r} must map exactly "
                          f"{', '.join(keys)} to numbers")
    for key in keys:
        if isinstance(depth[key], bool) or not isinstance(depth[key], (int, float)):
            raise ConfigError(f"classifier metadata {file}: field input.depth.{key} = {depth[key]!r} must be a number")
    try:
        return DepthScaling(float(depth["max_range"]), float(depth["mean"]), float(depth["std"]))
    except ConfigError as err:
        raise ConfigError(f"classifier metadata {file}: field input.depth: {err}") from err


class ObstacleClassifier:
    """Classifies the region of interest of an RGB (or RGB + depth) image as person / movable / clear.

    ``model``: an ONNX file (default: the shipped ``models/obstacle_classifier.onnx``); ``metadata``:
    its YAML (default: beside the model); ``roi``: overrides the metadata's; ``class_map``: model class
    name -> person / movable / ignore (default: by name, see :func:`class_roles`).
    """

    def __init__(
        self,
        model: Optional[PathLike] = None,
        metadata: Optional[PathLike] = None,
        roi: Optional[Roi] = None,
        class_map: Optional[Mapping[str, str]] = None,
    ) -> None:
        model_path = Path(model) if model is not None else DEFAULT_MODEL
        self.session = make_session(model_path, "classifier model")  # first: a wrong path is the likelier mistake
        self.metadata = load_metadata(metadata if metadata is not None else metadata_path_for(model_path))
        meta = self.metadata
        self.input_name, shape = image_input(self.session, f"classifier model {model_path}", meta.channels)
        size = static_size(shape)
        if size is not None and size != (meta.width, meta.height):
            raise ConfigError(
                f"classifier model {model_path} takes {size[0]}x{size[1]} images but its metadata "
                f"{meta.source} says input {meta.width}x{meta.height}"
            )
        outputs = self.session.get_outputs()
        if len(outputs) != 1:
            raise ConfigError(f"classifier model {model_path} must have one output (scores), it has {len(outputs)}")
        n_out = outputs[0].shape[-1] if outputs[0].shape else None
        if isinstance(n_out, int) and n_out != len(meta.classes):
            raise ConfigError(
                f"classifier model {model_path} outputs {n_out} scores but its metadata lists "
                f"{len(meta.classes)} classes {list(meta.classes)}"
            )
        self.path = model_path
        self.roi = roi if roi is not None else meta.roi
        self.roles = class_roles(meta.classes, class_map, "class_map")
        self.normaliser = Normaliser(meta.mean, meta.std)
        self._role_index = {label: np.array([i for i, r in enumerate(self.roles) if label_of_role(r) == label],
                                            dtype=np.int64) for label in LABELS}
        inputs = "RGB-D" if meta.depth is not None else "RGB"
        self.description = (f"classifier {model_path.name} ({', '.join(meta.classes)}; {inputs} "
                            f"{meta.width}x{meta.height})")

    @property
    def uses_depth(self) -> bool:
        """True if every frame needs the registered depth image too."""
        return self.metadata.depth is not None

    def input_tensor(self, rgb: np.ndarray, depth: Optional[np.ndarray] = None) -> np.ndarray:
        """The normalised NCHW float32 input for an RGB image (H, W, 3) uint8 and, for an RGB-D model, the
        depth image [m] (H', W') registered to it; ConfigError if the model needs depth and none is given."""
        meta = self.metadata
        patch = roi_patch(rgb, self.roi, meta.width, meta.height)[None]
        if meta.depth is None or depth is None:
            return self.batch_tensor(patch)
        depth_in_roi = depth_patch(depth, self.roi, meta.width, meta.height, meta.depth.max_range)
        return self.batch_tensor(patch, depth_in_roi[None])

    def batch_tensor(self, patches: np.ndarray, depth_patches: Optional[np.ndarray] = None) -> np.ndarray:
        """The normalised input for ROI patches (N, H, W, 3) uint8 and, for an RGB-D model, depth patches
        (N, H, W) [m]; ConfigError if the model needs depth and none is given."""
        colour = self.normaliser.batch(patches)
        if self.metadata.depth is None:
            return colour
        if depth_patches is None:
            raise ConfigError(f"classifier model {self.path} takes colour and depth: a depth image is needed "
                              "with every frame")
        return np.concatenate([colour, self.metadata.depth.batch(depth_patches)], axis=1)

    def probabilities(self, tensor: np.ndarray) -> np.ndarray:
        """Class probabilities (N, classes) for a normalised input batch."""
        scores = np.asarray(self.session.run(None, {self.input_name: tensor})[0], dtype=np.float64)
        if scores.ndim != 2 or scores.shape[1] != len(self.metadata.classes):
            raise ConfigError(f"classifier model {self.path} returned shape {scores.shape}, "
                              f"(N, {len(self.metadata.classes)}) expected")
        if self.metadata.output == "logits":
            scores = np.exp(scores - scores.max(axis=1, keepdims=True))
            scores /= scores.sum(axis=1, keepdims=True)
        return scores

    def classify(self, rgb: np.ndarray, depth: Optional[np.ndarray] = None) -> Prediction:
        """The label of the region of interest of ``rgb`` (H, W, 3) uint8 (with ``depth`` [m] registered to it
        for an RGB-D model) and its probability."""
        return self.decide(self.probabilities(self.input_tensor(rgb, depth))[0])

    def decide(self, probabilities: np.ndarray) -> Prediction:
        """Label = the role with the highest summed class probability."""
        scores: Dict[str, float] = {label: float(probabilities[idx].sum()) for label, idx in self._role_index.items()}
        label = max(LABELS, key=lambda name: scores[name])
        return Prediction(label, scores[label], scores)
