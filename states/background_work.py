"""BackgroundWork: something slow a state needs (a blocking service call, a search over a large map) in a daemon
thread, so that ``execute`` never blocks: it starts the work once and polls it on later ticks.

The state keeps its own deadline on the behavior's clock and forgets work it no longer wants (a timeout, the state
left): the thread then ends on its own and its result is dropped. Whatever the work raises is handed back by
:meth:`BackgroundWork.result`, never lost in the thread.
"""

from __future__ import annotations

import threading
from typing import Callable, Generic, Optional, TypeVar, cast

from flex_nav.exceptions import NotReadyError

T = TypeVar("T")

POLL_WAIT_S = 0.005  # [s] wall time a poll waits for the work at most (work that is quick is seen in the same tick)


class BackgroundWork(Generic[T]):
    """``work()`` running in a daemon thread named ``what``, started when made."""

    def __init__(self, what: str, work: Callable[[], T]) -> None:
        self.what = what
        self._work = work
        self._finished = threading.Event()
        self._value: Optional[T] = None
        self._error: Optional[Exception] = None
        threading.Thread(target=self._run, name=what, daemon=True).start()

    def _run(self) -> None:
        try:
            self._value = self._work()
        except Exception as err:  # handed to the state by result()
            self._error = err
        self._finished.set()

    def done(self, wait_s: float = POLL_WAIT_S) -> bool:
        """Whether the work has ended; waits at most ``wait_s`` [s] of wall time for it."""
        return self._finished.wait(wait_s)

    def result(self) -> T:
        """What ``work()`` returned, or raise what it raised; only once :meth:`done`."""
        if not self._finished.is_set():
            raise NotReadyError(f"{self.what}: the result was asked for before the work ended")
        if self._error is not None:
            raise self._error
        return cast(T, self._value)  # set by _run when it raised nothing
