"""The state library as a whole: documented exactly, no rospy, engine internals untouched, one proxies port (the
protocols, the real proxies and the shipped fakes agree), and every state loads from YAML parameters."""

from __future__ import annotations

import ast
import contextlib
import doctest
import inspect
import subprocess
import sys
from pathlib import Path
from typing import Callable, Dict, List, Tuple

import pytest

import flex_nav_states
from flex_nav.behavior import proxies
from flex_nav.behavior.docstring import check_state_doc, parse_state_doc
from flex_nav.behavior.state import State
from flex_nav.behavior.yaml_loader import load_behavior
from flex_nav.testing import fake_proxies
from flex_nav_states import proxy_types

REPO = Path(__file__).resolve().parents[3]
STATES_DIR = REPO / "states"
PROXIES_SRC = REPO / "src" / "flex_nav" / "ros" / "proxies.py"

# Parameters for the states that need some, plus non-default ones that exercise the docstring checks.
EXAMPLE_PARAMS: Dict[str, dict] = {
    **flex_nav_states.EXAMPLE_PARAMS,
    "OperatorDecisionState": {"outcomes": ["yes", "no", "later"], "suggestion": "yes"},
    "LogState": {"text": "hello"},
}

EXPECTED = {
    "GetPoseState", "GetPathState", "FollowPathState", "FollowPlannerState", "FollowTopicState",
    "ClearCostmapsState", "MoveDistanceState", "RotateAngleState", "TimedTwistState", "TimedStopState",
    "PurePursuitState", "BumperMonitorState", "StuckMonitorState", "SensorFreshnessState",
    "OperatorDecisionState", "LogState", "WaitState", "GoalListState", "ReplanState", "FollowUntilBlockedState",
    "ObstacleClassState", "ObstacleFusionState", "PushState", "WaitPathClearState", "BackoffState", "RobotPoseState",
    "FindFrontierState", "MarkFailedGoalState", "SaveMapState", "RememberObstacleState",
    "DetourCheckState",
}


def classes() -> List[type]:
    return flex_nav_states.state_classes()


def test_the_library_has_every_state_of_the_issue():
    assert {c.__name__ for c in classes()} == EXPECTED


@pytest.mark.parametrize("cls", classes(), ids=lambda c: c.__name__)
def test_state_docstring_matches_constructor_keys_and_outcomes(cls):
    params = EXAMPLE_PARAMS.get(cls.__name__, {})
    instance = cls(**params)
    assert check_state_doc(cls, instance, params) == []
    doc = parse_state_doc(cls.__doc__, cls.__name__)
    assert doc.outcomes, f"{cls.__name__} documents no outcome"
    for item in doc.params:
        assert item.type in ("float", "str", "list", "dict", "bool", "int"), f"{cls.__name__}.{item.name}: {item.type}"
        if item.name.endswith("_s") or item.name.endswith("_m"):
            assert "[" in item.text, f"{cls.__name__}.{item.name} does not state its unit"


def test_log_state_keys_become_input_keys_for_the_documented_parameter():
    cls = next(c for c in classes() if c.__name__ == "LogState")
    instance = cls(text="at {goal}", keys=["goal"])
    assert instance.input_keys == ("goal",)


