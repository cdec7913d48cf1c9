"""The evaluation driver (``python -m flex_nav.apps.eval.scenarios``) without a simulator: its plan of runs, the
result each run leaves behind, ``--resume`` and bad arguments. ``run_one`` is replaced by a function that
writes what ``scenario_run`` would print, so no master is needed."""

import json
import socket
import time
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
    (["--workers", "0"], "--workers 0"),
])
def test_bad_arguments_name_the_value(argv, needle, capsys):
    with pytest.raises(SystemExit) as stop:
        scenarios.parse_args(argv)
    assert stop.value.code == 2
    assert needle in capsys.readouterr().err


def test_a_run_without_result_or_whose_worker_was_lost_is_tried_once_more_and_reported(tmp_path, monkeypatch,
                                                                                        capsys):
    attempts: List[Tuple[str, int]] = []
    succeed = fake_run_one([])

    def flaky(args, world, behavior, seed, out):
        attempts.append((behavior, seed))
        first = attempts.count((behavior, seed)) == 1
        if first and behavior == "move_base_like":
            return None  # the run process crashed
        if first and behavior == "push_or_avoid":
            raise ConnectionError("worker lost")  # what a future of a lost worker raises
        return succeed(args, world, behavior, seed, out)

    monkeypatch.setattr(scenarios, "run_one", flaky)
    argv = ["--scenarios", "s1_light_box_door", "--seeds", "1", "--out", str(tmp_path)]
    assert scenarios.main(argv) == 0
    assert sorted(attempts) == [("move_base_like", 0)] * 2 + [("push_or_avoid", 0)] * 2
    assert len((tmp_path / "results.csv").read_text().strip().splitlines()) == 1 + 2
    err = capsys.readouterr().err
    assert "run tried again: s1_light_box_door move_base_like seed 0: no result" in err
    assert "run tried again: s1_light_box_door push_or_avoid seed 0: ConnectionError: worker lost" in err


def test_workers_run_at_the_same_time_and_the_table_keeps_the_plan_order(tmp_path, monkeypatch, capsys):
    spans: List[Tuple[float, float]] = []
    succeed = fake_run_one([])

    def slow(args, world, behavior, seed, out):
        start = time.monotonic()
        time.sleep(0.3 if seed == 0 else 0.05)  # seed 0 ends last
        spans.append((start, time.monotonic()))
        return succeed(args, world, behavior, seed, out)

    monkeypatch.setattr(scenarios, "run_one", slow)
    argv = ["--scenarios", "s1_light_box_door", "--behaviors", "push_or_avoid", "--seeds", "2", "--workers", "2",
            "--out", str(tmp_path)]
    assert scenarios.main(argv) == 0
    (a_start, a_end), (b_start, b_end) = spans
    assert a_start < b_end and b_start < a_end  # they overlapped
    seeds = [line.split(",")[2] for line in (tmp_path / "results.csv").read_text().strip().splitlines()[1:]]
    assert seeds == ["0", "1"]
    assert "2 run(s) on 2 local worker(s)" in capsys.readouterr().out


def test_durations_of_an_earlier_table_start_the_longest_runs_first(tmp_path, monkeypatch, capsys):
    calls: List[Tuple[str, str, int]] = []
    monkeypatch.setattr(scenarios, "run_one", fake_run_one(calls))
    earlier = tmp_path / "earlier.csv"
    earlier.write_text("world,behavior,seed,success,time_s,note\n"
                       "s1_light_box_door,move_base_like,0,True,40.0,\n"
                       "s1_light_box_door,push_or_avoid,0,True,45.0,\n"
                       "s5_heavy_box_short_route,move_base_like,0,True,88.0,\n"
                       "s5_heavy_box_short_route,push_or_avoid,0,False,,goal given up\n")  # ran to the limit
    argv = ["--scenarios", "s1_light_box_door,s5_heavy_box_short_route,s6_people_crossing", "--seeds", "1",
            "--workers", "1", "--out", str(tmp_path / "out"), "--durations", str(earlier)]
    assert scenarios.main(argv) == 0
    assert calls == [  # not arrived and unknown (s6) count as the 150 s limit, in the plan's order; then by time
        ("s5_heavy_box_short_route", "push_or_avoid", 0), ("s6_people_crossing", "move_base_like", 0),
        ("s6_people_crossing", "push_or_avoid", 0), ("s5_heavy_box_short_route", "move_base_like", 0),
        ("s1_light_box_door", "push_or_avoid", 0), ("s1_light_box_door", "move_base_like", 0)]
    worlds = [line.split(",")[0] for line in (tmp_path / "out" / "results.csv").read_text().splitlines()[1:]]
    assert worlds[0] == "s1_light_box_door" and worlds[-1] == "s6_people_crossing"  # the table keeps plan order
    not_a_table = tmp_path / "notes.csv"
    not_a_table.write_text("a,b\n1,2\n")
    assert scenarios.main([*argv[:-1], str(not_a_table)]) == 2
    assert "no column" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        scenarios.parse_args(["--durations", str(tmp_path / "missing.csv")])


def test_an_unreachable_cluster_is_named_and_nothing_runs(tmp_path, monkeypatch, capsys):
    calls: List[Tuple[str, str, int]] = []
    monkeypatch.setattr(scenarios, "run_one", fake_run_one(calls))
    monkeypatch.setattr(scenarios, "CLUSTER_CONNECT_TIMEOUT_S", 1.0)
    with socket.socket() as sock:  # a port nobody listens on
        sock.bind(("127.0.0.1", 0))
        address = f"tcp://127.0.0.1:{sock.getsockname()[1]}"
    assert scenarios.main(["--scenarios", "s1_light_box_door", "--seeds", "1", "--cluster", address,
                           "--out", str(tmp_path)]) == 2
    assert f"cannot reach the Dask scheduler at '{address}'" in capsys.readouterr().err
    assert calls == []
