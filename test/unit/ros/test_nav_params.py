"""planner_params reads every PlannerParams field it accepts: a name reject_unknown lets through but the
reader ignored would keep its default without a word (``diagonal_factor`` did). rospy.get_param is served
from a dict, so no master is needed."""

import dataclasses
from typing import Any, Dict

import pytest
import rospy

from flex_nav.exceptions import ConfigError
from flex_nav.nav.planning.planner import PlannerParams
from flex_nav.ros.nav_params import planner_params

MISSING = object()


def serve(monkeypatch: pytest.MonkeyPatch, planner: Dict[str, Any]) -> None:
    def get_param(name: str, default: Any = MISSING) -> Any:
        if name == "~planner":
            return dict(planner)
        key = name[len("~planner/"):]
        return planner.get(key, default)

    monkeypatch.setattr(rospy, "get_param", get_param)
    monkeypatch.setattr(rospy, "resolve_name", lambda name: "/node/" + name.lstrip("~"))


def changed(value: Any) -> Any:
    """A valid value different from a default (every field's range admits these)."""
    if isinstance(value, bool):
        return not value
    if isinstance(value, int):
        return value - 1
    return value * 1.1 if value else 0.25


def test_every_accepted_planner_parameter_is_read(monkeypatch: pytest.MonkeyPatch) -> None:
    defaults = PlannerParams()
    given = {f.name: changed(getattr(defaults, f.name)) for f in dataclasses.fields(PlannerParams)}
    serve(monkeypatch, given)
    read = planner_params()
    ignored = [name for name, value in given.items() if getattr(read, name) != pytest.approx(value)]
    assert not ignored, f"accepted but not read: {ignored}"


def test_a_bad_planner_value_names_the_namespace(monkeypatch: pytest.MonkeyPatch) -> None:
    serve(monkeypatch, {"diagonal_factor": 3.0})
    with pytest.raises(ConfigError, match=r"~planner/.*diagonal_factor"):
        planner_params()
