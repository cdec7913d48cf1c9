"""ObstacleFusionState: what blocks the way, from two cues, the camera's class and the lidar's shape, with a
bounded "look again" when the camera is unsure or the cues disagree.

The camera's class comes from the ``obstacle_class`` topic as in
:class:`~flex_nav_states.obstacle_class_state.ObstacleClassState` (a person in the latest frame at once, any
other vote from frames taken ``settle_s`` after entry); the lidar's from the newest ``scan_topic`` scan
(:func:`flex_nav.perception.lidar_shape.cue_ahead`: the object with the nearest hit in a corridor ahead; the
scan's frame is taken as the robot's, x forward, as for the back-off's rear check; the object's speed is its
centre's displacement since the first scan of the visit, over at least 0.5 s, while the robot stands). The two
are fused by :func:`flex_nav.perception.fusion.fuse` (its module documents the rule); the decision and both cues
are logged on one line. With ``fuse_lidar`` false the state decides from the camera alone, exactly as ObstacleClassState
(it never looks again).
"""

from __future__ import annotations

import math
from typing import Optional, Tuple

from sensor_msgs.msg import LaserScan

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.perception.fusion import LOOK_AGAIN, MAX_LOOKS, CameraCue, FusionParams, fuse
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON, UNKNOWN
from flex_nav.perception.lidar_shape import PERSON as LIDAR_PERSON
from flex_nav.perception.lidar_shape import UNSURE, ShapeCue, cue_ahead
from flex_nav_states import validation
from flex_nav_states.messages import message_age_s
from flex_nav_states.obstacle_class_state import DECIDED, ClassReader, settle_and_timeout
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of

MOVING_WINDOW_S = 0.5  # [s] the object's speed is measured over at least this long (centre noise ~1 cm: < 0.05 m/s)


