"""An action server whose goals run one at a time on a worker thread, never inside actionlib's callbacks.

actionlib's SimpleActionServer is used in the goal-callback form (``execute_cb`` stalls ~100 ms on
back-to-back goals). Its callbacks run with the server's locks held, so they only hand the goal over:

- a new goal is accepted at once and given a :class:`GoalTicket`; the worker thread runs ``run(ticket)``;
- a cancel ends the goal at once as preempted (result code PREEMPT where the action has one, else FAILURE)
  and calls ``on_cancel(ticket, replaced=False)`` (e.g. publish a zero twist) before returning;
- a newer goal replaces the running one: the old goal is preempted with the reason "replaced by a newer
  goal" and ``on_cancel(ticket, replaced=True)``; the worker moves on to the new goal when ``run`` returns;
- ``ticket.cancelled`` is set in both cases, so ``run`` stops at its next check.

Results go through :meth:`GoalServer.finish`, which ends the goal only while it is still the current one
(checked under actionlib's locks, taken in actionlib's order), so a worker can never end a goal that has
replaced its own. Any exception escaping ``run`` aborts the goal with the error as the reason after
``on_error(ticket, error)`` (e.g. publish a zero twist).

With ``client_timeout_s`` > 0 a goal whose client has gone is ended too: the node that sent the goal (the
``callerid`` of the goal message's connection) must stay subscribed to the server's status topic, which
actionlib publishes at a few Hz, so the connection of a process that exited or was killed is dropped within a
few publications. Once that node has been seen connected, ``client_timeout_s`` [s] (ROS time, as the
controllers' other timeouts) without that same connection aborts the goal after
``on_cancel(ticket, replaced=False)``, like a cancel nobody could send: a behavior runner that dies while a
controller drives leaves the robot stopped. A node restarted under the same name connects anew, and its
predecessor's goal is ended too. Not detected: a client process that hangs, or whose host drops off the
network (the TCP connection then stays open for minutes). A goal whose sender was never seen connected (e.g.
published by hand with ``rostopic pub``) is not watched; the server logs that once.

actionlib's SimpleActionServer takes a goal only if it is stamped at or after the current one: after ROS time
moved backwards (a restarted simulation, a looped bag) it would cancel every new goal for as long as the old
timeline's last goal is remembered. A goal stamped more than ``OLD_TIMELINE_TOLERANCE_S`` ahead of this node's
clock is taken for the old timeline's: a newer-but-earlier goal ends it (aborted with the reason, if still
running) and is taken.

In a lockstep simulation (:mod:`flex_nav.ros.lockstep`) a flex_nav client holds the simulation from sending a goal
until the server lets go of that hold (``lockstep_accept``): ``run`` does once its goal holds the simulation on its
own, and the worker does when ``run`` returns, so no simulated time passes between a goal's send and its start.

What of actionlib this needs beyond its public API (holding its two locks, a goal's sender, the status topic's
connections, the goal handles SimpleActionServer remembers, a hook ahead of its stamp check) is gathered in
:mod:`flex_nav.ros.actionlib_internals`, each item with the reason no public API serves.
"""

from __future__ import annotations

import enum
import math
import threading
import time
import traceback
from typing import Any, Callable, Optional

import actionlib
import rospy

from flex_nav.action_types import ActionType
from flex_nav.exceptions import ConfigError
from flex_nav.ros.actionlib_internals import RememberedGoal, SimpleServerInternals
from flex_nav.ros.lockstep import server_accept_hold

CLIENT_CHECK_PERIOD_S = 0.1  # [s] how often the client of the running goal is looked for
OLD_TIMELINE_TOLERANCE_S = 1.0  # [s] a goal stamped this far ahead of the node's clock is from before a jump back


class GoalOutcome(enum.Enum):
    """How the worker ends a goal (:meth:`GoalServer.finish`); cancels and replacements preempt it instead."""

    SUCCEEDED = "succeeded"
    ABORTED = "aborted"


