"""FramePairing: colour and depth frames paired by stamp, in either order, each used once, never stale."""

from __future__ import annotations

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.perception.frame_pairing import FramePairing


def test_pairs_in_either_order_within_the_lag() -> None:
    pairing: FramePairing[str, str] = FramePairing(max_lag=0.05)
    assert pairing.add_colour(1.00, "c1") is None
    assert pairing.add_depth(1.03, "d1") == (1.00, "c1", "d1")
    assert pairing.add_depth(2.00, "d2") is None
    assert pairing.add_colour(2.00, "c2") == (2.00, "c2", "d2")
    assert pairing.dropped == 0


def test_each_frame_is_used_once() -> None:
    pairing: FramePairing[str, str] = FramePairing(max_lag=0.1)
    assert pairing.add_colour(1.0, "c1") is None
    assert pairing.add_depth(1.0, "d1") == (1.0, "c1", "d1")
    assert pairing.add_colour(1.05, "c2") is None  # d1 is spent: no pair with it again


def test_a_stale_partner_is_dropped_not_paired() -> None:
    pairing: FramePairing[str, str] = FramePairing(max_lag=0.1)
    assert pairing.add_depth(1.0, "d1") is None
    assert pairing.add_colour(1.2, "c2") is None  # 0.2 s apart: d1 can never pair now
    assert pairing.dropped == 1
    assert pairing.add_depth(1.21, "d2") == (1.2, "c2", "d2")
    assert pairing.add_colour(3.0, "c3") is None
    assert pairing.add_colour(3.2, "c4") is None  # c3 replaced by a newer colour frame before its depth came
    assert pairing.dropped == 2
    assert pairing.add_depth(3.0, "d3") is None  # c3's depth, too late: older than c4 by more than the lag
    assert pairing.add_depth(3.2, "d4") == (3.2, "c4", "d4")


def test_clear_forgets_unpaired_frames_and_bad_lag_is_named() -> None:
    pairing: FramePairing[str, str] = FramePairing(max_lag=0.0)
    assert pairing.add_colour(5.0, "c") is None
    pairing.clear()
    assert pairing.add_depth(5.0, "d") is None
    assert pairing.add_colour(5.0, "c") == (5.0, "c", "d")  # exactly equal stamps pair at max_lag 0
    with pytest.raises(ConfigError, match="max_lag -1 must be a finite number of seconds >= 0"):
        FramePairing(-1)
    with pytest.raises(ConfigError, match="max_lag nan"):
        FramePairing(float("nan"))
