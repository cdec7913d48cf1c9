"""YAML behaviors: the examples load and run; every error case reports file:line: what (valid: ...)."""

from __future__ import annotations

import textwrap
from functools import partial
from pathlib import Path
from typing import List, Tuple

import pytest
from unit.behavior.behavior_testlib import child

from flex_nav.behavior import (
    Autonomy,
    BehaviorExecutor,
    BehaviorStatus,
    ConcurrencyContainer,
    ManualClock,
    PriorityContainer,
    StateMachine,
)
from flex_nav.behavior.builtin_states import Calculation, Compare, Log, Wait
from flex_nav.behavior.events import LogEvent, TransitionEvent
from flex_nav.behavior.yaml_loader import find_behavior, list_behaviors, load_behavior, load_behavior_text
from flex_nav.exceptions import BehaviorLoadError, ConfigError

DATA = Path(__file__).resolve().parent / "data"
STATES = "flex_nav.behavior.builtin_states"


def record_transition(into: List[Tuple[float, str, str, str]], event: TransitionEvent) -> None:
    into.append((event.time_s, event.path, event.outcome, event.target))


def run(behavior, **kwargs):
    kwargs.setdefault("clock", ManualClock())
    ex = BehaviorExecutor(behavior, **kwargs)
    logs: List[LogEvent] = []
    ex.context.hooks.log.append(logs.append)
    return ex, ex.run(timeout_s=60.0, stop_on_timeout=False), logs


# --- the examples --------------------------------------------------------------------------------


def test_count_loop_runs_with_defaults_and_waits_for_high_autonomy():
    behavior = load_behavior(DATA / "count_loop.yaml")
    assert behavior.name == "count_loop"
    assert behavior.parameters == {"step": 1.0, "limit": 3.0}
    assert isinstance(behavior.root, StateMachine)
    ex, result, _ = run(behavior, autonomy=Autonomy.HIGH)
    assert result.status is BehaviorStatus.RUNNING
    assert [(r.path, r.outcome, r.required) for r in ex.requested_outcomes()] == [("/Count", "reached", Autonomy.HIGH)]
    ex.approve("/Count")
    result = ex.run(timeout_s=5.0)
    assert (result.status, result.outcome, result.outputs) == (BehaviorStatus.FINISHED, "finished", {"count": 3.0})


def test_parameters_are_overridable_at_load_time():
    behavior = load_behavior(DATA / "count_loop.yaml", parameters={"step": 0.5, "limit": 1})
    assert behavior.parameters == {"step": 0.5, "limit": 1.0}
    _, result, logs = run(behavior)
    assert result.outputs == {"count": 1.0}
    assert [(log.message, log.path) for log in logs] == [("limit reached", "/Report")]


def test_guarded_wait_uses_concurrency_priority_and_a_sub_behavior_by_name():
    behavior = load_behavior("guarded_wait", search_path=[DATA])
    nav = child(behavior.root, "Guarded")
    assert isinstance(nav, ConcurrencyContainer)
    recover = child(nav, "Guard", "Recover")
    assert isinstance(recover, PriorityContainer)
    announce = recover["Announce"]
    assert isinstance(announce, StateMachine) and list(announce.children) == ["Say", "Pause"]
    assert isinstance(announce["Say"], Log) and isinstance(nav["Work"], Wait)
    assert nav["Work"].rate_hz == 20.0
    _, result, logs = run(behavior)
    assert (result.status, result.outcome) == (BehaviorStatus.FINISHED, "finished")
    assert [(log.message, log.path) for log in logs] == [("recovering", "/Guarded/Guard/Recover/Announce/Say")]


