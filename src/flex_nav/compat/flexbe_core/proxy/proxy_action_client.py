"""FlexBE's ProxyActionClient: process-wide action clients by action name (see :mod:`.hub`).

``setupClient`` creates the client once per process and waits a bounded time for the server, logging an error if
it is not there (as FlexBE does); ``send_goal`` waits at most ``SEND_GOAL_SERVER_WAIT_S`` and raises
:class:`~flex_nav.exceptions.NotReadyError` if the server is still missing. Results and feedback belong to the
client, as in FlexBE (two states of one process that use the same action share them): ``has_result`` /
``get_result`` / ``remove_result``, ``has_feedback`` / ``get_feedback`` / ``remove_feedback``, ``get_state`` (an
``actionlib_msgs/GoalStatus`` value), ``is_active``, ``cancel``.
"""

from __future__ import annotations

from typing import Any, ClassVar, Dict, Optional

from flex_nav.behavior.proxies import ActionClientLike
from flex_nav.compat.flexbe_core.logger import Logger
from flex_nav.compat.flexbe_core.proxy.hub import on_reset, process_proxies
from flex_nav.exceptions import NotReadyError

SEND_GOAL_SERVER_WAIT_S = 1.0  # [s] longest wait for the server when sending a goal (setupClient waited already)


class ProxyActionClient:
    """Action clients shared by the whole process (``ProxyActionClient({'move': MoveAction})``)."""

    _clients: ClassVar[Dict[str, type]] = {}  # action name -> action type, as set up by any proxy of the process

    def __init__(self, topics: Optional[Dict[str, type]] = None, wait_duration: float = 10) -> None:
        for topic, msg_type in (topics or {}).items():
            self.setupClient(topic, msg_type, wait_duration)

    def setupClient(self, topic: str, msg_type: type, wait_duration: float = 10) -> None:  # noqa: N802  (FlexBE's name)
        """Create the client for ``topic`` (once per process); wait at most ``wait_duration`` [s] for its server."""
        client = process_proxies().action_client(topic, msg_type)
        ProxyActionClient._clients[topic] = msg_type
        if wait_duration > 0 and not client.is_available(float(wait_duration)):
            Logger.logerr(f"Action client {topic} timed out: no server after {float(wait_duration):.1f} s")

    def send_goal(self, topic: str, goal: Any) -> None:
        """Send ``goal`` (replacing the client's previous goal; its result and feedback are forgotten)."""
        self._client(topic).send_goal(goal, server_timeout_s=SEND_GOAL_SERVER_WAIT_S)

    def is_available(self, topic: str) -> bool:
        """True if the client is set up in this process and its server is connected."""
        if topic not in ProxyActionClient._clients:
            return False
        client = process_proxies().get_action_client(topic)
        return client is not None and bool(client.is_available(0.0))

    def has_result(self, topic: str) -> bool:
        return self._client(topic).has_result()

    def get_result(self, topic: str) -> Any:
        return self._client(topic).result()

    def remove_result(self, topic: str) -> None:
        self._client(topic).forget_result()

    def has_feedback(self, topic: str) -> bool:
        return self._client(topic).feedback() is not None

    def get_feedback(self, topic: str) -> Any:
        return self._client(topic).feedback()

    def remove_feedback(self, topic: str) -> None:
        self._client(topic).forget_feedback()

    def get_state(self, topic: str) -> int:
        """actionlib_msgs/GoalStatus value of the last goal."""
        return self._client(topic).state()

    def is_active(self, topic: str) -> bool:
        return self._client(topic).is_active()

    def cancel(self, topic: str) -> None:
        self._client(topic).cancel()

    def _client(self, topic: str) -> ActionClientLike:
        client = process_proxies().get_action_client(topic) if topic in ProxyActionClient._clients else None
        if client is None:
            raise NotReadyError(
                f"ProxyActionClient: action {topic!r} is not set up; call setupClient(topic, type) first "
                f"(set up in this process: {', '.join(ProxyActionClient._clients) or 'none'})"
            )
        return client


on_reset(ProxyActionClient._clients.clear)

__all__ = ["ProxyActionClient"]
