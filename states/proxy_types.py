"""What states use of the behavior's proxies: the interface of :class:`flex_nav.ros.proxies.RosProxies`.

States are typed against these protocols, not against the ROS implementation, so they import no rospy and
run unchanged on the test double (``test/unit/states/fake_proxies.py``). :func:`proxies_of` fetches the
proxies of the behavior a state runs in (``NotReadyError`` if its runner injected none).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Callable, Optional, Protocol, cast

if TYPE_CHECKING:
    from flex_nav.behavior.state import State


class PublisherLike(Protocol):
    def publish(self, msg: Any) -> None: ...


class SubscriptionLike(Protocol):
    topic: str

    def has_msg(self) -> bool: ...

    def last(self) -> Optional[Any]: ...

    def age_s(self) -> float:
        """[s] wall time since the newest message arrived (inf if none)."""
        ...

    def remove_last(self) -> None: ...

    def has_buffered(self) -> bool: ...

    def pop_buffered(self) -> Optional[Any]: ...

    def add_callback(self, callback: Callable[[Any], None]) -> None:
        """Also call ``callback(msg)`` for every message (in the transport's thread)."""
        ...


class ActionClientLike(Protocol):
    name: str

    def is_available(self, timeout_s: float = 0.0) -> bool: ...

    def send_goal(self, goal: Any, server_timeout_s: float = 5.0) -> None: ...

    def has_result(self) -> bool: ...

    def result(self) -> Any: ...

    def state(self) -> int:
        """actionlib_msgs/GoalStatus value of the last goal."""
        ...

    def feedback(self) -> Any: ...

    def is_active(self) -> bool: ...

    def cancel(self) -> None: ...


class ProxiesLike(Protocol):
    def publisher(self, topic: str, msg_type: type, latch: bool = False, queue_size: int = 10) -> PublisherLike: ...

    def subscription(self, topic: str, msg_type: type, buffer_size: int = 0) -> SubscriptionLike: ...

    def action_client(self, name: str, action_type: type) -> ActionClientLike: ...


def proxies_of(state: State) -> ProxiesLike:
    """The proxies of the behavior ``state`` runs in."""
    return cast(ProxiesLike, state.context.require_proxies())
