"""Roughening: jitter for a cloud that does not move, so that resampling cannot collapse it onto one pose.

The odometry motion model spreads the particles in proportion to the motion; standing still (no-motion updates,
e.g. a global localization with the robot stopped) it spreads them not at all, and resampling at every scan then
copies the best few particles until the cloud is a handful of identical poses, wherever they are, and its spread
says "converged". Roughening (Gordon, Salmond and Smith 1993, "Novel approach to nonlinear/non-Gaussian Bayesian
state estimation", IEE Proc. F 140(2), section 4) adds a small independent jitter to every resampled particle.
Here the jitter follows the sensor model's current Gaussian width (the annealed sigma, which is wide while the
cloud is wide and laser_sigma_hit once it has converged): ``ROUGHENING_GAIN * sigma`` in x and y, and that over
``ROUGHENING_LEVER`` in heading (the turn that moves a beam end point at that distance as far). The cloud keeps
exploring around its modes at the resolution the scans can still tell apart, and the weighted mean, not any one
particle, is the estimate.
"""

from __future__ import annotations

import numpy as np

ROUGHENING_GAIN = 0.5  # [-] jitter std in x and y as a fraction of the sensor model's sigma
ROUGHENING_LEVER = 1.0  # [m] heading jitter = xy jitter / this [rad]


def roughen(particles: np.ndarray, sigma: float, rng: np.random.Generator) -> None:
    """Add Gaussian jitter in place to ``particles`` ``[x [m], y [m], yaw [rad]]`` for a sensor model of std
    ``sigma`` [m] (headings wrapped into [-pi, pi])."""
    std_xy = ROUGHENING_GAIN * sigma
    count = particles.shape[0]
    particles[:, 0] += std_xy * rng.standard_normal(count)
    particles[:, 1] += std_xy * rng.standard_normal(count)
    yaw = particles[:, 2] + (std_xy / ROUGHENING_LEVER) * rng.standard_normal(count)
    particles[:, 2] = np.arctan2(np.sin(yaw), np.cos(yaw))
