"""Localization error of a run: each estimate (amcl_pose) against the ground truth at the estimate's stamp.

Ground truth comes at the odometry rate (50 Hz in the simulator) and estimates at the filter's rate; the truth
at an estimate's stamp is linearly interpolated between the two truth samples around it (yaw along the shorter
arc). Estimates older than the kept truth, or newer than the newest truth by more than ``max_gap_s``, are
held back until they can be paired or are dropped. Pure Python: the demo feeds it from its subscribers.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from typing import List, NamedTuple, Optional, Tuple

from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.planar import Pose2D

TRUTH_KEPT_S = 10.0  # [s] ground truth kept for pairing (estimates arrive within a scan period of their stamp)


class ErrorSummary(NamedTuple):
    """Position error [cm] (median, 95th percentile, maximum) and heading error [deg] (median) of ``estimates``
    estimates."""

    estimates: int
    median_cm: float
    p95_cm: float
    max_cm: float
    heading_median_deg: float

    def line(self) -> str:
        """The demo's summary line, e.g. ``localization: median 1.8 cm, p95 4.0 cm, max 6.2 cm`` (+ heading)."""
        if self.estimates == 0:
            return "localization: no estimates paired with ground truth"
        return (f"localization: median {self.median_cm:.1f} cm, p95 {self.p95_cm:.1f} cm, max {self.max_cm:.1f} cm "
                f"(heading median {self.heading_median_deg:.2f} deg, {self.estimates} estimates)")


def percentile(sorted_values: List[float], fraction: float) -> float:
    """Linear-interpolated percentile of already sorted values (``fraction`` in [0, 1])."""
    if not sorted_values:
        return math.nan
    position = fraction * (len(sorted_values) - 1)
    low = math.floor(position)
    high = min(low + 1, len(sorted_values) - 1)
    return sorted_values[low] + (sorted_values[high] - sorted_values[low]) * (position - low)


@dataclass
class LocalizationErrors:
    """Collects (stamp, truth) and (stamp, estimate) pairs of one robot; :meth:`summary` gives the statistics."""

    max_gap_s: float = 0.1  # [s] an estimate further than this from every truth sample is not paired

    def __post_init__(self) -> None:
        self._truth_t: List[float] = []
        self._truth: List[Pose2D] = []
        self._waiting: List[Tuple[float, Pose2D]] = []  # estimates newer than the newest truth
        self.position_m: List[float] = []  # [m] one per paired estimate
        self.heading_rad: List[float] = []  # [rad] absolute

    def add_truth(self, stamp_s: float, pose: Pose2D) -> None:
        if self._truth_t and stamp_s <= self._truth_t[-1]:
            if stamp_s < self._truth_t[-1] - 1.0:  # time went back (a restarted simulation): start afresh
                self._truth_t.clear()
                self._truth.clear()
                self._waiting.clear()
            else:
                return
        self._truth_t.append(stamp_s)
        self._truth.append(pose)
        cut = bisect.bisect_left(self._truth_t, stamp_s - TRUTH_KEPT_S)
        if cut:
            del self._truth_t[:cut], self._truth[:cut]
        waiting, self._waiting = self._waiting, []
        for t, estimate in waiting:
            self.add_estimate(t, estimate)

    def add_estimate(self, stamp_s: float, pose: Pose2D) -> None:
        if self._truth_t and stamp_s > self._truth_t[-1]:
            if stamp_s - self._truth_t[-1] <= 1.0:
                self._waiting.append((stamp_s, pose))
            return
        truth = self.truth_at(stamp_s)
        if truth is None:
            return
        self.position_m.append(math.hypot(pose[0] - truth[0], pose[1] - truth[1]))
        self.heading_rad.append(abs(wrap_angle(pose[2] - truth[2])))

    def truth_at(self, stamp_s: float) -> Optional[Pose2D]:
        """Ground truth interpolated at ``stamp_s`` [s]; None when no two samples within ``max_gap_s`` bracket it."""
        index = bisect.bisect_left(self._truth_t, stamp_s)
        if index < len(self._truth_t) and self._truth_t[index] == stamp_s:
            return self._truth[index]
        if index == 0 or index == len(self._truth_t):
            return None
        t0, t1 = self._truth_t[index - 1], self._truth_t[index]
        if t1 - t0 > 2.0 * self.max_gap_s:
            return None
        a, b = self._truth[index - 1], self._truth[index]
        f = (stamp_s - t0) / (t1 - t0)
        return (a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), wrap_angle(a[2] + f * wrap_angle(b[2] - a[2])))

    def summary(self) -> ErrorSummary:
        position = sorted(self.position_m)
        heading = sorted(self.heading_rad)
        if not position:
            return ErrorSummary(0, math.nan, math.nan, math.nan, math.nan)
        return ErrorSummary(len(position), 100.0 * percentile(position, 0.5), 100.0 * percentile(position, 0.95),
                            100.0 * position[-1], math.degrees(percentile(heading, 0.5)))


def merged(parts: List[LocalizationErrors]) -> LocalizationErrors:
    """One collection holding every paired error of ``parts`` (several robots of one run)."""
    out = LocalizationErrors()
    for part in parts:
        out.position_m.extend(part.position_m)
        out.heading_rad.extend(part.heading_rad)
    return out
