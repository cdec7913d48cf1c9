"""BackoffState: wait before the next try of a goal, longer after each try (bounded exponential back-off)."""

from __future__ import annotations

from typing import Optional

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.exceptions import ConfigError
from flex_nav_states import validation


def retry_delay_s(tries: int, first_s: float, max_s: float) -> float:
    """[s] to wait before try ``tries + 1`` after ``tries`` failed ones: ``first_s`` doubling, at most ``max_s``
    (0 before the first try)."""
    if tries <= 0:
        return 0.0
    return min(first_s * 2.0 ** min(tries - 1, 60), max_s)


class BackoffState(State):
    """Waits before the next try of the same goal: ``first_s`` after the first failure, doubling, at most ``max_s``.

    Back-to-back retries fail for the same reason when it is transient (odometry that drops out for a second, a
    server restarting): spaced out, a fault shorter than the wait costs one try instead of all of them. The try
    number comes from the userdata counter ``tries`` (as counted by a Calculation state), or from ``attempt``
    where a fixed chain of retries has one BackoffState per step (move_base_like's recovery chain).

    -- first_s  float  [s] Wait after the first failed try (> 0).
    -- max_s    float  [s] Longest wait (>= first_s).
    -- attempt  int    Failed tries so far, fixed (>= 1); 0: read them from the ``tries`` input key.

    ># tries  float  Failed tries of this goal so far (read only when ``attempt`` is 0).

    <= done  The wait is over; try again.
    """

    def __init__(self, first_s: float = 0.5, max_s: float = 4.0, attempt: int = 0) -> None:
        owner = type(self).__name__
        attempt = validation.integer(owner, "attempt", attempt, minimum=0)  # 0: from the tries input key
        super().__init__(outcomes=["done"], input_keys=[] if attempt else ["tries"])
        self._first_s = validation.number(owner, "first_s", first_s, positive=True, unit="[s]")
        self._max_s = validation.number(owner, "max_s", max_s, minimum=self._first_s, unit="[s]")
        self._attempt = attempt
        self._until_s = 0.0

    def on_enter(self, userdata: UserDataView) -> None:
        tries = self._attempt
        if not tries:
            value = unwrap(userdata.tries)
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ConfigError(f"{type(self).__name__}: input key tries must be a number, got {value!r}")
            tries = int(value)
        delay_s = retry_delay_s(tries, self._first_s, self._max_s)
        self._until_s = self.now_s() + delay_s
        self.log_info(f"try {tries + 1}: waiting {delay_s:.1f} s first (back-off)")

    def execute(self, userdata: UserDataView) -> Optional[str]:
        return "done" if self.now_s() >= self._until_s else None
