"""The demo's localization error: estimates paired with interpolated ground truth, and the summary line."""

from __future__ import annotations

import math

import pytest

from flex_nav.apps.eval.localization_error import LocalizationErrors, merged, percentile


def test_truth_is_interpolated_at_the_estimate_stamp() -> None:
    errors = LocalizationErrors()
    errors.add_truth(0.00, (0.0, 0.0, math.pi - 0.1))
    errors.add_truth(0.02, (0.02, 0.0, -math.pi + 0.1))  # yaw crosses +-pi: the short way round
    truth = errors.truth_at(0.01)
    assert truth is not None
    assert truth[:2] == pytest.approx((0.01, 0.0))
    assert abs(abs(truth[2]) - math.pi) < 1e-9
    errors.add_estimate(0.01, (0.04, 0.04, math.pi))
    assert errors.position_m == pytest.approx([0.05])
    assert errors.heading_rad == pytest.approx([0.0], abs=1e-9)


def test_estimates_wait_for_truth_and_gaps_are_not_paired() -> None:
    errors = LocalizationErrors(max_gap_s=0.1)
    errors.add_truth(0.0, (0.0, 0.0, 0.0))
    errors.add_estimate(0.05, (0.1, 0.0, 0.0))  # newer than every truth: waits
    assert errors.position_m == []
    errors.add_truth(0.1, (0.2, 0.0, 0.0))
    assert errors.position_m == pytest.approx([0.0])
    errors.add_truth(5.0, (1.0, 0.0, 0.0))  # 4.9 s without truth
    errors.add_estimate(3.0, (0.0, 0.0, 0.0))
    errors.add_estimate(-1.0, (0.0, 0.0, 0.0))  # before every truth
    assert len(errors.position_m) == 1


def test_summary_and_line() -> None:
    errors = LocalizationErrors()
    for i in range(101):
        errors.add_truth(i * 0.1, (0.0, 0.0, 0.0))
    for i in range(100):
        errors.add_estimate(i * 0.1 + 0.05, (0.001 * (i + 1), 0.0, math.radians(0.01 * (i + 1))))
    summary = errors.summary()
    assert summary.estimates == 100
    assert summary.median_cm == pytest.approx(5.05)
    assert summary.p95_cm == pytest.approx(9.505)
    assert summary.max_cm == pytest.approx(10.0)
    assert summary.heading_median_deg == pytest.approx(0.505)
    assert summary.line().startswith("localization: median 5.1 cm, p95 9.5 cm, max 10.0 cm (heading median 0.51 deg")
    assert LocalizationErrors().summary().line() == "localization: no estimates paired with ground truth"
    assert merged([errors, errors]).summary().estimates == 200
    assert math.isnan(percentile([], 0.5))
