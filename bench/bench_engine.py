#!/usr/bin/env python3
"""Behavior engine overheads against SMACH's core (standalone-smach), measured in the same run.

Figures (issue 4 targets):

1. transition overhead of a 2-state loop, no supervision hooks: flex_nav executor vs SMACH
   ``StateMachine.execute`` doing the same loop (SMACH's loggers silenced so that both time only the
   engine) -- target ratio <= 1.0;
2. the same loop with a transition hook that serialises every transition to JSON (a stand-in for the
   operator publisher) -- target <= 50 us per transition (FlexBE with its mirror attached: ~1000 us);
3. a concurrency container with 2 children, both running: us per container tick (target <= 20 us) and
   threads started (target 0); reference: SMACH ``Concurrence`` with 2 children, one execute;
4. the 2-state loop where both states read a 1 MB input-only message (read-only view): us per
   transition (target <= 20 us); references: the same loop without userdata, and FlexBE's
   protection cost (``hash(repr(value))`` twice per transition) on the same message.

States run with ``rate_hz=inf`` (no throttling) on a manual clock, so only engine work is timed.
Each figure is the best of REPEATS runs (the machine is shared). Exit status 1 if a target is missed.
"""

from __future__ import annotations

import json
import math
import sys
import threading
import time
from pathlib import Path
from typing import Any, Callable, List, Optional

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

from flex_nav.behavior import (  # noqa: E402
    BehaviorExecutor,
    ConcurrencyContainer,
    ManualClock,
    State,
    StateMachine,
)

try:
    import smach  # standalone-smach, bench/requirements.txt
except ImportError:  # pragma: no cover
    print("standalone-smach is missing: run bench/run.sh engine (it installs bench/requirements.txt)", file=sys.stderr)
    sys.exit(2)

# The SMACH side (its loggers silenced, the same 2-state loop and 2-child Concurrence): the compat bench's
from bench_smach_compat import concurrence_seconds, loop_seconds  # noqa: E402

LOOP_TRANSITIONS = 100_000
CC_TICKS = 20_000
MB_TRANSITIONS = 50_000
REPEATS = 5
INF = math.inf


def best_of(fn: Callable[[], float], repeats: int = REPEATS) -> float:
    return min(fn() for _ in range(repeats))


# --- flex_nav side -----------------------------------------------------------------------------------


class Ping(State):
    def __init__(self, keys: tuple = ()) -> None:
        super().__init__(outcomes=["next"], input_keys=keys, rate_hz=INF)
        self.read = bool(keys)

    def execute(self, userdata: Any) -> Optional[str]:
        if self.read:
            userdata.cloud.header.frame_id  # noqa: B018  (read through the read-only view)
        return "next"


class Counter(State):
    def __init__(self, n: int, keys: tuple = ()) -> None:
        super().__init__(outcomes=["next", "done"], input_keys=keys, rate_hz=INF)
        self.n = n
        self.i = 0
        self.read = bool(keys)

    def execute(self, userdata: Any) -> Optional[str]:
        if self.read:
            userdata.cloud.header.frame_id  # noqa: B018
        self.i += 1
        return "done" if self.i >= self.n else "next"


def run_seconds(ex: BehaviorExecutor) -> float:
    """[s] Wall time of running the behavior from its start to its end, which must be the outcome done."""
    ex.start()
    start = time.perf_counter()
    result = ex.run()
    elapsed = time.perf_counter() - start
    assert result.outcome == "done", result
    return elapsed


def flex_loop(transitions: int, hook: Optional[Callable[[Any], None]] = None, cloud: Any = None) -> float:
    keys = ("cloud",) if cloud is not None else ()
    sm = StateMachine(outcomes=["done"], input_keys=keys)
    sm.add("A", Ping(keys), transitions={"next": "B"})
    sm.add("B", Counter(transitions // 2, keys), transitions={"next": "A", "done": "done"})
    ex = BehaviorExecutor(sm, clock=ManualClock(), inputs={"cloud": cloud} if cloud is not None else None)
    if hook is not None:
        ex.context.hooks.transition.append(hook)
    return run_seconds(ex) / transitions


class Runner(State):
    def __init__(self, ticks: int, threads: List[int]) -> None:
        super().__init__(outcomes=["done"], rate_hz=INF)
        self.ticks = ticks
        self.i = 0
        self.threads = threads

    def execute(self, userdata: Any) -> Optional[str]:
        self.i += 1
        if self.i == self.ticks // 2:
            self.threads.append(threading.active_count())
        return "done" if self.i >= self.ticks else None


def flex_concurrency(ticks: int, threads: List[int]) -> float:
    cc = ConcurrencyContainer(outcomes=["done"], conditions=[("done", [("A", "done"), ("B", "done")])])
    cc.add("A", Runner(ticks, threads))
    cc.add("B", Runner(ticks, threads))
    sm = StateMachine(outcomes=["done"])
    sm.add("CC", cc, transitions={"done": "done"})
    ex = BehaviorExecutor(sm, clock=ManualClock())
    return run_seconds(ex) / ticks


# --- the 1 MB message ------------------------------------------------------------------------------


def one_mb_cloud() -> Any:
    """A sensor_msgs/PointCloud2 with 1 MB of data (a plain stand-in if the ROS messages are absent)."""
    try:
        from sensor_msgs.msg import PointCloud2, PointField  # noqa: PLC0415
    except ImportError:

        class Header:
            frame_id = "base_link"

        class Cloud:
            def __init__(self) -> None:
                self.header = Header()
                self.data = bytearray(1_000_000)
                self.fields: list = []

        return Cloud()
    cloud = PointCloud2()
    cloud.header.frame_id = "base_link"
    cloud.height, cloud.width = 1, 1_000_000 // 16
    cloud.fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1) for i, n in enumerate("xyz")]
    cloud.point_step, cloud.row_step = 16, 1_000_000
    cloud.data = bytes(1_000_000)
    return cloud


