"""Helpers for the compatibility-layer tests: a fake per-behavior ROS hub, data paths (no ROS; fixtures: conftest).

FakeHub implements flex_nav.behavior.proxies.Proxies, as RosProxies does (mypy checks it: the end of this module).
Tests drive it directly: ``sub.inject(msg)`` as if a message arrived, ``client.finish(state, result)`` as if the
server answered.
"""

from __future__ import annotations

import collections
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Deque, Dict, List, Optional

from flex_nav.exceptions import NotReadyError

if TYPE_CHECKING:
    from flex_nav.behavior.proxies import Proxies

DATA_DIR = Path(__file__).resolve().parents[2] / "data" / "compat"

# GoalStatus values (actionlib_msgs/GoalStatus), without importing actionlib
PENDING, ACTIVE, PREEMPTED, SUCCEEDED, ABORTED, LOST = 0, 1, 2, 3, 4, 9


class FakePublisher:
    def __init__(self, topic: str, msg_type: type) -> None:
        self.topic = topic
        self.msg_type = msg_type
        self.sent: List[Any] = []
        self.connections = 0

    def publish(self, msg: Any) -> None:
        assert isinstance(msg, self.msg_type), f"{type(msg).__name__} published on {self.topic} ({self.msg_type})"
        self.sent.append(msg)

    def get_num_connections(self) -> int:
        return self.connections


class FakeSubscription:
    def __init__(self, topic: str, msg_type: type, buffer_size: int) -> None:
        self.topic = topic
        self.msg_type = msg_type
        self._last: Any = None
        self._buffered = buffer_size > 0
        self._buffer: Deque[Any] = collections.deque()
        self.callbacks: List[Callable[[Any], None]] = []

    def inject(self, msg: Any) -> None:
        self._last = msg
        if self._buffered:
            self._buffer.append(msg)
        for callback in list(self.callbacks):
            callback(msg)

    def has_msg(self) -> bool:
        return self._last is not None

    def age_s(self) -> float:
        """[s] 0 once a message was injected (as if it arrived now), inf before."""
        return 0.0 if self._last is not None else math.inf

    def last(self) -> Any:
        return self._last

    def remove_last(self) -> None:
        self._last = None

    def enable_buffer(self, size: int = 10) -> None:
        self._buffered = True

    def disable_buffer(self) -> None:
        self._buffered = False
        self._buffer.clear()

    def has_buffered(self) -> bool:
        return bool(self._buffer)

    def pop_buffered(self) -> Any:
        return self._buffer.popleft() if self._buffer else None

    def add_callback(self, callback: Callable[[Any], None]) -> None:
        self.callbacks.append(callback)

    def remove_callback(self, callback: Callable[[Any], None]) -> None:
        if callback in self.callbacks:
            self.callbacks.remove(callback)


class FakeActionClient:
    def __init__(self, name: str, action_type: type, server_up: bool = True) -> None:
        self.name = name
        self.action_type = action_type
        self.server_up = server_up
        self.goals: List[Any] = []
        self.cancels = 0
        self.availability_waits: List[float] = []
        self._state = LOST
        self._result: Any = None
        self._done = False
        self._feedback: Any = None

    def is_available(self, timeout_s: float = 0.0) -> bool:
        self.availability_waits.append(timeout_s)
        return self.server_up

    def send_goal(self, goal: Any, server_timeout_s: float = 5.0) -> None:
        if not self.server_up:
            raise NotReadyError(f"action server {self.name} is not available after {server_timeout_s:.1f} s")
        self.goals.append(goal)
        self._state, self._result, self._done, self._feedback = ACTIVE, None, False, None

    def finish(self, state: int, result: Any) -> None:
        self._state, self._result, self._done = state, result, True

    def give_feedback(self, feedback: Any) -> None:
        self._feedback = feedback

    def has_result(self) -> bool:
        return self._done

    def result(self) -> Any:
        return self._result

    def state(self) -> int:
        return self._state

    def feedback(self) -> Any:
        return self._feedback

    def is_active(self) -> bool:
        return self._state in (PENDING, ACTIVE)

    def cancel(self) -> None:
        if self.is_active():
            self.cancels += 1
            self.finish(PREEMPTED, None)

    def forget_result(self) -> None:
        self._result, self._done = None, False

    def forget_feedback(self) -> None:
        self._feedback = None


class FakeServiceCaller:
    def __init__(self, name: str, srv_type: type, handler: Optional[Callable[[Any], Any]] = None) -> None:
        self.name = name
        self.srv_type = srv_type
        self.handler = handler
        self.requests: List[Any] = []

    def is_available(self, timeout_s: float = 0.0) -> bool:
        return self.handler is not None

    def call(self, request: Any, timeout_s: float = 5.0) -> Any:
        if self.handler is None:
            raise NotReadyError(f"service {self.name} is not available after {timeout_s:.1f} s")
        self.requests.append(request)
        return self.handler(request)


class FakeHub:
    """The connections of one behavior, shared by name (like RosProxies)."""

    def __init__(self, servers_up: bool = True) -> None:
        self.servers_up = servers_up
        self.publishers: Dict[str, FakePublisher] = {}
        self.subscriptions: Dict[str, FakeSubscription] = {}
        self.action_clients: Dict[str, FakeActionClient] = {}
        self.services: Dict[str, FakeServiceCaller] = {}
        self.service_handlers: Dict[str, Callable[[Any], Any]] = {}

    def publisher(self, topic: str, msg_type: type, latch: bool = False, queue_size: int = 10) -> FakePublisher:
        return self.publishers.setdefault(topic, FakePublisher(topic, msg_type))

    def subscription(self, topic: str, msg_type: type, buffer_size: int = 0) -> FakeSubscription:
        sub = self.subscriptions.setdefault(topic, FakeSubscription(topic, msg_type, buffer_size))
        if buffer_size > 0:
            sub.enable_buffer(buffer_size)
        return sub

    def action_client(self, name: str, action_type: type) -> FakeActionClient:
        return self.action_clients.setdefault(name, FakeActionClient(name, action_type, self.servers_up))

    def service_caller(self, name: str, srv_type: type) -> FakeServiceCaller:
        return self.services.setdefault(name, FakeServiceCaller(name, srv_type, self.service_handlers.get(name)))

    def get_publisher(self, topic: str) -> Optional[FakePublisher]:
        return self.publishers.get(topic)

    def get_subscription(self, topic: str) -> Optional[FakeSubscription]:
        return self.subscriptions.get(topic)

    def get_action_client(self, name: str) -> Optional[FakeActionClient]:
        return self.action_clients.get(name)

    def get_service_caller(self, name: str) -> Optional[FakeServiceCaller]:
        return self.services.get(name)


if TYPE_CHECKING:  # mypy: FakeHub (and so its publisher, subscription, action client, service caller) is a Proxies
    _CONFORMS: Proxies = FakeHub()
