"""Pairing colour and depth frames that arrive on two topics, by their stamps.

An RGB-D classifier needs the depth image taken with each colour image. The two come as separate
messages in either order; :class:`FramePairing` keeps the newest unpaired one of each and hands out a
pair as soon as the two stamps are at most ``max_lag`` apart. Each frame is used once; a newer frame
replaces an older unpaired one of its kind, so a frame whose partner never comes is dropped, never
paired with a stale partner.
"""

from __future__ import annotations

import math
from typing import Generic, Optional, Tuple, TypeVar

from flex_nav.exceptions import ConfigError

C = TypeVar("C")
D = TypeVar("D")


class FramePairing(Generic[C, D]):
    """Newest-first pairing of colour frames (``C``) and depth frames (``D``) by stamp [s]; not thread-safe."""

    def __init__(self, max_lag: float) -> None:
        if not (math.isfinite(max_lag) and max_lag >= 0.0):
            raise ConfigError(f"max_lag {max_lag!r} must be a finite number of seconds >= 0")
        self.max_lag = max_lag  # [s]
        self._colour: Optional[Tuple[float, C]] = None
        self._depth: Optional[Tuple[float, D]] = None
        self.dropped = 0  # frames replaced before they found a partner

    def add_colour(self, stamp: float, frame: C) -> Optional[Tuple[float, C, D]]:
        """Add a colour frame; returns (colour stamp, colour, depth) if it completes a pair."""
        if self._colour is not None:
            self.dropped += 1
        self._colour = (stamp, frame)
        return self._pair()

    def add_depth(self, stamp: float, frame: D) -> Optional[Tuple[float, C, D]]:
        """Add a depth frame; returns (colour stamp, colour, depth) if it completes a pair."""
        if self._depth is not None:
            self.dropped += 1
        self._depth = (stamp, frame)
        return self._pair()

    def clear(self) -> None:
        """Forget the unpaired frames (e.g. after time went backwards)."""
        self._colour = self._depth = None

    def _pair(self) -> Optional[Tuple[float, C, D]]:
        if self._colour is None or self._depth is None:
            return None
        (t_colour, colour), (t_depth, depth) = self._colour, self._depth
        if abs(t_colour - t_depth) > self.max_lag:
            if t_depth < t_colour:  # the older one can no longer be paired: drop it
                self._depth = None
            else:
                self._colour = None
            self.dropped += 1
            return None
        self._colour = self._depth = None
        return t_colour, colour, depth
