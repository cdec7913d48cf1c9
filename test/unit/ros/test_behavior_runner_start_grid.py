"""A behavior in a lockstep simulation starts on a whole second of simulated time (``wait_for_start_grid``)."""

from __future__ import annotations

import threading
from typing import List

import pytest

from flex_nav.nodes import behavior_runner
from flex_nav.nodes.behavior_runner import wait_for_start_grid


@pytest.fixture(autouse=True)
def ros_running(monkeypatch: pytest.MonkeyPatch) -> None:
    """rospy as in a running node: an earlier test in this process may have shut rospy down for good."""
    monkeypatch.setattr(behavior_runner.rospy, "is_shutdown", lambda: False)
    monkeypatch.setattr(behavior_runner.rospy, "logwarn", lambda *args, **kwargs: None)


class ScriptedClock:
    """ROS time [s] read from a script, one reading per ``now``; the last reading repeats. Records the deadlines
    a lockstep hold was placed at (``wait_until``)."""

    def __init__(self, readings: List[float]) -> None:
        self.readings = list(readings)
        self.holds: List[float] = []

    def now(self) -> float:
        return self.readings.pop(0) if len(self.readings) > 1 else self.readings[0]

    def wait_until(self, deadline_s: float, wake: threading.Event) -> None:
        self.holds.append(deadline_s)


def test_starts_at_the_next_whole_second_it_is_held_at() -> None:
    clock = ScriptedClock([3.4, 3.6, 4.0])
    assert wait_for_start_grid(clock, "b") == pytest.approx(4.0)
    assert clock.holds == [pytest.approx(4.0, abs=1e-5)]  # once, at 3.6 s


def test_a_grid_point_passed_before_the_clock_came_does_not_count() -> None:
    """No /clock yet (0), then ROS time jumps over 1 s to 1.1625 s: the behavior waits for 2 s (this run started
    at 1.1625 s, its rerun at a higher rtf at 3 s, and their goals were seen a tick apart)."""
    clock = ScriptedClock([0.0, 0.0, 1.1625, 1.1625, 1.9, 2.0])
    assert wait_for_start_grid(clock, "b") == pytest.approx(2.0)
    assert clock.holds[0] == pytest.approx(1.0, abs=1e-5)
    assert clock.holds[-1] == pytest.approx(2.0, abs=1e-5)


def test_a_stalled_clock_starts_it_after_the_wall_bound() -> None:
    clock = ScriptedClock([0.5])
    assert wait_for_start_grid(clock, "b", wait_s=0.05) == 0.5
    assert clock.holds and all(hold == pytest.approx(1.0, abs=1e-5) for hold in clock.holds)
