"""The fusion rule of the camera's class and the lidar's shape: every row of the table, bounded looks, the log line,
the parameters (no ROS)."""

from __future__ import annotations

import re
from typing import List, Optional

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.perception import fusion
from flex_nav.perception.fusion import LOOK_AGAIN, CameraCue, FusionParams, fuse, lidar_label
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON, UNKNOWN, Prediction
from flex_nav.perception.lidar_shape import BOX, NONE, UNSURE, ShapeCue
from flex_nav.perception.lidar_shape import PERSON as LIDAR_PERSON
from flex_nav.perception.smoothing import MajorityVote

PARAMS = FusionParams(camera_min_confidence=0.7, lidar_min_confidence=0.6, max_looks=2)


def camera(label: str, confidence: float = 0.9, frame: Optional[str] = None) -> CameraCue:
    return CameraCue(label, confidence, 4, 5, frame if frame is not None else (label if label != UNKNOWN else CLEAR),
                     confidence)


def lidar(label: str, confidence: float = 0.9) -> ShapeCue:
    return ShapeCue(label, confidence, "test")


# (row, camera, lidar, looks taken, decision): every row of the module's table, with looks left and without
ROWS = [
    (1, camera(PERSON), lidar(BOX), 0, PERSON),
    (1, camera(PERSON, 0.4), lidar(NONE), 2, PERSON),  # an unsure person is still a person
    (1, camera(MOVABLE, frame=PERSON), lidar(BOX), 0, PERSON),  # the latest frame alone
    (2, camera(MOVABLE), lidar(LIDAR_PERSON), 0, PERSON),
    (2, camera(CLEAR), lidar(LIDAR_PERSON, 0.3), 2, PERSON),  # a lidar person counts at any confidence
    (2, camera(UNKNOWN, 0.0), lidar(LIDAR_PERSON), 0, PERSON),
    (3, camera(UNKNOWN, 0.0), lidar(BOX), 0, LOOK_AGAIN),
    (3, camera(CLEAR, 0.55), lidar(UNSURE), 1, LOOK_AGAIN),  # the 0.4 m cube head-on: near 50/50
    (3, camera(CLEAR, 0.55), lidar(BOX), 1, LOOK_AGAIN),  # unsure and disagreeing: row 3 first
    (3, camera(MOVABLE, 0.6), lidar(BOX), 0, LOOK_AGAIN),
    (4, camera(CLEAR), lidar(BOX), 0, LOOK_AGAIN),
    (4, camera(CLEAR), lidar(BOX), 1, LOOK_AGAIN),
    (5, camera(MOVABLE), lidar(NONE), 0, LOOK_AGAIN),
    (6, camera(MOVABLE), lidar(BOX), 0, MOVABLE),
    (6, camera(MOVABLE), lidar(UNSURE), 0, MOVABLE),
    (6, camera(MOVABLE), lidar(NONE), 2, MOVABLE),  # below the scan plane: the camera's word after the looks
    (6, camera(MOVABLE, 0.6), lidar(UNSURE), 2, MOVABLE),
    (7, camera(UNKNOWN, 0.0), lidar(BOX), 2, MOVABLE),  # the camera undecided after the looks: the box shape
    (8, camera(CLEAR), lidar(BOX), 2, CLEAR),  # the looks ran out: the camera's clear stands against a box
    (8, camera(CLEAR, 0.55), lidar(BOX), 2, CLEAR),  # an unsure clear too
    (8, camera(CLEAR), lidar(UNSURE), 0, CLEAR),
    (8, camera(CLEAR), lidar(NONE), 0, CLEAR),
    (8, camera(CLEAR, 0.5), lidar(NONE), 2, CLEAR),
    (8, camera(CLEAR), lidar(BOX, 0.5), 0, CLEAR),  # a box below lidar_min_confidence is unsure
    (9, camera(UNKNOWN, 0.0), lidar(UNSURE), 2, UNKNOWN),
    (9, camera(UNKNOWN, 0.0), lidar(NONE), 2, UNKNOWN),
]


@pytest.mark.parametrize(("row", "cam", "lid", "looks", "expected"), ROWS)
def test_every_row_of_the_rule(row: int, cam: CameraCue, lid: ShapeCue, looks: int, expected: str) -> None:
    decision = fuse(cam, lid, looks, PARAMS)
    assert (decision.label, decision.row) == (expected, row), decision.line()


def test_every_row_is_covered() -> None:
    assert sorted({row for row, *_ in ROWS}) == list(range(1, 10))


def docstring_table() -> List[List[str]]:
    """The rows of the module docstring's rule table, cells stripped."""
    lines = [line for line in (fusion.__doc__ or "").splitlines() if re.match(r"^\| \d+ \|", line)]
    return [[cell.strip() for cell in line.strip("|").split("|")] for line in lines]


def test_the_docstring_table_is_the_rule() -> None:
    """Its rows are numbered 1-9, and each row's decision and looks column are the ones the rule gives there."""
    table = docstring_table()
    assert [int(cells[0]) for cells in table] == list(range(1, 10))
    decided = {row: (expected, looks) for row, _, _, looks, expected in ROWS}
    for number, _camera, _lidar, looks, decision in table:
        label, taken = decided[int(number)]
        assert decision.split(" (")[0].replace(" ", "_") == label, (number, decision)
        assert looks == "any" or (looks == "< max") == (taken < PARAMS.max_looks), (number, looks)
    assert table[6][1] == "unknown"  # row 7: a box beats only an undecided camera (box_beats_clear "never")


