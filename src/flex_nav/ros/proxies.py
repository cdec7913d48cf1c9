"""ROS connections for one behavior: publishers, cached subscribers, action clients and service callers.

A :class:`RosProxies` instance belongs to ONE running behavior (FlexBE keeps these in class-level dicts, so two
behaviors in one process share and trample them; here each behavior owns its hub and shuts it down when it
ends). Within a behavior, states that ask for the same topic or action share one connection. Every wait is
bounded and fails with a typed error (:class:`NotReadyError`, :class:`TimedOutError`, :class:`ConfigError`).
Nothing received is eval'd or unpickled: messages are genpy objects handed over as they are.

:class:`RosProxies` implements :class:`flex_nav.behavior.proxies.Proxies`, the port the states and the FlexBE
proxies use; mypy checks it (the typed assignment at the end of this module)."""

from __future__ import annotations

import collections
import math
import threading
import time
from typing import TYPE_CHECKING, Any, Callable, Deque, Generic, List, Optional, Tuple, TypeVar

import actionlib
import rospy
from actionlib.action_client import ClientGoalHandle, CommState
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Path

from flex_nav.behavior.proxies import Connections
from flex_nav.exceptions import NotReadyError, TimedOutError
from flex_nav.ros.lockstep import LockstepParticipant, accept_hold_name, accept_hold_param, stamped_before

if TYPE_CHECKING:
    from flex_nav.behavior.proxies import Proxies

MsgT = TypeVar("MsgT")

DEFAULT_BUFFER_SIZE = 10  # messages kept by a buffered subscription
PUBLISH_DRAIN_S = 1.0  # [s] bound on sending what is still queued (a final zero twist) before unregistering
SHUTDOWN_DRAIN_S = 0.5  # [s] bound on sending a node's last zero twist while it shuts down
# [s] lockstep: a stamped message at most this far ahead of ROS time waits for it (one stamped further ahead was
# stamped on another clock: taken in at once, the states judge its age)
EARLY_WINDOW_S = 1.0
AVAILABILITY_POLL_S = 0.01  # [s] how often ActionClientProxy.is_available looks again while it may wait


def _stamp_s(msg: Any) -> float:
    """[s] a message's header stamp (0: it has none)."""
    header = getattr(msg, "header", None)
    stamp = getattr(header, "stamp", None)
    return float(stamp.to_sec()) if stamp is not None else 0.0


