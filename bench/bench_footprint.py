#!/usr/bin/env python3
"""The demo's footprint: memory per process, CPU per simulated second and the real-time factor reached.

Runs the README's demo (``python -m flex_nav.apps.nav_demo``, one TurtleBot 2, the lab lap of 4 goals), or with
``--run s4`` the scenario S4 (``python -m flex_nav.apps.scenario_run``, TurtleBot 4, push_or_avoid with the
camera and the obstacle classifier), twice in the same run: with one robot's navigation servers and controllers
in one ``navigation`` process (the default) and with a process each (``--separate-processes``, the reference).
While each runs, every process under it is sampled every 0.25 s (psutil): resident memory (RSS) and CPU time
(user + system).

Figures per run:
- RSS per process (its peak) and the robot's total: every flex_nav process of the robot (navigation servers and
  controllers, twist_relay, bumper_relay, localizer, behavior runner, the obstacle classifier in S4) and the map
  server; the simulator and
  ROS's own processes (roslaunch, rosmaster, rosout, rosbag) listed apart;
- CPU-seconds per simulated second from the first goal to the last arrival, per process and for the robot;
- the real-time factor reached over the same span (simulated seconds per wall second) at the asked ``--rtf``
  (default 0: as fast as possible).

Prints the ratio combined / separate for memory and CPU, and the machine's load. Run one at a time: a second
simulated stack on this machine halves every figure.
Run: .venv/bin/python bench/bench_footprint.py [--rtf 0] [--mode both|combined|separate]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Tuple

import psutil  # type: ignore[import-untyped]  # a dependency (requirements.txt) without stubs

REPO = Path(__file__).resolve().parents[1]
SAMPLE_PERIOD_S = 0.25  # [s] wall
ROBOT = {"navigation", "obstacle_classifier", "get_path_server", "follow_path_server", "follow_topic_server",
         "pure_pursuit_path", "pure_pursuit_topic", "twist_relay", "bumper_relay", "localizer", "behavior_runner",
         "map_server"}
SIM_LINE = re.compile(r"^\[sim\s+([0-9.]+) s\]")
END_LINE = re.compile(r"goals reached: (\d+)/(\d+).*sim time: ([0-9.]+) s, wall time: ([0-9.]+) s")


def label_of(cmdline: List[str]) -> str:
    """A process's name: its ROS node name (``__name:=``), else the program it runs; "" for anything else (the
    shell wrappers and short-lived helpers rosrun and roslaunch start), which is not listed."""
    if not cmdline or os.path.basename(cmdline[0]) in ("bash", "sh"):
        return ""
    for arg in cmdline:
        if arg.startswith("__name:="):
            return arg.split(":=", 1)[1]
    for arg in cmdline[:3]:
        base = os.path.basename(arg)
        if base in ("sim", "map_server", "obstacle_classifier", "roscore", "rosmaster", "roslaunch", "record"):
            return base
    return ""


@dataclass
class ProcessSample:
    label: str
    rss_peak_mb: float = 0.0
    cpu_s: float = 0.0  # [s] user + system, the newest sample
    cpu_at_first_goal_s: Optional[float] = None


@dataclass
class RunFigures:
    mode: str
    processes: Dict[int, ProcessSample] = field(default_factory=dict)
    robot_rss_peak_mb: float = 0.0  # peak of the robot's summed RSS over the samples
    first_goal: Optional[Tuple[float, float]] = None  # (sim [s], wall [s]) when the first goal started
    end: Optional[Tuple[float, float]] = None  # (sim [s], wall [s]) at the last line with a sim time
    reached: str = "?"
    load: Tuple[float, float, float] = (0.0, 0.0, 0.0)

    def robot(self) -> List[ProcessSample]:
        return [p for p in self.processes.values() if p.label in ROBOT]


class Sampler:
    def __init__(self, root: psutil.Process, figures: RunFigures) -> None:
        self.root = root
        self.figures = figures
        self.lock = threading.Lock()
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._loop, daemon=True)
        self.thread.start()

    def _loop(self) -> None:
        while not self.stop.wait(SAMPLE_PERIOD_S):
            try:
                children = self.root.children(recursive=True)
            except psutil.Error:
                return
            robot_rss = 0.0
            for proc in children:
                try:
                    with proc.oneshot():
                        cmdline = proc.cmdline()
                        rss_mb = proc.memory_info().rss / 2**20
                        times = proc.cpu_times()
                except psutil.Error:
                    continue
                label = label_of(cmdline)
                if not label:
                    continue
                with self.lock:
                    sample = self.figures.processes.setdefault(proc.pid, ProcessSample(label))
                    sample.label = label  # a child of roslaunch shows roslaunch's command line until it execs
                    sample.rss_peak_mb = max(sample.rss_peak_mb, rss_mb)
                    sample.cpu_s = times.user + times.system
                if sample.label in ROBOT:
                    robot_rss += rss_mb
            with self.lock:
                self.figures.robot_rss_peak_mb = max(self.figures.robot_rss_peak_mb, robot_rss)

    def mark_first_goal(self) -> None:
        with self.lock:
            for sample in self.figures.processes.values():
                sample.cpu_at_first_goal_s = sample.cpu_s


S4_ARGV = ["-m", "flex_nav.apps.scenario_run", "--world", "s4_light_box_short_route", "--behavior", "push_or_avoid"]


def run_demo(mode: str, rtf: float, out: Path, scenario: bool = False) -> RunFigures:
    app = S4_ARGV if scenario else ["-m", "flex_nav.apps.nav_demo"]
    argv = [sys.executable, *app, "--rtf", str(rtf), "--out", str(out)]
    if mode == "separate":
        argv.append("--separate-processes")
    figures = RunFigures(mode)
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen(argv, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    sampler = Sampler(psutil.Process(proc.pid), figures)
    assert proc.stdout is not None
    log = (out.parent / f"{mode}.log").open("w")
    for line in proc.stdout:
        log.write(line)
        now = time.monotonic()
        match = SIM_LINE.match(line)
        if match:
            sim_s = float(match.group(1))
            if figures.first_goal is None and re.search(r"goal 1/\d+: \S+ at", line):
                sampler.mark_first_goal()
                figures.first_goal = (sim_s, now)
            if "reached after" in line:
                figures.end = (sim_s, now)
        ended = END_LINE.search(line)
        if ended:
            figures.reached = f"{ended.group(1)}/{ended.group(2)}"
        if line.startswith("RESULT "):
            result = json.loads(line[len("RESULT "):])
            figures.reached = (f"{'arrived' if result.get('success') else 'NOT arrived'}, pushes "
                               f"{result.get('pushes_succeeded')}/{result.get('pushes_tried')}")
    proc.wait(timeout=60)
    log.close()
    if figures.reached == "?" or figures.first_goal is None:
        print(f"the demo ({mode}) did not run its goals; its last lines:\n"
              + "".join((out.parent / f"{mode}.log").read_text().splitlines(keepends=True)[-15:]))
    sampler.stop.set()
    sampler.thread.join(5.0)
    figures.load = os.getloadavg()
    return figures


def report(figures: RunFigures) -> Tuple[float, float, float]:
    """Prints one run's table; returns (robot RSS [MB], robot CPU-s per sim s, rtf reached)."""
    span_sim = span_wall = float("nan")
    if figures.first_goal and figures.end:
        span_sim = figures.end[0] - figures.first_goal[0]
        span_wall = figures.end[1] - figures.first_goal[1]
    print(f"--- {figures.mode}: goals {figures.reached}; first goal to last arrival {span_sim:.1f} s simulated in "
          f"{span_wall:.1f} s wall (rtf reached {span_sim / span_wall:.2f}); load after the run "
          f"{figures.load[0]:.2f} {figures.load[1]:.2f} {figures.load[2]:.2f}")
    print(f"    {'process':22s} {'RSS peak [MB]':>13s} {'CPU-s / sim s':>14s}")
    by_label = sorted(figures.processes.values(), key=lambda p: (p.label not in ROBOT, p.label))
    robot_cpu = 0.0
    for sample in by_label:
        used = sample.cpu_s - (sample.cpu_at_first_goal_s or 0.0)
        per_sim = used / span_sim if span_sim > 0 else float("nan")
        if sample.label in ROBOT:
            robot_cpu += per_sim
        tag = "" if sample.label in ROBOT else "  (not counted)"
        print(f"    {sample.label:22s} {sample.rss_peak_mb:13.1f} {per_sim:14.3f}{tag}")
    rss = figures.robot_rss_peak_mb
    print(f"    robot total (peak of the sum): {rss:.1f} MB; CPU {robot_cpu:.3f} CPU-s per simulated s")
    return rss, robot_cpu, span_sim / span_wall


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rtf", type=float, default=0.0, help="demo real-time factor (0: as fast as possible)")
    parser.add_argument("--mode", choices=("both", "combined", "separate"), default="both")
    parser.add_argument("--run", choices=("demo", "s4"), default="demo",
                        help="the README's demo, or the scenario S4 (push_or_avoid, camera and classifier)")
    args = parser.parse_args()
    print(f"load before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}; {os.cpu_count()} cores")
    modes = ["combined", "separate"] if args.mode == "both" else [args.mode]
    results: Dict[str, Tuple[float, float, float]] = {}
    out = Path(tempfile.mkdtemp(prefix="bench_footprint_"))
    print(f"demo outputs and logs in {out}")
    for mode in modes:
        results[mode] = report(run_demo(mode, args.rtf, out / mode, scenario=args.run == "s4"))
    if len(results) == 2:
        (c_rss, c_cpu, c_rtf), (s_rss, s_cpu, s_rtf) = results["combined"], results["separate"]
        print(f"combined / separate: memory {c_rss / s_rss:.2f}x, CPU {c_cpu / s_cpu:.2f}x, "
              f"rtf reached {c_rtf:.2f} vs {s_rtf:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
