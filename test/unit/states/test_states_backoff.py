"""BackoffState: a wait before the next try, doubling with the failed tries, bounded; fixed or from userdata."""

from __future__ import annotations

import pytest
from unit.states.states_testlib import Harness

from flex_nav.behavior import BehaviorStatus
from flex_nav.exceptions import ConfigError
from flex_nav_states.backoff_state import BackoffState, retry_delay_s


def test_retry_delay_doubles_and_is_bounded() -> None:
    assert [retry_delay_s(n, 0.5, 4.0) for n in range(7)] == [0.0, 0.5, 1.0, 2.0, 4.0, 4.0, 4.0]
    assert retry_delay_s(10_000, 0.5, 4.0) == 4.0  # no overflow


@pytest.mark.parametrize(("tries", "expected_s"), [(1.0, 0.5), (2.0, 1.0), (3.0, 2.0), (5.0, 4.0)])
def test_waits_by_the_tries_in_userdata(tries: float, expected_s: float) -> None:
    h = Harness(BackoffState(first_s=0.5, max_s=4.0), inputs={"tries": tries})
    start = h.clock.now()
    result = h.start().run(max_time_s=10.0, step_s=0.01)
    assert result.status is BehaviorStatus.FINISHED and result.outcome == "done"
    assert expected_s <= h.clock.now() - start <= expected_s + 0.11  # late by at most one tick (10 Hz)
    assert any(f"waiting {expected_s:.1f} s" in t for t in h.texts())


def test_a_fixed_attempt_needs_no_userdata() -> None:
    state = BackoffState(first_s=0.5, max_s=4.0, attempt=3)
    assert list(state.input_keys) == []
    h = Harness(state)
    start = h.clock.now()
    h.start().run(max_time_s=10.0, step_s=0.01)
    assert 2.0 <= h.clock.now() - start <= 2.11


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"first_s": 0.0}, "first_s must be > 0"),
    ({"first_s": 2.0, "max_s": 1.0}, "max_s must be >= 2.0"),
    ({"attempt": -1}, "attempt must be an integer >= 0"),
    ({"attempt": 1.5}, "attempt must be an integer >= 0"),
])
def test_bad_parameters_are_refused_at_load_time(kwargs: dict, match: str) -> None:
    with pytest.raises(ConfigError, match=match):
        BackoffState(**kwargs)
