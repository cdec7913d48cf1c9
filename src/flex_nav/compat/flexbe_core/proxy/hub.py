"""Which behavior's connections a FlexBE proxy uses, and what it needs from them.

FlexBE's proxies keep their publishers, subscribers and clients in class-level dicts: one set per
process, shared by every behavior. Here a proxy object uses the connection hub of ONE behavior: the
``proxies`` of the behavior context current when the proxy was created (states build their proxies in
``__init__``, which :func:`flex_nav.compat.flexbe_core.build_behavior` runs inside the behavior's
context), or, if there was none, the context running when the proxy is first used. Within that
behavior the hub shares connections by name (two states asking for the same topic get one
subscriber); two behaviors never share anything.

The hub is what the ROS runner injects as ``BehaviorContext.proxies``:
:class:`flex_nav.ros.proxies.RosProxies`. :class:`ProxyHub` and the ``*Like`` protocols below are the
part of its interface the FlexBE proxies use (pure unit tests implement them with fakes).
"""

from __future__ import annotations

from typing import Any, Callable, List, Optional, Protocol

from flex_nav.behavior.context import current_context
from flex_nav.exceptions import NotReadyError


class PublisherLike(Protocol):
    def publish(self, msg: Any) -> None: ...

    def get_num_connections(self) -> int: ...


class SubscriptionLike(Protocol):
    def has_msg(self) -> bool: ...

    def last(self) -> Any: ...

    def remove_last(self) -> None: ...

    def enable_buffer(self, size: int = ...) -> None: ...

    def disable_buffer(self) -> None: ...

    def has_buffered(self) -> bool: ...

    def pop_buffered(self) -> Any: ...

    def add_callback(self, callback: Callable[[Any], None]) -> None: ...

    def remove_callback(self, callback: Callable[[Any], None]) -> None: ...


class ActionClientLike(Protocol):
    def is_available(self, timeout_s: float = ...) -> bool: ...

    def send_goal(self, goal: Any, server_timeout_s: float = ...) -> None: ...

    def has_result(self) -> bool: ...

    def result(self) -> Any: ...

    def state(self) -> int: ...

    def feedback(self) -> Any: ...

    def is_active(self) -> bool: ...

    def cancel(self) -> None: ...

    def forget_result(self) -> None: ...

    def forget_feedback(self) -> None: ...


class ServiceCallerLike(Protocol):
    def is_available(self, timeout_s: float = ...) -> bool: ...

    def call(self, request: Any, timeout_s: float = ...) -> Any: ...


class ProxyHub(Protocol):
    """The per-behavior connection hub (RosProxies) as the FlexBE proxies use it."""

    def publisher(self, topic: str, msg_type: type, latch: bool = ..., queue_size: int = ...) -> Any: ...

    def subscription(self, topic: str, msg_type: type, buffer_size: int = ...) -> Any: ...

    def action_client(self, name: str, action_type: type) -> Any: ...

    def service_caller(self, name: str, srv_type: type) -> Any: ...

    def get_publisher(self, topic: str) -> Any: ...

    def get_subscription(self, topic: str) -> Any: ...

    def get_action_client(self, name: str) -> Any: ...

    def get_service_caller(self, name: str) -> Any: ...


class Binding:
    """The hub of one FlexBE proxy object, with the setup calls made before a hub was known."""

    __slots__ = ("_hub", "_owner", "_pending")

    def __init__(self, owner: str) -> None:
        self._owner = owner
        self._hub: Optional[ProxyHub] = self._current_hub()
        self._pending: List[Callable[[ProxyHub], None]] = []

    @staticmethod
    def _current_hub() -> Optional[ProxyHub]:
        ctx = current_context()
        return ctx.proxies if ctx is not None else None

    @property
    def bound(self) -> bool:
        return self._hub is not None

    def setup(self, action: Callable[[ProxyHub], None]) -> None:
        """Run ``action(hub)`` now if a hub is known, else when the proxy is first used in a running behavior."""
        hub = self._hub if self._hub is not None else self._bind()
        if hub is None:
            self._pending.append(action)
        else:
            action(hub)

    def peek(self) -> Optional[ProxyHub]:
        """The hub if one is known or a running behavior provides one now, else None (never raises)."""
        return self._hub if self._hub is not None else self._bind()

    def hub(self) -> ProxyHub:
        """The hub, binding to the running behavior's on first use; NotReadyError outside any behavior."""
        hub = self._hub if self._hub is not None else self._bind()
        if hub is None:
            raise NotReadyError(
                f"{self._owner} is used outside a behavior that has ROS proxies: create and use it while a "
                "flex_nav behavior runs (or is built) with proxies injected by its runner"
            )
        return hub

    def _bind(self) -> Optional[ProxyHub]:
        hub = self._current_hub()
        if hub is None:
            return None
        self._hub = hub
        pending, self._pending = self._pending, []
        for action in pending:
            action(hub)
        return hub


__all__ = [
    "ActionClientLike",
    "Binding",
    "ProxyHub",
    "PublisherLike",
    "ServiceCallerLike",
    "SubscriptionLike",
]
