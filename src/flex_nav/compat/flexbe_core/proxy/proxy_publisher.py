"""FlexBE's ProxyPublisher: process-wide publishers by topic (see :mod:`.hub`): ``createPublisher``, ``publish``,
``is_available``, ``wait_for_any``."""

from __future__ import annotations

import time
from typing import Any, ClassVar, Dict, Optional

from flex_nav.compat.flexbe_core.logger import Logger
from flex_nav.compat.flexbe_core.proxy.hub import on_reset, process_proxies

WAIT_POLL_S = 0.01  # [s] poll period of wait_for_any


class ProxyPublisher:
    """Publishers shared by the whole process, by topic (``ProxyPublisher({'/cmd_vel': Twist})``)."""

    _topics: ClassVar[Dict[str, type]] = {}  # topic -> message type, as created by any proxy of the process

    def __init__(self, topics: Optional[Dict[str, type]] = None, _latch: bool = False, _queue_size: int = 100) -> None:
        for topic, msg_type in (topics or {}).items():
            self.createPublisher(topic, msg_type, _latch, _queue_size)

    def createPublisher(  # noqa: N802  (FlexBE's name)
        self, topic: str, msg_type: type, _latch: bool = False, _queue_size: int = 100
    ) -> None:
        """Advertise ``topic`` (once per process; later calls reuse the publisher)."""
        if topic not in ProxyPublisher._topics:
            process_proxies().publisher(topic, msg_type, latch=_latch, queue_size=_queue_size)
            ProxyPublisher._topics[topic] = msg_type

    def is_available(self, topic: str) -> bool:
        """True if some proxy of this process created a publisher for ``topic``."""
        return topic in ProxyPublisher._topics

    def publish(self, topic: str, msg: Any) -> None:
        """Publish ``msg`` on ``topic``; a topic nobody created is logged as a warning (as in FlexBE)."""
        pub = process_proxies().get_publisher(topic) if topic in ProxyPublisher._topics else None
        if pub is None:
            Logger.logwarn(f"ProxyPublisher: topic {topic} not yet registered!")
            return
        pub.publish(msg)

    def wait_for_any(self, topic: str, timeout: float = 5.0) -> bool:
        """Wait (at most ``timeout`` [s]) until ``topic`` has a subscriber; False when the wait runs out."""
        pub = process_proxies().get_publisher(topic) if topic in ProxyPublisher._topics else None
        if pub is None:
            Logger.logerr(f"Publisher {topic} not yet registered, need to add it first!")
            return False
        deadline = time.monotonic() + max(0.0, timeout)
        while pub.get_num_connections() < 1:
            if time.monotonic() >= deadline:
                Logger.logerr(f"Waiting for subscribers on {topic} timed out!")
                return False
            time.sleep(WAIT_POLL_S)
        return True


on_reset(ProxyPublisher._topics.clear)

__all__ = ["ProxyPublisher"]
