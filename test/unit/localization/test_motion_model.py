"""The diff-corrected odometry motion model: mean motion, spread per alpha, zero motion, driving backwards."""

import math

import numpy as np
import pytest

from flex_nav.localization.jit import Kernel
from flex_nav.localization.motion_model import OdometryMotion, decompose, noise_stds, sample_motion

COUNT = 200_000  # samples: standard errors of the estimated stds below 0.2 %


def cloud(yaw=0.0):
    particles = np.zeros((COUNT, 3))
    particles[:, 2] = yaw
    return particles


def test_decompose_turn_drive_turn():
    motion = decompose((1.0, 2.0, 0.0), (1.0, 3.0, math.pi))
    assert motion.rot1 == pytest.approx(math.pi / 2)
    assert motion.trans == pytest.approx(1.0)
    assert motion.rot2 == pytest.approx(math.pi / 2)


def test_decompose_small_step_is_a_turn_on_the_spot():
    motion = decompose((0.0, 0.0, 0.0), (0.005, 0.005, 0.3))
    assert motion.rot1 == 0.0
    assert motion.rot2 == pytest.approx(0.3)


def test_straight_drive_mean_and_spread_follow_alpha2_and_alpha3():
    alphas = (0.0, 0.04, 0.01, 0.0)
    particles = cloud()
    sample_motion(particles, decompose((0, 0, 0), (0.5, 0.0, 0.0)), alphas, np.random.default_rng(1))
    # x = trans cos(rot1), rot1 ~ N(0, 0.1²): E[cos] = exp(-0.1² / 2)
    assert particles[:, 0].mean() == pytest.approx(0.5 * math.exp(-0.005), abs=1e-3)
    assert particles[:, 1].mean() == pytest.approx(0.0, abs=1e-3)
    assert particles[:, 0].std() == pytest.approx(math.sqrt(0.01) * 0.5, rel=0.01)  # alpha3 trans²
    # rot1 and rot2 each get variance alpha2 trans²; the final heading has both
    assert particles[:, 2].std() == pytest.approx(math.sqrt(2 * 0.04) * 0.5, rel=0.01)
    # the sideways spread comes from rot1 only: trans * sin(rot1)
    assert particles[:, 1].std() == pytest.approx(0.5 * math.sqrt(0.04) * 0.5, rel=0.02)


def test_turn_on_the_spot_spread_follows_alpha1_and_alpha4():
    alphas = (0.09, 0.0, 0.0, 0.0025)
    particles = cloud()
    sample_motion(particles, decompose((0, 0, 0), (0.0, 0.0, 1.0)), alphas, np.random.default_rng(2))
    assert particles[:, 2].mean() == pytest.approx(1.0, abs=1e-3)
    assert particles[:, 2].std() == pytest.approx(math.sqrt(0.09) * 1.0, rel=0.01)  # alpha1 rot²
    assert np.hypot(particles[:, 0], particles[:, 1]).std() == pytest.approx(
        math.sqrt(0.0025) * 1.0 * math.sqrt(1 - 2 / math.pi), rel=0.02)  # |N(0, alpha4 rot²)|


def test_noise_stds_are_the_square_roots_of_the_variance_sums():
    rot1, std_trans, rot2 = noise_stds(OdometryMotion(0.2, 0.5, -0.1), (0.1, 0.2, 0.3, 0.4))
    assert rot1 == pytest.approx(math.sqrt(0.1 * 0.04 + 0.2 * 0.25))
    assert std_trans == pytest.approx(math.sqrt(0.3 * 0.25 + 0.4 * (0.04 + 0.01)))
    assert rot2 == pytest.approx(math.sqrt(0.1 * 0.01 + 0.2 * 0.25))


def test_zero_motion_stays_put():
    rng = np.random.default_rng(3)
    particles = np.column_stack([rng.uniform(-5, 5, 1000), rng.uniform(-5, 5, 1000), rng.uniform(-3, 3, 1000)])
    before = particles.copy()
    sample_motion(particles, decompose((1.0, 1.0, 0.5), (1.0, 1.0, 0.5)), (0.2, 0.2, 0.2, 0.2), rng)
    np.testing.assert_allclose(particles, before, atol=1e-12)


def test_driving_backwards_is_no_half_turn():
    motion = decompose((0.0, 0.0, 0.0), (-0.5, 0.0, 0.0))
    assert abs(motion.rot1) == pytest.approx(math.pi)
    std_rot1, std_trans, std_rot2 = noise_stds(motion, (1.0, 0.0, 0.01, 1.0))
    assert std_rot1 == pytest.approx(0.0, abs=1e-12) and std_rot2 == pytest.approx(0.0, abs=1e-12)
    assert std_trans == pytest.approx(0.05)
    particles = cloud()
    sample_motion(particles, motion, (1.0, 0.0, 0.01, 1.0), np.random.default_rng(4))
    assert particles[:, 0].mean() == pytest.approx(-0.5, abs=1e-3)
    assert np.abs(particles[:, 2]).max() < 1e-9


def test_motion_is_in_each_particles_own_frame():
    particles = np.array([[0.0, 0.0, 0.0], [1.0, 1.0, math.pi / 2], [0.0, 0.0, math.pi]])
    sample_motion(particles, decompose((5, 5, 1.0), (5 + 0.3 * math.cos(1.0), 5 + 0.3 * math.sin(1.0), 1.5)),
                  (0.0, 0.0, 0.0, 0.0), np.random.default_rng(5))
    np.testing.assert_allclose(particles, [[0.3, 0.0, 0.5], [1.0, 1.3, math.pi / 2 + 0.5],
                                           [-0.3, 0.0, -math.pi + 0.5]], atol=1e-12)


def test_same_seed_same_samples():
    a, b = cloud()[:100], cloud()[:100]
    motion = decompose((0, 0, 0), (0.2, 0.1, 0.3))
    sample_motion(a, motion, (0.1, 0.1, 0.1, 0.1), np.random.default_rng(7))
    sample_motion(b, motion, (0.1, 0.1, 0.1, 0.1), np.random.default_rng(7))
    np.testing.assert_array_equal(a, b)


def test_numba_and_numpy_loops_agree():
    rng = np.random.default_rng(8)
    start = np.column_stack([rng.uniform(-5, 5, 500), rng.uniform(-5, 5, 500), rng.uniform(-3.1, 3.1, 500)])
    moved = []
    for kernel in Kernel:
        particles = start.copy()
        sample_motion(particles, decompose((0, 0, 0), (0.3, -0.2, 2.5)), (0.1, 0.2, 0.1, 0.05),
                      np.random.default_rng(9), kernel)
        moved.append(particles)
    np.testing.assert_allclose(moved[0], moved[1], atol=1e-12)
    assert np.abs(moved[0][:, 2]).max() <= math.pi
