"""FlexBE's ProxySubscriberCached on the behavior's connection hub.

The newest message of each topic is cached (and optionally buffered) by the hub's subscription, shared
by all states of the behavior that subscribe to the topic: ``get_last_msg``, ``has_msg``,
``remove_last_msg``, ``enable_buffer`` / ``disable_buffer``, ``has_buffered``, ``get_from_buffer``.
``unsubscribe_topic`` removes this proxy's callbacks; the connection itself is shared with the
behavior's other states and closed when the behavior ends.
"""

from __future__ import annotations

from typing import Any, Callable, Dict, List, Optional, Tuple

from flex_nav.behavior.proxies import Proxies, SubscriptionLike
from flex_nav.compat.flexbe_core.proxy.hub import Binding

DEFAULT_BUFFER_SIZE = 100  # messages kept per buffered topic


class ProxySubscriberCached:
    """Cached subscriptions of the current behavior, by topic (``ProxySubscriberCached({'/scan': LaserScan})``)."""

    def __init__(self, topics: Optional[Dict[str, type]] = None) -> None:
        self._binding = Binding("ProxySubscriberCached", set_up_by="subscribe", set_up_as="subscribed")
        self._topics: Dict[str, type] = {}
        self._callbacks: List[Tuple[str, Callable[[Any], None]]] = []
        for topic, msg_type in (topics or {}).items():
            self.subscribe(topic, msg_type)

    def subscribe(
        self, topic: str, msg_type: type, callback: Optional[Callable[[Any], None]] = None, buffered: bool = False
    ) -> None:
        """Subscribe ``topic`` (cached; ``buffered`` keeps every message until taken); ``callback(msg)`` per message."""
        self._topics[topic] = msg_type

        def create(hub: Proxies) -> None:
            sub = hub.subscription(topic, msg_type, buffer_size=DEFAULT_BUFFER_SIZE if buffered else 0)
            if callback is not None:
                sub.add_callback(callback)
                self._callbacks.append((topic, callback))

        self._binding.setup(create)

    def set_callback(self, topic: str, callback: Callable[[Any], None]) -> None:
        self._sub(topic).add_callback(callback)
        self._callbacks.append((topic, callback))

    def enable_buffer(self, topic: str) -> None:
        self._sub(topic).enable_buffer(DEFAULT_BUFFER_SIZE)

    def disable_buffer(self, topic: str) -> None:
        self._sub(topic).disable_buffer()

    def is_available(self, topic: str) -> bool:
        """True if this behavior subscribes ``topic``."""
        hub = self._binding.peek()
        if hub is None:
            return topic in self._topics
        return hub.get_subscription(topic) is not None

    def get_last_msg(self, topic: str) -> Any:
        """The newest message of ``topic`` (None if none arrived since it was last removed)."""
        return self._sub(topic).last()

    def has_msg(self, topic: str) -> bool:
        hub = self._binding.peek()
        sub = hub.get_subscription(topic) if hub is not None else None
        return sub is not None and bool(sub.has_msg())

    def remove_last_msg(self, topic: str, clear_buffer: bool = False) -> None:
        """Forget the cached message (``has_msg`` waits for a new one); optionally empty the buffer too."""
        sub = self._sub(topic)
        sub.remove_last()
        if clear_buffer:
            while sub.pop_buffered() is not None:
                pass

    def has_buffered(self, topic: str) -> bool:
        return self._sub(topic).has_buffered()

    def get_from_buffer(self, topic: str) -> Any:
        """The oldest buffered message not yet taken, or None."""
        return self._sub(topic).pop_buffered()

    def unsubscribe_topic(self, topic: str) -> None:
        """Remove this proxy's callbacks of ``topic`` (the shared connection stays until the behavior ends)."""
        keep: List[Tuple[str, Callable[[Any], None]]] = []
        for cb_topic, callback in self._callbacks:
            if cb_topic == topic:
                self._sub(topic).remove_callback(callback)
            else:
                keep.append((cb_topic, callback))
        self._callbacks = keep

    def _sub(self, topic: str) -> SubscriptionLike:
        sub = self._binding.hub().get_subscription(topic)
        return self._binding.require(sub, f"topic {topic!r} is not subscribed", self._topics)


__all__ = ["ProxySubscriberCached"]
