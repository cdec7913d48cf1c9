"""The runner's ``~userdata``: the active states' userdata, summarized, rate-limited, latched (std_msgs/String, JSON).

One :class:`UserdataPublisher` per running behavior, with its own thread: it reads
:meth:`~flex_nav.behavior.executor.BehaviorExecutor.active_userdata` (references taken under the behavior's lock,
bounded by ``LOCK_WAIT_S``), summarizes them off the behavior's thread (:mod:`flex_nav.behavior.userdata_summary`:
bounded per key and per message, ROS messages as their type and a few fields, nothing evaluated or pickled) and
publishes the JSON only when it changed, at most ``rate_hz`` times a second. It looks again when the active states
change (the executor's hook only sets an event) and every ``1 / rate_hz`` seconds otherwise, so a value a state
writes while it stays active shows within that period. When the behavior ends it latches a message with no states
and stops.
"""

from __future__ import annotations

import json
import threading
import time
from typing import Callable, Optional

import rospy
from std_msgs.msg import String

from flex_nav.behavior.executor import BehaviorExecutor
from flex_nav.behavior.userdata_summary import DEFAULT_LIMITS, SummaryLimits, userdata_message
from flex_nav.exceptions import ConfigError

DEFAULT_RATE_HZ = 2.0  # [Hz] most messages a second (and how often values are looked at)
MAX_RATE_HZ = 20.0  # [Hz]
LOCK_WAIT_S = 0.05  # [s] longest wait for the behavior's lock (a busy tick: try again next period)
STOP_WAIT_S = 2.0  # [s] bound on joining the thread


class UserdataPublisher:
    """Publishes one executor's active userdata with ``publish`` (see the module doc); ``stop()`` ends it."""

    def __init__(self, executor: BehaviorExecutor, behavior: str, publish: Callable[[str], None], *,
                 rate_hz: float = DEFAULT_RATE_HZ, limits: SummaryLimits = DEFAULT_LIMITS,
                 clock: Callable[[], float] = time.monotonic) -> None:
        if not 0.0 < rate_hz <= MAX_RATE_HZ:
            raise ConfigError(f"userdata rate must be in (0, {MAX_RATE_HZ:g}] Hz, got {rate_hz!r}")
        self.executor = executor
        self.behavior = behavior
        self.publish = publish
        self.period_s = 1.0 / rate_hz
        self.limits = limits
        self.clock = clock
        self.published = 0
        self._last = ""
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name=f"userdata {behavior}", daemon=True)
        hooks = executor.context.hooks
        hooks.active.append(lambda _event: self._wake.set())
        hooks.status.append(lambda _event: self._wake.set())

    def start(self) -> UserdataPublisher:
        self._thread.start()
        return self

    def stop(self) -> None:
        self._stop.set()
        self._wake.set()
        if self._thread.ident is not None:
            self._thread.join(STOP_WAIT_S)

    def sample(self) -> Optional[str]:
        """Read and summarize once; the JSON if it differs from the last one published (None otherwise, or when
        the behavior's lock was busy)."""
        states = self.executor.active_userdata(LOCK_WAIT_S)
        if states is None:
            return None
        message = userdata_message(self.behavior if states else "", self.executor.context.clock.now(), states,
                                   self.limits)
        stamp = message.pop("stamp")
        unchanged = json.dumps(message, separators=(",", ":"), allow_nan=False)
        if unchanged == self._last:
            return None
        self._last = unchanged
        message["stamp"] = stamp
        return json.dumps(message, separators=(",", ":"), allow_nan=False)

    def _run(self) -> None:
        while not self._stop.is_set():
            began = self.clock()
            ended = self.executor.status.is_terminal
            text = self.sample()
            if text is not None:
                try:
                    self.publish(text)
                    self.published += 1
                except (rospy.ROSException, ValueError, TypeError) as err:
                    rospy.logwarn_throttle(5.0, f"userdata: could not publish: {err}")
            if ended:
                return
            self._wake.wait(self.period_s)
            self._wake.clear()
            rest = self.period_s - (self.clock() - began)  # never more than rate_hz messages a second
            if rest > 0.0:
                self._stop.wait(rest)


def userdata_topic(name: str = "~userdata") -> Callable[[str], None]:
    """A latched std_msgs/String publisher on ``name``, as the callable UserdataPublisher publishes with."""
    publisher = rospy.Publisher(name, String, queue_size=1, latch=True)

    def publish(text: str) -> None:
        publisher.publish(String(data=text))

    return publish


def no_userdata(publish: Callable[[str], None]) -> None:
    """Latch the message of no behavior (at the runner's start)."""
    publish(json.dumps(userdata_message("", float("nan"), ()), separators=(",", ":")))
