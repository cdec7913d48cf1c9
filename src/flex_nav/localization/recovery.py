"""Random particles when the scans stop fitting (Augmented MCL, Probabilistic Robotics table 8.3).

Two exponential averages follow the mean likelihood of each sensor update: a slow one (rate alpha_slow)
and a fast one (alpha_fast > alpha_slow). When the fast one drops below the slow one, the recent scans fit
worse than the long-run ones, and each resampled particle is replaced by a random pose with probability
``max(0, 1 - w_fast / w_slow)``. Both averages start at the first update's mean and start again after
particles were injected (as amcl does), so that one bad stretch does not inject particles at every update.
Kept in logarithms: scan likelihoods of many beams are far below the smallest float.
"""

from __future__ import annotations

import math
from typing import Optional


class RecoveryAverages:
    """The slow and fast averages of the mean scan likelihood; rates 0 and 0 disable injection."""

    def __init__(self, alpha_slow: float, alpha_fast: float) -> None:
        self.alpha_slow = alpha_slow
        self.alpha_fast = alpha_fast
        self.log_slow: Optional[float] = None  # log w_slow
        self.log_fast: Optional[float] = None  # log w_fast

    @property
    def enabled(self) -> bool:
        return self.alpha_slow > 0.0 and self.alpha_fast > 0.0

    def observe(self, log_mean_likelihood: float) -> None:
        """Fold in one sensor update's log mean likelihood (the weights before the update times the scan's
        likelihood, summed)."""
        if not self.enabled or not math.isfinite(log_mean_likelihood):
            return
        if self.log_slow is None or self.log_fast is None:
            self.log_slow = self.log_fast = log_mean_likelihood
            return
        self.log_slow = _blend(self.log_slow, log_mean_likelihood, self.alpha_slow)
        self.log_fast = _blend(self.log_fast, log_mean_likelihood, self.alpha_fast)

    def injection_probability(self) -> float:
        """``max(0, 1 - w_fast / w_slow)``: the chance that one resampled particle is replaced by a random one."""
        if self.log_slow is None or self.log_fast is None:
            return 0.0
        return max(0.0, 1.0 - math.exp(min(self.log_fast - self.log_slow, 0.0)))

    def reset(self) -> None:
        """Start both averages again (after an injection, a new pose or a new map)."""
        self.log_slow = self.log_fast = None


def _blend(log_average: float, log_value: float, alpha: float) -> float:
    """log((1 - alpha) * average + alpha * value), computed in logarithms."""
    a = math.log1p(-alpha) + log_average if alpha < 1.0 else -math.inf
    b = math.log(alpha) + log_value
    high = max(a, b)
    return high + math.log(math.exp(a - high) + math.exp(b - high))
