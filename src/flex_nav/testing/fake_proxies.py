"""Test doubles of the behavior's proxies (:class:`flex_nav.behavior.proxies.Proxies`): no ROS, no master,
time from the test's clock. Test your own states with them, as the state library's tests do.

- :class:`FakeProxies` is what the runner would inject (``BehaviorContext.proxies``); it keeps what the
  states made by name: ``publishers``, ``subscriptions``, ``clients``, ``services`` (``pub``/``sub`` raise
  KeyError naming the known ones; ``client`` and ``service`` make one so the test can script it before the
  state asks for it).
- :class:`FakePublisher` records every published message with the clock time (``published``, ``messages``).
- :class:`FakeSubscription` takes messages from the test (``inject``); ``last``/``age_s``/``pop_buffered``
  behave as the real one, with arrival ages on the injected clock instead of wall time.
- :class:`FakeActionClient` is scripted: ``available_at_s`` says when its server "connects"; each sent goal
  takes the next queued :class:`Response` (``respond``, answered after its ``delay_s`` on the clock) or stays
  active until the test calls ``finish``; ``cancel`` is recorded and, by default, ends the goal as PREEMPTED
  like a real server.
- :class:`FakeServiceCaller` is scripted too: ``available_at_s`` says when its service appears; each call takes
  the next queued answer (``respond``: a response, or an exception to raise) and records the request.

A user's state tested on a :class:`~flex_nav.behavior.ManualClock` with :class:`FakeProxies`, run by
:class:`flex_nav.testing.state_harness.StateHarness` (which holds both)::

    >>> from std_msgs.msg import Bool, String
    >>> from flex_nav.behavior import State
    >>> from flex_nav.testing.state_harness import StateHarness
    >>> class Greet(State):  # says hello once "go" is True
    ...     def __init__(self): super().__init__(outcomes=["done"])
    ...     def on_start(self):
    ...         p = self.context.require_proxies()
    ...         self.go, self.out = p.subscription("go", Bool), p.publisher("out", String)
    ...     def execute(self, userdata):
    ...         if self.go.has_msg() and self.go.last().data:
    ...             self.out.publish(String(data="hello"))
    ...             return "done"
    ...         return None
    >>> h = StateHarness(Greet()).start()
    >>> h.run_for(1.0)  # ticks for 1 s of the ManualClock: nothing heard, so it keeps running
    >>> h.proxies.sub("go").inject(Bool(data=True))
    >>> h.run().outcome, [m.data for m in h.proxies.pub("out").messages]
    ('done', ['hello'])

Same method names and signatures as :mod:`flex_nav.ros.proxies` (mypy checks :class:`FakeProxies` against
:class:`~flex_nav.behavior.proxies.Proxies` at the end of this module; the unit tests also compare parameter
names and defaults with ``RosProxies``), and the same "one type per topic/action" rule. Nothing here
imports rospy: only the actionlib_msgs message module, for GoalStatus.
"""

from __future__ import annotations

import collections
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Deque, List, Optional, Tuple

from actionlib_msgs.msg import GoalStatus

from flex_nav.behavior.clock import Clock
from flex_nav.behavior.proxies import Connections
from flex_nav.exceptions import NotReadyError

if TYPE_CHECKING:
    from flex_nav.behavior.clock import ManualClock
    from flex_nav.behavior.proxies import Proxies


class FakePublisher:
    def __init__(self, topic: str, msg_type: type, clock: Clock) -> None:
        self.topic = topic
        self.msg_type = msg_type
        self._clock = clock
        self.published: List[Tuple[float, Any]] = []  # ([s] clock time, message) of every publish
        self.connections = 0  # subscribers get_num_connections reports (set by the test)

    def publish(self, msg: Any) -> None:
        if not isinstance(msg, self.msg_type):
            raise TypeError(f"{self.topic}: published {type(msg).__name__}, expected {self.msg_type.__name__}")
        self.published.append((self._clock.now(), msg))

    def get_num_connections(self) -> int:
        return self.connections

    @property
    def messages(self) -> List[Any]:
        return [m for _, m in self.published]

    def last(self) -> Any:
        return self.published[-1][1] if self.published else None

    def unregister(self) -> None:
        pass


