"""The simulator's lockstep barrier (pure): when holds block, how a replaced hold lets the stepping thread go on,
and the bounded wait that drops a hold nobody replaces."""

from __future__ import annotations

import math
import threading
import time
from typing import List

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav_sim.lockstep import CLOCK_TOPIC, Hold, LockstepBarrier

SCAN = "/robot1/scan"


class ManualWall:
    """A wall clock the test moves; each read advances it by ``step_s`` so a waiting loop makes progress."""

    def __init__(self, step_s: float = 0.0) -> None:
        self.now_s = 0.0
        self.step_s = step_s

    def __call__(self) -> float:
        self.now_s += self.step_s
        return self.now_s


def test_a_clock_hold_blocks_once_simulated_time_reaches_it() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update("/robot1/pure_pursuit_path/control", True, CLOCK_TOPIC, 2.0)
    barrier.published(CLOCK_TOPIC, 1.99)
    assert barrier.blocking() == []
    barrier.published(CLOCK_TOPIC, 2.0)
    assert barrier.blocking() == [Hold("/robot1/pure_pursuit_path/control", CLOCK_TOPIC, 2.0)]


def test_a_topic_hold_blocks_only_after_a_message_on_its_topic_stamped_at_or_after_it() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update("/robot1/localizer/scan", True, SCAN, 1.0)
    barrier.published(CLOCK_TOPIC, 5.0)  # time alone does not reach a topic hold
    barrier.published("/robot1/odom", 5.0)  # nor a message on another topic
    barrier.published(SCAN, 0.9)
    assert barrier.blocking() == []
    barrier.published(SCAN, 1.0)
    assert [h.participant for h in barrier.blocking()] == ["/robot1/localizer/scan"]
    barrier.published(SCAN, 0.5)  # an older stamp does not move the topic back
    assert len(barrier.blocking()) == 1


def test_a_new_hold_or_a_release_replaces_the_participants_old_one() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update("a", True, CLOCK_TOPIC, 1.0)
    barrier.update("b", True, CLOCK_TOPIC, 1.0)
    barrier.published(CLOCK_TOPIC, 1.0)
    assert {h.participant for h in barrier.blocking()} == {"a", "b"}
    barrier.update("a", True, CLOCK_TOPIC, 1.05)
    barrier.update("b", False, "", -math.inf)
    assert barrier.blocking() == []
    assert barrier.holds() == [Hold("a", CLOCK_TOPIC, 1.05)]


ACCEPT = "/robot1/get_path/accept"  # a client holds it when it sends a goal, the server lets go once the goal runs


def test_a_release_through_a_stamp_lets_go_only_of_holds_up_to_it() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update(ACCEPT, True, CLOCK_TOPIC, 3.0)  # a later goal's hold
    barrier.published(CLOCK_TOPIC, 3.0)
    barrier.update(ACCEPT, False, "", 2.5)  # the release of an earlier goal's run
    assert [h.stamp_s for h in barrier.blocking()] == [3.0]
    barrier.update(ACCEPT, False, "", 3.0)
    assert barrier.blocking() == []


def test_a_hold_overtaken_by_its_release_is_not_placed() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.published(CLOCK_TOPIC, 2.0)
    barrier.update(ACCEPT, False, "", 2.0)  # the server's release arrived first
    barrier.update(ACCEPT, True, CLOCK_TOPIC, 2.0)  # the client's hold, sent before the goal, arrives late
    assert barrier.blocking() == []
    assert barrier.holds() == []
    barrier.update(ACCEPT, True, CLOCK_TOPIC, 2.0 + 1e-6)  # the next goal's hold is placed
    assert barrier.holds() == [Hold(ACCEPT, CLOCK_TOPIC, 2.0 + 1e-6)]
    barrier.update(ACCEPT, False, "", 2.0 + 1e-6)
    barrier.update(ACCEPT, False, "", 1.0)  # an older release does not move the mark back
    barrier.update(ACCEPT, True, CLOCK_TOPIC, 2.0)
    assert barrier.holds() == []


def test_an_unstamped_release_lets_go_of_any_hold_and_marks_nothing() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update("a", True, CLOCK_TOPIC, 5.0)
    barrier.update("a", False, "", -math.inf)
    assert barrier.holds() == []
    barrier.update("a", True, CLOCK_TOPIC, 0.0)
    assert barrier.holds() == [Hold("a", CLOCK_TOPIC, 0.0)]


