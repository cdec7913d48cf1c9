"""Two cues, one decision: the camera's class and the lidar's shape of the blocking object, fused by a fixed rule.

The camera (:mod:`flex_nav.perception.classifier`, smoothed by :mod:`~flex_nav.perception.smoothing`) tells a
person, a movable object and clear (fixed furniture, walls, nothing) apart from colour and texture, from one
viewpoint; the lidar (:mod:`flex_nav.perception.lidar_shape`) sees the outline in its plane whatever the
colour: a box, a person (by default only something that moves), unsure, or nothing (``none``).

The camera is *unsure* when its vote is ``unknown``, its confidence is below ``camera_min_confidence`` or it
has fewer than ``camera_min_votes`` votes; a lidar ``box`` below ``lidar_min_confidence`` counts as ``unsure``.
A lidar ``person`` counts at any confidence, and so does a person in the camera's vote or in its latest frame.
Rule, first row that applies (``looks``: looks already taken, at most ``max_looks``; "look again" means: move a
little, e.g. turn a few degrees or back off, and decide on fresh cues):

| row | camera | lidar | looks | decision |
|---|---|---|---|---|
| 1 | person (vote or latest frame) | any | any | person |
| 2 | any | person | any | person |
| 3 | unsure | box, unsure, none | < max | look again (the camera is unsure) |
| 4 | clear | box | < max | look again (the cues disagree) |
| 5 | movable | none | < max | look again (the cues disagree: the lidar sees nothing there) |
| 6 | movable (sure, or unsure after the looks) | box, unsure, none | any | movable |
| 7 | unknown | box | = max | movable (a box-like shape and no person cue) |
| 8 | clear (sure, or unsure after the looks) | box, unsure, none | any | clear |
| 9 | unknown | unsure, none | = max | unknown |

So a person on either cue is a person; movable needs the camera's movable or, with the camera undecided
(``unknown``), a box-like lidar shape, with no person cue; a box the camera calls clear is looked at again, and
when the looks run out the camera's clear stands. That is ``box_beats_clear`` ``"never"`` (the default since
2026-11-29); with ``"unsure"`` row 7 also takes an unsure clear (below ``camera_min_confidence``) and with
``"always"`` (the rule before) any clear, row 8 the rest. The lidar box beat the camera's clear before: on the
classifier's validation scenes it turned box-shaped furniture, and a seated person's chair, cart or bench, into
movable; of 18 candidate rules and lidar cues (``tools/perception/evaluate_fused.py``, "Choosing a rule") this
one was chosen on the validation splits by a criterion stated before scoring (``models/README.md``).
:meth:`FusedDecision.line` puts the decision and both cues on one log line.

Pure, no ROS, no clock; the caller counts the looks.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, NamedTuple, Tuple

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON, UNKNOWN, VOTE_LABELS
from flex_nav.perception.lidar_shape import BOX, LIDAR_LABELS, ShapeCue
from flex_nav.perception.lidar_shape import NONE as LIDAR_NONE
from flex_nav.perception.lidar_shape import PERSON as LIDAR_PERSON
from flex_nav.perception.lidar_shape import UNSURE as LIDAR_UNSURE
from flex_nav.perception.smoothing import Vote

LOOK_AGAIN = "look_again"
DECISIONS: Tuple[str, ...] = (PERSON, MOVABLE, CLEAR, UNKNOWN, LOOK_AGAIN)
MAX_LOOKS = 10  # upper bound of max_looks: looking again is bounded
BOX_BEATS_CLEAR: Tuple[str, ...] = ("never", "unsure", "always")  # which camera clear a lidar box beats (row 7)


@dataclass(frozen=True)
class FusionParams:
    """Parameters of :func:`fuse`; see the module docstring."""

    camera_min_confidence: float = 0.7  # [0..1] a camera vote below this is unsure
    camera_min_votes: int = 0  # a camera vote with fewer votes is unsure (0: any majority)
    lidar_min_confidence: float = 0.6  # [0..1] a lidar box below this counts as unsure
    max_looks: int = 2  # looks again before deciding without them (0: never look again)
    box_beats_clear: str = "never"  # row 7: a lidar box beats no camera clear, an unsure one, or any

    def __post_init__(self) -> None:
        validation.number("fusion", "camera_min_confidence", self.camera_min_confidence, minimum=0.0, maximum=1.0)
        validation.number("fusion", "lidar_min_confidence", self.lidar_min_confidence, minimum=0.0, maximum=1.0)
        validation.integer("fusion", "camera_min_votes", self.camera_min_votes, minimum=0, maximum=255)
        validation.integer("fusion", "max_looks", self.max_looks, minimum=0, maximum=MAX_LOOKS)
        validation.choice("fusion", "box_beats_clear", self.box_beats_clear, BOX_BEATS_CLEAR)


@dataclass(frozen=True)
class CameraCue:
    """The camera's smoothed class: label (person, movable, clear, unknown), mean confidence [0..1], votes of a
    window, and the latest frame's own label and confidence."""

    label: str
    confidence: float
    votes: int = 0
    window: int = 0
    frame_label: str = UNKNOWN
    frame_confidence: float = 0.0

    def __post_init__(self) -> None:
        validation.choice("camera cue", "label", self.label, VOTE_LABELS)
        validation.choice("camera cue", "frame_label", self.frame_label, VOTE_LABELS)
        validation.number("camera cue", "confidence", self.confidence, minimum=0.0, maximum=1.0)

    @classmethod
    def from_vote(cls, vote: Vote) -> CameraCue:
        """The cue of a :class:`~flex_nav.perception.smoothing.Vote`."""
        latest = vote.latest
        return cls(vote.label, vote.confidence, vote.votes, vote.window,
                   latest.label if latest is not None else UNKNOWN, latest.confidence if latest is not None else 0.0)

    @property
    def sees_person(self) -> bool:
        """A person in the vote or in the latest frame."""
        return PERSON in (self.label, self.frame_label)

    def unsure(self, params: FusionParams) -> bool:
        """True if the vote is unknown, not confident enough, or has too few votes."""
        return (self.label == UNKNOWN or self.confidence < params.camera_min_confidence
                or self.votes < params.camera_min_votes)

    def describe(self) -> str:
        """``movable 0.93 (4/5 votes; latest movable 0.95)``."""
        return (f"{self.label} {self.confidence:.2f} ({self.votes}/{self.window} votes; latest {self.frame_label} "
                f"{self.frame_confidence:.2f})")