def _imports(path: Path) -> List[str]:
    tree = ast.parse(path.read_text(), str(path))
    found: List[str] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.extend(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            found.append(node.module)
    return found


FORBIDDEN = ("rospy", "actionlib", "tf2_ros", "rosgraph", "flex_nav.ros", "time")


@pytest.mark.parametrize("module", sorted(STATES_DIR.glob("*.py")), ids=lambda p: p.name)
def test_state_modules_import_no_ros_client_library_and_no_wall_clock(module):
    bad = [m for m in _imports(module) if any(m == f or m.startswith(f + ".") for f in FORBIDDEN)]
    assert bad == [], f"{module.name} imports {bad}: states use the proxies and the behavior's clock"


def assert_loads_no_ros_client(code: str) -> None:
    """``code``, run in a fresh interpreter, leaves no module of rospy, actionlib or tf2_ros loaded."""
    check = (
        "import sys\n"
        "bad = sorted(m for m in sys.modules if m.split('.')[0] in ('rospy', 'actionlib', 'tf2_ros'))\n"
        "print(bad)\n"
        "sys.exit(1 if bad else 0)\n"
    )
    proc = subprocess.run([sys.executable, "-c", code + check], capture_output=True, text=True, timeout=120,
                          check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_importing_every_state_loads_no_rospy():
    assert_loads_no_ros_client("import flex_nav_states\nflex_nav_states.state_classes()\n")


def _engine_attributes() -> set:
    class Probe(State):
        def execute(self, userdata):
            return "done"

    return set(Probe(outcomes=["done"]).__dict__)


@pytest.mark.parametrize("module", sorted(STATES_DIR.glob("*.py")), ids=lambda p: p.name)
def test_states_never_assign_engine_internal_attributes(module):
    engine = _engine_attributes()
    assert engine == {"__flex_nav_runtime__"}  # the probe sees the engine's bookkeeping: one record
    tree = ast.parse(module.read_text(), str(module))
    assigned = set()
    for node in ast.walk(tree):
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(
            node, (ast.AnnAssign, ast.AugAssign)) else []
        for target in targets:
            for sub in ast.walk(target):
                if isinstance(sub, ast.Attribute) and isinstance(sub.value, ast.Name) and sub.value.id == "self":
                    assigned.add(sub.attr)
    clash = sorted(assigned & engine)
    assert clash == [], f"{module.name} overwrites engine attributes {clash}"


# --- one proxies port: the protocols, the real proxies and the fake ones agree ----------------------------------
# mypy checks RosProxies and FakeProxies against flex_nav.behavior.proxies.Proxies (types, arity, which parameters
# have defaults) but compares neither parameter names nor default values, on which a state passing keywords
# (send_goal(goal, server_timeout_s=...)) or leaving them out relies; nor the fake's methods outside the protocol
# (shutdown, close, wait_for_server, unregister). These tests do, on the source of ros/proxies.py (no rospy here).

NO_DEFAULT = "<no default>"


def _real_methods(class_name: str) -> Dict[str, Tuple[Tuple[str, object], ...]]:
    """Public methods of a class of ros/proxies.py: name -> ((parameter, default), ...) without self."""
    tree = ast.parse(PROXIES_SRC.read_text(), str(PROXIES_SRC))
    constants = {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            with contextlib.suppress(ValueError):  # only literal constants can be defaults here
                constants[node.targets[0].id] = ast.literal_eval(node.value)

    def value(default: ast.expr) -> object:
        return constants[default.id] if isinstance(default, ast.Name) else ast.literal_eval(default)

    def params(f: ast.FunctionDef) -> Tuple[Tuple[str, object], ...]:
        args = f.args.args[1:]
        defaults = [NO_DEFAULT] * (len(args) - len(f.args.defaults)) + [value(d) for d in f.args.defaults]
        return tuple((a.arg, d) for a, d in zip(args, defaults))

    for node in tree.body:
        if isinstance(node, ast.ClassDef) and node.name == class_name:
            return {
                f.name: params(f) for f in node.body if isinstance(f, ast.FunctionDef) and not f.name.startswith("_")
            }
    raise AssertionError(f"{class_name} not found in {PROXIES_SRC}")


def _params(function: Callable[..., object]) -> Tuple[Tuple[str, object], ...]:
    parameters = list(inspect.signature(function).parameters.values())[1:]
    return tuple((p.name, NO_DEFAULT if p.default is inspect.Parameter.empty else p.default) for p in parameters)


@pytest.mark.parametrize(
    ("real", "fake"),
    [
        ("Subscription", fake_proxies.FakeSubscription),
        ("ActionClientProxy", fake_proxies.FakeActionClient),
        ("ServiceCallerProxy", fake_proxies.FakeServiceCaller),
        ("RosProxies", fake_proxies.FakeProxies),
    ],
)
def test_fake_proxies_mirror_ros_proxies(real, fake):
    for name, params in _real_methods(real).items():
        if name in ("wait_for_message", "wait_for_result"):  # blocking helpers, not for states
            continue
        assert hasattr(fake, name), f"{fake.__name__} lacks {name}"
        fake_params = _params(getattr(fake, name))
        assert fake_params == params, f"{fake.__name__}.{name}{fake_params} != {real}.{name}{params}"


@pytest.mark.parametrize(
    ("protocol", "real"),
    [
        (proxies.SubscriptionLike, "Subscription"),
        (proxies.ActionClientLike, "ActionClientProxy"),
        (proxies.ServiceCallerLike, "ServiceCallerProxy"),
        (proxies.Proxies, "RosProxies"),
    ],
)
def test_proxy_protocols_match_ros_proxies(protocol, real):
    methods = _real_methods(real)
    for name, member in vars(protocol).items():
        if name.startswith("_") or not callable(member):
            continue
        assert name in methods, f"{protocol.__name__}.{name} is not a method of {real}"
        params = _params(member)
        assert params == methods[name], f"{protocol.__name__}.{name}{params} != {real}.{name}{methods[name]}"


def test_state_library_proxy_types_are_the_engine_protocols():
    for name in ("Proxies", "PublisherLike", "SubscriptionLike", "ActionClientLike", "ServiceCallerLike"):
        assert getattr(proxy_types, name) is getattr(proxies, name), name
    assert proxy_types.ProxiesLike is proxies.Proxies  # the former name


def test_the_test_doubles_load_no_rospy():
    assert_loads_no_ros_client("import flex_nav.testing.state_harness, flex_nav.testing.fake_proxies\n")


def test_the_fake_proxies_example_runs():
    outcome = doctest.testmod(fake_proxies, verbose=False, report=True)
    assert outcome.attempted > 0
    assert outcome.failed == 0, "the example in flex_nav.testing.fake_proxies' docstring fails (see the output)"


# --- loading from a behavior file ---------------------------------------------------------------------------


def test_states_load_from_yaml_with_their_parameters(tmp_path):
    (tmp_path / "recovery.yaml").write_text(
        """
behavior: recovery
description: stop, back up, clear, replan
parameters:
  backup_distance: {type: float, default: 0.25, description: "[m] how far to back up"}
input_keys: [goal]
output_keys: [plan]
outcomes: [replanned, failed]
states:
  Stop:
    class: flex_nav_states.timed_stop_state.TimedStopState
    parameters: {duration_s: 0.5}
    transitions: {done: BackUp, failed: failed}
  BackUp:
    class: flex_nav_states.move_distance_state.MoveDistanceState
    parameters: {distance_m: -$backup_distance, speed_mps: 0.1}
    transitions: {done: Clear, failed: failed}
  Clear:
    class: flex_nav_states.clear_costmaps_state.ClearCostmapsState
    parameters: {costmaps: [get_path_server/clear_costmap, follow_path_server/clear_costmap], timeout_s: 3.0}
    transitions: {done: Plan, failed: failed}
  Plan:
    class: flex_nav_states.get_path_state.GetPathState
    transitions: {planned: replanned, empty: failed, failed: failed}
"""
    )
    with pytest.raises(Exception, match="distance_m"):  # '-$backup_distance' is a string, not a number
        load_behavior("recovery", search_path=[tmp_path])
    text = (tmp_path / "recovery.yaml").read_text().replace("distance_m: -$backup_distance", "distance_m: -0.25")
    (tmp_path / "recovery.yaml").write_text(text)
    behavior = load_behavior("recovery", search_path=[tmp_path])
    assert behavior.name == "recovery"
