"""SmachStateAdapter: SMACH states inside a flex_nav behavior (worker thread per activation, preempt on exit)."""

from __future__ import annotations

import threading

import pytest

from flex_nav.behavior import BehaviorExecutor, BehaviorStatus, StateMachine
from flex_nav.compat import smach
from flex_nav.compat.smach_adapter import SmachStateAdapter
from flex_nav.exceptions import ConfigError

WAIT_S = 10.0  # [s] bound of every wait (run timeouts too); never reached when the code is right
FAST_HZ = 200.0  # [Hz] adapter polling rate in these tests


class Double(smach.State):
    def __init__(self):
        super().__init__(outcomes=["doubled", "failed"], input_keys=["value"], output_keys=["result"])
        self.threads = []

    def execute(self, ud):
        self.threads.append(threading.get_ident())
        ud.result = 2 * ud.value
        return "doubled"


class Blocking(smach.State):
    def __init__(self, obey=True):
        super().__init__(outcomes=["done", "preempted"], output_keys=["partial"])
        self.started = threading.Event()
        self.release = threading.Event()
        self.obey = obey

    def execute(self, ud):
        self.started.set()
        poll = threading.Event()
        for _ in range(int(WAIT_S / 0.005)):
            if self.release.is_set():
                break
            if self.obey and self.preempt_requested():
                self.service_preempt()
                ud.partial = "written while preempted"
                return "preempted"
            poll.wait(0.005)
        return "done"


def behavior(adapter, input_keys=("value",), output_keys=("result",)):
    sm = StateMachine(outcomes=["finished", "failed"], input_keys=list(input_keys), output_keys=list(output_keys))
    outcomes = adapter.outcomes
    sm.add("Legacy", adapter, transitions={o: ("finished" if o in ("doubled", "done") else "failed") for o in outcomes})
    return sm


def test_outputs_written_back_and_outcome_routed():
    legacy = Double()
    ex = BehaviorExecutor(behavior(SmachStateAdapter(legacy, rate_hz=FAST_HZ)), inputs={"value": 21})
    result = ex.run(timeout_s=WAIT_S)
    assert result.status is BehaviorStatus.FINISHED, result.reason
    assert result.outcome == "finished"
    assert result.outputs == {"result": 42}
    assert legacy.threads and legacy.threads[0] != threading.get_ident()  # ran in a worker thread


def test_one_worker_thread_per_activation_not_per_tick():
    legacy = Double()
    adapter = SmachStateAdapter(legacy, rate_hz=FAST_HZ)
    sm = StateMachine(outcomes=["finished"], input_keys=["value"], output_keys=["result"])
    sm.add("Legacy", adapter, transitions={"doubled": "Again", "failed": "finished"})
    again = SmachStateAdapter(smach.CBState(lambda ud: "done", outcomes=["done"]), rate_hz=FAST_HZ)
    sm.add("Again", again, transitions={"done": "Legacy2"})
    legacy2 = Double()
    sm.add(
        "Legacy2",
        SmachStateAdapter(legacy2, rate_hz=FAST_HZ),
        transitions={"doubled": "finished", "failed": "finished"},
    )
    result = BehaviorExecutor(sm, inputs={"value": 1}).run(timeout_s=WAIT_S)
    assert result.status is BehaviorStatus.FINISHED, result.reason
    assert len(legacy.threads) == 1 and len(legacy2.threads) == 1


def test_input_only_values_are_read_only_for_the_smach_state():
    def mutate(ud):
        ud.items.append(4)
        return "done"

    adapter = SmachStateAdapter(smach.CBState(mutate, outcomes=["done"], input_keys=["items"]), rate_hz=FAST_HZ)
    sm = StateMachine(outcomes=["finished"], input_keys=["items"])
    sm.add("Legacy", adapter, transitions={"done": "finished"})
    items = [1, 2, 3]
    result = BehaviorExecutor(sm, inputs={"items": items}).run(timeout_s=WAIT_S)
    assert result.status is BehaviorStatus.FAILED
    assert "InvalidUserCodeError" in type(result.error).__name__
    assert "ReadOnlyUserDataError" in result.reason and "'/Legacy'" in result.reason
    assert items == [1, 2, 3]


def test_preempting_the_behavior_preempts_the_smach_state_and_discards_its_outputs():
    legacy = Blocking()
    adapter = SmachStateAdapter(legacy, rate_hz=FAST_HZ)
    ex = BehaviorExecutor(behavior(adapter, input_keys=(), output_keys=("partial",)))
    threading.Thread(target=lambda: legacy.started.wait(WAIT_S) and ex.preempt(), daemon=True).start()
    result = ex.run(timeout_s=WAIT_S)
    assert result.status is BehaviorStatus.PREEMPTED, result.reason
    assert result.outputs == {}  # written by the SMACH state after the preempt: not handed to the behavior
    assert not legacy.preempt_requested()  # it serviced the request


def test_smach_state_that_ignores_preempt_fails_the_behavior_after_the_bound():
    legacy = Blocking(obey=False)
    adapter = SmachStateAdapter(legacy, rate_hz=FAST_HZ, stop_timeout_s=0.2)
    ex = BehaviorExecutor(behavior(adapter, input_keys=(), output_keys=()))
    threading.Thread(target=lambda: legacy.started.wait(WAIT_S) and ex.preempt(), daemon=True).start()
    try:
        result = ex.run(timeout_s=WAIT_S)
    finally:
        legacy.release.set()  # let the abandoned worker thread end
    assert result.status is BehaviorStatus.FAILED
    assert "did not return within 0.2 s of its preempt request" in result.reason


def test_unregistered_outcome_and_bad_arguments():
    adapter = SmachStateAdapter(smach.CBState(lambda ud: "oops", outcomes=["done"]), rate_hz=FAST_HZ)
    sm = StateMachine(outcomes=["finished"])
    sm.add("Legacy", adapter, transitions={"done": "finished"})
    result = BehaviorExecutor(sm).run(timeout_s=WAIT_S)
    assert result.status is BehaviorStatus.FAILED
    assert "returned outcome 'oops', which it does not register (registered: done)" in result.reason
    with pytest.raises(ConfigError, match="needs a SMACH state"):
        SmachStateAdapter(object())
    with pytest.raises(ConfigError, match="stop_timeout_s must be > 0"):
        SmachStateAdapter(smach.CBState(lambda ud: "done", outcomes=["done"]), stop_timeout_s=0.0)


def test_a_smach_state_machine_runs_as_one_state():
    inner = smach.StateMachine(outcomes=["ok"], input_keys=["value"], output_keys=["result"])
    with inner:
        smach.StateMachine.add("D", Double(), transitions={"doubled": "ok", "failed": "ok"})
    adapter = SmachStateAdapter(inner, rate_hz=FAST_HZ)
    sm = StateMachine(outcomes=["finished"], input_keys=["value"], output_keys=["result"])
    sm.add("Legacy", adapter, transitions={"ok": "finished"})
    result = BehaviorExecutor(sm, inputs={"value": 5}).run(timeout_s=WAIT_S)
    assert result.status is BehaviorStatus.FINISHED and result.outputs == {"result": 10}
