#!/usr/bin/env bash
# Runs the benchmarks: installs the bench-only references (bench/requirements.txt) into the project
# venv, then runs the benches (all but the classifier's and the localization accuracy run by default, or the ones
# named: bench/run.sh planner localization_accuracy).
# Each bench prints its figures and the ratio to a reference measured in the same run.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PY="$REPO/.venv/bin/python"
if [ ! -x "$PY" ]; then
  echo "[bench] no venv at $REPO/.venv: run tools/install.sh first" >&2
  exit 2
fi
"$PY" -m pip install --quiet --disable-pip-version-check -r "$REPO/bench/requirements.txt"
names=("$@")
ALL=(costmap planner planner_random pure_pursuit controller_latency engine smach_compat sim localization pose_graph yield)
if [ "${#names[@]}" -eq 0 ]; then names=("${ALL[@]}"); fi
status=0
for name in "${names[@]}"; do
  script="$REPO/bench/bench_${name}.py"
  if [ ! -f "$script" ]; then
    echo "[bench] no such bench: $script (valid: ${ALL[*]} classifier localization_accuracy console_latency)" >&2
    exit 2
  fi
  echo "=== bench_${name} ==="
  "$PY" "$script" || status=1
done
exit "$status"