def flexbe_protection_cost(value: Any, samples: int = 3) -> float:
    """FlexBE hashes repr() of every input-only value before and after execute: twice per transition."""
    start = time.perf_counter()
    for _ in range(samples):
        hash(repr(value))
        hash(repr(value))
    return (time.perf_counter() - start) / samples


# --- report --------------------------------------------------------------------------------------------


def main() -> int:
    failures = []

    def report(name: str, value_s: float, reference_s: float, ref_name: str, target: str, ok: bool) -> None:
        ratio = value_s / reference_s if reference_s > 0 else float("inf")
        status = "PASS" if ok else "FAIL"
        print(
            f"{name:52s} {value_s * 1e6:9.2f} us   {ref_name:34s} {reference_s * 1e6:10.2f} us   "
            f"ratio {ratio:6.2f}x   target {target:18s} {status}"
        )
        if not ok:
            failures.append(name)

    print(f"python {sys.version.split()[0]}, standalone-smach, best of {REPEATS} runs\n")

    flex = best_of(lambda: flex_loop(LOOP_TRANSITIONS))
    ref = best_of(lambda: loop_seconds(smach, LOOP_TRANSITIONS) / LOOP_TRANSITIONS)
    report("2-state loop, per transition (no hooks)", flex, ref, "SMACH StateMachine", "<= 1.0x SMACH", flex <= ref)

    sink: List[bytes] = []

    def publish(event: Any) -> None:  # what an operator publisher does per transition
        message = {
            "stamp": event.time_s,
            "path": event.path,
            "outcome": event.outcome,
            "target": event.target,
            "target_path": event.target_path,
            "required_autonomy": int(event.required),
            "forced": event.forced,
        }
        sink.append(json.dumps(message).encode())
        if len(sink) > 1000:
            sink.clear()

    hooked = best_of(lambda: flex_loop(LOOP_TRANSITIONS, hook=publish))
    report(
        "2-state loop + hook serialising each transition",
        hooked,
        1000e-6,
        "FlexBE with mirror (published)",
        "<= 50 us",
        hooked <= 50e-6,
    )
    print(
        f"{'  (hook cost over the bare loop)':52s} {(hooked - flex) * 1e6:9.2f} us   "
        f"measured reference: the bare loop above, {flex * 1e6:.2f} us; SMACH core {ref * 1e6:.2f} us"
    )

    threads: List[int] = []
    before = threading.active_count()
    cc_tick = best_of(lambda: flex_concurrency(CC_TICKS, threads))
    extra_threads = max(threads) - before
    cc_ref = best_of(lambda: concurrence_seconds(smach, 2_000) / 2_000)
    report(
        "concurrency container, 2 children, per tick",
        cc_tick,
        cc_ref,
        "SMACH Concurrence (1 execute)",
        "<= 20 us",
        cc_tick <= 20e-6,
    )
    print(
        f"{'  threads started while ticking':52s} {extra_threads:9d}      (target 0)"
        f"{'':60s}{'PASS' if extra_threads == 0 else 'FAIL'}"
    )
    if extra_threads:
        failures.append("threads")

    cloud = one_mb_cloud()
    with_mb = best_of(lambda: flex_loop(MB_TRANSITIONS, cloud=cloud))
    flexbe = flexbe_protection_cost(cloud)
    report(
        "2-state loop reading 1 MB input-only, per transition",
        with_mb,
        flexbe,
        "FlexBE hash(repr()) x2 (same msg)",
        "<= 20 us",
        with_mb <= 20e-6,
    )
    print(
        f"{'  (same loop without userdata)':52s} {flex * 1e6:9.2f} us   "
        f"input-only read costs {(with_mb - flex) * 1e6:.2f} us per transition (2 reads)"
    )

    print()
    if failures:
        print(f"FAIL: {', '.join(failures)}")
        return 1
    print("all targets met")
    return 0


if __name__ == "__main__":
    sys.exit(main())
