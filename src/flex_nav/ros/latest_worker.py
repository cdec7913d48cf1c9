"""Handling a subscription's newest message on a thread of its own.

rospy delivers the messages of one topic to every subscriber *of one process* from one receiving thread, one
callback after another. A callback that waits there -- for a transform at the message's stamp, say -- delays every
other callback of that topic in the process. When several components share a process (the ``navigation`` node),
a costmap waiting for ``map -> odom`` at a scan's stamp would hold back the localizer that publishes it from the
same scan. A :class:`LatestWorker` takes the message at once and hands the newest one to its own thread; a message
not yet taken is replaced by a newer one (the ``queue_size=1`` rule of the subscription, kept).

In the simulator's lockstep mode (:mod:`flex_nav.ros.lockstep`) a worker subscribed by :meth:`LatestWorker.subscribe`
holds the simulation after each message on its topic until it has handled it, so no message is replaced unseen.
"""

from __future__ import annotations

import threading
from typing import Callable, Generic, Optional, TypeVar

import rospy

from flex_nav.ros.lockstep import LockstepParticipant

Message = TypeVar("Message")
IDLE_WAIT_S = 0.5  # [s] wall: longest sleep between checks for shutdown
NEXT_STAMP_S = 1e-6  # [s] a hold "after this message" waits for a message stamped at least this much later


class LatestWorker(Generic[Message]):
    """Calls ``handle(message)`` on a daemon thread named ``name`` for the newest message :meth:`offer` got."""

    def __init__(self, handle: Callable[[Message], None], name: str) -> None:
        self._handle = handle
        self._ready = threading.Condition()
        self._next: Optional[Message] = None
        self._closed = False
        self.replaced = 0  # messages replaced by a newer one before the thread took them
        self._lockstep: Optional[LockstepParticipant] = None
        self._topic = ""
        self._thread = threading.Thread(target=self._loop, name=name, daemon=True)
        self._thread.start()

    def subscribe(self, topic: str, msg_type: type, participant: LockstepParticipant,
                  buff_size: int = rospy.topics.DEFAULT_BUFF_SIZE) -> rospy.Subscriber:
        """Subscribe :meth:`offer` to ``topic`` (queue_size 1); in lockstep mode, after handling each message (it has
        a header), hold the simulation at the next one (``participant``'s hold on the resolved topic)."""
        subscriber = rospy.Subscriber(topic, msg_type, self.offer, queue_size=1, buff_size=buff_size)
        self._topic = subscriber.resolved_name
        self._lockstep = participant
        return subscriber

    def offer(self, message: Message) -> None:
        """The subscription's callback: keeps ``message`` as the newest and wakes the thread; never waits."""
        with self._ready:
            if self._next is not None:
                self.replaced += 1
            self._next = message
            self._ready.notify()

    def close(self, timeout_s: float = 2.0) -> None:
        """Stop the thread once it has finished the message in hand (waits at most ``timeout_s`` [s]); a closed
        worker holds the simulation no longer."""
        with self._ready:
            self._closed = True
            self._ready.notify()
        self._thread.join(timeout_s)
        if self._lockstep is not None:
            self._lockstep.release()

    def _loop(self) -> None:
        while True:
            with self._ready:
                while self._next is None and not self._closed and not rospy.is_shutdown():
                    self._ready.wait(IDLE_WAIT_S)
                if self._closed or rospy.is_shutdown():
                    return
                message, self._next = self._next, None
            if message is not None:
                try:
                    self._handle(message)
                finally:
                    if self._lockstep is not None:
                        stamp_s = message.header.stamp.to_sec()  # type: ignore[attr-defined]
                        self._lockstep.hold_topic(self._topic, stamp_s + NEXT_STAMP_S)
