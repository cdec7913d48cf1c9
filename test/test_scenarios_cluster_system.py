"""The scenario evaluation on a Dask distributed cluster: a scheduler and two single-thread workers on loopback
(``distributed.LocalCluster``, worker processes as ``dask worker`` would start), the driver connected with
``--cluster ADDRESS``, two real scenario runs (S1 light box in the door, S3 person in the door, push_or_avoid,
each its own simulator and private master) at the same time, one per worker. The outcomes asserted are those of
the obstacle-aware system tests (test_push_or_avoid_system.py keeps the other scenarios). Then S3 once more alone at
rtf 4: the same outcome within 0.5 s of simulated time (issue 28's determinism check; the runs are lockstep, the
evaluation's default)."""

from __future__ import annotations

import contextlib
import csv
import dataclasses
import io
import json
import os
import sys
from pathlib import Path
from typing import Dict, Iterator

import pytest
from harness import run_command_bounded, system_env

from flex_nav.apps.eval import scenarios

distributed = pytest.importorskip("distributed")

SIM_LIMIT_S = 100.0  # [s] simulated time bound of a goal
CLUSTER_START_TIMEOUT_S = 60.0  # [s]
RUN_TIMEOUT_S = 300.0  # [s] wall bound of the run at rtf 4
# [s] of simulated time: the same run at another rtf and load ends within this (issue 28). Lockstep S3 ended
# 43.0-43.3 s at rtf 1, 2, 4 and 4 with a core busy (without lockstep 41.2-44.7 s). S1 is not the check: its
# last drive after the push still varies by up to ~0.6 s (docs/push_or_avoid.md).
DETERMINISM_S = 0.5


@dataclasses.dataclass
class ClusterRun:
    status: int
    printed: str  # what the driver printed
    out: Path


@pytest.fixture(scope="module")
def cluster_run(tmp_path_factory: pytest.TempPathFactory) -> Iterator[ClusterRun]:
    """S1 and S3 at rtf 1 on the two-worker cluster, once for the module's tests."""
    out = tmp_path_factory.mktemp("cluster")
    printed = io.StringIO()
    with pytest.MonkeyPatch.context() as monkeypatch:
        for name, value in system_env().items():  # the workers inherit it: venv first, the package findable
            if os.environ.get(name) != value:
                monkeypatch.setenv(name, value)
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                      dashboard_address=None, timeout=CLUSTER_START_TIMEOUT_S) as cluster, \
                contextlib.redirect_stdout(printed):
            status = scenarios.main([
                "--cluster", cluster.scheduler_address, "--scenarios", "s1_light_box_door,s3_person_in_door",
                "--behaviors", "push_or_avoid", "--seeds", "1", "--rtf", "1", "--sim-limit", str(SIM_LIMIT_S),
                "--out", str(out)])
    yield ClusterRun(status, printed.getvalue(), out)


def rows_of(run: ClusterRun) -> Dict[str, Dict[str, str]]:
    return {row["world"]: row for row in csv.DictReader(io.StringIO((run.out / "results.csv").read_text()))}


@pytest.mark.ros
def test_two_scenarios_run_at_once_on_a_two_worker_cluster(cluster_run: ClusterRun) -> None:
    assert cluster_run.status == 0, cluster_run.printed[-3000:]
    assert "2 run(s) on 2 cluster worker(s)" in cluster_run.printed, cluster_run.printed
    tmp_path = cluster_run.out
    rows = rows_of(cluster_run)
    assert list(rows) == ["s1_light_box_door", "s3_person_in_door"]  # the plan's order
    s1_log = (tmp_path / "s1_light_box_door-push_or_avoid-0" / "run.log").read_text()
    s3_log = (tmp_path / "s3_person_in_door-push_or_avoid-0" / "run.log").read_text()
    s1, s3 = rows["s1_light_box_door"], rows["s3_person_in_door"]
    # S1: the light box in the only door is pushed out of the way
    assert s1["success"] == "True", s1_log[-5000:]
    assert int(s1["pushes_succeeded"]) >= 1 and int(s1["people_contacts"]) == 0
    assert "/Classify --movable--> Push" in s1_log
    # S3: the person in the door is backed off from, never touched, never pushed; they walk away at 25 s
    assert s3["success"] == "True", s3_log[-5000:]
    assert int(s3["people_contacts"]) == 0 and int(s3["pushes_tried"]) == 0
    assert float(s3["min_people_clearance_m"]) > 0.0
    assert "/Classify --person--> BackOffPerson" in s3_log
    for run in ("s1_light_box_door-push_or_avoid-0", "s3_person_in_door-push_or_avoid-0"):
        assert (tmp_path / run / "run.png").stat().st_size > 5_000


@pytest.mark.ros
def test_the_same_run_at_rtf_4_alone_ends_as_at_rtf_1_beside_another(cluster_run: ClusterRun,
                                                                     tmp_path: Path) -> None:
    """Determinism: the simulator steps in lockstep with the nodes, so S3 (seed 0) at rtf 4 on an otherwise quiet
    machine takes the time it took at rtf 1 while S1 ran on the other core."""
    before = rows_of(cluster_run)["s3_person_in_door"]
    assert before["success"] == "True"
    outcome = run_command_bounded(
        [sys.executable, "-m", "flex_nav.apps.scenario_run", "--world", "s3_person_in_door", "--behavior",
         "push_or_avoid", "--seed", "0", "--rtf", "4", "--sim-limit", str(SIM_LIMIT_S), "--out", str(tmp_path)],
        env=system_env(), timeout_s=RUN_TIMEOUT_S)
    lines = [line for line in outcome.output.splitlines() if line.startswith("RESULT ")]
    assert outcome.returncode == 0 and lines, outcome.output[-5000:]
    again = json.loads(lines[-1][len("RESULT "):])
    assert again["success"] and again["pushes_tried"] == int(before["pushes_tried"]) == 0
    assert abs(float(again["time_s"]) - float(before["time_s"])) <= DETERMINISM_S, (again["time_s"], before["time_s"])
