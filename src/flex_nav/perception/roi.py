"""The region of interest in front of the robot, as fractions of the image (resolution independent)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError

MIN_PIXELS = 2  # [px] a region narrower or lower than this in an image is an error


@dataclass(frozen=True)
class Roi:
    """``[x_min, y_min, x_max, y_max]`` as fractions of the width/height (0 = left/top, 1 = right/bottom).

    The default (the middle 60 % of the width, the full height) covers the robot's width from about
    0.4 m ahead onwards for the simulated cameras (57-69 deg horizontal field of view) and includes
    the floor and everything up to the top of the image, where a standing person's legs and body are.
    """

    x_min: float = 0.2
    y_min: float = 0.0
    x_max: float = 0.8
    y_max: float = 1.0

    def __post_init__(self) -> None:
        values = (self.x_min, self.y_min, self.x_max, self.y_max)
        if not all(math.isfinite(v) and 0.0 <= v <= 1.0 for v in values):
            raise ConfigError(f"roi {list(values)} must be 4 fractions in [0, 1] (x_min, y_min, x_max, y_max)")
        if not (self.x_min < self.x_max and self.y_min < self.y_max):
            raise ConfigError(f"roi {list(values)} must have x_min < x_max and y_min < y_max")

    @classmethod
    def from_sequence(cls, values: Sequence[float], what: str = "roi") -> Roi:
        """From ``[x_min, y_min, x_max, y_max]``; ConfigError naming ``what`` if it is not 4 numbers."""
        if isinstance(values, (str, bytes)) or len(values) != 4:
            raise ConfigError(f"{what} = {values!r} must be a list of 4 fractions [x_min, y_min, x_max, y_max]")
        try:
            numbers = [float(v) for v in values]
        except (TypeError, ValueError):
            raise ConfigError(f"{what} = {values!r} must hold numbers") from None
        try:
            return cls(*numbers)
        except ConfigError as err:
            raise ConfigError(f"{what}: {err}") from err

    def pixels(self, width: int, height: int) -> Tuple[int, int, int, int]:
        """(x0, y0, x1, y1) [px] of the region in an image of this size (x1, y1 exclusive)."""
        x0, x1 = round(self.x_min * width), round(self.x_max * width)
        y0, y1 = round(self.y_min * height), round(self.y_max * height)
        if x1 - x0 < MIN_PIXELS or y1 - y0 < MIN_PIXELS:
            raise ConfigError(f"roi {self} covers less than {MIN_PIXELS} px of a {width}x{height} image")
        return x0, y0, x1, y1

    def crop(self, image: np.ndarray) -> np.ndarray:
        """The region of an (height, width, channels) image (a view)."""
        x0, y0, x1, y1 = self.pixels(image.shape[1], image.shape[0])
        return image[y0:y1, x0:x1]

    def overlap(self, box: Tuple[float, float, float, float], width: int, height: int) -> float:
        """Fraction [0..1] of the area of ``box`` (x1, y1, x2, y2 [px]) that lies inside the region."""
        x0, y0, x1, y1 = self.x_min * width, self.y_min * height, self.x_max * width, self.y_max * height
        bx0, by0, bx1, by1 = box
        area = max(bx1 - bx0, 0.0) * max(by1 - by0, 0.0)
        if area <= 0.0:
            return 0.0
        ix = max(0.0, min(x1, bx1) - max(x0, bx0))
        iy = max(0.0, min(y1, by1) - max(y0, by0))
        return ix * iy / area
