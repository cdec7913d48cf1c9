"""Lockstep: the simulator waits for the nodes that compute on its time (pure logic; ROS side in sim_bridge).

Without it the simulator steps at its real-time factor whatever the nodes do, so a node's wall-time latency
becomes simulated latency scaled by the rtf (one wall millisecond of planning is four simulated ones at rtf 4)
and a run's outcome depends on the rtf and the machine's load. With it, each *participant* (a controller, a
costmap, the localizer, the classifier, the behavior runner ...) holds the simulation at the point where it has
work to do, and lets it go on once that work is done:

- a **clock hold** ``(topic "", stamp)``: step no further once simulated time has reached ``stamp`` (a loop paced on
  ROS time holds at its next tick; a server holds at "now" while it plans);
- a **topic hold** ``(topic, stamp)``: step no further once a message on ``topic`` stamped at or after ``stamp`` has
  been published (a scan consumer holds on the next scan, the classifier on the next image it will classify).

A hold may also say that its participant has just *sent* the simulator a message (a velocity command stamped
``sent_stamp_s`` on ``sent_topic``): the simulation steps on only once that message has come in (:meth:`received`),
so a command computed at one step is applied from the next, whatever the load (the two messages travel on two
connections and either may arrive first). Messages between two nodes are waited for the same way once their
receiver says it receives the topic (``received_topic`` with stamp -inf; +inf: it no longer does) and reports each
message it has taken in (``received_topic``, ``received_stamp_s``): a controller following a plan topic takes each
plan the behavior publishes before the simulation steps on.

A participant replaces its hold by sending the next one (or lets go). Every wait is bounded: a hold that keeps the
simulation waiting ``timeout_s`` [s of wall time] is dropped, reported, and counted (a participant that died or
lost a message must not stop the world); its next hold counts again.
"""

from __future__ import annotations

import math
import threading
import time
from dataclasses import dataclass
from typing import Callable, Dict, List, Tuple

from flex_nav.exceptions import ConfigError

CLOCK_TOPIC = ""  # a hold on simulated time itself
POLL_S = 0.05  # [s] wall: longest wait before the stop condition is looked at again


@dataclass(frozen=True)
class Hold:
    """What one participant waits for: simulated time (``topic`` empty) or a message on ``topic``, at ``stamp_s``."""

    participant: str
    topic: str
    stamp_s: float  # [s] simulated time
    sent: bool = False  # True: the simulator waits to receive the participant's message on topic, at stamp_s

    def describe(self) -> str:
        if self.sent:
            return f"{self.participant} (its message on {self.topic} stamped {self.stamp_s:.3f} s has not arrived)"
        what = "simulated time" if self.topic == CLOCK_TOPIC else f"a message on {self.topic} stamped"
        return f"{self.participant} (waiting for {what} >= {self.stamp_s:.3f} s)"


@dataclass
class LockstepStats:
    """What the waiting cost: waits that blocked, their wall time, holds dropped on timeout."""

    waits: int = 0
    wait_s: float = 0.0  # [s] wall
    dropped: int = 0

    def line(self) -> str:
        return f"lockstep: {self.waits} waits, {self.wait_s:.1f} s wall waiting, {self.dropped} holds dropped"