@pytest.mark.parametrize(("mode", "sure_clear", "unsure_clear"), [
    ("never", (CLEAR, 8), (CLEAR, 8)),
    ("unsure", (CLEAR, 8), (MOVABLE, 7)),
    ("always", (MOVABLE, 7), (MOVABLE, 7)),
])
def test_which_clear_a_box_beats_after_the_looks(mode: str, sure_clear: tuple, unsure_clear: tuple) -> None:
    params = FusionParams(box_beats_clear=mode)
    for cam, expected in ((camera(CLEAR, 0.9), sure_clear), (camera(CLEAR, 0.55), unsure_clear)):
        decision = fuse(cam, lidar(BOX), params.max_looks, params)
        assert (decision.label, decision.row) == expected, (mode, decision.line())
        assert fuse(cam, lidar(BOX), 0, params).label == LOOK_AGAIN  # the looks are asked for in every mode
        assert fuse(cam, lidar(UNSURE), params.max_looks, params).label == CLEAR  # no box: clear in every mode
    assert fuse(camera(UNKNOWN, 0.0), lidar(BOX), params.max_looks, params).row == 7  # undecided: the box
    assert fuse(camera(CLEAR), lidar(LIDAR_PERSON), params.max_looks, params).label == PERSON


def test_the_default_lets_no_clear_give_way_to_a_box() -> None:
    assert FusionParams().box_beats_clear == "never"


def test_looks_are_bounded_whatever_the_cues() -> None:
    for cam in (camera(UNKNOWN, 0.0), camera(CLEAR), camera(MOVABLE), camera(CLEAR, 0.3)):
        for lid in (lidar(BOX), lidar(NONE), lidar(UNSURE)):
            looks = 0
            while fuse(cam, lid, looks, PARAMS).label == LOOK_AGAIN:
                looks += 1
                assert looks <= PARAMS.max_looks
            assert fuse(cam, lid, looks, PARAMS).label != LOOK_AGAIN


def test_no_looks_allowed_decides_at_once() -> None:
    params = FusionParams(max_looks=0)
    assert fuse(camera(CLEAR), lidar(BOX), 0, params).label == CLEAR
    assert fuse(camera(UNKNOWN, 0.0), lidar(BOX), 0, params).label == MOVABLE
    assert fuse(camera(UNKNOWN, 0.0), lidar(UNSURE), 0, params).label == UNKNOWN


def test_the_log_line_holds_the_decision_and_both_cues() -> None:
    cue = ShapeCue(BOX, 0.9, "corner of 88 deg within the noise")
    line = fuse(camera(CLEAR, 0.55), cue, 1, PARAMS).line()
    assert "\n" not in line
    assert line.startswith("fused look_again (row 3: the camera is unsure; look 1/2)")
    assert "camera unsure clear 0.55 (4/5 votes; latest clear 0.55)" in line
    assert "lidar box 0.90 (corner of 88 deg within the noise)" in line


def test_a_camera_cue_from_the_vote() -> None:
    vote = MajorityVote(5)
    for label in (MOVABLE, MOVABLE, CLEAR, MOVABLE):
        vote.add(Prediction(label, 0.8))
    cue = CameraCue.from_vote(vote.add(Prediction(PERSON, 0.6)))
    assert (cue.label, cue.votes, cue.window, cue.frame_label) == (MOVABLE, 3, 5, PERSON)
    assert fuse(cue, lidar(BOX), 0, PARAMS).label == PERSON  # the latest frame saw a person
    empty = CameraCue.from_vote(MajorityVote(5).vote())
    assert (empty.label, empty.frame_label) == (UNKNOWN, UNKNOWN)


def test_min_votes_makes_a_thin_majority_unsure() -> None:
    params = FusionParams(camera_min_votes=4)
    thin = CameraCue(MOVABLE, 0.9, 3, 5, MOVABLE, 0.9)
    assert fuse(thin, lidar(UNSURE), 0, params).label == LOOK_AGAIN
    assert fuse(CameraCue(MOVABLE, 0.9, 4, 5, MOVABLE, 0.9), lidar(UNSURE), 0, params).label == MOVABLE


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"camera_min_confidence": 1.5}, "camera_min_confidence"),
    ({"lidar_min_confidence": -0.1}, "lidar_min_confidence"),
    ({"max_looks": -1}, "max_looks"),
    ({"max_looks": 11}, "max_looks"),
    ({"camera_min_votes": 1.5}, "camera_min_votes"),
    ({"box_beats_clear": "sometimes"}, "box_beats_clear"),
    ({"box_beats_clear": True}, "box_beats_clear"),
])
def test_parameters_are_validated(kwargs: dict, match: str) -> None:
    with pytest.raises(ConfigError, match=match):
        FusionParams(**kwargs)


def test_bad_cues_and_looks_are_refused() -> None:
    with pytest.raises(ConfigError, match="label"):
        CameraCue("chair", 0.5)
    with pytest.raises(ConfigError, match="confidence"):
        CameraCue(CLEAR, 1.5)
    with pytest.raises(ConfigError, match="lidar cue label"):
        lidar_label(ShapeCue("chair", 0.5, "x"), PARAMS)
    with pytest.raises(ConfigError, match="looks"):
        fuse(camera(CLEAR), lidar(BOX), -1, PARAMS)
