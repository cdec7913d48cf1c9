"""LockstepTimer's grid (flex_nav.ros.ros_clock.next_grid_point): ticks at k * period whenever the timer started."""

from __future__ import annotations

import pytest

from flex_nav.ros.ros_clock import GRID_SLACK_S, next_grid_point


@pytest.mark.parametrize("started_s", [0.0, 1.234, 2.9, 3.0, 4.05])
def test_timers_started_at_different_times_tick_at_the_same_times(started_s: float) -> None:
    ticks, now_s = [], started_s
    for _ in range(5):
        now_s = next_grid_point(now_s, 0.2)
        ticks.append(now_s)
    assert all(abs(t / 0.2 - round(t / 0.2)) < 1e-4 for t in ticks)  # on the grid of the period
    assert all(b - a == pytest.approx(0.2) for a, b in zip(ticks, ticks[1:]))  # one after the next, none twice


def test_a_tick_read_exactly_on_or_just_before_its_grid_point_is_not_due_again() -> None:
    for k in range(1, 200):
        on_grid = k * 0.2  # as the simulator's clock gives it
        assert next_grid_point(on_grid, 0.2) == pytest.approx((k + 1) * 0.2, abs=1e-5)
        assert next_grid_point(on_grid - GRID_SLACK_S, 0.2) == pytest.approx((k + 1) * 0.2, abs=1e-5)


def test_a_time_just_before_the_slack_waits_for_that_grid_point() -> None:
    assert next_grid_point(0.6 - 3 * GRID_SLACK_S, 0.2) == pytest.approx(0.6 - GRID_SLACK_S)
    assert next_grid_point(0.61, 0.2) == pytest.approx(0.8 - GRID_SLACK_S)