def test_wait_returns_when_the_blocking_hold_is_replaced_from_another_thread() -> None:
    barrier = LockstepBarrier(5.0)
    barrier.update("control", True, CLOCK_TOPIC, 1.0)
    barrier.published(CLOCK_TOPIC, 1.0)
    order: List[str] = []

    def participant() -> None:
        time.sleep(0.05)
        order.append("replaced")
        barrier.update("control", True, CLOCK_TOPIC, 1.05)

    thread = threading.Thread(target=participant)
    thread.start()
    dropped = barrier.wait()
    order.append("stepping on")
    thread.join(2.0)
    assert dropped == []
    assert order == ["replaced", "stepping on"]
    assert barrier.stats.waits == 1 and barrier.stats.dropped == 0
    assert barrier.stats.wait_s > 0.0


def test_a_hold_not_replaced_within_the_timeout_is_dropped_and_counted() -> None:
    wall = ManualWall(step_s=0.3)
    barrier = LockstepBarrier(1.0, wall_clock=wall)
    barrier.update("dead", True, CLOCK_TOPIC, 1.0)
    barrier.update("alive", True, CLOCK_TOPIC, 9.0)
    barrier.published(CLOCK_TOPIC, 1.0)
    dropped = barrier.wait()
    assert dropped == [Hold("dead", CLOCK_TOPIC, 1.0)]
    assert barrier.holds() == [Hold("alive", CLOCK_TOPIC, 9.0)]
    assert barrier.stats.dropped == 1
    assert wall.now_s >= 1.0  # it waited the timeout first
    barrier.update("dead", True, CLOCK_TOPIC, 1.0)  # its next hold counts again
    assert len(barrier.blocking()) == 1


def test_wait_without_a_blocking_hold_returns_at_once_and_counts_no_wait() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update("later", True, CLOCK_TOPIC, 3.0)
    barrier.published(CLOCK_TOPIC, 1.0)
    assert barrier.wait() == []
    assert barrier.stats.waits == 0


def test_wait_ends_when_asked_to_stop() -> None:
    barrier = LockstepBarrier(60.0)
    barrier.update("slow", True, CLOCK_TOPIC, 0.0)
    barrier.published(CLOCK_TOPIC, 0.0)
    started = time.monotonic()
    assert barrier.wait(stop=lambda: time.monotonic() - started > 0.1) == []
    assert barrier.blocking() != []  # nothing dropped: the simulation is stopping


@pytest.mark.parametrize("timeout_s", [0.0, -1.0, float("nan"), float("inf")])
def test_a_timeout_that_is_not_a_positive_number_is_refused(timeout_s: float) -> None:
    with pytest.raises(ConfigError, match="lockstep timeout"):
        LockstepBarrier(timeout_s)


def test_a_hold_without_a_participant_or_a_finite_stamp_is_refused() -> None:
    barrier = LockstepBarrier(1.0)
    with pytest.raises(ConfigError, match="name its participant"):
        barrier.update("", True, CLOCK_TOPIC, 1.0)
    with pytest.raises(ConfigError, match="not a finite time"):
        barrier.update("x", True, CLOCK_TOPIC, float("nan"))


CMD = "/robot1/cmd_vel_stamped"
CONTROL = "/robot1/pure_pursuit_path/control"


def test_a_sent_command_blocks_until_the_simulator_has_received_it() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.subscribed(CMD)
    barrier.update(CONTROL, True, "/robot1/odom", 2.0, sent_topic=CMD, sent_stamp_s=1.95)
    assert barrier.blocking() == [Hold(CONTROL, CMD, 1.95, sent=True)]  # its hold has not come, the command is due
    barrier.received(CMD, 1.9)  # an older command is not the one sent
    assert len(barrier.blocking()) == 1
    barrier.received(CMD, 1.95)
    assert barrier.blocking() == []


def test_a_command_received_before_the_hold_that_announces_it_is_not_waited_for() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.subscribed(CMD)
    barrier.received(CMD, 1.95)  # the command overtook the hold on its own connection
    barrier.update(CONTROL, False, "", -math.inf, sent_topic=CMD, sent_stamp_s=1.95)
    assert barrier.blocking() == []


def test_a_message_sent_where_the_simulator_does_not_listen_is_not_waited_for() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update(CONTROL, False, "", -math.inf, sent_topic="/robot1/remapped_cmd", sent_stamp_s=1.0)
    assert barrier.blocking() == []


