"""Handling a subscription's newest message on a thread of its own.

rospy delivers the messages of one topic to every subscriber *of one process* from one receiving thread, one
callback after another. A callback that waits there -- for a transform at the message's stamp, say -- delays every
other callback of that topic in the process. When several components share a process (the ``navigation`` node),
a costmap waiting for ``map -> odom`` at a scan's stamp would hold back the localizer that publishes it from the
same scan. A :class:`LatestWorker` takes the message at once and hands the newest one to its own thread; a message
not yet taken is replaced by a newer one (the ``queue_size=1`` rule of the subscription, kept).
"""

from __future__ import annotations

import threading
from typing import Callable, Generic, Optional, TypeVar

import rospy

Message = TypeVar("Message")
IDLE_WAIT_S = 0.5  # [s] wall: longest sleep between checks for shutdown


class LatestWorker(Generic[Message]):
    """Calls ``handle(message)`` on a daemon thread named ``name`` for the newest message :meth:`offer` got."""

    def __init__(self, handle: Callable[[Message], None], name: str) -> None:
        self._handle = handle
        self._ready = threading.Condition()
        self._next: Optional[Message] = None
        self._closed = False
        self.replaced = 0  # messages replaced by a newer one before the thread took them
        self._thread = threading.Thread(target=self._loop, name=name, daemon=True)
        self._thread.start()

    def offer(self, message: Message) -> None:
        """The subscription's callback: keeps ``message`` as the newest and wakes the thread; never waits."""
        with self._ready:
            if self._next is not None:
                self.replaced += 1
            self._next = message
            self._ready.notify()

    def close(self, timeout_s: float = 2.0) -> None:
        """Stop the thread once it has finished the message in hand (waits at most ``timeout_s`` [s])."""
        with self._ready:
            self._closed = True
            self._ready.notify()
        self._thread.join(timeout_s)

    def _loop(self) -> None:
        while True:
            with self._ready:
                while self._next is None and not self._closed and not rospy.is_shutdown():
                    self._ready.wait(IDLE_WAIT_S)
                if self._closed or rospy.is_shutdown():
                    return
                message, self._next = self._next, None
            if message is not None:
                self._handle(message)
