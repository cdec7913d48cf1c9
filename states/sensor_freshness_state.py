"""SensorFreshnessState: report when a sensor topic goes quiet (its newest message is too old)."""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CameraInfo, Image, Imu, LaserScan, PointCloud2

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.msg import BumperState, CreateBumper
from flex_nav_states import validation
from flex_nav_states.messages import message_age_s
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of

# Message types a sensor entry may name (a fixed table: names from a behavior file are never imported).
SENSOR_TYPES: Dict[str, type] = {
    "Odometry": Odometry,
    "LaserScan": LaserScan,
    "Image": Image,
    "CameraInfo": CameraInfo,
    "PointCloud2": PointCloud2,
    "Imu": Imu,
    "PoseStamped": PoseStamped,
    "PoseWithCovarianceStamped": PoseWithCovarianceStamped,
    "BumperState": BumperState,
    "CreateBumper": CreateBumper,
}
_ENTRY_KEYS = ("topic", "type", "max_age_s")
DEFAULT_SENSORS = (
    {"topic": "odom", "type": "Odometry", "max_age_s": 0.5},
    {"topic": "scan", "type": "LaserScan", "max_age_s": 1.0},
)


class SensorFreshnessState(State):
    """Returns ``stale`` when any watched sensor topic's newest message is older than its limit.

    Age is measured by header stamp on the behavior's clock (by arrival time for unstamped messages).
    After entry each sensor gets ``startup_grace_s`` (at least its own max_age_s) to deliver, so a monitor
    entered right after start-up does not fire on sensors that are still connecting. Only periodic
    topics belong here (not event topics such as kobuki bumper events).

    -- sensors          list   Entries {topic: str, type: str, max_age_s: float}; type is one of Odometry,
                               LaserScan, Image, CameraInfo, PointCloud2, Imu, PoseStamped,
                               PoseWithCovarianceStamped, BumperState, CreateBumper.
    -- startup_grace_s  float  [s] Time after entry before a sensor that has not delivered counts as stale.

    #> stale_topics  list  The topics that were found stale.

    <= stale  A sensor is stale; the topics and ages are logged.
    """

    def __init__(self, sensors: Sequence[Mapping[str, Any]] = DEFAULT_SENSORS, startup_grace_s: float = 2.0) -> None:
        super().__init__(outcomes=["stale"], output_keys=["stale_topics"])
        owner = type(self).__name__
        if isinstance(sensors, (str, Mapping)) or not isinstance(sensors, (list, tuple)) or not sensors:
            raise ConfigError(
                f"{owner}: sensors must be a non-empty list of {{topic, type, max_age_s}}, got {sensors!r}"
            )
        self._sensors: List[Tuple[str, type, float]] = []
        for index, entry in enumerate(sensors):
            where = f"sensors[{index}]"
            if not isinstance(entry, Mapping):
                raise ConfigError(f"{owner}: {where} must be a mapping {{topic, type, max_age_s}}, got {entry!r}")
            for key in entry:
                validation.choice(owner, f"{where} key", key, _ENTRY_KEYS)
            missing = [k for k in _ENTRY_KEYS if k not in entry]
            if missing:
                raise ConfigError(f"{owner}: {where} lacks {', '.join(missing)}")
            topic = validation.name(owner, f"{where}.topic", entry["topic"])
            msg_type = SENSOR_TYPES[validation.choice(owner, f"{where}.type", entry["type"], SENSOR_TYPES)]
            max_age = validation.number(owner, f"{where}.max_age_s", entry["max_age_s"], positive=True, unit="[s]")
            if any(topic == t for t, _, _ in self._sensors):
                raise ConfigError(f"{owner}: topic {topic} is listed twice in sensors")
            self._sensors.append((topic, msg_type, max_age))
        self._grace_s = validation.number(owner, "startup_grace_s", startup_grace_s, minimum=0.0, unit="[s]")
        self._subs: List[SubscriptionLike] = []
        self._enter_s = 0.0

    def on_start(self) -> None:
        proxies = proxies_of(self)
        self._subs = [proxies.subscription(topic, msg_type) for topic, msg_type, _ in self._sensors]

    def on_enter(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()

    def on_resume(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()  # the grace applies again after a pause

    def execute(self, userdata: UserDataView) -> Optional[str]:
        if not self._subs:
            self.on_start()
        now = self.now_s()
        since_entry = now - self._enter_s
        stale: List[str] = []
        details: List[str] = []
        for (topic, _, max_age), sub in zip(self._sensors, self._subs):
            if since_entry <= max(max_age, self._grace_s):
                continue
            msg = sub.last()
            if msg is None:
                stale.append(topic)
                details.append(f"{topic}: no message")
                continue
            age = message_age_s(msg, sub, now)
            if age > max_age:
                stale.append(topic)
                details.append(f"{topic}: {age:.2f} s old (max_age_s {max_age:g} s)")
        if stale:
            userdata.stale_topics = stale
            self.log_error(f"stale sensor(s): {'; '.join(details)}")
            return "stale"
        return None
