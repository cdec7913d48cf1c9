"""System test of mapping end to end: the explore behavior maps the lab from scratch on flex_nav's mapper
(``python -m flex_nav.apps.mapping_run``), the saved map is loaded by flex_nav's map server and the demo
(flex_planner, the localizer, 4 goals, bumper recovery) navigates on it. Each run starts and stops its own
private master and every process."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest
from harness import run_command_bounded, system_env

from flex_nav.nav.costmap.map_io import load_map

RUN_TIMEOUT_S = 600.0  # [s] wall bound of one run (the lab is explored in ~60-70 s of wall time here)
SUMMARY = re.compile(r"goals reached: (?P<reached>\d+)/(?P<total>\d+), bumper recoveries: (?P<recoveries>\d+)")


@pytest.mark.ros
def test_explore_the_lab_save_reload_and_navigate_on_the_map(tmp_path: Path) -> None:
    mapped = tmp_path / "mapping"
    outcome = run_command_bounded(
        [sys.executable, "-m", "flex_nav.apps.mapping_run", "--world", "lab", "--out", str(mapped), "--timeout", "480"],
        env=system_env(), timeout_s=RUN_TIMEOUT_S,
    )
    assert outcome.returncode == 0, outcome.output[-6000:]
    metrics = json.loads((mapped / "metrics.json").read_text(encoding="utf-8"))
    assert metrics["outcome"] == "finished" and metrics["map_saved"], metrics
    # the map targets (>= 97 % of the observed cells agree, walls within a cell, >= 95 % explored, ATE <= 5 cm),
    # measured 97.2-99.5 % / 0 cm / 98.9-99.7 % / 1.4-2.9 cm over nine runs: the agreement is asserted with a point
    # of margin for run-to-run variation (the README reports the runs)
    assert metrics["map"]["agree"] >= 0.96, metrics["map"]
    assert metrics["map"]["wall_median_cm"] <= 5.0, metrics["map"]
    assert metrics["map"]["explored"] >= 0.95, metrics["map"]
    # the trajectory target is after optimisation (the final graph's keyframes); the live estimates, which the
    # navigation used, include the drift later loop closures corrected (11.3 cm in one of ~20 runs): they are held
    # to the clearance explore keeps beyond the base (robot_radius_m 0.3 m - the TurtleBot's 0.177 m)
    # no collisions with what the lidar sees: the only thing touched may be the low step (5 cm, below every
    # lidar, in no map), which the bumper finds and the recovery goes around
    assert set(metrics["touched"]) <= {"low_step"}, metrics["touched"]
    assert metrics["keyframe_pairs"] >= 50, metrics
    assert metrics["ate_optimised_cm_aligned"] <= 5.0, metrics
    assert metrics["ate_cm_aligned"] is not None and metrics["ate_cm_aligned"] <= 12.0, metrics
    grid = load_map(mapped / "map.yaml")  # a map_server pair flex_nav's loader reads
    assert grid.resolution == pytest.approx(0.05)
    assert (mapped / "map.png").stat().st_size > 10_000
    assert (mapped / "map.posegraph").stat().st_size > 10_000
    assert "/SaveMap --saved--> MapSaved" in outcome.output and "/CheckSaved --met--> finished" in outcome.output

    navigated = run_command_bounded(
        [sys.executable, "-m", "flex_nav.apps.nav_demo", "--map", str(mapped / "map.yaml"), "--out",
         str(tmp_path / "demo"), "--timeout", "300"],
        env=system_env(), timeout_s=RUN_TIMEOUT_S,
    )
    summary = SUMMARY.search(navigated.output)
    assert summary is not None, navigated.output[-5000:]
    assert navigated.returncode == 0, navigated.output[-5000:]
    assert summary["reached"] == summary["total"] == "4", navigated.output[-5000:]
    assert int(summary["recoveries"]) >= 1, "the low step is not in the map either: the bumper finds it"
    print(f"mapping: {json.dumps({k: metrics[k] for k in ('sim_time_s', 'distance_m', 'bumper_contacts')})}, "
          f"map {metrics['map']}, ATE optimised {metrics['ate_optimised_cm_aligned']:.1f} cm, live "
          f"{metrics['ate_cm_aligned']:.1f} cm; demo on the map: {summary.group(0)}")
