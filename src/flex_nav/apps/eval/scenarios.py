"""Evaluate the push-or-avoid scenarios: ``python -m flex_nav.apps.eval.scenarios [--seeds 3] [--out DIR]``.

Runs every scenario (S1..S6 worlds, or world files such as variants of them) x behavior (move_base_like,
push_or_avoid) x seed headless, one ``python -m flex_nav.apps.scenario_run`` process per run (each with its own
private master, so a failed run cannot affect the next), with a progress bar on stderr. Runs are independent, so
they run in parallel: ``--workers N`` of them at once on this machine (default: one per core), or on a Dask
distributed cluster with ``--cluster ADDRESS`` (a ``dask scheduler`` and ``dask worker ADDRESS`` processes started
from checkouts of this repository where tools/install.sh has run; each worker runs one run at a time with
``--nthreads 1``). A run that ends without a result (it crashed, timed out, or its worker was lost) is tried once
more, and reported; one that fails twice is reported and fails the evaluation, never dropped silently. Writes
``results.csv`` (one row per run), ``results.md`` (summary per scenario and behavior), both rewritten as each run
ends, and one ``<scenario>-<behavior>-<seed>/run.png`` per run to ``--out`` (on a cluster: on the worker's file
system, at the same path), plus the run's own ``result.json``. ``--resume`` keeps the runs of ``--out`` that have a
``result.json`` (an interrupted evaluation goes on where it stopped; more behaviors or seeds can be added later).
``--durations CSV`` (the ``results.csv`` of an earlier evaluation, e.g. docs/eval/results.csv) starts the runs
longest first by the times it holds (a run it lacks or that did not arrive counts as the simulated-time limit), so
that no long run is left to end alone on one worker while the others idle.
Exit 0 when every run was recorded, 1 when a run could not start or crashed twice, 2 when the cluster cannot be
reached or ``--durations`` cannot be read.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import socket
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Protocol, Sequence, Tuple

from flex_nav.apps.eval.metrics import RunResult
from flex_nav.apps.eval.table import to_csv, to_markdown
from flex_nav.exceptions import FlexNavError, choices_message
from flex_nav.nav.control.yielding import PLANNERS
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
CLUSTER_CONNECT_TIMEOUT_S = 20.0  # [s] to reach a Dask scheduler
POLL_PERIOD_S = 0.2  # [s] wall: how often the driver looks at the runs in flight
ATTEMPTS = 2  # a run without a result is tried once more


def parse_args(argv: Optional[Sequence[str]] = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m flex_nav.apps.eval.scenarios",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenarios", default=",".join(SCENARIOS),
                        help="comma-separated worlds: the six's names (default: all six) or world files (variants)")
    parser.add_argument("--behaviors", default=",".join(BEHAVIORS), help="comma-separated behaviors")
    parser.add_argument("--behavior-param", action="append", default=[], metavar="BEHAVIOR:KEY=VALUE",
                        help="a parameter override for every run of BEHAVIOR (e.g. push_or_avoid:fuse_lidar=true); "
                             "repeatable")
    parser.add_argument("--seeds", type=int, default=3, help="seeds 0..N-1 per scenario and behavior")
    parser.add_argument("--rtf", type=float, default=1.0, help="simulation real-time factor")
    parser.add_argument("--sim-limit", type=float, default=150.0, help="[s] simulated time bound of one goal")
    parser.add_argument("--lockstep", action=argparse.BooleanOptionalAction, default=True,
                        help="run the simulator in lockstep with the nodes (scenario_run --lockstep, the default)")
    parser.add_argument("--out", type=Path, default=None, help="output directory (default out/scenarios-<time>)")
    parser.add_argument("--resume", action="store_true", help="keep the runs in --out that have a result.json")
    parser.add_argument("--durations", type=Path, default=None, metavar="CSV",
                        help="an earlier results.csv: start the runs longest first by its times")
    parser.add_argument("--localization", choices=("localizer", "oracle"), default="localizer",
                        help="map -> odom from flex_nav's localizer (default) or the simulator's ground truth")
    parser.add_argument("--yield-planner", choices=PLANNERS, default=None,
                        help="push_or_avoid's way of giving way to walkers (scenario_run --yield-planner; default: "
                             "scenario_run's, checked)")
    parser.add_argument("--yield-param", action="append", default=[], metavar="KEY=VALUE",
                        help="a yield parameter for every run (scenario_run --yield-param); repeatable")
    parser.add_argument("--social-distance", type=float, default=None, metavar="M",
                        help="[m] keep this distance from tracked people while moving (scenario_run --social-distance; "
                             "default: scenario_run's, 0.3; 0: off)")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                        help="runs at once on this machine (default: one per core; 1: one after another)")
    parser.add_argument("--cluster", default="", metavar="ADDRESS",
                        help="run on a Dask distributed scheduler (e.g. tcp://10.0.0.5:8786) instead of locally")
    args = parser.parse_args(argv)
    args.scenario_list = [s for s in args.scenarios.split(",") if s]
    args.behavior_list = [b for b in args.behaviors.split(",") if b]
    for i, name in enumerate(args.scenario_list):
        if name.endswith(".yaml"):  # a world file: the runs start elsewhere, so its absolute path
            if not Path(name).is_file():
                parser.error(f"scenario world file {name!r} does not exist")
            args.scenario_list[i] = str(Path(name).resolve())
        elif name not in SCENARIOS:
            parser.error(choices_message("scenario", name, SCENARIOS) + " (or a world file ending in .yaml)")
    known_behaviors = sorted(p.stem for p in behaviors_dir().glob("*.yaml"))
    for name in args.behavior_list:
        if name not in known_behaviors:
            parser.error(choices_message("behavior", name, known_behaviors))
    args.behavior_params = {}  # behavior -> ["KEY=VALUE", ...]
    for item in args.behavior_param:
        behavior, sep, setting = item.partition(":")
        if not sep or "=" not in setting or behavior not in args.behavior_list:
            parser.error(f"--behavior-param takes BEHAVIOR:KEY=VALUE with BEHAVIOR one of "
                         f"{', '.join(args.behavior_list)}; got {item!r}")
        args.behavior_params.setdefault(behavior, []).append(setting)
    if args.seeds < 1:
        parser.error(f"--seeds {args.seeds} must be >= 1")
    if args.social_distance is not None and not args.social_distance >= 0.0:
        parser.error(f"--social-distance {args.social_distance} [m] must be >= 0 (0: off)")
    if args.workers < 1:
        parser.error(f"--workers {args.workers} must be >= 1")
    if args.durations is not None and not args.durations.is_file():
        parser.error(f"--durations {str(args.durations)!r} is not a file (an earlier evaluation's results.csv)")
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
               "--localization", args.localization, "--lockstep" if args.lockstep else "--no-lockstep"]
    for setting in args.behavior_params.get(behavior, []):
        command += ["--behavior-param", setting]
    if args.social_distance is not None:
        command += ["--social-distance", str(args.social_distance)]
    if args.yield_planner is not None:
        command += ["--yield-planner", args.yield_planner]
    for setting in args.yield_param:
        command += ["--yield-param", setting]
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


@dataclass(frozen=True)
class PlannedRun:
    world: str
    behavior: str
    seed: int

    @property
    def label(self) -> str:
        return f"{Path(self.world).stem} {self.behavior} seed {self.seed}"

    @property
    def directory(self) -> str:
        return f"{Path(self.world).stem}-{self.behavior}-{self.seed}"


class RunFuture(Protocol):
    """What the driver needs of a future: concurrent.futures' and Dask distributed's both have it."""

    def done(self) -> bool: ...

    def result(self) -> Any: ...


Submit = Callable[[PlannedRun, int], RunFuture]  # (run, attempt) -> the future of (result or None, worker)


def run_on_worker(args: argparse.Namespace, run: PlannedRun, out: Path) -> Tuple[Optional[RunResult], str]:
    """One run where a worker executes it; with the worker's name (host:pid) for the report."""
    return run_one(args, run.world, run.behavior, run.seed, out), f"{socket.gethostname()}:{os.getpid()}"


