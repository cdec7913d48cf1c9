"""Adaptive (KLD-sampling) Monte Carlo localization on a known occupancy grid, without ROS (an AMCL-class
filter: odometry motion model, likelihood-field laser model, Augmented MCL recovery).

- :mod:`~flex_nav.localization.params`           FilterParams (amcl's parameter names), validated once
- :mod:`~flex_nav.localization.scan`             ScanBeams, the choice of the beams an update uses
- :mod:`~flex_nav.localization.motion_model`     amcl's diff-corrected odometry model, vectorised
- :mod:`~flex_nav.localization.likelihood_field` distance to the nearest obstacle per cell (exact EDT)
- :mod:`~flex_nav.localization.sensor_model`     particles x beams likelihood (numba, and a numpy reference)
- :mod:`~flex_nav.localization.kld`              KLD-sampling bound and bins
- :mod:`~flex_nav.localization.resampling`       low-variance resampling
- :mod:`~flex_nav.localization.recovery`         w_slow / w_fast averages of Augmented MCL
- :mod:`~flex_nav.localization.free_space`       uniform poses over free cells
- :mod:`~flex_nav.localization.estimate`         Estimate, LocalizerStatus, weighted mean and covariance
- :mod:`~flex_nav.localization.consistency`      do the scans fit the estimate: the match fraction behind LOST
- :mod:`~flex_nav.localization.pose_search`      the whole map searched for poses that fit a scan as well
- :mod:`~flex_nav.localization.hypotheses`       rival poses tracked until the scans tell them apart
- :mod:`~flex_nav.localization.roughening`       jitter on no-motion updates, so a still cloud does not collapse
- :mod:`~flex_nav.localization.localizer`        Localizer, the filter
- :mod:`~flex_nav.localization.jit`              numba with an on-disk cache where it can; Kernel (numba or numpy)
"""

from __future__ import annotations

from flex_nav.localization.estimate import Estimate, LocalizerStatus
from flex_nav.localization.jit import Kernel
from flex_nav.localization.localizer import Localizer
from flex_nav.localization.params import FilterParams
from flex_nav.localization.scan import ScanBeams
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.planar import Pose2D

__all__ = ["Estimate", "FilterParams", "GridMap", "Kernel", "Localizer", "LocalizerStatus", "Pose2D", "ScanBeams"]
