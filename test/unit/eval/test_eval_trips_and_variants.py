"""Issue 28's evaluation additions without a simulator: trips (``scenario_run --trips``), behavior parameter
overrides, world files as scenarios (the hidden variants) with their own static map, and the trip times in the
results (JSON and CSV)."""

import json
import math
from pathlib import Path

import pytest
import yaml

from flex_nav.apps import scenario_run
from flex_nav.apps.eval import scenarios
from flex_nav.apps.eval.metrics import RunResult
from flex_nav.apps.eval.table import to_csv
from flex_nav.apps.nav_demo import map_of_world, world_map
from flex_nav_sim.world import load_world

VARIANTS = Path(__file__).resolve().parents[2] / "data" / "issue28" / "variants"
START, GOAL = (1.0, 0.5, 0.0), (9.0, 0.5, 0.0)


def test_trips_go_to_the_goal_and_back_to_the_start_between_them():
    assert scenario_run.trip_goals(GOAL, START, 1) == [("goal", GOAL)]
    assert scenario_run.trip_goals(GOAL, START, 3) == [("goal", GOAL), ("start", START), ("goal", GOAL),
                                                       ("start", START), ("goal", GOAL)]


@pytest.mark.parametrize("not_before_s, sim_s, expected_s", [
    (0.0, 3.0, scenario_run.WORLD_START_S),  # up early: the fixed start
    (0.0, scenario_run.WORLD_START_S - 1.5, scenario_run.WORLD_START_S),
    (0.0, scenario_run.WORLD_START_S - 0.5, scenario_run.WORLD_START_S + 2.0),  # nearly there: the next grid point
    (0.0, 25.3, 28.0),  # up late: the grid point half a grid ahead
    (31.0, 3.0, 32.0)])  # not before a later time
def test_the_world_starts_at_one_simulated_time_when_the_system_is_up_by_then(not_before_s, sim_s, expected_s):
    assert scenario_run.world_start_s(not_before_s, sim_s) == pytest.approx(expected_s)


def test_scenario_run_reads_behavior_parameters_as_yaml_values():
    args = scenario_run.parse_args(["--world", "s5_heavy_box_short_route", "--behavior", "push_or_avoid",
                                    "--out", "/tmp/x", "--trips", "2", "--behavior-param", "remember_heavy=true",
                                    "--behavior-param", "max_looks=3"])
    assert args.trips == 2
    assert args.behavior_params == {"remember_heavy": True, "max_looks": 3}


def test_scenario_run_reads_yield_parameters_by_name():
    args = scenario_run.parse_args(["--world", "s6_people_crossing", "--behavior", "push_or_avoid", "--out", "/tmp/x",
                                    "--yield-planner", "checked", "--yield-param", "check_moving_gap_m=0.35"])
    assert args.yield_params == {"check_moving_gap_m": 0.35}


@pytest.mark.parametrize("argv, needle", [
    (["--trips", "0"], "--trips must be at least 1, got 0"),
    (["--behavior-param", "remember_heavy"], "KEY=VALUE, got 'remember_heavy'"),
    (["--yield-param", "check_gap=0.3"], "'check_gap' is not valid (valid: accel_mps2,"),
    (["--yield-param", "0.3"], "--yield-param takes KEY=VALUE, got '0.3'"),
])
def test_scenario_run_bad_arguments_name_the_value(argv, needle, capsys):
    with pytest.raises(SystemExit):
        scenario_run.parse_args(["--world", "s1_light_box_door", "--behavior", "push_or_avoid", "--out", "/tmp/x",
                                 *argv])
    assert needle in capsys.readouterr().err


def test_trip_times_survive_json_and_csv():
    result = RunResult("s5", "push_or_avoid", 0, success=False, time_s=110.0, trip_times_s=[110.0, math.nan])
    data = json.loads(json.dumps(result.to_dict()))
    assert data["trip_times_s"] == [110.0, None]
    again = RunResult.from_dict(data)
    assert again.trip_times_s[0] == 110.0 and math.isnan(again.trip_times_s[1])
    assert RunResult.from_dict({k: v for k, v in data.items() if k != "trip_times_s"}).trip_times_s == []
    row = to_csv([result]).splitlines()[1]
    assert "110.0;," in row  # the list in one cell, the unreached trip empty


def test_a_world_file_is_navigated_on_its_own_static_map(tmp_path):
    shipped = map_of_world("s1_light_box_door", tmp_path)
    assert shipped == world_map("s1_light_box_door") and not (tmp_path / "map").exists()
    variant = map_of_world(str(VARIANTS / "h1_light_box_door.yaml"), tmp_path)
    assert variant == tmp_path / "map" / "h1_light_box_door.yaml" and variant.is_file()
    meta = yaml.safe_load(variant.read_text())
    shipped_meta = yaml.safe_load(shipped.read_text())
    assert meta["resolution"] == 0.05
    # the variant's room is 4.5 m deep, S1's 4 m: not S1's map under another name
    assert (tmp_path / "map" / "h1_light_box_door.pgm").read_bytes() != (shipped.parent /
                                                                         shipped_meta["image"]).read_bytes()


def test_every_variant_loads_and_differs_from_its_scenario():
    names = sorted(p.stem for p in VARIANTS.glob("h*.yaml"))
    assert len(names) == 6
    for name, scenario in zip(names, scenarios.SCENARIOS):
        variant = load_world(str(VARIANTS / f"{name}.yaml"))
        shipped = load_world(scenario)
        assert name[1] == scenario[1]  # h1 varies s1, ...
        assert variant.goals["goal"] != shipped.goals["goal"] or variant.solids != shipped.solids


def test_the_driver_takes_world_files_and_passes_parameters_to_one_behavior(tmp_path, monkeypatch, capsys):
    commands = []

    class Done:
        stdout = "RESULT " + json.dumps(RunResult("h1_light_box_door", "push_or_avoid", 0).to_dict()) + "\n"

    def fake_run(command, **_kwargs):
        commands.append(command)
        return Done()

    monkeypatch.setattr(scenarios.subprocess, "run", fake_run)
    world = str(VARIANTS / "h1_light_box_door.yaml")
    assert scenarios.main(["--scenarios", world, "--seeds", "1", "--workers", "1", "--out", str(tmp_path),
                           "--behavior-param", "push_or_avoid:fuse_lidar=true",
                           "--yield-param", "check_moving_gap_m=0.35"]) == 0
    by_behavior = {c[c.index("--behavior") + 1]: c for c in commands}
    assert by_behavior["push_or_avoid"][-4:] == ["--behavior-param", "fuse_lidar=true",
                                                 "--yield-param", "check_moving_gap_m=0.35"]
    assert "--behavior-param" not in by_behavior["move_base_like"]
    assert by_behavior["move_base_like"][by_behavior["move_base_like"].index("--world") + 1] == world
    assert (tmp_path / "h1_light_box_door-push_or_avoid-0" / "result.json").is_file()
    capsys.readouterr()


@pytest.mark.parametrize("argv, needle", [
    (["--scenarios", "/nowhere/h9.yaml"], "'/nowhere/h9.yaml' does not exist"),
    (["--behavior-param", "fuse_lidar=true"], "BEHAVIOR:KEY=VALUE"),
    (["--behaviors", "push_or_avoid", "--behavior-param", "move_base_like:x=1"], "one of push_or_avoid"),
])
def test_driver_bad_arguments_name_the_value(argv, needle, capsys):
    with pytest.raises(SystemExit):
        scenarios.parse_args(argv)
    assert needle in capsys.readouterr().err