def longest_first(plan: Sequence[PlannedRun], results_csv: Path, limit_s: float) -> List[PlannedRun]:
    """``plan`` ordered by the simulated times [s] of an earlier ``results_csv`` (world by name, behavior, seed),
    longest first; a run it lacks or that did not arrive counts as ``limit_s`` (it may run to the limit). Stable:
    equal times keep the plan's order. FlexNavError when the file is not a results.csv."""
    with results_csv.open(newline="") as f:
        rows = list(csv.DictReader(f))
    missing = {"world", "behavior", "seed", "success", "time_s"} - set(rows[0] if rows else {})
    if missing:
        raise FlexNavError(f"{results_csv} is not a results.csv (no column {', '.join(sorted(missing))})")
    known = {(r["world"], r["behavior"], r["seed"]): float(r["time_s"]) for r in rows
             if r["success"] == "True" and r["time_s"]}

    def expected_s(run: PlannedRun) -> float:
        return known.get((Path(run.world).stem, run.behavior, str(run.seed)), limit_s)

    return sorted(plan, key=expected_s, reverse=True)


@dataclass
class Evaluation:
    """The runs' outcomes as they come in."""

    results: Dict[PlannedRun, RunResult]
    broken: List[str]  # labels of runs without a result after every attempt, with the reason
    retried: List[str]  # labels of runs tried again, with the reason
    workers: Dict[PlannedRun, str]  # who ran each recorded run


