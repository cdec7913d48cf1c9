"""The proxies port: how a behavior's states reach ROS (publishers, subscriptions, action clients, services).

Defined once, here in the pure engine, so that :class:`~flex_nav.behavior.context.BehaviorContext` can type
what its runner injects without importing ROS. Every user of the port is typed against these protocols:

- the state library (:mod:`flex_nav_states.proxy_types` re-exports them) and the FlexBE proxies of the
  compatibility layer (:mod:`flex_nav.compat.flexbe_core.proxy`) call them;
- :class:`flex_nav.ros.proxies.RosProxies` implements them on rospy/actionlib, one instance per running
  behavior (connections shared by name among its states, one message type per name);
- :class:`flex_nav.testing.fake_proxies.FakeProxies` implements them without ROS, on an injected clock, so
  states are tested without a master.

Both implementations are checked against :class:`Proxies` by mypy (a typed assignment at the end of their
modules). Messages, goals, results and requests are genpy objects of the type given when the connection was
made; the protocols leave them as ``Any``. Every wait is bounded by the ``timeout_s`` given (0: just look).
"""

from __future__ import annotations

from typing import Any, Callable, Dict, Optional, Protocol, TypeVar

from flex_nav.exceptions import ConfigError

C = TypeVar("C")


class PublisherLike(Protocol):
    """A topic's publisher (rospy.Publisher in ROS)."""

    def publish(self, msg: Any) -> None: ...

    def get_num_connections(self) -> int:
        """Number of subscribers connected now."""
        ...


class SubscriptionLike(Protocol):
    """The newest message of a topic (and, once enabled, a bounded buffer of the ones not yet taken)."""

    @property
    def topic(self) -> str: ...

    def has_msg(self) -> bool: ...

    def last(self) -> Optional[Any]:
        """The newest message, or None if none arrived (or it was removed)."""
        ...

    def age_s(self) -> float:
        """[s] time since the newest message arrived (inf if none)."""
        ...

    def remove_last(self) -> None:
        """Forget the newest message, so that :meth:`has_msg` waits for a new one."""
        ...

    def enable_buffer(self, size: int = 10) -> None:
        """Also keep up to ``size`` messages until taken by :meth:`pop_buffered` (no-op when buffering)."""
        ...

    def disable_buffer(self) -> None:
        """Stop buffering and drop the buffered messages (the newest message stays)."""
        ...

    def has_buffered(self) -> bool: ...

    def pop_buffered(self) -> Optional[Any]:
        """The oldest buffered message not yet taken, or None."""
        ...

    def add_callback(self, callback: Callable[[Any], None]) -> None:
        """Also call ``callback(msg)`` for every message (in the transport's thread)."""
        ...

    def remove_callback(self, callback: Callable[[Any], None]) -> None: ...


class ActionClientLike(Protocol):
    """A non-blocking action client: one goal at a time; send, poll, cancel."""

    @property
    def name(self) -> str: ...

    def is_available(self, timeout_s: float = 0.0) -> bool:
        """True when the server is connected; waits at most ``timeout_s`` [s] (states pass 0: never block)."""
        ...

    def send_goal(self, goal: Any, server_timeout_s: float = 5.0) -> None:
        """Send ``goal``, replacing any active one; NotReadyError if no server within ``server_timeout_s`` [s]."""
        ...

    def has_result(self) -> bool: ...

    def result(self) -> Any:
        """The result of the last goal (None until it is done, or if the server sent none)."""
        ...

    def state(self) -> int:
        """actionlib_msgs/GoalStatus value of the last goal."""
        ...

    def feedback(self) -> Any: ...

    def forget_result(self) -> None:
        """Drop the stored result, so :meth:`has_result` is False until the next goal finishes."""
        ...

    def forget_feedback(self) -> None: ...

    def is_active(self) -> bool: ...

    def cancel(self) -> None:
        """Cancel the active goal (no-op when none is active)."""
        ...


class ServiceCallerLike(Protocol):
    """A service caller with a bounded wait for the service."""

    def is_available(self, timeout_s: float = 0.0) -> bool: ...

    def call(self, request: Any, timeout_s: float = 5.0) -> Any:
        """The response; NotReadyError if the service is absent after ``timeout_s`` [s] or the call fails."""
        ...


class Proxies(Protocol):
    """The connections of ONE behavior, shared among its states by name (``BehaviorContext.proxies``).

    Asking twice for the same name returns the same connection; asking with another type than the first
    time raises ConfigError. ``get_*`` return the connection some state of the behavior made, or None.
    """

    def publisher(self, topic: str, msg_type: type, latch: bool = False, queue_size: int = 10) -> PublisherLike: ...

    def subscription(self, topic: str, msg_type: type, buffer_size: int = 0) -> SubscriptionLike:
        """The topic's subscription (``buffer_size`` > 0 also enables its buffer)."""
        ...

    def action_client(self, name: str, action_type: type) -> ActionClientLike: ...

    def service_caller(self, name: str, srv_type: type) -> ServiceCallerLike: ...

    def get_publisher(self, topic: str) -> Optional[PublisherLike]: ...

    def get_subscription(self, topic: str) -> Optional[SubscriptionLike]: ...

    def get_action_client(self, name: str) -> Optional[ActionClientLike]: ...

    def get_service_caller(self, name: str) -> Optional[ServiceCallerLike]: ...


class Connections(Dict[str, C]):
    """An implementation's connections of one ``kind`` (topic, action, service) by name; :meth:`shared` keeps the
    rule of :class:`Proxies`: one connection per name, made the first time, and one type per name."""

    def __init__(self, kind: str, type_of: Callable[[C], type]) -> None:
        """``type_of``: the message, action or service type a connection was made with."""
        super().__init__()
        self.kind = kind
        self._type_of = type_of

    def shared(self, name: str, wanted: type, make: Callable[[], C]) -> C:
        """The connection of ``name``, ``make()`` the first time; ConfigError if it has another type than ``wanted``."""
        known = self.get(name)
        if known is None:
            known = self[name] = make()
        elif self._type_of(known) is not wanted:
            raise ConfigError(
                f"{self.kind} {name} is already used with type {self._type_of(known).__name__} in this behavior; "
                f"cannot use it as {wanted.__name__}"
            )
        return known


__all__ = ["ActionClientLike", "Connections", "Proxies", "PublisherLike", "ServiceCallerLike", "SubscriptionLike"]
