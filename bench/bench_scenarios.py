#!/usr/bin/env python3
"""The scenario evaluation at scale and its reproducibility (issue 28): wall time with two local workers against
one after another, and the same runs' outcomes and times at other real-time factors and under load.

Runs ``python -m flex_nav.apps.eval.scenarios`` on the same plan (default: S1..S6 x both behaviors x seed 0, 12
runs) several times in one bench run and compares them run by run:

- ``--mode workers`` (default): ``--workers 1`` (the reference: one run after another) and ``--workers 2`` at
  ``--rtf`` (default 2), the two workers starting the runs longest first by the serial run's times
  (``--durations``; ``--plan-order``: in the plan's order). Prints both wall times, their ratio (the speed-up;
  issue 28 asks >= 1.8x on a 2-core machine) and, per run, the outcome and the time to goal of both, with the
  largest difference;
- ``--mode rtf``: one run after another at each of ``--rtfs`` (default 1,2,4), and with ``--busy`` the last of
  them again with one core kept busy by a spinning process (``--busy`` adds that row). The reference is the
  first rtf; prints per run the times at each and the largest difference from the reference (issue 28 asks
  +-0.5 s of simulated time and the same outcome).

Each evaluation writes its own ``results.csv`` under ``--out`` (kept). The machine's load average is printed
before every evaluation. Run nothing else meanwhile: a second simulated stack changes every figure.
Run: .venv/bin/python bench/bench_scenarios.py [--mode workers|rtf] [--seeds 1] [--scenarios ...] [--out DIR]
"""

from __future__ import annotations

import argparse
import csv
import math
import multiprocessing
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

REPO = Path(__file__).resolve().parents[1]
RunKey = Tuple[str, str, int]  # (world, behavior, seed)
Outcome = Tuple[bool, float]  # (reached, time to goal [s] simulated; nan when not reached)


def load_average() -> str:
    return " ".join(f"{v:.2f}" for v in os.getloadavg())


def spin(stop_at: float) -> None:
    """Keep one core busy until ``stop_at`` (time.monotonic() [s])."""
    x = 0
    while time.monotonic() < stop_at:
        x = (x * 1103515245 + 12345) % 2147483648


def evaluate(out: Path, rtf: float, workers: int, args: argparse.Namespace, durations: Optional[Path] = None,
             ) -> Tuple[float, Dict[RunKey, Outcome]]:
    """One evaluation (runs longest first by ``durations``, an earlier results.csv, if given); its wall time [s] and
    every run's outcome."""
    command = [sys.executable, "-m", "flex_nav.apps.eval.scenarios", "--seeds", str(args.seeds), "--rtf", str(rtf),
               "--workers", str(workers), "--out", str(out), "--scenarios", args.scenarios, "--behaviors",
               args.behaviors, "--lockstep" if args.lockstep else "--no-lockstep"]
    if durations is not None:
        command += ["--durations", str(durations)]
    for setting in args.behavior_param:
        command += ["--behavior-param", setting]
    print(f"  load average {load_average()} before: {' '.join(command[3:])}", flush=True)
    started = time.monotonic()
    proc = subprocess.run(command, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                          check=False)
    wall_s = time.monotonic() - started
    if proc.returncode != 0:
        print(f"  evaluation exited {proc.returncode}: {proc.stdout[-2000:]}", flush=True)
    return wall_s, read_results(out / "results.csv")


def read_results(path: Path) -> Dict[RunKey, Outcome]:
    results: Dict[RunKey, Outcome] = {}
    if not path.is_file():
        return results
    with open(path, newline="") as handle:
        for row in csv.DictReader(handle):
            reached = row["success"] == "True"
            results[(row["world"], row["behavior"], int(row["seed"]))] = (
                reached, float(row["time_s"]) if reached and row["time_s"] else math.nan)
    return results