class Subscription(Generic[MsgT]):
    """The newest message of a topic (and optionally a bounded buffer of recent ones), filled by a callback.

    ``lockstep`` (a behavior's subscriptions in a lockstep simulation): a stamped message is taken in only once ROS
    time has passed its stamp. A message stamped at the time the simulation stands at arrives before or after the
    reader's tick at that time by a wall-time race; so it is seen at the next tick either way, whatever the load.
    Such a message is taken in before any later one (on the next arrival or read), so the newest message is never
    an older one (a scan of 38.0 s that had waited would else have replaced the one of 38.9 s at the next read).
    (The extra callbacks still get every message as it arrives.)"""

    def __init__(self, topic: str, msg_type: type, buffer_size: int = 0, *, lockstep: bool = False) -> None:
        self.topic = topic
        self.msg_type = msg_type
        self._lockstep = lockstep
        self._early: Deque[MsgT] = collections.deque()  # (lockstep) arrived, stamped at or after ROS time then
        self._lock = threading.Lock()
        self._last: Optional[MsgT] = None
        self._last_wall_s = 0.0  # [s] time.monotonic() when the newest message arrived
        self._buffer: Deque[MsgT] = collections.deque(maxlen=max(1, buffer_size))
        self._buffered = buffer_size > 0
        self._callbacks: List[Callable[[MsgT], None]] = []  # extra callbacks (FlexBE's subscribe(callback=...))
        # rospy hands a subscriber only the newest ``queue_size`` messages of each read from a connection: a
        # burst published back to back would reach the buffer and the callbacks as its last message alone
        self._subscriber = rospy.Subscriber(
            topic, msg_type, self._callback, queue_size=max(DEFAULT_BUFFER_SIZE, buffer_size)
        )

    def _callback(self, msg: MsgT) -> None:
        with self._lock:
            self._take_due()  # before ``msg``: an early message taken later would replace a newer one
            if self._lockstep and self._is_early(msg):
                self._early.append(msg)
            else:
                self._take(msg)
            callbacks = list(self._callbacks)
        for callback in callbacks:  # outside the lock: a callback may read this subscription
            callback(msg)

    @staticmethod
    def _is_early(msg: Any) -> bool:
        """Stamped at or after ROS time (and within EARLY_WINDOW_S of it): taken in once time has passed it."""
        stamp_s, now_s = _stamp_s(msg), rospy.get_time()
        return not stamped_before(stamp_s, now_s) and stamp_s - now_s < EARLY_WINDOW_S

    def _take(self, msg: MsgT) -> None:
        """(lock held) ``msg`` becomes the newest message (and is buffered)."""
        self._last = msg
        self._last_wall_s = time.monotonic()
        if self._buffered:
            self._buffer.append(msg)

    def _take_due(self) -> None:
        """(lock held; lockstep) Take in the early messages whose stamp ROS time has passed, in arrival order."""
        if not self._early:
            return
        now_s = rospy.get_time()
        waiting: Deque[MsgT] = collections.deque()
        for msg in self._early:  # in the order they arrived
            if stamped_before(_stamp_s(msg), now_s):
                self._take(msg)
            else:
                waiting.append(msg)
        self._early = waiting

    def add_callback(self, callback: Callable[[MsgT], None]) -> None:
        """Also call ``callback(msg)`` for every message (in rospy's thread, after caching it)."""
        with self._lock:
            self._callbacks.append(callback)

    def remove_callback(self, callback: Callable[[MsgT], None]) -> None:
        with self._lock:
            if callback in self._callbacks:
                self._callbacks.remove(callback)

    def enable_buffer(self, size: int = DEFAULT_BUFFER_SIZE) -> None:
        with self._lock:
            if not self._buffered:
                self._buffer = collections.deque(maxlen=max(1, size))
                self._buffered = True

    def disable_buffer(self) -> None:
        """Stop buffering and drop the buffered messages (the newest message stays cached)."""
        with self._lock:
            self._buffered = False
            self._buffer.clear()

    def has_msg(self) -> bool:
        with self._lock:
            self._take_due()
            return self._last is not None

    def last(self) -> Optional[MsgT]:
        """The newest message, or None if none arrived (or it was removed)."""
        with self._lock:
            self._take_due()
            return self._last

    def age_s(self) -> float:
        """[s] wall time since the newest message arrived (inf if none)."""
        with self._lock:
            self._take_due()
            return time.monotonic() - self._last_wall_s if self._last is not None else float("inf")

    def remove_last(self) -> None:
        """Forget the newest message, so that :meth:`has_msg` waits for a new one."""
        with self._lock:
            self._take_due()
            self._last = None

    def has_buffered(self) -> bool:
        with self._lock:
            self._take_due()
            return bool(self._buffer)

    def pop_buffered(self) -> Optional[MsgT]:
        """The oldest buffered message not yet taken, or None."""
        with self._lock:
            self._take_due()
            return self._buffer.popleft() if self._buffer else None

    def wait_for_message(self, timeout_s: float) -> MsgT:
        """The newest message, waiting at most ``timeout_s`` [s] for one; TimedOutError otherwise."""
        deadline = time.monotonic() + timeout_s
        while True:
            msg = self.last()
            if msg is not None:
                return msg
            if time.monotonic() >= deadline:
                raise TimedOutError(f"no message on {self.topic} within {timeout_s:.1f} s")
            time.sleep(0.01)

    def unregister(self) -> None:
        self._subscriber.unregister()


