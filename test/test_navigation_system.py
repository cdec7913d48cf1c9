"""System tests of Flexible Navigation end to end: simulator + map server + servers + controllers + behavior
runner against a real master on simulated time, driven by the demo runner (``python -m flex_nav.apps.nav_demo``)
or by the operator scenario script. Each test starts and stops its own private master and every process."""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path
from typing import Tuple

import pytest
from harness import REPO_ROOT, run_command_bounded, system_env

SUMMARY = re.compile(
    r"goals reached: (?P<reached>\d+)/(?P<total>\d+), bumper recoveries: (?P<recoveries>\d+), "
    r"sim time: (?P<sim>[\d.]+) s, wall time: (?P<wall>[\d.]+) s"
)
LOCALIZATION = re.compile(r"localization: median (?P<median>[\d.]+) cm, p95 (?P<p95>[\d.]+) cm, max (?P<max>[\d.]+) cm "
                          r"\(heading median (?P<heading>[\d.]+) deg")
RUN_TIMEOUT_S = 420.0  # [s] wall bound of one system run (a lap takes ~45-80 s of wall time here)
REPLAY_BAG_S = 20.0  # [s] of the demo's bag replayed (the first goal is planned by then)


def run_demo(out: Path, *args: str) -> Tuple[int, str, re.Match]:
    outcome = run_command_bounded(
        [sys.executable, "-m", "flex_nav.apps.nav_demo", "--out", str(out), "--timeout", "300", *args],
        env=system_env(), timeout_s=RUN_TIMEOUT_S,
    )
    match = SUMMARY.search(outcome.output)
    assert match is not None, f"no summary line (exit {outcome.returncode}):\n{outcome.output[-5000:]}"
    return outcome.returncode, outcome.output, match


@pytest.mark.ros
@pytest.mark.parametrize("profile", ["turtlebot2", "create", "turtlebot4"])
def test_flex_planner_lap_with_bumper_recovery(tmp_path: Path, profile: str, request: pytest.FixtureRequest) -> None:
    out = tmp_path / "demo"  # beside the replay's master (tmp_path / "ros_home")
    code, output, summary = run_demo(out, "--profile", profile)
    assert code == 0, output[-5000:]
    assert summary["reached"] == summary["total"] == "4", output[-5000:]
    assert int(summary["recoveries"]) >= 1, "the low step must be found by the bumper and recovered from"
    assert "BUMPER hit" in output and "/Recovery --done--> CountReplan" in output
    # driven on flex_nav's localizer (the simulator's oracle is off): the accuracy targets on the lap
    error = LOCALIZATION.search(output)
    assert error is not None, output[-3000:]
    assert float(error["median"]) <= 3.0 and float(error["p95"]) <= 8.0, error.group(0)
    assert float(error["heading"]) <= 1.0, error.group(0)
    assert (out / "run.png").stat().st_size > 10_000
    assert (out / "run.bag").stat().st_size > 10_000
    if profile == "turtlebot2":  # the bag replays into RViz: scans placed in map through tf, costmap, plan, footprint
        master = request.getfixturevalue("ros_master")
        replay = run_command_bounded(
            [sys.executable, str(REPO_ROOT / "test" / "system" / "bag_replay_check.py"), str(out / "run.bag"),
             "robot1", str(REPLAY_BAG_S)], env=master.env, timeout_s=REPLAY_BAG_S * 4 + 120.0)
        assert replay.returncode == 0 and "REPLAY PASSED" in replay.output, replay.output[-3000:]


@pytest.mark.ros
def test_move_base_like_baseline_reaches_the_same_goals(tmp_path: Path) -> None:
    # The same lap, low step included: the baseline has no bumper recovery of the navigator, only the base's
    # safety back-off; the contact reaches the costmaps and the 1 Hz replanning goes around the step.
    code, output, summary = run_demo(tmp_path, "--behavior", "move_base_like")
    assert code == 0, output[-5000:]
    assert summary["reached"] == summary["total"] == "4"
    assert "BUMPER hit" in output and "--bumper--> SafetyBackoff" in output
    assert "/Navigate --arrived--> Arrived" in output


@pytest.mark.ros
@pytest.mark.parametrize("behavior", ["multi_level_planner", "create_flex_planner"])
def test_planner_variants_reach_a_goal_past_the_low_step(tmp_path: Path, behavior: str) -> None:
    profile = "create" if behavior.startswith("create") else "turtlebot2"
    code, output, summary = run_demo(tmp_path, "--behavior", behavior, "--profile", profile, "--goals", "g1")
    assert code == 0, output[-5000:]
    assert summary["reached"] == summary["total"] == "1"
    assert "/FlexPlanner/Navigate" in output  # the variant's own Navigate ran


