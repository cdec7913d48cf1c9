"""Publishes what a running behavior does, for the operator tool, without slowing the behavior down.

The executor's hooks run in its tick thread; they only append an event to a queue (a few µs). A publisher
thread turns events into messages and publishes them on the runner's topics:

- ``~status`` (BehaviorStatus, latched), ``~activity`` (BehaviorActivity, latched: active states and pending
  outcome requests), ``~log`` (BehaviorLog), ``~transitions`` (BehaviorTransition),
  ``~command_feedback`` (BehaviorCommandFeedback: ``pending`` marks a first answer that a final one follows),
  ``~structure`` (std_msgs/String, latched: JSON of the loaded behavior's states, transitions, autonomy and
  parameters, and the behaviors the runner can start; schema in :mod:`flex_nav.behavior.structure`).
"""

from __future__ import annotations

import collections
import threading
from typing import Any, Callable, Deque, Dict, List, Tuple

import rospy
from std_msgs.msg import String

from flex_nav.behavior.events import (
    ActiveStatesEvent,
    BehaviorStatus,
    LogEvent,
    RequestEvent,
    StatusEvent,
    TransitionEvent,
)
from flex_nav.msg import (
    BehaviorActivity,
    BehaviorCommandFeedback,
    BehaviorLog,
    BehaviorTransition,
    OutcomeRequest,
)
from flex_nav.msg import (
    BehaviorStatus as BehaviorStatusMsg,
)

STATUS_CODES: Dict[BehaviorStatus, int] = {
    BehaviorStatus.READY: BehaviorStatusMsg.READY,
    BehaviorStatus.RUNNING: BehaviorStatusMsg.RUNNING,
    BehaviorStatus.PAUSED: BehaviorStatusMsg.PAUSED,
    BehaviorStatus.FINISHED: BehaviorStatusMsg.FINISHED,
    BehaviorStatus.PREEMPTED: BehaviorStatusMsg.PREEMPTED,
    BehaviorStatus.FAILED: BehaviorStatusMsg.FAILED,
}
QUEUE_LIMIT = 10000  # events kept when the publisher thread falls behind (oldest dropped, counted)


