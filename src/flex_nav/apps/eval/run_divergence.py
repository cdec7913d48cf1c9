"""Where two recordings of the same run part: the first stamp at which their ground truth or their scans differ.

``python -m flex_nav.apps.eval.run_divergence A/run.bag B/run.bag [--robot robot1] [--tolerance 1e-6] [--absolute]``

Two runs of one world, behavior and seed (``scenario_run --bag``, e.g. one after another and beside another run,
or at two real-time factors) should be the same run in a lockstep simulation. When their times differ, this names
the first simulated time [s] at which the robot's ground truth (pose [m], velocities [m/s], [rad/s]) differs by more
than ``--tolerance``, the first scan that differs, and the behavior transitions of each run around it: what to look
at next. Times are counted from each run's first behavior transition (the goal's arrival), so two runs whose
world started at different simulated times compare step by step (``--absolute``: the recorded stamps). The
comparison is pure (:func:`first_divergence`); only :func:`read_bag` needs rosbag.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple

STAMP_DIGITS = 4  # stamps are matched rounded to 0.1 ms (the simulator steps at 1/240 s)


class Divergence(NamedTuple):
    """The first common stamp [s] whose samples differ, and the two samples there."""

    stamp_s: float
    first: Tuple[float, ...]
    second: Tuple[float, ...]


class Recording(NamedTuple):
    """One run's samples by stamp [s]: ground truth (x, y [m], yaw [rad], v [m/s], w [rad/s]), scan ranges [m],
    and the behavior's transitions (stamp [s], "path --outcome--> target")."""

    truth: Dict[float, Tuple[float, ...]]
    scans: Dict[float, Tuple[float, ...]]
    transitions: List[Tuple[float, str]]


def first_divergence(first: Mapping[float, Sequence[float]], second: Mapping[float, Sequence[float]],
                     tolerance: float) -> Optional[Divergence]:
    """The earliest stamp both hold whose samples differ in length or in any value by more than ``tolerance``
    (NaN equals NaN, inf equals inf); None when every common stamp agrees."""
    if not (math.isfinite(tolerance) and tolerance >= 0.0):
        raise ValueError(f"tolerance {tolerance!r}: must be a finite number >= 0")
    for stamp_s in sorted(set(first) & set(second)):
        a, b = tuple(first[stamp_s]), tuple(second[stamp_s])
        if len(a) != len(b) or any(not _same(x, y, tolerance) for x, y in zip(a, b)):
            return Divergence(stamp_s, a, b)
    return None


def _same(x: float, y: float, tolerance: float) -> bool:
    if math.isnan(x) or math.isnan(y):
        return math.isnan(x) and math.isnan(y)
    if math.isinf(x) or math.isinf(y):
        return x == y
    return abs(x - y) <= tolerance


def aligned(recording: Recording) -> Recording:
    """``recording`` with every stamp counted from its first transition (unchanged without transitions)."""
    if not recording.transitions:
        return recording
    origin_s = min(s for s, _ in recording.transitions)

    def shifted(samples: Dict[float, Tuple[float, ...]]) -> Dict[float, Tuple[float, ...]]:
        return {round(s - origin_s, STAMP_DIGITS): v for s, v in samples.items()}

    return Recording(shifted(recording.truth), shifted(recording.scans),
                     [(round(s - origin_s, STAMP_DIGITS), what) for s, what in recording.transitions])


def read_bag(path: Path, robot: str) -> Recording:
    """``robot``'s ground truth, scans and behavior transitions from a ``scenario_run --bag`` recording."""
    import rosbag  # noqa: PLC0415  (only this reads bags; the comparison is pure)

    from flex_nav.ros.conversions import xy_yaw_of_pose  # noqa: PLC0415

    truth: Dict[float, Tuple[float, ...]] = {}
    scans: Dict[float, Tuple[float, ...]] = {}
    transitions: List[Tuple[float, str]] = []
    topics = [f"/{robot}/ground_truth", f"/{robot}/scan", f"/{robot}/behavior_runner/transitions"]
    with rosbag.Bag(str(path)) as bag:
        for topic, msg, _t in bag.read_messages(topics=topics):
            stamp_s = round(msg.header.stamp.to_sec(), STAMP_DIGITS)
            if topic == topics[0]:
                twist = msg.twist.twist
                truth[stamp_s] = (*xy_yaw_of_pose(msg.pose.pose), twist.linear.x, twist.angular.z)
            elif topic == topics[1]:
                scans[stamp_s] = tuple(msg.ranges)
            else:
                transitions.append((stamp_s, f"{msg.path} --{msg.outcome}--> {msg.target}"))
    return Recording(truth, scans, transitions)


def report(first: Recording, second: Recording, tolerance: float, context_s: float = 2.0) -> List[str]:
    """The lines the command prints."""
    lines = [f"ground truth: {len(first.truth)} / {len(second.truth)} samples, "
             f"{len(set(first.truth) & set(second.truth))} at common stamps"]
    truth = first_divergence(first.truth, second.truth, tolerance)
    scans = first_divergence(first.scans, second.scans, tolerance)
    if truth is None:
        lines.append("ground truth: the same at every common stamp")
    else:
        lines.append(f"ground truth parts at {truth.stamp_s:.4f} s: (x, y, yaw, v, w) "
                     f"{_shown(truth.first)} vs {_shown(truth.second)}")
    if scans is None:
        lines.append("scans: the same at every common stamp")
    else:
        changed = sum(1 for x, y in zip(scans.first, scans.second) if not _same(x, y, tolerance))
        lines.append(f"scans part at {scans.stamp_s:.4f} s ({changed} of {len(scans.first)} ranges differ)")
    parted = [d.stamp_s for d in (truth, scans) if d is not None]
    if parted:
        at_s = min(parted)
        for name, recording in (("first", first), ("second", second)):
            near = [f"  {s:.3f} s {what}" for s, what in recording.transitions if abs(s - at_s) <= context_s]
            lines.append(f"{name} run's transitions within {context_s:g} s of {at_s:.3f} s:")
            lines.extend(near or ["  (none)"])
    return lines


def _shown(values: Sequence[float]) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in values) + ")"


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n", 1)[0])
    parser.add_argument("first", type=Path, help="run.bag of one run (scenario_run --bag)")
    parser.add_argument("second", type=Path, help="run.bag of the other run")
    parser.add_argument("--robot", default="robot1", help="the robot's namespace")
    parser.add_argument("--tolerance", type=float, default=1e-6, help="largest difference that counts as equal")
    parser.add_argument("--absolute", action="store_true",
                        help="compare at the recorded stamps (default: from each run's first behavior transition)")
    args = parser.parse_args(argv)
    for path in (args.first, args.second):
        if not path.is_file():
            parser.error(f"no such bag: {path}")
    first, second = read_bag(args.first, args.robot), read_bag(args.second, args.robot)
    if not first.truth or not second.truth:
        empty = args.first if not first.truth else args.second
        print(f"{empty}: no ground truth of robot {args.robot!r} (/{args.robot}/ground_truth)", file=sys.stderr)
        return 2
    if not args.absolute:
        first, second = aligned(first), aligned(second)
        print("times [s] from each run's first behavior transition (the goal's arrival)")
    for line in report(first, second, args.tolerance):
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
