"""A node's side of the simulator's lockstep mode (the barrier: :mod:`flex_nav_sim.lockstep`).

With ``/lockstep`` true (and ``/use_sim_time``), the simulator steps no further than its participants allow: each
sends :class:`flex_nav.msg.LockstepHold` on ``/lockstep/holds`` saying what it waits for next -- simulated time
reaching its next tick, or the next message on a sensor topic -- and replaces that hold once the work it held
for is done. So a node's compute time costs no simulated time, whatever the real-time factor or the machine's load.
Without ``/lockstep`` (every real robot) a :class:`LockstepParticipant` does nothing.
"""

from __future__ import annotations

import math
import threading
import time
from typing import Any, Optional, Tuple

import rospy

from flex_nav.msg import LockstepHold
from flex_nav.ros.params import param_bool
from flex_nav.ros.private_ns import private_namespace

HOLDS_TOPIC = "/lockstep/holds"
CONNECT_POLL_S = 0.01  # [s] wall
HOLDS_QUEUE = 100  # holds of one process in flight (several participants answer every scan)
# [s] a stamp made from a ROS time compares equal to it within this: genpy.Time.from_sec truncates to whole
# nanoseconds (20.2 s becomes 20.199999999 s), so a message stamped at the step would count as one before it
STAMP_TOLERANCE_S = 1e-6


def stamped_before(stamp_s: float, time_s: float) -> bool:
    """True for a stamp [s] before ROS time ``time_s`` [s] (not one made from that time: STAMP_TOLERANCE_S)."""
    return stamp_s + STAMP_TOLERANCE_S < time_s


def lockstep_enabled() -> bool:
    """``/lockstep`` (bool, false by default) on simulated time (a node on the wall clock, or none started, does not
    even ask the master; an unreachable master means off, with a warning)."""
    if rospy.rostime.is_wallclock() or not rospy.core.is_initialized():
        return False  # (no node: no master to ask)
    try:
        return param_bool("/lockstep", False)
    except OSError as err:  # the master is gone (a test process whose earlier node's master stopped)
        rospy.logwarn(f"lockstep off: the master could not be asked for /lockstep: {err}")
        return False


def accept_hold_name(server: str) -> str:
    """The hold a client of action server ``server`` (resolved) places when it sends a goal, and the server lets go
    of once the goal holds on its own: the simulation stands from the send to the server's first hold."""
    return f"{server}/accept"


def accept_hold_param(server: str) -> str:
    """Set true by a server that lets go of :func:`accept_hold_name` (a client holds only for such a server)."""
    return f"{server}/lockstep_accepts"


class LockstepParticipant:
    """One participant's holds, named ``<private namespace>/<what>`` (build it in the component's constructor, see
    :mod:`flex_nav.ros.private_ns`) or ``name``; every method is a no-op when lockstep is off. ``dedupe``: a hold
    equal to the last one sent is not sent again (False where another node replaces this participant's holds)."""

    def __init__(self, what: str = "", enabled: Optional[bool] = None, *, name: Optional[str] = None,
                 dedupe: bool = True) -> None:
        if (name is None) == (not what):
            raise ValueError(f"a lockstep participant needs what ({what!r}) or name ({name!r}), exactly one")
        self.name = name if name is not None else f"{private_namespace()}/{what}"
        self.dedupe = dedupe
        self.enabled = lockstep_enabled() if enabled is None else enabled
        self._lock = threading.Lock()
        self._last: Optional[Tuple[bool, str, float]] = None
        self._publisher = rospy.Publisher(HOLDS_TOPIC, LockstepHold, queue_size=HOLDS_QUEUE) if self.enabled else None

    def wait_connected(self, timeout_s: float) -> bool:
        """Wait at most ``timeout_s`` [s wall] until the simulator listens to this participant's holds (a hold sent
        before would be lost); True at once when lockstep is off."""
        deadline = time.monotonic() + timeout_s
        while self._publisher is not None and self._publisher.get_num_connections() == 0:
            if time.monotonic() >= deadline or rospy.is_shutdown():
                return False
            time.sleep(CONNECT_POLL_S)
        return True

    def hold_clock(self, stamp_s: float) -> None:
        """Wait for me once simulated time reaches ``stamp_s`` [s] (a finite time; now: freeze it until I go on)."""
        self._send(True, "", stamp_s)

    def hold_topic(self, topic: str, stamp_s: float) -> None:
        """Wait for me once a message on ``topic`` (resolved) stamped at or after ``stamp_s`` [s] is published."""
        self._send(True, topic, stamp_s)

    def release(self, through_s: float = -math.inf) -> None:
        """I wait for nothing now; with ``through_s`` [s]: for nothing stamped up to it, even a hold of mine that is
        still on its way from another node (an action server letting go of the hold its client placed)."""
        self._send(False, "", through_s)

    def sent(self, topic: str, stamp_s: float) -> None:
        """I have just published a message stamped ``stamp_s`` [s] on ``topic`` (resolved; the simulator subscribes
        to it, e.g. a velocity command, or a node that reports it with :meth:`received`): the simulation steps on
        only once it has received that message. Sent with my current hold, before any later one."""
        self._report(sent_topic=topic, sent_stamp_s=stamp_s)

    def received(self, topic: str, stamp_s: float) -> None:
        """I have taken in a message stamped ``stamp_s`` [s] on ``topic`` (resolved): what was sent there up to that
        stamp is waited for no more. ``stamp_s`` -inf: I receive ``topic`` from now on (messages announced there
        are waited for until I report them); +inf: I no longer do."""
        self._report(received_topic=topic, received_stamp_s=stamp_s)

    def _report(self, **fields: Any) -> None:
        """My current hold again, with ``fields`` of LockstepHold (a send or a receipt)."""
        if self._publisher is None:
            return
        with self._lock:
            holding, topic_held, stamp_held = self._last if self._last is not None else (False, "", -math.inf)
            self._publisher.publish(LockstepHold(participant=self.name, holding=holding, topic=topic_held,
                                                 stamp_s=stamp_held, **fields))

    def _send(self, holding: bool, topic: str, stamp_s: float) -> None:
        if self._publisher is None:
            return
        if holding and not math.isfinite(stamp_s):
            holding, topic, stamp_s = False, "", 0.0  # no finite next tick: nothing to wait for
        with self._lock:
            key = (holding, topic, stamp_s)
            if key == self._last and self.dedupe:
                return
            self._last = key
            msg = LockstepHold(participant=self.name, holding=holding, topic=topic, stamp_s=stamp_s)
            self._publisher.publish(msg)


def server_accept_hold(server: str) -> LockstepParticipant:
    """An action server's side of :func:`accept_hold_name` (``server`` resolved): the participant it lets go of that
    hold with, and, under lockstep, :func:`accept_hold_param` set so that its clients place the hold."""
    accept = LockstepParticipant(name=accept_hold_name(server), dedupe=False)
    if accept.enabled:
        rospy.set_param(accept_hold_param(server), True)
    return accept