@dataclass(frozen=True)
class FusedDecision:
    """The decision (:data:`DECISIONS`), the rule row it came from and why, both cues, the looks taken."""

    label: str
    row: int
    reason: str
    camera: CameraCue
    camera_unsure: bool
    lidar: ShapeCue
    looks: int
    max_looks: int

    def line(self) -> str:
        """The decision and both cues on one line."""
        sure = " unsure" if self.camera_unsure else ""
        return (f"fused {self.label} (row {self.row}: {self.reason}; look {self.looks}/{self.max_looks}) | "
                f"camera{sure} {self.camera.describe()} | lidar {self.lidar.describe()}")


def lidar_label(lidar: ShapeCue, params: FusionParams) -> str:
    """The lidar's label as the rule reads it: a box below ``lidar_min_confidence`` is unsure."""
    if lidar.label not in LIDAR_LABELS:
        raise ConfigError(f"lidar cue label {lidar.label!r} is not one of {LIDAR_LABELS}")
    if lidar.label == BOX and lidar.confidence < params.lidar_min_confidence:
        return LIDAR_UNSURE
    return lidar.label


def fuse(camera: CameraCue, lidar: ShapeCue, looks: int, params: FusionParams = FusionParams()) -> FusedDecision:
    """The decision on the blocking object from both cues after ``looks`` looks again (see the module table)."""
    validation.integer("fusion", "looks", looks, minimum=0)
    unsure = camera.unsure(params)
    yields = camera.label == UNKNOWN or (camera.label == CLEAR and (
        params.box_beats_clear == "always" or (params.box_beats_clear == "unsure" and unsure)))
    case = _Case(camera.label, camera.sees_person, unsure, lidar_label(lidar, params), looks < params.max_looks,
                 yields)
    row, label, reason = 9, UNKNOWN, ""
    for number, applies, decision, why in _ROWS:
        if applies(case):
            row, label, reason = number, decision, why
            break
    return FusedDecision(label, row, reason, camera, case.unsure, lidar, looks, params.max_looks)


class _Case(NamedTuple):
    """What the rule reads: the camera's label, a person in its vote or frame, unsure, the lidar's label (after
    its confidence), looks left, whether the camera's label gives way to a lidar box (``box_beats_clear``)."""

    camera: str
    camera_person: bool
    unsure: bool
    lidar: str
    more: bool
    yields_to_box: bool  # the camera's label gives way to a lidar box (row 7)


# The module table: (row, applies, decision, reason), first row that applies; the last always does.
_ROWS: Tuple[Tuple[int, Callable[[_Case], bool], str, str], ...] = (
    (1, lambda c: c.camera_person, PERSON, "the camera sees a person"),
    (2, lambda c: c.lidar == LIDAR_PERSON, PERSON, "the lidar sees a person"),
    (3, lambda c: c.more and c.unsure, LOOK_AGAIN, "the camera is unsure"),
    (4, lambda c: c.more and c.camera == CLEAR and c.lidar == BOX, LOOK_AGAIN,
     "the camera sees clear, the lidar a box"),
    (5, lambda c: c.more and c.camera == MOVABLE and c.lidar == LIDAR_NONE, LOOK_AGAIN,
     "the camera sees a movable object, the lidar nothing there"),
    (6, lambda c: c.camera == MOVABLE, MOVABLE, "the camera sees a movable object, no person cue"),
    (7, lambda c: c.lidar == BOX and c.yields_to_box, MOVABLE, "the lidar sees a box, no person cue"),
    (8, lambda c: c.camera == CLEAR, CLEAR, "the camera sees clear, no person cue"),
    (9, lambda c: True, UNKNOWN, "neither cue decides"),
)
