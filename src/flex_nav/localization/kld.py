"""KLD-sampling (Fox 2003): how many particles a belief needs, from the number of histogram bins it occupies.

With k occupied bins, ``n = (k - 1) / (2 err) * (1 - 2 / (9 (k - 1)) + sqrt(2 / (9 (k - 1))) * z)³`` particles
bound the Kullback-Leibler divergence between the sample-based and the true posterior by ``err`` with
probability ``1 - delta`` (the Wilson-Hilferty approximation of the chi-square quantile; ``z`` is the upper
standard normal quantile z_(1-delta), amcl's ``kld_z``). Bins are 0.5 m x 0.5 m x 10 deg, as amcl's.

Samples are counted as they are drawn (in random order): drawing stops once the count reaches both
min_particles and the bound for the bins occupied so far, or max_particles. One deviation from amcl: with a single
bin occupied the bound is 0 (the clamp gives min_particles); amcl asks for max_particles there, so that a
tight cloud would grow to the maximum.
"""

from __future__ import annotations

import math
from typing import Union

import numpy as np

BIN_XY = 0.5  # [m] bin size in x and y (amcl)
BIN_YAW = math.radians(10.0)  # [rad] bin size in yaw (amcl)
_OFFSET = 1 << 20  # keeps bin indices non-negative within +-262 km of the origin
_SHIFT = 21  # bits per index in the packed key


def kld_bound(bins: Union[int, np.ndarray], err: float, z: float) -> np.ndarray:
    """Particles needed for ``bins`` occupied bins (int or array of ints), not yet clamped; 0 for fewer than 2
    bins. Rounded up to an integer (returned as float64)."""
    k = np.asarray(bins, dtype=np.float64)
    dof = np.maximum(k - 1.0, 1.0)
    c = 2.0 / (9.0 * dof)
    x = 1.0 - c + np.sqrt(c) * z
    n = np.ceil(dof / (2.0 * err) * x * x * x)
    return np.asarray(np.where(k > 1.0, n, 0.0))


def bin_keys(particles: np.ndarray) -> np.ndarray:
    """(N,) int64: one key per particle's (x, y, yaw) bin; equal keys, same bin."""
    ix = np.floor(particles[:, 0] / BIN_XY).astype(np.int64) + _OFFSET
    iy = np.floor(particles[:, 1] / BIN_XY).astype(np.int64) + _OFFSET
    ia = np.floor(particles[:, 2] / BIN_YAW).astype(np.int64) + _OFFSET
    return np.asarray((ix << (2 * _SHIFT)) | (iy << _SHIFT) | ia)


def sample_count(keys: np.ndarray, err: float, z: float, min_count: int, max_count: int) -> int:
    """How many of the samples whose bin ``keys`` are given (in the order drawn) KLD-sampling keeps: the first
    count n >= min_count with n >= the bound for the bins occupied by the first n samples; max_count if no prefix
    of the (at most max_count) keys satisfies it."""
    keys = np.asarray(keys)[:max_count]
    if keys.size == 0:
        return int(min_count)
    _, first = np.unique(keys, return_index=True)
    new_bin = np.zeros(keys.size, dtype=np.int64)
    new_bin[first] = 1
    occupied = np.cumsum(new_bin)
    drawn = np.arange(1, keys.size + 1, dtype=np.float64)
    enough = np.flatnonzero((drawn >= kld_bound(occupied, err, z)) & (drawn >= min_count))
    count = int(enough[0]) + 1 if enough.size else int(max_count)
    return int(min(max(count, min_count), max_count))