class LockstepBarrier:
    """The holds of every participant and what the simulator has published; :meth:`wait` blocks the stepping thread.

    ``timeout_s`` [s wall] bounds how long one hold may keep the simulation waiting. Thread-safe: holds arrive on
    ROS threads (:meth:`update`), the stepping thread reports what it published and waits.
    """

    def __init__(self, timeout_s: float, wall_clock: Callable[[], float] = time.monotonic) -> None:
        if not (math.isfinite(timeout_s) and timeout_s > 0.0):
            raise ConfigError(f"lockstep timeout {timeout_s!r} s: must be a positive number of seconds")
        self.timeout_s = timeout_s
        self._wall = wall_clock
        self._cond = threading.Condition()
        self._holds: Dict[str, Hold] = {}
        self._published: Dict[str, float] = {CLOCK_TOPIC: -math.inf}  # topic -> newest stamp [s]
        self._released_through: Dict[str, float] = {}  # participant -> newest stamp it let go through [s]
        self._sent: Dict[Tuple[str, str], Hold] = {}  # (participant, topic) -> a message it sent, not received yet
        self._received: Dict[str, float] = {}  # topic the simulator or a node receives -> newest stamp received [s]
        self.stats = LockstepStats()

    def update(self, participant: str, holding: bool, topic: str, stamp_s: float, *, sent_topic: str = "",
               sent_stamp_s: float = 0.0, received_topic: str = "", received_stamp_s: float = 0.0) -> None:
        """A participant's new hold replaces its old one (``holding`` False: it lets go); with ``sent_topic``, it
        sent the simulator a message stamped ``sent_stamp_s`` [s] there, to be waited for until :meth:`received`.

        A release with a finite ``stamp_s`` lets go only of holds stamped up to it, and also of such a hold that
        arrives after it: a participant whose holds and releases come from two nodes (an action client holds from
        sending its goal, the server lets go once the goal runs) has no order between them, and the server's release
        may overtake the client's hold. Any other release (stamp -inf) lets go of whatever is held.

        ``received_topic``: the participant receives that topic (``received_stamp_s`` -inf; +inf: no longer) or has
        taken in a message stamped ``received_stamp_s`` [s] there (see the module docstring)."""
        if not participant:
            raise ConfigError("a lockstep hold must name its participant")
        if holding and not math.isfinite(stamp_s):
            raise ConfigError(f"lockstep hold of {participant}: stamp {stamp_s!r} is not a finite time")
        if received_topic and math.isnan(received_stamp_s):
            raise ConfigError(f"lockstep hold of {participant}: received stamp {received_stamp_s!r} is not a time")
        if sent_topic and not math.isfinite(sent_stamp_s):
            raise ConfigError(f"lockstep hold of {participant}: sent stamp {sent_stamp_s!r} is not a finite time")
        with self._cond:
            if holding and stamp_s <= self._released_through.get(participant, -math.inf):
                pass  # let go of already: a release through a later stamp overtook it
            elif holding:
                self._holds[participant] = Hold(participant, topic, stamp_s)
            elif math.isfinite(stamp_s):  # let go of holds up to stamp_s, also one still on its way
                self._released_through[participant] = max(stamp_s, self._released_through.get(participant, -math.inf))
                old = self._holds.get(participant)
                if old is not None and old.stamp_s <= stamp_s:
                    del self._holds[participant]
            else:
                self._holds.pop(participant, None)
            if sent_topic in self._received and self._received[sent_topic] < sent_stamp_s:
                self._sent[(participant, sent_topic)] = Hold(participant, sent_topic, sent_stamp_s, sent=True)
            if received_topic and received_stamp_s == -math.inf:  # it receives the topic (again)
                self._received[received_topic] = -math.inf
            elif received_topic:  # a message it took in (+inf: it no longer receives the topic)
                self._took(received_topic, received_stamp_s)
            self._cond.notify_all()

    def subscribed(self, topic: str) -> None:
        """The simulator receives ``topic``: messages sent there are waited for (on any other topic they are not: a
        node that publishes where the simulator does not listen must not stop it)."""
        with self._cond:
            self._received.setdefault(topic, -math.inf)

    def received(self, topic: str, stamp_s: float) -> None:
        """The simulator received a message stamped ``stamp_s`` [s] on ``topic`` (a ROS thread)."""
        with self._cond:
            self._took(topic, stamp_s)

    def _took(self, topic: str, stamp_s: float) -> None:
        """(lock held) A message stamped ``stamp_s`` [s] on ``topic`` is in: sends up to it are waited for no more."""
        if stamp_s > self._received.get(topic, -math.inf):
            self._received[topic] = stamp_s
        for key, sent in list(self._sent.items()):
            if sent.topic == topic and sent.stamp_s <= stamp_s:
                del self._sent[key]
        self._cond.notify_all()

    def published(self, topic: str, stamp_s: float) -> None:
        """The stepping thread published a message on ``topic`` (:data:`CLOCK_TOPIC`: reached time) at ``stamp_s``."""
        with self._cond:
            if stamp_s > self._published.get(topic, -math.inf):
                self._published[topic] = stamp_s

    def holds(self) -> List[Hold]:
        with self._cond:
            return list(self._holds.values())

    def _reached(self, hold: Hold) -> bool:
        return self._published.get(hold.topic, -math.inf) >= hold.stamp_s  # exactly: as the participant compares

    def _blocking(self) -> List[Hold]:
        """(lock held) The holds whose wait has come and the messages sent but not received yet."""
        return [h for h in self._holds.values() if self._reached(h)] + list(self._sent.values())

    def blocking(self) -> List[Hold]:
        """The holds whose wait has come (and the sent messages still on their way): the simulation must not step on
        while any is left."""
        with self._cond:
            return self._blocking()

    def wait(self, stop: Callable[[], bool] = lambda: False) -> List[Hold]:
        """Block until no hold has come (or ``stop()``); returns the holds dropped after ``timeout_s`` each."""
        dropped: List[Hold] = []
        started = self._wall()
        first_blocked: Dict[Hold, float] = {}
        with self._cond:
            while not stop():
                now = self._wall()
                blocking = self._blocking()
                if not blocking:
                    break
                for hold in blocking:
                    since = first_blocked.setdefault(hold, now)
                    if now - since < self.timeout_s:
                        continue
                    if hold.sent and self._sent.get((hold.participant, hold.topic)) == hold:
                        del self._sent[(hold.participant, hold.topic)]
                        dropped.append(hold)
                    elif not hold.sent and self._holds.get(hold.participant) == hold:
                        del self._holds[hold.participant]
                        dropped.append(hold)
                oldest = min(first_blocked.get(h, now) for h in blocking)
                self._cond.wait(max(0.0, min(POLL_S, oldest + self.timeout_s - now)))
            waited = self._wall() - started
            if first_blocked:
                self.stats.waits += 1
                self.stats.wait_s += waited
            self.stats.dropped += len(dropped)
        return dropped
