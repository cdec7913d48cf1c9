"""flexbe_core API: a FlexBE-idiom state library and generated-style behaviors run in flex_nav's executor.

The library in test/data/compat/example_flexbe_states imports only ``flexbe_core`` (aliased by the
``aliases`` fixture) and std_msgs / flex_nav messages; nothing here touches ROS (FakeHub stands in
for the behavior's connections).
"""

from __future__ import annotations

import logging
from typing import List

import pytest

from flex_nav.behavior import Autonomy, BehaviorContext, BehaviorExecutor, BehaviorStatus, ManualClock, using_context
from flex_nav.behavior import PriorityContainer as EnginePriority
from flex_nav.behavior import StateMachine as EngineStateMachine
from flex_nav.behavior.events import LogEvent
from flex_nav.compat.flexbe_core.proxy.hub import process_proxies
from flex_nav.exceptions import (
    BehaviorConstructionError,
    ConfigError,
    UnknownTargetError,
    UnregisteredOutcomeError,
    UserDataKeyError,
)


def context(name="test", autonomy=Autonomy.FULL, hub=None):
    ctx = BehaviorContext(
        name, clock=ManualClock(), proxies=hub if hub is not None else process_proxies(), autonomy=autonomy
    )
    logs: List[LogEvent] = []
    ctx.hooks.log.append(logs.append)
    return ctx, logs


def run(behavior, ctx, timeout_s=60.0, **kwargs):
    executor = BehaviorExecutor(behavior, context=ctx, **kwargs)
    return executor, executor.run(timeout_s=timeout_s, stop_on_timeout=False)


# --- generated-style behaviors ---------------------------------------------------------------------------
def test_example_behavior_waits_for_operator_at_low_autonomy_then_finishes(aliases):
    from example_flexbe_states.example_behaviors import ExampleSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    ctx, logs = context(autonomy=Autonomy.LOW)
    behavior = build_behavior(ExampleSM, context=ctx, parameters={"limit": 2})
    assert behavior.name == "Example Behavior"
    assert behavior.parameters == {"limit": 2, "message": "counting", "topic": "/example_text"}
    assert "Counts up to a limit" in behavior.description
    executor, result = run(behavior, ctx)
    assert result.status is BehaviorStatus.RUNNING
    assert [(r.path, r.outcome, r.required) for r in executor.requested_outcomes()] == [
        ("/Check", "done", Autonomy.HIGH)
    ]
    executor.approve("/Check")
    result = executor.run(timeout_s=60.0)
    assert result.status is BehaviorStatus.FINISHED and result.outcome == "finished"
    assert result.outputs == {"value": 2, "doubled": 4}
    assert [(e.level.name, e.message) for e in logs] == [("HINT", "counting")]
    assert [m.data for m in ctx.proxies.publishers["/example_text"].sent] == ["hello"]


def test_full_autonomy_runs_through_and_parameters_change_the_result(aliases):
    from example_flexbe_states.example_behaviors import ExampleSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    ctx, _logs = context(autonomy=Autonomy.FULL)
    _executor, result = run(build_behavior(ExampleSM, context=ctx, parameters={"limit": 5}), ctx)
    assert result.status is BehaviorStatus.FINISHED
    assert result.outputs == {"value": 5, "doubled": 10}


