"""The state library as a whole: documented exactly, no rospy, engine internals untouched, the fake mirrors
the real proxies, and every state loads from YAML parameters."""

from __future__ import annotations

import ast
import inspect
import subprocess
import sys
from pathlib import Path
from typing import Dict, List, Tuple

import pytest
from unit.states import fake_proxies

import flex_nav_states
from flex_nav.behavior.docstring import check_state_doc, parse_state_doc
from flex_nav.behavior.state import State
from flex_nav.behavior.yaml_loader import load_behavior
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
    "ObstacleClassState", "PushState", "WaitPathClearState", "BackoffState",
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


def test_importing_every_state_loads_no_rospy():
    code = (
        "import sys, flex_nav_states\n"
        "flex_nav_states.state_classes()\n"
        "bad = sorted(m for m in sys.modules if m.split('.')[0] in ('rospy', 'actionlib', 'tf2_ros'))\n"
        "print(bad)\n"
        "sys.exit(1 if bad else 0)\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr


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


# --- the fake proxies mirror the real ones ------------------------------------------------------------------


def _real_methods(class_name: str) -> Dict[str, Tuple[str, ...]]:
    tree = ast.parse(PROXIES_SRC.read_text(), str(PROXIES_SRC))
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and node.name == class_name:
            return {
                f.name: tuple(a.arg for a in f.args.args[1:])
                for f in node.body
                if isinstance(f, ast.FunctionDef) and not f.name.startswith("_")
            }
    raise AssertionError(f"{class_name} not found in {PROXIES_SRC}")


@pytest.mark.parametrize(
    ("real", "fake"),
    [
        ("Subscription", fake_proxies.FakeSubscription),
        ("ActionClientProxy", fake_proxies.FakeActionClient),
        ("RosProxies", fake_proxies.FakeProxies),
    ],
)
def test_fake_proxies_mirror_ros_proxies(real, fake):
    for name, args in _real_methods(real).items():
        if name in ("wait_for_message", "wait_for_result"):  # blocking helpers, not for states
            continue
        assert hasattr(fake, name), f"{fake.__name__} lacks {name}"
        fake_args = tuple(list(inspect.signature(getattr(fake, name)).parameters)[1:])
        assert fake_args == args, f"{fake.__name__}.{name}{fake_args} != {real}.{name}{args}"


@pytest.mark.parametrize(
    ("protocol", "real"),
    [
        (proxy_types.SubscriptionLike, "Subscription"),
        (proxy_types.ActionClientLike, "ActionClientProxy"),
        (proxy_types.ProxiesLike, "RosProxies"),
    ],
)
def test_proxy_protocols_match_ros_proxies(protocol, real):
    methods = _real_methods(real)
    for name, member in vars(protocol).items():
        if name.startswith("_") or not callable(member):
            continue
        assert name in methods, f"{protocol.__name__}.{name} is not a method of {real}"
        args = tuple(list(inspect.signature(member).parameters)[1:])
        assert args == methods[name], f"{protocol.__name__}.{name}{args} != {real}.{name}{methods[name]}"


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
