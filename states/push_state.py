"""PushState: push an obstacle straight ahead by a distance at a speed, closed loop on odometry.

A push has three ways to fail, all ending in a zero twist: no progress on odometry within
``stall_window_s`` (the object is too heavy: detected within about one window, the thesis needed 3 s),
the whole push taking longer than ``distance_m / speed_mps + margin_s`` (progress too slow; but a push that got
``enough_fraction`` of the distance by then moved the object and counts as done), and the
perception seeing a person in front of the robot (the state never starts and never goes on pushing a
person; it also refuses to start without a fresh class that is not person).

With ``person_frames`` above 1, a single frame said person makes the robot stand (no push toward anyone on any
frame), and the push ends only when that many classified frames in a row, or the vote, say person; otherwise it
goes on. At contact the object fills the camera's view, out of the range the classifier was trained for (0.55-1.8
m): issue 28's h4 (a green box) gave one person frame of confidence 0.45 there, then the wall-like "clear" of a face
filling the view, and every push ended at once.

With ``approach_speed_mps`` and a ``scan_topic``, the gap to the object's face on the scan at the start is driven
faster, up to ``contact_slack_m`` before it; the push itself (contact, and a heavy object's stall) is at
``speed_mps`` (S5, where the robot stops ~0.5 m before the box: the failed push took 3.2 s with a 0.3 m/s approach,
4.0 s without).

With ``passage_extra_m`` and a ``scan_topic``, a push that has gone ``distance_m`` while the robot is still in a
passage (a scan return on both sides, within ``passage_side_m`` of its centre line, beside or up to
``passage_behind_m`` behind its centre) goes on until a side opens, at most ``passage_extra_m`` farther: the object
leaves the passage with room behind it for the robot to get by (issue 28's h4: a 0.8 m-wide box pushed 2 m along a
4 m, 1.2 m-wide route stayed at its end, and the replan was a 17.5 m detour).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from sensor_msgs.msg import LaserScan

from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.nav.angles import wrap_angle
from flex_nav.perception.labels import PERSON
from flex_nav_states import validation
from flex_nav_states.messages import OdomSample, message_age_s
from flex_nav_states.motion_base import MotionBase, stall_watch
from flex_nav_states.motion_params import SPEED_LIMITS, CommandOutput, OdometryInput
from flex_nav_states.obstacle_class_state import ClassReader
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of
from flex_nav_states.rear_clearance import gap_ahead_m, walled_in

HEADING_GAIN = 1.0  # [1/s] yaw rate per radian of heading error (pushes straight)
MAX_HEADING_RATE = 0.3  # [rad/s] bound of the heading correction


class PushState(MotionBase):
    """Pushes straight forward by ``distance_m`` at ``speed_mps`` and stops; fails fast on a heavy object.

    Progress is the odometry displacement along the heading at the start. The class topic is read on
    every tick: a person (by the vote or the latest frame) stops the robot at once; the push ends with
    ``person`` then (``person_frames`` 1), or once ``person_frames`` frames in a row or the vote say person
    (standing in between; the time stood does not count against the push's time or stall window); no
    fresh class, at entry or while pushing (the classifier or its camera went silent), also gives ``person``
    (unknown is treated as a person).
    The robot stops (zero twist) on every exit.

    -- distance_m        float  [m] How far to push (> 0).
    -- speed_mps         float  [m/s] Pushing speed (> 0).
    -- margin_s          float  [s] Timeout = distance_m / speed_mps + margin_s.
    -- enough_fraction   float  [0..1] A push timed out after this fraction of distance_m is done (1: fails).
    -- stall_window_s    float  [s] Fail when progress grew by less than stall_distance_m in this window.
    -- stall_distance_m  float  [m] Least progress per stall window (> 0, below speed_mps x stall_window_s).
    -- class_topic       str    flex_nav/ObstacleClass topic of the obstacle classifier.
    -- class_max_age_s   float  [s] Older class messages do not count.
    -- person_frames     int    Classified frames in a row said person that end the push (>= 1; the vote saying
                                person always does); fewer make the robot stand.
    -- odom_topic        str    nav_msgs/Odometry topic.
    -- odom_timeout_s    float  [s] Fail when no fresh odometry for this long.
    -- cmd_topic         str    geometry_msgs/TwistStamped command topic.
    -- frame_id          str    frame_id of the commands (the robot's base frame).
    -- approach_speed_mps  float  [m/s] Speed up to the object's face seen on the scan at the start (0: speed_mps
                                  all the way; else at least speed_mps, and needs scan_topic).
    -- scan_topic        str    sensor_msgs/LaserScan topic for the gap ahead ("" for none); its frame is taken as
                                the base's (a lidar near the centre, as flex_nav_states.rear_clearance).
    -- robot_radius_m    float  [m] Radius of the base: the gap is from its front (> 0).
    -- contact_slack_m   float  [m] The last this far before the face is driven at speed_mps (>= 0).
    -- scan_max_age_s    float  [s] An older scan gives no approach (speed_mps all the way) and ends a push at
                                distance_m.
    -- passage_extra_m   float  [m] Pushed this much farther at most while the robot is in a passage (0: off; needs
                                scan_topic).
    -- passage_side_m    float  [m] A scan return this close to the centre line on each side is a passage (> 0).
    -- passage_behind_m  float  [m] ... beside the centre or up to this far behind it (>= 0).

    #> push_progress_m  float  [m] How far the robot got.

    <= done    Pushed the whole distance (or enough_fraction of it when the time ran out).
    <= failed  No progress (heavy object), too slow, or odometry missing; the reason is logged.
    <= person  A person is in front (or no fresh class): nothing or no more was pushed.
    """

    def __init__(
        self,
        distance_m: float,
        speed_mps: float = 0.1,
        *,
        margin_s: float = 2.0,
        enough_fraction: float = 0.75,
        stall_window_s: float = 1.0,
        stall_distance_m: float = 0.02,
        class_topic: str = "obstacle_class",
        class_max_age_s: float = 1.0,
        person_frames: int = 1,
        odom_topic: str = "odom",
        odom_timeout_s: float = 0.5,
        cmd_topic: str = "cmd_vel_stamped",
        frame_id: str = "base_footprint",
        approach_speed_mps: float = 0.0,
        scan_topic: str = "",
        robot_radius_m: float = 0.2,
        contact_slack_m: float = 0.05,
        scan_max_age_s: float = 0.5,
        passage_extra_m: float = 0.0,
        passage_side_m: float = 0.8,
        passage_behind_m: float = 0.4,
    ) -> None:
        owner = type(self).__name__
        super().__init__(
            ["done", "failed", PERSON],
            odometry=OdometryInput(owner, odom_topic, odom_timeout_s),
            command=CommandOutput(owner, cmd_topic, frame_id),
            output_keys=["push_progress_m"],
        )
        self._distance_m = validation.number(owner, "distance_m", distance_m, positive=True, unit="[m]")
        self._speed_mps = SPEED_LIMITS.linear(owner, "speed_mps", speed_mps)
        margin = validation.number(owner, "margin_s", margin_s, minimum=0.0, unit="[s]")
        self._passage_extra_m = validation.number(owner, "passage_extra_m", passage_extra_m, minimum=0.0, unit="[m]")
        self._passage_side_m = validation.number(owner, "passage_side_m", passage_side_m, positive=True, unit="[m]")
        self._passage_behind_m = validation.number(owner, "passage_behind_m", passage_behind_m, minimum=0.0,
                                                   unit="[m]")
        if self._passage_extra_m > 0.0 and not scan_topic:
            raise ConfigError(f"{owner}: passage_extra_m {passage_extra_m:g} m needs a scan_topic (the passage's "
                              "sides)")
        self._timeout_s = (self._distance_m + self._passage_extra_m) / self._speed_mps + margin
        self._enough_m = self._distance_m * validation.number(owner, "enough_fraction", enough_fraction,
                                                              minimum=0.0, maximum=1.0, unit="[0..1]")
        self._stall = stall_watch(owner, stall_window_s, progress_name="stall_distance_m",
                                  min_progress=stall_distance_m, unit="m", slowest_speed=self._speed_mps)
        self._reader = ClassReader(owner, class_topic, class_max_age_s)
        self._person_frames = validation.integer(owner, "person_frames", person_frames, minimum=1)
        self._person_run = 0  # classified frames in a row said person (counted once per frame stamp)
        self._person_stamp: Optional[float] = None  # [s] stamp of the last frame counted
        self._stand_since: Optional[float] = None  # [s] when the robot stood for a person frame (None: pushing)
        self._stood_s = 0.0  # [s] time stood so far (not counted against the timeout)
        self._approach = _Approach(owner, approach_speed_mps, self._speed_mps, scan_topic, robot_radius_m,
                                   contact_slack_m, scan_max_age_s)  # checked there
        self._scan: Optional[SubscriptionLike] = None
        self._approach_m = 0.0  # [m] of progress at approach_speed_mps (from the scan at the start)
        self._start: Optional[OdomSample] = None
        self._progress_m = 0.0
        self._checked = False
        self._passage_logged = False  # the push past distance_m in a passage was logged

    @property
    def timeout_s(self) -> float:
        """[s] (distance_m + passage_extra_m) / speed_mps + margin_s."""
        return self._timeout_s

    def on_start(self) -> None:
        super().on_start()
        self._reader.start(self)
        if self._approach.enabled or self._passage_extra_m > 0.0:
            self._scan = proxies_of(self).subscription(self._approach.scan_topic, LaserScan)

    def on_enter(self, userdata: UserDataView) -> None:
        super().on_enter(userdata)
        self._start = None
        self._progress_m = 0.0
        self._checked = False
        self._person_run, self._person_stamp = 0, None
        self._stand_since, self._stood_s = None, 0.0
        self._passage_logged = False

    def on_exit(self, userdata: UserDataView) -> None:
        super().on_exit(userdata)
        userdata.push_progress_m = self._progress_m

    def on_resume(self, userdata: UserDataView) -> None:
        super().on_resume(userdata)
        self._stall.restart_window(self.now_s())

    def execute(self, userdata: UserDataView) -> Optional[str]:
        msg = self._reader.latest(self)
        if msg is None:  # the classifier or camera went silent: it could be a person now
            self.stop()
            what = f"push stopped at {self._progress_m:.2f} m" if self._checked else "push refused"
            self.log_error(f"{what}: no fresh obstacle class on {self._reader.topic} "
                           f"for {self._reader.max_age_s:g} s (could be a person)")
            return PERSON
        self._checked = True
        if PERSON in (msg.label, msg.frame_label):
            self.stop()
            stamp_s = msg.header.stamp.to_sec()
            if stamp_s != self._person_stamp:
                self._person_run, self._person_stamp = self._person_run + 1, stamp_s
            if msg.label == PERSON or self._person_run >= self._person_frames:
                self.log_warn(f"push stopped: a person is in front of the robot (pushed {self._progress_m:.2f} m)")
                return PERSON
            if self._stand_since is None:
                self._stand_since = self.now_s()
                self.log_info(f"push: a frame said person ({msg.frame_confidence:.2f}): standing "
                              f"(pushed {self._progress_m:.2f} m)")
            return None
        self._person_run = 0
        if self._stand_since is not None:  # the frame after it did not say person: push on
            now = self.now_s()
            self._stood_s += now - self._stand_since
            self._stand_since = None
            self._stall.restart_window(now)
            self.log_info(f"push: the next frame said {msg.frame_label}: pushing on")
        return self._drive()

    def _drive(self) -> Optional[str]:
        now = self.now_s()
        sample = self.odometry()
        if sample is None:
            if self.odometry_lost():
                self.log_error(f"push: {self.odometry_problem()}")
                return "failed"
            self.stop()
            return None
        if self._start is None:
            self._start = sample
            self._stall.reset(0.0, now)
            self._approach_m = self._gap_to_approach_m()
        start = self._start
        self._progress_m = (sample.x - start.x) * math.cos(start.yaw) + (sample.y - start.y) * math.sin(start.yaw)
        if self._progress_m >= self._distance_m and not self._in_passage():
            self.log_info(f"pushed {self._progress_m:.2f} m")
            return "done"
        if self.elapsed_s() - self._stood_s > self._timeout_s:
            return self._timed_out()
        if self._stall.stalled(self._progress_m, now):
            self.log_error(f"push stalled at {self._progress_m:.2f} m: less than {self._stall.min_progress:g} m "
                           f"in {self._stall.window_s:g} s (object too heavy)")
            return "failed"
        heading_error = wrap_angle(sample.yaw - start.yaw)
        w = max(-MAX_HEADING_RATE, min(MAX_HEADING_RATE, -HEADING_GAIN * heading_error))
        speed = self._approach.speed_mps if self._progress_m < self._approach_m else self._speed_mps
        self.send(speed, w)
        return None

    def _fresh_scan(self) -> Optional[LaserScan]:
        """The newest scan if it is at most scan_max_age_s old (None: none, or none subscribed)."""
        if self._scan is None:
            return None
        scan = self._scan.last()
        if scan is None or message_age_s(scan, self._scan, self.now_s()) > self._approach.scan_max_age_s:
            return None
        return scan

    def _in_passage(self) -> bool:
        """True while a push past distance_m goes on: within passage_extra_m more, with a fresh scan that shows the
        robot walled in (logged once per push when it starts)."""
        if self._passage_extra_m <= 0.0 or self._progress_m >= self._distance_m + self._passage_extra_m:
            return False
        scan = self._fresh_scan()
        if scan is None:
            return False
        inside = walled_in(scan, self._passage_side_m, self._passage_behind_m)
        if inside and not self._passage_logged:
            self._passage_logged = True
            self.log_info(f"push: {self._progress_m:.2f} m pushed and the robot is still in a passage: pushing on "
                          f"until a side opens, at most to {self._distance_m + self._passage_extra_m:.2f} m")
        return inside

    def _gap_to_approach_m(self) -> float:
        """[m] of the push to drive at approach_speed_mps: the gap to the face on a fresh scan less
        contact_slack_m; 0 without an approach speed, a fresh scan or anything ahead within distance_m."""
        approach = self._approach
        if not approach.enabled:
            return 0.0
        scan = self._fresh_scan()
        if scan is None:
            self.log_warn(f"push: no scan on {approach.scan_topic} newer than {approach.scan_max_age_s:g} s: "
                          f"no faster approach")
            return 0.0
        gap = gap_ahead_m(scan, approach.robot_radius_m, 0.0, self._distance_m)
        if gap is None:
            return 0.0
        approach_m = max(0.0, gap - approach.contact_slack_m)
        self.log_info(f"push: the object is {gap:.2f} m ahead: {approach_m:.2f} m at {approach.speed_mps:g} m/s, "
                      f"then {self._speed_mps:g} m/s")
        return approach_m

    def _timed_out(self) -> str:
        """``done`` when the push got ``enough_fraction`` of the distance (the object moves, only slower than
        planned: it is not heavy), else ``failed``; logged either way."""
        at = f"{self._progress_m:.2f} m of {self._distance_m:g} m"
        if self._progress_m >= self._enough_m:
            self.log_warn(f"push timed out after {self._timeout_s:.1f} s at {at}: the object moved, counted as pushed")
            return "done"
        self.log_error(f"push timed out after {self._timeout_s:.1f} s at {at}")
        return "failed"


@dataclass(frozen=True)
class _Approach:
    """PushState's checked approach parameters (see its docstring)."""

    owner: str
    speed_mps: float  # [m/s] 0: none
    push_speed_mps: float  # [m/s] the push's own speed (checked already)
    scan_topic: str
    robot_radius_m: float  # [m]
    contact_slack_m: float  # [m]
    scan_max_age_s: float  # [s]

    def __post_init__(self) -> None:
        owner, speed = self.owner, self.speed_mps
        validation.name(owner, "scan_topic", self.scan_topic, allow_empty=True)
        validation.number(owner, "approach_speed_mps", speed, minimum=0.0, unit="[m/s]")
        if speed > 0.0:
            SPEED_LIMITS.linear(owner, "approach_speed_mps", speed)
            if speed < self.push_speed_mps:
                raise ConfigError(f"{owner}: approach_speed_mps {speed:g} m/s must be 0 or at least speed_mps "
                                  f"{self.push_speed_mps:g} m/s")
            if not self.scan_topic:
                raise ConfigError(f"{owner}: approach_speed_mps {speed:g} m/s needs a scan_topic (the gap ahead)")
        validation.number(owner, "robot_radius_m", self.robot_radius_m, positive=True, unit="[m]")
        validation.number(owner, "contact_slack_m", self.contact_slack_m, minimum=0.0, unit="[m]")
        validation.number(owner, "scan_max_age_s", self.scan_max_age_s, positive=True, unit="[s]")

    @property
    def enabled(self) -> bool:
        """True with an approach speed (and so a scan topic)."""
        return self.speed_mps > 0.0
