"""``obstacle_classifier`` node: person / movable / clear in front of the robot, smoothed, and "safe to push".

``rosrun flex_nav obstacle_classifier`` in the robot's namespace (``ROS_NAMESPACE=robot1`` or a
``<group ns>``). Every received image (at most ``~max_rate`` per second) is classified
(:mod:`flex_nav.perception`); the majority of the last ``~window`` frames is published. In a lockstep simulation
(``/lockstep``, :mod:`flex_nav.ros.lockstep`) the rate runs on the images' stamps, and the simulator waits at the
next image to classify until its class is published.

Subscribes ``camera/rgb/image_raw`` (sensor_msgs/Image: rgb8, bgr8, rgba8, bgra8 or mono8) and, for a
model that takes depth (the shipped one does), ``camera/depth/image_raw`` (32FC1 [m] or 16UC1 [mm], REP
118, registered to the colour image: same field of view, any resolution); a colour frame is classified
with the depth frame whose stamp is at most ``~max_depth_lag`` away, and skipped if none comes.
Publishes ``obstacle_class`` (flex_nav/ObstacleClass) after every classified frame (and the same as an RViz text
on ``obstacle_class_marker``, :mod:`flex_nav.nodes.obstacle_class_marker`) and, with a scan
(``~scan_topic``, sensor_msgs/LaserScan, its frame taken as the robot's: x forward), ``obstacle_fusion``
(std_msgs/String): the camera's vote fused with the lidar's shape of the object ahead
(:mod:`flex_nav.perception.fusion`, no look taken yet), the decision and both cues on one line.
Serves ``safe_to_push`` (std_srvs/SetBool): ``success`` is True only when the smoothed label is
``movable``, fewer than ``~person_veto`` frames of the window saw a person and the latest classified
image is at most ``~max_image_age`` old; ``message`` says what the robot sees. ``data``: False = answer
from the current window (the thesis' behavior); True = a *fresh vote*: forget the window, wait for
``~window`` new frames (at most ``~fresh_vote_timeout`` [s] wall clock, else not safe), then answer
(use it after stopping in front of the obstacle, so frames taken while approaching do not count).
The answer (``success``) is the camera's alone, as before; ``message`` ends with the fused line.

Private parameters (a misspelt one, a bad value, a missing or broken model make the node exit with
status 2 and a message naming the parameter or field):
  ~model_type          str    classifier   classifier | yolo
  ~model               str    ''           ONNX file; '' = the shipped models/obstacle_classifier.onnx (classifier)
  ~metadata            str    ''           classifier metadata YAML; '' = beside the model
  ~class_map           dict   {}           model class name -> person | movable | ignore (classes named
                                           person/movable map to themselves; every other class is ignored)
  ~class_names         list   []           yolo: class names in model order; [] = the model's 'names' metadata
  ~roi                 list   []           [x_min, y_min, x_max, y_max] fractions; [] = the model's (classifier)
                                           or [0.2, 0.0, 0.8, 1.0] (yolo)
  ~conf_threshold      float  0.25         yolo: minimum detection score
  ~iou_threshold       float  0.45         yolo: class-wise NMS overlap
  ~min_roi_overlap     float  0.3          yolo: share of a box's area inside the roi for it to count
  ~yolo_layout         str    auto         auto | raw (1, 4+nc, N) | end2end (1, K, 6)
  ~input_size          list   []           yolo with a dynamic input size: [width, height] [px]
  ~window              int    5            frames in the majority vote
  ~max_rate            float  10.0         [Hz] classify at most this many images per second (0 = every image)
  ~person_veto         int    2            safe_to_push refuses with this many person frames in the window (0 = off)
  ~max_image_age       float  1.0          [s] safe_to_push refuses when the latest classified image is older
  ~fresh_vote_timeout  float  5.0          [s] wall-clock bound of a fresh vote (data = True)
  ~max_depth_lag       float  0.1          [s] RGB-D models: largest stamp difference of a colour and a depth frame
  ~scan_topic          str    scan         sensor_msgs/LaserScan of the lidar's cue ('' = none: lidar unsure)
  ~scan_max_age        float  0.5          [s] an older scan (by arrival) is no lidar cue
  ~scan_reach          float  1.2          [m] the object is the nearest scan hit this far ahead...
  ~scan_half_width     float  0.3          [m] ...and at most this far to either side
  ~camera_min_confidence float 0.7        fusion: a camera vote less confident than this is unsure
  ~lidar_min_confidence float  0.6        fusion: a lidar box less confident than this is unsure
  ~max_looks           int    2            fusion: looks again the rule allows (the node reports look 0)
"""