def test_a_sent_command_that_never_arrives_is_dropped_after_the_timeout_and_the_hold_kept() -> None:
    wall = ManualWall(step_s=0.3)
    barrier = LockstepBarrier(1.0, wall_clock=wall)
    barrier.subscribed(CMD)
    barrier.update(CONTROL, True, "/robot1/odom", 2.0, sent_topic=CMD, sent_stamp_s=1.95)
    dropped = barrier.wait()
    assert dropped == [Hold(CONTROL, CMD, 1.95, sent=True)]
    assert "has not arrived" in dropped[0].describe()
    assert barrier.holds() == [Hold(CONTROL, "/robot1/odom", 2.0)]  # the participant's own hold stays
    assert barrier.blocking() == []


def test_wait_returns_when_the_sent_command_arrives_from_another_thread() -> None:
    barrier = LockstepBarrier(5.0)
    barrier.subscribed(CMD)
    barrier.update(CONTROL, False, "", -math.inf, sent_topic=CMD, sent_stamp_s=3.0)
    arrival = threading.Timer(0.05, barrier.received, (CMD, 3.0))
    arrival.start()
    started = time.monotonic()
    assert barrier.wait() == []
    arrival.join()
    assert 0.04 <= time.monotonic() - started < 4.0
    assert barrier.stats.waits == 1


PLAN = "/robot1/move_base_like/plan"
BEHAVIOR = "/robot1/behavior_runner/behavior"
PATHS = "/robot1/pure_pursuit_topic/paths"  # the controller's receiver of the plan topic


def test_a_plan_sent_to_a_node_that_receives_its_topic_blocks_until_the_node_reports_it() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update(BEHAVIOR, False, "", -math.inf, sent_topic=PLAN, sent_stamp_s=1.0)  # nobody receives it yet
    assert barrier.blocking() == []
    barrier.update(PATHS, False, "", -math.inf, received_topic=PLAN, received_stamp_s=-math.inf)
    barrier.update(BEHAVIOR, False, "", -math.inf, sent_topic=PLAN, sent_stamp_s=2.0)
    assert barrier.blocking() == [Hold(BEHAVIOR, PLAN, 2.0, sent=True)]
    barrier.update(PATHS, False, "", -math.inf, received_topic=PLAN, received_stamp_s=2.0)
    assert barrier.blocking() == []
    barrier.update(PATHS, False, "", -math.inf, received_topic=PLAN, received_stamp_s=3.0)  # overtook its announcement
    barrier.update(BEHAVIOR, False, "", -math.inf, sent_topic=PLAN, sent_stamp_s=3.0)
    assert barrier.blocking() == []


def test_a_node_that_stops_receiving_a_topic_lets_go_of_what_was_sent_there() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.update(PATHS, False, "", -math.inf, received_topic=PLAN, received_stamp_s=-math.inf)
    barrier.update(BEHAVIOR, False, "", -math.inf, sent_topic=PLAN, sent_stamp_s=2.0)
    assert len(barrier.blocking()) == 1
    barrier.update(PATHS, False, "", -math.inf, received_topic=PLAN, received_stamp_s=math.inf)
    assert barrier.blocking() == []
    barrier.update(BEHAVIOR, False, "", -math.inf, sent_topic=PLAN, sent_stamp_s=5.0)
    assert barrier.blocking() == []
    barrier.update(PATHS, False, "", -math.inf, received_topic=PLAN, received_stamp_s=-math.inf)  # again
    barrier.update(BEHAVIOR, False, "", -math.inf, sent_topic=PLAN, sent_stamp_s=6.0)
    assert barrier.blocking() == [Hold(BEHAVIOR, PLAN, 6.0, sent=True)]


def test_a_command_and_a_plan_sent_by_one_participant_are_both_waited_for() -> None:
    barrier = LockstepBarrier(1.0)
    barrier.subscribed(CMD)
    barrier.update(PATHS, False, "", -math.inf, received_topic=PLAN, received_stamp_s=-math.inf)
    barrier.update(BEHAVIOR, False, "", -math.inf, sent_topic=CMD, sent_stamp_s=2.0)
    barrier.update(BEHAVIOR, False, "", -math.inf, sent_topic=PLAN, sent_stamp_s=2.0)
    assert {h.topic for h in barrier.blocking()} == {CMD, PLAN}
    barrier.received(CMD, 2.0)
    assert barrier.blocking() == [Hold(BEHAVIOR, PLAN, 2.0, sent=True)]


def test_a_receipt_without_a_time_is_refused() -> None:
    with pytest.raises(ConfigError, match="received stamp"):
        LockstepBarrier(1.0).update(PATHS, False, "", -math.inf, received_topic=PLAN, received_stamp_s=math.nan)