def test_sub_behavior_input_overrides_its_default_unless_default_keys(aliases):
    from example_flexbe_states.example_behaviors import CountSM  # noqa: PLC0415
    from flexbe_core import Autonomy as FlexBEAutonomy  # noqa: PLC0415
    from flexbe_core import Behavior, OperatableStateMachine, build_behavior  # noqa: PLC0415

    class Parent(Behavior):
        def __init__(self, default_keys):
            super().__init__()
            self.name = "Parent"
            self.default_keys = default_keys
            self.add_behavior(CountSM, "Count")

        def create(self):
            sm = OperatableStateMachine(outcomes=["finished"], output_keys=["value"])
            sm.userdata.value = 7
            with sm:
                OperatableStateMachine.add(
                    "Count",
                    self.use_behavior(CountSM, "Count", default_keys=self.default_keys, parameters={"increment": 10}),
                    transitions={"finished": "finished"},
                    autonomy={"finished": FlexBEAutonomy.Inherit},
                )
            return sm

    ctx, _ = context()
    _, result = run(build_behavior(Parent(default_keys=None), context=ctx), ctx)
    assert result.outputs == {"value": 17}  # the parent's 7, plus 10
    ctx, _ = context()
    _, result = run(build_behavior(Parent(default_keys=["value"]), context=ctx), ctx)
    assert result.outputs == {"value": 110}  # the sub-behavior started from its own default, 100, not the parent's 7
    with pytest.raises(ConfigError, match=r"default_keys \['nope'\] are not input keys"):
        build_behavior(Parent(default_keys=["nope"]))


def test_parameter_overrides_are_checked(aliases):
    from example_flexbe_states.example_behaviors import ExampleSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    with pytest.raises(ConfigError, match=r"parameter 'limt' is not valid \(valid: limit, message, topic\)"):
        build_behavior(ExampleSM, parameters={"limt": 3})
    with pytest.raises(ConfigError, match="parameter 'limit' must be a int like its default 3, got 'three'"):
        build_behavior(ExampleSM, parameters={"limit": "three"})


def test_use_behavior_of_an_unknown_id_names_the_added_ones(aliases):
    from example_flexbe_states.example_behaviors import CountSM  # noqa: PLC0415
    from flexbe_core import Behavior, build_behavior  # noqa: PLC0415

    class Broken(Behavior):
        def __init__(self):
            super().__init__()
            self.name = "Broken"
            self.add_behavior(CountSM, "Count")

        def create(self):
            return self.use_behavior(CountSM, "Cuont")

    with pytest.raises(ConfigError, match=r"sub-behavior 'Cuont' is not valid \(valid: Count\)"):
        build_behavior(Broken)


def test_construction_errors_name_the_valid_choices(aliases):
    from example_flexbe_states.log_state import LogState  # noqa: PLC0415
    from flexbe_core import Behavior, OperatableStateMachine, build_behavior  # noqa: PLC0415

    class TypoTarget(Behavior):
        def create(self):
            sm = OperatableStateMachine(outcomes=["finished", "failed"])
            with sm:
                OperatableStateMachine.add("Log", LogState(text="x"), transitions={"done": "Finnished"})
            return sm

    with pytest.raises(UnknownTargetError, match=r"unknown target 'Finnished' \(valid: Log, finished, failed\)"):
        build_behavior(TypoTarget)
    sm = OperatableStateMachine(outcomes=["finished"])
    with sm, pytest.raises(UnregisteredOutcomeError, match=r"outcome 'dnoe'.*\(valid: done\)"):
        OperatableStateMachine.add("Log", LogState(text="x"), transitions={"dnoe": "finished"})
    with pytest.raises(BehaviorConstructionError, match="no container is opened"):
        OperatableStateMachine.add("Log", LogState(text="x"), transitions={"done": "finished"})
    with pytest.raises(ConfigError, match="create\\(\\) must return a state machine"):

        class Nothing(Behavior):
            def create(self):
                return None

        build_behavior(Nothing)


# --- containers ----------------------------------------------------------------------------------------------
def test_concurrency_container_conditions_and_child_transition_checks(aliases):
    from example_flexbe_states.calculation_state import CalculationState  # noqa: PLC0415
    from flexbe_core import ConcurrencyContainer, OperatableStateMachine  # noqa: PLC0415

    cc = ConcurrencyContainer(outcomes=["finished", "failed"], conditions={"finished": [("A", "done")]})
    assert cc.conditions == [("finished", (("A", "done"),))]
    with cc:
        with pytest.raises(UnknownTargetError, match=r"goes to 'elsewhere'.*\(valid: finished, failed\)"):
            OperatableStateMachine.add("A", CalculationState(lambda x: x), transitions={"done": "elsewhere"})
        with pytest.raises(UnregisteredOutcomeError, match=r"'nope'.*\(valid: done\)"):
            OperatableStateMachine.add("A", CalculationState(lambda x: x), transitions={"nope": "finished"})
        OperatableStateMachine.add(
            "A", CalculationState(lambda x: x + 1), transitions={"done": "finished"}, remapping={"input_value": "v"}
        )
    assert list(cc.children) == ["A"]