from __future__ import annotations

import threading
import time
from typing import Any, Dict, Optional, Tuple

import rospy
from sensor_msgs.msg import Image, LaserScan
from std_msgs.msg import String
from std_srvs.srv import SetBool, SetBoolResponse

from flex_nav.exceptions import ConfigError
from flex_nav.msg import ObstacleClass
from flex_nav.nodes.obstacle_class_marker import ClassMarkerPublisher
from flex_nav.perception.factory import PerceptionConfig, as_names, build
from flex_nav.perception.frame_pairing import FramePairing
from flex_nav.perception.fusion import MAX_LOOKS, CameraCue, FusedDecision, FusionParams, fuse
from flex_nav.perception.image import to_depth, to_rgb
from flex_nav.perception.labels import LABELS, Prediction
from flex_nav.perception.lidar_shape import UNSURE, ShapeCue, cue_ahead
from flex_nav.perception.push_decision import describe, safe_to_push
from flex_nav.perception.roi import Roi
from flex_nav.perception.smoothing import MAX_WINDOW, MajorityVote, Vote
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.params import param_float, param_int, param_str, reject_unknown

PARAMS = (
    "model_type", "model", "metadata", "class_map", "class_names", "roi", "conf_threshold", "iou_threshold",
    "min_roi_overlap", "yolo_layout", "input_size", "window", "max_rate", "person_veto", "max_image_age",
    "fresh_vote_timeout", "max_depth_lag", "scan_topic", "scan_max_age", "scan_reach", "scan_half_width",
    "camera_min_confidence", "lidar_min_confidence", "max_looks",
)
RATE_SLACK_S = 1e-6  # [s] an image this much early for the rate limit still counts (stamps are not exact sums)
IMAGE_BUFFER = 1 << 24  # [bytes] socket buffer: a whole 640x480 image fits, so the queue of one holds the newest


def _param_list(name: str) -> list:
    value = rospy.get_param(name, [])
    if not isinstance(value, list):
        raise ConfigError(f"parameter {rospy.resolve_name(name)} = {value!r} must be a list")
    return value


def _param_class_map(name: str) -> Dict[str, str]:
    value = rospy.get_param(name, {})
    if not isinstance(value, dict) or not all(isinstance(k, str) and isinstance(v, str) for k, v in value.items()):
        raise ConfigError(f"parameter {rospy.resolve_name(name)} = {value!r} must map class names to "
                          "person | movable | ignore")
    return dict(value)


def read_config() -> PerceptionConfig:
    """The perception configuration from the private parameters (ConfigError names the parameter)."""
    roi_values = _param_list("~roi")
    size = _param_list("~input_size")
    roi = Roi.from_sequence(roi_values, f"parameter {rospy.resolve_name('~roi')}") if roi_values else None
    if size and (len(size) != 2 or not all(isinstance(v, int) and not isinstance(v, bool) for v in size)):
        raise ConfigError(f"parameter {rospy.resolve_name('~input_size')} = {size!r} must be [width, height] [px]")
    return PerceptionConfig(
        model_type=param_str("~model_type", "classifier"),
        model=param_str("~model", ""),
        metadata=param_str("~metadata", ""),
        class_map=_param_class_map("~class_map"),
        class_names=as_names(_param_list("~class_names"), f"parameter {rospy.resolve_name('~class_names')}"),
        roi=roi,
        conf_threshold=param_float("~conf_threshold", 0.25, 0.0, 1.0),
        iou_threshold=param_float("~iou_threshold", 0.45, 0.0, 1.0),
        min_roi_overlap=param_float("~min_roi_overlap", 0.3, 0.0, 1.0),
        yolo_layout=param_str("~yolo_layout", "auto"),
        input_size=(int(size[0]), int(size[1])) if size else None,
    )