class ActionClientProxy:
    """A non-blocking action client: send, poll state/result/feedback, cancel. One goal at a time.

    Built on actionlib's ActionClient, not its SimpleActionClient: the latter records the goal handle only
    when ``send_goal`` returns and drops every transition that arrives before (ros/actionlib#206), so the
    result of a fast server (a ClearCostmap answered within the send) could be lost and the goal waited on
    until its timeout. Here each goal's callbacks carry the goal's sequence number, known before sending;
    callbacks of a replaced goal are ignored.
    """

    def __init__(self, name: str, action_type: type) -> None:
        self.name = name
        self.action_type = action_type
        self._client = actionlib.ActionClient(name, action_type)
        server = rospy.resolve_name(name)
        self._accept = LockstepParticipant(name=accept_hold_name(server), dedupe=False)
        self._accept_param = accept_hold_param(server)
        self._server_accepts = False  # lockstep: the server lets go of the accept hold (cached once true)
        self._accept_held_s = -math.inf  # [s] lockstep: the stamp of the last accept hold placed
        self._lock = threading.Condition()  # guards the fields below; notified when a goal is done
        self._goal_number = 0  # sequence number of the goal the fields below describe
        self._handle: Optional[ClientGoalHandle] = None
        self._result: Any = None
        self._feedback: Any = None
        self._state: int = GoalStatus.LOST
        self._done = False
        self._done_stamp_s = -math.inf  # [s] ROS time the server stamped the last goal's result with
        self._active = False

    def is_available(self, timeout_s: float = 0.0) -> bool:
        """True when the server is connected; waits at most ``timeout_s`` [s] of wall time (0: just looks).

        actionlib's own wait_for_server measures its bound in ROS time, so with a simulated clock that stalls
        it never returns — and a state calls this on every tick. The test is the same: the server that sent
        the last status message is connected to our goal and cancel topics and publishes our result and
        feedback topics; when that node dies, its connections drop and this turns False."""
        deadline = time.monotonic() + max(timeout_s, 0.0)
        while not self._server_connected():
            if time.monotonic() >= deadline or rospy.is_shutdown():
                return False
            time.sleep(AVAILABILITY_POLL_S)
        return True

    def _server_connected(self) -> bool:
        client = self._client
        status = client.last_status_msg
        if status is None:
            return False
        server = status._connection_header["callerid"]
        if not (client.pub_goal.impl.has_connection(server) and client.pub_cancel.impl.has_connection(server)):
            return False
        return all(any(c.callerid_pub == server for c in sub.impl.connections)
                   for sub in (client.result_sub, client.feedback_sub))

    def wait_for_server(self, timeout_s: float) -> None:
        if not self.is_available(timeout_s):
            raise NotReadyError(
                f"action server {rospy.resolve_name(self.name)} is not available after {timeout_s:.1f} s"
            )

    def send_goal(self, goal: Any, server_timeout_s: float = 5.0) -> None:
        """Send ``goal`` (replacing any active one); NotReadyError if the server is not there within the bound."""
        self.wait_for_server(server_timeout_s)
        with self._lock:
            self._goal_number += 1
            number = self._goal_number
            self._handle = None
            self._result, self._feedback, self._done, self._active = None, None, False, True
            self._state = GoalStatus.PENDING
        if self._accept.enabled:
            if not self._server_accepts:  # asked again until true (a server that started later sets it then)
                self._server_accepts = bool(rospy.get_param(self._accept_param, False))
            if self._server_accepts:
                self._accept_held_s = rospy.get_time()
                self._accept.hold_clock(self._accept_held_s)  # the simulation stands until the server holds
        handle = self._client.send_goal(
            goal,
            transition_cb=lambda gh: self._on_transition(number, gh),
            feedback_cb=lambda _gh, feedback: self._on_feedback(number, feedback),
        )
        with self._lock:
            if self._goal_number == number:
                self._handle = handle  # also keeps the goal tracked: actionlib holds it only weakly

    def _on_transition(self, number: int, handle: ClientGoalHandle) -> None:
        comm_state = handle.get_comm_state()
        if comm_state == CommState.DONE:
            state, result = handle.get_terminal_state(), handle.get_result()
            action_result = handle.comm_state_machine.latest_result  # None: done by a lost or recalled status
            done_stamp_s = action_result.header.stamp.to_sec() if action_result is not None else -math.inf
        with self._lock:
            if number != self._goal_number or self._done:
                return
            if comm_state == CommState.ACTIVE:
                self._state = GoalStatus.ACTIVE
            elif comm_state == CommState.DONE:
                self._state, self._result, self._done, self._active = state, result, True, False
                self._done_stamp_s = done_stamp_s
                self._lock.notify_all()

    def _on_feedback(self, number: int, feedback: Any) -> None:
        with self._lock:
            if number == self._goal_number:
                self._feedback = feedback

    def has_result(self) -> bool:
        """True once the last goal is done. In a lockstep simulation only from a ROS time after the one the server
        stamped its result with: a result sent while the simulation stands at the caller's tick arrives before or
        after that tick by a wall-time race, and is seen at the next tick either way, whatever the load."""
        with self._lock:
            done, done_stamp_s = self._done, self._done_stamp_s
        return done and not (self._accept.enabled and rospy.get_time() <= done_stamp_s)

    def wait_for_result(self, timeout_s: float) -> bool:
        """Block until the last goal is done or ``timeout_s`` [s] of wall time passed; True if it is done."""
        with self._lock:
            return self._lock.wait_for(lambda: self._done, timeout=max(timeout_s, 0.0))

    def result(self) -> Any:
        """The result of the last goal (None until it is done, or if the server sent none)."""
        with self._lock:
            return self._result

    def state(self) -> int:
        """actionlib_msgs/GoalStatus value of the last goal."""
        with self._lock:
            return self._state

    def feedback(self) -> Any:
        with self._lock:
            return self._feedback

    def forget_result(self) -> None:
        """Drop the stored result, so :meth:`has_result` is False until the next goal finishes."""
        with self._lock:
            self._result, self._done = None, False

    def forget_feedback(self) -> None:
        with self._lock:
            self._feedback = None

    def is_active(self) -> bool:
        with self._lock:
            return self._active

    def cancel(self) -> None:
        """Cancel the active goal (no-op when none is active)."""
        with self._lock:
            handle = self._handle if self._active else None
        if handle is not None:
            handle.cancel()  # outside the lock: actionlib calls the transition callback from here
            if self._accept.enabled and self._server_accepts:
                # a goal cancelled before the server took it (the cancel may even arrive first: actionlib then
                # recalls the goal unseen) never runs, and nothing else would let go of the hold placed for it
                self._accept.release(through_s=self._accept_held_s)

    def close(self, deadline: float) -> None:
        """Unregister the client's five topics, after the goal and cancel messages already published were sent
        (or at ``deadline``, time.monotonic() [s]); cancel first to stop an active goal. The proxy is unusable
        afterwards."""
        for pub in (self._client.pub_goal, self._client.pub_cancel):
            drain_publisher(pub, deadline)
        self._client.stop()


