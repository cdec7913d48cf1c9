"""The scenario table: every run as CSV, and a Markdown summary per scenario and behavior.

Summary columns: runs, successes, mean time to goal over the successful runs [s], mean path length over
the successful runs [m], pushes tried / succeeded (sums), contacts with people (sum; how many were the robot's
doing, when they were classified) and the smallest
clearance to a person over every run [m] ("-" without people).
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import fields
from typing import Dict, List, Sequence, Tuple

from flex_nav.apps.eval.metrics import RunResult

CSV_FIELDS = tuple(f.name for f in fields(RunResult))


def to_csv(results: Sequence[RunResult]) -> str:
    out = io.StringIO()
    writer = csv.DictWriter(out, fieldnames=CSV_FIELDS, lineterminator="\n")
    writer.writeheader()
    for result in results:
        row = result.to_dict()
        writer.writerow({k: _cell(row[k]) for k in CSV_FIELDS})
    return out.getvalue()


def _cell(value: object) -> object:
    """A CSV cell: empty for None, a list's items joined by ';' (empty items for None)."""
    if value is None:
        return ""
    if isinstance(value, list):
        return ";".join("" if v is None else str(v) for v in value)
    return value


def _mean(values: List[float]) -> float:
    return sum(values) / len(values) if values else math.nan


def _fmt(value: float, digits: int = 1) -> str:
    return "-" if not math.isfinite(value) else f"{value:.{digits}f}"


def _contacts(runs: Sequence[RunResult]) -> str:
    """The contacts with people (sum), and how many were the robot's doing when any were classified:
    "3 (1 by the robot)"; just "3" for results recorded before contacts were classified."""
    total = sum(r.people_contacts for r in runs)
    robot = sum(r.people_contacts_robot_caused for r in runs)
    classified = robot + sum(r.people_contacts_person_caused for r in runs)
    return f"{total} ({robot} by the robot)" if total and classified else str(total)


def summary_rows(results: Sequence[RunResult]) -> List[Dict[str, str]]:
    """One row per (world, behavior), in the order they first appear."""
    groups: Dict[Tuple[str, str], List[RunResult]] = {}
    for result in results:
        groups.setdefault((result.world, result.behavior), []).append(result)
    rows = []
    for (world, behavior), runs in groups.items():
        reached = [r for r in runs if r.success]
        clearance = min((r.min_people_clearance_m for r in runs), default=math.inf)
        rows.append({
            "scenario": world,
            "behavior": behavior,
            "success": f"{len(reached)}/{len(runs)}",
            "time to goal [s]": _fmt(_mean([r.time_s for r in reached])),
            "path length [m]": _fmt(_mean([r.path_m for r in reached])),
            "pushes tried/succeeded": f"{sum(r.pushes_tried for r in runs)}/{sum(r.pushes_succeeded for r in runs)}",
            "contacts with people": _contacts(runs),
            "min distance to people [m]": _fmt(clearance, 2),
        })
    return rows


def to_markdown(results: Sequence[RunResult]) -> str:
    rows = summary_rows(results)
    if not rows:
        return "(no runs)\n"
    header = list(rows[0])
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(row[h] for h in header) + " |" for row in rows]
    notes = [f"- {r.world} / {r.behavior} / seed {r.seed}: {r.note}" for r in results if r.note]
    text = "\n".join(lines) + "\n"
    if notes:
        text += "\nRuns that did not reach the goal:\n\n" + "\n".join(notes) + "\n"
    return text