class GoalTicket:
    """One accepted goal: the goal message, its sequence number, the node that sent it ("" if unknown), and
    whether it was cancelled or replaced."""

    def __init__(self, goal: Any, number: int, sender: str = "", stamp_s: float = -math.inf) -> None:
        self.goal = goal
        self.number = number
        self.sender = sender
        self.stamp_s = stamp_s  # [s] ROS time of the goal id's stamp (its client sent it then)
        self.cancelled = threading.Event()
        self.sender_connection: Optional[int] = None  # id of the sender's status connection, once seen
        self.sender_missing_since: Optional[float] = None  # [s] ROS time
        self.unseen_since: Optional[float] = None  # [s] ROS time of the first check that did not see the sender
        self.unseen_logged = False

    def __repr__(self) -> str:
        return f"GoalTicket(#{self.number}{', cancelled' if self.cancelled.is_set() else ''})"


class GoalServer:
    """Serves ``spec`` on ``name``; see the module docstring for the contract of the three callables."""

    def __init__(
        self,
        name: str,
        spec: ActionType,
        run: Callable[[GoalTicket], None],
        on_cancel: Optional[Callable[[GoalTicket, bool], None]] = None,
        on_error: Optional[Callable[[GoalTicket, BaseException], None]] = None,
        *,
        client_timeout_s: float = 0.0,
    ) -> None:
        if not client_timeout_s >= 0.0:
            raise ConfigError(f"{name}: client timeout {client_timeout_s!r} s is not valid (valid: >= 0, 0 = off)")
        self.name = name
        self.client_timeout_s = client_timeout_s
        self.spec = spec
        self._run = run
        self._on_cancel = on_cancel
        self._on_error = on_error
        self._codes = spec.result_codes
        self._cond = threading.Condition()
        self._current: Optional[GoalTicket] = None
        self._pending: Optional[GoalTicket] = None
        self._count = 0
        self._stopping = False
        self.server = actionlib.SimpleActionServer(name, spec.action, auto_start=False)
        self._internals = SimpleServerInternals(self.server)
        self.server.register_goal_callback(self._on_goal)
        self._internals.intercept_goals(self._on_goal_arrival)
        self.server.register_preempt_callback(self._on_preempt)
        # lockstep: a client's hold from its send to this server's first hold of the goal (accept_hold_name)
        self.lockstep_accept = server_accept_hold(rospy.resolve_name(name))
        self._worker = threading.Thread(target=self._work, name=f"goals:{name}", daemon=True)
        self._client_watch = threading.Thread(target=self._watch_clients, name=f"clients:{name}", daemon=True)

    def start(self) -> None:
        self._worker.start()
        self.server.start()
        if self.client_timeout_s > 0.0:
            self._client_watch.start()

    def shutdown(self) -> None:
        with self._cond:
            self._stopping = True
            self._cond.notify_all()

    # ------------------------------------------------------------------ for the worker
    def result(self, code_name: str, message: str, **fields: Any) -> Any:
        """A Result message with ``code`` set from its name (e.g. "FAILURE"), ``message`` and other fields."""
        result = self.spec.result()
        result.code = self._codes[code_name]
        result.message = message
        for key, value in fields.items():
            setattr(result, key, value)
        return result

    def finish(self, ticket: GoalTicket, outcome: GoalOutcome, result: Any) -> bool:
        """End ``ticket``'s goal as ``outcome``; False if it is no longer the current goal."""
        with self._internals.locked():
            if ticket is not self._current or ticket.cancelled.is_set() or not self.server.is_active():
                return False
            if outcome is GoalOutcome.SUCCEEDED:
                self.server.set_succeeded(result, result.message)
            elif outcome is GoalOutcome.ABORTED:
                self.server.set_aborted(result, result.message)
            else:  # a caller without type checking
                valid = ", ".join(str(member) for member in GoalOutcome)  # type: ignore[unreachable]
                raise ValueError(f"outcome {outcome!r} is not valid (valid: {valid})")
            self._current = None
            return True

    def feedback(self, ticket: GoalTicket, feedback: Any) -> None:
        """Publish feedback for ``ticket``'s goal if it is still the current one."""
        with self._internals.locked():
            if ticket is self._current and not ticket.cancelled.is_set() and self.server.is_active():
                self.server.publish_feedback(feedback)

    def is_current(self, ticket: GoalTicket) -> bool:
        return ticket is self._current and not ticket.cancelled.is_set()

    # ------------------------------------------------------------------ actionlib callbacks (its locks held)
    def _on_goal_arrival(self, incoming: Any) -> None:
        """Every goal, before SimpleActionServer's stamp check: forget goals of an old timeline first."""
        stamp = incoming.get_goal_id().stamp
        self._forget_old_timeline(stamp)
        if self.lockstep_accept.enabled and any(
                old is not None and stamp < old for old in map(self._internals.remembered_stamp, RememberedGoal)):
            # SimpleActionServer cancels it (older than a goal it keeps): no run of it lets go of the hold
            self._release_accept_if_idle(stamp.to_sec())

    def _forget_old_timeline(self, stamp: rospy.Time) -> None:
        ahead_of = rospy.Time.now() + rospy.Duration(OLD_TIMELINE_TOLERANCE_S)
        for which in RememberedGoal:
            old_stamp = self._internals.remembered_stamp(which)
            if old_stamp is None or not (stamp < old_stamp and old_stamp > ahead_of):
                continue
            with self._internals.locked():  # (the ActionServer's lock is held already: this adds the simple one)
                if which is RememberedGoal.CURRENT and self.server.is_active():
                    reason = "ROS time moved backwards: the goal belongs to the old timeline"
                    if self._current is not None:
                        self._stop(self._current, replaced=False)
                        self._current = None
                    self.server.set_aborted(self.result("FAILURE", reason), reason)
                    rospy.logwarn(f"{self.name}: {reason}; aborted it for a new goal")
                self._internals.forget(which)

    def _on_goal(self) -> None:
        goal = self.server.accept_new_goal()
        if goal is None:
            return
        with self._cond:
            self._count += 1
            stamp_s = self.server.current_goal.get_goal_id().stamp.to_sec()
            ticket = GoalTicket(goal, self._count, self._internals.sender_of_current_goal(), stamp_s)
            self._current = ticket
            if self.server.is_preempt_requested():  # cancelled between arrival and acceptance
                self._preempt(ticket, replaced=False)
                self._release_accept_if_idle(ticket.stamp_s)  # no run of it will let go of its sender's hold
                return
            self._pending = ticket
            self._cond.notify_all()

    def _on_preempt(self) -> None:
        ticket = self._current
        if ticket is None or not self.server.is_active():
            return
        self._preempt(ticket, replaced=self.server.is_new_goal_available())

    def _preempt(self, ticket: GoalTicket, replaced: bool) -> None:
        self._stop(ticket, replaced)
        reason = "replaced by a newer goal" if replaced else "preempted"
        code = "PREEMPT" if "PREEMPT" in self._codes else "FAILURE"
        if self.server.is_active():
            self.server.set_preempted(self.result(code, reason), reason)
        if self._current is ticket:
            self._current = None

    def _stop(self, ticket: GoalTicket, replaced: bool) -> None:
        """Mark ``ticket`` cancelled and call ``on_cancel`` (its errors logged: the goal must still end)."""
        ticket.cancelled.set()
        if self._on_cancel is not None:
            try:
                self._on_cancel(ticket, replaced)
            except Exception as err:
                rospy.logerr(f"{self.name}: error while stopping goal #{ticket.number}: {err}")

    def release_accept(self, ticket: GoalTicket) -> None:
        """Let go of the accept hold ``ticket``'s client placed when it sent the goal (the goal holds on its own
        now); only of holds up to the goal's stamp, so a later goal's hold stays, and one overtaken stays released."""
        self.lockstep_accept.release(through_s=ticket.stamp_s)

    def _release_accept_if_idle(self, through_s: float) -> None:
        """Let go of the clients' accept hold up to ``through_s`` [s] unless a goal waits for its run (that run lets
        go of it: releasing it here would let the simulation step before the waiting goal holds it)."""
        with self._cond:
            if self._pending is None:
                self.lockstep_accept.release(through_s=through_s)

    # ------------------------------------------------------------------ client watch thread
    def _watch_clients(self) -> None:
        while not self._stopping and not rospy.is_shutdown():
            time.sleep(CLIENT_CHECK_PERIOD_S)  # wall-clock polling; the timeout itself runs on ROS time
            try:
                self._check_client()
            except Exception as err:  # the watch must go on
                rospy.logerr(f"{self.name}: client watch error: {err}\n{traceback.format_exc()}")

    def _check_client(self) -> None:
        ticket = self._current
        if ticket is None or not ticket.sender or ticket.cancelled.is_set():
            return
        now_s = rospy.get_time()
        ids = [cid for cid, caller in self._internals.status_connections() if caller == ticket.sender]
        if ticket.sender_connection is None:
            if ids:
                ticket.sender_connection = ids[0]
            elif ticket.unseen_since is None:
                ticket.unseen_since = now_s
            elif now_s - ticket.unseen_since >= self.client_timeout_s and not ticket.unseen_logged:
                ticket.unseen_logged = True
                rospy.logwarn(f"{self.name}: goal #{ticket.number} is not watched: its sender {ticket.sender} is "
                              "not connected to the status topic (it is, once it connects)")
            return
        if ticket.sender_connection in ids:
            ticket.sender_missing_since = None
        elif ticket.sender_missing_since is None or now_s < ticket.sender_missing_since:  # (time went back)
            ticket.sender_missing_since = now_s
        elif now_s - ticket.sender_missing_since >= self.client_timeout_s:
            self._abandon(ticket)

    def _abandon(self, ticket: GoalTicket) -> None:
        """Stop and abort ``ticket``'s goal: the node that sent it is gone."""
        reason = (f"the client {ticket.sender} that sent this goal is gone "
                  f"(its connection closed {self.client_timeout_s:.1f} s ago)")
        with self._internals.locked():
            if ticket is not self._current or ticket.cancelled.is_set() or not self.server.is_active():
                return
            self._stop(ticket, replaced=False)
            self.server.set_aborted(self.result("FAILURE", reason), reason)
            self._current = None
        rospy.logerr(f"{self.name}: goal #{ticket.number} aborted, robot stopped: {reason}")

    # ------------------------------------------------------------------ worker thread
    def _work(self) -> None:
        while True:
            with self._cond:
                while self._pending is None and not self._stopping and not rospy.is_shutdown():
                    self._cond.wait(0.5)
                if self._stopping or rospy.is_shutdown():
                    return
                ticket, self._pending = self._pending, None
            assert ticket is not None
            try:
                self._run(ticket)  # releases lockstep_accept once the goal holds on its own, else it ends here
            except Exception as err:
                rospy.logerr(f"{self.name}: goal #{ticket.number} failed: {err}\n{traceback.format_exc()}")
                if self._on_error is not None:
                    try:
                        self._on_error(ticket, err)
                    except Exception as inner:
                        rospy.logerr(f"{self.name}: error handler failed too: {inner}")
                self.finish(ticket, GoalOutcome.ABORTED, self.result("FAILURE", f"internal error: {err!r}"))
            self._release_accept_if_idle(ticket.stamp_s)
            if self.finish(ticket, GoalOutcome.ABORTED, self.result("FAILURE", "the server ended without a result")):
                rospy.logerr(f"{self.name}: goal #{ticket.number} ended without a result (a bug); aborted it")
