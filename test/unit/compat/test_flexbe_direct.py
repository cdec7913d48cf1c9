"""FlexBE code that drives states itself: flexbe_testing's Tester with YAML cases, direct ``execute()`` of states and
containers with FlexBE's semantics, and a behavior in the FlexBE App's generated ``*_sm.py`` layout (no ROS: the
FlexBE proxies' process-wide connections are a FakeHub, the ``process_hub`` fixture)."""

from __future__ import annotations

from pathlib import Path
from typing import List

import pytest
from unit.compat.compat_testlib import DATA_DIR

from flex_nav.behavior import Autonomy, BehaviorContext, BehaviorExecutor, BehaviorStatus, ManualClock

CASES = sorted((DATA_DIR / "flexbe_tests").glob("*.test"))


# --- the Tester and FlexBE's YAML test cases --------------------------------------------------------------------------
@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_yaml_state_case_passes_through_the_tester(aliases, process_hub, case: Path):
    from flexbe_testing import Tester, load_test_cases  # noqa: PLC0415

    tester = Tester()
    ((name, config),) = load_test_cases([case]).items()
    assert tester.run_test(name, config) == 1, tester.failures.get(name)
    if name == "publish_string_state":
        assert [m.data for m in process_hub.publishers["/tester_text"].sent] == ["hello tester"]


def test_tester_reports_wrong_outcomes_outputs_and_bad_configs(aliases):
    from flexbe_testing import Tester  # noqa: PLC0415

    tester = Tester()
    calc = {"path": "example_flexbe_states.calculation_state", "class": "CalculationState"}
    wrong = {**calc, "params": {"calculation": "lambda x: x + 1"}, "input": {"input_value": 1}}
    assert tester.run_test("wrong_output", {**wrong, "output": {"output_value": 3}, "outcome": "done"}) == 0
    assert "wrong result for output_value: 2 != 3" in tester.failures["wrong_output"]
    assert tester.run_test("missing_output", {**wrong, "output": {"nothing": 3}, "outcome": "done"}) == 0
    assert "no result for nothing" in tester.failures["missing_output"]
    assert tester.run_test("no_outcome", calc) == 0
    assert "missing 'outcome'" in tester.failures["no_outcome"]
    assert tester.run_test("bad_class", {**calc, "class": "Nope", "import_only": True}) == 0
    assert "'Nope' is not valid (valid: CalculationState)" in tester.failures["bad_class"]
    assert tester.run_test("bad_param", {**calc, "params": {"nope": 1}, "outcome": "done"}) == 0
    assert "unable to instantiate" in tester.failures["bad_param"]
    checks = tester.test_case_class("flex_nav")
    assert {"test_wrong_output_pass", "test_wrong_output_outcome", "test_wrong_output_output_output_value"} <= set(
        vars(checks)
    )


def test_tester_bounds_a_state_that_never_finishes(aliases):
    from flexbe_testing import Tester  # noqa: PLC0415

    tester = Tester()
    never = {
        "path": "example_flexbe_states.decision_state",
        "class": "DecisionState",
        "params": {"outcomes": ["done"], "conditions": "lambda v: None"},
        "input": {"input_value": 0},
        "outcome": "done",
        "time_limit": 0.3,
    }
    assert tester.run_test("never", never) == 0
    assert "no outcome within the time limit of 0.3 s" in tester.failures["never"]


# --- direct execution: states ------------------------------------------------------------------------------------
def _subject():
    from flexbe_core import EventState  # noqa: PLC0415

    class Subject(EventState):
        def __init__(self):
            super().__init__(outcomes=["done", "error"])
            self.result = None
            self.events: List[str] = []

        def execute(self, userdata):
            return self.result

        def on_enter(self, userdata):
            self.events.append("on_enter")

        def on_exit(self, userdata):
            self.events.append("on_exit")

    return Subject()


