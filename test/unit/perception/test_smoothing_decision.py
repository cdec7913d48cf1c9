"""The majority of the last N frames and the safe-to-push answer built on it."""

from __future__ import annotations

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON, UNKNOWN, Prediction
from flex_nav.perception.push_decision import safe_to_push
from flex_nav.perception.smoothing import MajorityVote


def _p(label: str, confidence: float = 0.9) -> Prediction:
    return Prediction(label, confidence)


def test_a_label_needs_more_than_half_of_the_window() -> None:
    vote = MajorityVote(5)
    assert vote.add(_p(MOVABLE)).label == UNKNOWN
    assert vote.add(_p(MOVABLE)).label == UNKNOWN  # 2 of 5 is not a majority of the window
    result = vote.add(_p(MOVABLE))
    assert (result.label, result.votes, result.window, result.frames) == (MOVABLE, 3, 5, 3)


def test_one_odd_frame_does_not_flip_the_answer_and_the_window_slides() -> None:
    vote = MajorityVote(5)
    for label in (PERSON, PERSON, PERSON, MOVABLE, PERSON):
        result = vote.add(_p(label))
    assert (result.label, result.votes) == (PERSON, 4)
    assert result.latest is not None and result.latest.label == PERSON
    for _ in range(3):
        result = vote.add(_p(MOVABLE))  # window now: movable, person, movable, movable, movable
    assert result.counts == {PERSON: 1, MOVABLE: 4, CLEAR: 0}
    assert (result.label, result.frames) == (MOVABLE, 5)


def test_a_split_vote_is_unknown() -> None:
    vote = MajorityVote(5)
    for label in (PERSON, PERSON, MOVABLE, MOVABLE, CLEAR):
        result = vote.add(_p(label))
    assert result.label == UNKNOWN and result.votes == 0 and result.confidence == 0.0
    assert result.person_votes == 2


def test_confidence_is_the_mean_of_the_winning_frames() -> None:
    vote = MajorityVote(3)
    vote.add(_p(CLEAR, 0.6))
    vote.add(_p(MOVABLE, 0.2))
    result = vote.add(_p(CLEAR, 0.8))
    assert result.label == CLEAR and result.confidence == pytest.approx(0.7)


def test_reset_forgets_every_frame() -> None:
    vote = MajorityVote(3)
    for _ in range(3):
        vote.add(_p(MOVABLE))
    vote.reset()
    result = vote.vote()
    assert result.label == UNKNOWN and result.frames == 0 and result.latest is None


@pytest.mark.parametrize("window", [0, -1, 256, 2.5, True])
def test_bad_window_is_rejected(window: object) -> None:
    with pytest.raises(ConfigError, match="smoothing window"):
        MajorityVote(window)  # type: ignore[arg-type]


def test_bad_frame_label_is_rejected() -> None:
    with pytest.raises(ValueError, match="unknown"):
        MajorityVote().add(_p(UNKNOWN))


def _vote(*labels: str):
    vote = MajorityVote(5)
    for label in labels:
        result = vote.add(_p(label))
    return result


def test_safe_only_for_a_fresh_movable_majority() -> None:
    safe, message = safe_to_push(_vote(MOVABLE, MOVABLE, MOVABLE, MOVABLE, CLEAR), 0.1, 1.0, 2)
    assert safe
    assert message.startswith("safe: movable 4/5 votes")


def test_person_majority_is_not_safe_and_says_so() -> None:
    safe, message = safe_to_push(_vote(PERSON, PERSON, PERSON), 0.1, 1.0, 0)
    assert not safe
    assert "person 3/5 votes" in message


def test_person_veto_refuses_a_movable_majority() -> None:
    vote = _vote(PERSON, MOVABLE, PERSON, MOVABLE, MOVABLE)
    assert vote.label == MOVABLE
    safe, message = safe_to_push(vote, 0.1, 1.0, 2)
    assert not safe and "2 frame(s) saw a person (veto at 2)" in message
    assert safe_to_push(vote, 0.1, 1.0, 0)[0], "person_veto 0 disables the veto"
    assert safe_to_push(vote, 0.1, 1.0, 3)[0]


def test_stale_or_missing_images_are_not_safe() -> None:
    vote = _vote(MOVABLE, MOVABLE, MOVABLE)
    safe, message = safe_to_push(vote, 1.5, 1.0, 2)
    assert not safe and "1.50 s old (max 1.00 s)" in message
    safe, message = safe_to_push(vote, None, 1.0, 2)
    assert not safe and "no camera image" in message


def test_unknown_and_clear_are_not_safe() -> None:
    assert not safe_to_push(_vote(MOVABLE, MOVABLE), 0.0, 1.0, 2)[0]
    safe, message = safe_to_push(_vote(CLEAR, CLEAR, CLEAR), 0.0, 1.0, 2)
    assert not safe and "clear 3/5" in message
