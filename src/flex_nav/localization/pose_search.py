"""Which other poses on the map explain a scan as well as the estimate? An exhaustive search over the free space.

A particle filter converging from particles everywhere (global localization) settles on whichever good pose its
particles happened to land near first. Where the map repeats itself (a room symmetric about its centre, two
identical doors), the other pose that fits as well may never have been sampled closely enough to compete, and the
cloud then converges, tight and matching every beam, on the wrong one: the checks of ``consistency`` cannot tell,
because the scan does fit there. The search looks where the particles did not:

1. coarse: every free position on a lattice of ``stride`` [m] (at least ``CLEARANCE`` [m] from an obstacle;
   the stride is widened on large maps so that at most ``MAX_POSITIONS`` positions are scored) times
   ``HEADINGS`` headings, each scored with the sensor model at a Gaussian about as wide as the lattice's step;
2. the best-scoring poses that are distinct (``DISTINCT_XY`` [m] apart or ``DISTINCT_YAW`` [rad] turned, from the
   estimate and from each other), at most ``CANDIDATES`` of them, are refined by a local search (:func:`refine`:
   coordinate steps, coarse Gaussian to laser_sigma_hit) and scored at laser_sigma_hit, as the estimate is.

Every candidate scoring within a margin of the estimate is an alternative. The search is exhaustive rather than
randomised so that it finds the same alternatives every time; on the lab map (8.5 x 6.5 m at 5 cm) it scores
about 300 000 poses (the cost is printed by ``bench/bench_localization.py``). It is run only when a lost filter is
about to report itself localized, not every update.
"""

from __future__ import annotations

import math
from typing import List, NamedTuple, Sequence

import numpy as np

from flex_nav.localization.jit import Kernel
from flex_nav.localization.scan import SelectedBeams
from flex_nav.localization.sensor_model import SensorModel
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.planar import Pose2D

STRIDE = 0.1  # [m] lattice step of the coarse search (widened on large maps)
HEADINGS = 72  # headings of the coarse search (5 deg apart)
CLEARANCE = 0.1  # [m] positions closer than this to an obstacle are not searched
MAX_POSITIONS = 20_000  # lattice positions scored at most (the stride grows until they fit)
CANDIDATES = 6  # distinct poses refined after the coarse pass ...
SCANNED = 20_000  # ... picked from this many best-scoring lattice poses
DISTINCT_XY = 0.5  # [m] two poses this far apart ...
DISTINCT_YAW = math.radians(30.0)  # [rad] ... or turned this far from each other are different hypotheses
# the local search: (Gaussian width as a multiple of laser_sigma_hit, position step [m], heading step [rad])
REFINE_STAGES = ((4.0, 0.04, math.radians(2.0)), (2.0, 0.02, math.radians(1.0)), (1.0, 0.01, math.radians(0.5)))
REFINE_ITERATIONS = 12  # steps per stage at most


class ScoredPose(NamedTuple):
    pose: Pose2D  # [m, m, rad] map frame
    score: float  # tempered log-likelihood of the scan at laser_sigma_hit


def distinct(a: Pose2D, b: Pose2D) -> bool:
    """True when ``a`` and ``b`` are different hypotheses: DISTINCT_XY apart or DISTINCT_YAW turned."""
    return math.hypot(a[0] - b[0], a[1] - b[1]) >= DISTINCT_XY or abs(wrap_angle(a[2] - b[2])) >= DISTINCT_YAW