def test_direct_execute_enters_on_first_call_and_exits_with_an_outcome(aliases):
    state = _subject()
    assert state.execute(None) is None and state.events == ["on_enter"]
    assert state.execute(None) is None and state.events == ["on_enter"]
    state.result = "done"
    assert state.execute(None) == "done" and state.events == ["on_enter", "on_exit"]
    state.result = None
    state.execute(None)
    assert state.events == ["on_enter", "on_exit", "on_enter"]  # re-entered after leaving


def test_direct_execute_of_a_machine_preempt_and_current_state(aliases):
    from flexbe_core import OperatableStateMachine  # noqa: PLC0415
    from flexbe_core.core import PreemptableState  # noqa: PLC0415
    from flexbe_core.core.exceptions import StateMachineError  # noqa: PLC0415

    state = _subject()
    sm = OperatableStateMachine(outcomes=["done", "error"])
    with sm:
        OperatableStateMachine.add("subject", state, transitions={"done": "done", "error": "error"})
    assert sm.execute(None) is None and sm.current_state is state and state.path == "/subject"
    PreemptableState.preempt = True
    try:
        assert sm.execute(None) == "preempted"
    finally:
        PreemptableState.preempt = False
    with pytest.raises(StateMachineError, match="No state active"):
        _ = sm.current_state
    state.result = "error"
    assert sm.execute(None) == "error"


def test_direct_execute_keeps_errors_in_last_exception(aliases):
    from flexbe_core import EventState, OperatableStateMachine  # noqa: PLC0415
    from flexbe_core.core.exceptions import StateError, StateMachineError, UserDataError  # noqa: PLC0415

    class Returns(EventState):
        def __init__(self, outcome, input_keys=()):
            super().__init__(outcomes=["done"], input_keys=list(input_keys))
            self._outcome = outcome

        def execute(self, userdata):
            if self.input_keys:
                userdata.only_input["new"] = "not allowed"
            return self._outcome

    def machine(state, transitions, **defaults):
        sm = OperatableStateMachine(outcomes=["done"])
        for key, value in defaults.items():
            sm.userdata[key] = value
        with sm:
            OperatableStateMachine.add("state", state, transitions=transitions)
        return sm

    sm = machine(Returns("invalid"), {"done": "done"})
    assert sm.execute(None) is None and isinstance(sm._last_exception, StateError)
    inner = machine(Returns("done"), {"done": "nowhere"})
    outer = machine(inner, {"done": "done"})
    assert outer.execute(None) is None and isinstance(outer._last_exception, StateMachineError)
    sm = machine(Returns("done", ["only_input"]), {"done": "done"}, only_input={"existing": 1})
    assert sm.execute(None) is None and isinstance(sm._last_exception, UserDataError)


def test_nested_machine_userdata_as_in_flexbe(aliases):
    from flexbe_core import EventState, OperatableStateMachine  # noqa: PLC0415

    class Copy(EventState):
        def __init__(self, text="copied"):
            super().__init__(outcomes=["done"], input_keys=["data_in"], output_keys=["data_out"])
            self.seen = None
            self._text = text

        def execute(self, userdata):
            self.seen = userdata.data_in
            userdata.data_out = self._text
            return "done"

    inner = OperatableStateMachine(outcomes=["done"], input_keys=["sm_in"], output_keys=["sm_out"])
    inner.userdata.own = "own"
    with inner:
        OperatableStateMachine.add(
            "own", Copy("inner"), transitions={"done": "read"}, remapping={"data_in": "own", "data_out": "sm_out"}
        )
        OperatableStateMachine.add("read", Copy(), transitions={"done": "done"}, remapping={"data_in": "sm_in"})
    sm = OperatableStateMachine(outcomes=["done"])
    sm.userdata.outside = "outside"
    with sm:
        OperatableStateMachine.add("inner", inner, transitions={"done": "after"}, remapping={"sm_in": "outside"})
        OperatableStateMachine.add("after", Copy(), transitions={"done": "done"}, remapping={"data_in": "sm_out"})
    outcome = None
    for _ in range(3):
        outcome = sm.execute(None)
    assert outcome == "done"
    assert (inner["own"].seen, inner["read"].seen, sm["after"].seen) == ("own", "outside", "inner")
    assert "own" not in sm._userdata and sm._userdata.sm_out == "inner" and "data_out" in sm._userdata