def test_same_behavior_built_from_python_runs_the_same():
    yaml_behavior = load_behavior(DATA / "count_loop.yaml", parameters={"limit": 2.0})

    inner = StateMachine(outcomes=["reached"], input_keys=["count"], output_keys=["count"])
    inner.add(
        "Add",
        Calculation("add", 1.0),
        transitions={"done": "Check"},
        remapping={"input_value": "count", "output_value": "count"},
    )
    inner.add(
        "Check", Compare(">=", 2.0), transitions={"met": "reached", "not_met": "Add"}, remapping={"value": "count"}
    )
    root = StateMachine(outcomes=["finished", "failed"], output_keys=["count"], userdata={"count": 0.0})
    root.add("Count", inner, transitions={"reached": "Report"}, autonomy={"reached": Autonomy.HIGH})
    root.add("Report", Log("limit reached", "hint"), transitions={"done": "finished"})
    results = []
    for behavior in (yaml_behavior, root):
        ex = BehaviorExecutor(behavior, clock=ManualClock())
        transitions: List[Tuple[float, str, str, str]] = []
        ex.context.hooks.transition.append(partial(record_transition, transitions))
        results.append((ex.run(timeout_s=10.0), transitions))
    assert results[0] == results[1]


def test_search_path_helpers(tmp_path, monkeypatch):
    assert set(list_behaviors([DATA])) == {"announce", "count_loop", "guarded_wait"}
    assert find_behavior("announce", [DATA]) == DATA / "announce.yaml"
    with pytest.raises(
        ConfigError,
        match=r"behavior \(looked in: .*\) 'nope' is not valid \(valid: announce, count_loop, guarded_wait\)",
    ):
        find_behavior("nope", [DATA])
    with pytest.raises(ConfigError, match="no paths"):
        find_behavior("../etc/passwd", [DATA])
    monkeypatch.setenv("FLEX_NAV_BEHAVIOR_PATH", str(DATA))
    assert load_behavior("announce").name == "announce"


def test_override_errors_are_config_errors():
    with pytest.raises(
        ConfigError, match=r"behavior 'count_loop' has no parameter; override 'stp' is not valid \(valid: step, limit\)"
    ):
        load_behavior(DATA / "count_loop.yaml", parameters={"stp": 1.0})
    with pytest.raises(ConfigError, match=r"override of parameter 'step' must be float, got str 'big'"):
        load_behavior(DATA / "count_loop.yaml", parameters={"step": "big"})
    with pytest.raises(ConfigError, match=r"parameter 'step' = -1.0 is below its minimum 0.0"):
        load_behavior(DATA / "count_loop.yaml", parameters={"step": -1.0})


def test_yaml_words_stay_names_in_names_and_values_in_values(tmp_path):
    """Names (outcomes, autonomy levels) are taken as written; parameter values are YAML values (quote on/off)."""
    text = f"""\
    behavior: words
    parameters:
      flag: {{type: bool, default: true}}
    outcomes: [finished, failed]
    states:
      A:
        class: {STATES}.Decision
        parameters: {{outcomes: ["on", "off"], choice: "on"}}
        transitions: {{on: finished, off: failed}}
        autonomy: {{on: off, off: 3}}
    """
    behavior = load_behavior_text(textwrap.dedent(text), "words.yaml")
    assert behavior.parameters == {"flag": True}
    root = behavior.root
    assert isinstance(root, StateMachine)
    assert root["A"].outcomes == ("on", "off")
    assert root.autonomy_of("A") == {"on": Autonomy.OFF, "off": Autonomy.FULL}


def test_dollar_escapes_a_literal_dollar():
    text = f"""\
    behavior: money
    outcomes: [finished]
    states:
      Say:
        class: {STATES}.Log
        parameters: {{text: "$$5"}}
        transitions: {{done: finished}}
    """
    behavior = load_behavior_text(textwrap.dedent(text))
    _, _, logs = run(behavior)
    assert [log.message for log in logs] == ["$5"]


# --- error cases: each one names file, line and the valid choices ----------------------------------

BASE_STATE = f"""\
  A:
    class: {STATES}.Decision
    parameters: {{outcomes: [done, failed], choice: done}}
    transitions: {{done: finished, failed: failed}}
"""


def header(name="case"):
    return f"behavior: {name}\noutcomes: [finished, failed]\n"


