"""FlexBE's ProxyPublisher on the behavior's connection hub: ``createPublisher``, ``publish``, ``wait_for_any``."""

from __future__ import annotations

import time
from typing import Any, Dict, Optional

from flex_nav.behavior.proxies import Proxies, PublisherLike
from flex_nav.compat.flexbe_core.proxy.hub import Binding

WAIT_POLL_S = 0.01  # [s] poll period of wait_for_any


class ProxyPublisher:
    """Publishers of the current behavior, by topic (``ProxyPublisher({'/cmd_vel': Twist})``)."""

    def __init__(self, topics: Optional[Dict[str, type]] = None, _latch: bool = False, _queue_size: int = 100) -> None:
        self._binding = Binding("ProxyPublisher", set_up_by="createPublisher", set_up_as="created")
        self._topics: Dict[str, type] = {}
        for topic, msg_type in (topics or {}).items():
            self.createPublisher(topic, msg_type, _latch, _queue_size)

    def createPublisher(  # noqa: N802  (FlexBE's name)
        self, topic: str, msg_type: type, _latch: bool = False, _queue_size: int = 100
    ) -> None:
        """Advertise ``topic`` for this behavior (shared with its other states)."""
        self._topics[topic] = msg_type

        def create(hub: Proxies) -> None:
            hub.publisher(topic, msg_type, latch=_latch, queue_size=_queue_size)

        self._binding.setup(create)

    def is_available(self, topic: str) -> bool:
        """True if a publisher for ``topic`` exists in this behavior (created by any of its states)."""
        hub = self._binding.peek()
        if hub is None:
            return topic in self._topics
        return hub.get_publisher(topic) is not None

    def publish(self, topic: str, msg: Any) -> None:
        """Publish ``msg`` on ``topic`` (NotReadyError if no state of this behavior created the publisher)."""
        self._publisher(topic).publish(msg)

    def wait_for_any(self, topic: str, timeout: float = 5.0) -> bool:
        """Wait (at most ``timeout`` [s]) until ``topic`` has a subscriber; False when the wait runs out."""
        pub = self._publisher(topic)
        deadline = time.monotonic() + max(0.0, timeout)
        while pub.get_num_connections() < 1:
            if time.monotonic() >= deadline:
                return False
            time.sleep(WAIT_POLL_S)
        return True

    def _publisher(self, topic: str) -> PublisherLike:
        pub = self._binding.hub().get_publisher(topic)
        return self._binding.require(pub, f"no publisher for topic {topic!r}", self._topics)


__all__ = ["ProxyPublisher"]
