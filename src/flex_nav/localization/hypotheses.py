"""Several poses explain the scans: keep them all until the scans tell them apart (a sequential likelihood-ratio
test).

When the search of ``pose_search`` finds poses other than the estimate that fit the scan within ``margin``
(tempered log-likelihood), the filter does not report itself localized. It tracks every such pose instead: after
each sensor update each hypothesis is moved by the odometry, refined to the scan (``pose_search.refine``, the
fine stage only) and its score is added to its total. A hypothesis whose total falls ``margin`` behind the
leader's is dropped; one left means the scans have told them apart (the likelihood ratio of the survivor to every
other is at least e^margin). In a scene that is truly the same from two poses no evidence comes, and both stay: the
robot is reported lost (ambiguous) until it moves somewhere that tells them apart or is given a pose.
"""

from __future__ import annotations

from typing import List, Sequence

from flex_nav.localization.jit import Kernel
from flex_nav.localization.pose_search import REFINE_STAGES, ScoredPose, distinct, refine
from flex_nav.localization.scan import SelectedBeams
from flex_nav.localization.sensor_model import SensorModel
from flex_nav.nav.planar import Pose2D, compose_poses

TRACKING_STAGES = REFINE_STAGES[-2:]  # a hypothesis moved by the odometry is at most a few cm off


class Hypotheses:
    """The poses still in the running and their accumulated scores; empty when there is no ambiguity to resolve."""

    def __init__(self, margin: float) -> None:
        self.margin = margin  # [-] tempered log-likelihood
        self._poses: List[Pose2D] = []
        self._totals: List[float] = []

    def start(self, candidates: Sequence[ScoredPose]) -> None:
        """Track ``candidates`` (the estimate and its alternatives), each starting from its score."""
        self._poses = [candidate.pose for candidate in candidates]
        self._totals = [candidate.score for candidate in candidates]
        self._drop_trailing()

    def clear(self) -> None:
        self._poses, self._totals = [], []

    @property
    def active(self) -> bool:
        """True while two or more hypotheses are still in the running."""
        return len(self._poses) > 1

    @property
    def tracked(self) -> List[ScoredPose]:
        """The hypotheses with their accumulated scores, best first."""
        order = sorted(range(len(self._poses)), key=lambda index: -self._totals[index])
        return [ScoredPose(self._poses[index], self._totals[index]) for index in order]

    @property
    def leader(self) -> ScoredPose:
        """The hypothesis with the best total; IndexError when none is tracked."""
        return self.tracked[0]

    def observe(
        self, motion: Pose2D, model: SensorModel, beams: SelectedBeams, range_max: float,
        kernel: Kernel = Kernel.NUMBA,
    ) -> None:
        """Move every hypothesis by ``motion`` (the odometry since the last update, in the robot's frame), refine it
        to the scan, add its score; drop the ones ``margin`` behind the leader."""
        if not self._poses:
            return
        updated = [
            refine(model, compose_poses(pose, motion), beams, range_max, kernel=kernel, stages=TRACKING_STAGES)
            for pose in self._poses
        ]
        self._poses = [scored.pose for scored in updated]
        self._totals = [total + scored.score for total, scored in zip(self._totals, updated)]
        self._drop_trailing()

    def _drop_trailing(self) -> None:
        """Drop the hypotheses ``margin`` behind the leader, and any that has come to the same pose as a better one
        (two refined to one local optimum)."""
        kept: List[int] = []
        best = max(self._totals, default=0.0)
        for index in sorted(range(len(self._totals)), key=lambda i: -self._totals[i]):
            if self._totals[index] >= best - self.margin and all(
                distinct(self._poses[index], self._poses[other]) for other in kept
            ):
                kept.append(index)
        self._poses = [self._poses[index] for index in kept]
        self._totals = [self._totals[index] for index in kept]
