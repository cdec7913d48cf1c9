"""State docstring convention: the parser, and every state class of flex_nav.behavior documented exactly."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
from typing import Any, Dict

import pytest

import flex_nav.behavior
from flex_nav.behavior import Container, State
from flex_nav.behavior.docstring import check_state_doc, constructor_params, parse_state_doc
from flex_nav.exceptions import ConfigError

# Constructor arguments to instantiate each state class of the package (a new class must be added here).
SAMPLE_PARAMS: Dict[str, Dict[str, Any]] = {
    "Wait": {"wait_time_s": 1.0},
    "Log": {"text": "hello", "severity": "warn"},
    "Decision": {"outcomes": ["left", "right"], "choice": "left"},
    "Calculation": {"operation": "add", "operand": 2.0},
    "Compare": {"comparison": ">=", "threshold": 1.0},
}


def package_state_classes():
    classes = {}
    for info in pkgutil.iter_modules(flex_nav.behavior.__path__):
        module = importlib.import_module(f"flex_nav.behavior.{info.name}")
        for _, cls in inspect.getmembers(module, inspect.isclass):
            is_leaf_state = issubclass(cls, State) and cls is not State and not issubclass(cls, Container)
            if is_leaf_state and cls.__module__.startswith("flex_nav.behavior."):
                classes[cls.__name__] = cls
    return classes


def test_every_state_class_of_the_package_has_sample_params():
    assert set(package_state_classes()) == set(SAMPLE_PARAMS)


@pytest.mark.parametrize("name", sorted(SAMPLE_PARAMS))
def test_state_class_documents_exactly_its_params_keys_and_outcomes(name):
    cls = package_state_classes()[name]
    params = SAMPLE_PARAMS[name]
    assert check_state_doc(cls, cls(**params), params) == []


def test_parser_reads_all_item_kinds_and_continuations():
    doc = parse_state_doc(
        """Moves the robot.

        Second paragraph of the description.

        -- distance_m  float  [m] How far; negative
                              drives backwards.
        -- speed       float  [m/s] How fast.

        ># pose  Pose  Where we start.
        #> moved  float  [m] Distance actually moved.

        <= done     Arrived.
        <= failed   Blocked or timed out.
        """
    )
    assert doc.description == "Moves the robot.\n\nSecond paragraph of the description."
    assert [(p.name, p.type, p.text) for p in doc.params] == [
        ("distance_m", "float", "[m] How far; negative drives backwards."),
        ("speed", "float", "[m/s] How fast."),
    ]
    assert [(i.name, i.type) for i in doc.inputs] == [("pose", "Pose")]
    assert [(o.name, o.type, o.text) for o in doc.outputs] == [("moved", "float", "[m] Distance actually moved.")]
    assert [(o.name, o.text) for o in doc.outcomes] == [("done", "Arrived."), ("failed", "Blocked or timed out.")]


def test_parser_rejects_malformed_items():
    with pytest.raises(ConfigError, match=r"Bad docstring line 3: '-- speed' needs a type and a text"):
        parse_state_doc("Bad.\n\n-- speed\n", "Bad")
    with pytest.raises(ConfigError, match=r"line 4: text after the items must be an indented continuation"):
        parse_state_doc("Bad.\n\n<= done  ok\nstray text\n", "Bad")


def test_check_reports_each_kind_of_mismatch():
    class Sloppy(State):
        """Does things.

        -- speed  float  How fast.

        ># goal  Pose  Where.

        <= done  Finished.
        """

        def __init__(self, speed: float, timeout_s: float = 1.0) -> None:
            super().__init__(outcomes=["done", "failed"], output_keys=["result"])

        def execute(self, userdata):
            return "done"

    problems = check_state_doc(Sloppy, Sloppy(1.0), {"speed": 1.0})
    assert problems == [
        "Sloppy: documented constructor parameters (--) ['speed'] differ from the real ones ['speed', 'timeout_s']",
        "Sloppy: documented input keys (>#) ['goal'] differ from the real ones []",
        "Sloppy: documented output keys (#>) [] differ from the real ones ['result']",
        "Sloppy: documented outcomes (<=) ['done'] differ from the real ones ['done', 'failed']",
    ]
    assert constructor_params(Sloppy) == ["speed", "timeout_s"]
