"""Adaptive Monte Carlo localization on a known occupancy grid: the filter that ties the pieces together.

One update (when a scan comes and the robot has moved ``update_min_d`` or turned ``update_min_a`` since the
last one, or a no-motion update was asked for):

1. resample, if the previous update left that due (every ``resample_interval`` sensor updates): KLD-sampling
   sets the count, low-variance resampling draws the particles, and Augmented MCL replaces some with random
   poses in free space when the scans have lately fitted worse than in the long run;
2. move every particle by the odometry since the last update (``motion_model``); on a no-motion update (the
   robot has not moved past the thresholds) jitter the resampled particles instead (``roughening``), so that a
   cloud standing still does not collapse onto one pose;
3. weight every particle by the likelihood of the scan (``sensor_model``; the Gaussian widened while the cloud
   is wide, the update tempered where it would leave too few effective particles: ``weighting``), and derive
   the estimate from the weighted cloud (``estimate``) and the status from its spread and from how well the
   scans fit the estimate (``consistency``).

Resampling at the start of the next update rather than at the end of this one (the order of Probabilistic
Robotics' MCL) leaves the weighted cloud in place between updates: the estimate is the weighted mean, which
resampling would only blur, and ``particles``/``weights`` are the set the estimate comes from.

Not thread-safe: a node calls it from one thread (or holds a lock). Deterministic for a given seed, inputs and
call sequence (one numpy Generator draws every random number).
"""

from __future__ import annotations

import math
import time
from typing import List, Optional

import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.localization import kld
from flex_nav.localization.consistency import (
    CONVERGED_CLEAR_FRACTION,
    MatchHistory,
    clear_fraction,
    distinct_fit,
    match_fraction,
)
from flex_nav.localization.estimate import (
    CONVERGED_FRACTION,
    Estimate,
    LocalizerStatus,
    spread_xy,
    weighted_mean_and_covariance,
)
from flex_nav.localization.free_space import FreeSpace
from flex_nav.localization.hypotheses import Hypotheses
from flex_nav.localization.jit import Kernel
from flex_nav.localization.likelihood_field import LikelihoodField
from flex_nav.localization.motion_model import decompose, sample_motion
from flex_nav.localization.params import FilterParams
from flex_nav.localization.pose_search import PoseSearch, ScoredPose, distinct, refine
from flex_nav.localization.recovery import RecoveryAverages
from flex_nav.localization.resampling import low_variance_indices
from flex_nav.localization.roughening import roughen
from flex_nav.localization.scan import ScanBeams, SelectedBeams, select_beams
from flex_nav.localization.sensor_model import SensorModel, annealed_sigma
from flex_nav.localization.weighting import reweigh
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.planar import Pose2D, compose_poses, inverse_pose

_SYMMETRY_TOLERANCE = 1e-9  # relative, for the covariance given to set_pose
_PSD_TOLERANCE = 1e-12  # relative: eigenvalues down to -this * largest count as 0 (rounding)
AMBIGUITY_MARGIN = 10.0  # [-] tempered log-likelihood: another pose fitting the scans within this is a rival
RESEED_STD = (0.05, 0.05, 0.05)  # [m, m, rad] the cloud restarted on the pose the scans chose among rivals


