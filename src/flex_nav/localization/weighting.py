"""Turning log-likelihoods into particle weights without losing the cloud in one update.

A scan of many beams can score one particle e^50 above its neighbours. When the cloud is still wide (a rough
initial pose, global localization) and no particle is close to the truth yet, taking that at face value puts
all the weight on the few best wrong ones and resampling collapses the cloud there. The update is therefore
tempered further when needed: the log-likelihoods are scaled by the largest factor in (0, 1] that leaves an
effective sample size (1 / sum(w²)) of at least ``MIN_ESS_FRACTION`` of the particles (likelihood tempering
as in annealed importance sampling). A tracking cloud is never touched: its weights are far from that
degenerate.
"""

from __future__ import annotations

import math
from typing import Tuple

import numpy as np

MIN_ESS_FRACTION = 0.01  # [-] effective sample size kept after a sensor update, as a fraction of the particles
MIN_ESS_FRACTION_COARSE = 0.1  # [-] the same while the sensor model is widened (the cloud is still wide)
_BISECTIONS = 12  # the scale is found to 1/4096


def ess_fraction(log_weights: np.ndarray) -> float:
    """Effective sample size 1 / sum(w²) of the normalised ``exp(log_weights)``, divided by their number."""
    w = np.exp(log_weights - float(log_weights.max()))
    w /= w.sum()
    return float(1.0 / (w @ w) / w.size)


def tempering_scale(log_prior: np.ndarray, log_likelihood: np.ndarray, coarse: bool = False) -> float:
    """The largest s in (0, 1] with ``ess_fraction(log_prior + s * log_likelihood) >= min_fraction`` (1 when the
    full update keeps that much, or when the prior itself has less); ``min_fraction`` is
    :data:`MIN_ESS_FRACTION_COARSE` for a ``coarse`` update, else :data:`MIN_ESS_FRACTION`."""
    min_fraction = MIN_ESS_FRACTION_COARSE if coarse else MIN_ESS_FRACTION
    if ess_fraction(log_prior + log_likelihood) >= min_fraction or ess_fraction(log_prior) < min_fraction:
        return 1.0
    low, high = 0.0, 1.0
    for _ in range(_BISECTIONS):
        middle = 0.5 * (low + high)
        if ess_fraction(log_prior + middle * log_likelihood) >= min_fraction:
            low = middle
        else:
            high = middle
    return low if low > 0.0 else high / 2.0


def reweigh(weights: np.ndarray, log_likelihood: np.ndarray, uniform: bool, coarse: bool) -> Tuple[np.ndarray, float]:
    """The normalised posterior weights from the prior ``weights`` (normalised; ``uniform`` if they are all
    1/N, e.g. just after resampling) and the particles' ``log_likelihood``, tempered by :func:`tempering_scale`
    where the full update would leave too few effective particles; and the log of the (tempered) mean likelihood
    ``log(sum(w_i * L_i))``."""
    count = weights.size
    if uniform:
        log_prior = np.full(count, -math.log(count))
    else:
        with np.errstate(divide="ignore"):
            log_prior = np.log(weights)
    posterior, log_total = _normalised(log_prior + log_likelihood)
    floor = MIN_ESS_FRACTION_COARSE if coarse else MIN_ESS_FRACTION
    if 1.0 / float(posterior @ posterior) >= floor * count:
        return posterior, log_total
    scale = tempering_scale(log_prior, log_likelihood, coarse)
    return _normalised(log_prior + scale * log_likelihood) if scale < 1.0 else (posterior, log_total)


def _normalised(log_weights: np.ndarray) -> Tuple[np.ndarray, float]:
    """``exp(log_weights)`` normalised, and the log of their sum."""
    high = float(log_weights.max())
    weights = np.exp(log_weights - high)
    total = float(weights.sum())
    weights /= total
    return weights, high + math.log(total)