def test_concurrency_container_executes_children_at_their_rates(aliases):
    from flexbe_core import ConcurrencyContainer, OperatableStateMachine  # noqa: PLC0415

    cc = ConcurrencyContainer(
        outcomes=["done", "error"],
        conditions=[
            ("error", [("main", "error")]),
            ("done", [("main", "done"), ("side", "done")]),
        ],
    )
    with cc:
        OperatableStateMachine.add("main", _subject(), transitions={"done": "done", "error": "error"})
        OperatableStateMachine.add("side", _subject(), transitions={"done": "done", "error": "error"})
    cc["main"].set_rate(50)
    cc["side"].set_rate(25)
    counts = {"main": 0, "side": 0}
    for label in counts:
        state = cc[label]
        original = type(state).execute

        def counting(ud, state=state, label=label, original=original):
            counts[label] += 1
            return original(state, ud)

        state.execute = counting
    steps = 0
    import time  # noqa: PLC0415

    start = time.monotonic()
    while time.monotonic() - start < 0.4:
        assert cc.execute(None) is None
        cc.sleep()
        steps += 1
    assert 17 <= counts["main"] <= 22 and 8 <= counts["side"] <= 12 and steps <= 32
    cc["side"].result = "done"
    cc["main"].result = "done"
    outcome = None
    for _ in range(10):
        outcome = outcome or cc.execute(None)
        cc.sleep()
    assert outcome == "done"
    assert cc["main"].events[-1] == "on_exit" and cc["side"].events[-1] == "on_exit"


def test_sleep_follows_the_state_rate(aliases):
    import time  # noqa: PLC0415

    state = _subject()
    state.set_rate(20)
    assert state.rate_hz == 20.0 and state.sleep_duration == pytest.approx(0.05, abs=1e-3)
    start = time.monotonic()
    for _ in range(4):
        state.sleep()
    assert 0.19 <= time.monotonic() - start < 0.3


# --- a behavior in the FlexBE App's generated layout ----------------------------------------------------------------
def test_generated_behavior_runs_in_the_engine_and_waits_for_the_operator_at_low(aliases):
    from example_flexbe_behaviors.hello_flexbe_sm import HelloFlexBESM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    ctx = BehaviorContext("hello", clock=ManualClock(), autonomy=Autonomy.LOW)
    logs: List[str] = []
    ctx.hooks.log.append(lambda e: logs.append(e.message))
    behavior = build_behavior(HelloFlexBESM, context=ctx, parameters={"limit": 10})
    assert behavior.name == "Hello FlexBE" and "Greets, squares a number" in behavior.description
    executor = BehaviorExecutor(behavior, context=ctx, inputs={"number": 2})
    executor.run(timeout_s=30.0, stop_on_timeout=False)
    assert [(r.path, r.outcome) for r in executor.requested_outcomes()] == [("/Enough", "yes")]  # Autonomy.Low
    executor.approve("/Enough")
    result = executor.run(timeout_s=30.0)
    assert result.status is BehaviorStatus.FINISHED and result.outcome == "finished"
    assert result.outputs == {"result": 16}
    assert logs == ["Hello from a generated behavior", "reporting"]


def test_generated_behavior_driven_directly_as_flexbe_does(aliases):
    from example_flexbe_behaviors.hello_flexbe_sm import HelloFlexBESM  # noqa: PLC0415
    from flexbe_core.core.user_data import UserData  # noqa: PLC0415

    behavior = HelloFlexBESM()
    assert behavior.set_parameter("limit", "5") and behavior.limit == 5  # FlexBE converts to the parameter's type
    assert not behavior.set_parameter("nope", 1)
    behavior.set_up(id=7, autonomy_level=255, debug=False)
    behavior.prepare_for_execution({"number": 3})
    behavior.confirm()
    userdata = UserData()
    assert behavior._state_machine.spin(userdata) == "finished"
    assert userdata["result"] == 9
