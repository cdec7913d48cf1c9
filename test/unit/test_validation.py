"""flex_nav.validation: the one set of parameter checks (number, integer, boolean, text, name, choice), and the
places that use it - states, simulator files, ROS parameters, planner and pure pursuit parameters - accepting and
refusing the same values, each message naming the owner, the parameter, the bad value and what is valid."""

from __future__ import annotations

import math
from typing import Any, Dict

import pytest
import rospy

import flex_nav_states.validation as state_validation
from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.planning.planner import PlannerParams
from flex_nav.ros import params
from flex_nav_sim.yaml_fields import Fields

MISSING = object()


@pytest.mark.parametrize(
    ("value", "rules", "message"),
    [
        ("fast", {}, "Owner: speed must be a finite number [m/s], got 'fast'"),
        (True, {}, "Owner: speed must be a finite number [m/s], got True"),
        (math.nan, {}, "Owner: speed must be a finite number [m/s], got nan"),
        (math.inf, {"maximum": 1.0}, "Owner: speed must be a finite number [m/s], got inf"),
        (0.0, {"positive": True}, "Owner: speed must be > 0 [m/s], got 0.0"),
        (-2, {"minimum": -1.0}, "Owner: speed must be >= -1.0 [m/s], got -2"),
        (20.0, {"positive": True, "maximum": 1.0}, "Owner: speed must be <= 1.0 [m/s], got 20.0"),
    ],
)
def test_number_names_owner_parameter_value_rule_and_unit(value: Any, rules: Dict[str, Any], message: str) -> None:
    with pytest.raises(ConfigError) as info:
        validation.number("Owner", "speed", value, unit="[m/s]", **rules)
    assert str(info.value) == message


def test_number_returns_a_float_and_accepts_the_bounds_themselves() -> None:
    assert validation.number("o", "n", 1, minimum=1.0, maximum=1.0) == 1.0
    assert isinstance(validation.number("o", "n", 3), float)
    assert validation.number("o", "n", -5.5) == -5.5  # no rule but finite


@pytest.mark.parametrize(
    ("value", "bounds", "rule"),
    [
        (True, {}, "must be an integer"),
        (2.0, {}, "must be an integer"),
        (300, {"minimum": 1, "maximum": 255}, "must be an integer in 1..255"),
        (-1, {"minimum": 0}, "must be an integer >= 0"),
        (9, {"maximum": 8}, "must be an integer <= 8"),
    ],
)
def test_integer_refuses_bools_floats_and_values_out_of_range(value: Any, bounds: Dict[str, int], rule: str) -> None:
    with pytest.raises(ConfigError, match=f"^o: n {rule}, got {value!r}$"):
        validation.integer("o", "n", value, **bounds)
    assert validation.integer("o", "n", 7, minimum=7, maximum=7) == 7


def test_boolean_text_name_choice_and_names() -> None:
    assert validation.boolean("o", "flag", False) is False
    with pytest.raises(ConfigError, match=r"^o: flag must be true or false, got 1$"):
        validation.boolean("o", "flag", 1)
    with pytest.raises(ConfigError, match=r"^o: label must be a string, got 3$"):
        validation.text("o", "label", 3)
    assert validation.name("o", "topic", "/robot1/odom") == "/robot1/odom"
    assert validation.name("o", "topic", "", allow_empty=True) == ""
    with pytest.raises(ConfigError, match="o: topic must not be empty"):
        validation.name("o", "topic", "")
    with pytest.raises(ConfigError, match="o: topic must not contain blanks"):
        validation.name("o", "topic", "cmd vel")
    with pytest.raises(ConfigError, match="o: topic: 'a//b' is not a legal ROS name"):
        validation.name("o", "topic", "a//b")
    with pytest.raises(ConfigError, match=r"^o: mode 'fast' is not valid \(valid: slow, careful\)$"):
        validation.choice("o", "mode", "fast", ("slow", "careful"))
    with pytest.raises(ConfigError, match="o: zones repeats left"):
        validation.names("o", "zones", ["left", "right", "left"])


def test_a_long_bad_value_is_cut_in_the_message() -> None:
    with pytest.raises(ConfigError) as info:
        validation.number("o", "n", list(range(100)))
    assert str(info.value).endswith("...") and len(str(info.value)) < 120


