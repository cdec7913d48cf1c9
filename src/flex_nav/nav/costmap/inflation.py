"""Inflation of lethal cells with costmap_2d's cost function, on an exact Euclidean distance transform.

For a cell whose centre is ``d`` [m] from the centre of the nearest LETHAL cell:

- ``d == 0``                      -> 254 (LETHAL)
- ``d <= inscribed_radius``       -> 253 (INSCRIBED)
- ``d`` within the inflation radius -> ``int(252 · exp(−cost_scaling_factor · (d − inscribed_radius)))``
- farther                          -> 0

"Within the inflation radius" is costmap_2d's test ``d_cells <= ceil(inflation_radius / resolution)``.
Distances come from OpenCV's ``distanceTransform(DIST_L2, DIST_MASK_PRECISE)``, which is exact, so the
squared distance in cells is an integer and the cost is a table lookup on it.

Combining with the master costs follows costmap_2d: the result is the maximum of the old and the inflated
cost, except that a NO_INFORMATION cell keeps 255 unless the inflated cost is at least INSCRIBED
(or, with ``inflate_unknown``, any cost above FREE).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.costmap_grid import INSCRIBED, LETHAL, MAX_NON_OBSTACLE, NO_INFORMATION


@dataclass(frozen=True)
class InflationParams:
    """Parameters of the inflation layer (costmap_2d's names and meaning)."""

    inscribed_radius: float = 0.2  # [m] radius of the robot's inscribed circle
    inflation_radius: float = 0.55  # [m] inflate up to this distance from obstacles
    cost_scaling_factor: float = 3.0  # [1/m] k in 252·exp(−k·(d − r_inscribed))
    inflate_unknown: bool = False  # inflate into NO_INFORMATION cells too

    def __post_init__(self) -> None:
        for name in ("inscribed_radius", "inflation_radius", "cost_scaling_factor"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
                raise ConfigError(f"inflation {name} must be a finite number >= 0, got {value!r}")
        if self.inflation_radius < self.inscribed_radius:
            raise ConfigError(
                f"inflation inflation_radius ({self.inflation_radius} m) must be >= inscribed_radius "
                f"({self.inscribed_radius} m)"
            )


def cost_of_distance(distance_m: float, params: InflationParams) -> int:
    """costmap_2d's cost of a cell ``distance_m`` [m] from the nearest lethal cell (ignores the radius cut-off)."""
    if distance_m == 0.0:
        return LETHAL
    if distance_m <= params.inscribed_radius:
        return INSCRIBED
    factor = math.exp(-params.cost_scaling_factor * (distance_m - params.inscribed_radius))
    return int(MAX_NON_OBSTACLE * factor)


class Inflator:
    """Inflates a cost array in place; caches the lookup table for one resolution.

    One instance per costmap (it holds scratch state, so do not share between threads).
    """

    def __init__(self, params: InflationParams, resolution: float) -> None:
        if not math.isfinite(resolution) or resolution <= 0.0:
            raise ConfigError(f"inflation resolution must be a finite number > 0 [m/cell], got {resolution!r}")
        self.params = params
        self.resolution = float(resolution)
        self.radius_cells = max(0, math.ceil(params.inflation_radius / resolution - 1e-9))
        # cost by squared distance [cells²]; one extra entry (0) for everything beyond the radius
        limit = self.radius_cells * self.radius_cells
        table = np.zeros(limit + 2, dtype=np.uint8)
        for d2 in range(limit + 1):
            table[d2] = cost_of_distance(math.sqrt(d2) * resolution, params)
        self.table = table
        self._unknown_floor = 1 if params.inflate_unknown else INSCRIBED

    def inflated_costs(self, costs: np.ndarray) -> np.ndarray:
        """Inflation costs alone (uint8, same shape) for the LETHAL cells of ``costs``."""
        src = (costs != LETHAL).view(np.uint8)
        dist = cv2.distanceTransform(src, cv2.DIST_L2, cv2.DIST_MASK_PRECISE)
        # beyond the radius every distance maps to the last (zero) entry
        np.minimum(dist, float(self.radius_cells + 1), out=dist)
        np.multiply(dist, dist, out=dist)
        index = cv2.convertScaleAbs(dist, alpha=1.0) if len(self.table) <= 256 else np.rint(dist).astype(np.intp)
        np.minimum(index, len(self.table) - 1, out=index)
        inflated: np.ndarray = self.table[index]
        return inflated

    def apply(self, costs: np.ndarray) -> None:
        """Inflate ``costs`` (uint8 (H, W)) in place with costmap_2d's combination rule."""
        if costs.dtype != np.uint8 or costs.ndim != 2:
            raise ConfigError(f"costs must be a 2-D uint8 array, got {costs.dtype} {costs.shape}")
        if not (costs == LETHAL).any():
            return
        inflated = self.inflated_costs(costs)
        unknown = costs == NO_INFORMATION
        np.maximum(costs, inflated, out=costs)  # unknown cells stay 255 here
        if unknown.any():
            take = unknown & (inflated >= self._unknown_floor)
            costs[take] = inflated[take]


def inflate(costs: np.ndarray, resolution: float, params: InflationParams) -> np.ndarray:
    """A new inflated copy of ``costs`` (convenience wrapper around :class:`Inflator`)."""
    out = np.array(costs, dtype=np.uint8, copy=True)
    Inflator(params, resolution).apply(out)
    return out