class FakeSubscription:
    def __init__(self, topic: str, msg_type: type, clock: Clock, buffer_size: int = 0) -> None:
        self.topic = topic
        self.msg_type = msg_type
        self._clock = clock
        self._last: Optional[Any] = None
        self._last_arrival_s = 0.0
        self._buffer: Deque[Any] = collections.deque(maxlen=max(1, buffer_size))
        self._buffered = buffer_size > 0
        self._callbacks: List[Callable[[Any], None]] = []

    # --- test side ---
    def inject(self, msg: Any) -> None:
        """Deliver ``msg`` as the subscriber callback would, arriving now on the clock."""
        if not isinstance(msg, self.msg_type):
            raise TypeError(f"{self.topic}: injected {type(msg).__name__}, expected {self.msg_type.__name__}")
        self._last = msg
        self._last_arrival_s = self._clock.now()
        if self._buffered:
            self._buffer.append(msg)
        for callback in list(self._callbacks):
            callback(msg)

    # --- RosProxies.Subscription interface ---
    def add_callback(self, callback: Callable[[Any], None]) -> None:
        self._callbacks.append(callback)

    def remove_callback(self, callback: Callable[[Any], None]) -> None:
        if callback in self._callbacks:
            self._callbacks.remove(callback)

    def disable_buffer(self) -> None:
        self._buffered = False
        self._buffer.clear()

    def enable_buffer(self, size: int = 10) -> None:
        if not self._buffered:
            self._buffer = collections.deque(maxlen=max(1, size))
            self._buffered = True

    def has_msg(self) -> bool:
        return self._last is not None

    def last(self) -> Optional[Any]:
        return self._last

    def age_s(self) -> float:
        return self._clock.now() - self._last_arrival_s if self._last is not None else math.inf

    def remove_last(self) -> None:
        self._last = None

    def has_buffered(self) -> bool:
        return bool(self._buffer)

    def pop_buffered(self) -> Optional[Any]:
        return self._buffer.popleft() if self._buffer else None

    def unregister(self) -> None:
        pass


@dataclass
class Response:
    """How the fake server answers one goal: terminal ``status`` and ``result``, ``delay_s`` after the send."""

    status: int
    result: Any
    delay_s: float = 0.0


class FakeActionClient:
    def __init__(self, name: str, action_type: type, clock: Clock) -> None:
        self.name = name
        self.action_type = action_type
        self._clock = clock
        self.available_at_s = -math.inf  # [s] clock time from which the server is connected (inf: never)
        self.responses: Deque[Response] = collections.deque()
        self.preempt_on_cancel = True  # a cancel ends the goal as PREEMPTED (as flex_nav's servers do)
        self.goals: List[Any] = []
        self.sent_at: List[float] = []
        self.cancels = 0
        self.availability_checks: List[float] = []  # timeout_s of each is_available call (must be ~0)
        self._state = GoalStatus.LOST
        self._result: Any = None
        self._feedback: Any = None
        self._active = False
        self._done = False
        self._pending: Optional[Response] = None

    # --- test side ---
    def respond(self, status: int, result: Any, delay_s: float = 0.0) -> None:
        """Queue the answer to the next goal sent."""
        self.responses.append(Response(status, result, delay_s))

    def finish(self, status: int, result: Any) -> None:
        """End the current goal now."""
        if not self._active:
            raise AssertionError(f"{self.name}: no active goal to finish")
        self._pending = None
        self._state, self._result, self._done, self._active = status, result, True, False

    def set_feedback(self, feedback: Any) -> None:
        self._feedback = feedback

    @property
    def active_goal(self) -> Any:
        return self.goals[-1] if self._active else None

    # --- RosProxies.ActionClientProxy interface ---
    def is_available(self, timeout_s: float = 0.0) -> bool:
        self.availability_checks.append(timeout_s)
        return self._clock.now() >= self.available_at_s

    def wait_for_server(self, timeout_s: float) -> None:
        if not self.is_available(timeout_s):
            raise NotReadyError(f"action server {self.name} is not available after {timeout_s:.1f} s")

    def send_goal(self, goal: Any, server_timeout_s: float = 5.0) -> None:
        self.wait_for_server(server_timeout_s)
        self.goals.append(goal)
        self.sent_at.append(self._clock.now())
        self._result, self._feedback, self._done, self._active = None, None, False, True
        self._state = GoalStatus.ACTIVE
        self._pending = self.responses.popleft() if self.responses else None

    def _apply_due(self) -> None:
        pending = self._pending
        if pending is not None and self._active and self._clock.now() >= self.sent_at[-1] + pending.delay_s:
            self.finish(pending.status, pending.result)

    def has_result(self) -> bool:
        self._apply_due()
        return self._done

    def result(self) -> Any:
        self._apply_due()
        return self._result

    def state(self) -> int:
        self._apply_due()
        return int(self._state)

    def feedback(self) -> Any:
        return self._feedback

    def forget_result(self) -> None:
        self._apply_due()
        self._result, self._done = None, False

    def forget_feedback(self) -> None:
        self._feedback = None

    def is_active(self) -> bool:
        self._apply_due()
        return self._active

    def cancel(self) -> None:
        self._apply_due()
        if not self._active:
            return
        self.cancels += 1
        if self.preempt_on_cancel:
            result = self.action_type().action_result.result  # the action's default Result
            if hasattr(result, "message"):
                result.message = "cancelled"
            self.finish(GoalStatus.PREEMPTED, result)

    def close(self, deadline: float) -> None:
        """Disconnect (the proxies' shutdown, after its cancel): nothing to do without ROS; ``deadline`` [s] unused."""


