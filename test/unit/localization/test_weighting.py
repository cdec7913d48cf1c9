"""Weights from log-likelihoods: log-sum-exp, effective sample size, tempering of a degenerate update."""

import math

import numpy as np
import pytest

from flex_nav.localization.weighting import (
    MIN_ESS_FRACTION,
    MIN_ESS_FRACTION_COARSE,
    ess_fraction,
    tempering_scale,
)


def test_ess_fraction():
    assert ess_fraction(np.zeros(100)) == pytest.approx(1.0)
    one_hot = np.full(100, -1e9)
    one_hot[3] = 0.0
    assert ess_fraction(one_hot) == pytest.approx(0.01)


def test_a_mild_update_is_not_tempered():
    log_prior = np.full(1000, -math.log(1000))
    likelihood = np.random.default_rng(0).normal(0.0, 0.5, 1000)
    assert tempering_scale(log_prior, likelihood) == 1.0


@pytest.mark.parametrize(("coarse", "floor"), [(False, MIN_ESS_FRACTION), (True, MIN_ESS_FRACTION_COARSE)])
def test_a_degenerate_update_is_tempered_to_the_floor(coarse, floor):
    log_prior = np.full(5000, -math.log(5000))
    likelihood = np.random.default_rng(1).normal(0.0, 40.0, 5000)
    scale = tempering_scale(log_prior, likelihood, coarse=coarse)
    assert 0.0 < scale < 1.0
    assert ess_fraction(log_prior + scale * likelihood) >= floor
    assert ess_fraction(log_prior + 1.1 * scale * likelihood) < floor * 1.2
