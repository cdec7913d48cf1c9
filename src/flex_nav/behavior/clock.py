"""Clocks for the behavior executor: time is injected, never read from a global.

A :class:`Clock` gives the current time [s] and waits until a deadline or until woken (a command
arrived). :class:`MonotonicClock` is wall-clock monotonic time; :class:`ManualClock` is a
deterministic clock for tests and benchmarks whose waits advance time instantly. The ROS adapter
injects a clock on ROS time (simulated time included).
"""

from __future__ import annotations

import math
import threading
import time
from typing import Protocol


class Clock(Protocol):
    """What the executor needs from time."""

    def now(self) -> float:
        """Current time [s] (any epoch; only differences matter)."""
        ...

    def wait_until(self, deadline_s: float, wake: threading.Event) -> None:
        """Return at ``deadline_s`` or earlier when ``wake`` is set (spurious early returns are allowed)."""
        ...


class MonotonicClock:
    """``time.monotonic`` with waits on the wake event (a command interrupts a wait at once)."""

    def now(self) -> float:
        return time.monotonic()

    def wait_until(self, deadline_s: float, wake: threading.Event) -> None:
        remaining_s = deadline_s - time.monotonic()
        if remaining_s > 0.0:
            wake.wait(remaining_s if math.isfinite(remaining_s) else None)


class ManualClock:
    """A clock that only moves when told: ``wait_until`` jumps to the deadline (never sleeps).

    A wait with an infinite deadline does not move time; it returns at once so the caller can look
    at its commands (the executor bounds such loops itself).
    """

    def __init__(self, start_s: float = 0.0) -> None:
        self._now_s = start_s
        self.waits = 0  # number of wait_until calls that moved time, for tests

    def now(self) -> float:
        return self._now_s

    def advance(self, duration_s: float) -> None:
        if duration_s < 0.0:
            raise ValueError(f"cannot move a clock backwards by {duration_s} s")
        self._now_s += duration_s

    def wait_until(self, deadline_s: float, wake: threading.Event) -> None:
        if wake.is_set() or not math.isfinite(deadline_s):
            return
        if deadline_s > self._now_s:
            self._now_s = deadline_s
            self.waits += 1
