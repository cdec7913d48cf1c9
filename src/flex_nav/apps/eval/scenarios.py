"""Evaluate the push-or-avoid scenarios: ``python -m flex_nav.apps.eval.scenarios [--seeds 3] [--out DIR]``.

Runs every scenario (S1..S6 worlds) x behavior (move_base_like, push_or_avoid) x seed headless, one
``python -m flex_nav.apps.scenario_run`` process per run (each with its own private master, so a failed run
cannot affect the next), with a progress bar on stderr. Writes ``results.csv`` (one row per run),
``results.md`` (summary per scenario and behavior) and one ``<scenario>-<behavior>-<seed>/run.png`` per
run to ``--out``, plus the run's own ``result.json``. ``--resume`` keeps the runs of ``--out`` that have a
``result.json`` (an interrupted evaluation goes on where it stopped; more behaviors or seeds can be added
later). Exit 0 when every run was recorded, 1 when a run could not start or crashed.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path
from typing import List, Optional, Sequence

from flex_nav.apps.eval.metrics import RunResult
from flex_nav.apps.eval.table import to_csv, to_markdown
from flex_nav.exceptions import choices_message
from flex_nav.resources import behaviors_dir

REPO_ROOT = Path(__file__).resolve().parents[4]  # a source checkout: the scenario runs start tools/ scripts
SCENARIOS = (
    "s1_light_box_door",
    "s2_heavy_box_door",
    "s3_person_in_door",
    "s4_light_box_short_route",
    "s5_heavy_box_short_route",
    "s6_people_crossing",
)
BEHAVIORS = ("move_base_like", "push_or_avoid")
RUN_WALL_LIMIT_S = 900.0  # [s] wall bound of one run process


def parse_args(argv: Optional[Sequence[str]] = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m flex_nav.apps.eval.scenarios",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenarios", default=",".join(SCENARIOS), help="comma-separated worlds (default: all six)")
    parser.add_argument("--behaviors", default=",".join(BEHAVIORS), help="comma-separated behaviors")
    parser.add_argument("--seeds", type=int, default=3, help="seeds 0..N-1 per scenario and behavior")
    parser.add_argument("--rtf", type=float, default=1.0, help="simulation real-time factor")
    parser.add_argument("--sim-limit", type=float, default=150.0, help="[s] simulated time bound of one goal")
    parser.add_argument("--out", type=Path, default=None, help="output directory (default out/scenarios-<time>)")
    parser.add_argument("--resume", action="store_true", help="keep the runs in --out that have a result.json")
    parser.add_argument("--localization", choices=("localizer", "oracle"), default="localizer",
                        help="map -> odom from flex_nav's localizer (default) or the simulator's ground truth")
    args = parser.parse_args(argv)
    args.scenario_list = [s for s in args.scenarios.split(",") if s]
    args.behavior_list = [b for b in args.behaviors.split(",") if b]
    for name in args.scenario_list:
        if name not in SCENARIOS:
            parser.error(choices_message("scenario", name, SCENARIOS))
    known_behaviors = sorted(p.stem for p in behaviors_dir().glob("*.yaml"))
    for name in args.behavior_list:
        if name not in known_behaviors:
            parser.error(choices_message("behavior", name, known_behaviors))
    if args.seeds < 1:
        parser.error(f"--seeds {args.seeds} must be >= 1")
    return args


def progress(done: int, total: int, started: float, label: str) -> None:
    width = 30
    filled = int(width * done / total) if total else width
    elapsed = time.monotonic() - started
    eta = elapsed / done * (total - done) if done else float("nan")
    sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} {elapsed:5.0f} s "
                     f"(eta {eta:5.0f} s) {label:<50.50}")
    sys.stderr.flush()


def run_one(args: argparse.Namespace, world: str, behavior: str, seed: int, out: Path) -> Optional[RunResult]:
    command = [sys.executable, "-m", "flex_nav.apps.scenario_run", "--world", world, "--behavior", behavior,
               "--seed", str(seed), "--rtf", str(args.rtf), "--sim-limit", str(args.sim_limit), "--out", str(out),
               "--localization", args.localization]
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "run.log", "w") as log:
        try:
            proc = subprocess.run(command, stdout=subprocess.PIPE, stderr=log, text=True,
                                  timeout=RUN_WALL_LIMIT_S, check=False)
        except subprocess.TimeoutExpired:
            return None
        log.write(proc.stdout)
    for line in proc.stdout.splitlines():
        if line.startswith("RESULT "):
            data = json.loads(line[len("RESULT "):])
            (out / "result.json").write_text(json.dumps(data, indent=1) + "\n")
            return RunResult.from_dict(data)
    return None


def recorded(out: Path) -> Optional[RunResult]:
    """The result a previous evaluation wrote to ``out`` (a run directory), or None."""
    path = out / "result.json"
    return RunResult.from_dict(json.loads(path.read_text())) if path.is_file() else None


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = parse_args(argv)
    out = args.out or REPO_ROOT / "out" / time.strftime("scenarios-%Y%m%d-%H%M%S")
    out.mkdir(parents=True, exist_ok=True)
    plan = [(w, b, s) for w in args.scenario_list for b in args.behavior_list for s in range(args.seeds)]
    results: List[RunResult] = []
    broken: List[str] = []
    started = time.monotonic()
    for index, (world, behavior, seed) in enumerate(plan):
        label = f"{world} {behavior} seed {seed}"
        progress(index, len(plan), started, label)
        run_dir = out / f"{world}-{behavior}-{seed}"
        result = recorded(run_dir) if args.resume else None
        if result is None:
            result = run_one(args, world, behavior, seed, run_dir)
        if result is None:
            broken.append(label)
            continue
        results.append(result)
        (out / "results.csv").write_text(to_csv(results))  # written after every run: partial results survive
        (out / "results.md").write_text(to_markdown(results))
    progress(len(plan), len(plan), started, "done")
    sys.stderr.write("\n")
    print(to_markdown(results))
    print(f"results: {out / 'results.md'}, {out / 'results.csv'}")
    for label in broken:
        print(f"run did not produce a result: {label} (see its run.log)", file=sys.stderr)
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
