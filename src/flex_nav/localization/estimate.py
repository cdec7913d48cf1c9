"""What the localizer reports: a status, and the pose with its covariance from the weighted particles.

The spread of the cloud, the standard deviation along its widest horizontal direction (the square root of the
larger eigenvalue of the weighted x/y covariance), and how well the scans fit the estimate
(:mod:`~flex_nav.localization.consistency`) decide the status after every sensor update: above ``lost_std_xy``, or
with the scans no longer fitting, a localized filter is LOST; a lost one (after global localization, or recovered
by random particles) is LOCALIZED again once the spread is down to ``CONVERGED_FRACTION * lost_std_xy`` (a margin,
so that the status does not flicker at the threshold) and the scans fit the estimate well and distinctly. A pose
given by ``set_pose`` is LOCALIZED whatever its covariance until the sensor updates have weighed it; global
localization starts LOST.
"""

from __future__ import annotations

import enum
import math
from typing import NamedTuple, Tuple

import numpy as np

from flex_nav.localization.jit import Kernel, cached_njit
from flex_nav.nav.planar import Pose2D

CONVERGED_FRACTION = 0.25  # [-] a lost filter is localized again at this fraction of lost_std_xy
_TWO_PI = 2.0 * math.pi


class LocalizerStatus(enum.Enum):
    UNINITIALIZED = "uninitialized"  # no pose given and no global localization asked for yet
    LOCALIZED = "localized"  # the estimate can be used
    LOST = "lost"  # the cloud is spread wider than lost_std_xy, the scans do not fit it, or it is still converging


class Estimate(NamedTuple):
    pose: Pose2D  # weighted mean (circular mean for yaw)
    covariance: np.ndarray  # (3,3) over x [m], y [m], yaw [rad]
    particle_count: int
    status: LocalizerStatus


def weighted_mean_and_covariance(
    particles: np.ndarray, weights: np.ndarray, kernel: Kernel = Kernel.NUMBA
) -> Tuple[Pose2D, np.ndarray]:
    """Weighted mean pose (circular mean of the yaws) and the (3, 3) weighted covariance about it (yaw
    deviations wrapped into [-pi, pi]) of particles ``[x [m], y [m], yaw [rad]]`` with normalised ``weights``."""
    moments = (moments_numba if kernel is Kernel.NUMBA else moments_numpy)(particles, weights)
    mean = (float(moments[0]), float(moments[1]), float(moments[2]))
    covariance = np.array([[moments[3], moments[4], moments[5]], [moments[4], moments[6], moments[7]],
                           [moments[5], moments[7], moments[8]]])
    return mean, covariance


@cached_njit
def moments_numba(particles: np.ndarray, weights: np.ndarray) -> np.ndarray:  # pragma: no cover  (compiled)
    """(9,): mean x, y, yaw, then the covariance's xx, xy, x-yaw, yy, y-yaw, yaw-yaw (see :func:`moments_numpy`)."""
    mean_x = mean_y = sin_sum = cos_sum = 0.0
    for i in range(weights.shape[0]):
        w = weights[i]
        mean_x += w * particles[i, 0]
        mean_y += w * particles[i, 1]
        sin_sum += w * math.sin(particles[i, 2])
        cos_sum += w * math.cos(particles[i, 2])
    mean_yaw = math.atan2(sin_sum, cos_sum)
    out = np.zeros(9)
    out[0], out[1], out[2] = mean_x, mean_y, mean_yaw
    for i in range(weights.shape[0]):
        w = weights[i]
        dx = particles[i, 0] - mean_x
        dy = particles[i, 1] - mean_y
        da = particles[i, 2] - mean_yaw
        da -= _TWO_PI * math.floor((da + math.pi) / _TWO_PI)
        out[3] += w * dx * dx
        out[4] += w * dx * dy
        out[5] += w * dx * da
        out[6] += w * dy * dy
        out[7] += w * dy * da
        out[8] += w * da * da
    return out


def moments_numpy(particles: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """:func:`moments_numba` in plain numpy."""
    mean_x = float(weights @ particles[:, 0])
    mean_y = float(weights @ particles[:, 1])
    mean_yaw = math.atan2(float(weights @ np.sin(particles[:, 2])), float(weights @ np.cos(particles[:, 2])))
    dx = particles[:, 0] - mean_x
    dy = particles[:, 1] - mean_y
    da = particles[:, 2] - mean_yaw
    da -= _TWO_PI * np.floor((da + math.pi) / _TWO_PI)
    wx, wy = weights * dx, weights * dy
    return np.array([mean_x, mean_y, mean_yaw, wx @ dx, wx @ dy, wx @ da, wy @ dy, wy @ da, (weights * da) @ da])


def spread_xy(covariance: np.ndarray) -> float:
    """Standard deviation [m] along the widest horizontal direction of ``covariance`` (x/y block)."""
    xx, xy, yy = float(covariance[0, 0]), float(covariance[0, 1]), float(covariance[1, 1])
    half_trace = 0.5 * (xx + yy)
    largest = half_trace + math.sqrt(max(0.25 * (xx - yy) ** 2 + xy * xy, 0.0))
    return math.sqrt(max(largest, 0.0))
