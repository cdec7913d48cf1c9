"""WaitPathClearState: wait, with bounded patience, until the region in front of the robot is clear."""

from __future__ import annotations

from typing import List, Optional, Sequence

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON, UNKNOWN
from flex_nav_states import validation
from flex_nav_states.obstacle_class_state import ClassReader

BLOCKING_CHOICES = (PERSON, MOVABLE, UNKNOWN)


class WaitPathClearState(State):
    """Waits until the obstacle class stayed free of the blocking labels for ``clear_for_s``, at most
    ``patience_s``. The robot is not commanded here (the state before it stopped it).

    A label counts as free when it is not in ``blocking``; a silent classifier (no fresh message) is
    never free, so a dead camera cannot let the robot drive into a person.

    -- patience_s       float  [s] Give up after this long (> 0).
    -- clear_for_s      float  [s] The class must stay free this long without a break.
    -- blocking         list   Labels that keep the path blocked: some of person, movable, unknown.
    -- class_topic      str    flex_nav/ObstacleClass topic of the obstacle classifier.
    -- class_max_age_s  float  [s] Older class messages do not count.

    #> waited_s  float  [s] How long the state waited.

    <= clear          The path stayed free for clear_for_s.
    <= still_blocked  Patience ran out; the last label is logged.
    """

    def __init__(self, patience_s: float = 10.0, clear_for_s: float = 1.0,
                 blocking: Sequence[str] = (PERSON, UNKNOWN), class_topic: str = "obstacle_class",
                 class_max_age_s: float = 1.0) -> None:
        super().__init__(outcomes=[CLEAR, "still_blocked"], output_keys=["waited_s"], rate_hz=10.0)
        owner = type(self).__name__
        self._patience_s = validation.number(owner, "patience_s", patience_s, positive=True, unit="[s]")
        self._clear_for_s = validation.number(owner, "clear_for_s", clear_for_s, minimum=0.0, unit="[s]")
        self._blocking: List[str] = [validation.choice(owner, "blocking", b, BLOCKING_CHOICES)
                                     for b in validation.names(owner, "blocking", list(blocking))]
        self._reader = ClassReader(owner, class_topic, class_max_age_s)
        self._enter_s = 0.0
        self._free_since_s: Optional[float] = None
        self._last = UNKNOWN

    def on_start(self) -> None:
        self._reader.start(self)

    def on_enter(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()
        self._free_since_s = None
        self._last = UNKNOWN

    def on_resume(self, userdata: UserDataView) -> None:
        self._free_since_s = None  # what was seen before a pause does not count

    def execute(self, userdata: UserDataView) -> Optional[str]:
        now = self.now_s()
        msg = self._reader.latest(self)
        free = False
        if msg is not None:
            self._last = PERSON if PERSON in (msg.label, msg.frame_label) else msg.label
            free = self._last not in self._blocking and self._last in (CLEAR, MOVABLE, PERSON)
        else:
            self._last = "no fresh message"
        waited_s = now - self._enter_s
        if free:
            if self._free_since_s is None:
                self._free_since_s = now
            if now - self._free_since_s >= self._clear_for_s:
                userdata.waited_s = waited_s
                self.log_info(f"path clear ({self._last}) after {waited_s:.1f} s")
                return CLEAR
        else:
            self._free_since_s = None
        if waited_s >= self._patience_s:
            userdata.waited_s = waited_s
            self.log_warn(f"path still blocked after {waited_s:.1f} s (patience_s {self._patience_s:g} s): "
                          f"{self._last}")
            return "still_blocked"
        return None
