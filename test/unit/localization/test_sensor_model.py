"""The likelihood-field sensor model over particles: the true pose scores best, the compiled kernel equals the
numpy reference, the coarse-to-fine widening of sigma."""

import math

import numpy as np
import pytest
from unit.localization.room import RANGE_MAX, asymmetric_room, scan_at

from flex_nav.localization import FilterParams
from flex_nav.localization.likelihood_field import LikelihoodField
from flex_nav.localization.scan import select_beams
from flex_nav.localization.sensor_model import (
    ANNEAL_LEVELS,
    TEMPERATURE,
    Kernel,
    SensorModel,
    annealed_sigma,
    beam_sums_numba,
    beam_sums_numpy,
)

TRUTH = (2.0, 1.2, 0.3)


@pytest.fixture(scope="module")
def model():
    grid = asymmetric_room()
    params = FilterParams()
    return SensorModel(params, LikelihoodField(grid, params.laser_likelihood_max_dist))


@pytest.fixture(scope="module")
def beams():
    return select_beams(scan_at(asymmetric_room(), TRUTH, np.random.default_rng(0), 0.01), 60)


@pytest.mark.parametrize("kernel", list(Kernel))
def test_the_true_pose_outscores_shifted_ones(model, beams, kernel):
    x, y, yaw = TRUTH
    shifts = [(0.03, 0, 0), (-0.03, 0, 0), (0, 0.03, 0), (0, -0.03, 0), (0, 0, 0.02), (0, 0, -0.02),
              (0.1, 0.1, 0), (0.5, 0, 0), (0, 0, 0.5)]
    particles = np.array([TRUTH] + [(x + dx, y + dy, yaw + da) for dx, dy, da in shifts])
    scores = model.log_likelihoods(particles, beams, RANGE_MAX, kernel=kernel)
    assert np.argmax(scores) == 0
    assert (scores[1:] < scores[0]).all()
    # farther is worse
    assert scores[7] < min(scores[1:5]) and scores[9] < min(scores[5:7])


def test_numba_equals_the_numpy_reference(model, beams):
    rng = np.random.default_rng(1)
    count = 3000
    particles = np.column_stack([rng.uniform(-1.0, 8.0, count), rng.uniform(-1.0, 6.0, count),
                                 rng.uniform(-math.pi, math.pi, count)])  # inside, outside, unknown
    particles[:500] = TRUTH + 0.05 * rng.standard_normal((500, 3))
    for sigma in (None, 0.2):
        fast = model.log_likelihoods(particles, beams, RANGE_MAX, sigma, Kernel.NUMBA)
        reference = model.log_likelihoods(particles, beams, RANGE_MAX, sigma, Kernel.NUMPY)
        np.testing.assert_allclose(fast, reference, rtol=1e-9, atol=1e-9)


def test_kernels_sum_table_values_per_particle():
    table = np.arange(13, dtype=np.float32)  # 3 x 4 grid + outside (12)
    px, py = np.array([0.5, 3.5, -0.5]), np.array([0.5, 2.5, 0.5])
    cos_yaw, sin_yaw = np.ones(3), np.zeros(3)
    bx, by = np.array([0.0, 1.0]), np.array([0.0, 0.0])
    for kernel in (beam_sums_numba, beam_sums_numpy):
        sums = kernel(px, py, cos_yaw, sin_yaw, bx, by, table, 3, 4)
        # particle 0: cells (0, 0) and (0, 1); particle 1: (2, 3) and outside; particle 2: outside and (0, 0)
        np.testing.assert_array_equal(sums, [0 + 1, 11 + 12, 12 + 0])


def test_outside_the_map_is_the_floor(model, beams):
    far = np.array([[100.0, 100.0, 0.0]])
    floor = math.log(model.params.laser_z_rand / RANGE_MAX)
    score = model.log_likelihoods(far, beams, RANGE_MAX)[0]
    assert score == pytest.approx(TEMPERATURE * beams.x.size * floor, rel=1e-6)


def test_annealed_sigma_follows_the_spread_in_steps_of_two():
    assert annealed_sigma(0.03, 0.0) == 0.03
    assert annealed_sigma(0.03, 0.02) == 0.03
    assert annealed_sigma(0.03, 0.13) == 0.06  # half the spread 0.065 -> one step
    assert annealed_sigma(0.03, 0.5) == 0.24
    assert annealed_sigma(0.03, 100.0) == 0.03 * 2 ** (ANNEAL_LEVELS - 1)


def test_tables_are_built_once_and_a_few_kept(model):
    first = model.table(RANGE_MAX, 0.03)
    assert model.table(RANGE_MAX, 0.03) is first
    for sigma in (0.06, 0.12, 0.24, 0.48):
        model.table(RANGE_MAX, sigma)
    assert model.table(RANGE_MAX, 0.03) is not first  # rebuilt after falling out
