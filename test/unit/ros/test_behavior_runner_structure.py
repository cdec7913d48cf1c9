"""behavior_runner's ~structure: latched JSON of no behavior (with the startable list) when it starts, of the
behavior once one is loaded and started. No master: rospy's publishers, subscribers and clock are replaced by
recorders for the test."""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any, ClassVar, Dict, List, Tuple

import pytest
import rospy

from flex_nav.behavior.clock import MonotonicClock
from flex_nav.nodes import behavior_runner
from flex_nav.nodes.behavior_runner import BehaviorRunner

SMALL = """behavior: small
parameters:
  wait_s: {type: float, default: 0.05, min: 0.0, description: "[s] how long"}
outcomes: [finished]
states:
  Wait:
    class: flex_nav.behavior.builtin_states.Wait
    parameters: {wait_time_s: $wait_s}
    transitions: {done: finished}
    autonomy: {done: low}
"""


class Recorder:
    published: ClassVar[List[Tuple[str, Any, bool]]] = []

    def __init__(self, name: str, msg_type: Any, queue_size: int = 0, latch: bool = False, **_: Any) -> None:
        self.name, self.latch = name, latch

    def publish(self, msg: Any) -> None:
        Recorder.published.append((self.name, msg, self.latch))

    def unregister(self) -> None:
        pass


class Silent:
    def __init__(self, *args: Any, **kwargs: Any) -> None:
        pass

    def unregister(self) -> None:
        pass


@pytest.fixture
def runner(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Any:
    Recorder.published = []
    monkeypatch.setattr(rospy, "Publisher", Recorder)
    monkeypatch.setattr(rospy, "Subscriber", Silent)
    monkeypatch.setattr(rospy.Time, "now", staticmethod(lambda: rospy.Time(0)))
    monkeypatch.setattr(behavior_runner, "RosClock", MonotonicClock)
    # a test earlier in the same pytest process may have shut rospy down (test_console_browser_system.py
    # signals shutdown when its stack stops): a runner's behavior stops at once while rospy says so
    monkeypatch.setattr(rospy, "is_shutdown", lambda: False)
    (tmp_path / "small.yaml").write_text(SMALL)
    made = BehaviorRunner([tmp_path])
    yield made
    made.shutdown()


def structures(timeout_s: float = 5.0, count: int = 1) -> List[Dict[str, Any]]:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        found = [json.loads(msg.data) for name, msg, latch in list(Recorder.published)
                 if name == "~structure" and latch]
        if len(found) >= count:
            return found
        time.sleep(0.01)
    raise AssertionError(f"fewer than {count} structures published within {timeout_s} s")


def test_an_idle_runner_latches_an_empty_structure_with_what_it_can_start(runner: BehaviorRunner) -> None:
    (idle,) = structures()
    assert idle["behavior"] == "" and idle["states"] == []
    assert idle["startable"] == [{"name": "small", "error": "", "parameters": [
        {"name": "wait_s", "type": "float", "default": 0.05, "has_default": True, "min": 0.0, "max": None,
         "choices": None, "description": "[s] how long"}]}]


def test_a_started_behavior_is_described_before_it_runs(runner: BehaviorRunner, tmp_path: Path) -> None:
    runner.start_local("small", "full", {"wait_s": 0.01})
    idle, loaded = structures(count=2)
    assert idle["behavior"] == "" and loaded["behavior"] == "small"
    assert [s["path"] for s in loaded["states"]] == ["/", "/Wait"]
    assert loaded["states"][1]["autonomy"] == {"done": 1}
    assert loaded["values"] == {"wait_s": 0.01}
    names = [name for name, _, _ in Recorder.published]
    assert names.index("~structure", names.index("~structure") + 1) < names.index("~activity")  # before its activity