@dataclass(eq=False)
class FakeServiceCaller:
    name: str
    srv_type: type
    clock: Clock
    available_at_s: float = -math.inf  # [s] clock time from which the service is there (inf: never)
    answers: Deque[Any] = field(default_factory=collections.deque)  # responses, or exceptions a call raises
    requests: List[Any] = field(default_factory=list)

    # --- test side ---
    def respond(self, answer: Any) -> None:
        """Queue the answer to the next call: a response, or an exception the call raises."""
        self.answers.append(answer)

    # --- RosProxies.ServiceCallerProxy interface ---
    def is_available(self, timeout_s: float = 0.0) -> bool:
        return self.clock.now() >= self.available_at_s

    def call(self, request: Any, timeout_s: float = 5.0) -> Any:
        """The next queued answer, as the real one: NotReadyError if the service is not there (at once: the fake
        does not wait) or nothing is queued (a real call that failed)."""
        if not self.is_available(timeout_s):
            raise NotReadyError(f"service {self.name} is not available after {timeout_s:.1f} s")
        self.requests.append(request)
        if not self.answers:
            raise NotReadyError(f"service {self.name} failed: the test queued no answer")
        answer = self.answers.popleft()
        if isinstance(answer, BaseException):
            raise answer
        return answer


class FakeProxies:
    """The proxies of one behavior, with the test's clock; ``publishers``/``subscriptions``/``clients``/``services``
    by name."""

    def __init__(self, clock: Clock) -> None:
        self.clock = clock
        self.publishers: Connections[FakePublisher] = Connections("topic", lambda known: known.msg_type)
        self.subscriptions: Connections[FakeSubscription] = Connections("topic", lambda known: known.msg_type)
        self.clients: Connections[FakeActionClient] = Connections("action", lambda known: known.action_type)
        self.services: Connections[FakeServiceCaller] = Connections("service", lambda known: known.srv_type)

    def publisher(self, topic: str, msg_type: type, latch: bool = False, queue_size: int = 10) -> FakePublisher:
        return self.publishers.shared(topic, msg_type, lambda: FakePublisher(topic, msg_type, self.clock))

    def subscription(self, topic: str, msg_type: type, buffer_size: int = 0) -> FakeSubscription:
        sub = self.subscriptions.shared(
            topic, msg_type, lambda: FakeSubscription(topic, msg_type, self.clock, buffer_size)
        )
        if buffer_size > 0:  # a subscription made before without a buffer gets one (no-op when buffering)
            sub.enable_buffer(buffer_size)
        return sub

    def action_client(self, name: str, action_type: type) -> FakeActionClient:
        return self.clients.shared(name, action_type, lambda: FakeActionClient(name, action_type, self.clock))

    def service_caller(self, name: str, srv_type: type) -> FakeServiceCaller:
        return self.services.shared(name, srv_type, lambda: FakeServiceCaller(name, srv_type, self.clock))

    def get_publisher(self, topic: str) -> Optional[FakePublisher]:
        return self.publishers.get(topic)

    def get_subscription(self, topic: str) -> Optional[FakeSubscription]:
        return self.subscriptions.get(topic)

    def get_action_client(self, name: str) -> Optional[FakeActionClient]:
        return self.clients.get(name)

    def get_service_caller(self, name: str) -> Optional[FakeServiceCaller]:
        return self.services.get(name)

    def shutdown(self) -> None:
        """As RosProxies.shutdown: cancel every active goal, then disconnect every client."""
        for client in self.clients.values():
            client.cancel()
        for client in self.clients.values():
            client.close(deadline=0.0)

    # --- conveniences for tests ---
    def sub(self, topic: str) -> FakeSubscription:
        """The subscription a state made on ``topic`` (KeyError naming the known ones otherwise)."""
        try:
            return self.subscriptions[topic]
        except KeyError:
            raise KeyError(f"no subscription on {topic!r} (have: {', '.join(self.subscriptions)})") from None

    def pub(self, topic: str) -> FakePublisher:
        try:
            return self.publishers[topic]
        except KeyError:
            raise KeyError(f"no publisher on {topic!r} (have: {', '.join(self.publishers)})") from None

    def client(self, name: str, action_type: type) -> FakeActionClient:
        """The client for ``name``, created now if no state asked for it yet (to script it before start)."""
        return self.action_client(name, action_type)

    def service(self, name: str, srv_type: type) -> FakeServiceCaller:
        """The service caller for ``name``, created now if no state asked for it yet (to script it first)."""
        return self.service_caller(name, srv_type)


if TYPE_CHECKING:  # mypy: FakeProxies (and so its publisher, subscription, action client, service caller) is a Proxies
    _CONFORMS: Proxies = FakeProxies(ManualClock())
