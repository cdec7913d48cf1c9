"""ObstacleClassState: what stands in front of the robot (person, movable object, clear), from perception.

The class comes from the ``obstacle_class`` topic (flex_nav/ObstacleClass, published by the
``obstacle_classifier`` node after every classified frame: the majority of its last frames). Only a
message stamped no earlier than ``max_age_s`` before now counts, so a class seen before the robot got
where it is does not decide. :class:`ClassReader` is the shared reading used by the push and wait states.
"""

from __future__ import annotations

import math
from typing import Optional, Tuple

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.msg import ObstacleClass
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON, UNKNOWN
from flex_nav_states import validation
from flex_nav_states.messages import message_age_s, stamp_s
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of

DECIDED = (PERSON, MOVABLE, CLEAR)


class ClassReader:
    """The newest fresh ObstacleClass on one topic (helper of the perception states, not a state)."""

    def __init__(self, owner: str, topic: str, max_age_s: float) -> None:
        self.topic = validation.name(owner, "class_topic", topic)
        self.max_age_s = validation.number(owner, "class_max_age_s", max_age_s, positive=True, unit="[s]")
        self._sub: Optional[SubscriptionLike] = None

    def start(self, state: State) -> None:
        self._sub = proxies_of(state).subscription(self.topic, ObstacleClass)

    def latest(self, state: State, not_before_s: float = -math.inf) -> Optional[ObstacleClass]:
        """The newest message if it is at most max_age_s old on the behavior's clock (and, for a stamped
        message, stamped at or after ``not_before_s`` [s]), else None."""
        if self._sub is None:
            self.start(state)
        sub = self._sub
        assert sub is not None
        msg: Optional[ObstacleClass] = sub.last()
        if msg is None or message_age_s(msg, sub, state.now_s()) > self.max_age_s:
            return None
        stamp = stamp_s(msg)
        if stamp > 0.0 and stamp < not_before_s:
            return None
        return msg

    def settled(self, state: State, not_before_s: float) -> Tuple[str, Optional[ObstacleClass]]:
        """(label, message): person at once when the newest fresh message's vote or latest frame is a person;
        else the vote of the newest fresh message stamped at or after ``not_before_s`` [s]; unknown (and None)
        without one."""
        msg = self.latest(state)
        if msg is not None and PERSON in (msg.label, msg.frame_label):
            return PERSON, msg
        msg = self.latest(state, not_before_s=not_before_s)
        return (msg.label, msg) if msg is not None else (UNKNOWN, None)


def settle_and_timeout(owner: str, settle_s: float, timeout_s: float) -> tuple[float, float]:
    """The checked ``settle_s`` [s] (>= 0) and ``timeout_s`` [s] (longer than it) of a classifying state."""
    settle = validation.number(owner, "settle_s", settle_s, minimum=0.0, unit="[s]")
    timeout = validation.number(owner, "timeout_s", timeout_s, positive=True, unit="[s]")
    if timeout <= settle:
        raise ConfigError(f"{owner}: timeout_s {timeout:g} s must be longer than settle_s {settle:g} s")
    return settle, timeout


class ObstacleClassState(State):
    """Reads the class of the region in front of the robot from the obstacle classifier.

    Waits up to ``timeout_s`` after entry for a fresh message whose vote is decided (person, movable or
    clear). A person seen by the latest frame alone already counts as person at once (never push a person
    on a vote that lags); any other label counts only from a message stamped ``settle_s`` after entry, so
    the vote is made of frames taken after the robot stopped in front of the obstacle, not while it was
    approaching or turning. Nothing decided in time gives ``unknown``.

    -- class_topic      str    flex_nav/ObstacleClass topic of the obstacle_classifier node.
    -- class_max_age_s  float  [s] Older messages (by header stamp) do not count.
    -- settle_s         float  [s] Labels other than person count from messages stamped this long after entry.
    -- timeout_s        float  [s] How long to wait for a decided class (longer than settle_s).

    #> obstacle_class  str  person, movable, clear or unknown.

    <= person   A person is in front of the robot.
    <= movable  A movable object (a box) is in front of the robot.
    <= clear    Nothing the classifier knows is in front of the robot.
    <= unknown  No fresh decided class within timeout_s (classifier silent or undecided).
    """

    def __init__(self, class_topic: str = "obstacle_class", class_max_age_s: float = 1.0, settle_s: float = 0.0,
                 timeout_s: float = 2.0) -> None:
        super().__init__(outcomes=[PERSON, MOVABLE, CLEAR, UNKNOWN], output_keys=["obstacle_class"], rate_hz=20.0)
        owner = type(self).__name__
        self._reader = ClassReader(owner, class_topic, class_max_age_s)
        self._settle_s, self._timeout_s = settle_and_timeout(owner, settle_s, timeout_s)
        self._enter_s = 0.0

    def on_start(self) -> None:
        self._reader.start(self)

    def on_enter(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()

    def execute(self, userdata: UserDataView) -> Optional[str]:
        label, msg = self._reader.settled(self, self._enter_s + self._settle_s)
        if label in DECIDED:
            userdata.obstacle_class = label
            confidence = f" ({msg.votes}/{msg.window} votes, confidence {msg.confidence:.2f})" if msg else ""
            self.log_info(f"obstacle class: {label}{confidence}")
            return label
        waited_s = self.now_s() - self._enter_s
        if waited_s >= self._timeout_s:
            userdata.obstacle_class = UNKNOWN
            why = "no fresh message" if msg is None else f"undecided vote ({msg.label})"
            self.log_warn(f"obstacle class unknown after {waited_s:.1f} s on {self._reader.topic}: {why}")
            return UNKNOWN
        return None
