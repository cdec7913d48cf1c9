"""BackgroundLoad: a load in a worker thread whose wait is bounded and whose late result is discarded."""

from __future__ import annotations

import threading
import time
from typing import List

import pytest

from flex_nav.behavior.background_load import BackgroundLoad, LoadState
from flex_nav.exceptions import BehaviorCommandError, BehaviorLoadError, ConfigError, TimedOutError

BOUND_S = 5.0  # [s] no wait in these tests may take longer


def test_the_result_is_handed_over_once() -> None:
    job = BackgroundLoad("'x'", lambda: 42, lambda _: None, BOUND_S)
    job.start()
    assert job.wait() == 42
    assert job.state is LoadState.DONE
    with pytest.raises(BehaviorCommandError, match="already taken"):
        job.wait()


def test_errors_arrive_typed() -> None:
    def bad_config() -> int:
        raise ConfigError("bad value")

    job = BackgroundLoad("'x'", bad_config, lambda _: None, BOUND_S)
    job.start()
    with pytest.raises(ConfigError, match="bad value"):
        job.wait()

    def broken() -> int:
        raise KeyError("k")

    job = BackgroundLoad("'y'", broken, lambda _: None, BOUND_S)
    job.start()
    with pytest.raises(BehaviorLoadError, match="loading 'y' failed: KeyError") as info:
        job.wait()
    assert isinstance(info.value.__cause__, KeyError)


def slow_job(release: threading.Event, discarded: List[int], timeout_s: float) -> BackgroundLoad[int]:
    def build() -> int:
        release.wait(BOUND_S)
        return 7

    return BackgroundLoad("'slow'", build, discarded.append, timeout_s)


def test_a_load_over_its_bound_fails_in_time_and_its_late_result_is_discarded() -> None:
    release = threading.Event()
    discarded: List[int] = []
    job = slow_job(release, discarded, timeout_s=0.2)
    started = time.monotonic()
    job.start()
    with pytest.raises(TimedOutError, match=r"loading 'slow' took longer than 0.2 s .* will not start"):
        job.wait()
    assert 0.15 < time.monotonic() - started < 2.0
    assert job.state is LoadState.TIMED_OUT
    release.set()
    deadline = time.monotonic() + BOUND_S
    while job.worker_alive() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert discarded == [7]
    with pytest.raises(TimedOutError):
        job.wait()  # never the late result


def test_a_cancelled_load_answers_cancelled_and_discards_its_result() -> None:
    release = threading.Event()
    discarded: List[int] = []
    job = slow_job(release, discarded, timeout_s=BOUND_S)
    job.start()
    assert job.cancel("stopped by the operator")
    assert not job.cancel("again")
    with pytest.raises(BehaviorCommandError, match="loading 'slow' was cancelled: stopped by the operator"):
        job.wait()
    release.set()
    deadline = time.monotonic() + BOUND_S
    while job.worker_alive() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert discarded == [7]


def test_start_and_wait_are_checked() -> None:
    job = BackgroundLoad("'x'", lambda: 1, lambda _: None, BOUND_S)
    with pytest.raises(BehaviorCommandError, match="was not started"):
        job.wait()
    assert job.elapsed_s() == 0.0
    job.start()
    with pytest.raises(BehaviorCommandError, match="already started"):
        job.start()
    with pytest.raises(ConfigError, match="timeout_s must be positive, got 0"):
        BackgroundLoad("'x'", lambda: 1, lambda _: None, 0.0)