def priority_behavior(guard_first):
    """Both = Work (4 ticks) || Guard (a PriorityContainer running Stop for 3 ticks); journal of calls."""
    from flexbe_core import ConcurrencyContainer, EventState, OperatableStateMachine, PriorityContainer  # noqa: PLC0415

    journal = []

    class Ticks(EventState):
        def __init__(self, name, ticks):
            super().__init__(outcomes=["done"])
            self._name, self._ticks, self._count = name, ticks, 0

        def on_enter(self, userdata):
            self._count = 0
            journal.append((self._name, "enter"))

        def execute(self, userdata):
            self._count += 1
            journal.append((self._name, "execute"))
            return "done" if self._count >= self._ticks else None

        def on_pause(self):
            journal.append((self._name, "pause"))

        def on_resume(self, userdata):
            journal.append((self._name, "resume"))

    root = OperatableStateMachine(outcomes=["finished"])
    cc = ConcurrencyContainer(
        outcomes=["finished"], conditions=[("finished", [("Work", "done"), ("Guard", "finished")])]
    )
    guard = PriorityContainer(outcomes=["finished"])
    assert issubclass(PriorityContainer, EnginePriority) and issubclass(PriorityContainer, OperatableStateMachine)
    with guard:
        OperatableStateMachine.add("Stop", Ticks("stop", 3), transitions={"done": "finished"})
    with cc:
        if guard_first:
            OperatableStateMachine.add("Guard", guard, transitions={"finished": "finished"})
        OperatableStateMachine.add("Work", Ticks("work", 4), transitions={"done": "finished"})
        if not guard_first:
            OperatableStateMachine.add("Guard", guard, transitions={"finished": "finished"})
    with root:
        OperatableStateMachine.add("Both", cc, transitions={"finished": "finished"})
    return root, journal


def run_priority_behavior(guard_first):
    """Run priority_behavior to its end; its journal. The guard's three ticks come first, then the work's four."""
    root, journal = priority_behavior(guard_first)
    ctx, _ = context()
    _, result = run(root, ctx)
    assert result.status is BehaviorStatus.FINISHED, result.reason
    assert [who for who, call in journal if call == "execute"] == ["stop"] * 3 + ["work"] * 4
    return journal


def test_priority_container_holds_the_other_branch_while_it_runs(aliases):
    journal = run_priority_behavior(guard_first=True)
    assert journal.index(("stop", "execute")) < journal.index(("work", "enter"))  # held before it even started


def test_priority_container_releases_a_sibling_listed_before_it(aliases):
    run_priority_behavior(guard_first=False)


def test_userdata_defaults_view(aliases):
    from flexbe_core import OperatableStateMachine  # noqa: PLC0415

    sm = OperatableStateMachine(outcomes=["finished"])
    sm.userdata.speed = 0.5
    sm.userdata["name"] = "robot"
    assert sm.userdata.speed == 0.5 and sm.userdata["name"] == "robot"
    assert "speed" in sm.userdata and sorted(sm.userdata.keys()) == ["name", "speed"]
    assert sm.userdata_defaults == {"speed": 0.5, "name": "robot"}
    with pytest.raises(UserDataKeyError, match=r"no default 'sped' \(defaults: name, speed\)"):
        sm.userdata.sped  # noqa: B018
    with pytest.raises(ConfigError, match="must be a name"):
        sm.userdata["_private"] = 1
    assert isinstance(sm, EngineStateMachine)