class Localizer:
    """KLD-sampling Monte Carlo localization; see the module docstring. ``kernel`` picks the implementation of the
    hot loops (sensor model, motion model, estimate): the compiled one, or the plain-numpy twins the benchmark
    compares it with (same maths, same results)."""

    def __init__(
        self, params: FilterParams, grid: GridMap, seed: Optional[int] = None, *, kernel: Kernel = Kernel.NUMBA
    ) -> None:
        self.params = params
        self.kernel = kernel
        self._rng = np.random.default_rng(seed)
        self._alphas = (params.odom_alpha1, params.odom_alpha2, params.odom_alpha3, params.odom_alpha4)
        self._recovery = RecoveryAverages(params.recovery_alpha_slow, params.recovery_alpha_fast)
        self._particles = np.empty((0, 3))
        self._weights = np.empty(0)
        self._uniform = True  # all weights 1/N (after a start or a resampling)
        self._status = LocalizerStatus.UNINITIALIZED
        self._estimate = Estimate((0.0, 0.0, 0.0), np.zeros((3, 3)), 0, self._status)
        self._odom_filter: Optional[Pose2D] = None  # odometry pose the particles belong to
        self._odom_latest: Optional[Pose2D] = None  # odometry pose of the latest update() call
        self._force_update = False  # run the sensor model at the next scan even without motion
        self._sensor_updates = 0  # since the last resampling
        self._resample_due = False
        self._last_dropped = 0
        self._matches = MatchHistory(params.lost_match_updates)
        self._last_match = math.nan
        self._hypotheses = Hypotheses(AMBIGUITY_MARGIN)
        self.set_map(grid)

    # --- set-up ------------------------------------------------------------------------------------------------
    def set_map(self, grid: GridMap) -> None:
        """Use ``grid`` from now on: rebuilds the likelihood field and the free-space sampler; particles kept."""
        self.grid = grid
        self.field = LikelihoodField(grid, self.params.laser_likelihood_max_dist)
        self.sensor_model = SensorModel(self.params, self.field)
        self.free_space = FreeSpace(grid)
        self.pose_search = PoseSearch(self.sensor_model)
        self._hypotheses.clear()
        self._recovery.reset()
        self._matches.clear()  # fractions measured on the old map

    def reseed(self, seed: int) -> None:
        """Draw every later random number from a generator started afresh from ``seed``."""
        self._rng = np.random.default_rng(seed)

    def set_pose(self, pose: Pose2D, covariance: np.ndarray) -> None:
        """Start from a Gaussian cloud around ``pose`` (map frame) for the robot where the latest odometry given to
        :meth:`update` has it: KLD-sampling picks the count (at least min_particles; a wide cloud gets up to
        max_particles). :class:`ConfigError` for a non-finite pose or a covariance that is not a finite,
        symmetric, positive semi-definite (3, 3) matrix over x [m], y [m], yaw [rad]."""
        mean = validation.planar_pose("localization", "set_pose: pose", pose)
        root = _covariance_root(covariance)
        p = self.params
        draws = mean + self._rng.standard_normal((p.max_particles, 3)) @ root.T
        draws[:, 2] = np.arctan2(np.sin(draws[:, 2]), np.cos(draws[:, 2]))
        count = kld.sample_count(kld.bin_keys(draws), p.kld_err, p.kld_z, p.min_particles, p.max_particles)
        self._hypotheses.clear()
        self._start(draws[:count], LocalizerStatus.LOCALIZED)

    def global_localization(self) -> None:
        """Start from max_particles poses uniform over the free cells, with uniform headings. The status is LOST
        until the cloud has converged on a pose that no other pose of the map rivals (``pose_search``,
        ``hypotheses``)."""
        self._hypotheses.clear()
        self._start(self.free_space.sample(self.params.max_particles, self._rng), LocalizerStatus.LOST)

    def restart_odometry(self) -> None:
        """Forget the odometry the particles belong to (time went back, the odometry source restarted): the next
        :meth:`update` only stores its odometry, so no motion is applied across the break."""
        self._odom_filter = None

    def request_nomotion_update(self) -> None:
        """Make the next :meth:`update` with a scan run the sensor model even if the robot has not moved."""
        self._force_update = True

    # --- the filter ---------------------------------------------------------------------------------------------
    def update(self, odom: Pose2D, scan: Optional[ScanBeams]) -> bool:
        """Take the robot's odometry pose ``odom`` (odom frame) and, if there is one, a scan taken there. The first
        call only stores the odometry; a call without a scan changes nothing but the odometry a later
        :meth:`set_pose` refers to. Returns True when the filter ran a sensor update (the estimate is then for
        ``odom``). :class:`ConfigError` for a non-finite odometry pose or a malformed scan."""
        odom = validation.planar_pose("localization", "update: odom", odom)
        self._odom_latest = odom
        if self._odom_filter is None or self._status is LocalizerStatus.UNINITIALIZED:
            self._odom_filter = odom
            return False
        if scan is None:
            return False
        motion = decompose(self._odom_filter, odom)
        p = self.params
        moved = motion.trans > p.update_min_d or abs(wrap_angle(odom[2] - self._odom_filter[2])) > p.update_min_a
        if not (moved or self._force_update):
            return False
        beams = select_beams(scan, p.laser_max_beams)
        self._last_dropped = beams.dropped
        sigma = annealed_sigma(p.laser_sigma_hit, spread_xy(self._estimate.covariance))
        resampled = self._resample_due
        if resampled:
            self._resample()
        sample_motion(self._particles, motion, self._alphas, self._rng, self.kernel)
        if resampled and not moved:
            roughen(self._particles, sigma, self._rng)
        odom_step = compose_poses(inverse_pose(self._odom_filter), odom)  # in the robot's frame
        self._odom_filter = odom
        if beams.x.size == 0:  # nothing to weigh with: the motion is applied, the sensor update waits
            return False
        log_likelihood = self.sensor_model.log_likelihoods(
            self._particles, beams, float(scan.range_max), sigma, self.kernel
        )
        self._weights, log_mean = reweigh(self._weights, log_likelihood, self._uniform, sigma > p.laser_sigma_hit)
        self._uniform = False
        self._recovery.observe(log_mean)
        self._force_update = False
        self._sensor_updates += 1
        if self._sensor_updates >= p.resample_interval:
            self._resample_due = True
        self._refresh_estimate(beams, float(scan.range_max), odom_step)
        return True

    def estimate(self) -> Estimate:
        """The weighted mean pose, covariance, particle count and status (pose (0, 0, 0) and a zero covariance while
        UNINITIALIZED)."""
        e = self._estimate
        return Estimate(e.pose, e.covariance.copy(), e.particle_count, e.status)

    @property
    def particles(self) -> np.ndarray:
        """(N, 3) ``[x [m], y [m], yaw [rad]]`` in the map frame, a read-only view."""
        view = self._particles.view()
        view.flags.writeable = False
        return view

    @property
    def weights(self) -> np.ndarray:
        """(N,) normalised weights of :attr:`particles` (a read-only view)."""
        view = self._weights.view()
        view.flags.writeable = False
        return view

    @property
    def last_dropped_beams(self) -> int:
        """Beams of the last update's scan dropped as invalid (NaN, inf, out of range)."""
        return self._last_dropped

    @property
    def status(self) -> LocalizerStatus:
        return self._status

    @property
    def rivals(self) -> List[ScoredPose]:
        """While a lost filter's cloud has converged on a pose that other poses of the map rival (they fit the scans
        as well, within AMBIGUITY_MARGIN): every such pose with its accumulated score, best first; else empty."""
        return self._hypotheses.tracked if self._hypotheses.active else []

    @property
    def match_fraction(self) -> float:
        """Share of the last sensor update's beams that fit the map from its estimate (``consistency``); NaN before
        the first update after a start."""
        return self._last_match

    @property
    def match_fraction_mean(self) -> float:
        """Mean match fraction over the consecutive updates of a tight cloud that the status is judged on (up to
        ``lost_match_updates`` of them); NaN when there are none (the cloud is wide, or no update yet)."""
        return self._matches.mean()

    # --- internals ----------------------------------------------------------------------------------------------
    def _start(self, particles: np.ndarray, status: LocalizerStatus) -> None:
        self._particles = np.ascontiguousarray(particles, dtype=np.float64)
        self._weights = np.full(len(particles), 1.0 / len(particles))
        self._uniform = True
        self._status = status
        self._odom_filter = self._odom_latest
        self._force_update = True  # the first scan after a new start is weighed even if the robot stands still
        self._sensor_updates = 0
        self._resample_due = False
        self._recovery.reset()
        self._matches.clear()
        self._last_match = math.nan
        self._refresh_estimate()  # a pose given is trusted until the scans have had a say

    def _resample(self) -> None:
        p = self.params
        weights = self._weights
        count = p.max_particles
        if p.min_particles < p.max_particles:
            # KLD: count the bins of a proportional sample in random order, then draw that many, low-variance
            candidates = low_variance_indices(weights, p.max_particles, self._rng)
            keys = kld.bin_keys(self._particles[candidates[self._rng.permutation(candidates.size)]])
            count = kld.sample_count(keys, p.kld_err, p.kld_z, p.min_particles, p.max_particles)
        injection = self._recovery.injection_probability()
        random_count = int(self._rng.binomial(count, injection)) if injection > 0.0 else 0
        kept = self._particles[low_variance_indices(weights, count - random_count, self._rng)]
        if random_count:
            kept = np.vstack([kept, self.free_space.sample(random_count, self._rng)])
            self._recovery.reset()
        self._particles = np.ascontiguousarray(kept)
        self._weights = np.full(count, 1.0 / count)
        self._uniform = True
        self._sensor_updates = 0
        self._resample_due = False

    def _refresh_estimate(
        self, beams: Optional[SelectedBeams] = None, range_max: float = math.inf, odom_step: Pose2D = (0.0, 0.0, 0.0)
    ) -> None:
        """The estimate of the current weighted cloud; after a sensor update with ``beams`` (taken ``odom_step`` on
        from the previous update's), the status too.

        LOCALIZED -> LOST when the spread exceeds lost_std_xy, or when the scans have stopped fitting the estimate
        (mean match fraction of ``lost_match_updates`` consecutive updates of a tight cloud below
        lost_match_fraction). LOST -> LOCALIZED when the spread is down to ``CONVERGED_FRACTION * lost_std_xy`` and
        the mean match fraction of as many updates reaches converged_match_fraction, the scan fits the estimate
        distinctly better than the poses around it (``consistency.distinct_fit``), its rays do not pass through
        walls (``consistency.clear_fraction``), and no other pose of the map rivals it
        (:meth:`_chosen_among_rivals`)."""
        p = self.params
        pose, covariance = weighted_mean_and_covariance(self._particles, self._weights, self.kernel)
        spread = spread_xy(covariance)
        if beams is not None:
            self._last_match = match_fraction(self.field, pose, beams, p.lost_match_distance)
            tight = spread <= CONVERGED_FRACTION * p.lost_std_xy
            if tight and math.isfinite(self._last_match):
                self._matches.add(self._last_match)
            else:
                self._matches.clear()
            judged = self._matches.full
            fit = self._matches.mean()
            if self._status is LocalizerStatus.LOCALIZED:
                if spread > p.lost_std_xy or (judged and fit < p.lost_match_fraction):
                    self._status = LocalizerStatus.LOST
            elif self._status is LocalizerStatus.LOST:
                self._hypotheses.observe(odom_step, self.sensor_model, beams, range_max, self.kernel)
                if (
                    tight and judged and fit >= p.converged_match_fraction
                    and distinct_fit(self.sensor_model, pose, beams, range_max, self.kernel)
                    and clear_fraction(self.field, pose, beams, p.lost_match_distance) >= CONVERGED_CLEAR_FRACTION
                ):
                    chosen = self._chosen_among_rivals(pose, beams, range_max)
                    if chosen is not None and distinct(chosen, pose):
                        self._restart_around(chosen)  # the cloud sits on a pose the scans have ruled out
                        return
                    if chosen is not None:
                        self._status = LocalizerStatus.LOCALIZED
                        self._hypotheses.clear()
        self._estimate = Estimate(pose, covariance, len(self._particles), self._status)

    def _chosen_among_rivals(self, pose: Pose2D, beams: SelectedBeams, range_max: float) -> Optional[Pose2D]:
        """(LOST, the cloud converged on ``pose``) The pose the scans single out: ``pose`` itself when no other pose
        of the map explains them as well; None while rivals are still in the running.

        The first time: ``pose_search`` looks for poses distinct from ``pose`` fitting this scan within
        AMBIGUITY_MARGIN (and whose rays do not cross walls); with none, ``pose`` is chosen. With some, all are
        tracked (``hypotheses``) from then on, each update, until one leads every other by the margin: that one is
        chosen, wherever the cloud is."""
        p = self.params
        if not self._hypotheses.tracked:
            estimate = refine(self.sensor_model, pose, beams, range_max, kernel=self.kernel)
            rivals = [
                rival for rival in self.pose_search.alternatives(beams, range_max, estimate, AMBIGUITY_MARGIN,
                                                                 self.kernel)
                if clear_fraction(self.field, rival.pose, beams, p.lost_match_distance) >= CONVERGED_CLEAR_FRACTION
            ]
            self._hypotheses.start([estimate, *rivals])
        if self._hypotheses.active:
            return None
        leader = self._hypotheses.leader.pose
        return pose if not distinct(leader, pose) else leader

    def _restart_around(self, pose: Pose2D) -> None:
        """Restart the cloud (as many particles) around ``pose``, RESEED_STD wide; still LOST: the usual checks
        follow."""
        draws = np.asarray(pose) + self._rng.standard_normal((len(self._particles), 3)) * np.asarray(RESEED_STD)
        draws[:, 2] = np.arctan2(np.sin(draws[:, 2]), np.cos(draws[:, 2]))
        self._start(draws, LocalizerStatus.LOST)


