"""The estimate of a weighted cloud: weighted mean, circular mean of the yaws, covariance, spread."""

import math

import numpy as np
import pytest

from flex_nav.localization.estimate import spread_xy, weighted_mean_and_covariance
from flex_nav.localization.jit import Kernel


@pytest.mark.parametrize("kernel", list(Kernel))
def test_weighted_mean_and_covariance(kernel):
    particles = np.array([[0.0, 0.0, math.pi - 0.1], [2.0, 1.0, -math.pi + 0.1], [1.0, 0.5, math.pi]])
    weights = np.array([0.25, 0.25, 0.5])
    (x, y, yaw), covariance = weighted_mean_and_covariance(particles, weights, kernel)
    assert (x, y) == pytest.approx((1.0, 0.5))
    assert abs(math.atan2(math.sin(yaw - math.pi), math.cos(yaw - math.pi))) < 1e-12  # across the wrap
    assert covariance[0, 0] == pytest.approx(0.5)
    assert covariance[1, 1] == pytest.approx(0.125)
    assert covariance[0, 1] == pytest.approx(0.25) and covariance[1, 0] == covariance[0, 1]
    assert covariance[2, 2] == pytest.approx(0.5 * 0.01)  # wrapped deviations +-0.1 rad, not +-2 pi


def test_kernels_agree_on_a_random_cloud():
    rng = np.random.default_rng(0)
    particles = np.column_stack([rng.normal(3, 0.2, 1000), rng.normal(-1, 0.1, 1000), rng.uniform(-3, 3, 1000)])
    weights = rng.random(1000)
    weights /= weights.sum()
    results = [weighted_mean_and_covariance(particles, weights, kernel) for kernel in Kernel]
    np.testing.assert_allclose(results[0][0], results[1][0], atol=1e-12)
    np.testing.assert_allclose(results[0][1], results[1][1], atol=1e-12)


def test_spread_is_the_std_along_the_widest_direction():
    assert spread_xy(np.diag([0.04, 0.01, 1.0])) == pytest.approx(0.2)
    rotated = np.array([[0.025, 0.015, 0.0], [0.015, 0.025, 0.0], [0.0, 0.0, 0.0]])  # eigenvalues 0.04, 0.01
    assert spread_xy(rotated) == pytest.approx(0.2)