ERROR_CASES = {
    "yaml syntax": (
        header() + "states:\n  A: {class: x\n  B: [  # <-\n",
        "YAML syntax error",
    ),
    "not a mapping": ("- behavior  # <-\n", "a behavior file must be a mapping, got a list"),
    "unknown top-level key": (
        header() + "state:  # <-\n" + BASE_STATE,
        "unknown key in a behavior file: 'state' is not valid (valid: behavior, description, parameters, input_keys, "
        "output_keys, userdata, outcomes, initial, states)",
    ),
    "missing states": ("behavior: case  # <-\noutcomes: [finished]\n", "a behavior file needs the key 'states'"),
    "name differs from file": (
        "behavior: other  # <-\noutcomes: [finished, failed]\nstates:\n" + BASE_STATE,
        "behavior 'other' must be in a file named other.yaml, not case.yaml",
    ),
    "outcomes not a list": (
        "behavior: case\noutcomes: finished  # <-\nstates:\n" + BASE_STATE,
        "outcomes must be a list of names",
    ),
    "duplicate label": (
        header() + "states:\n" + BASE_STATE + "  A:  # <-\n    class: x.Y\n",
        "duplicate key 'A' in states of state machine / (first on line 4)",
    ),
    "no kind": (
        header() + "states:\n  A:  # <-\n    transitions: {done: finished}\n",
        "state 'A' needs exactly one of class, state_machine, concurrency, priority, behavior (found: none)",
    ),
    "two kinds": (
        header() + f"states:\n  A:  # <-\n    class: {STATES}.Wait\n    behavior: announce\n",
        "needs exactly one of class, state_machine, concurrency, priority, behavior (found: class, behavior)",
    ),
    "unknown state key": (
        header() + f"states:\n  A:\n    class: {STATES}.Log\n    parameters: {{text: hi}}\n"
        "    transition: {done: finished}  # <-\n",
        "unknown key in state 'A': 'transition' is not valid "
        "(valid: class, parameters, rate_hz, transitions, autonomy, remapping)",
    ),
    "class not dotted": (
        header() + "states:\n  A:\n    class: Wait  # <-\n",
        "class 'Wait' must be a dotted path module.Class",
    ),
    "module missing": (
        header() + "states:\n  A:\n    class: no_such_pkg.Wait  # <-\n",
        "cannot import module 'no_such_pkg' for state class 'no_such_pkg.Wait': No module named 'no_such_pkg'",
    ),
    "class missing": (
        header() + f"states:\n  A:\n    class: {STATES}.Sleep  # <-\n",
        "module 'flex_nav.behavior.builtin_states' has no state class 'Sleep' is not valid "
        "(valid: Calculation, Compare, Decision, Log, State, Wait)",
    ),
    "not a state class": (
        header() + "states:\n  A:\n    class: flex_nav.behavior.autonomy.Autonomy  # <-\n",
        "'flex_nav.behavior.autonomy.Autonomy' is not a State class",
    ),
    "container as class": (
        header() + "states:\n  A:\n    class: flex_nav.behavior.state_machine.StateMachine  # <-\n",
        "is a container: use state_machine:, concurrency: or priority: instead",
    ),
    "unknown constructor parameter": (
        header() + f"states:\n  A:\n    class: {STATES}.Wait\n    parameters:\n      wait_time: 1.0  # <-\n"
        "    transitions: {done: finished}\n",
        "state class Wait has no parameter 'wait_time' is not valid (valid: wait_time_s)",
    ),
    "missing constructor parameter": (
        header() + f"states:\n  A:\n    class: {STATES}.Wait  # <-\n    transitions: {{done: finished}}\n",
        "state 'A': Wait needs parameter(s) wait_time_s (parameters: wait_time_s)",
    ),
    "constructor rejects value": (
        header()
        + f"states:\n  A:\n    class: {STATES}.Decision  # <-\n    parameters: {{outcomes: [a, b], choice: c}}\n",
        "state 'A': Decision rejected its parameters: Decision: choice 'c' is not valid (valid: a, b)",
    ),
    "bad rate": (
        header() + f"states:\n  A:\n    class: {STATES}.Log\n    parameters: {{text: hi}}\n    rate_hz: -1  # <-\n",
        "state 'A': Log: rate_hz must be a number > 0 [Hz], got -1",
    ),
    "unregistered outcome in transitions": (
        header() + f"states:\n  A:\n    class: {STATES}.Log\n    parameters: {{text: hi}}\n    transitions:\n"
        "      finished: finished  # <-\n",
        "transition of 'A' names outcome 'finished' that Log does not register (valid: done)",
    ),
    "unknown target": (
        header() + f"states:\n  A:\n    class: {STATES}.Log\n    parameters: {{text: hi}}\n    transitions:\n"
        "      done: Nowhere  # <-\n",
        "transition 'A'.done goes to unknown target 'Nowhere' (valid: A, finished, failed)",
    ),
    "missing transition": (
        header()
        + f"states:\n  A:  # <-\n    class: {STATES}.Decision\n    parameters: {{outcomes: [x, y], choice: x}}\n"
        "    transitions: {x: finished}\n",
        "outcome 'y' of state 'A' has no transition (valid targets: A, finished, failed)",
    ),
    "unreachable state": (
        header() + "states:\n" + BASE_STATE + f"  B:  # <-\n    class: {STATES}.Log\n    parameters: {{text: hi}}\n"
        "    transitions: {done: A}\n",
        "state 'B' cannot be reached from the initial state 'A' (reachable: A)",
    ),
    "label is an outcome": (
        header() + f"states:\n  finished:  # <-\n    class: {STATES}.Log\n    parameters: {{text: hi}}\n"
        "    transitions: {done: finished}\n",
        "state label 'finished' is also an outcome of the machine (outcomes: finished, failed); rename one",
    ),
    "unknown initial state": (
        header() + "initial: Start  # <-\nstates:\n" + BASE_STATE,
        "initial state 'Start' is not one of its states (valid: A)",
    ),
    "bad autonomy level": (
        header() + "states:\n" + BASE_STATE + "    autonomy:\n      done: medium  # <-\n",
        "autonomy of 'A' for 'done': autonomy level 'medium' is not valid (valid: off, low, high, full, 0, 1, 2, 3)",
    ),
    "autonomy of unregistered outcome": (
        header() + "states:\n" + BASE_STATE + "    autonomy:\n      ok: low  # <-\n",
        "autonomy of 'A' names outcome 'ok' that Decision does not register (valid: done, failed)",
    ),
    "remapping of undeclared key": (
        header() + f"states:\n  A:\n    class: {STATES}.Compare\n    parameters: {{comparison: '>', threshold: 1}}\n"
        "    transitions: {met: finished, not_met: failed}\n    remapping:\n      val: x  # <-\n",
        "remapping of 'A' names key 'val' that Compare does not declare (valid: value)",
    ),
    "undeclared input key": (
        header()
        + f"states:\n  A:  # <-\n    class: {STATES}.Compare\n    parameters: {{comparison: '>', threshold: 1}}\n"
        "    transitions: {met: finished, not_met: failed}\n",
        "input key 'value' of state 'A' is neither an input key nor a userdata default of the container nor an output "
        "of any of its states (available: none)",
    ),
    "output key nobody writes": (
        "behavior: case\noutcomes: [finished, failed]\noutput_keys:\n  - result  # <-\nstates:\n" + BASE_STATE,
        "output key 'result' is produced by no state and is neither an input key nor a userdata default "
        "(available: none)",
    ),
    "unknown parameter reference": (
        "behavior: case\nparameters:\n  wait: {type: float, default: 1.0}\noutcomes: [finished]\nstates:\n"
        f"  A:\n    class: {STATES}.Wait\n    parameters:\n      wait_time_s: $wiat  # <-\n"
        "    transitions: {done: finished}\n",
        "parameter reference '$wiat' is not valid (valid: $wait)",
    ),
    "parameter without type": (
        "behavior: case\nparameters:\n  wait: {default: 1.0}  # <-\n"
        + "outcomes: [finished, failed]\nstates:\n"
        + BASE_STATE,
        "parameter 'wait' needs a type (valid: float, int, bool, str, list, dict)",
    ),
    "parameter of unknown type": (
        "behavior: case\nparameters:\n  wait: {type: double, default: 1.0}  # <-\n"
        + "outcomes: [finished, failed]\nstates:\n"
        + BASE_STATE,
        "type of parameter 'wait' 'double' is not valid (valid: float, int, bool, str, list, dict)",
    ),
    "parameter default of wrong type": (
        "behavior: case\nparameters:\n  wait:\n    type: int\n    default: 1.5  # <-\n"
        + "outcomes: [finished, failed]\nstates:\n"
        + BASE_STATE,
        "default of parameter 'wait' must be int, got float 1.5",
    ),
    "parameter without default": (
        "behavior: case\nparameters:\n  wait: {type: float}  # <-\n"
        + "outcomes: [finished, failed]\nstates:\n"
        + BASE_STATE,
        "behavior 'case' needs a value for parameter 'wait' (it has no default)",
    ),
    "sub-behavior not found": (
        header() + "states:\n  A:\n    behavior: nothing_here  # <-\n    transitions: {done: finished}\n",
        "state 'A': behavior (looked in: ",
    ),
    "sub-behavior parameter unknown": (
        header()
        + "states:\n  A:\n    behavior: announce  # <-\n    parameters: {txt: hi}\n    transitions: {done: finished}\n",
        "behavior 'announce' has no parameter; override 'txt' is not valid (valid: text, pause_s)",
    ),
    "sub-behavior includes itself": (
        header() + "states:\n  A:\n    behavior: case  # <-\n    transitions: {finished: finished, failed: failed}\n",
        "behavior includes itself: case -> case",
    ),
    "concurrency condition names unknown state": (
        header() + "states:\n  P:\n    concurrency:\n      outcomes: [finished]\n      states:\n"
        f"        W:\n          class: {STATES}.Wait\n          parameters: {{wait_time_s: 1}}\n"
        "      conditions:\n        - outcome: finished\n          when: [[V, done]]  # <-\n"
        "    transitions: {finished: finished}\n",
        "condition for 'finished' names unknown state 'V' (valid: W)",
    ),
    "concurrency condition outcome unknown": (
        header() + "states:\n  P:\n    concurrency:\n      outcomes: [finished]\n      states:\n"
        f"        W:\n          class: {STATES}.Wait\n          parameters: {{wait_time_s: 1}}\n"
        "      conditions:\n        - outcome: done  # <-\n          when: [[W, done]]\n"
        "    transitions: {finished: finished}\n",
        "condition outcome 'done' is not an outcome of the container (valid: finished)",
    ),
    "concurrency condition pair malformed": (
        header() + "states:\n  P:\n    concurrency:\n      outcomes: [finished]\n      states:\n"
        f"        W:\n          class: {STATES}.Wait\n          parameters: {{wait_time_s: 1}}\n"
        "      conditions:\n        - outcome: finished\n          when: [W, done]  # <-\n"
        "    transitions: {finished: finished}\n",
        "each item of when of condition 'finished' must be a pair [state, outcome]",
    ),
    "concurrency without conditions": (
        header() + "states:\n  P:\n    concurrency:  # <-\n      outcomes: [finished]\n      states:\n"
        f"        W:\n          class: {STATES}.Wait\n          parameters: {{wait_time_s: 1}}\n"
        "    transitions: {finished: finished}\n",
        "concurrency container /P needs conditions",
    ),
    "transitions inside concurrency": (
        header() + "states:\n  P:\n    concurrency:\n      outcomes: [finished]\n      states:\n"
        f"        W:\n          class: {STATES}.Wait\n          parameters: {{wait_time_s: 1}}\n"
        "          transitions: {done: finished}  # <-\n"
        "      conditions:\n        - {outcome: finished, when: [[W, done]]}\n    transitions: {finished: finished}\n",
        "unknown key in state 'W': 'transitions' is not valid (valid: class, parameters, rate_hz, autonomy, remapping)",
    ),
    "nested machine error points into it": (
        header() + "states:\n  N:\n    state_machine:\n      outcomes: [ok]\n      states:\n"
        f"        X:\n          class: {STATES}.Log\n          parameters: {{text: hi}}\n"
        "          transitions: {done: finished}  # <-\n    transitions: {ok: finished}\n",
        "state machine /N: transition 'X'.done goes to unknown target 'finished' (valid: X, ok)",
    ),
}


