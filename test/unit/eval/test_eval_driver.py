"""The evaluation driver (``python -m flex_nav.apps.eval.scenarios``) without a simulator: its plan of runs, the
result each run leaves behind, ``--resume`` and bad arguments. ``run_one`` is replaced by a function that
writes what ``scenario_run`` would print, so no master is needed."""

import json
from typing import List, Tuple

import pytest

from flex_nav.apps.eval import scenarios
from flex_nav.apps.eval.metrics import RunResult


def fake_run_one(calls):
    def run_one(args, world, behavior, seed, out):
        calls.append((world, behavior, seed))
        out.mkdir(parents=True, exist_ok=True)
        result = RunResult(world=world, behavior=behavior, seed=seed, success=seed == 0, time_s=10.0 + seed)
        (out / "result.json").write_text(json.dumps(result.to_dict()))
        return result
    return run_one


def test_every_scenario_behavior_and_seed_runs_once_and_resume_keeps_them(tmp_path, monkeypatch, capsys):
    calls: List[Tuple[str, str, int]] = []  # (world, behavior, seed) of each run
    monkeypatch.setattr(scenarios, "run_one", fake_run_one(calls))
    argv = ["--scenarios", "s1_light_box_door,s5_heavy_box_short_route", "--seeds", "2", "--out", str(tmp_path)]
    assert scenarios.main(argv) == 0
    assert len(calls) == 2 * 2 * 2 and len(set(calls)) == 8
    rows = (tmp_path / "results.csv").read_text().strip().splitlines()
    assert len(rows) == 1 + 8
    assert "s5_heavy_box_short_route" in (tmp_path / "results.md").read_text()
    calls.clear()
    assert scenarios.main([*argv, "--resume"]) == 0
    assert calls == []  # every run had its result.json
    assert scenarios.main([*argv, "--seeds", "3", "--resume"]) == 0
    assert sorted(calls) == [("s1_light_box_door", b, 2) for b in scenarios.BEHAVIORS] + [
        ("s5_heavy_box_short_route", b, 2) for b in scenarios.BEHAVIORS]
    assert len((tmp_path / "results.csv").read_text().strip().splitlines()) == 1 + 12
    capsys.readouterr()


def test_a_run_without_result_is_reported_and_fails_the_evaluation(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(scenarios, "run_one", lambda *args: None)
    assert scenarios.main(["--scenarios", "s1_light_box_door", "--seeds", "1", "--out", str(tmp_path)]) == 1
    assert "run did not produce a result: s1_light_box_door move_base_like seed 0" in capsys.readouterr().err


@pytest.mark.parametrize("argv, needle", [
    (["--scenarios", "s7_nothing"], "s7_nothing"),
    (["--seeds", "0"], "--seeds 0"),
    (["--behaviors", "push_or_avoid,move_base"], "move_base_like"),  # the message lists the valid ones
])
def test_bad_arguments_name_the_value(argv, needle, capsys):
    with pytest.raises(SystemExit) as stop:
        scenarios.parse_args(argv)
    assert stop.value.code == 2
    assert needle in capsys.readouterr().err
