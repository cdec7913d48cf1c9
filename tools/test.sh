#!/usr/bin/env bash
# The README's test command: installs what is missing, then runs every test (unit tests without a
# master, rostests against private masters, ruff and mypy) through one pytest run.
# Extra arguments go to pytest, e.g.  tools/test.sh -k planner
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$REPO/tools/install.sh"
export PATH="$REPO/.venv/bin:$PATH"
export ROS_PACKAGE_PATH="$REPO${ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}"
export ROS_IP=127.0.0.1
# Tests start their own masters; make sure nothing falls back to a default one on 11311.
export ROS_MASTER_URI=http://127.0.0.1:9/
cd "$REPO"
exec "$REPO/.venv/bin/python" -m pytest "$@"