def test_the_state_library_uses_the_same_checks() -> None:
    for check in ("number", "integer", "boolean", "text", "name", "names", "choice"):
        assert getattr(state_validation, check) is getattr(validation, check)


def test_planner_and_pure_pursuit_parameters_go_through_the_shared_checks() -> None:
    with pytest.raises(ConfigError, match=r"^planner: start_escape must be >= 0.0 \[m\], got -1.0$"):
        PlannerParams(start_escape=-1.0)
    with pytest.raises(ConfigError, match=r"^planner: lethal_cost must be an integer in 1..255, got 300$"):
        PlannerParams(lethal_cost=300)
    with pytest.raises(ConfigError, match=r"^planner: diagonal_factor must be <= 2.0, got 3.0$"):
        PlannerParams(diagonal_factor=3.0)
    with pytest.raises(ConfigError, match=r"^pure pursuit: lookahead_dist must be > 0, got 0.0$"):
        PurePursuitParams(lookahead_dist=0.0)
    with pytest.raises(ConfigError, match=r"^pure pursuit: cost_scaling_gain must be <= 1.0, got 1.5$"):
        PurePursuitParams(cost_scaling_gain=1.5)
    with pytest.raises(ConfigError, match=r"^pure pursuit: allow_unknown must be true or false, got 1$"):
        PurePursuitParams(allow_unknown=1)  # type: ignore[arg-type]
    with pytest.raises(ConfigError, match=r"^pure pursuit: approach_velocity_scaling_dist must be >= 0.0"):
        PurePursuitParams(approach_velocity_scaling_dist=-0.1)


def test_simulator_files_go_through_the_shared_checks() -> None:
    fields = Fields({"drive": {"wheel_radius": 0, "rate": 2.5, "on": "yes"}}, "robot.yaml").sub("drive")
    with pytest.raises(ConfigError, match=r"^robot.yaml: drive.wheel_radius must be > 0 \[m\], got 0$"):
        fields.positive("wheel_radius", unit="[m]")
    with pytest.raises(ConfigError, match=r"^robot.yaml: drive.rate must be an integer >= 1, got 2.5$"):
        fields.integer("rate", minimum=1)
    with pytest.raises(ConfigError, match=r"^robot.yaml: drive.on must be true or false, got 'yes'$"):
        fields.boolean("on")
    with pytest.raises(ConfigError, match=r"^robot.yaml: pose\[1\] must be a finite number, got 'x'$"):
        Fields({"pose": [1.0, "x"]}, "robot.yaml").pose("pose")


def serve(monkeypatch: pytest.MonkeyPatch, values: Dict[str, Any]) -> None:
    def get_param(name: str, default: Any = MISSING) -> Any:
        return values.get(name, default)

    monkeypatch.setattr(rospy, "get_param", get_param)
    monkeypatch.setattr(rospy, "resolve_name", lambda name: "/node/" + name.lstrip("~"))


def test_ros_parameters_keep_their_wording_and_their_lenience(monkeypatch: pytest.MonkeyPatch) -> None:
    serve(monkeypatch, {"~timeout": -1.0, "~rate": "0.5", "~nan": math.nan, "~cost": 300, "~flag": 1, "~n": True})
    with pytest.raises(ConfigError, match=r"^parameter /node/timeout = -1.0 is outside \[0.0, 3600.0\]$"):
        params.param_float("~timeout", minimum=0.0, maximum=3600.0)
    with pytest.raises(ConfigError, match=r"^parameter /node/nan = nan is outside \[-inf, inf\]$"):
        params.param_float("~nan")
    assert params.param_float("~rate") == 0.5  # what float() takes counts, as before
    with pytest.raises(ConfigError, match=r"^parameter /node/cost = 300 is outside \[1, 255\]$"):
        params.param_int("~cost", minimum=1, maximum=255)
    with pytest.raises(ConfigError, match=r"^parameter /node/n = True is not an integer$"):
        params.param_int("~n")
    with pytest.raises(ConfigError, match=r"^parameter /node/flag = 1 is not true/false$"):
        params.param_bool("~flag")
    with pytest.raises(ConfigError, match=r"^required parameter /node/missing is not set$"):
        params.param_float("~missing")