class ServiceCallerProxy:
    """A service caller with a bounded wait for the service and a typed failure."""

    def __init__(self, name: str, srv_type: type) -> None:
        self.name = name
        self.srv_type = srv_type
        self._proxy = rospy.ServiceProxy(name, srv_type)

    def is_available(self, timeout_s: float = 0.0) -> bool:
        try:
            rospy.wait_for_service(self.name, timeout=max(timeout_s, 1e-3))
        except rospy.ROSException:
            return False
        return True

    def call(self, request: Any, timeout_s: float = 5.0) -> Any:
        if not self.is_available(timeout_s):
            raise NotReadyError(f"service {rospy.resolve_name(self.name)} is not available after {timeout_s:.1f} s")
        try:
            return self._proxy.call(request)
        except rospy.ServiceException as err:
            raise NotReadyError(f"service {rospy.resolve_name(self.name)} failed: {err}") from err


ANNOUNCED_TYPES = (TwistStamped, Path)  # a behavior's messages the simulator (commands) or a node (plans) waits for


class AnnouncingPublisher(rospy.Publisher):
    """A behavior's publisher of velocity commands or plans in a lockstep simulation: after each message it tells the
    simulator, through the behavior's ``lockstep`` participant, that the message (stamped) is on its way; the
    simulation steps on once it is in (the simulator's own command topic, or a node that reports what it takes in,
    as a controller following a plan topic does), so a state's command drives the robot from the next step and a
    plan reaches its controller at the same step whatever the load."""

    def __init__(self, topic: str, msg_type: type, lockstep: LockstepParticipant, **kwargs: Any) -> None:
        super().__init__(topic, msg_type, **kwargs)
        self._lockstep = lockstep

    def publish(self, *args: Any, **kwargs: Any) -> None:
        super().publish(*args, **kwargs)
        msg = args[0] if args else None
        if isinstance(msg, ANNOUNCED_TYPES):
            self._lockstep.sent(self.resolved_name, msg.header.stamp.to_sec())