def _covariance_root(covariance: np.ndarray) -> np.ndarray:
    """A (3, 3) matrix R with R R^T = ``covariance``; ConfigError unless it is finite, symmetric and PSD."""
    try:
        cov = np.array(covariance, dtype=np.float64)
    except (TypeError, ValueError) as err:
        raise ConfigError(f"localization: set_pose: covariance must be a (3, 3) matrix of numbers: {err}") from err
    if cov.shape != (3, 3):
        raise ConfigError(f"localization: set_pose: covariance must be (3, 3) over x, y, yaw, got shape {cov.shape}")
    if not np.isfinite(cov).all():
        raise ConfigError(f"localization: set_pose: covariance must be finite, got {cov.tolist()}")
    scale = max(float(np.abs(cov).max()), 1e-300)
    if float(np.abs(cov - cov.T).max()) > _SYMMETRY_TOLERANCE * scale:
        raise ConfigError(f"localization: set_pose: covariance must be symmetric, got {cov.tolist()}")
    values, vectors = np.linalg.eigh(0.5 * (cov + cov.T))
    if float(values.min()) < -_PSD_TOLERANCE * scale:
        raise ConfigError(
            f"localization: set_pose: covariance must be positive semi-definite (smallest eigenvalue "
            f"{float(values.min()):.3g}), got {cov.tolist()}"
        )
    return np.asarray(vectors * np.sqrt(np.maximum(values, 0.0)))


def warm_up() -> float:
    """Run every compiled kernel of the localizer once on a tiny map, so that numba compiles them into its cache
    (or loads them from it); returns the wall time it took [s]. For an installer's warm-up step."""
    started = time.monotonic()
    occupancy = np.zeros((20, 20), dtype=np.int8)
    occupancy[0, :] = 100
    localizer = Localizer(FilterParams(min_particles=10, max_particles=20), GridMap(occupancy, 0.1), seed=0)
    localizer.update((0.0, 0.0, 0.0), None)
    localizer.set_pose((1.0, 1.0, 0.0), np.diag([0.01, 0.01, 0.01]))
    scan = ScanBeams(np.full(5, 1.0), np.linspace(-2.0, -1.0, 5), (0.0, 0.0, 0.0), 0.1, 5.0)
    localizer.update((0.0, 0.0, 0.0), scan)
    localizer.update((0.2, 0.0, 0.0), scan)
    return time.monotonic() - started
