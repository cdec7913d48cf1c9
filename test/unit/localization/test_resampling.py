"""Low-variance resampling: proportions, determinism, equal weights unchanged."""

import numpy as np
import pytest

from flex_nav.localization.resampling import low_variance_indices


def test_each_particle_is_taken_floor_or_ceil_of_count_times_weight():
    rng = np.random.default_rng(0)
    weights = rng.random(50) ** 3
    for _ in range(20):
        counts = np.bincount(low_variance_indices(weights, 1000, rng), minlength=50)
        expected = 1000 * weights / weights.sum()
        assert (counts >= np.floor(expected) - 1e-9).all() and (counts <= np.ceil(expected) + 1e-9).all()
        assert counts.sum() == 1000


def test_proportions_of_a_few_weights():
    counts = np.bincount(low_variance_indices(np.array([0.1, 0.0, 0.6, 0.3]), 10, np.random.default_rng(1)),
                         minlength=4)
    np.testing.assert_array_equal(counts, [1, 0, 6, 3])


def test_equal_weights_come_back_unchanged():
    indices = low_variance_indices(np.full(7, 1 / 7), 7, np.random.default_rng(2))
    np.testing.assert_array_equal(indices, np.arange(7))


def test_deterministic_for_a_seed_and_sorted():
    weights = np.random.default_rng(3).random(100)
    a = low_variance_indices(weights, 300, np.random.default_rng(4))
    b = low_variance_indices(weights, 300, np.random.default_rng(4))
    np.testing.assert_array_equal(a, b)
    assert (np.diff(a) >= 0).all()


def test_weights_need_a_positive_finite_sum():
    with pytest.raises(ValueError, match="positive sum"):
        low_variance_indices(np.zeros(3), 3, np.random.default_rng(5))
