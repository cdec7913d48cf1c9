"""flexbe_core.core.ros_state: FlexBE's RosState: the execution rate (``set_rate``, ``sleep``, ``sleep_duration``),
the FlexBE proxies every state has (``self._pub``, ``self._sub``) and the "controlled" flag.

The rate is FlexBE's ``rospy.Rate`` semantics on the monotonic clock (:class:`Rate`): ``sleep()`` waits until one
period after the previous call (the first call waits one period), ``sleep_duration`` is the time left until then
[s] (<= 0: due). They matter when FlexBE code drives the state itself (flexbe_testing's Tester, a directly executed
container); flex_nav's executor schedules by ``rate_hz``, which ``set_rate`` sets too.
"""

from __future__ import annotations

import time
from typing import Any, Iterable

from flex_nav.compat.flexbe_core.core.state import State
from flex_nav.exceptions import ConfigError

DEFAULT_RATE_HZ = 10.0  # [Hz] FlexBE's default execution rate


class Duration:
    """What ``Rate.remaining()`` returns: ``to_sec()`` like rospy.Duration."""

    __slots__ = ("_s",)

    def __init__(self, seconds: float) -> None:
        self._s = seconds

    def to_sec(self) -> float:
        return self._s


class Rate:
    """rospy.Rate's semantics on ``time.monotonic()``; the period starts at the first ``remaining()`` / ``sleep()``."""

    def __init__(self, hz: float) -> None:
        if isinstance(hz, bool) or not isinstance(hz, (int, float)) or not hz > 0:
            raise ConfigError(f"rate must be a number > 0 [Hz], got {hz!r}")
        self.period_s = 1.0 / float(hz)
        self._last: float = -1.0  # [s] monotonic time the current period started; < 0: not started

    def _now(self) -> float:
        now = time.monotonic()
        if self._last < 0.0 or self._last > now:
            self._last = now
        return now

    def remaining(self) -> Duration:
        """Time until the end of the current period [s] (negative when overdue)."""
        now = self._now()
        return Duration(self._last + self.period_s - now)

    def sleep(self) -> None:
        """Wait for the end of the current period and start the next one (resynchronised when 2 periods behind)."""
        now = self._now()
        wait = self._last + self.period_s - now
        if wait > 0.0:
            time.sleep(wait)
        self._last += self.period_s
        if now - self._last > 2.0 * self.period_s:
            self._last = now


class RosState(State):
    """A state with an execution rate and FlexBE's per-state proxies."""

    def __init__(
        self,
        outcomes: Iterable[str] = (),
        input_keys: Iterable[str] = (),
        output_keys: Iterable[str] = (),
        io_keys: Iterable[str] = (),
    ) -> None:
        super().__init__(outcomes=outcomes, input_keys=input_keys, output_keys=output_keys, io_keys=io_keys)
        from flex_nav.compat.flexbe_core.proxy import ProxyPublisher, ProxySubscriberCached  # noqa: PLC0415

        self._rate: Any = Rate(DEFAULT_RATE_HZ)
        self._is_controlled = False
        self._pub = ProxyPublisher()
        self._sub = ProxySubscriberCached()

    def set_rate(self, rate: float) -> None:
        """Execute this state at ``rate`` [Hz] (the engine's ``rate_hz`` and FlexBE's ``sleep`` both follow it)."""
        self.rate_hz = rate
        self._rate = Rate(rate)

    def sleep(self) -> None:
        """Wait until this state is due again (FlexBE code that drives the state calls it between executions)."""
        self._rate.sleep()

    @property
    def sleep_duration(self) -> float:
        """[s] time until this state is due again (<= 0: due now)."""
        remaining = self._rate.remaining()
        return float(remaining.to_sec() if hasattr(remaining, "to_sec") else remaining)

    def _enable_ros_control(self) -> None:
        self._is_controlled = True

    def _disable_ros_control(self) -> None:
        self._is_controlled = False

    @property
    def is_breakpoint(self) -> bool:
        """FlexBE's breakpoints belong to its App; flex_nav's operator locks states instead."""
        return False


__all__ = ["DEFAULT_RATE_HZ", "Duration", "Rate", "RosState"]
