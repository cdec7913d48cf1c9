"""TopicPath's rule for the tick at which a controller takes a new Path (lockstep: never at the step it was sent)."""

from __future__ import annotations

import genpy

from flex_nav.ros.topic_path import takes_path


def test_a_new_path_is_taken_at_once_without_lockstep() -> None:
    assert takes_path(count=2, used=1, arrived_s=20.2, stamp_s=20.2, tick_s=20.2, defer_same_step=False)
    assert not takes_path(count=1, used=1, arrived_s=20.0, stamp_s=20.0, tick_s=20.2, defer_same_step=False)


def test_lockstep_defers_a_path_sent_at_the_ticks_step_whatever_the_clock_showed_at_its_arrival() -> None:
    # a plan the behavior published at its tick at 20.2 s, stamped then; this node's clock still showed the step
    # before (20.1917 s) when it came in: the stamp says it is the tick's own step, taken at the next tick
    assert not takes_path(count=2, used=1, arrived_s=20.1917, stamp_s=20.2, tick_s=20.2, defer_same_step=True)
    assert takes_path(count=2, used=1, arrived_s=20.1917, stamp_s=20.2, tick_s=20.25, defer_same_step=True)


def test_lockstep_defers_a_path_that_arrived_at_the_ticks_step_whatever_its_stamp() -> None:
    # stamped long before (a server's plan) but in at the tick's step: it may have come before or after the tick
    assert not takes_path(count=2, used=1, arrived_s=20.2, stamp_s=19.0, tick_s=20.2, defer_same_step=True)
    assert takes_path(count=2, used=1, arrived_s=20.15, stamp_s=19.0, tick_s=20.2, defer_same_step=True)


def test_a_stamp_truncated_by_genpy_counts_as_the_tick_it_was_made_at() -> None:
    stamp_s = genpy.Time.from_sec(20.2).to_sec()  # 20.199999999 s
    assert not takes_path(count=2, used=1, arrived_s=20.1917, stamp_s=stamp_s, tick_s=20.2, defer_same_step=True)
