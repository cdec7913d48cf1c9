"""The scenario evaluation on a Dask distributed cluster: a scheduler and two single-thread workers on loopback
(``distributed.LocalCluster``, worker processes as ``dask worker`` would start), the driver connected with
``--cluster ADDRESS``, two real scenario runs (S1 light box in the door, S3 person in the door, push_or_avoid,
each its own simulator and private master) at the same time, one per worker. The outcomes asserted are those of
the obstacle-aware system tests (test_push_or_avoid_system.py keeps the other scenarios)."""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path

import pytest
from harness import system_env

from flex_nav.apps.eval import scenarios

distributed = pytest.importorskip("distributed")

SIM_LIMIT_S = 100.0  # [s] simulated time bound of a goal
CLUSTER_START_TIMEOUT_S = 60.0  # [s]


@pytest.mark.ros
def test_two_scenarios_run_at_once_on_a_two_worker_cluster(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    for name, value in system_env().items():  # the workers inherit it: venv first, the package findable
        if os.environ.get(name) != value:
            monkeypatch.setenv(name, value)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None, timeout=CLUSTER_START_TIMEOUT_S) as cluster:
        status = scenarios.main([
            "--cluster", cluster.scheduler_address, "--scenarios", "s1_light_box_door,s3_person_in_door",
            "--behaviors", "push_or_avoid", "--seeds", "1", "--rtf", "1", "--sim-limit", str(SIM_LIMIT_S),
            "--out", str(tmp_path)])
    printed = capsys.readouterr()
    assert status == 0, printed.err[-3000:]
    assert "2 run(s) on 2 worker(s)" in printed.out, printed.out
    rows = {row["world"]: row for row in csv.DictReader(io.StringIO((tmp_path / "results.csv").read_text()))}
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
