"""Augmented MCL: the slow and fast averages, the injection probability, and random particles in the filter when
the robot is carried off."""

import math

import numpy as np
import pytest
from unit.localization.room import asymmetric_room, scan_at

from flex_nav.localization import FilterParams, Localizer
from flex_nav.localization.recovery import RecoveryAverages


def test_disabled_never_injects():
    averages = RecoveryAverages(0.0, 0.0)
    for value in (0.0, -50.0, -100.0):
        averages.observe(value)
    assert averages.injection_probability() == 0.0


def test_a_drop_of_the_likelihood_gives_one_minus_fast_over_slow():
    averages = RecoveryAverages(0.001, 0.1)
    averages.observe(math.log(1.0))  # both start here
    assert averages.injection_probability() == 0.0
    averages.observe(math.log(0.1))
    slow, fast = 0.999 * 1.0 + 0.001 * 0.1, 0.9 * 1.0 + 0.1 * 0.1
    assert averages.injection_probability() == pytest.approx(1.0 - fast / slow)


def test_a_rise_of_the_likelihood_injects_nothing_and_reset_starts_again():
    averages = RecoveryAverages(0.001, 0.1)
    averages.observe(-3.0)
    averages.observe(-1.0)
    assert averages.injection_probability() == 0.0
    for _ in range(10):  # the fast average falls below the slow one after a few bad updates
        averages.observe(-30.0)
    assert averages.injection_probability() > 0.4
    averages.reset()
    assert averages.injection_probability() == 0.0


def test_tiny_likelihoods_do_not_underflow():
    averages = RecoveryAverages(0.001, 0.1)
    averages.observe(-2000.0)
    averages.observe(-2010.0)
    assert 0.0 < averages.injection_probability() < 1.0


def kidnap(params):
    """Localize at A, then give scans taken at B with no odometry motion but requested updates; returns the
    distances of the particles from A."""
    grid = asymmetric_room()
    rng = np.random.default_rng(1)
    a, b = (1.5, 1.2, 0.0), (3.5, 2.2, 2.0)
    localizer = Localizer(params, grid, seed=3)
    localizer.update((0.0, 0.0, 0.0), None)
    localizer.set_pose(a, np.diag([0.01, 0.01, 0.01]))
    for _ in range(5):
        localizer.request_nomotion_update()
        localizer.update((0.0, 0.0, 0.0), scan_at(grid, a, rng, 0.01))
    for _ in range(5):
        localizer.request_nomotion_update()
        localizer.update((0.0, 0.0, 0.0), scan_at(grid, b, rng, 0.01))
    return np.hypot(localizer.particles[:, 0] - a[0], localizer.particles[:, 1] - a[1])


def test_random_particles_are_injected_when_the_scans_stop_fitting():
    far = kidnap(FilterParams(recovery_alpha_slow=0.001, recovery_alpha_fast=0.1)) > 1.0
    assert far.sum() > 10


def test_no_random_particles_without_recovery():
    assert (kidnap(FilterParams()) < 1.0).all()
