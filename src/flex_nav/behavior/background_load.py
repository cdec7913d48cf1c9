"""A load (read, build, validate a behavior) in a worker thread, with a bound on how long anyone waits for it.

The behavior runner must answer an operator at once and must not start a behavior whose load it already
reported as failed. :class:`BackgroundLoad` runs ``build()`` in a daemon thread; :meth:`BackgroundLoad.wait`
returns its result or raises, at the latest ``timeout_s`` after :meth:`BackgroundLoad.start`. A load that
timed out or was cancelled is *abandoned*: if its worker still finishes, the result goes to ``discard``
(e.g. to close the connections its states opened) and never to the caller. Whatever ``build()`` raises
reaches the caller as a :class:`~flex_nav.exceptions.FlexNavError`. No ROS here.
"""

from __future__ import annotations

import enum
import threading
import time
from typing import Callable, Generic, Optional, TypeVar

from flex_nav.exceptions import BehaviorCommandError, BehaviorLoadError, ConfigError, FlexNavError, TimedOutError

T = TypeVar("T")


class LoadState(enum.Enum):
    READY = "ready"  # not started
    LOADING = "loading"
    DONE = "done"  # built; wait() hands the result over
    FAILED = "failed"  # build() raised
    TIMED_OUT = "timed out"  # abandoned by wait()
    CANCELLED = "cancelled"  # abandoned by cancel()


class BackgroundLoad(Generic[T]):
    """One load: ``build()`` in a daemon thread, bounded by ``timeout_s`` [s] from :meth:`start`.

    ``what`` names the load in messages (e.g. ``"behavior 'patrol'"``); ``discard`` receives a result that
    arrives after the load was abandoned. ``clock`` returns seconds (monotonic).
    """

    def __init__(self, what: str, build: Callable[[], T], discard: Callable[[T], None], timeout_s: float,
                 clock: Callable[[], float] = time.monotonic) -> None:
        if not timeout_s > 0.0:
            raise ConfigError(f"timeout_s must be positive, got {timeout_s!r}")
        self.what = what
        self.timeout_s = timeout_s
        self._build = build
        self._discard = discard
        self._clock = clock
        self._lock = threading.Lock()
        self._finished = threading.Event()
        self._state = LoadState.READY
        self._started_s = 0.0
        self._value: Optional[T] = None
        self._error: Optional[FlexNavError] = None
        self._reason = ""
        self._thread: Optional[threading.Thread] = None

    @property
    def state(self) -> LoadState:
        with self._lock:
            return self._state

    def elapsed_s(self) -> float:
        """[s] since :meth:`start` (0 before)."""
        with self._lock:
            return 0.0 if self._state is LoadState.READY else self._clock() - self._started_s

    def start(self) -> None:
        with self._lock:
            if self._state is not LoadState.READY:
                raise BehaviorCommandError(f"the load of {self.what} was already started ({self._state.value})")
            self._state = LoadState.LOADING
            self._started_s = self._clock()
        self._thread = threading.Thread(target=self._work, name=f"load {self.what}", daemon=True)
        self._thread.start()

    def worker_alive(self) -> bool:
        """Whether the worker thread still runs (an abandoned one may, until build() returns)."""
        return self._thread is not None and self._thread.is_alive()

    def _work(self) -> None:
        value: Optional[T] = None
        error: Optional[FlexNavError] = None
        try:
            value = self._build()
        except FlexNavError as err:
            error = err
        except BaseException as err:  # anything build() raises becomes a typed answer
            error = BehaviorLoadError(f"loading {self.what} failed: {type(err).__name__}: {err}")
            error.__cause__ = err
        with self._lock:
            if self._state is LoadState.LOADING:
                self._value, self._error = value, error
                self._state = LoadState.DONE if error is None else LoadState.FAILED
                self._finished.set()
                return
        if value is not None:  # abandoned meanwhile: the result is never used
            self._discard(value)

    def cancel(self, reason: str) -> bool:
        """Abandon the load if it is still loading (True); its result, if it comes, is discarded."""
        with self._lock:
            if self._state is not LoadState.LOADING:
                return False
            self._state, self._reason = LoadState.CANCELLED, reason
            self._finished.set()
            return True

    def wait(self) -> T:
        """The result, once: blocks until the load ended, at most until ``timeout_s`` after :meth:`start`.

        Raises what the load raised (a FlexNavError), TimedOutError when it took too long (the load is then
        abandoned), BehaviorCommandError when it was cancelled or was never started.
        """
        with self._lock:
            if self._state is LoadState.READY:
                raise BehaviorCommandError(f"the load of {self.what} was not started")
            left_s = self._started_s + self.timeout_s - self._clock()
        self._finished.wait(max(0.0, left_s))
        with self._lock:
            if self._state is LoadState.LOADING:
                self._state = LoadState.TIMED_OUT
                self._finished.set()
            state, value, error = self._state, self._value, self._error
            self._value = None  # handed over once
        if state is LoadState.DONE and value is not None:
            return value
        if state is LoadState.FAILED and error is not None:
            raise error
        if state is LoadState.TIMED_OUT:
            raise TimedOutError(
                f"loading {self.what} took longer than {self.timeout_s:g} s (the load time limit); "
                "it was abandoned and will not start"
            )
        if state is LoadState.CANCELLED:
            raise BehaviorCommandError(f"loading {self.what} was cancelled: {self._reason}")
        raise BehaviorCommandError(f"the result of loading {self.what} was already taken")


__all__ = ["BackgroundLoad", "LoadState"]