@pytest.mark.parametrize("case", list(ERROR_CASES))
def test_yaml_error_case(case, tmp_path):
    text, message = ERROR_CASES[case]
    marked = [number for number, line in enumerate(text.splitlines(), start=1) if "# <-" in line]
    assert len(marked) == 1, "each case marks the line its error must point at"
    path = tmp_path / "case.yaml"
    path.write_text(text)
    (tmp_path / "announce.yaml").write_text((DATA / "announce.yaml").read_text())
    with pytest.raises(BehaviorLoadError) as info:
        load_behavior(path, search_path=[tmp_path])
    err = info.value
    assert message in err.reason, f"{case}: {err}"
    assert (err.file, err.line) == (str(path), marked[0]), f"{case}: {err}"
    assert str(err) == f"{path}:{marked[0]}: {err.reason}"


def test_empty_file_and_unreadable_file(tmp_path):
    empty = tmp_path / "empty.yaml"
    empty.write_text("")
    with pytest.raises(BehaviorLoadError, match=r"empty.yaml:1: the file is empty"):
        load_behavior(empty)
    with pytest.raises(BehaviorLoadError, match=r"missing.yaml:0: cannot read the file"):
        load_behavior(tmp_path / "missing.yaml")


def test_error_in_a_sub_behavior_names_its_own_file(tmp_path):
    (tmp_path / "inner.yaml").write_text(
        f"behavior: inner\noutcomes: [done]\nstates:\n  S:\n    class: {STATES}.Log\n    parameters: {{text: x}}\n"
        "    transitions: {done: gone}\n"
    )
    outer = tmp_path / "outer.yaml"
    outer.write_text(header("outer") + "states:\n  I:\n    behavior: inner\n    transitions: {done: finished}\n")
    with pytest.raises(BehaviorLoadError) as info:
        load_behavior(outer)
    assert (info.value.file, info.value.line) == (str(tmp_path / "inner.yaml"), 7)
    assert "state machine /I: transition 'S'.done goes to unknown target 'gone' (valid: S, done)" in info.value.reason