def evaluate(plan: Sequence[PlannedRun], submit: Submit, on_result: Callable[[Evaluation, str], None],
             ) -> Evaluation:
    """Submit every run, collect them as they end (in any order), try a run without a result once more."""
    evaluation = Evaluation({}, [], [], {})
    in_flight: Dict[Any, Tuple[PlannedRun, int]] = {}
    for run in plan:
        in_flight[submit(run, 1)] = (run, 1)
    while in_flight:
        finished = [future for future in in_flight if future.done()]
        if not finished:
            time.sleep(POLL_PERIOD_S)
            continue
        for future in finished:
            run, attempt = in_flight.pop(future)
            try:
                result, worker = future.result()
                reason = "no result (see its run.log)" if result is None else ""
            except Exception as err:  # a lost worker, a run that raised: the run is what failed, not the driver
                result, worker, reason = None, "", f"{type(err).__name__}: {err}"
            if result is not None:
                evaluation.results[run] = result
                evaluation.workers[run] = worker
                on_result(evaluation, run.label)
            elif attempt < ATTEMPTS:
                evaluation.retried.append(f"{run.label}: {reason}")
                in_flight[submit(run, attempt + 1)] = (run, attempt + 1)
            else:
                evaluation.broken.append(f"{run.label}: {reason}")
                on_result(evaluation, run.label)
    return evaluation


def local_submitter(pool: ThreadPoolExecutor, args: argparse.Namespace, out: Path) -> Submit:
    """Runs in this machine's pool of threads (each waits for its own run process)."""
    return lambda run, _attempt: pool.submit(run_on_worker, args, run, out / run.directory)


def cluster_submitter(client: Any, args: argparse.Namespace, out: Path) -> Submit:
    """Runs on a Dask distributed cluster; every attempt is a new task (pure=False, its own key)."""
    def submit(run: PlannedRun, attempt: int) -> RunFuture:
        future: RunFuture = client.submit(run_on_worker, args, run, out / run.directory, pure=False,
                                          key=f"flex_nav-{run.directory}-try{attempt}", retries=0)
        return future
    return submit


def connect_cluster(address: str) -> Any:
    """A Dask distributed client of the scheduler at ``address``; FlexNavError naming it when it cannot be
    reached within CLUSTER_CONNECT_TIMEOUT_S."""
    from distributed import Client  # noqa: PLC0415 - only for --cluster

    try:
        return Client(address, timeout=CLUSTER_CONNECT_TIMEOUT_S, set_as_default=False)
    except (OSError, TimeoutError) as err:
        raise FlexNavError(f"cannot reach the Dask scheduler at {address!r} within "
                           f"{CLUSTER_CONNECT_TIMEOUT_S:g} s: {err}") from err


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = parse_args(argv)
    out = (args.out or REPO_ROOT / "out" / time.strftime("scenarios-%Y%m%d-%H%M%S")).resolve()
    out.mkdir(parents=True, exist_ok=True)
    plan = [PlannedRun(w, b, s) for w in args.scenario_list for b in args.behavior_list for s in range(args.seeds)]
    kept = {run: result for run in plan if args.resume and (result := recorded(out / run.directory)) is not None}
    todo = [run for run in plan if run not in kept]
    if args.durations is not None:
        try:
            todo = longest_first(todo, args.durations, args.sim_limit)
        except (FlexNavError, OSError, ValueError) as err:
            print(f"scenarios: --durations: {err}", file=sys.stderr)
            return 2
    started = time.monotonic()

    def on_result(evaluation: Evaluation, label: str) -> None:
        ordered = [r for run in plan if (r := kept.get(run) or evaluation.results.get(run)) is not None]
        (out / "results.csv").write_text(to_csv(ordered))  # rewritten after every run: partial results survive
        (out / "results.md").write_text(to_markdown(ordered))
        progress(len(evaluation.results) + len(evaluation.broken), len(todo), started, label)

    progress(0, len(todo), started, "starting")
    if args.cluster:
        try:
            client = connect_cluster(args.cluster)
        except FlexNavError as err:
            print(f"scenarios: {err}", file=sys.stderr)
            return 2
        with client:
            evaluation = evaluate(todo, cluster_submitter(client, args, out), on_result)
    else:
        with ThreadPoolExecutor(max_workers=args.workers, thread_name_prefix="scenario-run") as pool:
            evaluation = evaluate(todo, local_submitter(pool, args, out), on_result)
    if not todo:
        on_result(evaluation, "done")
    sys.stderr.write("\n")
    print(to_markdown([r for run in plan if (r := kept.get(run) or evaluation.results.get(run)) is not None]))
    where = (f"{len(set(evaluation.workers.values()))} cluster worker(s)" if args.cluster
             else f"{args.workers} local worker(s)")  # (a local pool's threads all report this process)
    print(f"results: {out / 'results.md'}, {out / 'results.csv'}; {len(evaluation.results)} run(s) on {where} in "
          f"{time.monotonic() - started:.0f} s")
    for label in evaluation.retried:
        print(f"run tried again: {label}", file=sys.stderr)
    for label in evaluation.broken:
        print(f"run did not produce a result: {label}", file=sys.stderr)
    return 1 if evaluation.broken else 0


if __name__ == "__main__":
    sys.exit(main())
