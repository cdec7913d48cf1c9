"""Roughening: the jitter's size, and a cloud standing still (no-motion updates) keeps its diversity."""

import math

import numpy as np
import pytest
from unit.localization.room import asymmetric_room, scan_at

from flex_nav.localization import FilterParams, Localizer, LocalizerStatus, roughening
from flex_nav.localization.roughening import ROUGHENING_GAIN, ROUGHENING_LEVER, roughen

START = (1.5, 1.2, 0.0)


@pytest.fixture(scope="module")
def grid():
    return asymmetric_room()


def test_jitter_follows_the_sigma():
    particles = np.zeros((20000, 3))
    particles[:, 2] = math.pi - 1e-3  # wraps
    roughen(particles, 0.2, np.random.default_rng(0))
    assert np.std(particles[:, 0]) == pytest.approx(ROUGHENING_GAIN * 0.2, rel=0.03)
    assert np.std(particles[:, 1]) == pytest.approx(ROUGHENING_GAIN * 0.2, rel=0.03)
    yaw_error = np.arctan2(np.sin(particles[:, 2] - math.pi), np.cos(particles[:, 2] - math.pi))
    assert np.std(yaw_error) == pytest.approx(ROUGHENING_GAIN * 0.2 / ROUGHENING_LEVER, rel=0.03)
    assert np.all(np.abs(particles[:, 2]) <= math.pi)


def standing_still(grid, updates, seed=0):
    localizer = Localizer(FilterParams(), grid, seed=seed)
    localizer.update((0.0, 0.0, 0.0), None)
    localizer.set_pose(START, np.diag([0.03**2, 0.03**2, 0.03**2]))
    rng = np.random.default_rng(seed)
    for _ in range(updates):
        localizer.request_nomotion_update()
        assert localizer.update((0.0, 0.0, 0.0), scan_at(grid, START, rng, 0.01))
    return localizer


def test_no_motion_updates_keep_the_cloud_diverse(grid):
    localizer = standing_still(grid, 30)
    particles = localizer.particles
    unique = np.unique(particles, axis=0).shape[0]
    assert unique == particles.shape[0]  # every resampled copy was moved apart
    spread = math.sqrt(np.linalg.eigvalsh(localizer.estimate().covariance[:2, :2]).max())
    assert spread > 0.005
    x, y, _ = localizer.estimate().pose
    assert math.hypot(x - START[0], y - START[1]) < 0.03
    assert localizer.status is LocalizerStatus.LOCALIZED


def test_without_roughening_the_cloud_collapses(grid, monkeypatch):
    monkeypatch.setattr(roughening, "ROUGHENING_GAIN", 0.0)
    particles = standing_still(grid, 30).particles
    assert np.unique(particles, axis=0).shape[0] < particles.shape[0] / 4