def test_sub_behavior_named_by_a_parameter(tmp_path):
    for name, text in (("left", "went left"), ("right", "went right")):
        (tmp_path / f"{name}.yaml").write_text(
            f"behavior: {name}\noutcomes: [done]\nstates:\n  S:\n    class: {STATES}.Log\n"
            f"    parameters: {{text: {text}}}\n    transitions: {{done: done}}\n"
        )
    outer = tmp_path / "outer.yaml"
    outer.write_text(
        "behavior: outer\nparameters:\n  way: {type: str, default: left}\n  nothing: {type: float, default: 1.0}\n"
        "outcomes: [finished]\nstates:\n  Go:\n    behavior: $way\n    transitions: {done: finished}\n"
    )
    for way, text in ((None, "went left"), ("right", "went right")):
        said = child(load_behavior(outer, parameters={"way": way} if way else None).root, "Go", "S")
        assert isinstance(said, Log) and said._text == text
    with pytest.raises(BehaviorLoadError, match=r"outer.yaml:8: state 'Go': behavior .* 'nowhere' is not valid"):
        load_behavior(outer, parameters={"way": "nowhere"})
    bad = tmp_path / "bad.yaml"
    bad.write_text(outer.read_text().replace("$way", "$nothing").replace("behavior: outer", "behavior: bad"))
    with pytest.raises(BehaviorLoadError, match=r"bad.yaml:8: behavior of 'Go': parameter \$nothing must name"):
        load_behavior(bad)