@pytest.mark.ros
def test_three_robots_in_their_namespaces(tmp_path: Path) -> None:
    # three robots are ~30 processes on this 2-core machine: run them in real time
    # one leg each, all at once (robot1 over the low step, robot2 and robot3 on the next legs): with longer runs
    # the robots meet at each other's goals and one sometimes gives a goal up (seen in 1 of 3 two-leg runs)
    code, output, summary = run_demo(tmp_path, "--profiles", "turtlebot2,turtlebot2,create", "--goals-per-robot", "1",
                                     "--rtf", "1")
    assert code == 0, output[-5000:]
    assert summary["reached"] == summary["total"] == "3", output[-5000:]
    for robot in ("robot1", "robot2", "robot3"):
        assert re.search(rf"{robot}: goal 1/1 \(\w+ at [\d.]+, [\d.]+\) reached", output), robot


@pytest.mark.ros
def test_low_autonomy_waits_for_the_operator_and_preempt_stops_the_robot(tmp_path: Path) -> None:
    outcome = run_command_bounded(
        [sys.executable, str(REPO_ROOT / "test" / "system" / "operator_scenario.py"), str(tmp_path)],
        env=system_env(), timeout_s=RUN_TIMEOUT_S,
    )
    assert outcome.returncode == 0, outcome.output[-6000:]
    assert "SCENARIO PASSED" in outcome.output


KIDNAP_AT_S = 35.0  # [s] simulated: near g2 on the lap, about 4 m from the teleport's target
KIDNAP_TO = (4.0, 1.9, 90.0)  # [m, m, deg] between the low step and the island
STOPPED_MPS = 0.02  # [m/s] ground-truth speed counted as standing still


@pytest.mark.ros
def test_kidnapped_robot_is_lost_stops_and_is_found_again(tmp_path: Path) -> None:
    import rosbag  # noqa: PLC0415 - Debian's rosbag, only for the system tests

    world = tmp_path / "lab.yaml"  # the lab (same name, same map) with a teleport mid-lap
    x, y, yaw = KIDNAP_TO
    event = f"{{at: {KIDNAP_AT_S}, action: teleport, target: robot1, pose: [{x}, {y}, {yaw}]}}"
    world.write_text((REPO_ROOT / "sim" / "worlds" / "lab.yaml").read_text() + f"events:\n  - {event}\n")
    _code, output, summary = run_demo(tmp_path / "out", "--world", str(world))
    statuses, truth = [], []
    with rosbag.Bag(str(tmp_path / "out" / "run.bag")) as bag:
        for topic, msg, recorded in bag.read_messages(["/robot1/localizer/status", "/robot1/ground_truth"]):
            if topic.endswith("status"):  # recorded on simulated time (use_sim_time)
                statuses.append((recorded.to_sec(), msg.data))
            else:
                truth.append((msg.header.stamp.to_sec(), msg.pose.pose.position.x, msg.pose.pose.position.y,
                              msg.twist.twist.linear.x))
    lost = [t for t, text in statuses if text.startswith("lost") and t > KIDNAP_AT_S]
    assert lost, f"never reported lost after the kidnapping at {KIDNAP_AT_S} s: {statuses}\n{output[-4000:]}"
    assert lost[0] - KIDNAP_AT_S <= 1.5, f"lost only {lost[0] - KIDNAP_AT_S:.1f} s after the kidnapping"
    found = [(t, text) for t, text in statuses if text.startswith("localized") and t > lost[0]]
    assert found, f"not localized again after {lost[0]:.1f} s: {statuses}\n{output[-4000:]}"
    found_at = found[0][0]
    # little motion on the wrong pose: from the kidnapping until found again, then none once the controllers'
    # localization_timeout (1 s, + 0.1 s post-dating + 0.5 s braking) has passed
    path = [(x, y) for t, x, y, _v in truth if KIDNAP_AT_S + 0.05 < t < found_at]
    driven = sum(math.dist(a, b) for a, b in zip(path, path[1:]))
    assert driven < 0.5, f"drove {driven:.2f} m between the kidnapping and the new fix"
    standing = [abs(v) for t, _x, _y, v in truth if lost[0] + 1.6 < t < found_at]
    assert all(v < STOPPED_MPS for v in standing), f"moved while lost: max {max(standing):.3f} m/s"
    # the new fix is right: not the mirror pose north of the island (1.8 m off), which fits the scans nearly as
    # well standing still there (before the pose search, 1 run in 3 settled on it and drove on)
    fx, fy = (float(v) for v in found[0][1].split("(")[1].split(",")[:2])
    tx, ty = next((x, y) for t, x, y, _v in truth if t >= found_at)
    assert math.hypot(fx - tx, fy - ty) <= 0.10, f"relocalized at ({fx:.2f}, {fy:.2f}), truly at ({tx:.2f}, {ty:.2f})"
    print(f"kidnapped at {KIDNAP_AT_S:.1f} s, lost at {lost[0]:.1f} s, found at {found_at:.1f} s, driven "
          f"{driven:.2f} m; goals {summary['reached']}/{summary['total']}; {output.strip().splitlines()[-1]}")