class OperatorPublisher:
    """Queues behavior events and publishes them from its own thread. ``close()`` flushes and stops it."""

    def __init__(self) -> None:
        self.status_pub = rospy.Publisher("~status", BehaviorStatusMsg, queue_size=10, latch=True)
        self.activity_pub = rospy.Publisher("~activity", BehaviorActivity, queue_size=10, latch=True)
        self.log_pub = rospy.Publisher("~log", BehaviorLog, queue_size=100)
        self.transition_pub = rospy.Publisher("~transitions", BehaviorTransition, queue_size=100)
        self.feedback_pub = rospy.Publisher("~command_feedback", BehaviorCommandFeedback, queue_size=10)
        self.structure_pub = rospy.Publisher("~structure", String, queue_size=1, latch=True)
        self._queue: Deque[Tuple[Callable[..., Any], Tuple[Any, ...]]] = collections.deque(maxlen=QUEUE_LIMIT)
        self._cv = threading.Condition()
        self._closed = False
        # what the latched activity message shows, kept by the publisher thread only
        self._behavior = ""
        self._autonomy = 0
        self._active: Tuple[str, ...] = ()
        self._requests: Dict[Tuple[str, str], OutcomeRequest] = {}
        self._thread = threading.Thread(target=self._run, name="operator_publisher", daemon=True)
        self._thread.start()

    # --- hooks (executor thread): enqueue only ------------------------------------------------------
    def attach(self, hooks: Any, behavior: str, autonomy: int) -> None:
        """Register on an executor context's hooks for the behavior called ``behavior``."""
        self._post(self._set_behavior, behavior, autonomy)
        hooks.transition.append(lambda event: self._post(self._publish_transition, behavior, event))
        hooks.request.append(lambda event: self._post(self._on_request, event))
        hooks.log.append(lambda event: self._post(self._publish_log, behavior, event))
        hooks.status.append(lambda event: self._post(self._publish_status, behavior, event))
        hooks.active.append(lambda event: self._post(self._on_active, event))

    def _post(self, handler: Callable[..., Any], *args: Any) -> None:
        with self._cv:
            self._queue.append((handler, args))
            self._cv.notify()

    # --- direct publications (any thread) -----------------------------------------------------------
    def publish_idle(self, behavior: str, reason: str, autonomy: int) -> None:
        self._post(self._publish_raw_status, behavior, BehaviorStatusMsg.IDLE, "", reason, autonomy)

    def publish_autonomy(self, autonomy: int) -> None:
        self._post(self._set_autonomy, autonomy)

    def publish_feedback(self, command: str, args: List[str], ok: bool, message: str, pending: bool = False) -> None:
        """Answer a command; ``pending``: accepted, still being carried out, a final answer follows."""
        self._post(self._publish_feedback, command, list(args), ok, message, pending)

    def publish_structure(self, structure_json: str) -> None:
        """Latch the JSON structure of the behavior now loaded (or of none)."""
        self._post(self.structure_pub.publish, String(data=structure_json))

    def close(self, timeout_s: float = 2.0) -> None:
        with self._cv:
            self._closed = True
            self._cv.notify()
        self._thread.join(timeout_s)

    # --- publisher thread ---------------------------------------------------------------------------
    def _run(self) -> None:
        while True:
            with self._cv:
                while not self._queue and not self._closed:
                    self._cv.wait(0.5)
                if not self._queue and self._closed:
                    return
                handler, args = self._queue.popleft()
            try:
                handler(*args)
            except (rospy.ROSException, ValueError, TypeError) as err:
                rospy.logwarn_throttle(5.0, f"operator interface: could not publish: {err}")

    def _header_now(self, msg: Any) -> Any:
        msg.header.stamp = rospy.Time.now()
        return msg

    def _set_behavior(self, behavior: str, autonomy: int) -> None:
        self._behavior, self._autonomy, self._active, self._requests = behavior, autonomy, (), {}
        self._publish_activity()

    def _set_autonomy(self, autonomy: int) -> None:
        self._autonomy = autonomy
        self._publish_activity()

    def _publish_transition(self, behavior: str, event: TransitionEvent) -> None:
        self.transition_pub.publish(self._header_now(BehaviorTransition(
            behavior=behavior, path=event.path, outcome=event.outcome, target=event.target,
            required=int(event.required), forced=event.forced,
        )))

    def _on_request(self, event: RequestEvent) -> None:
        key = (event.path, event.outcome)
        if event.pending:
            self._requests[key] = OutcomeRequest(
                path=event.path, outcome=event.outcome, required=int(event.required), reason=event.reason
            )
        else:
            self._requests.pop(key, None)
        self._publish_activity()

    def _on_active(self, event: ActiveStatesEvent) -> None:
        self._active = tuple(event.paths)
        active = set(self._active)
        self._requests = {key: req for key, req in self._requests.items() if key[0] in active}
        self._publish_activity()

    def _publish_activity(self) -> None:
        self.activity_pub.publish(self._header_now(BehaviorActivity(
            behavior=self._behavior, autonomy=self._autonomy, active_paths=list(self._active),
            requests=list(self._requests.values()),
        )))

    def _publish_log(self, behavior: str, event: LogEvent) -> None:
        self.log_pub.publish(self._header_now(BehaviorLog(
            behavior=behavior, level=int(event.level), path=event.path, text=event.message
        )))

    def _publish_status(self, behavior: str, event: StatusEvent) -> None:
        self._publish_raw_status(behavior, STATUS_CODES[event.status], event.outcome or "", event.reason,
                                 self._autonomy)
        if event.status.is_terminal:
            self._active, self._requests = (), {}
            self._publish_activity()

    def _publish_raw_status(self, behavior: str, code: int, outcome: str, reason: str, autonomy: int) -> None:
        self.status_pub.publish(self._header_now(BehaviorStatusMsg(
            behavior=behavior, code=code, outcome=outcome, reason=reason, autonomy=autonomy
        )))

    def _publish_feedback(self, command: str, args: List[str], ok: bool, message: str, pending: bool) -> None:
        self.feedback_pub.publish(self._header_now(BehaviorCommandFeedback(
            command=command, args=args, ok=ok, message=message, pending=pending
        )))


def status_name(code: int) -> str:
    """Name of a BehaviorStatus code ("RUNNING", ...)."""
    for name in ("READY", "RUNNING", "PAUSED", "FINISHED", "PREEMPTED", "FAILED", "IDLE"):
        if getattr(BehaviorStatusMsg, name) == code:
            return name
    return f"UNKNOWN({code})"

