"""Giving-way bench: the latency of one controller tick's yield decision, for each of the three planners.

    .venv/bin/python bench/bench_yield.py [--ticks 400]

An 8 m path along y = 0 and three walkers looping across it (h6-like: one up and down x = 3 at 0.7 m/s, one
diagonal at 1.0 m/s, one slow at x = 5.5), their lanes learnt over the first 40 s. Then the robot is put at
``--ticks`` places along the path and times (x from 1 to 5 m, t from 40 s on) and each planner decides once
there, on one thread:

1. ``rules`` (:class:`~flex_nav.nav.control.yielding.YieldRule`): the reference;
2. ``space_time`` (:class:`~flex_nav.nav.control.space_time_yield.SpaceTimeYield`, 8 s horizon);
3. ``checked`` (:class:`~flex_nav.nav.control.checked_yield.CheckedYield`): the rules and one or two plans.

Prints median, 95th percentile and maximum [ms], the ratio of each median to the rules' (measured in the same
run), the load average, and PASS/FAIL of every p95 against the budget: half of the TurtleBot 4 profile's
20 Hz control tick. The exit status is 1 on FAIL.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Callable, Dict, List

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

from flex_nav.nav.control.checked_yield import CheckedYield  # noqa: E402
from flex_nav.nav.control.space_time_yield import SpaceTimeYield  # noqa: E402
from flex_nav.nav.control.yielding import YieldParams, YieldRule  # noqa: E402
from flex_nav.nav.path import cumulative_lengths  # noqa: E402
from flex_nav.perception.moving_obstacles import Track  # noqa: E402
from flex_nav.perception.walker_lanes import WalkerLanes  # noqa: E402

BUDGET_MS = 25.0  # [ms] half of a 20 Hz control tick (the pure pursuit, costmap and social checks take the rest)
LEARN_S = 40.0  # [s] the walkers seen this long before the first decision
TICK_S = 0.1  # [s]
PATH = np.column_stack((np.linspace(0.0, 8.0, 81), np.zeros(81)))
LENGTHS = cumulative_lengths(PATH)
# (start (x, y), end (x, y)) [m], speed [m/s], radius [m]: walked back and forth
WALKERS = (((3.0, -3.0), (3.0, 3.0), 0.7, 0.2), ((7.0, 3.0), (1.5, -3.0), 1.0, 0.2),
           ((5.5, 3.0), (5.5, -3.0), 0.45, 0.25))


def walkers_at(t: float) -> List[Track]:
    tracks = []
    for i, (a, b, speed, radius) in enumerate(WALKERS):
        start, end = np.array(a), np.array(b)
        length = float(np.hypot(*(end - start)))
        phase = (speed * t) % (2.0 * length)
        direction = (end - start) / length
        if phase <= length:
            x, y = start + direction * phase
            vx, vy = direction * speed
        else:
            x, y = end - direction * (phase - length)
            vx, vy = -direction * speed
        tracks.append(Track(i + 1, float(x), float(y), float(vx), float(vy), radius, t, 10))
    return tracks


def timed(rule: YieldRule, places: List[tuple]) -> List[float]:
    """[ms] one decision per place (x [m], t [s])."""
    lanes = getattr(rule, "lanes", None)
    if lanes is not None:
        for k in range(round(LEARN_S / TICK_S) + 1):
            lanes.update(k * TICK_S, walkers_at(k * TICK_S))
        rule.learns_in_decide = False  # type: ignore[attr-defined]  # as with the tracker's owner updating them
    figures = []
    for x, t in places:
        tracks = walkers_at(t)
        start = time.perf_counter()
        rule.decide(t, (x, 0.0, 0.0), (0.26, 0.0), path=PATH, lengths=LENGTHS, s_robot=x, tracks=tracks, speed=0.26)
        figures.append((time.perf_counter() - start) * 1e3)
    return figures


def main(argv: List[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=400)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(0)
    places = [(float(rng.uniform(1.0, 5.0)), LEARN_S + float(rng.uniform(0.0, 30.0))) for _ in range(args.ticks)]
    base = YieldParams(robot_radius_m=0.171, speed_mps=0.26, hurry_speed_mps=0.3, comfort_margin_m=0.3,
                       moving_gap_m=0.4)  # the evaluation's, with the social distance at 0.3 m
    makers: Dict[str, Callable[[], YieldRule]] = {
        "rules": lambda: YieldRule(base),
        "space_time": lambda: SpaceTimeYield(dataclasses.replace(base, planner="space_time", horizon_s=8.0,
                                                                 max_range_m=8.0), WalkerLanes()),
        "checked": lambda: CheckedYield(dataclasses.replace(base, planner="checked"), WalkerLanes()),
    }
    status = 0
    reference = None
    print(f"load average {os.getloadavg()[0]:.2f} (1 min); {args.ticks} decisions each, budget p95 <= {BUDGET_MS} ms")
    for name, make in makers.items():
        timed(make(), places[:20])  # warm up
        figures = sorted(timed(make(), places))
        median = statistics.median(figures)
        p95 = figures[min(len(figures) - 1, int(0.95 * len(figures)))]
        reference = median if reference is None else reference
        verdict = "PASS" if p95 <= BUDGET_MS else "FAIL"
        status |= verdict == "FAIL"
        print(f"{name:>10}: median {median:6.2f} ms  p95 {p95:6.2f} ms  max {figures[-1]:6.2f} ms  "
              f"x{median / reference:5.1f} the rules' median  {verdict}")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