def refine(
    model: SensorModel, pose: Pose2D, beams: SelectedBeams, range_max: float, *, kernel: Kernel = Kernel.NUMBA,
    stages: Sequence[Sequence[float]] = REFINE_STAGES,
) -> ScoredPose:
    """The pose near ``pose`` that fits the scan best, by a coordinate search (x, y, yaw steps, then half steps,
    with the sensor model's Gaussian narrowing to laser_sigma_hit), and its score at laser_sigma_hit."""
    sigma_hit = model.params.laser_sigma_hit
    x, y, yaw = pose
    for width, step_xy, step_yaw in stages:
        sigma = width * sigma_hit
        for _ in range(REFINE_ITERATIONS):
            probes = np.array([
                (x, y, yaw), (x + step_xy, y, yaw), (x - step_xy, y, yaw), (x, y + step_xy, yaw),
                (x, y - step_xy, yaw), (x, y, yaw + step_yaw), (x, y, yaw - step_yaw),
            ])
            scores = model.log_likelihoods(probes, beams, range_max, sigma, kernel)
            best = int(np.argmax(scores))
            if best == 0:
                break
            x, y, yaw = (float(v) for v in probes[best])
    score = float(model.log_likelihoods(np.array([(x, y, yaw)]), beams, range_max, None, kernel)[0])
    return ScoredPose((x, y, wrap_angle(yaw)), score)


class PoseSearch:
    """The coarse lattice of one map (positions fixed at construction) and the search over it."""

    def __init__(self, model: SensorModel) -> None:
        self.model = model
        field = model.field
        grid = field.grid
        free = field.known & ~field.occupied & (field.distance >= CLEARANCE)
        step = max(1, round(STRIDE / grid.resolution))
        while True:
            rows, cols = np.nonzero(free[step // 2::step, step // 2::step])
            if rows.size <= MAX_POSITIONS:
                break
            step += 1
        self.stride = step * grid.resolution  # [m]
        xs, ys = grid.cells_to_world(rows * step + step // 2, cols * step + step // 2)
        self.positions = np.column_stack([xs, ys])  # (P, 2) [m] map frame, cell centres
        self.headings = np.linspace(-math.pi, math.pi, HEADINGS, endpoint=False)  # [rad]
        sigma_hit = model.params.laser_sigma_hit
        self.coarse_sigma = sigma_hit * 2.0 ** max(0, math.ceil(math.log2(self.stride / sigma_hit)))  # [m]

    @property
    def pose_count(self) -> int:
        """Poses scored by one coarse pass."""
        return int(self.positions.shape[0]) * HEADINGS

    def alternatives(
        self, beams: SelectedBeams, range_max: float, estimate: ScoredPose, margin: float,
        kernel: Kernel = Kernel.NUMBA,
    ) -> List[ScoredPose]:
        """The refined poses distinct from ``estimate`` (and from each other) whose score is at least
        ``estimate.score - margin``, best first; empty when the scan singles the estimate out."""
        count = self.positions.shape[0]
        if count == 0 or beams.x.size == 0:
            return []
        scores = np.empty((HEADINGS, count))
        poses = np.empty((count, 3))
        poses[:, :2] = self.positions
        for index, heading in enumerate(self.headings):
            poses[:, 2] = heading
            scores[index] = self.model.log_likelihoods(poses, beams, range_max, self.coarse_sigma, kernel)
        flat_scores = scores.ravel()
        top = np.argpartition(flat_scores, -min(SCANNED, flat_scores.size))[-SCANNED:]
        picked: List[Pose2D] = []
        for flat in top[np.argsort(flat_scores[top])[::-1]]:
            heading_index, position_index = divmod(int(flat), count)
            x, y = self.positions[position_index]
            pose = (float(x), float(y), float(self.headings[heading_index]))
            if distinct(pose, estimate.pose) and all(distinct(pose, other) for other in picked):
                picked.append(pose)
                if len(picked) == CANDIDATES:
                    break
        found = sorted((refine(self.model, pose, beams, range_max, kernel=kernel) for pose in picked),
                       key=lambda candidate: -candidate.score)
        close: List[ScoredPose] = []
        for candidate in found:  # two candidates may refine to one pose, or to the estimate's
            if candidate.score >= estimate.score - margin and all(
                distinct(candidate.pose, other.pose) for other in (estimate, *close)
            ):
                close.append(candidate)
        return close
