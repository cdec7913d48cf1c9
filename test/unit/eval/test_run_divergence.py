"""Where two recordings of one run part (flex_nav.apps.eval.run_divergence): the pure comparison and the report."""

from __future__ import annotations

import math

import pytest

from flex_nav.apps.eval.run_divergence import Divergence, Recording, aligned, first_divergence, report


def test_the_earliest_common_stamp_that_differs_is_found_whatever_the_order_given() -> None:
    first = {0.2: (1.0, 0.5), 0.1: (1.0, 0.0), 0.3: (2.0, 0.0)}
    second = {0.3: (2.5, 0.0), 0.1: (1.0, 0.0), 0.2: (1.0, 0.6)}
    assert first_divergence(first, second, 1e-6) == Divergence(0.2, (1.0, 0.5), (1.0, 0.6))


def test_differences_within_the_tolerance_and_stamps_only_one_holds_do_not_count() -> None:
    first = {0.0: (1.0,), 0.05: (9.0,), 0.1: (2.0,)}
    second = {0.0: (1.0 + 1e-9,), 0.1: (2.0,), 0.15: (7.0,)}
    assert first_divergence(first, second, 1e-6) is None
    assert first_divergence(first, second, 0.0) == Divergence(0.0, (1.0,), (1.0 + 1e-9,))


def test_nan_equals_nan_inf_equals_inf_and_a_length_change_differs() -> None:
    nan, inf = math.nan, math.inf
    assert first_divergence({1.0: (nan, inf)}, {1.0: (nan, inf)}, 1e-6) is None
    assert first_divergence({1.0: (nan,)}, {1.0: (0.0,)}, 1e-6) is not None
    assert first_divergence({1.0: (inf,)}, {1.0: (1e308,)}, 1e308) is not None
    assert first_divergence({1.0: (1.0,)}, {1.0: (1.0, 2.0)}, 1e-6) is not None


@pytest.mark.parametrize("tolerance", [-1.0, math.nan, math.inf])
def test_a_tolerance_that_is_not_a_finite_number_at_least_zero_is_refused(tolerance: float) -> None:
    with pytest.raises(ValueError, match="tolerance"):
        first_divergence({}, {}, tolerance)


def test_the_report_names_where_truth_and_scans_part_and_the_transitions_around_it() -> None:
    same_scan = (1.0, 2.0, math.inf)
    first = Recording({8.0: (1.0, 5.0, 0.0, 0.0, 0.0), 8.1: (1.0, 5.0, 0.0, 0.0, 0.0)},
                      {8.0: same_scan, 8.2: (1.0, 2.0, 3.0)},
                      [(8.029, "/Plan --planned--> Follow"), (20.0, "/Follow --blocked--> Classify")])
    second = Recording({8.0: (1.0, 5.0, 0.0, 0.0, 0.0), 8.1: (1.0004, 5.0, 0.0, 0.02, 0.0)},
                       {8.0: same_scan, 8.2: (1.0, 2.5, 3.0)},
                       [(8.129, "/Plan --planned--> Follow")])
    lines = report(first, second, 1e-6)
    assert lines[0] == "ground truth: 2 / 2 samples, 2 at common stamps"
    assert lines[1].startswith("ground truth parts at 8.1000 s: (x, y, yaw, v, w) (1, 5, 0, 0, 0) vs (1.0004, 5,")
    assert lines[2] == "scans part at 8.2000 s (1 of 3 ranges differ)"
    assert "  8.029 s /Plan --planned--> Follow" in lines
    assert "  8.129 s /Plan --planned--> Follow" in lines
    assert not any("Classify" in line for line in lines)  # far from where they part


def test_the_report_of_two_equal_runs_says_so() -> None:
    run = Recording({1.0: (0.0,)}, {1.0: (1.0,)}, [])
    assert report(run, run, 0.0)[1:] == ["ground truth: the same at every common stamp",
                                        "scans: the same at every common stamp"]


def test_recordings_are_aligned_on_their_first_transition() -> None:
    late = Recording({10.0: (1.0,), 10.1: (2.0,)}, {10.05: (3.0,)}, [(10.029, "/Plan --planned--> Follow"),
                                                                   (10.0, "/ReceiveGoal --received--> Plan")])
    shifted = aligned(late)
    assert shifted.truth == {0.0: (1.0,), 0.1: (2.0,)}
    assert shifted.scans == {0.05: (3.0,)}
    assert shifted.transitions == [(0.029, "/Plan --planned--> Follow"), (0.0, "/ReceiveGoal --received--> Plan")]
    assert aligned(Recording({1.0: (1.0,)}, {}, [])).truth == {1.0: (1.0,)}
