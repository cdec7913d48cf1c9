"""KLD-sampling: the Wilson-Hilferty bound's known values, its growth with the occupied bins, the clamp, and the
sequential count."""

import math

import numpy as np
import pytest

from flex_nav.localization.kld import BIN_XY, BIN_YAW, bin_keys, kld_bound, sample_count


@pytest.mark.parametrize(
    ("bins", "err", "z", "expected"),
    [
        # (k-1)/(2 err) * (1 - 2/(9(k-1)) + sqrt(2/(9(k-1))) z)^3, rounded up, worked by hand
        (2, 0.05, 2.326, 66),  # 10 * (0.77778 + 0.47140 * 2.326)^3 = 65.84
        (11, 0.01, 0.99, 713),  # 500 * (0.97778 + 0.14907 * 0.99)^3 = 712.59
        (101, 0.05, 2.326, 1359),  # 1000 * (0.99778 + 0.04714 * 2.326)^3 = 1358.13
    ],
)
def test_known_values_of_the_wilson_hilferty_bound(bins, err, z, expected):
    assert kld_bound(bins, err, z) == expected


def test_bound_is_near_the_chi_square_quantile():
    stats = pytest.importorskip("scipy.stats")
    for bins in (5, 20, 200, 2000):
        chi2 = stats.chi2.ppf(stats.norm.cdf(2.326), bins - 1) / (2 * 0.05)
        assert kld_bound(bins, 0.05, 2.326) == pytest.approx(chi2, rel=0.02)


def test_bound_grows_with_the_occupied_bins_and_is_zero_below_two():
    values = kld_bound(np.arange(0, 500), 0.01, 0.99)
    assert values[0] == 0 and values[1] == 0
    assert (np.diff(values[2:]) > 0).all()


def test_bins_are_half_a_metre_and_ten_degrees():
    particles = np.array([[0.1, 0.1, 0.01], [0.4, 0.49, 0.1], [0.6, 0.1, 0.01], [0.1, -0.1, 0.01],
                          [0.1, 0.1, math.radians(10.5)]])
    keys = bin_keys(particles)
    assert keys[0] == keys[1]
    assert len(set(keys.tolist())) == 4
    assert BIN_XY == 0.5
    assert pytest.approx(math.radians(10)) == BIN_YAW


def test_sample_count_one_bin_is_the_minimum():
    keys = np.zeros(5000, dtype=np.int64)
    assert sample_count(keys, 0.01, 0.99, 500, 5000) == 500


def test_sample_count_stops_at_the_bound_of_the_bins_seen():
    keys = np.arange(5000, dtype=np.int64) % 11  # 11 bins, all seen within the first 11 samples
    assert sample_count(keys, 0.01, 0.99, 100, 5000) == 713


def test_sample_count_is_clamped_to_the_maximum():
    keys = np.arange(3000, dtype=np.int64)  # every sample a new bin: the bound is never reached
    assert sample_count(keys, 0.01, 0.99, 100, 2000) == 2000
    assert sample_count(keys[:10], 0.01, 0.99, 100, 2000) == 2000


def test_sample_count_grows_with_the_spread():
    rng = np.random.default_rng(0)
    counts = []
    for spread in (0.05, 0.5, 2.0):
        particles = np.column_stack([spread * rng.standard_normal(5000), spread * rng.standard_normal(5000),
                                     spread * rng.standard_normal(5000)])
        counts.append(sample_count(bin_keys(particles), 0.05, 0.99, 100, 5000))
    assert counts[0] < counts[1] < counts[2]