# --- EventState ---------------------------------------------------------------------------------------------
def test_event_state_lifecycle_runs_on_the_engine(aliases):
    from flexbe_core import EventState, OperatableStateMachine  # noqa: PLC0415

    calls = []

    class Recorder(EventState):
        def __init__(self):
            super().__init__(outcomes=["done", "done"], io_keys=["count"])

        def on_start(self):
            calls.append("start")

        def on_enter(self, userdata):
            calls.append("enter")

        def execute(self, userdata):
            calls.append("execute")
            userdata.count = userdata.count + 1
            return "done" if userdata.count >= 3 else None

        def on_exit(self, userdata):
            calls.append("exit")

        def on_stop(self):
            calls.append("stop")

    state = Recorder()
    assert state.outcomes == ("done",)  # repeated outcomes are merged, as FlexBE does
    assert state.input_keys == ("count",) and state.output_keys == ("count",)
    state.set_rate(20.0)
    assert state.rate_hz == 20.0 and state.sleep_duration == pytest.approx(0.05)
    sm = OperatableStateMachine(outcomes=["finished"], output_keys=["count"])
    sm.userdata.count = 0
    with sm:
        OperatableStateMachine.add("R", state, transitions={"done": "finished"})
    ctx, _ = context()
    _, result = run(sm, ctx)
    assert result.outputs == {"count": 3}
    assert calls == ["start", "enter", "execute", "execute", "execute", "exit", "stop"]


def test_event_state_refuses_a_bare_string(aliases):
    from flexbe_core import EventState  # noqa: PLC0415

    with pytest.raises(ConfigError, match="outcomes must be a list of names, not the string 'done'"):
        EventState(outcomes="done")
    with pytest.raises(ConfigError, match="io_keys must be a list"):
        EventState(outcomes=["done"], io_keys="key")


# --- Logger ----------------------------------------------------------------------------------------------------
def test_logger_goes_to_the_current_behavior_and_throttles_per_behavior(aliases, caplog):
    from flexbe_core import Logger  # noqa: PLC0415

    first, first_logs = context("first")
    second, second_logs = context("second")
    with using_context(first):
        Logger.loginfo("value %d", 3)
        Logger.logwarn_throttle(1.0, "slow")
        Logger.logwarn_throttle(1.0, "slow")  # suppressed: same text within 1 s of this behavior's clock
        Logger.log("odd", 7)
    with using_context(second):
        Logger.logwarn_throttle(1.0, "slow")  # not suppressed by the first behavior's memory
        Logger.loghint("100% done")  # no args: no %-formatting
    first.clock.advance(1.5)
    with using_context(first):
        Logger.logwarn_throttle(1.0, "slow")
    assert [(e.level.name, e.message) for e in first_logs] == [
        ("INFO", "value 3"),
        ("WARN", "slow"),
        ("DEBUG", "odd (unknown log level 7)"),
        ("WARN", "slow"),
    ]
    assert [(e.level.name, e.message) for e in second_logs] == [("WARN", "slow"), ("HINT", "100% done")]
    with caplog.at_level(logging.INFO, logger="flex_nav.compat.flexbe"):
        Logger.logerr("outside any behavior")
        Logger.localinfo("local only")
    assert "outside any behavior" in caplog.text and "local only" in caplog.text


def test_autonomy_constants_are_flexbe_levels(aliases):
    from flexbe_core import Autonomy as FlexBEAutonomy  # noqa: PLC0415

    levels = (FlexBEAutonomy.Inherit, FlexBEAutonomy.Off, FlexBEAutonomy.Low, FlexBEAutonomy.High, FlexBEAutonomy.Full)
    assert [Autonomy.parse(level) for level in levels] == [
        Autonomy.OFF,
        Autonomy.OFF,
        Autonomy.LOW,
        Autonomy.HIGH,
        Autonomy.FULL,
    ]