class ObstacleFusionState(State):
    """Decides person / movable / clear / unknown from the camera's class and the lidar's shape, or asks to look
    again (at most ``max_looks`` times in a row; the count is kept in ``looks``).

    Waits up to ``timeout_s`` after entry for a fresh decided camera vote (see ObstacleClassState); a person seen
    by the camera's latest frame or by the lidar decides at once. Then the cues are fused; without a decided
    vote in time the camera's cue is unknown (and the lidar may still decide). ``looks`` counts the looks again
    of this blocked episode: it goes up by one on ``look_again`` and back to 0 on every other outcome.

    -- class_topic            str    flex_nav/ObstacleClass topic of the obstacle_classifier node.
    -- class_max_age_s        float  [s] Older class messages do not count.
    -- settle_s               float  [s] Camera votes other than person count from messages this long after entry.
    -- timeout_s              float  [s] How long to wait for a decided camera vote (longer than settle_s).
    -- fuse_lidar             bool   Fuse the lidar's shape; false: the camera alone, never look again.
    -- scan_topic             str    sensor_msgs/LaserScan topic (its frame taken as the robot's, x forward).
    -- scan_max_age_s         float  [s] An older scan is no lidar cue (unsure).
    -- reach_m                float  [m] The object is the nearest hit within this far ahead.
    -- half_width_m           float  [m] Half the width of the corridor ahead searched for it.
    -- max_looks              int    Looks again before deciding without them (0..10).
    -- camera_min_confidence  float  A camera vote less confident than this is unsure.
    -- lidar_min_confidence   float  A lidar box less confident than this counts as unsure.

    ># looks            float  Looks again taken in this blocked episode (0 at the first try).
    #> looks            float  Looks again so far: one more on look_again, 0 on every other outcome.
    #> obstacle_class   str    person, movable, clear, unknown or look_again.
    #> obstacle_fusion  str    The decision and both cues on one line.

    <= person      A person is in front of the robot (on either cue).
    <= movable     A movable object is in front of the robot (the camera's movable, or a box shape and no person cue).
    <= clear       Nothing the camera knows is in front, and the lidar sees no box.
    <= unknown     Neither cue decides (after the looks again).
    <= look_again  The camera is unsure or the cues disagree: move a little (turn, back off) and come back.
    """

    def __init__(
        self,
        class_topic: str = "obstacle_class",
        class_max_age_s: float = 1.0,
        settle_s: float = 0.0,
        timeout_s: float = 2.0,
        *,
        fuse_lidar: bool = True,
        scan_topic: str = "scan",
        scan_max_age_s: float = 0.5,
        reach_m: float = 1.2,
        half_width_m: float = 0.3,
        max_looks: int = 2,
        camera_min_confidence: float = 0.7,
        lidar_min_confidence: float = 0.6,
    ) -> None:
        super().__init__(outcomes=[PERSON, MOVABLE, CLEAR, UNKNOWN, LOOK_AGAIN], input_keys=["looks"],
                         output_keys=["looks", "obstacle_class", "obstacle_fusion"], rate_hz=20.0)
        owner = type(self).__name__
        self._reader = ClassReader(owner, class_topic, class_max_age_s)
        self._settle_s, self._timeout_s = settle_and_timeout(owner, settle_s, timeout_s)
        self._fuse = validation.boolean(owner, "fuse_lidar", fuse_lidar)
        self._scan_topic = validation.name(owner, "scan_topic", scan_topic)
        self._scan_max_age_s = validation.number(owner, "scan_max_age_s", scan_max_age_s, positive=True, unit="[s]")
        self._reach_m = validation.number(owner, "reach_m", reach_m, positive=True, unit="[m]")
        self._half_width_m = validation.number(owner, "half_width_m", half_width_m, positive=True, unit="[m]")
        validation.integer(owner, "max_looks", max_looks, minimum=0, maximum=MAX_LOOKS)
        try:
            self._params = FusionParams(camera_min_confidence=camera_min_confidence,
                                        lidar_min_confidence=lidar_min_confidence, max_looks=max_looks)
        except ConfigError as err:
            raise ConfigError(f"{owner}: {err}") from err
        self._scan: Optional[SubscriptionLike] = None
        self._enter_s = 0.0
        self._first_centre: Optional[Tuple[float, Tuple[float, float]]] = None  # ([s], (x, y) [m]) of this visit

    def on_start(self) -> None:
        self._reader.start(self)
        if self._fuse:
            self._scan = proxies_of(self).subscription(self._scan_topic, LaserScan)

    def on_enter(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()
        self._first_centre = None

    def execute(self, userdata: UserDataView) -> Optional[str]:
        label, msg = self._reader.settled(self, self._enter_s + self._settle_s)
        waited_s = self.now_s() - self._enter_s
        timed_out = waited_s >= self._timeout_s
        if not self._fuse:
            if label in DECIDED or timed_out:
                return self._camera_only(userdata, label if label in DECIDED else UNKNOWN, msg, waited_s)
            return None
        lidar = self._lidar_cue()
        if label not in DECIDED and lidar.label != LIDAR_PERSON and not timed_out:
            return None
        camera = CameraCue(UNKNOWN, 0.0) if msg is None else CameraCue(
            label if label == PERSON else msg.label, float(msg.confidence), int(msg.votes), int(msg.window),
            msg.frame_label or UNKNOWN, float(msg.frame_confidence))
        looks = int(userdata.looks) if userdata.looks is not None else 0
        decision = fuse(camera, lidar, min(looks, self._params.max_looks), self._params)
        userdata.looks = float(looks + 1) if decision.label == LOOK_AGAIN else 0.0
        userdata.obstacle_class = decision.label
        userdata.obstacle_fusion = decision.line()
        self.log_info(f"obstacle: {decision.line()}")
        return decision.label

    def _camera_only(self, userdata: UserDataView, label: str, msg: object, waited_s: float) -> str:
        userdata.obstacle_class = label
        userdata.looks = 0.0
        userdata.obstacle_fusion = f"camera only: {label}"
        if label == UNKNOWN:
            why = "no fresh message" if msg is None else "undecided vote"
            self.log_warn(f"obstacle class unknown after {waited_s:.1f} s on {self._reader.topic}: {why}")
        else:
            self.log_info(f"obstacle class: {label} (camera only)")
        return label

    def _lidar_cue(self) -> ShapeCue:
        sub = self._scan
        if sub is None:
            sub = self._scan = proxies_of(self).subscription(self._scan_topic, LaserScan)
        scan = sub.last()
        if scan is None or message_age_s(scan, sub, self.now_s()) > self._scan_max_age_s:
            return ShapeCue(UNSURE, 0.0, f"no scan on {self._scan_topic} newer than {self._scan_max_age_s:g} s")
        cue = cue_ahead(scan.ranges, scan.angle_min, scan.angle_increment, scan.range_min, scan.range_max,
                        reach_m=self._reach_m, half_width_m=self._half_width_m)
        speed = self._object_speed(cue)
        if speed is None:
            return cue
        return cue_ahead(scan.ranges, scan.angle_min, scan.angle_increment, scan.range_min, scan.range_max,
                         reach_m=self._reach_m, half_width_m=self._half_width_m, speed_mps=speed)

    def _object_speed(self, cue: ShapeCue) -> Optional[float]:
        """[m/s] how fast the object's centre moved since the first cue of this visit (the robot stands while it
        classifies), once at least MOVING_WINDOW_S apart; None before that or without an object."""
        if cue.features is None:
            return None
        now = self.now_s()
        if self._first_centre is None:
            self._first_centre = (now, cue.features.centre)
            return None
        start_s, (x0, y0) = self._first_centre
        if now - start_s < MOVING_WINDOW_S:
            return None
        x1, y1 = cue.features.centre
        return math.hypot(x1 - x0, y1 - y0) / (now - start_s)
