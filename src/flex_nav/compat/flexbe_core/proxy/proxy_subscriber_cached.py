"""FlexBE's ProxySubscriberCached: process-wide cached subscriptions by topic (see :mod:`.hub`).

The newest message of each topic is cached for the whole process (and, once buffered, every message until taken):
``get_last_msg``, ``has_msg``, ``remove_last_msg``, ``enable_buffer`` / ``disable_buffer``, ``has_buffered``,
``get_from_buffer``, ``make_persistant``; ``subscribe(callback=...)`` / ``set_callback`` add callbacks;
``unsubscribe_topic`` drops the topic's cache and callbacks for every proxy of the process (as in FlexBE). As in
FlexBE, ``_callback(msg, topic)`` is what receiving does, so tests inject messages by calling it.
"""

from __future__ import annotations

import threading
from typing import Any, Callable, ClassVar, Dict, List, Optional

from flex_nav.compat.flexbe_core.logger import Logger
from flex_nav.compat.flexbe_core.proxy.hub import on_reset, process_proxies

Callback = Callable[[Any], None]


class _Topic:
    """The process-wide cache of one topic."""

    __slots__ = ("buffered", "callbacks", "feed", "last_msg", "msg_queue", "msg_type", "source")

    def __init__(self, msg_type: type, buffered: bool) -> None:
        self.msg_type = msg_type
        self.last_msg: Any = None
        self.buffered = buffered
        self.msg_queue: List[Any] = []
        self.callbacks: List[Callback] = []
        self.source: Any = None  # the connection's subscription (it calls ``feed``)
        self.feed: Optional[Callback] = None


class ProxySubscriberCached:
    """Cached subscriptions shared by the whole process, by topic (``ProxySubscriberCached({'/scan': LaserScan})``)."""

    _topics: ClassVar[Dict[str, _Topic]] = {}
    _persistant_topics: ClassVar[List[str]] = []
    _lock: ClassVar[threading.RLock] = threading.RLock()

    def __init__(self, topics: Optional[Dict[str, type]] = None) -> None:
        for topic, msg_type in (topics or {}).items():
            self.subscribe(topic, msg_type)

    def subscribe(
        self, topic: str, msg_type: type, callback: Optional[Callback] = None, buffered: bool = False
    ) -> None:
        """Subscribe ``topic`` (once per process); ``buffered`` keeps every message until taken; ``callback(msg)``
        is called for every message."""
        with self._lock:
            entry = ProxySubscriberCached._topics.get(topic)
            if entry is None:
                entry = ProxySubscriberCached._topics[topic] = _Topic(msg_type, buffered)
                source = process_proxies().subscription(topic, msg_type)

                def feed(msg: Any, name: str = topic) -> None:
                    self._callback(msg, name)

                entry.source, entry.feed = source, feed
                source.add_callback(feed)
            if callback is not None:
                entry.callbacks.append(callback)

    def _callback(self, msg: Any, topic: str) -> None:
        """A message of ``topic`` arrived: cache it, buffer it if buffered, call the topic's callbacks."""
        with self._lock:
            entry = ProxySubscriberCached._topics.get(topic)
            if entry is None:
                return
            entry.last_msg = msg
            if entry.buffered:
                entry.msg_queue.append(msg)
            callbacks = list(entry.callbacks)
        for callback in callbacks:
            callback(msg)

    def set_callback(self, topic: str, callback: Callback) -> None:
        with self._lock:
            self._entry(topic).callbacks.append(callback)

    def enable_buffer(self, topic: str) -> None:
        with self._lock:
            self._entry(topic).buffered = True

    def disable_buffer(self, topic: str) -> None:
        with self._lock:
            entry = self._entry(topic)
            entry.buffered = False
            entry.msg_queue = []

    def is_available(self, topic: str) -> bool:
        """True if some proxy of this process subscribes ``topic``."""
        return topic in ProxySubscriberCached._topics

    def get_last_msg(self, topic: str) -> Any:
        """The newest message of ``topic`` (None if none arrived since it was last removed, or not subscribed)."""
        entry = ProxySubscriberCached._topics.get(topic)
        if entry is None:
            Logger.logwarn(f"ProxySubscriberCached: topic {topic} is not subscribed")
            return None
        return entry.last_msg

    def has_msg(self, topic: str) -> bool:
        entry = ProxySubscriberCached._topics.get(topic)
        return entry is not None and entry.last_msg is not None

    def get_from_buffer(self, topic: str) -> Any:
        """The oldest buffered message not yet taken, or None."""
        with self._lock:
            entry = self._entry(topic)
            if not entry.buffered:
                Logger.logwarn("Attempted to access buffer of non-buffered topic!")
                return None
            return entry.msg_queue.pop(0) if entry.msg_queue else None

    def has_buffered(self, topic: str) -> bool:
        entry = ProxySubscriberCached._topics.get(topic)
        return entry is not None and bool(entry.msg_queue)

    def remove_last_msg(self, topic: str, clear_buffer: bool = False) -> None:
        """Forget the cached message (``has_msg`` waits for a new one); optionally empty the buffer too."""
        if topic in ProxySubscriberCached._persistant_topics:
            return
        with self._lock:
            entry = self._entry(topic)
            entry.last_msg = None
            if clear_buffer:
                entry.msg_queue = []

    def make_persistant(self, topic: str) -> None:
        """Messages of ``topic`` can no longer be removed, only replaced by newer ones."""
        if topic not in ProxySubscriberCached._persistant_topics:
            ProxySubscriberCached._persistant_topics.append(topic)

    def has_topic(self, topic: str) -> bool:
        return self.is_available(topic)

    def unsubscribe_topic(self, topic: str) -> None:
        """Drop ``topic``: its cache and callbacks, for every proxy of the process (subscribe again to use it)."""
        with self._lock:
            entry = ProxySubscriberCached._topics.pop(topic, None)
        if entry is not None and entry.source is not None and entry.feed is not None:
            entry.source.remove_callback(entry.feed)

    def shutdown(self) -> None:
        """Drop every topic (FlexBE calls this when its node shuts down)."""
        for topic in list(ProxySubscriberCached._topics):
            self.unsubscribe_topic(topic)

    def _entry(self, topic: str) -> _Topic:
        entry = ProxySubscriberCached._topics.get(topic)
        if entry is None:
            raise KeyError(
                f"ProxySubscriberCached: topic {topic!r} is not subscribed; call subscribe(topic, type) first"
            )
        return entry


def _reset() -> None:
    ProxySubscriberCached._topics.clear()
    ProxySubscriberCached._persistant_topics.clear()


on_reset(_reset)

__all__ = ["ProxySubscriberCached"]