def compare(reference: Dict[RunKey, Outcome], other: Dict[RunKey, Outcome]) -> Tuple[int, float, List[str]]:
    """(runs whose outcome differs or is missing, the largest |time difference| [s] of runs reached in both,
    one line per run)."""
    differ, largest, lines = 0, 0.0, []
    for key in sorted(set(reference) | set(other)):
        a, b = reference.get(key), other.get(key)
        if a is None or b is None or a[0] != b[0]:
            differ += 1
            lines.append(f"    {key[0]:<26} {key[1]:<15} seed {key[2]}: OUTCOME DIFFERS {a} vs {b}")
            continue
        delta = b[1] - a[1] if a[0] else 0.0
        largest = max(largest, abs(delta))
        text = f"{a[1]:7.1f} s vs {b[1]:7.1f} s ({delta:+.2f} s)" if a[0] else "not reached in both"
        lines.append(f"    {key[0]:<26} {key[1]:<15} seed {key[2]}: {text}")
    return differ, largest, lines


def report(name: str, reference: Dict[RunKey, Outcome], other: Dict[RunKey, Outcome]) -> None:
    differ, largest, lines = compare(reference, other)
    print(f"  {name}: {len(other)} runs, outcomes differing {differ}, largest time difference {largest:.2f} s")
    for line in lines:
        print(line)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mode", choices=("workers", "rtf"), default="workers")
    parser.add_argument("--rtf", type=float, default=2.0, help="--mode workers: the real-time factor")
    parser.add_argument("--rtfs", default="1,2,4", help="--mode rtf: comma-separated real-time factors")
    parser.add_argument("--busy", action="store_true", help="--mode rtf: the last rtf again with a core kept busy")
    parser.add_argument("--seeds", type=int, default=1)
    parser.add_argument("--scenarios", default="s1_light_box_door,s2_heavy_box_door,s3_person_in_door,"
                                                "s4_light_box_short_route,s5_heavy_box_short_route,s6_people_crossing")
    parser.add_argument("--behaviors", default="move_base_like,push_or_avoid")
    parser.add_argument("--behavior-param", action="append", default=[], metavar="BEHAVIOR:KEY=VALUE")
    parser.add_argument("--out", type=Path, default=None, help="where the evaluations write (default: a temp dir)")
    parser.add_argument("--lockstep", action=argparse.BooleanOptionalAction, default=True,
                        help="the evaluations' simulator in lockstep with the nodes (the default)")
    parser.add_argument("--plan-order", action="store_true",
                        help="--mode workers: the two workers take the runs in the plan's order, not longest first")
    args = parser.parse_args(argv)
    out = args.out or Path(tempfile.mkdtemp(prefix="bench_scenarios-"))
    print(f"bench_scenarios ({args.mode}) on {os.cpu_count()} cores; evaluations under {out}", flush=True)
    if args.mode == "workers":
        serial_s, serial = evaluate(out / "workers1", args.rtf, 1, args)
        print(f"  one after another: {serial_s:.0f} s wall for {len(serial)} runs", flush=True)
        durations = None if args.plan_order else out / "workers1" / "results.csv"
        parallel_s, parallel = evaluate(out / "workers2", args.rtf, 2, args, durations)
        print(f"  two workers: {parallel_s:.0f} s wall for {len(parallel)} runs", flush=True)
        print(f"speed-up two workers / one after another: {serial_s / parallel_s:.2f}x "
              f"({serial_s:.0f} s -> {parallel_s:.0f} s, rtf {args.rtf:g})")
        report("two workers against one after another", serial, parallel)
        return 0
    rtfs = [float(r) for r in args.rtfs.split(",") if r]
    runs: List[Tuple[str, Dict[RunKey, Outcome]]] = []
    for rtf in rtfs:
        wall_s, results = evaluate(out / f"rtf{rtf:g}", rtf, 1, args)
        print(f"  rtf {rtf:g}: {wall_s:.0f} s wall for {len(results)} runs", flush=True)
        runs.append((f"rtf {rtf:g}", results))
    if args.busy:
        spinner = multiprocessing.Process(target=spin, args=(time.monotonic() + 24 * 3600.0,), daemon=True)
        spinner.start()
        try:
            wall_s, results = evaluate(out / f"rtf{rtfs[-1]:g}-busy", rtfs[-1], 1, args)
        finally:
            spinner.terminate()
            spinner.join(5.0)
        print(f"  rtf {rtfs[-1]:g} with a core busy: {wall_s:.0f} s wall for {len(results)} runs", flush=True)
        runs.append((f"rtf {rtfs[-1]:g} with a core busy", results))
    name0, reference = runs[0]
    for name, results in runs[1:]:
        report(f"{name} against {name0}", reference, results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
