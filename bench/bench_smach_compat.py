"""flex_nav.compat.smach against SMACH's core (standalone-smach), measured in the same run.

Figures (best of REPEATS runs each, wall time):
- 2-state loop: time per transition of a StateMachine ping-ponging between two trivial states;
- Concurrence: time per execute of a Concurrence with two trivial children (both start a thread per
  child per execute: that is SMACH's design, kept by the compatibility layer).

Prints each figure and the ratio compat / SMACH (below 1.0: the compatibility layer is faster).
Run: bench/run.sh smach_compat (installs bench/requirements.txt), or .venv/bin/python bench/bench_smach_compat.py.
"""

from __future__ import annotations

import sys
import threading
import time
from types import ModuleType
from typing import Any, Callable

try:
    import smach as ref_smach  # standalone-smach, bench/requirements.txt
except ImportError:
    print("standalone-smach is missing: run bench/run.sh smach_compat", file=sys.stderr)
    sys.exit(2)

from flex_nav.compat import smach as compat_smach

REPEATS = 5
LOOP_TRANSITIONS = 20_000
CONCURRENCE_EXECUTES = 1_000

ref_smach.set_loggers(lambda msg: None, lambda msg: None, lambda msg: None, lambda msg: None)
compat_smach.set_loggers(lambda msg: None, lambda msg: None, lambda msg: None, lambda msg: None)
if not hasattr(threading.Thread, "isAlive"):  # standalone-smach 0.0.9's Concurrence predates Python 3.9
    threading.Thread.isAlive = threading.Thread.is_alive  # type: ignore[attr-defined]


def loop_seconds(smach: ModuleType, transitions: int) -> float:
    state_base: Any = smach.State  # either library's State: a base class mypy cannot resolve statically

    class Ping(state_base):
        def __init__(self) -> None:
            smach.State.__init__(self, outcomes=["next"])

        def execute(self, ud: Any) -> str:
            return "next"

    class Count(state_base):
        def __init__(self, limit: int) -> None:
            smach.State.__init__(self, outcomes=["next", "done"])
            self.left = limit

        def execute(self, ud: Any) -> str:
            self.left -= 1
            return "next" if self.left > 0 else "done"

    sm = smach.StateMachine(outcomes=["done"])
    with sm:
        smach.StateMachine.add("A", Ping(), transitions={"next": "B"})
        smach.StateMachine.add("B", Count(transitions // 2), transitions={"next": "A", "done": "done"})
    start = time.perf_counter()
    outcome = sm.execute(smach.UserData())
    elapsed = time.perf_counter() - start
    assert outcome == "done"
    return elapsed


def concurrence_seconds(smach: ModuleType, executes: int) -> float:
    state_base: Any = smach.State

    class Once(state_base):
        def __init__(self) -> None:
            smach.State.__init__(self, outcomes=["done"])

        def execute(self, ud: Any) -> str:
            return "done"

    cc = smach.Concurrence(outcomes=["done"], default_outcome="done", outcome_map={"done": {"A": "done", "B": "done"}})
    with cc:
        smach.Concurrence.add("A", Once())
        smach.Concurrence.add("B", Once())
    start = time.perf_counter()
    for _ in range(executes):
        cc.execute(smach.UserData())
    return time.perf_counter() - start


def best_of(fn: Callable[[], float]) -> float:
    return min(fn() for _ in range(REPEATS))


def main() -> None:
    print(f"python {sys.version.split()[0]}, standalone-smach vs flex_nav.compat.smach, best of {REPEATS} runs\n")
    ref = best_of(lambda: loop_seconds(ref_smach, LOOP_TRANSITIONS)) / LOOP_TRANSITIONS * 1e6
    ours = best_of(lambda: loop_seconds(compat_smach, LOOP_TRANSITIONS)) / LOOP_TRANSITIONS * 1e6
    print(f"2-state loop      SMACH {ref:8.2f} us/transition  compat {ours:8.2f} us/transition  ratio {ours / ref:.2f}")
    ref = best_of(lambda: concurrence_seconds(ref_smach, CONCURRENCE_EXECUTES)) / CONCURRENCE_EXECUTES * 1e6
    ours = best_of(lambda: concurrence_seconds(compat_smach, CONCURRENCE_EXECUTES)) / CONCURRENCE_EXECUTES * 1e6
    print(f"Concurrence (2)   SMACH {ref:8.2f} us/execute     compat {ours:8.2f} us/execute     ratio {ours / ref:.2f}")


if __name__ == "__main__":
    main()
