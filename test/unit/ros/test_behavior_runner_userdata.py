"""behavior_runner's ~userdata: latched JSON of the active states' userdata (an input key with its value, an output
key once written), only when it changed, and no states once the behavior ended. No master: rospy's publishers,
subscribers and clock are replaced by recorders (as in test_behavior_runner_structure.py)."""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any, Callable, Dict, List

from unit.ros import test_behavior_runner_structure as structure_tests

from flex_nav.nodes.behavior_runner import BehaviorRunner

Recorder = structure_tests.Recorder
runner = structure_tests.runner  # the fixture: a runner whose publishers are recorded, its search path tmp_path

# Count adds 2.5 to start_value and writes it; its outcome needs autonomy High, so at Low it stays active
COUNTING = """behavior: counting
outcomes: [finished]
input_keys: [label]
userdata: {start_value: 1.0}
states:
  Count:
    class: flex_nav.behavior.builtin_states.Calculation
    parameters: {operation: add, operand: 2.5}
    remapping: {input_value: start_value, output_value: result}
    transitions: {done: Say}
    autonomy: {done: high}
  Say:
    class: flex_nav_states.log_state.LogState
    parameters: {text: "the label is {label}", severity: info, keys: [label]}
    transitions: {done: finished}
"""


def userdata() -> List[Dict[str, Any]]:
    return [json.loads(msg.data) for name, msg, latch in list(Recorder.published) if name == "~userdata" and latch]


def until(found: Callable[[Dict[str, Any]], bool], timeout_s: float = 5.0) -> Dict[str, Any]:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        matching = [m for m in userdata() if found(m)]
        if matching:
            return matching[-1]
        time.sleep(0.01)
    raise AssertionError(f"no ~userdata message as wanted within {timeout_s} s; published: {userdata()}")


def test_the_active_states_userdata_is_latched(runner: BehaviorRunner, tmp_path: Path) -> None:
    (tmp_path / "counting.yaml").write_text(COUNTING)  # beside the fixture's behavior, on the runner's search path
    runner.userdata_rate_hz = 20.0
    assert userdata()[0]["behavior"] == "" and userdata()[0]["states"] == []  # the idle runner's
    runner.start_local("counting", "low", {}, {"label": "kitchen"})
    held = until(lambda m: any(s["path"] == "/Count" for s in m["states"]))
    assert held["schema"] == "flex_nav/userdata" and held["behavior"] == "counting"
    count = next(s for s in held["states"] if s["path"] == "/Count")
    assert count["keys"] == [{"key": "input_value", "role": "in", "set": True, "value": 1.0},
                             {"key": "output_value", "role": "out", "set": True, "value": 3.5}]
    root = next(s for s in held["states"] if s["path"] == "/")
    assert root["keys"] == [{"key": "label", "role": "in", "set": True, "value": "kitchen"}]
    time.sleep(0.3)  # nothing changes while Count waits: no new message
    assert len([m for m in userdata() if m["behavior"] == "counting"]) == 1
    runner.handle("approve", ["/Count"])
    ended = until(lambda m: m["behavior"] == "" and m["stamp"] is not None)  # the idle runner's has no stamp
    assert ended["states"] == []
    deadline = time.monotonic() + 5.0  # the runner's thread records the result just after the last userdata
    while runner.result() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    result = runner.result()
    assert result is not None and result.status.name == "FINISHED"
