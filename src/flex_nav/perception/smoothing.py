"""Temporal smoothing of per-frame labels: the majority of the last N frames (the thesis used N = 5).

A label wins when more than half of the *window* (not of the frames seen so far) voted for it, so
with N = 5 it needs 3 votes; until then, or when the votes split, the result is ``unknown``. One
misclassified frame therefore never flips the answer, and a fresh vote (after :meth:`reset`) needs
at least ``N // 2 + 1`` new frames.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import Deque, Dict, Optional

from flex_nav.exceptions import ConfigError
from flex_nav.perception.labels import LABELS, PERSON, UNKNOWN, Prediction

MAX_WINDOW = 255  # frames (the message field is a uint8)


@dataclass(frozen=True)
class Vote:
    """The smoothed label over the window and how it came about."""

    label: str  # one of VOTE_LABELS
    votes: int  # frames in the window that voted for ``label`` (0 for unknown)
    window: int  # window size N
    frames: int  # frames currently in the window (<= N)
    confidence: float  # mean frame confidence of the frames that voted for ``label`` (0 for unknown)
    counts: Dict[str, int]  # votes per label of LABELS
    latest: Optional[Prediction]  # the newest frame's prediction

    @property
    def person_votes(self) -> int:
        return self.counts.get(PERSON, 0)


class MajorityVote:
    """The last ``window`` frame predictions and their majority (not thread-safe: the caller locks)."""

    def __init__(self, window: int = 5) -> None:
        if isinstance(window, bool) or not isinstance(window, int) or not 1 <= window <= MAX_WINDOW:
            raise ConfigError(f"smoothing window {window!r} must be an integer in [1, {MAX_WINDOW}] frames")
        self.window = window
        self._frames: Deque[Prediction] = deque(maxlen=window)

    def add(self, prediction: Prediction) -> Vote:
        """Add the newest frame (the oldest leaves a full window) and return the vote."""
        if prediction.label not in LABELS:
            raise ValueError(f"frame label {prediction.label!r} is not one of {LABELS}")
        self._frames.append(prediction)
        return self.vote()

    def reset(self) -> None:
        """Forget every frame (the next vote starts from scratch)."""
        self._frames.clear()

    def vote(self) -> Vote:
        counts = {label: 0 for label in LABELS}
        for frame in self._frames:
            counts[frame.label] += 1
        latest = self._frames[-1] if self._frames else None
        best = max(LABELS, key=lambda label: counts[label])
        if counts[best] * 2 <= self.window:
            return Vote(UNKNOWN, 0, self.window, len(self._frames), 0.0, counts, latest)
        confidence = sum(f.confidence for f in self._frames if f.label == best) / counts[best]
        return Vote(best, counts[best], self.window, len(self._frames), confidence, counts, latest)