class ObstacleClassifierNode:
    """Classify, vote, publish, answer; the callbacks run on rospy's threads, the vote is guarded by a lock."""

    def __init__(self) -> None:
        reject_unknown("~", PARAMS)
        config = read_config()
        try:
            self.classifier = build(config)
        except ConfigError as err:
            model = config.model or "(the shipped classifier)"
            raise ConfigError(f"~model_type={config.model_type} ~model={model}: {err}") from err
        self.window = param_int("~window", 5, 1, MAX_WINDOW)
        self.max_rate = param_float("~max_rate", 10.0, 0.0)  # [Hz]
        self.person_veto = param_int("~person_veto", 2, 0, MAX_WINDOW)
        self.max_image_age = param_float("~max_image_age", 1.0, 0.0)  # [s]
        self.fresh_vote_timeout = param_float("~fresh_vote_timeout", 5.0, 0.0)  # [s] wall clock
        self.max_depth_lag = param_float("~max_depth_lag", 0.1, 0.0)  # [s]
        self._pairing: FramePairing[Image, Image] = FramePairing(self.max_depth_lag)
        self._cond = threading.Condition()
        self._vote = MajorityVote(self.window)
        self._last_frame: Optional[float] = None  # [s] ROS time the latest classified image arrived
        self._last_start: Optional[float] = None  # [s] ROS time the latest classification started (rate limit)
        self._first_colour: Optional[float] = None  # [s] ROS time the first colour image arrived
        self._fresh_frames = 0  # frames classified since the last reset
        self.publisher = rospy.Publisher("obstacle_class", ObstacleClass, queue_size=5)
        self.class_marker = ClassMarkerPublisher()  # the class as an RViz text marker
        self._read_fusion_params()
        self._scan: Optional[Tuple[float, LaserScan]] = None  # ([s] ROS time of arrival, the newest scan)
        self.fusion_publisher = rospy.Publisher("obstacle_fusion", String, queue_size=5)
        self.scan_subscriber = rospy.Subscriber(self.scan_topic, LaserScan, self._on_scan, queue_size=1,
                                                buff_size=1 << 20) if self.scan_topic else None
        self.service = rospy.Service("safe_to_push", SetBool, self._on_safe_to_push)
        self.subscriber = rospy.Subscriber(
            "camera/rgb/image_raw", Image, self._on_image, queue_size=1, buff_size=IMAGE_BUFFER
        )
        # lockstep: the simulation holds at the next image to classify until its class is out, and the rate limit
        # runs on the images' stamps (the ROS time an image arrives at depends on the wall time it took)
        self.lockstep = LockstepParticipant("classify")
        self.depth_subscriber: Optional[rospy.Subscriber] = None
        depth = ""
        if self.classifier.uses_depth:
            self.depth_subscriber = rospy.Subscriber(
                "camera/depth/image_raw", Image, self._on_depth, queue_size=1, buff_size=IMAGE_BUFFER
            )
            depth = f"; depth from {self.depth_subscriber.resolved_name} within {self.max_depth_lag:g} s"
        rospy.loginfo(f"{rospy.get_name()}: {self.classifier.description}; window {self.window}, "
                      f"at most {self.max_rate:g} Hz, person veto {self.person_veto}{depth}")

    # -- images -------------------------------------------------------------------------------------
    def _on_image(self, msg: Image) -> None:
        now = msg.header.stamp.to_sec() if self.lockstep.enabled else rospy.get_time()
        unpaired: Optional[Tuple[str, float, int]] = None  # (depth topic, [s] since the last classification, dropped)
        with self._cond:
            if self._last_start is not None and now < self._last_start:
                self._last_start = self._first_colour = None  # time went backwards (a simulation restarted)
                self._pairing.clear()
            if self.max_rate > 0.0 and self._last_start is not None and now < self._next_start_after(self._last_start):
                return
            self._last_start = now
            if self._first_colour is None:
                self._first_colour = now
            if self.depth_subscriber is None:
                pair: Optional[Tuple[float, Image, Optional[Image]]] = (0.0, msg, None)
            else:
                pair = self._pairing.add_colour(msg.header.stamp.to_sec(), msg)
                since = self._first_colour if self._last_frame is None else self._last_frame
                if pair is None and now - since > self.max_image_age:
                    unpaired = (self.depth_subscriber.resolved_name, now - since, self._pairing.dropped)
        if pair is not None:
            self._classify(pair[1], pair[2])
        elif unpaired is not None:
            self._warn_unpaired(*unpaired)

    def _warn_unpaired(self, topic: str, waited: float, dropped: int) -> None:
        """Colour images come, but none has found its depth image for longer than ``~max_image_age``."""
        rospy.logwarn_throttle(5.0, (
            f"{rospy.get_name()}: no colour image has had a depth image on {topic} within {self.max_depth_lag:g} s "
            f"of its stamp for {waited:.1f} s ({dropped} frame(s) found no partner): nothing is classified and "
            "safe_to_push refuses; check the depth topic's remapping and that both images share a clock"))

    def _on_depth(self, msg: Image) -> None:
        with self._cond:
            pair = self._pairing.add_depth(msg.header.stamp.to_sec(), msg)
        if pair is not None:
            self._classify(pair[1], pair[2])

    def _next_start_after(self, start_s: float) -> float:
        """[s] the stamp of the first image the rate limit lets through after one classified at ``start_s`` (no
        limit: any later image)."""
        return start_s + (1.0 / self.max_rate - RATE_SLACK_S if self.max_rate > 0.0 else RATE_SLACK_S)

    def _classify(self, colour: Image, depth_msg: Optional[Image]) -> None:
        try:
            self._classify_frame(colour, depth_msg)
        finally:  # lockstep: the next image that will be classified holds the simulation, whatever happened here
            with self._cond:
                next_s = self._next_start_after(self._last_start or 0.0)
            self.lockstep.hold_topic(self.subscriber.resolved_name, next_s)

    def _classify_frame(self, colour: Image, depth_msg: Optional[Image]) -> None:
        try:
            rgb = to_rgb(colour.data, colour.width, colour.height, colour.encoding, colour.step)
            depth = None if depth_msg is None else to_depth(
                depth_msg.data, depth_msg.width, depth_msg.height, depth_msg.encoding, depth_msg.step,
                bigendian=bool(depth_msg.is_bigendian))
        except ConfigError as err:
            rospy.logwarn_throttle(5.0, f"{rospy.get_name()}: frame skipped: {err}")
            return
        prediction = self.classifier.classify(rgb, depth)
        with self._cond:
            vote = self._vote.add(prediction)
            self._last_frame = rospy.get_time()
            self._fresh_frames += 1
            self._cond.notify_all()
        message = self._message(vote, prediction, colour)
        self.publisher.publish(message)
        scan = self._scan
        self.class_marker.publish(message, scan[1].header.frame_id if scan is not None else None)
        self.fusion_publisher.publish(String(data=self.fused(vote).line()))

    @staticmethod
    def _message(vote: Vote, prediction: Prediction, image: Image) -> ObstacleClass:
        out = ObstacleClass()
        out.header = image.header
        out.label = vote.label
        out.confidence = vote.confidence
        out.votes = vote.votes
        out.window = vote.window
        out.frame_label = prediction.label
        out.frame_confidence = prediction.confidence
        out.labels = list(LABELS)
        out.counts = bytes(vote.counts[label] for label in LABELS)  # uint8[] is bytes in genpy
        return out

    # -- lidar and fusion ---------------------------------------------------------------------------
    def _read_fusion_params(self) -> None:
        self.scan_topic = param_str("~scan_topic", "scan")
        self.scan_max_age = param_float("~scan_max_age", 0.5, 0.0)  # [s]
        self.scan_reach = param_float("~scan_reach", 1.2, 0.01)  # [m]
        self.scan_half_width = param_float("~scan_half_width", 0.3, 0.01)  # [m]
        self.fusion = FusionParams(camera_min_confidence=param_float("~camera_min_confidence", 0.7, 0.0, 1.0),
                                   lidar_min_confidence=param_float("~lidar_min_confidence", 0.6, 0.0, 1.0),
                                   max_looks=param_int("~max_looks", 2, 0, MAX_LOOKS))

    def _on_scan(self, msg: LaserScan) -> None:
        with self._cond:
            self._scan = (rospy.get_time(), msg)

    def lidar_cue(self) -> ShapeCue:
        """The lidar's cue of the object ahead in the newest scan (unsure without a fresh one)."""
        with self._cond:
            entry = self._scan
        if entry is None:
            why = f"no scan on {self.scan_subscriber.resolved_name} yet" if self.scan_subscriber else "~scan_topic ''"
            return ShapeCue(UNSURE, 0.0, why)
        age = rospy.get_time() - entry[0]
        if age > self.scan_max_age:
            return ShapeCue(UNSURE, 0.0, f"the newest scan is {age:.2f} s old (max {self.scan_max_age:g} s)")
        scan = entry[1]
        return cue_ahead(scan.ranges, scan.angle_min, scan.angle_increment, scan.range_min, scan.range_max,
                         reach_m=self.scan_reach, half_width_m=self.scan_half_width)

    def fused(self, vote: Vote) -> FusedDecision:
        """The camera's ``vote`` fused with the lidar's cue, before any look again."""
        return fuse(CameraCue.from_vote(vote), self.lidar_cue(), 0, self.fusion)

    # -- service ------------------------------------------------------------------------------------
    def _on_safe_to_push(self, request: Any) -> SetBoolResponse:
        safe, message = self.answer(fresh=bool(request.data))
        rospy.loginfo(f"{rospy.get_name()}: safe_to_push{' (fresh vote)' if request.data else ''} -> {message}")
        return SetBoolResponse(success=safe, message=message)

    def answer(self, fresh: bool) -> Tuple[bool, str]:
        with self._cond:
            if fresh:
                self._vote.reset()
                self._fresh_frames = 0
                deadline = time.monotonic() + self.fresh_vote_timeout
                while self._fresh_frames < self.window and not rospy.is_shutdown():
                    remaining = deadline - time.monotonic()
                    if remaining <= 0.0:
                        return False, (f"not safe: a fresh vote got {self._fresh_frames} of {self.window} frames in "
                                       f"{self.fresh_vote_timeout:g} s; {describe(self._vote.vote())}")
                    self._cond.wait(min(remaining, 0.1))
            vote = self._vote.vote()
            age = None if self._last_frame is None else max(0.0, rospy.get_time() - self._last_frame)
            unpaired = self._pairing.dropped
        safe, message = safe_to_push(vote, age, self.max_image_age, self.person_veto)
        if age is None and self.depth_subscriber is not None:
            message += (f" (this model needs a depth image on {self.depth_subscriber.resolved_name} within "
                        f"{self.max_depth_lag:g} s of each colour image; {unpaired} frame(s) found no partner)")
        return safe, f"{message}; {self.fused(vote).line()}"
