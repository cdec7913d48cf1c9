"""BumperMonitorState: watch the bumper (and optionally cliff sensors) of any robot, configured by its profile."""

from __future__ import annotations

import threading
from typing import Any, Dict, List, Optional, Sequence, Set

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.msg import BumperEvent, BumperState, CreateBumper
from flex_nav_sim.profiles import BUMPER_STYLES, load_profile
from flex_nav_states import validation
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of

# How each driver style reports the bumper: message type, default topic, zone names it can report.
DRIVER_TOPICS = {"kobuki": "events/bumper", "create": "bumper", "zones": "bumper_state"}
DRIVER_TYPES = {"kobuki": BumperEvent, "create": CreateBumper, "zones": BumperState}
KOBUKI_ZONES = {BumperEvent.LEFT: "left", BumperEvent.CENTER: "center", BumperEvent.RIGHT: "right"}
CREATE_ZONES = ("left", "right")
MAX_UNKNOWN_REPORTS = 8  # unknown bumper ids kept for the next tick's warning (a driver sending them on a loop)


class BumperMonitorState(State):
    """Returns when a bumper zone is pressed (or a cliff is seen); robot-agnostic, configured by a robot profile.

    The profile (``sim/robots/<name>.yaml``) says how the robot's driver reports its bumper: ``kobuki``
    (flex_nav/BumperEvent press/release events, zones left/center/right), ``create`` (flex_nav/CreateBumper
    is_left_pressed/is_right_pressed, zones left/right) or ``zones`` (flex_nav/BumperState, the profile's
    zone names). A bumper still pressed when the state is entered counts at once; with kobuki events, so does
    a press released again between two ticks while the state is active (a glancing contact). Cliff sensors, when
    ``cliff_topic`` is set, are read as flex_nav/BumperState (zone = sensor name, pressed = cliff).

    -- profile       str   Robot profile name (kobuki, create2, turtlebot4) or path: driver style and zones.
    -- driver_style  str   Override of the profile's style: kobuki, create or zones ("" for the profile's).
    -- topic         str   Bumper topic ("" for the style's default: events/bumper, bumper or bumper_state).
    -- zones         list  Zone names that count ([] for every zone the driver reports).
    -- cliff_topic   str   flex_nav/BumperState topic of cliff sensors ("" for no cliff monitoring).

    #> bumper_zones  list  Names of the pressed zones (or of the cliff sensors that see a cliff).

    <= bumper  A watched bumper zone is pressed.
    <= cliff   A cliff sensor reports a cliff.
    """

    def __init__(
        self,
        profile: str = "kobuki",
        driver_style: str = "",
        topic: str = "",
        zones: Sequence[str] = (),
        cliff_topic: str = "",
    ) -> None:
        super().__init__(outcomes=["bumper", "cliff"], output_keys=["bumper_zones"])
        owner = type(self).__name__
        try:
            spec = load_profile(profile)
        except ConfigError as err:
            raise ConfigError(f"{owner}: profile: {err}") from err
        style = spec.bumper.driver_style
        if driver_style:
            style = validation.choice(owner, "driver_style", driver_style, BUMPER_STYLES)
        self._style = style
        if style == "kobuki":
            reported: List[str] = list(KOBUKI_ZONES.values())
        elif style == "create":
            reported = list(CREATE_ZONES)
        else:
            reported = [z.name for z in spec.bumper.zones]
        watched = validation.names(owner, "zones", zones)
        for zone in watched:
            if zone not in reported:
                raise ConfigError(
                    f"{owner}: zone {zone!r} is not reported by a {style}-style bumper of profile {spec.name} "
                    f"(valid: {', '.join(reported)})"
                )
        self._zones: List[str] = watched or reported
        self._topic = validation.name(owner, "topic", topic, allow_empty=True) or DRIVER_TOPICS[style]
        self._cliff_topic = validation.name(owner, "cliff_topic", cliff_topic, allow_empty=True)
        self._sub: Optional[SubscriptionLike] = None
        self._cliff_sub: Optional[SubscriptionLike] = None
        # kobuki: every event reaches every monitor of the behavior (a callback each, in rospy's thread), so
        # one that is not running does not miss the release that a running one saw
        self._events_lock = threading.Lock()
        self._kobuki_held: Set[str] = set()  # zones pressed and not released
        self._kobuki_hit: Set[str] = set()  # zones pressed since the last tick (or entry)
        self._unknown_bumpers: List[int] = []
        self._warned_missing: Set[str] = set()

    @property
    def watched_zones(self) -> List[str]:
        return list(self._zones)

    def on_start(self) -> None:
        proxies = proxies_of(self)
        self._sub = proxies.subscription(self._topic, DRIVER_TYPES[self._style])
        if self._cliff_topic:
            self._cliff_sub = proxies.subscription(self._cliff_topic, BumperState)
        with self._events_lock:
            self._kobuki_held.clear()
            self._kobuki_hit.clear()
        if self._style == "kobuki":
            self._sub.add_callback(self._on_kobuki_event)

    def on_enter(self, userdata: UserDataView) -> None:
        with self._events_lock:
            self._kobuki_hit.clear()  # a press released before entry does not count; one still held does
            self._unknown_bumpers.clear()  # nor is an unknown bumper seen while not running reported now

    def _on_kobuki_event(self, event: Any) -> None:
        zone = KOBUKI_ZONES.get(event.bumper)
        with self._events_lock:
            if zone is None:
                if len(self._unknown_bumpers) < MAX_UNKNOWN_REPORTS:  # bounded between two ticks
                    self._unknown_bumpers.append(event.bumper)
            elif event.state == BumperEvent.PRESSED:
                self._kobuki_held.add(zone)
                self._kobuki_hit.add(zone)
            else:
                self._kobuki_held.discard(zone)

    def execute(self, userdata: UserDataView) -> Optional[str]:
        if self._sub is None:
            self.on_start()
        pressed = [z for z in self._pressed_zones() if z in self._zones]
        if pressed:
            userdata.bumper_zones = pressed
            self.log_warn(f"bumper pressed: {', '.join(pressed)} (on {self._topic})")
            return "bumper"
        cliffs = self._cliffs()
        if cliffs:
            userdata.bumper_zones = cliffs
            self.log_warn(f"cliff detected: {', '.join(cliffs)} (on {self._cliff_topic})")
            return "cliff"
        return None

    def _pressed_zones(self) -> List[str]:
        sub = self._sub
        if sub is None:
            return []
        if self._style == "kobuki":
            with self._events_lock:
                pressed = self._kobuki_held | self._kobuki_hit
                self._kobuki_hit.clear()
                unknown, self._unknown_bumpers = self._unknown_bumpers, []
            for bumper in unknown:
                self.log_warn(f"ignored a bumper event with unknown bumper {bumper} on {self._topic}")
            return sorted(pressed, key=list(KOBUKI_ZONES.values()).index)
        msg = sub.last()
        if msg is None:
            return []
        if self._style == "create":
            flags = {"left": bool(msg.is_left_pressed), "right": bool(msg.is_right_pressed)}
            return [z for z in CREATE_ZONES if flags[z]]
        return self._zone_state(msg, self._topic, self._zones)

    def _cliffs(self) -> List[str]:
        sub = self._cliff_sub
        msg = sub.last() if sub is not None else None
        if msg is None:
            return []
        return self._zone_state(msg, self._cliff_topic, None)

    def _zone_state(self, msg: Any, topic: str, expected: Optional[List[str]]) -> List[str]:
        """Pressed zone names of a BumperState; warns once per topic when it lacks an expected zone."""
        if len(msg.zones) != len(msg.pressed):
            self.log_warn(f"ignored a BumperState on {topic} with {len(msg.zones)} zones but {len(msg.pressed)} flags")
            return []
        states: Dict[str, bool] = {str(z): bool(p) for z, p in zip(msg.zones, msg.pressed)}
        if expected is not None and topic not in self._warned_missing:
            missing = [z for z in expected if z not in states]
            if missing:
                self._warned_missing.add(topic)
                self.log_warn(f"{topic} does not report zone(s) {', '.join(missing)} (it reports {', '.join(states)})")
        return [z for z, p in states.items() if p]
