"""Low-variance (systematic) resampling (Probabilistic Robotics, table 4.4).

One random offset r in [0, 1/M) and the M equally spaced points r + m/M on the cumulative weights pick the
particles: a particle of weight w is taken floor(M w) or ceil(M w) times, never more or fewer, so resampling
adds as little noise as it can, and a set of equal weights comes back unchanged.
"""

from __future__ import annotations

import numpy as np


def low_variance_indices(weights: np.ndarray, count: int, rng: np.random.Generator) -> np.ndarray:
    """(count,) int64 indices into ``weights`` (non-negative, not all zero; normalised here), in ascending order."""
    cumulative = np.cumsum(weights, dtype=np.float64)
    total = cumulative[-1]
    if not (np.isfinite(total) and total > 0.0):
        raise ValueError(f"resampling needs finite weights with a positive sum, got sum {total!r}")
    points = (rng.random() + np.arange(count, dtype=np.float64)) * (total / count)
    index = np.searchsorted(cumulative, points, side="right")
    return np.asarray(np.minimum(index, weights.shape[0] - 1))
