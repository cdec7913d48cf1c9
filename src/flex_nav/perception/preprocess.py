"""Model inputs from an RGB (and depth) image: the classifier's normalised ROI patch and the YOLO letterbox.

Both return float32 NCHW tensors with a batch of one. The classifier patch is the region of interest
resized (area averaging) to the model's input size, then ``(pixel / 255 - mean) / std`` per channel;
training (``tools/perception``) uses :func:`roi_patch` too, so training and runtime see the same pixels.
An RGB-D classifier adds the same region of the registered depth image (:func:`depth_patch`) as a
fourth channel, ``(depth / max_range - mean) / std``.
The letterbox keeps the aspect ratio (ultralytics convention: scale to fit, pad evenly with grey 114,
pixel / 255) and :class:`Letterbox` maps boxes back to the original image.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence, Tuple

import cv2
import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.perception.roi import Roi

LETTERBOX_PAD = 114  # grey value of the letterbox border (ultralytics)


def roi_patch(rgb: np.ndarray, roi: Roi, width: int, height: int) -> np.ndarray:
    """The region of interest of ``rgb`` (H, W, 3) resized to (height, width, 3) uint8 (area averaging)."""
    return _resized(roi.crop(rgb), width, height)


def _resized(crop: np.ndarray, width: int, height: int) -> np.ndarray:
    """``crop`` at (height, width): area averaging when shrinking, bilinear when enlarging, as is if it fits."""
    if crop.shape[1] == width and crop.shape[0] == height:
        return np.ascontiguousarray(crop)
    interpolation = cv2.INTER_AREA if crop.shape[1] >= width else cv2.INTER_LINEAR
    return cv2.resize(np.ascontiguousarray(crop), (width, height), interpolation=interpolation)


def depth_patch(depth: np.ndarray, roi: Roi, width: int, height: int, max_range: float) -> np.ndarray:
    """The region of interest of a depth image [m] (H, W) resized to (height, width) float32 [m] (area averaging).

    Pixels without a return (NaN, +-inf, <= 0: REP 118's "no measurement" values) and pixels beyond
    ``max_range`` [m] count as ``max_range``: the model sees "nothing within range" there. The depth
    image must be registered to the colour image (same field of view); its resolution may differ."""
    crop = roi.crop(depth).astype(np.float32)
    with np.errstate(invalid="ignore"):
        valid = np.isfinite(crop) & (crop > 0.0)
    return _resized(np.where(valid, np.minimum(crop, np.float32(max_range)), np.float32(max_range)), width, height)


@dataclass(frozen=True)
class DepthScaling:
    """The depth channel of an RGB-D classifier: ``(depth / max_range - mean) / std`` (depth in [m])."""

    max_range: float  # [m] farther or missing returns count as this
    mean: float
    std: float

    def __post_init__(self) -> None:
        if not (math.isfinite(self.max_range) and self.max_range > 0.0):
            raise ConfigError(f"depth max_range {self.max_range!r} must be a finite number of metres > 0")
        if not (math.isfinite(self.std) and self.std > 0.0 and math.isfinite(self.mean)):
            raise ConfigError(f"depth std {self.std!r} must be finite and > 0, mean {self.mean!r} finite")

    def batch(self, patches: np.ndarray) -> np.ndarray:
        """(N, H, W) [m] -> (N, 1, H, W) float32."""
        scale = np.float32(1.0 / (self.max_range * self.std))
        return (patches.astype(np.float32) * scale - np.float32(self.mean / self.std))[:, None]


class Normaliser:
    """``(pixel / 255 - mean) / std`` per channel, NHWC uint8 -> NCHW float32."""

    def __init__(self, mean: Sequence[float], std: Sequence[float]) -> None:
        if len(mean) != 3 or len(std) != 3:
            raise ConfigError(f"mean {list(mean)} and std {list(std)} must have 3 values (R, G, B)")
        if not all(math.isfinite(s) and s > 0.0 for s in std) or not all(math.isfinite(m) for m in mean):
            raise ConfigError(f"std {list(std)} must be finite and > 0, mean {list(mean)} finite")
        self.mean = tuple(float(m) for m in mean)
        self.std = tuple(float(s) for s in std)
        self._scale = np.array([1.0 / (255.0 * s) for s in self.std], dtype=np.float32)
        self._offset = np.array([-m / s for m, s in zip(self.mean, self.std)], dtype=np.float32)

    def batch(self, patches: np.ndarray) -> np.ndarray:
        """(N, H, W, 3) uint8 -> (N, 3, H, W) float32."""
        nchw = patches.astype(np.float32).transpose(0, 3, 1, 2)
        scaled: np.ndarray = nchw * self._scale[None, :, None, None] + self._offset[None, :, None, None]
        return scaled


@dataclass(frozen=True)
class Letterbox:
    """How an image of ``width`` x ``height`` [px] was placed in the model input: scaled, then padded."""

    width: int  # [px] original image
    height: int  # [px]
    scale: float  # model px per image px
    pad_x: float  # [px] left border in the model input
    pad_y: float  # [px] top border

    def to_image(self, boxes: np.ndarray) -> np.ndarray:
        """(N, 4) x1, y1, x2, y2 in model input pixels -> original image pixels, clipped to the image."""
        out = np.empty(np.shape(boxes), dtype=np.float32)
        out[:, 0::2] = np.clip((boxes[:, 0::2] - self.pad_x) / self.scale, 0.0, float(self.width))
        out[:, 1::2] = np.clip((boxes[:, 1::2] - self.pad_y) / self.scale, 0.0, float(self.height))
        return out


def letterbox(rgb: np.ndarray, width: int, height: int) -> Tuple[np.ndarray, Letterbox]:
    """``rgb`` (H, W, 3) uint8 scaled to fit ``width`` x ``height`` keeping its aspect, padded evenly with grey.

    Returns the NCHW float32 input (pixel / 255) and the :class:`Letterbox` to map boxes back.
    """
    h, w = rgb.shape[:2]
    scale = min(width / w, height / h)
    new_w, new_h = max(1, round(w * scale)), max(1, round(h * scale))
    pad_x, pad_y = (width - new_w) / 2.0, (height - new_h) / 2.0
    left, top = round(pad_x - 0.1), round(pad_y - 0.1)  # ultralytics rounds the odd pixel to the right/bottom
    canvas = np.full((height, width, 3), LETTERBOX_PAD, dtype=np.uint8)
    resized = rgb if (new_w, new_h) == (w, h) else cv2.resize(rgb, (new_w, new_h), interpolation=cv2.INTER_LINEAR)
    canvas[top : top + new_h, left : left + new_w] = resized
    tensor = canvas.transpose(2, 0, 1)[None].astype(np.float32) * np.float32(1.0 / 255.0)
    return tensor, Letterbox(w, h, scale, float(left), float(top))
