"""System tests of obstacle-aware navigation end to end (issue 7): simulator with camera + obstacle classifier +
map server + servers + controllers + behavior runner on simulated time, one scenario run each
(``python -m flex_nav.apps.scenario_run``, its own private master), for scenarios S1 and S3 with the
move_base-like baseline, S5 with both behaviors (push_or_avoid twice, the second trip with the obstacle memory
only); S6 (people walking across) with push_or_avoid is test_social_distance_system.py's run; S1 and S3
with push_or_avoid run at the same time through the evaluation driver on a two-worker Dask cluster
(test_scenarios_cluster_system.py). Speeds are not asserted here (the evaluation command measures them)."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Sequence

import pytest
from harness import run_command_bounded, system_env

RUN_TIMEOUT_S = 300.0  # [s] wall bound of one run
SIM_LIMIT_S = 100.0  # [s] simulated time bound of the goal


def scenario(out: Path, world: str, behavior: str, sim_limit_s: float = SIM_LIMIT_S, extra: Sequence[str] = (),
             timeout_s: float = RUN_TIMEOUT_S) -> dict:
    outcome = run_command_bounded(
        [sys.executable, "-m", "flex_nav.apps.scenario_run", "--world", world, "--behavior", behavior,
         "--rtf", "2.0", "--sim-limit", str(sim_limit_s), "--timeout", str(timeout_s - 30.0), "--out", str(out),
         *extra],
        env=system_env(), timeout_s=timeout_s,
    )
    lines = [line for line in outcome.output.splitlines() if line.startswith("RESULT ")]
    assert outcome.returncode == 0 and lines, f"no result (exit {outcome.returncode}):\n{outcome.output[-5000:]}"
    result: dict = json.loads(lines[-1][len("RESULT "):])
    result["output"] = outcome.output
    assert (out / "run.png").stat().st_size > 5_000
    return result


@pytest.mark.ros
def test_s1_move_base_like_never_pushes(tmp_path: Path) -> None:
    result = scenario(tmp_path, "s1_light_box_door", "move_base_like")
    assert result["pushes_tried"] == 0
    assert result["people_contacts"] == 0


@pytest.mark.ros
def test_s3_move_base_like_never_touches_the_person_in_the_door(tmp_path: Path) -> None:
    result = scenario(tmp_path, "s3_person_in_door", "move_base_like")
    assert result["people_contacts"] == 0, result["output"][-5000:]
    assert result["min_people_clearance_m"] is not None and result["min_people_clearance_m"] > 0.0
    assert result["pushes_tried"] == 0


@pytest.mark.ros
def test_s5_heavy_box_move_base_like(tmp_path: Path) -> None:
    result = scenario(tmp_path, "s5_heavy_box_short_route", "move_base_like", sim_limit_s=160.0)  # detour ~20 m
    assert result["people_contacts"] == 0
    assert result["success"], result["output"][-5000:]  # it takes the detour north of the block
    assert result["pushes_tried"] == 0  # the baseline never pushes


@pytest.mark.ros
def test_s5_twice_push_or_avoid_remembers_the_heavy_box(tmp_path: Path) -> None:
    """Issue 28's obstacle memory: the first trip probes the box (the push stalls, the robot backs off, marks it
    and takes the detour); back at the start both costmaps are cleared, so only the memory knows the box; the
    second trip plans the detour at once and never pushes."""
    result = scenario(tmp_path, "s5_heavy_box_short_route", "push_or_avoid", sim_limit_s=160.0,
                      extra=["--trips", "2", "--clear-between-trips", "--behavior-param", "remember_heavy=true"],
                      timeout_s=2 * RUN_TIMEOUT_S)
    output = result["output"]
    assert result["success"], output[-5000:]
    assert result["people_contacts"] == 0
    assert "/Push --failed--> BackOffHeavy" in output and "/ReplanAround --planned--> Follow" in output
    assert "costmaps cleared before trip 2" in output and "cleared before trip 2:" not in output  # no problem
    assert result["pushes_tried"] == 1 and result["pushes_succeeded"] == 0, output[-5000:]  # trip 2: no push
    first_s, second_s = result["trip_times_s"]
    assert second_s < first_s - 15.0, output[-5000:]  # no way to the box and back (~12 s) and no probe