class RosProxies:
    """The connections of one behavior, shared among its states by name; :meth:`shutdown` releases them all.
    ``lockstep``: the behavior's participant in a lockstep simulation (its velocity commands and plans are announced
    with it)."""

    def __init__(self, lockstep: Optional[LockstepParticipant] = None) -> None:
        self._announce = lockstep if lockstep is not None and lockstep.enabled else None
        self._lock = threading.Lock()
        self._publishers: Connections[Tuple[type, rospy.Publisher]] = Connections("topic", lambda known: known[0])
        self._subscriptions: Connections[Subscription[Any]] = Connections("topic", lambda known: known.msg_type)
        self._action_clients: Connections[ActionClientProxy] = Connections("action", lambda known: known.action_type)
        self._services: Connections[ServiceCallerProxy] = Connections("service", lambda known: known.srv_type)

    def publisher(self, topic: str, msg_type: type, latch: bool = False, queue_size: int = 10) -> rospy.Publisher:
        def make() -> Tuple[type, rospy.Publisher]:  # kept with the type it was made with
            if self._announce is not None and msg_type in ANNOUNCED_TYPES:
                return msg_type, AnnouncingPublisher(topic, msg_type, self._announce, latch=latch,
                                                     queue_size=queue_size)
            return msg_type, rospy.Publisher(topic, msg_type, latch=latch, queue_size=queue_size)

        with self._lock:
            return self._publishers.shared(topic, msg_type, make)[1]

    def subscription(self, topic: str, msg_type: type, buffer_size: int = 0) -> Subscription[Any]:
        with self._lock:
            sub = self._subscriptions.shared(topic, msg_type, lambda: Subscription(
                topic, msg_type, buffer_size, lockstep=self._announce is not None))
            if buffer_size > 0:  # a subscription made before without a buffer gets one (no-op when buffering)
                sub.enable_buffer(buffer_size)
            return sub

    def action_client(self, name: str, action_type: type) -> ActionClientProxy:
        with self._lock:
            return self._action_clients.shared(name, action_type, lambda: ActionClientProxy(name, action_type))

    def service_caller(self, name: str, srv_type: type) -> ServiceCallerProxy:
        with self._lock:
            return self._services.shared(name, srv_type, lambda: ServiceCallerProxy(name, srv_type))

    def get_publisher(self, topic: str) -> Optional[rospy.Publisher]:
        """The publisher some state of this behavior created for ``topic``, or None."""
        with self._lock:
            known = self._publishers.get(topic)
            return known[1] if known is not None else None

    def get_subscription(self, topic: str) -> Optional[Subscription[Any]]:
        with self._lock:
            return self._subscriptions.get(topic)

    def get_action_client(self, name: str) -> Optional[ActionClientProxy]:
        with self._lock:
            return self._action_clients.get(name)

    def get_service_caller(self, name: str) -> Optional[ServiceCallerProxy]:
        with self._lock:
            return self._services.get(name)

    def shutdown(self) -> None:
        """Cancel active goals and unregister every connection of this behavior. What the states published last
        (e.g. the zero twist of an ``on_exit``) is sent first: rospy drops a connection's queue on unregister."""
        with self._lock:
            for client in self._action_clients.values():
                client.cancel()
            for sub in self._subscriptions.values():
                sub.unregister()
            deadline = time.monotonic() + PUBLISH_DRAIN_S
            for _msg_type, pub in self._publishers.values():
                drain_publisher(pub, deadline)
                pub.unregister()
            for client in self._action_clients.values():
                client.close(deadline)
            self._publishers.clear()
            self._subscriptions.clear()
            self._action_clients.clear()
            self._services.clear()


def drain_publisher(publisher: rospy.Publisher, deadline: float) -> None:
    """Wait until rospy has sent everything published on ``publisher``, or until ``deadline`` (time.monotonic()
    [s]). A publisher made with ``queue_size`` hands messages to one writer thread per
    connection (rospy's QueuedConnection), which takes the whole queue and writes it outside its lock; the
    connection is idle once its queue is empty and its writer waits for data again. Connections without that
    machinery (or a closed one) count as idle."""
    connections = list(getattr(publisher.impl, "connections", None) or [])
    while not all(_connection_idle(c) for c in connections) and time.monotonic() < deadline:
        time.sleep(0.005)


def _connection_idle(connection: Any) -> bool:
    lock = getattr(connection, "_lock", None)
    data_available = getattr(connection, "_cond_data_available", None)
    if lock is None or data_available is None or getattr(connection, "done", True):
        return True
    with lock:
        return not connection._queue and bool(getattr(data_available, "_waiters", True))


if TYPE_CHECKING:  # mypy: RosProxies (and so its Subscription, ActionClientProxy, ServiceCallerProxy) is a Proxies
    _CONFORMS: Proxies = RosProxies()
