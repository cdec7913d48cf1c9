"""The "safe to push" answer from a temporal vote, as the thesis' service gave it to its behavior tree.

Safe only when all of these hold, else not safe with the first reason that failed:
an image was classified recently (``max_image_age`` [s]); the majority label of the window is
``movable``; fewer than ``person_veto`` frames of the window saw a person (0 disables the veto).
The message always says what the robot sees (label, votes, confidence, latest frame).
"""

from __future__ import annotations

from typing import Optional, Tuple

from flex_nav.perception.labels import MOVABLE
from flex_nav.perception.smoothing import Vote


def describe(vote: Vote) -> str:
    """``movable 4/5 votes (confidence 0.93); latest frame movable 0.95; counts person 0, movable 4, clear 1``."""
    head = (f"{vote.label} {vote.votes}/{vote.window} votes (confidence {vote.confidence:.2f})"
            if vote.votes else f"unknown: no label has more than {vote.window // 2} of {vote.window} votes")
    latest = (f"latest frame {vote.latest.label} {vote.latest.confidence:.2f}" if vote.latest is not None
              else "no frame yet")
    counts = ", ".join(f"{label} {n}" for label, n in vote.counts.items())
    return f"{head}; {latest}; counts {counts}"


def safe_to_push(vote: Vote, image_age: Optional[float], max_image_age: float, person_veto: int) -> Tuple[bool, str]:
    """(safe, message) for a vote; ``image_age`` [s] since the latest classified image, None if there was none."""
    if image_age is None:
        return False, "not safe: no camera image classified yet"
    if image_age > max_image_age:
        return False, f"not safe: the latest classified image is {image_age:.2f} s old (max {max_image_age:.2f} s)"
    seen = describe(vote)
    if person_veto > 0 and vote.person_votes >= person_veto:
        return False, f"not safe: {vote.person_votes} frame(s) saw a person (veto at {person_veto}); {seen}"
    if vote.label != MOVABLE:
        return False, f"not safe: {seen}"
    return True, f"safe: {seen}"
