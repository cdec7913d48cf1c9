"""ClockWatch: a ROS clock that stops or moves backwards is found by comparing it with wall time."""

from __future__ import annotations

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.clock_watch import ClockChange, ClockWatch


def stalled(watch: ClockWatch) -> bool:
    """``watch.stalled`` read through a call: mypy keeps an attribute narrowed by an earlier assert across the
    method calls that change it."""
    return watch.stalled


def test_a_clock_that_advances_is_steady() -> None:
    watch = ClockWatch(0.5)
    for k in range(100):
        assert watch.observe(10.0 + 0.01 * k, 0.01 * k) is ClockChange.STEADY
    assert not watch.stalled


def test_a_clock_standing_still_longer_than_the_timeout_is_stalled_once_then_resumes() -> None:
    watch = ClockWatch(0.5)
    watch.observe(10.0, 0.0)
    watch.observe(10.1, 0.1)  # seen advancing: armed
    assert watch.observe(10.1, 0.55) is ClockChange.STEADY  # 0.45 s still: not yet
    assert watch.observe(10.1, 0.65) is ClockChange.STALLED  # 0.55 s still
    assert watch.stalled
    assert watch.observe(10.1, 5.0) is ClockChange.STEADY  # reported once
    assert watch.still_for_s(5.0) == pytest.approx(4.9)
    assert watch.observe(10.2, 5.1) is ClockChange.RESUMED
    assert not watch.stalled


def test_a_clock_never_seen_advancing_is_not_stalled() -> None:
    # before the simulator's first /clock ROS time is 0 and nothing has anything to stop
    watch = ClockWatch(0.5)
    for wall_s in (0.0, 1.0, 10.0):
        assert watch.observe(0.0, wall_s) is ClockChange.STEADY
    assert not watch.stalled


def test_a_jump_back_is_reported_with_its_size_and_clears_a_stall() -> None:
    watch = ClockWatch(0.5)
    watch.observe(50.0, 0.0)
    watch.observe(50.5, 0.5)
    watch.observe(50.5, 2.0)
    assert watch.stalled
    assert watch.observe(0.2, 2.1) is ClockChange.JUMPED_BACK
    assert watch.jump_s == pytest.approx(50.3)
    assert not stalled(watch)
    assert watch.observe(0.3, 2.2) is ClockChange.STEADY


def test_timeout_zero_reports_jumps_only() -> None:
    watch = ClockWatch(0.0)
    watch.observe(1.0, 0.0)
    watch.observe(2.0, 0.0)
    assert watch.observe(2.0, 100.0) is ClockChange.STEADY
    assert watch.observe(1.0, 100.0) is ClockChange.JUMPED_BACK


@pytest.mark.parametrize("bad", [-0.1, float("nan"), float("inf")])
def test_bad_timeouts_are_refused_with_the_value(bad: float) -> None:
    with pytest.raises(ConfigError, match="stall timeout"):
        ClockWatch(bad)
